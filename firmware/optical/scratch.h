/*
 * scratch.h - the work memory of firmware/optical (private). The MSP430 has 2 KB of RAM and a
 * small stack, so the fix works in static memory, and the identification's candidate list
 * shares its bytes with the triangulation's intermediates: the two never live at once
 * (identification is over before the first triangulation, and the confirmation pass after it
 * does not keep candidates). optical_fix and optical_triangulate are therefore not reentrant.
 */
#ifndef OPTICAL_SCRATCH_H
#define OPTICAL_SCRATCH_H

#include <stdint.h>

#include "fx/fx.h"
#include "optical/optical.h"

/* Candidate (sighting, beacon) pairs kept between identification passes. */
#define OPTICAL_MAX_CAND 40

typedef struct {
    uint8_t j[OPTICAL_MAX_CAND], k[OPTICAL_MAX_CAND]; /* sorted sighting, beacon */
    int16_t off[OPTICAL_MAX_CAND];                    /* th[j] - psi[k], 2^-16 turn */
    uint16_t e[OPTICAL_MAX_CAND];                     /* position part of the window + margin */
} optical_cand_t;

/* Intermediates of optical_triangulate (lambda units: see triangulate.c). */
typedef struct {
    int32_t b1[2], b3[2];     /* beacon offsets from beacon 2 */
    int32_t nA[2], nB[2];     /* doubled homogeneous centres A, B at beacon 2 */
    int32_t s1b1[2], s3b1[2]; /* A and C at beacon 1 */
    int32_t s2b3[2], s3b3[2]; /* B and C at beacon 3 */
    int32_t p[2];             /* one pair's intersection */
    fx_angle_t g[3], h[3];    /* gaps of the sorted sightings, the three bearings */
    fx_q30_t s1, c1, s2, c2, s3, c3;
} optical_tri_scratch_t;

typedef union {
    optical_cand_t cand; /* identification */
    struct {
        fx_angle_t ang[OPTICAL_MAX_SIGHTINGS]; /* the identified, reference-frame angles */
        optical_tri_scratch_t t;               /* triangulation */
    } solve;
} optical_scratch_t;

extern optical_scratch_t optical_scratch;

#endif
