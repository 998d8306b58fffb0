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
 * (fastmath.h: assembly on the MSP430).
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

    int32_t *v = T.v, *sc = T.sc;
    v[0] = b[k[0]].x - B2->x;
    v[1] = b[k[0]].y - B2->y;
    v[2] = b[k[2]].x - B2->x;
    v[3] = b[k[2]].y - B2->y;
    if ((mag(v[0]) | mag(v[1]) | mag(v[2]) | mag(v[3])) >= SPAN_LIMIT)
        return OPTICAL_E_ARG;
    if ((v[0] | v[1]) == 0 || (v[2] | v[3]) == 0 || (v[0] == v[2] && v[1] == v[3]))
        return OPTICAL_E_DEGENERATE;
    fx_sincos(a1, &sc[0], &sc[1]);
    fx_sincos(a3 - a1, &sc[2], &sc[3]);
    int8_t st = optical_tri_core(v, sc, &T.ts);
    if (st != OPTICAL_OK)
        return st;
    out->quality = optical_tri_quality(v, &T.ts);
    out->pose.x = B2->x + T.ts.off[0];
    out->pose.y = B2->y + T.ts.off[1];
    /* O10: the bearing from the direction of B2 (finer than the position's Q16) and its
     * sighting angle. */
    out->pose.heading = fx_atan2(T.ts.w[1], T.ts.w[0]) - theta[k[1]];
    return out->quality > quality_max ? OPTICAL_E_SINGULAR : OPTICAL_OK;
}
