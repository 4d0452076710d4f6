/* Start-up code for a Cortex-M4F / Cortex-M7 with newlib and semihosting (rdimon): the
 * vector table, the reset handler, and a fault handler that reports and stops.
 *
 * What has to happen before any C code runs, in this order:
 *   1. The FPU is switched on (CPACR: full access to coprocessors 10 and 11). Compiled with
 *      -mfloat-abi=hard, any function may use FP registers, and an FP instruction with the
 *      FPU off is a UsageFault. So the reset handler is a few instructions of assembly that
 *      enable it and only then branch to C.
 *   2. .data is copied from its load address in flash, .bss is zeroed (link.ld's symbols).
 *   3. Semihosting's standard handles are opened (initialise_monitor_handles, librdimon),
 *      so printf reaches the debugger (here QEMU's stdout), and the C library's
 *      constructors run (__libc_init_array; with -nostartfiles it calls the _init below).
 * Then main runs and its return value goes to exit(), which ends the QEMU run through the
 * semihosting SYS_EXIT call. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern uint32_t __data_start__[], __data_end__[], __data_load__[];
extern uint32_t __bss_start__[], __bss_end__[];
extern uint32_t __stack_top[];

extern int main(void);
extern void initialise_monitor_handles(void);
extern void __libc_init_array(void);

void Reset_Handler(void);
void Fault_Handler(void);
void Default_Handler(void);

/* -nostartfiles leaves out crti.o/crtn.o, whose _init and _fini __libc_init_array and exit
 * call; nothing needs them here. */
void _init(void) {}
void _fini(void) {}

/* Continues the reset once the FPU is on (called from Reset_Handler only). */
__attribute__((noreturn, used)) void reset_c(void) {
    uint32_t *src = __data_load__, *dst = __data_start__;
    while (dst < __data_end__) *dst++ = *src++;
    for (dst = __bss_start__; dst < __bss_end__;) *dst++ = 0;
    initialise_monitor_handles();
    __libc_init_array();
    exit(main());
}

/* CPACR (0xE000ED88) bits 20-23: CP10 and CP11 full access; DSB/ISB so that the next
 * instruction sees the FPU enabled (Armv7-M ARM, B3.2.20). */
__attribute__((naked, noreturn)) void Reset_Handler(void) {
    __asm volatile(
        "ldr r0, =0xE000ED88\n"
        "ldr r1, [r0]\n"
        "orr r1, r1, #(0xF << 20)\n"
        "str r1, [r0]\n"
        "dsb\n"
        "isb\n"
        "b reset_c\n");
}

/* A fault (a stack overflow into unmapped memory, an undefined instruction…) ends the run
 * with a message and a failing exit instead of a hang. */
void Fault_Handler(void) {
    static const char msg[] = "\nFAULT: the program took a hard/memory/bus/usage fault\n";
    write(2, msg, sizeof msg - 1);
    _exit(3);
}

void Default_Handler(void) {
    static const char msg[] = "\nFAULT: unexpected interrupt\n";
    write(2, msg, sizeof msg - 1);
    _exit(4);
}

/* The Armv7-M vector table: initial stack pointer, then the system exceptions. No device
 * interrupt is enabled by this program, so the table stops there. */
typedef union {
    uint32_t *stack;
    void (*handler)(void);
} vector;

__attribute__((section(".vectors"), used)) static const vector vectors[16] = {
    {.stack = __stack_top},
    {.handler = Reset_Handler},
    {.handler = Default_Handler}, /* NMI */
    {.handler = Fault_Handler},   /* HardFault */
    {.handler = Fault_Handler},   /* MemManage */
    {.handler = Fault_Handler},   /* BusFault */
    {.handler = Fault_Handler},   /* UsageFault */
    {0}, {0}, {0}, {0},           /* reserved */
    {.handler = Default_Handler}, /* SVCall */
    {.handler = Default_Handler}, /* DebugMonitor */
    {0},                          /* reserved */
    {.handler = Default_Handler}, /* PendSV */
    {.handler = Default_Handler}, /* SysTick */
};
