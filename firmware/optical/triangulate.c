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
 * component lies in [2^25, 2^26) ("lambda" units); sin/cos are Q1.30.
 */
#include <stdbool.h>

#include "optical/optical.h"

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

static int32_t mq(int32_t a, fx_q30_t b)
{
    return fx_mul_q30(a, b);
}

/*
 * One pairwise intersection, relative to the common beacon, in lambda units:
 * cross(nY, nX) rot90(W) / |W|^2 with W = sX nY - sY nX. False when the circles (nearly)
 * coincide so that the point does not fit.
 */
static bool pair_point(const int32_t nX[2], fx_q30_t sX, const int32_t nY[2], fx_q30_t sY,
                       int32_t out[2])
{
    int32_t wx = mq(nY[0], sX) - mq(nX[0], sY);
    int32_t wy = mq(nY[1], sX) - mq(nX[1], sY);
    int32_t a, b;
    /* |n| < 2^28.5: each product < 2^57, so >> 27 leaves < 2^30 and the difference fits. */
    fx_mul_shift(nY[0], nX[1], 27, &a);
    fx_mul_shift(nY[1], nX[0], 27, &b);
    int32_t x = a - b; /* cross(nY, nX) / 2^27 */
    /* W = W~ * 2^e with the larger component of W~ in [2^29, 2^30). */
    uint32_t m = mag(wx) | mag(wy);
    if (m == 0)
        return false;
    int8_t e = 0;
    while (m < (1ul << 29)) {
        m <<= 1;
        wx *= 2;
        wy *= 2;
        e--;
    }
    while (m >= (1ul << 30)) { /* only when the products above ran near the limit */
        m >>= 1;
        wx /= 2;
        wy /= 2;
        e++;
    }
    int32_t qx, qy;
    fx_mul_shift(wx, wx, 31, &qx);
    fx_mul_shift(wy, wy, 31, &qy);
    int32_t q = qx + qy; /* |W~|^2 / 2^31, in [2^27, 2^30) */
    /* t = x 2^26 / q; P = x 2^27 rot90(W~) / (q 2^31 2^e) = t rot90(W~) / 2^(30 + e). */
    int32_t t;
    if (!fx_div_shift(x, q, 26, &t))
        return false;
    int16_t sh = (int16_t)(30 + e);
    if (sh < 0)
        return false;
    int32_t px, py;
    if (!fx_mul_shift(t, -wy, (uint8_t)sh, &px) || !fx_mul_shift(t, wx, (uint8_t)sh, &py))
        return false;
    /* The vehicle lies within the field: beyond 2^28 lambda the circles nearly coincide. */
    if (mag(px) >= (1ul << 28) || mag(py) >= (1ul << 28))
        return false;
    out[0] = px;
    out[1] = py;
    return true;
}

/* Largest shift h such that every value >> h fits 15 bits (|v| < 2^15). */
static uint8_t shift15(const int32_t *v, uint8_t n)
{
    uint32_t m = 0;
    for (uint8_t i = 0; i < n; i++)
        m |= mag(v[i]);
    uint8_t h = 0;
    while (m >= (1ul << 15)) {
        m >>= 1;
        h++;
    }
    return h;
}

static int32_t asr(int32_t v, uint8_t h)
{
    while (h--)
        v /= 2; /* rounds toward zero: fine for the quality estimate */
    return v;
}

/*
 * Quality: the RMS position error for unit independent bearing errors,
 *     S = sqrt(c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2) / |r3 sin a12 + r1 sin a23 + r2 sin a31|
 * (chords c between beacons, ranges r from the vehicle), in Q16 metres per mrad. Inputs in
 * lambda units: b1, b3 the beacon offsets from beacon 2, d[i] the beacons from the vehicle.
 */
