/*
 * gnav_arith_k.c - the C twins of the groundnav kernels (gnav_arith.h, docs/kernels.md;
 * msp430/gnav_arith.S holds the same functions, built instead of this file there).
 */
#include "gnav_arith.h"

#include "hal/preempt.h"

void gnav_add64x2(int64_t *xy, const int32_t *v)
{
    xy[0] = (int64_t)((uint64_t)xy[0] + (uint64_t)(int64_t)v[0]);
    HAL_PREEMPT_POINT(); /* the harness may land an interrupt between the two */
    xy[1] = (int64_t)((uint64_t)xy[1] + (uint64_t)(int64_t)v[1]);
}

void gnav_sub64x2(int64_t *xy, const int32_t *v)
{
    xy[0] = (int64_t)((uint64_t)xy[0] - (uint64_t)(int64_t)v[0]);
    HAL_PREEMPT_POINT();
    xy[1] = (int64_t)((uint64_t)xy[1] - (uint64_t)(int64_t)v[1]);
}

void gnav_mac64(int64_t *acc, int16_t a, int16_t b)
{
    int32_t p = (int32_t)a * (int32_t)b;
    *acc = (int64_t)((uint64_t)*acc + (uint64_t)(int64_t)p);
}
