/*
 * tri_k.c - the C twins of the triangulation kernels optical_tri_core and optical_tri_quality
 * (optical/fastmath.h; docs/optical.md "O9" derives them; the assembly: msp430/optical_tri.S).
 * The definition of every result: the build takes this file or the assembly whole, and the
 * check images run both on every call (docs/kernels.md).
 */
#include <stdint.h>

#include "optical/fastmath.h"

/* floor(v / 2^n), n < 32 */
static int32_t asr(int32_t v, uint8_t n)
{
    return v < 0 ? (int32_t) ~(~(uint32_t)v >> n) : (int32_t)((uint32_t)v >> n);
}

/* x = hi(x) 2^16 + lo(x): lo the low word read as signed, |hi| <= 2^15 for |x| < 2^31 - 2^15 */
static int32_t lo16(int32_t x)
{
    return (int16_t)(uint16_t)(uint32_t)x;
}

static int32_t hi16(int32_t x)
{
    return (int16_t)(uint16_t)(((uint32_t)x + 0x8000u) >> 16);
}

/*
 * sum of x[i] y[i] / 2^32 (i < n): sum of hi hi + floor(sum of (hi lo + lo hi) / 2^16), the
 * products lo lo dropped (each below 2^30: a quarter unit). Every caller keeps both partial
 * sums below 2^31 (the MSP430 accumulates them in its multiplier).
 */
static int32_t dot(const int32_t *x, const int32_t *y, uint8_t n)
{
    int32_t hh = 0, m = 0;
    for (uint8_t i = 0; i < n; i++) {
        hh += hi16(x[i]) * hi16(y[i]);
        m += hi16(x[i]) * lo16(y[i]) + lo16(x[i]) * hi16(y[i]);
    }
    return hh + asr(m, 16);
}

/* The left shifts that bring m (nonzero) to 2^top or more. */
static uint8_t lead(uint32_t m, uint8_t top)
{
    uint8_t n = 0;
    for (; m < (1ul << top); m <<= 1)
        n++;
    return n;
}

static uint32_t tmag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static uint32_t mag2(int32_t a, int32_t b)
{
    return tmag(a) | tmag(b);
}

/*
 * R' = 2^(52 + g) / q for q in [2^22, 2^25), g = 9 - n with q 2^n in [2^31, 2^32): within 16
 * units (2^-25; measured over every 16-bit head of q 2^n and 300,000 random q: 15.4), in
 * [2^29, 2^30]. One Newton step on the multiplier from optical_recip_tab's interpolated
 * reciprocal r0 of the head qh (r0 = 2^46 / (q 2^n) within 1.1e-4, so |E| < 2^17):
 * R' = r0 2^15 (1 + E / 2^30), E = 2^30 - q 2^n r0 / 2^16, the product in 16-bit parts.
 */
static uint32_t recip_q(uint32_t q, uint8_t *g)
{
    uint8_t n = lead(q, 31);
    uint32_t qn = q << n;
    uint16_t qh = (uint16_t)(qn >> 16), ql = (uint16_t)qn;
    uint16_t i = (uint16_t)((qh >> 9) - 64u), f = (uint16_t)(qh << 7);
    uint16_t d = (uint16_t)(optical_recip_tab[i] - optical_recip_tab[i + 1u]);
    uint16_t r0 = (uint16_t)(optical_recip_tab[i] - (((uint32_t)d * f + 0x8000u) >> 16));
    uint32_t s = (uint32_t)qh * r0 + (((uint32_t)ql * r0) >> 16);
    int16_t e2 = (int16_t)(uint16_t)((0x40000000u - s) >> 2); /* E / 4: |E| < 2^17 */
    int32_t p = (int32_t)(r0 >> 1) * e2;
    *g = (uint8_t)(9u - n);
    return ((uint32_t)r0 << 15) + (uint32_t)asr(p, 12);
}

