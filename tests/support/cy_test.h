/*
 * cy_test.h - what a test program needs on both worlds: printing, checks, the verdict, the
 * simulator choreography and cycle measurement. On the MSP430 the output goes to the
 * simulator console and tools/msp430sim.py judges it; on the host the same program prints to
 * stdout, so the two outputs can be compared line by line.
 */
#ifndef CY_TEST_H
#define CY_TEST_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Print a string. */
void cy_print(const char *s);
/** Print @p v as exactly 4, 8 or 16 lower-case hex digits. */
void cy_print_hex16(uint16_t v);
void cy_print_hex32(uint32_t v);
void cy_print_hex64(uint64_t v);
/** Print a signed decimal. */
void cy_print_dec(int32_t v);
/** Print a newline. */
void cy_println(void);

/** Record a failed check (and print "FAIL <what>") when @p ok is zero. */
void cy_check(int ok, const char *what);
/** Number of failed checks so far. */
uint16_t cy_failures(void);
/** Print the verdict sentinel (CY-TEST-END PASS / FAIL n); the caller then returns. In a
 * kernel check image it first prints the kernels' cycle figures (cy_kernel_check_end). */
void cy_test_end(void);

/**
 * 1 in a kernel check image (docs/kernels.md: every kernel call runs the assembly and its C
 * twin and compares them), 0 in every other image and on the host. The cycle and stack figures
 * such an image measures are not the program's own: cy_bench_report() and cy_stack_report()
 * print nothing there, and a program asserts its cycle or stack bounds only when this is 0.
 */
int cy_kernel_check_mode(void);

/** Called by cy_test_end(): prints the kernels' figures in a check image, nothing elsewhere. */
void cy_kernel_check_end(void);

/** The next word of Marsaglia's xorshift32 generator (13, 17, 5) kept in @p *state (seed it
 * non-zero): the same sequence on both worlds, for test vectors. */
uint32_t cy_rand32(uint32_t *state);

/**
 * Ask the simulator to apply the queued `@sim` lines and resume (a breakpoint sits here).
 * On the host it does nothing: host twins of target tests do not use the choreography.
 */
void cy_target_sync(void);

/** Free-running cycle counter (Timer_B on SMCLK = MCLK); 0 on the host. */
void cy_bench_init(void);
uint16_t cy_bench_now(void);

/** Accumulates cycle samples of one measured operation. */
typedef struct {
    const char *name;
    uint32_t max;
    uint32_t sum;
    uint16_t n;
} cy_bench_stat_t;

/** Add a sample of @p cycles. */
void cy_bench_add(cy_bench_stat_t *st, uint32_t cycles);
/** Print "@cycles name max mean n" for the cycle report. */
void cy_bench_report(const cy_bench_stat_t *st);

/** Cycles the start/stop pair itself costs (subtracted by CY_BENCH). */
extern uint16_t cy_bench_overhead;

/** Measure one statement: st gets the cycles it took, excluding the counter reads. */
#define CY_BENCH(st, stmt)                                                                         \
    do {                                                                                           \
        uint16_t t0_ = cy_bench_now();                                                             \
        stmt;                                                                                      \
        uint16_t t1_ = cy_bench_now();                                                             \
        cy_bench_add((st), (uint16_t)(t1_ - t0_ - cy_bench_overhead));                             \
    } while (0)

/**
 * Stack depth of a call (MSP430): cy_stack_fill() fills the free RAM below the stack (from
 * the end of .bss/.noinit to a little below its own frame) with a pattern; cy_stack_used()
 * returns how many bytes below @p mark (the caller's stack pointer, cy_sp()) were written
 * since, interrupt frames included. 0 on the host.
 */
void cy_stack_fill(void);
uint16_t cy_stack_used(uint16_t mark);

#ifdef __MSP430__
static inline uint16_t cy_sp(void)
{
    uint16_t sp;
    __asm__ volatile("mov r1, %0" : "=r"(sp));
    return sp;
}
#else
static inline uint16_t cy_sp(void)
{
    return 0;
}
#endif

/** The deepest stack of one measured call. */
typedef struct {
    const char *name;
    uint16_t max;
} cy_stack_stat_t;

/** Print "@stack-use name bytes" for the cycle report. */
void cy_stack_report(const cy_stack_stat_t *st);

/** Measure the stack one statement needs (on top of its caller's frame). */
#define CY_STACK(st, stmt)                                                                         \
    do {                                                                                           \
        uint16_t m_ = cy_sp();                                                                     \
        cy_stack_fill();                                                                           \
        stmt;                                                                                      \
        uint16_t u_ = cy_stack_used(m_);                                                           \
        if (u_ > (st)->max)                                                                        \
            (st)->max = u_;                                                                        \
    } while (0)

#ifdef __cplusplus
}
#endif

#endif
