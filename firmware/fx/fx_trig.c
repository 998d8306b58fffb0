/*
 * fx_trig.c - sin, cos, tan, cot, atan2, asin, acos (fx.h) from the generated tables
 * (tools/gen_fx_tables.py). The integer steps here define the results bit for bit: the
 * MSP430 assembly (msp430/fx_trig.S, built instead of the functions under FX_ASM) performs
 * the very same steps.
 */
#include "fx_internal.h"

#ifndef FX_ASM /* MSP430: msp430/fx_trig.S */
/*
 * sin of x in [0, 2^30] (the first quadrant, closed), Q1.30, non-negative.
 *
 * x is rounded to the nearest 2^7 (the 16-bit fraction u of a 2^23 step i), then
 *   sin = T[i] + t (D + 2 G (1 - t)),   t = u / 2^16, D = T[i+1] - T[i]
 * the chord plus the second-order term 2 G t (1 - t) (G = fx_sin_corr in Q29 units of
 * h^2 m / 2, see tools/gen_fx_tables.py), in Horner form: the slope is
 * D + 2 ((G (2^16 - u)) >> 16), and then two multiplies (one 32 x 16). With u = 0 the slope
 * is multiplied by 0, so (2^16 - u) may be taken modulo 2^16.
 */
static fx_q30_t sin_q1(uint32_t x)
{
    uint32_t xr = x + 64u;
    uint16_t i = (uint16_t)(xr >> 23);
    uint16_t u = (uint16_t)(xr >> 7);
    uint32_t t0 = fx_sin_tab[i];
    uint16_t bend = (uint16_t)(((uint32_t)fx_sin_corr[i] * (uint16_t)(0u - u)) >> 16);
    uint32_t e = fx_sin_tab[i + 1u] - t0 + 2u * (uint32_t)bend;
    return (fx_q30_t)(t0 + (uint32_t)(uint16_t)(e >> 16) * u + (((uint32_t)(uint16_t)e * u) >> 16));
}

fx_q30_t fx_sin(fx_angle_t a)
{
    uint16_t quadrant = (uint16_t)(a >> 30);
    uint32_t x = a & 0x3FFFFFFFu;
    if (quadrant & 1u)
        x = 0x40000000u - x;
    fx_q30_t s = sin_q1(x);
    return (quadrant & 2u) ? -s : s;
}

fx_q30_t fx_cos(fx_angle_t a)
{
    return fx_sin(a + FX_ANGLE_QUARTER);
}

#endif

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

static uint32_t magnitude(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

#ifndef FX_ASM /* MSP430: msp430/fx_trig.S */
/* atan of the ratio q / 2^24 in [0, 0.5], binary angle: table of 1/256 steps, chord. */
static uint32_t atan_interp(uint32_t q)
{
    uint16_t i = (uint16_t)(q >> 16), u = (uint16_t)q;
    uint32_t t0 = fx_atan_tab[i];
    uint32_t d = fx_atan_tab[i + 1u] - t0; /* < 2^22 */
    return t0 + (uint32_t)(uint16_t)(d >> 16) * u + (((uint32_t)(uint16_t)d * u) >> 16);
}

/*
 * Octant reduction of the arctangent, for 0 <= ay <= ax, 0 < ax <= 2^31: both are
 * halved when ax >= 2^30 (so that ax + ay <= 2^31; the ratio keeps 29 bits), and a ratio
 * above 1/2 (ay > ax - ay) is turned by 45 degrees, atan(r) = 45 deg - atan((1-r) / (1+r)),
 * so the table only spans [0, 1/2]. Leaves num <= den / 2, 0 < den <= 2^31 in *num, *den
 * and says whether it turned.
 */
static bool octant_ratio(uint32_t ay, uint32_t ax, uint32_t *num, uint32_t *den)
{
    if (ax >= 0x40000000u) {
        ax >>= 1;
        ay >>= 1;
    }
    uint32_t rest = ax - ay;
    bool turned = ay > rest;
    *num = turned ? rest : ay;
    *den = turned ? ax + ay : ax;
    return turned;
}

fx_angle_t fx_atan_q1(uint32_t ay, uint32_t ax)
{
    bool swap = ay > ax;
    if (swap) {
        uint32_t t = ax;
        ax = ay;
        ay = t;
    }
    uint32_t num, den, rem;
    bool turned = octant_ratio(ay, ax, &num, &den);
    /* q = floor(num 2^24 / den) <= 2^23 */
    uint32_t t = atan_interp(fx_udiv64_32(num >> 8, num << 24, den, &rem));
    if (turned)
        t = 0x20000000u - t;
    if (swap)
        t = FX_ANGLE_QUARTER - t;
    return t;
}

fx_angle_t fx_atan2(int32_t y, int32_t x)
{
    uint32_t ax = magnitude(x), ay = magnitude(y);
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
    uint32_t an = magnitude(num), ad = magnitude(den);
    if ((an | ad) == 0)
        return 0;
    fx_angle_t t = fx_atan_q1(an, ad);
    return (num < 0) != (den < 0) ? 0u - t : t;
}
#endif

fx_angle_t fx_atan_q16(fx_q16_t t)
{
    return fx_atan_ratio(t, FX_Q16_ONE);
}

/* |v| clamped to 2^30 and sqrt(2^60 - v^2), the other leg of the unit right triangle. */
static uint32_t unit_leg(fx_q30_t v, uint32_t *mag)
{
    uint32_t m = magnitude(v);
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