int8_t optical_tri_core(int32_t v[4], const int32_t sc[4], optical_tsol_t *out)
{
    uint32_t m = mag2(v[0], v[1]) | mag2(v[2], v[3]);
    if (m >= (1ul << 27))
        return OPTICAL_E_ARG;
    if ((v[0] | v[1]) == 0 || (v[2] | v[3]) == 0 || (v[0] == v[2] && v[1] == v[3]))
        return OPTICAL_E_DEGENERATE;
    /* lambda: the largest component to [2^28, 2^29) */
    uint8_t sigma = lead(m, 28);
    for (uint8_t i = 0; i < 4; i++)
        v[i] = (int32_t)((uint32_t)v[i] << sigma);
    int32_t s1 = sc[0], c1 = sc[1], s2 = sc[2], c2 = sc[3];
    /* A = R(alpha1) b1 / 4, C = R(-alpha2) b3 / 4 */
    int32_t r[5][2] = {{c1, -s1}, {s1, c1}, {c2, s2}, {-s2, c2}, {s2, s1}};
    int32_t ax = dot(r[0], &v[0], 2), ay = dot(r[1], &v[0], 2);
    int32_t cx = dot(r[2], &v[2], 2), cy = dot(r[3], &v[2], 2);
    /* V = (s2 a + s1 c) / 16 = U / 16; 16 K = cross(4 A, 4 C) / 2^32 = kappa / 2^32 (the
     * halves of 4 A and 4 C: the products lo lo dropped stay below a unit) */
    int32_t xs[2] = {ax, cx}, ys[2] = {ay, cy};
    int32_t u[3] = {dot(r[4], xs, 2), dot(r[4], ys, 2), 0};
    int32_t k4[2] = {ax * 4, cx * 4}, kk[2] = {cy * 4, -ay * 4};
    int32_t k = dot(k4, kk, 2);
    m = mag2(u[0], u[1]);
    if (m == 0)
        return OPTICAL_E_SINGULAR;
    /* U^ = V 2^e, its larger component in [2^27, 2^28) (V < 2^26.5: e >= 1); K' = 16 K
     * 2^(e - 4) = r2 |U^| / 2^32: 2^28 or more only when beacon 2 lies beyond 2^31 lambda
     * (refused below) */
    uint8_t e = lead(m, 27);
    u[0] = (int32_t)((uint32_t)u[0] << e);
    u[1] = (int32_t)((uint32_t)u[1] << e);
    if (e < 4) {
        k = asr(k, (uint8_t)(4u - e));
    } else {
        if (k >= (1l << (32 - e)) || k < -(1l << (32 - e)))
            return OPTICAL_E_SINGULAR;
        k = (int32_t)((uint32_t)k << (e - 4u));
    }
    u[2] = k;
    /* Each beacon ahead along its sighting: l_i = (a U + c_i kappa) 2^e / 2^38 = +-r_i |U^| /
     * 2^34 (i = 1, 3) with the sign of K' = +-r2 |U^| / 2^32: on the other arc one of them has
     * the other sign. */
    int32_t la[3] = {ax, ay, c1}, lc[3] = {cx, cy, c2};
    int32_t l1 = dot(la, u, 3), l3 = dot(lc, u, 3);
    if (k == 0 || (l1 ^ k) < 0 || (l3 ^ k) < 0 || l1 == 0 || l3 == 0)
        return OPTICAL_E_INCONSISTENT;
    /* 1 / |U^|^2: Q = |U^|^2 / 2^32 in [2^22, 2^25), R' = 2^(52 + g) / Q in [2^29, 2^30] */
    uint8_t g;
    uint32_t rq = recip_q((uint32_t)dot(u, u, 2), &g);
    /* d = K' U^ / Q = K' R' U^ / 2^(52 + g): T = K'' R' / 2^32 with K'' = K' 2^f (|K''| in
     * [2^29, 2^30)), T' = T 2^t likewise, d = T' U^ / 2^32 2^(12 - f - g - t) */
    uint8_t f = lead(tmag(k), 29);
    int32_t kn = (int32_t)((uint32_t)k << f), rs = (int32_t)rq;
    int32_t t = dot(&kn, &rs, 1);
    uint8_t tt = lead(tmag(t), 29);
    t = (int32_t)((uint32_t)t << tt);
    int8_t sh = (int8_t)(12 - f - g - tt);
    int8_t rsh = (int8_t)(sigma - sh);
    for (uint8_t i = 0; i < 2; i++) {
        int32_t d = dot(&t, &u[i], 1); /* |d| < 2^26 */
        /* beacon 2 2^31 lambda (4 to 8 times the beacons' span) or farther: the circles all
         * but coincide */
        if (sh > 0 && (d >= (1l << (31 - sh)) || d < -(1l << (31 - sh))))
            return OPTICAL_E_SINGULAR;
        /* the vehicle relative to beacon 2: -d 2^sh / 2^sigma (Q16 m), rounded half up */
        uint32_t nd = 0u - (uint32_t)d;
        out->off[i] = rsh <= 0 ? (int32_t)(nd << (uint8_t)-rsh)
                               : asr((int32_t)nd, (uint8_t)rsh) + (int32_t)((nd >> (rsh - 1)) & 1u);
        out->w[i] = k < 0 ? -u[i] : u[i];
    }
    out->l[0] = l1 * 4;
    out->l[1] = k;
    out->l[2] = l3 * 4;
    out->r = rq;
    out->x = (int8_t)(e - g - sigma);
    return OPTICAL_OK;
}

