/* startup.c - a minimal Cortex-M7 start-up for QEMU's mps2-an500 board: vector table,
 * reset handler (FPU on, stack painted, .data copied, .bss and the arena zeroed),
 * semihosting output and exit; after the frames, the stack's high-water mark and what
 * the RAM holds.
 *
 * Run:  qemu-system-arm -M mps2-an500 -nographic -semihosting -kernel fw.elf
 *
 * Order matters: the library is built with -mfloat-abi=hard, so any float instruction
 * before CPACR grants CP10/CP11 access raises a NOCP UsageFault. The reset handler is
 * therefore naked assembly up to the point where the FPU is on; C starts after the ISB. */
#include <stddef.h>
#include <stdint.h>

#include "fw.h"

/* Linker-script symbols (mps2_an500.ld). Declared as functions or arrays so that their
 * address is all that is used. */
extern void fw_stack_top(void);
extern uint32_t fw_data_load[], fw_data_start[], fw_data_end[], fw_bss_start[], fw_bss_end[];
extern uint32_t fw_arena_start[], fw_arena_end[], fw_stack_bottom[];
extern uint8_t fw_ram_start[], fw_ram_end[];

/* What the reset handler writes over the whole stack before anything runs on it: the
 * lowest word that no longer holds it is as deep as the stack went. */
#define FW_STACK_PAINT 0xDEADBEEFu

void fw_reset(void) __attribute__((naked, noreturn));
void fw_start(void) __attribute__((noreturn, used));
static void fw_fault(void) __attribute__((noreturn));

/* ---- Semihosting (ARM DUI0471 / the Arm semihosting spec): bkpt 0xAB, op in r0 ------ */

#define SYS_WRITE0 0x04
#define SYS_EXIT 0x18
#define ADP_STOPPED_APPLICATION_EXIT 0x20026 /* QEMU exits with status 0 */
#define ADP_STOPPED_RUNTIME_ERROR 0x20023    /* QEMU exits with status 1 */

