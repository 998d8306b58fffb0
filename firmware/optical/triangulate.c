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
 * component lies in [2^27, 2^28) ("lambda" units); sin/cos are Q1.30; every product of two is
 * exact (64 bits) and rounded once per sum. The arithmetic core (the centres, the three
 * intersections, their mean) and the quality's parts are the kernels optical_tri_core() and
 * optical_quality_parts() (fastmath.h: assembly on the MSP430).
 */
#include <stdbool.h>
#include <stddef.h>

#include "optical/fastmath.h"
#include "optical/optical.h"

/** Largest disagreement of the three bearings of a solution (2e-4 rad). */
#define CONSISTENT 136707l

/** Offsets beyond this (Q16, 2048 m) are refused: the scaling needs them below 2^27. */
#define SPAN_LIMIT (1l << 27)

static uint32_t mag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

/*
 * Quality: the RMS position error for unit independent bearing errors,
 *     S = sqrt(c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2) / |r3 sin a12 + r1 sin a23 + r2 sin a31|
 * (chords c between beacons, ranges r from the vehicle), in Q16 metres per mrad:
 * num 2^(28 + sc) / den lambda per radian (fastmath.h), / 2^sigma, / 1000.
 */
static uint32_t quality(const int32_t v[4], const int32_t c[2], const int32_t s[3], uint8_t sigma)
{
    optical_qparts_t q;
    optical_quality_parts(v, c, s, &q);
    if (q.den == 0)
        return UINT32_MAX;
    uint8_t sh = (uint8_t)(28u + q.sc - sigma); /* sc >= 13: b1 or b3 reaches 2^27 */
    while (q.den >= (1ul << 21)) {              /* den 1000 below 2^31 */
        q.den >>= 1;
        sh--;
    }
    int32_t r;
    if (!fx_div_shift((int32_t)q.num, (int32_t)q.den * 1000, sh, &r) || r < 0)
        return UINT32_MAX;
    return (uint32_t)r;
}

static void order3(const fx_angle_t theta[3], uint8_t o[3])
{
    o[0] = 0;
    o[1] = 1;
    o[2] = 2;
    if (theta[1] < theta[0]) {
        o[0] = 1;
        o[1] = 0;
    }
    if (theta[2] < theta[o[1]]) {
        o[2] = o[1];
        o[1] = 2;
        if (theta[2] < theta[o[0]]) {
            o[1] = o[0];
            o[0] = 2;
        }
    }
}

int8_t optical_triangulate(const optical_xy_t b[3], const fx_angle_t theta[3], uint32_t quality_max,
                           optical_tri_t *out)
{
    out->quality = UINT32_MAX;
    /* O8: sort by angle (CCW), then start after the largest gap so that it is the third. */
    uint8_t o[3];
    order3(theta, o);
    fx_angle_t g[3];
    uint8_t r = 0;
    for (uint8_t i = 0; i < 3; i++) {
        g[i] = theta[o[i < 2 ? i + 1 : 0]] - theta[o[i]];
        if (g[i] == 0)
            return OPTICAL_E_DEGENERATE;
        if (g[i] > g[r])
            r = i;
    }
    /* k[i]: the input index of beacon i + 1 (B1 after the largest gap, then B2, B3) */
    uint8_t k[3];
    for (uint8_t i = 0; i < 3; i++)
        k[i] = o[(r + 1u + i) % 3u];
    const optical_xy_t *B2 = &b[k[1]];
    fx_angle_t a1 = g[(r + 1u) % 3u], a2 = g[(r + 2u) % 3u];

    int32_t v[4] = {b[k[0]].x - B2->x, b[k[0]].y - B2->y, b[k[2]].x - B2->x, b[k[2]].y - B2->y};
    uint32_t m = mag(v[0]) | mag(v[1]) | mag(v[2]) | mag(v[3]);
    if (m >= SPAN_LIMIT)
        return OPTICAL_E_ARG;
    if ((v[0] | v[1]) == 0 || (v[2] | v[3]) == 0 || (v[0] == v[2] && v[1] == v[3]))
        return OPTICAL_E_DEGENERATE;
    uint8_t sigma = 0;
    for (; m < (1ul << 27); m <<= 1)
        sigma++;
    for (uint8_t i = 0; i < 4; i++)
        v[i] *= (int32_t)1 << sigma;

    int32_t sc[6];
    fx_sincos(a1, &sc[0], &sc[1]);
    fx_sincos(a2, &sc[2], &sc[3]);
    fx_sincos(a1 + a2, &sc[4], &sc[5]);
    int32_t c[2];
    if (!optical_tri_core(v, sc, c))
        return OPTICAL_E_SINGULAR;
    int32_t s[3] = {sc[0], sc[2], sc[4]};
    out->quality = quality(v, c, s, sigma);

    /* Relative to B2 in Q16 metres: / 2^sigma, rounded half up. */
    int32_t px = c[0], py = c[1];
    if (sigma) {
        px += 1l << (sigma - 1);
        py += 1l << (sigma - 1);
        for (uint8_t i = 0; i < sigma; i++) {
            px = (px - (px < 0)) / 2; /* floor halving */
            py = (py - (py < 0)) / 2;
        }
    }
    out->pose.x = B2->x + px;
    out->pose.y = B2->y + py;
    /* O10: bearing = direction to each beacon - its sighting angle, averaged. Each beacon
     * must lie along its own sighting: a solution on the other arc of a circle (which the
     * circles alone cannot tell apart) leaves one direction off by about 180 degrees. Near
     * the beacons' circle a quantised input can land there. */
    fx_angle_t h[3];
    for (uint8_t i = 0; i < 3; i++)
        h[i] = fx_atan2(b[k[i]].y - out->pose.y, b[k[i]].x - out->pose.x) - theta[k[i]];
    int32_t d1 = (int32_t)(h[1] - h[0]), d2 = (int32_t)(h[2] - h[0]);
    int32_t mean = fx_mul_q30(d1, 357913941l) + fx_mul_q30(d2, 357913941l); /* 2^30 / 3 */
    if (mag(mean) > CONSISTENT || mag(d1 - mean) > CONSISTENT || mag(d2 - mean) > CONSISTENT)
        return OPTICAL_E_INCONSISTENT;
    out->pose.heading = h[0] + (fx_angle_t)mean;
    return out->quality > quality_max ? OPTICAL_E_SINGULAR : OPTICAL_OK;
}
