/*
 * groundnav_check.c - the check-mode wrappers of the groundnav kernels (docs/kernels.md,
 * kernel_check.h): the C twin runs on a copy of the accumulators, which are compared after.
 */
#include "gnav_arith.h"
#include "kernel_check.h"

void __real_gnav_add64x2(int64_t *xy, const int32_t *v);
void __wrap_gnav_add64x2(int64_t *xy, const int32_t *v);
void gnav_add64x2_c(int64_t *xy, const int32_t *v);
void __real_gnav_sub64x2(int64_t *xy, const int32_t *v);
void __wrap_gnav_sub64x2(int64_t *xy, const int32_t *v);
void gnav_sub64x2_c(int64_t *xy, const int32_t *v);
void __real_gnav_mac64(int64_t *acc, int16_t a, int16_t b);
void __wrap_gnav_mac64(int64_t *acc, int16_t a, int16_t b);
void gnav_mac64_c(int64_t *acc, int16_t a, int16_t b);

/* add64x2 and sub64x2: the two accumulators before the call and the step are the inputs. */
static void pair(const char *name, kcheck_stat_t *st, void (*real)(int64_t *, const int32_t *),
                 void (*twin)(int64_t *, const int32_t *), int64_t *xy, const int32_t *v)
{
    const uint32_t in[] = {(uint32_t)((uint64_t)xy[0] >> 32),
                           (uint32_t)xy[0],
                           (uint32_t)((uint64_t)xy[1] >> 32),
                           (uint32_t)xy[1],
                           (uint32_t)v[0],
                           (uint32_t)v[1]};
    int64_t copy[2] = {xy[0], xy[1]};
    KCHECK_RUN(st, real(xy, v), twin(copy, v));
    kcheck_bytes(name, "x_hi,x_lo,y_hi,y_lo,v0,v1", in, 6, xy, copy, sizeof copy);
}

void __wrap_gnav_add64x2(int64_t *xy, const int32_t *v)
{
    static kcheck_stat_t st = KCHECK_STAT("gnav_add64x2");
    pair("gnav_add64x2", &st, __real_gnav_add64x2, gnav_add64x2_c, xy, v);
}

void __wrap_gnav_sub64x2(int64_t *xy, const int32_t *v)
{
    static kcheck_stat_t st = KCHECK_STAT("gnav_sub64x2");
    pair("gnav_sub64x2", &st, __real_gnav_sub64x2, gnav_sub64x2_c, xy, v);
}

void __wrap_gnav_mac64(int64_t *acc, int16_t a, int16_t b)
{
    static kcheck_stat_t st = KCHECK_STAT("gnav_mac64");
    const uint32_t in[] = {(uint32_t)((uint64_t)*acc >> 32), (uint32_t)*acc, (uint32_t)(int32_t)a,
                           (uint32_t)(int32_t)b};
    int64_t copy = *acc;
    KCHECK_RUN(&st, __real_gnav_mac64(acc, a, b), gnav_mac64_c(&copy, a, b));
    kcheck_bytes("gnav_mac64", "acc_hi,acc_lo,a,b", in, 4, acc, &copy, sizeof copy);
}