static uint32_t semihost(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

static void write_semihost(const char *text)
{
    semihost(SYS_WRITE0, text);
}

static void __attribute__((noreturn)) exit_semihost(int failed)
{
    /* On 32-bit ARM, SYS_EXIT takes the reason itself in r1, not a parameter block. */
    semihost(SYS_EXIT, (const void *)(uintptr_t)(failed ? ADP_STOPPED_RUNTIME_ERROR
                                                        : ADP_STOPPED_APPLICATION_EXIT));
    for (;;) {
    }
}

/* ---- Vector table: initial SP, then the handlers (no interrupts are enabled) -------- */

typedef void (*fw_vector)(void);
__attribute__((section(".vectors"), used)) static const fw_vector vectors[16] = {
    fw_stack_top, /* initial main stack pointer */
    fw_reset,     /* reset */
    fw_fault,     /* NMI */
    fw_fault,     /* HardFault */
    fw_fault,     /* MemManage */
    fw_fault,     /* BusFault */
    fw_fault,     /* UsageFault (NOCP if the FPU were still off) */
    0, 0, 0, 0,   /* reserved */
    fw_fault,     /* SVCall */
    fw_fault,     /* DebugMonitor */
    0,            /* reserved */
    fw_fault,     /* PendSV */
    fw_fault,     /* SysTick */
};

/* CPACR (0xE000ED88) |= CP10 and CP11 full access (0xF << 20); DSB so the write has
 * completed, ISB so that the following instructions are fetched with the FPU enabled.
 * Then the whole stack, fw_stack_bottom .. fw_stack_top, is painted with FW_STACK_PAINT
 * (nothing has used it yet: SP is still the vector table's initial value, and this code
 * touches registers only). movw/movt instead of a literal pool: nothing here may depend
 * on section layout. */
void fw_reset(void)
{
    __asm__ volatile("movw r0, #0xED88\n\t"
                     "movt r0, #0xE000\n\t"
                     "ldr r1, [r0]\n\t"
                     "orr r1, r1, #(0xF << 20)\n\t"
                     "str r1, [r0]\n\t"
                     "dsb\n\t"
                     "isb\n\t"
                     "movw r0, #:lower16:fw_stack_bottom\n\t"
                     "movt r0, #:upper16:fw_stack_bottom\n\t"
                     "movw r1, #:lower16:fw_stack_top\n\t"
                     "movt r1, #:upper16:fw_stack_top\n\t"
                     "movw r2, #0xBEEF\n\t" /* FW_STACK_PAINT */
                     "movt r2, #0xDEAD\n\t"
                     "1:\n\t"
                     "cmp r0, r1\n\t"
                     "bhs 2f\n\t"
                     "str r2, [r0], #4\n\t"
                     "b 1b\n\t"
                     "2:\n\t"
                     "b fw_start\n\t");
}

static void put_hex_line(const char *label, uint32_t x)
{
    static const char hex[] = "0123456789abcdef";
    char buf[80];
    size_t n = 0;
    int shift;
    while (*label != '\0' && n < sizeof buf - 10u)
        buf[n++] = *label++;
    for (shift = 28; shift >= 0; shift -= 4)
        buf[n++] = hex[(x >> shift) & 0xFu];
    buf[n++] = '\n';
    buf[n] = '\0';
    write_semihost(buf);
}

static uint32_t bytes_between(const void *lo, const void *hi)
{
    return (uint32_t)((uintptr_t)hi - (uintptr_t)lo);
}

/* How deep the stack went (the bytes from the lowest word that lost FW_STACK_PAINT to
 * the top), and what the two RAMs hold. Lines not compared with the host's, which prints
 * "n/a" for the stack: a hosted stack is not ours to paint. */
static void put_memory(void)
{
    const uint32_t *p = fw_stack_bottom, *top = (const uint32_t *)(uintptr_t)fw_stack_top;
    while (p < top && *p == FW_STACK_PAINT)
        p++;
    fw_line_str("stack high water ");
    fw_line_u32(bytes_between(p, top));
    fw_line_str(" of ");
    fw_line_u32(bytes_between(fw_stack_bottom, top));
    fw_line_str(" bytes (painted at reset)");
    fw_line_end();
    fw_line_str("ram: ssram23 arena ");
    fw_line_u32(bytes_between(fw_arena_start, fw_arena_end));
    fw_line_str(" + .data+.bss ");
    fw_line_u32(bytes_between(fw_data_start, fw_data_end) + bytes_between(fw_bss_start, fw_bss_end));
    fw_line_str(" + stack ");
    fw_line_u32(bytes_between(fw_stack_bottom, top));
    fw_line_str(" of ");
    fw_line_u32(bytes_between(fw_ram_start, fw_ram_end));
    fw_line_str(" bytes");
    fw_line_end();
}

void fw_start(void)
{
    uint32_t *src = fw_data_load, *dst = fw_data_start;
    uint32_t fpscr;
    int rc;

    while (dst < fw_data_end)
        *dst++ = *src++;
    for (dst = fw_bss_start; dst < fw_bss_end; dst++)
        *dst = 0u;
    for (dst = fw_arena_start; dst < fw_arena_end; dst++)
        *dst = 0u;

    /* The float environment the host has (IEEE 754: round to nearest, subnormals kept,
     * NaN operands propagated): FPSCR.RMode = 0, FZ (bit 24) = 0, DN (bit 25) = 0. Those
     * are the Cortex-M7 reset values; an RTOS or vendor start-up may set FZ/DN, so the
     * example states what it found and then makes sure. */
    __asm__ volatile("vmrs %0, fpscr" : "=r"(fpscr));
    put_hex_line("target cortex-m7 fpscr at reset 0x", fpscr);
    fpscr &= ~((3u << 22) | (1u << 24) | (1u << 25));
    __asm__ volatile("vmsr fpscr, %0" : : "r"(fpscr));

    rc = fw_run(write_semihost);
    put_memory();
    exit_semihost(rc != 0);
}

static void fw_fault(void)
{
    write_semihost("FAIL: fault exception (vector table handler)\n");
    exit_semihost(1);
}
