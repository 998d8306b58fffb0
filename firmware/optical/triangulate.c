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
#include <stddef.h>

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

static int32_t mq(int32_t a, fx_q30_t b)
{
    return fx_mul_q30(a, b);
}

/*
 * One pairwise intersection, relative to the common beacon, in lambda units:
 * cross(nY, nX) rot90(W) / |W|^2 with W = sX nY - sY nX. False when the circles (nearly)
 * coincide so that the point does not fit.
 */
__attribute__((noinline)) static bool pair_point(const int32_t nX[2], fx_q30_t sX,
                                                 const int32_t nY[2], fx_q30_t sY, int32_t out[2])
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

/* Work area: optical_scratch (scratch.h; static, not reentrant). */
#define T (optical_scratch.solve.t)

/*
 * Quality: the RMS position error for unit independent bearing errors,
 *     S = sqrt(c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2) / |r3 sin a12 + r1 sin a23 + r2 sin a31|
 * (chords c between beacons, ranges r from the vehicle), in Q16 metres per mrad, from the
 * beacon offsets in T and the vehicle (cx, cy) relative to beacon 2, lambda units; the vectors
 * are cut to 15 bits (the estimate needs a few per cent, not more).
 */
/* Component i of: b1, b3, b3 - b1 (the chords 12, 23, 31), then the vectors from the vehicle
 * (cx, cy) to beacons 1, 2 (the origin) and 3. */
static int32_t qvec(uint8_t i, int32_t cx, int32_t cy)
{
    const int32_t *b1 = T.b1, *b3 = T.b3;
    uint8_t c = i & 1u;
    int32_t cc = c ? cy : cx;
    switch (i >> 1) {
    case 0:
        return b1[c];
    case 1:
        return b3[c];
    case 2:
        return b3[c] - b1[c];
    case 3:
        return b1[c] - cc;
    case 4:
        return -cc;
    default:
        return b3[c] - cc;
    }
}

__attribute__((noinline)) static uint32_t quality(int32_t cx, int32_t cy, uint8_t sigma)
{
    fx_q30_t s1 = T.s1, s2 = T.s2, s3 = T.s3;
    uint32_t m = 0;
    for (uint8_t i = 0; i < 12; i++)
        m |= mag(qvec(i, cx, cy));
    uint8_t h = 0;
    while (m >= (1ul << 15)) {
        m >>= 1;
        h++;
    }
    /* Squares of 15-bit values: a sum of two stays below 2^31. */
    int32_t *sq = T.sq;
    for (uint8_t i = 0; i < 6; i++) {
        int32_t a = qvec((uint8_t)(2 * i), cx, cy), b = qvec((uint8_t)(2 * i + 1), cx, cy);
        for (uint8_t k = 0; k < h; k++) {
            a /= 2; /* toward zero: fine for the estimate */
            b /= 2;
        }
        sq[i] = (int32_t)(int16_t)a * (int16_t)a + (int32_t)(int16_t)b * (int16_t)b;
    }
    /* sq: c12^2, c23^2, c31^2, r1^2, r2^2, r3^2 */
    int32_t t1, t2, t3;
    fx_mul_shift(sq[0], sq[5], 34, &t1);
    fx_mul_shift(sq[1], sq[3], 34, &t2);
    fx_mul_shift(sq[2], sq[4], 34, &t3);
    uint16_t num = fx_sqrt32((uint32_t)t1 + (uint32_t)t2 + (uint32_t)t3); /* num / 2^17 */
    int32_t r1 = fx_sqrt32((uint32_t)sq[3]), r2 = fx_sqrt32((uint32_t)sq[4]);
    int32_t r3 = fx_sqrt32((uint32_t)sq[5]);
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

    fx_sincos(a1, &T.s1, &T.c1);
    fx_sincos(a2, &T.s2, &T.c2);
    fx_sincos(a3, &T.s3, &T.c3);

    /* Doubled homogeneous centres n = 2 sin(alpha) (c - O), O = beacon 2 (1 or 3 below). */
    T.s1b1[0] = mq(b1[0], T.s1);
    T.s1b1[1] = mq(b1[1], T.s1);
    T.s2b3[0] = mq(b3[0], T.s2);
    T.s2b3[1] = mq(b3[1], T.s2);
    T.s3b1[0] = mq(b1[0], T.s3);
    T.s3b1[1] = mq(b1[1], T.s3);
    T.s3b3[0] = mq(b3[0], T.s3);
    T.s3b3[1] = mq(b3[1], T.s3);
    /* A (B1, B2, alpha1): s1 b1 - c1 rot90(b1); B (B2, B3, alpha2): s2 b3 + c2 rot90(b3);
     * C (B1, B3, alpha3): s3 (b1 + b3) + c3 rot90(b3 - b1). */
    T.nA[0] = T.s1b1[0] + mq(b1[1], T.c1);
    T.nA[1] = T.s1b1[1] - mq(b1[0], T.c1);
    T.nB[0] = T.s2b3[0] - mq(b3[1], T.c2);
    T.nB[1] = T.s2b3[1] + mq(b3[0], T.c2);
    T.nC[0] = T.s3b1[0] + T.s3b3[0] - mq(b3[1] - b1[1], T.c3);
    T.nC[1] = T.s3b1[1] + T.s3b3[1] + mq(b3[0] - b1[0], T.c3);

    /* The three pairwise intersections, each relative to its common beacon, summed relative
     * to B2. Moving the origin from B2 to Bi subtracts 2 sin(alpha) bi from n. */
    int32_t sx = 0, sy = 0;
    for (uint8_t pr = 0; pr < 3; pr++) {
        fx_q30_t sX = pr == 2 ? T.s2 : T.s1, sY = pr == 0 ? T.s2 : T.s3;
        const int32_t *org = pr == 0 ? NULL : pr == 1 ? b1 : b3;
        const int32_t *nX = pr == 2 ? T.nB : T.nA, *nY = pr == 0 ? T.nB : T.nC;
        const int32_t *dX = pr == 1 ? T.s1b1 : T.s2b3, *dY = pr == 1 ? T.s3b1 : T.s3b3;
        for (uint8_t i = 0; i < 2; i++) {
            T.nx[i] = org ? nX[i] - 2 * dX[i] : nX[i];
            T.ny[i] = org ? nY[i] - 2 * dY[i] : nY[i];
        }
        if (!pair_point(T.nx, sX, T.ny, sY, T.p))
            return OPTICAL_E_SINGULAR;
        sx += T.p[0] + (org ? org[0] : 0);
        sy += T.p[1] + (org ? org[1] : 0);
    }
    /* Average, relative to B2 (lambda), then to Q16 metres: / 3 / 2^sigma. */
    int32_t px, py, cx, cy;
    fx_mul_shift(sx, 357913941l /* 2^30 / 3 */, (uint8_t)(30 + sigma), &px);
    fx_mul_shift(sy, 357913941l, (uint8_t)(30 + sigma), &py);
    fx_mul_shift(sx, 357913941l, 30, &cx);
    fx_mul_shift(sy, 357913941l, 30, &cy);
    /* Quality from the chords and the vehicle-to-beacon vectors (lambda). */
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
