/*
 * fx.h - fixed-point navigation math for a 16-bit CPU without FPU (SPEC G2, issue 3).
 *
 * Formats used across the firmware (every public function states which it takes):
 *  - fx_angle_t: binary angle, unsigned 32 bits, 2^32 = one turn, counter-clockwise. Wraps
 *    for free: a + b, a - b are exact modulo one turn. 1 LSB = 8.4e-8 degrees, far finer than
 *    the goniometer's 50,000 counts per turn (0.0072 degrees). Read as int32_t it is the
 *    signed angle in [-half turn, half turn).
 *  - fx_q30_t: Q1.30, 1.0 = 2^30 (sin, cos, unit vectors).
 *  - fx_q16_t: Q15.16, 1.0 = 2^16. Lengths in metres (1 LSB = 15.3 um, range +-32768 m).
 *
 * Rounding is to nearest unless a function says otherwise. Each function documents its
 * valid input range and its maximum error; tests/unit/fx_test.cpp asserts them against
 * double precision and the MSP430 build gives bit-identical results to the host build.
 */
#ifndef FX_FX_H
#define FX_FX_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef uint32_t fx_angle_t;
typedef int32_t fx_q30_t;
typedef int32_t fx_q16_t;

#define FX_ANGLE_QUARTER 0x40000000ul
#define FX_ANGLE_HALF    0x80000000ul
#define FX_Q30_ONE       (1l << 30)
#define FX_Q16_ONE       (1l << 16)

/* ------------------------------------------------------------------ angles */

/**
 * Angle of @p counts on a goniometer with @p counts_per_turn counts per turn
 * (1 <= counts_per_turn <= 65535, 0 <= counts < counts_per_turn; larger counts wrap).
 */
fx_angle_t fx_angle_from_counts(uint32_t counts, uint16_t counts_per_turn);

/* ------------------------------------------------------------------ trigonometry */

/** sin(a), Q1.30. */
fx_q30_t fx_sin(fx_angle_t a);

/** cos(a), Q1.30. */
fx_q30_t fx_cos(fx_angle_t a);

/** sin and cos of one angle at once (cheaper than two calls). */
void fx_sincos(fx_angle_t a, fx_q30_t *s, fx_q30_t *c);

/**
 * Angle of the vector (x, y): atan2(y, x) as a binary angle in [0, 1 turn). Any common scale
 * of x and y (full int32 range). Exact on the axes; (0, 0) gives 0.
 */
fx_angle_t fx_atan2(int32_t y, int32_t x);

/* ------------------------------------------------------------------ roots */

/** floor(sqrt(x)), exact, for every x. */
uint16_t fx_sqrt32(uint32_t x);

/** floor(sqrt(x)), exact, for every x. */
uint32_t fx_sqrt64(uint64_t x);

/* ------------------------------------------------------------------ multiply, divide */

/** a * b / 2^30 rounded (scale a length or a count by a sin/cos). */
int32_t fx_mul_q30(int32_t a, fx_q30_t b);

/** a * b / 2^16 rounded. */
int32_t fx_mul_q16(int32_t a, int32_t b);

/**
 * a * b / 2^shift rounded to nearest, into *out; false (and *out untouched) when the result
 * does not fit int32_t. 0 <= shift <= 62.
 */
bool fx_mul_shift(int32_t a, int32_t b, uint8_t shift, int32_t *out);

/**
 * num / den rounded to nearest (ties away from zero) into *out; false (and *out untouched)
 * when den is 0 or the quotient does not fit int32_t.
 */
bool fx_div32(int32_t num, int32_t den, int32_t *out);

#ifdef __cplusplus
}
#endif

#endif
