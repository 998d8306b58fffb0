/*
 * kernel_check.h - what the per-module wrappers of a kernel check image use (docs/kernels.md,
 * "Check mode").
 *
 * A check image links a module's assembly kernels AND their C twins (compiled with each
 * kernel's name renamed to NAME_c) and routes every call of a kernel through the module's
 * wrapper (ld.lld --wrap=NAME: callers reach __wrap_NAME, which reaches the assembly as
 * __real_NAME). A wrapper runs both, times each (KCHECK_RUN), compares every output (return
 * value, out-parameters, the state the kernel writes: the C twin runs on a copy) and on the
 * first difference prints
 *
 *     KERNEL-MISMATCH <kernel> <input names>=<inputs> asm=<outputs> c=<outputs>
 *
 * and stops the image (tools/msp430sim.py fails the test on that line). Otherwise it returns
 * the assembly's results, so the program's output is the normal image's, line for line.
 */
#ifndef KERNEL_CHECK_H
#define KERNEL_CHECK_H

#include <stdint.h>

#include "cy_test.h"

/** Cycles of one side of a kernel over its calls (32-bit counts: a kernel may run a million
 * times in one program). */
typedef struct {
    uint16_t max;
    uint32_t sum, n;
} kcheck_cycles_t;

/** The cycles of one kernel: the assembly's and the C twin's, as measured in its wrapper. */
typedef struct kcheck_stat {
    const char *name;
    kcheck_cycles_t asm_cycles, c_cycles;
    struct kcheck_stat *next; /* the list of the report, joined at the first call */
    uint8_t registered;
} kcheck_stat_t;

/** Initialiser of a wrapper's static kcheck_stat_t for kernel @p kname. */
#define KCHECK_STAT(kname)                                                                         \
    {                                                                                              \
        kname, {0, 0, 0}, {0, 0, 0}, 0, 0                                                          \
    }

/** Register @p st for the report (once; callers may be interrupt handlers). */
void kcheck_register(kcheck_stat_t *st);

/** Add a sample of @p cycles. */
void kcheck_add(kcheck_cycles_t *c, uint16_t cycles);

/** Run @p asm_stmt and then @p c_stmt, timing each into @p st. */
#define KCHECK_RUN(st, asm_stmt, c_stmt)                                                           \
    do {                                                                                           \
        kcheck_register(st);                                                                       \
        uint16_t k0_ = cy_bench_now();                                                             \
        asm_stmt;                                                                                  \
        uint16_t k1_ = cy_bench_now();                                                             \
        c_stmt;                                                                                    \
        uint16_t k2_ = cy_bench_now();                                                             \
        kcheck_add(&(st)->asm_cycles, (uint16_t)(k1_ - k0_ - cy_bench_overhead));                  \
        kcheck_add(&(st)->c_cycles, (uint16_t)(k2_ - k1_ - cy_bench_overhead));                    \
    } while (0)

/**
 * Compare the outputs of one call: @p n_out words from the assembly (@p out_asm) and from the C
 * twin (@p out_c). Equal: returns. Different: prints the KERNEL-MISMATCH line with the @p n_in
 * input words @p in (named by @p in_names, e.g. "y,x"; 64-bit values as two words, high
 * first) and stops the image.
 */
void kcheck_words(const char *kernel, const char *in_names, const uint32_t *in, uint8_t n_in,
                  const uint32_t *out_asm, const uint32_t *out_c, uint8_t n_out);

/**
 * Compare @p size bytes of state the kernel wrote: the assembly's (@p asm_state) and the C
 * twin's copy (@p c_state); on a difference the line names the byte offset and the word
 * there ("asm=@6:0x1234 c=@6:0x1235") and the image stops.
 */
void kcheck_bytes(const char *kernel, const char *in_names, const uint32_t *in, uint8_t n_in,
                  const void *asm_state, const void *c_state, uint16_t size);

#endif
