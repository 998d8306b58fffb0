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
/** Print the verdict sentinel (CY-TEST-END PASS / FAIL n); the caller then returns. */
void cy_test_end(void);

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

#ifdef __cplusplus
}
#endif

#endif
