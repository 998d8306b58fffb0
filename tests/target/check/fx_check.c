/*
 * fx_check.c - the check-mode wrappers of the fx kernels (docs/kernels.md, kernel_check.h):
 * each call runs the assembly (__real_NAME) and the C twin (NAME_c), compares every output
 * and returns the assembly's.
 */
#include "fx_internal.h"
#include "kernel_check.h"

#define HI(v) ((uint32_t)((uint64_t)(v) >> 32))
#define LO(v) ((uint32_t)(v))

/* One wrapper per kernel: the prototypes of its three names, then the wrapper. */
#define KERNEL_NAMES(ret, name, params)                                                            \
    ret __real_##name params;                                                                      \
    ret __wrap_##name params;                                                                      \
    ret name##_c params

KERNEL_NAMES(uint64_t, fx_umul64, (uint32_t a, uint32_t b));
uint64_t __wrap_fx_umul64(uint32_t a, uint32_t b)
{
    static kcheck_stat_t st = KCHECK_STAT("fx_umul64");
    uint64_t ra, rc;
    KCHECK_RUN(&st, ra = __real_fx_umul64(a, b), rc = fx_umul64_c(a, b));
    const uint32_t in[] = {a, b}, oa[] = {HI(ra), LO(ra)}, oc[] = {HI(rc), LO(rc)};
    kcheck_words("fx_umul64", "a,b", in, 2, oa, oc, 2);
    return ra;
}

KERNEL_NAMES(uint16_t, fx_udiv32_16, (uint32_t n, uint16_t d, uint16_t *rem));
uint16_t __wrap_fx_udiv32_16(uint32_t n, uint16_t d, uint16_t *rem)
{
    static kcheck_stat_t st = KCHECK_STAT("fx_udiv32_16");
    uint16_t qa, qc, rc;
    KCHECK_RUN(&st, qa = __real_fx_udiv32_16(n, d, rem), qc = fx_udiv32_16_c(n, d, &rc));
    const uint32_t in[] = {n, d}, oa[] = {qa, *rem}, oc[] = {qc, rc};
    kcheck_words("fx_udiv32_16", "n,d", in, 2, oa, oc, 2);
    return qa;
}

/* fx_div_shift writes *out only on success: both sides start from the same value of *out,
 * so an untouched *out compares equal too. */
KERNEL_NAMES(bool, fx_div_shift, (int32_t num, int32_t den, uint8_t shift, int32_t *out));
bool __wrap_fx_div_shift(int32_t num, int32_t den, uint8_t shift, int32_t *out)
{
    static kcheck_stat_t st = KCHECK_STAT("fx_div_shift");
    int32_t oc_v = *out;
    bool ra, rc;
    KCHECK_RUN(&st, ra = __real_fx_div_shift(num, den, shift, out),
               rc = fx_div_shift_c(num, den, shift, &oc_v));
    const uint32_t in[] = {(uint32_t)num, (uint32_t)den, shift};
    const uint32_t oa[] = {ra, (uint32_t)*out}, oc[] = {rc, (uint32_t)oc_v};
    kcheck_words("fx_div_shift", "num,den,shift", in, 3, oa, oc, 2);
    return ra;
}

/* The kernels of two 32-bit operands and one 32-bit result (the macro ends in a declaration,
 * so that its use takes a semicolon). */
#define WRAP_2x32(ret, name, t1, t2)                                                               \
    KERNEL_NAMES(ret, name, (t1 a, t2 b));                                                         \
    ret __wrap_##name(t1 a, t2 b)                                                                  \
    {                                                                                              \
        static kcheck_stat_t st = KCHECK_STAT(#name);                                              \
        ret ra, rc;                                                                                \
        KCHECK_RUN(&st, ra = __real_##name(a, b), rc = name##_c(a, b));                            \
        const uint32_t in[] = {(uint32_t)a, (uint32_t)b}, oa[] = {(uint32_t)ra},                   \
                       oc[] = {(uint32_t)rc};                                                      \
        kcheck_words(#name, "a,b", in, 2, oa, oc, 1);                                              \
        return ra;                                                                                 \
    }                                                                                              \
    extern int kcheck_unused_##name

WRAP_2x32(int32_t, fx_mul_q30, int32_t, fx_q30_t);
WRAP_2x32(int32_t, fx_mul_q16, int32_t, int32_t);
WRAP_2x32(fx_angle_t, fx_atan_q1, uint32_t, uint32_t);

/* The kernels of one 32-bit operand. */
#define WRAP_1x32(ret, name, t1)                                                                   \
    KERNEL_NAMES(ret, name, (t1 a));                                                               \
    ret __wrap_##name(t1 a)                                                                        \
    {                                                                                              \
        static kcheck_stat_t st = KCHECK_STAT(#name);                                              \
        ret ra, rc;                                                                                \
        KCHECK_RUN(&st, ra = __real_##name(a), rc = name##_c(a));                                  \
        const uint32_t in[] = {(uint32_t)a}, oa[] = {(uint32_t)ra}, oc[] = {(uint32_t)rc};         \
        kcheck_words(#name, "a", in, 1, oa, oc, 1);                                                \
        return ra;                                                                                 \
    }                                                                                              \
    extern int kcheck_unused_##name

WRAP_1x32(fx_q30_t, fx_sin, fx_angle_t);
WRAP_1x32(fx_q30_t, fx_cos, fx_angle_t);
