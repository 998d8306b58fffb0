/*
 * optical_vectors.h - what the two optical vector programs share (optical_vectors.c: capture,
 * identification and the fix; optical_solve_vectors.c: selection, triangulation and the
 * three-reflector mode): printing a field, a pose, and the random stream (the same on both
 * worlds, tests/support/cy_test.h).
 */
#ifndef OPTICAL_VECTORS_H
#define OPTICAL_VECTORS_H

#include <stdint.h>

#include "cy_test.h"
#include "optical/optical.h"

static uint32_t rng = 0x2545F491u;

static inline uint32_t rnd32(void)
{
    return cy_rand32(&rng);
}

/* A random int32 in [-lim, lim]. */
static inline int32_t rnd_in(uint32_t lim)
{
    return (int32_t)(rnd32() % (2u * lim + 1u)) - (int32_t)lim;
}

/* " <label><v in hex>" */
static inline void field(const char *label, uint32_t v)
{
    cy_print(" ");
    cy_print(label);
    cy_print_hex32(v);
}

/* A pose's fields, as field() prints them. */
static inline void pose_fields(const optical_pose_t *p)
{
    field("x", (uint32_t)p->x);
    field("y", (uint32_t)p->y);
    field("h", p->heading);
}

#endif
