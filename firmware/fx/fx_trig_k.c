/*
 * fx_trig_k.c - the C twins of the trigonometry kernels (docs/kernels.md; msp430/fx_trig.S
 * holds the same functions, built instead of this file there): sin, cos and the
 * first-quadrant arctangent from the generated tables (tools/gen_fx_tables.py).
 */
#include "fx_internal.h"

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
static uint32_t mul16(uint16_t a, uint16_t b)
{
    return (uint32_t)a * b;
}

static fx_q30_t sin_q1(uint32_t x)
{
    uint32_t xr = x + 64u;
    uint16_t i = (uint16_t)(xr >> 23);
    uint16_t u = (uint16_t)(xr >> 7);
    uint32_t t0 = fx_sin_tab[i];
    uint16_t bend = (uint16_t)(mul16(fx_sin_corr[i], (uint16_t)(0u - u)) >> 16);
    uint32_t e = fx_sin_tab[i + 1u] - t0 + 2u * (uint32_t)bend;
    return (fx_q30_t)(t0 + mul16((uint16_t)(e >> 16), u) + (mul16((uint16_t)e, u) >> 16));
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

/* atan of the ratio q / 2^24 in [0, 0.5], binary angle: table of 1/256 steps, chord. */
static uint32_t atan_interp(uint32_t q)
{
    uint16_t i = (uint16_t)(q >> 16), u = (uint16_t)q;
    uint32_t t0 = fx_atan_tab[i];
    uint32_t d = fx_atan_tab[i + 1u] - t0; /* < 2^22 */
    return t0 + mul16((uint16_t)(d >> 16), u) + (mul16((uint16_t)d, u) >> 16);
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
    uint32_t num, den;
    bool turned = octant_ratio(ay, ax, &num, &den);
    /* q = floor(num 2^24 / den) <= 2^23: restoring division, 24 steps (num < den <= 2^31, so
     * the doubled remainder fits 32 bits) */
    uint32_t r = num, q = 0;
    for (uint8_t k = 0; k < 24u; k++) {
        uint16_t unused;
        r = fx_dbl32(r, 0, &unused);
        q = fx_dbl32(q, 0, &unused);
        if (r >= den) {
            r -= den;
            q |= 1u;
        }
    }
    uint32_t t = atan_interp(q);
    if (turned)
        t = 0x20000000u - t;
    if (swap)
        t = FX_ANGLE_QUARTER - t;
    return t;
}
