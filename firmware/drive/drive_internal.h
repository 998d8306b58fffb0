/*
 * drive_internal.h - arithmetic helpers shared by the drive module's sources (not public).
 */
#ifndef DRIVE_INTERNAL_H
#define DRIVE_INTERNAL_H

#include <stdint.h>

#include "fx/fx.h"

/** a * b, exact. */
uint64_t drive_umul(uint32_t a, uint32_t b);

/**
 * round(n / d), ties up; UINT32_MAX when the quotient does not fit 32 bits or d == 0.
 * 32 restoring steps (no 64-bit division helper).
 */
uint32_t drive_udiv64(uint64_t n, uint32_t d);

/** round(n * 2^sh / d) as drive_udiv64 (0 <= sh <= 63; saturates like it). */
uint32_t drive_udiv(uint32_t n, uint32_t d, uint8_t sh);

/** sqrt(a^2 + b^2) rounded down, exact for every int32 pair. */
uint32_t drive_hypot(int32_t a, int32_t b);

/** |x| as uint32 (also for INT32_MIN). */
static inline uint32_t drive_abs32(int32_t x)
{
    return x < 0 ? (uint32_t)0 - (uint32_t)x : (uint32_t)x;
}

/**
 * A signed binary angle (|a| <= half a turn) in radians, Q28: a * 2pi / 2^32 * 2^28, rounded.
 */
int32_t drive_angle_to_rad_q28(int32_t a);

/** Radians Q28 (|r| < 8) to a binary angle (wraps). */
fx_angle_t drive_rad_q28_to_angle(int32_t r);

/**
 * x / sin(x) for |x| <= 0.26 rad (Q30 in, Q30 out): 1 + x^2/6 + 7x^4/360 + 31x^6/15120,
 * truncation error below 1e-9.
 */
int32_t drive_x_over_sin_small(int32_t x_q30);

/** sin(x) / x for |x| <= 0.26 rad (Q30 in, Q30 out), truncation error below 1e-9. */
int32_t drive_sin_over_x_small(int32_t x_q30);

#endif
