/*
 * drive_internal.h - arithmetic helpers shared by the drive module's sources (not public).
 */
#ifndef DRIVE_INTERNAL_H
#define DRIVE_INTERNAL_H

#include <stdint.h>

#include "fx/fx.h"

/** |x| as uint32 (also for INT32_MIN). */
static inline uint32_t drive_abs32(int32_t x)
{
    return x < 0 ? (uint32_t)0 - (uint32_t)x : (uint32_t)x;
}

/** A signed binary angle (any) in radians, Q4.28, rounded (error < 1e-9 rad). */
int32_t drive_angle_to_rad_q28(int32_t a);

/** A signed binary angle, |a| < 0.6 turn / 2pi (under 2 rad), in radians Q1.30. */
int32_t drive_angle_to_rad_q30(int32_t a);

/** 1 / cos(x) for |x| <= 0.2 rad (Q30 in, Q30 out): 1 + x^2/2 + 5x^4/24 + 61x^6/720, error
 * below 1e-7. */
int32_t drive_sec_small(int32_t x_q30);

/** Radians Q28 (|r| < 8) to a binary angle (wraps). */
fx_angle_t drive_rad_q28_to_angle(int32_t r);

/**
 * x / sin(x) for |x| <= 0.2 rad (Q30 in, Q30 out): 1 + x^2/6 + 7x^4/360 + 31x^6/15120,
 * truncation error below 1e-9.
 */
int32_t drive_x_over_sin_small(int32_t x_q30);

/** sin(x) / x for |x| <= 0.2 rad (Q30 in, Q30 out), truncation error below 1e-9. */
int32_t drive_sin_over_x_small(int32_t x_q30);

#endif