uint32_t optical_tri_quality(const int32_t v[4], const optical_tsol_t *s)
{
    /* ranges: r_i = |l_i| 2^32 / |U^|; 16 bits by a common shift */
    uint8_t sr = 0;
    uint32_t m = mag2(s->l[0], s->l[1]) | tmag(s->l[2]);
    for (; m >= 0x8000u; m >>= 1)
        sr++;
    int32_t rl[3];
    for (uint8_t i = 0; i < 3; i++)
        rl[i] = asr(s->l[i], sr);
    /* chords b1, b3, b3 - b1: lambda / 2^15 */
    int32_t ch[6] = {asr(v[0], 15), asr(v[1], 15), asr(v[2], 15), asr(v[3], 15), 0, 0};
    ch[4] = ch[2] - ch[0];
    ch[5] = ch[3] - ch[1];
    /* M = c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2: each chord times its range, / 2^16, squared */
    static const uint8_t pair[3] = {2, 0, 1};
    uint32_t mm = 0;
    for (uint8_t c = 0; c < 3; c++)
        for (uint8_t j = 0; j < 2; j++) {
            int32_t w = asr(rl[pair[c]] * ch[2 * c + j], 16);
            mm += (uint32_t)(w * w);
        }
    if (mm == 0)
        return UINT32_MAX;
    /* S = sqrt(M) 2^(sr + 31) R' 2^(e - g - 56) lambda per radian */
    int8_t x = (int8_t)(s->x + sr - 19);
    while (mm < (1ul << 30)) {
        mm <<= 2;
        x--;
    }
    /* the root (optical_sqrt_tab interpolated, within 0.05 % low); Q16 m per mrad: / 2^sigma
     * / 1000 (2^25 / 1000 = 33554.4) */
    uint16_t k = (uint16_t)((mm >> 27) - 8u), f = (uint16_t)((mm >> 16) << 5);
    uint16_t d = (uint16_t)(optical_sqrt_tab[k + 1u] - optical_sqrt_tab[k]);
    uint16_t root = (uint16_t)(0x8000u + optical_sqrt_tab[k] + (((uint32_t)d * f) >> 16));
    uint32_t p = ((uint32_t)root * 33554u) >> 16;
    p *= s->r >> 15;
    if (x > 0)
        return x >= 31 || (p >> (32 - x)) != 0 ? UINT32_MAX : p << x;
    return x <= -32 ? 0 : p >> (uint8_t)-x;
}
