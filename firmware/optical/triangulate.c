/*
 * triangulate.c - position and bearing from three sightings (SPEC O8-O10).
 *
 * The seed's method: circle A through beacons 1, 2 and the vehicle, B through 2, 3, C through
 * 1, 3. A chord seen under the inscribed angle alpha has its centre on the chord's
 * perpendicular bisector, cot(alpha) / 2 chord lengths from the midpoint:
 *     c = (Bi + Bj) / 2 + cot(alpha) / 2 * rot90(Bj - Bi)         (alpha CCW from Bi to Bj)
 * which holds for every alpha in (0, 360) (cot has period 180). Two circles through a common
 * beacon O meet at O and at the vehicle P, the mirror image of O in the line of centres:
 *     P - O = 2 cross(cY - O, cX - O) rot90(cY - cX) / |cY - cX|^2.
 * Computed homogeneously (n = 2 sin(alpha) (c - O)), which keeps every quantity finite for
 * inscribed angles near 0 and 180 degrees:
 *     P - O = cross(nY, nX) rot90(W) / |W|^2,   W = sX nY - sY nX.
 * The three pairwise intersections (AB at beacon 2, AC at 1, BC at 3) are averaged.
 * docs/optical.md derives it and the quality measure.
 *
 * Fixed point: the two beacon offsets from beacon 2 are scaled by 2^sigma so that the largest
 * component lies in [2^27, 2^28) ("lambda" units); sin/cos are Q1.30; products of two go
 * through optical_dot2 (one rounding, exact 64-bit sum).
 */
#include <stdbool.h>
#include <stddef.h>

#include "optical/fastmath.h"
#include "optical/optical.h"
#include "scratch.h"

/** Largest disagreement of the three bearings of a solution (2e-4 rad). */
#define CONSISTENT 136707l

/** Offsets beyond this (Q16, 2048 m) are refused: the scaling needs them below 2^27. */
#define SPAN_LIMIT (1l << 27)

static uint32_t mag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static uint32_t max4(int32_t a, int32_t b, int32_t c, int32_t d)
{
    uint32_t m = mag(a), t = mag(b);
    if (t > m)
        m = t;
    t = mag(c);
    if (t > m)
        m = t;
    t = mag(d);
    return t > m ? t : m;
}

/*
 * One pairwise intersection, relative to the common beacon, in lambda units:
 * cross(nY, nX) rot90(W) / |W|^2 with W = sX nY - sY nX. False when the circles (nearly)
 * coincide so that the point does not fit. |n| < 2^29.5.
 */
__attribute__((noinline)) static bool pair_point(const int32_t nX[2], fx_q30_t sX,
                                                 const int32_t nY[2], fx_q30_t sY, int32_t out[2])
{
    int32_t wx = optical_dot2(nY[0], sX, nX[0], -sY); /* |W| < 2^30.5 */
    int32_t wy = optical_dot2(nY[1], sX, nX[1], -sY);
    int32_t x = optical_dot2(nY[0], nX[1], nY[1], -nX[0]); /* cross(nY, nX) / 2^30 */
    /* W = W~ 2^e with the larger component of W~ in [2^28, 2^29). */
    uint32_t m = mag(wx) | mag(wy);
    if (m == 0)
        return false;
    int8_t e = 0;
    while (m < (1ul << 28)) {
        m <<= 1;
        wx *= 2;
        wy *= 2;
        e--;
    }
    while (m >= (1ul << 29)) {
        m >>= 1;
        wx /= 2;
        wy /= 2;
        e++;
    }
    int32_t d = optical_dot2(wx, wx, wy, wy); /* |W~|^2 / 2^30, in [2^26, 2^29) */
    /* t = x 2^28 / d < 2^29.5; P = x 2^30 rot90(W~) 2^e / (d 2^30 2^2e)
     *   = t rot90(W~) / 2^(28 + e) = fx_mul_q30(t, rot90(W~)) 2^(2 - e). */
    int32_t t;
    if (!fx_div_shift(x, d, 28, &t))
        return false;
    int32_t px = fx_mul_q30(t, -wy), py = fx_mul_q30(t, wx); /* < 2^28.5 */
    int8_t sh = (int8_t)(2 - e);
    for (; sh > 0; sh--) {
        /* Beyond 2^30 lambda (eight times the beacons' span) the circles all but coincide. */
        if (mag(px) >= (1ul << 29) || mag(py) >= (1ul << 29))
            return false;
        px *= 2;
        py *= 2;
    }
    for (; sh < 0; sh++) {
        px /= 2;
        py /= 2;
    }
    out[0] = px;
    out[1] = py;
    return true;
}

