/*
 * fx_trig.c - sincos, tan, cot, the arctangents, asin and acos (fx.h), built on the
 * trigonometry kernels (fx_sin, fx_cos, fx_atan_q1: fx_trig_k.c or msp430/fx_trig.S), the
 * division and the square root.
 */
#include "fx_internal.h"

void fx_sincos(fx_angle_t a, fx_q30_t *s, fx_q30_t *c)
{
    *s = fx_sin(a);
    *c = fx_cos(a);
}

/*
 * n * 2^16 / d rounded, for tan (n = sin, d = cos) and cot (n = cos, d = sin) of the angle
 * a, saturated to +-FX_Q16_MAX with the sign the function has on that side of its pole.
 * d is 0 up to 64 LSB of angle off the pole (the rounding of sin/cos), so there the side
 * comes from a: delta = a - pole is small and positive (modulo a half turn) just after the
 * pole, where tan comes from -infinity and cot from +infinity (after_neg). Exactly at the
 * pole the sign is that of n.
 */
static fx_q16_t ratio_q16(int32_t n, int32_t d, uint32_t delta, bool after_neg)
{
    int32_t r;
    if (fx_div_shift(n, d, 16, &r))
        return r;
    bool neg;
    if (d != 0)
        neg = (n < 0) != (d < 0);
    else if ((delta & 0x7FFFFFFFu) == 0)
        neg = n < 0;
    else if ((delta & 0x40000000u) == 0) /* just after the pole */
        neg = after_neg;
    else
        neg = !after_neg;
    return neg ? -FX_Q16_MAX : FX_Q16_MAX;
}

fx_q16_t fx_tan(fx_angle_t a)
{
    return ratio_q16(fx_sin(a), fx_cos(a), a - FX_ANGLE_QUARTER, true);
}

fx_q16_t fx_cot(fx_angle_t a)
{
    return ratio_q16(fx_cos(a), fx_sin(a), a, false);
}

fx_angle_t fx_atan2(int32_t y, int32_t x)
{
    uint32_t ax = fx_magnitude(x), ay = fx_magnitude(y);
    if ((ax | ay) == 0)
        return 0;
    /* The first-quadrant angle placed in the quadrant of (x, y). */
    fx_angle_t t = fx_atan_q1(ay, ax);
    if (x < 0)
        t = FX_ANGLE_HALF - t;
    if (y < 0)
        t = 0u - t;
    return t;
}

fx_angle_t fx_atan_ratio(int32_t num, int32_t den)
{
    uint32_t an = fx_magnitude(num), ad = fx_magnitude(den);
    if ((an | ad) == 0)
        return 0;
    fx_angle_t t = fx_atan_q1(an, ad);
    return (num < 0) != (den < 0) ? 0u - t : t;
}

fx_angle_t fx_atan_q16(fx_q16_t t)
{
    return fx_atan_ratio(t, FX_Q16_ONE);
}

/* |v| clamped to 2^30 and sqrt(2^60 - v^2), the other leg of the unit right triangle. */
static uint32_t unit_leg(fx_q30_t v, uint32_t *mag)
{
    uint32_t m = fx_magnitude(v);
    if (m > (uint32_t)FX_Q30_ONE)
        m = (uint32_t)FX_Q30_ONE;
    *mag = m;
    return fx_sqrt64(((uint64_t)1 << 60) - fx_umul64(m, m));
}

fx_angle_t fx_asin(fx_q30_t s)
{
    uint32_t m, c = unit_leg(s, &m);
    fx_angle_t t = fx_atan_q1(m, c);
    return s < 0 ? 0u - t : t;
}

fx_angle_t fx_acos(fx_q30_t c)
{
    uint32_t m, s = unit_leg(c, &m);
    fx_angle_t t = fx_atan_q1(s, m);
    return c < 0 ? FX_ANGLE_HALF - t : t;
}
