/* ARM semihosting through `bkpt 0xAB`; see semihost.h. */
#include "semihost.h"



#define SYS_WRITE0 0x04
#define SYS_EXIT 0x18
/* SYS_EXIT reasons (32-bit ARM: passed by value). */
#define ADP_STOPPED_APPLICATION_EXIT 0x20026
#define ADP_STOPPED_RUN_TIME_ERROR 0x20023

static uint32_t semihost(uint32_t op, const void *arg) {
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void sh_write0(const char *s) { semihost(SYS_WRITE0, s); }

void sh_exit(int ok) {
    out_flush();
    semihost(SYS_EXIT, (const void *)(uintptr_t)(ok ? ADP_STOPPED_APPLICATION_EXIT
                                                    : ADP_STOPPED_RUN_TIME_ERROR));
    for (;;) {
    }
}

static char buf[257];
static unsigned len;

void out_flush(void) {
    if (len) {
        buf[len] = 0;
        sh_write0(buf);
        len = 0;
    }
}

void out_char(char c) {
    buf[len++] = c;
    if (len == sizeof buf - 1) out_flush();
}

void out_str(const char *s) {
    while (*s) out_char(*s++);
}

void out_u32(uint32_t v) {
    char d[10];
    int n = 0;
    do {
        d[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    while (n) out_char(d[--n]);
}

void out_i32(int32_t v) {
    if (v < 0) {
        out_char('-');
        out_u32(0u - (uint32_t)v);
    } else {
        out_u32((uint32_t)v);
    }
}

void out_hex32(uint32_t v) {
    static const char digits[] = "0123456789abcdef";
    for (int shift = 28; shift >= 0; shift -= 4) out_char(digits[(v >> shift) & 0xF]);
}

void out_f32(float x) {
    uint32_t bits;
    __builtin_memcpy(&bits, &x, sizeof bits);
    out_char(' ');
    out_hex32(bits);
}

void out_f64(double x) {
    uint64_t bits;
    __builtin_memcpy(&bits, &x, sizeof bits);
    out_char(' ');
    out_hex32((uint32_t)(bits >> 32));
    out_hex32((uint32_t)bits);
}
