/* Stack high-water marks on bare metal (Cortex-M): the free stack below the caller is painted
 * with a pattern before a case, and after it the lowest word that no longer holds the
 * pattern marks the deepest point the case reached. Hosted builds measure nothing. */
#ifndef FW_STACK_H
#define FW_STACK_H

#include <stdint.h>

#if defined(FW_BARE_METAL) && defined(__arm__)
#define FW_STACK_MEASURED 1
/* The stack pointer of the calling function (inlined into it). */
static inline uintptr_t fw_sp(void) {
    uintptr_t sp;
    __asm volatile("mov %0, sp" : "=r"(sp));
    return sp;
}
#else
#define FW_STACK_MEASURED 0
static inline uintptr_t fw_sp(void) { return 0; }
#endif

/* Paints the free stack and takes `ref` (the case function's stack pointer) as the zero. */
void fw_stack_paint(uintptr_t ref);
/* Bytes below `ref` the case touched; -1 when the pattern at the stack's limit was
 * overwritten (the stack overflowed, the figure is meaningless), -2 on hosted builds. */
long fw_stack_used(void);

#endif