static uint32_t quality(const int32_t b1[2], const int32_t b3[2], const int32_t d[6], fx_q30_t s1,
                        fx_q30_t s2, fx_q30_t s3, uint8_t sigma)
{
    int32_t v[12] = {b1[0], b1[1], b3[0], b3[1], b3[0] - b1[0], b3[1] - b1[1],
                     d[0],  d[1],  d[2],  d[3],  d[4],          d[5]};
    uint8_t h = shift15(v, 12);
    int32_t w[12];
    for (uint8_t i = 0; i < 12; i++)
        w[i] = asr(v[i], h);
    /* Squares of 15-bit values: < 2^31 for a sum of two. */
    int32_t c12 = w[0] * w[0] + w[1] * w[1];
    int32_t c23 = w[2] * w[2] + w[3] * w[3];
    int32_t c31 = w[4] * w[4] + w[5] * w[5];
    int32_t r1q = w[6] * w[6] + w[7] * w[7];
    int32_t r2q = w[8] * w[8] + w[9] * w[9];
    int32_t r3q = w[10] * w[10] + w[11] * w[11];
    int32_t t1, t2, t3;
    fx_mul_shift(c12, r3q, 34, &t1);
    fx_mul_shift(c23, r1q, 34, &t2);
    fx_mul_shift(c31, r2q, 34, &t3);
    uint16_t num = fx_sqrt32((uint32_t)t1 + (uint32_t)t2 + (uint32_t)t3); /* num / 2^17 */
    int32_t r1 = fx_sqrt32((uint32_t)r1q), r2 = fx_sqrt32((uint32_t)r2q);
    int32_t r3 = fx_sqrt32((uint32_t)r3q);
    /* a31 = 360 - alpha3: sin a31 = -s3. */
    int32_t den = mq(r3, s1) + mq(r1, s2) - mq(r2, s3);
    if (den < 0)
        den = -den;
    if (den == 0)
        return UINT32_MAX;
    /* S in Q16 m/rad = num 2^17 2^(h - sigma) / den; per mrad: / 1000. */
    int16_t sh = (int16_t)(17 + h - sigma);
    int32_t n = (int32_t)num;
    while (sh < 0) {
        n /= 2;
        sh++;
    }
    int32_t q;
    if (!fx_div_shift(n, den * 1000, (uint8_t)sh, &q) || q < 0)
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
    fx_angle_t g[3] = {theta[o[1]] - theta[o[0]], theta[o[2]] - theta[o[1]],
                       theta[o[0]] - theta[o[2]]};
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

    int32_t b1[2] = {B1->x - B2->x, B1->y - B2->y};
    int32_t b3[2] = {B3->x - B2->x, B3->y - B2->y};
    uint32_t m = max4(b1[0], b1[1], b3[0], b3[1]);
    if (m >= SPAN_LIMIT)
        return OPTICAL_E_ARG;
    if ((b1[0] | b1[1]) == 0 || (b3[0] | b3[1]) == 0 || (b1[0] == b3[0] && b1[1] == b3[1]))
        return OPTICAL_E_DEGENERATE;
    uint8_t sigma = 0;
    while (m < (1ul << 25)) {
        m <<= 1;
        sigma++;
    }
    for (uint8_t i = 0; i < sigma; i++) {
        b1[0] *= 2;
        b1[1] *= 2;
        b3[0] *= 2;
        b3[1] *= 2;
    }

    fx_q30_t s1, c1, s2, c2, s3, c3;
    fx_sincos(a1, &s1, &c1);
    fx_sincos(a2, &s2, &c2);
    fx_sincos(a3, &s3, &c3);

    /* Doubled homogeneous centres n = 2 sin(alpha) (c - O), O = beacon 2, 1 or 3. */
    int32_t s1b1[2] = {mq(b1[0], s1), mq(b1[1], s1)}, c1b1[2] = {mq(b1[0], c1), mq(b1[1], c1)};
    int32_t s2b3[2] = {mq(b3[0], s2), mq(b3[1], s2)}, c2b3[2] = {mq(b3[0], c2), mq(b3[1], c2)};
    int32_t s3b1[2] = {mq(b1[0], s3), mq(b1[1], s3)}, s3b3[2] = {mq(b3[0], s3), mq(b3[1], s3)};
    int32_t c3q[2] = {mq(b3[0] - b1[0], c3), mq(b3[1] - b1[1], c3)};
    /* A (B1, B2, alpha1): O = B2: s1 b1 - c1 rot90(b1); O = B1: subtract 2 s1 b1. */
    int32_t nA[2] = {s1b1[0] + c1b1[1], s1b1[1] - c1b1[0]};
    int32_t nA1[2] = {-s1b1[0] + c1b1[1], -s1b1[1] - c1b1[0]};
    /* B (B2, B3, alpha2): O = B2: s2 b3 + c2 rot90(b3); O = B3: subtract 2 s2 b3. */
    int32_t nB[2] = {s2b3[0] - c2b3[1], s2b3[1] + c2b3[0]};
    int32_t nB3[2] = {-s2b3[0] - c2b3[1], -s2b3[1] + c2b3[0]};
    /* C (B1, B3, alpha3): O = B2: s3 (b1 + b3) + c3 rot90(b3 - b1). */
    int32_t nC[2] = {s3b1[0] + s3b3[0] - c3q[1], s3b1[1] + s3b3[1] + c3q[0]};
    int32_t nC1[2] = {nC[0] - 2 * s3b1[0], nC[1] - 2 * s3b1[1]};
    int32_t nC3[2] = {nC[0] - 2 * s3b3[0], nC[1] - 2 * s3b3[1]};

    int32_t pab[2], pac[2], pbc[2];
    if (!pair_point(nA, s1, nB, s2, pab) || !pair_point(nA1, s1, nC1, s3, pac) ||
        !pair_point(nB3, s2, nC3, s3, pbc))
        return OPTICAL_E_SINGULAR;
    /* Average, relative to B2 (lambda), then to Q16 metres: / 3 / 2^sigma. */
    int32_t sx = pab[0] + (b1[0] + pac[0]) + (b3[0] + pbc[0]);
    int32_t sy = pab[1] + (b1[1] + pac[1]) + (b3[1] + pbc[1]);
    int32_t px, py;
    fx_mul_shift(sx, 357913941l /* 2^30 / 3 */, (uint8_t)(30 + sigma), &px);
    fx_mul_shift(sy, 357913941l, (uint8_t)(30 + sigma), &py);
    /* Vehicle-to-beacon vectors (lambda), from the average (before rounding to Q16). */
    int32_t cx, cy;
    fx_mul_shift(sx, 357913941l, 30, &cx);
    fx_mul_shift(sy, 357913941l, 30, &cy);
    int32_t d[6] = {b1[0] - cx, b1[1] - cy, -cx, -cy, b3[0] - cx, b3[1] - cy};
    uint32_t qual = quality(b1, b3, d, s1, s2, s3, sigma);

    out->pose.x = B2->x + px;
    out->pose.y = B2->y + py;
    /* O10: bearing = direction to each beacon - its sighting angle, averaged. */
    const optical_xy_t *bk[3] = {B1, B2, B3};
    const fx_angle_t th[3] = {theta[o[k1]], theta[o[k2]], theta[o[k3]]};
    fx_angle_t h[3];
    for (uint8_t i = 0; i < 3; i++)
        h[i] = fx_atan2(bk[i]->y - out->pose.y, bk[i]->x - out->pose.x) - th[i];
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
        return OPTICAL_E_SINGULAR;
    out->pose.heading = h[0] + (fx_angle_t)mean;
    out->quality = qual;
    return qual > quality_max ? OPTICAL_E_SINGULAR : OPTICAL_OK;
}
