/*
 * Minimal Cortex-M startup: the vector table, a reset handler that copies
 * .data, zeroes .bss, enables the FPU (Cortex-M4F), paints the free stack
 * for a high-water mark, and calls main(); a HardFault handler that reports
 * and exits. Symbols from the linker script (sections.ld).
 */
#include <stdint.h>

#include "semihost.h"

extern uint32_t _sidata[], _sdata[], _edata[], _sbss[], _ebss[], _stack_top[];

int main(void);

#define PAINT 0xC0FFEE55u

static void copy_and_zero(void) {
    uint32_t *src = _sidata;
    for (uint32_t *dst = _sdata; dst < _edata;) *dst++ = *src++;
    for (uint32_t *dst = _sbss; dst < _ebss;) *dst++ = 0;
}

/* Paints from the end of .bss up to 64 bytes below the current stack pointer. */
static void paint_stack(void) {
    uint32_t *sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    for (volatile uint32_t *p = _ebss; p < sp - 16;) *p++ = PAINT;
}

/* Paints the free stack again (below the caller's frame), for the next phase's mark. */
void stack_repaint(void) { paint_stack(); }

uint32_t stack_high_water(void) {
    const uint32_t *p = _ebss;
    while (p < _stack_top && *p == PAINT) ++p;
    return (uint32_t)((uintptr_t)_stack_top - (uintptr_t)p);
}

uint32_t stack_size(void) { return (uint32_t)((uintptr_t)_stack_top - (uintptr_t)_ebss); }

__attribute__((noreturn)) void Reset_Handler(void) {
#if defined(__ARM_FP)
    /* CPACR: full access to CP10 and CP11 (the FPU) before any float instruction. */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    copy_and_zero();
    paint_stack();
    sh_exit(main() == 0);
}

__attribute__((noreturn)) void HardFault_Handler(void) {
    out_str("hardfault\n");
    sh_exit(0);
}

__attribute__((noreturn)) static void Default_Handler(void) {
    out_str("unexpected exception\n");
    sh_exit(0);
}

/* Initial stack pointer, then the 15 system exception handlers. */
__attribute__((section(".vectors"), used)) static void *const vectors[16] = {
    _stack_top,      Reset_Handler,   Default_Handler, HardFault_Handler,
    Default_Handler, Default_Handler, Default_Handler, 0,
    0,               0,               0,               Default_Handler,
    Default_Handler, 0,               Default_Handler, Default_Handler,
};
