/*
 * The platform layer of main.c for a hosted C program (Linux, macOS): the
 * writer of semihost.h on stdout, and no stack measurement (a hosted
 * program's stack is the operating system's; the marks print as 0). With it
 * main.c is a host program linked against the host build of the staticlib
 * (`make host`), and the host test recomputes its numbers with the kernel.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "semihost.h"

void sh_write0(const char *s) { fputs(s, stdout); }

void sh_exit(int ok) {
    fflush(stdout);
    exit(ok ? 0 : 1);
}

void out_flush(void) { fflush(stdout); }
void out_char(char c) { putchar(c); }
void out_str(const char *s) { fputs(s, stdout); }
void out_u32(uint32_t v) { printf("%lu", (unsigned long)v); }
void out_i32(int32_t v) { printf("%ld", (long)v); }
void out_hex32(uint32_t v) { printf("%08lx", (unsigned long)v); }

void out_f32(float x) {
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    printf(" %08lx", (unsigned long)bits);
}

void out_f64(double x) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    printf(" %08lx%08lx", (unsigned long)(bits >> 32), (unsigned long)(bits & 0xFFFFFFFFu));
}

uint32_t stack_high_water(void) { return 0; }
uint32_t stack_size(void) { return 0; }
void stack_repaint(void) {}