/* Work area: optical_scratch (scratch.h; static, not reentrant). */
#define T (optical_scratch.solve.t)

/*
 * Quality: the RMS position error for unit independent bearing errors,
 *     S = sqrt(c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2) / |r3 sin a12 + r1 sin a23 + r2 sin a31|
 * (chords c between beacons, ranges r from the vehicle), in Q16 metres per mrad, from the
 * beacon offsets in T and the vehicle (cx, cy) relative to beacon 2, lambda units; the vectors
 * are cut to 15 bits (the estimate needs a few per cent, not more).
 */
/* |v|^2 / 2^32 of a lambda vector below 2^30.5: below 2^29. */
static int32_t sq(int32_t x, int32_t y)
{
    x /= 2;
    y /= 2;
    return optical_dot2(x, x, y, y);
}

/*
 * Quality: the RMS position error for unit independent bearing errors,
 *     S = sqrt(c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2) / |r3 sin a12 + r1 sin a23 + r2 sin a31|
 * (chords c between beacons, ranges r from the vehicle), in Q16 metres per mrad, from the
 * beacon offsets in T and the vehicle (cx, cy) relative to beacon 2, lambda units.
 */
__attribute__((noinline)) static uint32_t quality(int32_t cx, int32_t cy, uint8_t sigma)
{
    const int32_t *b1 = T.b1, *b3 = T.b3;
    int32_t c12 = sq(b1[0], b1[1]), c23 = sq(b3[0], b3[1]);
    int32_t c31 = sq(b3[0] - b1[0], b3[1] - b1[1]);
    int32_t q1 = sq(b1[0] - cx, b1[1] - cy), q2 = sq(cx, cy), q3 = sq(b3[0] - cx, b3[1] - cy);
    /* The squared ranges times 4^j, the largest in [2^28, 2^30): 15-bit ranges. The factor
     * 2^j scales numerator and denominator alike. */
    if ((q1 | q2 | q3) == 0)
        return UINT32_MAX;
    while ((uint32_t)(q1 | q2 | q3) < (1ul << 28)) {
        q1 *= 4;
        q2 *= 4;
        q3 *= 4;
    }
    /* 2^j sqrt(sum c^2 r^2) / 2^47 (each product below 2^29) */
    uint16_t num = fx_sqrt32((uint32_t)fx_mul_q30(c12, q3) + (uint32_t)fx_mul_q30(c23, q1) +
                             (uint32_t)fx_mul_q30(c31, q2));
    int32_t r1 = fx_sqrt32((uint32_t)q1), r2 = fx_sqrt32((uint32_t)q2); /* 2^j range / 2^16 */
    int32_t r3 = fx_sqrt32((uint32_t)q3);
    /* a31 = 360 - alpha3: sin a31 = -s3. */
    int32_t den = fx_mul_q30(r3, T.s1) + fx_mul_q30(r1, T.s2) - fx_mul_q30(r2, T.s3);
    if (den < 0)
        den = -den;
    if (den == 0)
        return UINT32_MAX;
    /* S = num 2^47 / (den 2^16) lambda; in Q16 m: / 2^sigma; per mrad: / 1000. */
    int32_t q;
    if (!fx_div_shift((int32_t)num, den * 1000, (uint8_t)(31 - sigma), &q) || q < 0)
        return UINT32_MAX;
    return (uint32_t)q;
}

