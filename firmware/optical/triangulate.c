/*
 * triangulate.c - position and bearing from three sightings (SPEC O8-O10).
 *
 * The seed's method: circle A through beacons 1, 2 and the vehicle, B through 2, 3, C through
 * 1, 3; every two of them meet at their common beacon and at the vehicle P. Here the two
 * circles through beacon 2, the middle one of the O8 ordering, are intersected (the pair
 * that crosses at the largest angle near the beacons' circle, where the others lose
 * precision first), in closed form and homogeneously (finite for every inscribed angle): with
 * b1 = B1 - B2, b3 = B3 - B2, a = R(alpha1) b1, c = R(-alpha2) b3,
 *     U = sin(alpha2) a + sin(alpha1) c,   kappa = cross(a, c),   B2 - P = kappa U / |U|^2.
 * The same quantities give the check that every beacon lies ahead along its sighting (not on
 * the other arc of a circle), the ranges and so the quality (the Cramer-Rao bound of the
 * geometry) without a square root per range: |U| is that bound's denominator. docs/optical.md
 * derives all of it.
 *
 * Fixed point: the offsets scaled by 2^sigma (largest component in [2^28, 2^29): "lambda"
 * units), sin/cos Q1.30, products of balanced 16-bit halves summed in the multiplier, one
 * reciprocal. The arithmetic is the kernels optical_tri_core() and optical_tri_quality()
 * (fastmath.h; tri_k.c, msp430/optical_tri.S: docs/kernels.md).
 */
#include <stdbool.h>

#include "optical/fastmath.h"
#include "optical/optical.h"

/* The work memory (optical_fix's, in a part that is free while it triangulates). */
#define T (optical_work.u.sv)

int8_t optical_triangulate(const optical_xy_t b[3], const fx_angle_t theta[3], uint32_t quality_max,
                           optical_tri_t *out)
{
    out->quality = UINT32_MAX;
    /* O8: with the sightings in CCW order (0, p, q) and the gaps between them, B1 is the one
     * after the largest gap (ties: the first in the order 0, p, q), so that the other two lie
     * within the shortest turn CCW from it; B2 the next. */
    fx_angle_t d1 = theta[1] - theta[0], d2 = theta[2] - theta[0];
    if (d1 == 0 || d2 == 0 || d1 == d2)
        return OPTICAL_E_DEGENERATE;
    uint8_t p = 1, q = 2;
    if (d1 > d2) {
        fx_angle_t t = d1;
        d1 = d2;
        d2 = t;
        p = 2;
        q = 1;
    }
    /* the gaps before 0, p and q: 0 - d2, d1, d2 - d1 */
    fx_angle_t g0 = 0u - d2, gq = d2 - d1, a1, a2;
    const optical_xy_t *B1, *B2, *B3;
    if (g0 >= d1 && g0 >= gq) {
        B1 = &b[0];
        B2 = &b[p];
        B3 = &b[q];
        a1 = d1;
        a2 = gq;
    } else if (d1 >= gq) {
        B1 = &b[p];
        B2 = &b[q];
        B3 = &b[0];
        a1 = gq;
        a2 = g0;
    } else {
        B1 = &b[q];
        B2 = &b[0];
        B3 = &b[p];
        a1 = g0;
        a2 = d1;
    }

    int32_t *v = T.v, *sc = T.sc;
    v[0] = B1->x - B2->x;
    v[1] = B1->y - B2->y;
    v[2] = B3->x - B2->x;
    v[3] = B3->y - B2->y;
    sc[0] = fx_sin(a1); /* (fx_sincos's values, without its wrapper) */
    sc[1] = fx_cos(a1);
    sc[2] = fx_sin(a2);
    sc[3] = fx_cos(a2);
    int8_t st = optical_tri_core(v, sc, &T.ts);
    if (st != OPTICAL_OK)
        return st;
    out->quality = optical_tri_quality(v, &T.ts);
    out->pose.x = B2->x + T.ts.off[0];
    out->pose.y = B2->y + T.ts.off[1];
    /* O10: the bearing from the direction of B2 (finer than the position's Q16) and its
     * sighting angle. */
    out->pose.heading = fx_atan2(T.ts.w[1], T.ts.w[0]) - theta[B2 - b];
    return out->quality > quality_max ? OPTICAL_E_SINGULAR : OPTICAL_OK;
}

int8_t optical_tri_take(const optical_xy_t *map, const uint8_t t[3], uint32_t quality_max,
                        optical_tri_t *out)
{
    fx_angle_t th[3];
    for (uint8_t i = 0; i < 3; i++) {
        T.b[i] = map[optical_work.sm[optical_work.pos[t[i]]]];
        th[i] = T.ang[t[i]];
    }
    return optical_triangulate(T.b, th, quality_max, out);
}
