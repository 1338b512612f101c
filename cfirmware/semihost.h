/*
 * ARM semihosting (the debugger's or QEMU's console and exit), the two
 * operations this firmware needs: SYS_WRITE0 and SYS_EXIT, via `bkpt 0xAB`
 * (the Thumb semihosting trap on Cortex-M).
 */
#ifndef CFIRMWARE_SEMIHOST_H
#define CFIRMWARE_SEMIHOST_H

#include <stdint.h>

/* Writes a NUL-terminated string to the host console. */
void sh_write0(const char *s);

/* Ends the run: QEMU exits with status 0 when `ok`, else 1. */
__attribute__((noreturn)) void sh_exit(int ok);

/* A small buffered line writer on top of sh_write0 (one trap per 256 bytes). */
void out_str(const char *s);
void out_char(char c);
void out_u32(uint32_t v);        /* decimal */
void out_i32(int32_t v);         /* decimal */
void out_hex32(uint32_t v);      /* 8 hex digits */
void out_f32(float x);           /* " " + its bits, 8 hex digits */
void out_f64(double x);          /* " " + its bits, 16 hex digits */
void out_flush(void);

#endif
