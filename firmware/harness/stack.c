#include "stack.h"

#if FW_STACK_MEASURED

#define PAINT 0xC5ACCE55u

extern uint32_t __stack_limit[]; /* link.ld */
static uintptr_t ref_sp;

__attribute__((noinline)) void fw_stack_paint(uintptr_t ref) {
    uint32_t *p = __stack_limit;
    uint32_t *end = (uint32_t *)(fw_sp() & ~(uintptr_t)3);
    ref_sp = ref;
    /* Everything below this function's own stack pointer is free. */
    while (p < end) *p++ = PAINT;
}

long fw_stack_used(void) {
    const uint32_t *p = __stack_limit;
    if (*p != PAINT) return -1;
    while ((uintptr_t)p < ref_sp && *p == PAINT) p++;
    return (uintptr_t)p >= ref_sp ? 0 : (long)(ref_sp - (uintptr_t)p);
}

#else

void fw_stack_paint(uintptr_t ref) { (void)ref; }
long fw_stack_used(void) { return -2; }

#endif
