/*
 * kcheck_demo.h - the smallest kernel group there is, for the check mode's own test
 * (docs/kernels.md, "The check's own test"): one kernel that returns a value and writes
 * state, in assembly (kcheck_demo.S, the state's offsets from kcheck_demo_offsets.c) and C
 * (kcheck_demo_k.c).
 */
#ifndef KCHECK_DEMO_H
#define KCHECK_DEMO_H

#include <stdint.h>

/** The state the kernel writes (its offsets are generated for the assembly). */
typedef struct {
    uint16_t calls; /**< calls so far (wraps) */
    int32_t sum;    /**< the sum of the products (modulo 2^32) */
} kcheck_demo_acc_t;

/** acc->sum += a * b (modulo 2^32), acc->calls++; returns the product a * b. */
int32_t kcheck_demo_mac(kcheck_demo_acc_t *acc, int16_t a, int16_t b);

#endif
