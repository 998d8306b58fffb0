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

/** Offsets beyond this (Q16, 2048 m) are refused: the scaling needs them below 2^27. */
#define SPAN_LIMIT (1l << 27)

/* The work memory (optical_fix's, in a part that is free while it triangulates). */
#define T (optical_work.u.sv)

static uint32_t mag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

/*
 * Largest disagreement of the three directions of a solution with the sightings, 2^-16 turn:
 * 2e-4 rad (2.1) plus the error of one optical_angle16 (0.97), of fx_atan2 rounded to 16 bits
 * (0.5) and of a gap rounded to 16 bits (0.5).
 */
#define CONSISTENT 5u

static uint16_t a16(fx_angle_t a)
{
    return (uint16_t)((a + 0x8000ul) >> 16);
}

/*
 * Quality: the RMS position error for unit independent bearing errors,
 *     S = sqrt(c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2) / |r3 sin a12 + r1 sin a23 + r2 sin a31|
 * (chords c between beacons, ranges r from the vehicle), in Q16 metres per mrad:
 * num 2^(28 + sc) / den lambda per radian (fastmath.h), / 2^sigma, / 1000.
 */
static uint32_t quality(const optical_qparts_t *q, uint8_t sigma)
{
    if (q->den == 0)
        return UINT32_MAX;
    uint8_t sh = (uint8_t)(28u + q->sc - sigma); /* sc >= 13: b1 or b3 reaches 2^27 */
    uint32_t den = q->den;
    while (den >= (1ul << 21)) { /* den 1000 below 2^31 */
        den >>= 1;
        sh--;
    }
    int32_t r;
    if (!fx_div_shift((int32_t)q->num, (int32_t)den * 1000, sh, &r) || r < 0)
        return UINT32_MAX;
    return (uint32_t)r;
}

int8_t optical_triangulate(const optical_xy_t b[3], const fx_angle_t theta[3], uint32_t quality_max,
                           optical_tri_t *out)
{
    out->quality = UINT32_MAX;
    /* O8: B1 is the beacon from which the other two lie within the shortest turn CCW (the
     * largest gap then lies between B3 and B1); B2 the nearer of them. */
    static const uint8_t ring[4] = {1, 2, 0, 1};
    uint8_t k[3] = {0, 0, 0};
    fx_angle_t a1 = 0, a3 = UINT32_MAX;
    for (uint8_t i = 0; i < 3; i++) {
        uint8_t j = ring[i], l = ring[i + 1];
        fx_angle_t dj = theta[j] - theta[i], dl = theta[l] - theta[i];
        if (dj == 0 || dl == 0)
            return OPTICAL_E_DEGENERATE;
        if (dj > dl) {
            fx_angle_t t = dj;
            dj = dl;
            dl = t;
            j = l;
            l = ring[i];
        }
        if (dl < a3) {
            a3 = dl;
            a1 = dj;
            k[0] = i;
            k[1] = j;
            k[2] = l;
        }
    }
    const optical_xy_t *B2 = &b[k[1]];
    fx_angle_t a2 = a3 - a1;

    int32_t *v = T.v, *sc = T.sc, *c = T.c;
    v[0] = b[k[0]].x - B2->x;
    v[1] = b[k[0]].y - B2->y;
    v[2] = b[k[2]].x - B2->x;
    v[3] = b[k[2]].y - B2->y;
    uint32_t m = mag(v[0]) | mag(v[1]) | mag(v[2]) | mag(v[3]);
    if (m >= SPAN_LIMIT)
        return OPTICAL_E_ARG;
    if ((v[0] | v[1]) == 0 || (v[2] | v[3]) == 0 || (v[0] == v[2] && v[1] == v[3]))
        return OPTICAL_E_DEGENERATE;
    uint8_t sigma = 0;
    for (; m < (1ul << 20); m <<= 8)
        sigma += 8;
    for (uint16_t h = (uint16_t)(m >> 16); h < 0x800u; h <<= 1) /* m < 2^27: its high word */
        sigma++;
    for (uint8_t i = 0; i < 4; i++)
        v[i] = (int32_t)optical_shl32((uint32_t)v[i], sigma);

    fx_sincos(a1, &sc[0], &sc[1]);
    fx_sincos(a2, &sc[2], &sc[3]);
    fx_sincos(a3, &sc[4], &sc[5]);
    if (!optical_tri_core(v, sc, c))
        return OPTICAL_E_SINGULAR;
    optical_quality_parts(v, c, sc, &T.qp);
    out->quality = quality(&T.qp, sigma);
    /* Relative to B2 in Q16 metres: / 2^sigma, rounded half up. */
    int32_t half = sigma ? (int32_t)optical_shl32(1, (uint8_t)(sigma - 1u)) : 0;
    out->pose.x = B2->x + optical_asr32(c[0] + half, sigma);
    out->pose.y = B2->y + optical_asr32(c[1] + half, sigma);
    /* Each beacon must lie along its own sighting: the directions to B2 and B3 (2^-16 turn,
     * optical_angle16) must differ from the direction to B1 (fx_atan2, rounded to 2^-16 turn:
     * the bearing's below) by alpha1 and alpha3 within
     * CONSISTENT. A solution on the other arc of a circle (which the circles alone cannot tell
     * apart) leaves one off by about 180 degrees; near the beacons' circle a quantised input
     * can land there, or the arithmetic can lose the point. */
    int32_t ux = v[0] - c[0], uy = v[1] - c[1];
    fx_angle_t u1 = fx_atan2(uy, ux); /* the direction to B1, also the bearing's */
    uint16_t h1 = a16(u1);
    uint16_t d2 = (uint16_t)(optical_angle16(-c[0], -c[1]) - h1 - a16(a1));
    uint16_t d3 = (uint16_t)(optical_angle16(v[2] - c[0], v[3] - c[1]) - h1 - a16(a3));
    if ((uint16_t)(d2 + CONSISTENT) > 2u * CONSISTENT ||
        (uint16_t)(d3 + CONSISTENT) > 2u * CONSISTENT)
        return OPTICAL_E_INCONSISTENT;
    /* O10: the bearing from the direction of B1 (lambda units: finer than the position's Q16)
     * and its sighting angle. */
    out->pose.heading = u1 - theta[k[0]];
    return out->quality > quality_max ? OPTICAL_E_SINGULAR : OPTICAL_OK;
}