int8_t optical_triangulate(const optical_xy_t b[3], const fx_angle_t theta[3], uint32_t quality_max,
                           optical_tri_t *out)
{
    out->quality = UINT32_MAX;
    /* O8: sort by angle (CCW), then start after the largest gap so that it is the third. */
    uint8_t o[3] = {0, 1, 2};
    if (theta[o[1]] < theta[o[0]]) {
        o[0] = 1;
        o[1] = 0;
    }
    if (theta[o[2]] < theta[o[1]]) {
        uint8_t t = o[2];
        o[2] = o[1];
        o[1] = t;
        if (theta[o[1]] < theta[o[0]]) {
            t = o[1];
            o[1] = o[0];
            o[0] = t;
        }
    }
    fx_angle_t *g = T.g;
    g[0] = theta[o[1]] - theta[o[0]];
    g[1] = theta[o[2]] - theta[o[1]];
    g[2] = theta[o[0]] - theta[o[2]];
    if (g[0] == 0 || g[1] == 0 || g[2] == 0)
        return OPTICAL_E_DEGENERATE;
    uint8_t r = 0;
    if (g[1] > g[r])
        r = 1;
    if (g[2] > g[r])
        r = 2;
    static const uint8_t next[3] = {1, 2, 0};
    uint8_t k1 = next[r], k2 = next[k1], k3 = next[k2];
    const optical_xy_t *B1 = &b[o[k1]], *B2 = &b[o[k2]], *B3 = &b[o[k3]];
    fx_angle_t a1 = g[k1], a2 = g[k2], a3 = a1 + a2;

    int32_t *b1 = T.b1, *b3 = T.b3;
    b1[0] = B1->x - B2->x;
    b1[1] = B1->y - B2->y;
    b3[0] = B3->x - B2->x;
    b3[1] = B3->y - B2->y;
    uint32_t m = max4(b1[0], b1[1], b3[0], b3[1]);
    if (m >= SPAN_LIMIT)
        return OPTICAL_E_ARG;
    if ((b1[0] | b1[1]) == 0 || (b3[0] | b3[1]) == 0 || (b1[0] == b3[0] && b1[1] == b3[1]))
        return OPTICAL_E_DEGENERATE;
    uint8_t sigma = 0;
    while (m < (1ul << 27)) {
        m <<= 1;
        sigma++;
    }
    for (uint8_t i = 0; i < sigma; i++) {
        b1[0] *= 2;
        b1[1] *= 2;
        b3[0] *= 2;
        b3[1] *= 2;
    }

    fx_sincos(a1, &T.s1, &T.c1);
    fx_sincos(a2, &T.s2, &T.c2);
    fx_sincos(a3, &T.s3, &T.c3);

    /* Doubled homogeneous centres n = 2 sin(alpha) (c - O) of circle A (B1, B2, alpha1),
     * B (B2, B3, alpha2) and C (B1, B3, alpha3), at the origin of each pair's common beacon:
     *   A at B2: s1 b1 - c1 rot90(b1)      A at B1: -s1 b1 - c1 rot90(b1)
     *   B at B2: s2 b3 + c2 rot90(b3)      B at B3: -s2 b3 + c2 rot90(b3)
     *   C at B1: s3 q + c3 rot90(q)        C at B3: -s3 q + c3 rot90(q),   q = b3 - b1
     * (C at B2 would be s3 (b1 + b3) + c3 rot90(q): moving the origin by bi subtracts
     * 2 sin(alpha) bi.) rot90(v) = (-vy, vx); every n is a rotated beacon offset. */
    int32_t q[2] = {b3[0] - b1[0], b3[1] - b1[1]};
    T.nA[0] = optical_dot2(b1[0], T.s1, b1[1], T.c1); /* A at B2 */
    T.nA[1] = optical_dot2(b1[1], T.s1, b1[0], -T.c1);
    T.nB[0] = optical_dot2(b3[0], T.s2, b3[1], -T.c2); /* B at B2 */
    T.nB[1] = optical_dot2(b3[1], T.s2, b3[0], T.c2);
    T.s1b1[0] = optical_dot2(b1[0], -T.s1, b1[1], T.c1); /* A at B1 */
    T.s1b1[1] = optical_dot2(b1[1], -T.s1, b1[0], -T.c1);
    T.s3b1[0] = optical_dot2(q[0], T.s3, q[1], -T.c3); /* C at B1 */
    T.s3b1[1] = optical_dot2(q[1], T.s3, q[0], T.c3);
    T.s2b3[0] = optical_dot2(b3[0], -T.s2, b3[1], -T.c2); /* B at B3 */
    T.s2b3[1] = optical_dot2(b3[1], -T.s2, b3[0], T.c2);
    T.s3b3[0] = optical_dot2(q[0], -T.s3, q[1], -T.c3); /* C at B3 */
    T.s3b3[1] = optical_dot2(q[1], -T.s3, q[0], T.c3);

    /* The three pairwise intersections (AB at B2, AC at B1, BC at B3), summed relative to
     * B2. */
    int64_t sx = 0, sy = 0; /* (three values below 2^30.3: only added, never multiplied) */
    for (uint8_t pr = 0; pr < 3; pr++) {
        const int32_t *org = pr == 0 ? NULL : pr == 1 ? b1 : b3;
        const int32_t *nX = pr == 0 ? T.nA : pr == 1 ? T.s1b1 : T.s2b3;
        const int32_t *nY = pr == 0 ? T.nB : pr == 1 ? T.s3b1 : T.s3b3;
        fx_q30_t sX = pr == 2 ? T.s2 : T.s1, sY = pr == 0 ? T.s2 : T.s3;
        if (!pair_point(nX, sX, nY, sY, T.p))
            return OPTICAL_E_SINGULAR;
        sx += T.p[0] + (org ? org[0] : 0);
        sy += T.p[1] + (org ? org[1] : 0);
    }
    /* Average, relative to B2 (lambda; the sums halved to 32 bits first), then to Q16
     * metres: / 2^sigma, rounded. */
    int32_t hx = (int32_t)(sx / 2), hy = (int32_t)(sy / 2);
    int32_t cx = 2 * fx_mul_q30(hx, 357913941l /* 2^30 / 3 */);
    int32_t cy = 2 * fx_mul_q30(hy, 357913941l);
    int32_t px = cx, py = cy;
    if (sigma) {
        px += 1l << (sigma - 1); /* round half up: floor((v + 2^(sigma-1)) / 2^sigma) */
        py += 1l << (sigma - 1);
        for (uint8_t i = 0; i < sigma; i++) {
            px = (px - (px < 0)) / 2; /* floor halving */
            py = (py - (py < 0)) / 2;
        }
    }
    out->quality = quality(cx, cy, sigma);

    out->pose.x = B2->x + px;
    out->pose.y = B2->y + py;
    /* O10: bearing = direction to each beacon - its sighting angle, averaged. */
    fx_angle_t *h = T.h;
    h[0] = fx_atan2(B1->y - out->pose.y, B1->x - out->pose.x) - theta[o[k1]];
    h[1] = fx_atan2(B2->y - out->pose.y, B2->x - out->pose.x) - theta[o[k2]];
    h[2] = fx_atan2(B3->y - out->pose.y, B3->x - out->pose.x) - theta[o[k3]];
    /* Each beacon must lie along its own sighting: a solution on the other arc of a circle
     * (which the circles alone cannot tell apart) leaves one direction off by about 180
     * degrees. Near the beacons' circle a quantised input can land there. */
    int32_t d1 = (int32_t)(h[1] - h[0]), d2 = (int32_t)(h[2] - h[0]);
    int32_t mean = fx_mul_q30(d1, 357913941l) + fx_mul_q30(d2, 357913941l);
    int32_t e0 = mean, e1 = d1 - mean, e2 = d2 - mean;
    if (e0 < 0)
        e0 = -e0;
    if (e1 < 0)
        e1 = -e1;
    if (e2 < 0)
        e2 = -e2;
    if (e0 > CONSISTENT || e1 > CONSISTENT || e2 > CONSISTENT)
        return OPTICAL_E_INCONSISTENT;
    out->pose.heading = h[0] + (fx_angle_t)mean;
    return out->quality > quality_max ? OPTICAL_E_SINGULAR : OPTICAL_OK;
}
