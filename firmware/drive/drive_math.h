/*
 * drive_math.h - small arithmetic the drive module's sources share (not public; drive_math.c):
 * an absolute value, a rotation into a frame, and the short series the solver and
 * drive_pose_advance() evaluate instead of a division near zero. All of it is fx underneath.
 */
#ifndef DRIVE_DRIVE_MATH_H
#define DRIVE_DRIVE_MATH_H

#include <stdint.h>

#include "fx/fx.h"

/** |x| as uint32 (also for INT32_MIN). */
static inline uint32_t drive_abs32(int32_t x)
{
    return x < 0 ? (uint32_t)0 - (uint32_t)x : (uint32_t)x;
}

/**
 * The vector (@p x, @p y) in the frame whose x axis points at @p a: *u = x cos a + y sin a
 * (along a), *v = y cos a - x sin a (to its left). Any int32 inputs whose results fit; each
 * of the four products is rounded (fx_mul_q30), error within 1 LSB + |(x, y)| * 1.1e-7
 * (fx_sincos). With a the direction of a vector of length l, (l, 0) in the frame of -a is
 * that vector (fx_sin is exactly odd, fx_cos exactly even).
 */
void drive_to_frame(int32_t x, int32_t y, fx_angle_t a, int32_t *u, int32_t *v);

/**
 * 1 + x^2 (k[0] + x^2 (k[1] + x^2 k[2])) in Q30 for x in Q30 radians, |x| <= 0.2 (Horner
 * with fx_mul_q30): with the coefficients of one of the series below, a function of x within
 * 1e-9 (x / sin x, sin x / x) or 1e-7 (1 / cos x), plus the rounding of four products.
 */
int32_t drive_series(int32_t x, const int32_t k[3]);

/** pi / 2 in Q30: a binary angle times it (fx_mul_q30) is its radians in Q30. */
#define DRIVE_PI_2_Q30 1686629713l

#endif
