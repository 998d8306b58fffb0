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
 * Rounding is to nearest unless a function says otherwise; ties go away from zero, so every
 * odd function here is exactly odd (f(-x) == -f(x)): a mirrored manoeuvre gives exactly the
 * mirrored numbers. Each function documents its valid input range and its maximum error,
 * measured over the whole input range by tests/unit/fx_test.cpp against double precision
 * (docs/fx.md has the table); the MSP430 build gives bit-identical results to the host build
 * (tests/vectors/fx_vectors.c), also where it uses assembly kernels (firmware/fx/msp430/,
 * docs/kernels.md).
 *
 * Every function is reentrant (no state) and safe in maskable interrupt handlers. On the
 * MSP430 the kernels hold interrupts off while they use the hardware multiplier, as the
 * compiler's multiply helpers do, so a maskable interrupt cannot corrupt a product in
 * progress; nothing here may run in the NMI (DINT does not hold it off). Cycle counts:
 * build/msp430/cycles.json (docs/fx.md).
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
/** Saturation value of fx_tan/fx_cot (and their negation): 32768 - 2^-16. */
#define FX_Q16_MAX       0x7FFFFFFFl

/* ------------------------------------------------------------------ angles */

/**
 * Angle of @p counts on a goniometer with @p counts_per_turn counts per turn:
 * round(counts * 2^32 / counts_per_turn) modulo one turn (ties upwards), exact.
 * 1 <= counts_per_turn <= 65535 (0 gives 0), 0 <= counts < counts_per_turn; larger counts
 * wrap (counts and counts mod counts_per_turn give the same angle).
 */
fx_angle_t fx_angle_from_counts(uint32_t counts, uint16_t counts_per_turn);

/* ------------------------------------------------------------------ trigonometry */

/**
 * sin(a), Q1.30, any angle. Max error 1.1e-7 (118 LSB); |result| <= 2^30, exactly 0 and
 * +-2^30 at multiples of a quarter turn, exactly odd and symmetric about the quarter turns.
 * First-quadrant table of 128 steps (generated), chord plus a second-order term.
 */
fx_q30_t fx_sin(fx_angle_t a);

/** cos(a) = fx_sin(a + quarter turn), Q1.30; same error and properties as fx_sin. */
fx_q30_t fx_cos(fx_angle_t a);

/** sin and cos of one angle at once: *s = fx_sin(a), *c = fx_cos(a), bit for bit. */
void fx_sincos(fx_angle_t a, fx_q30_t *s, fx_q30_t *c);

/**
 * tan(a), Q15.16, any angle: fx_sin(a) * 2^16 / fx_cos(a) rounded. Saturates at
 * +-FX_Q16_MAX where |tan a| >= 32768, i.e. within 3.05e-5 rad (0.00175 degrees) of the
 * poles a = +-quarter turn; exactly at a pole (cos = 0) the sign is that of sin (+ at a
 * quarter turn, - at three quarters); just past a pole it saturates with the sign tan has
 * there. Max error 0.5 LSB + 1.6e-7 * (1 + tan^2 a) in units of the result (the sin/cos
 * error divided by cos).
 */
fx_q16_t fx_tan(fx_angle_t a);

/**
 * cot(a) = cos/sin, Q15.16, any angle; saturates at +-FX_Q16_MAX within 3.05e-5 rad of the
 * poles a = 0 and a = half turn (exactly at a pole: + at 0, - at a half turn; next to a
 * pole with the sign cot has on that side). Max error 0.5 LSB + 1.6e-7 * (1 + cot^2 a).
 */
fx_q16_t fx_cot(fx_angle_t a);

/**
 * Angle of the vector (x, y): atan2(y, x) as a binary angle in [0, 1 turn). Any common scale
 * of x and y (full int32 range). Exact on the axes and the diagonals; (0, 0) gives 0.
 * Max error 1.3e-6 rad (7.5e-5 degrees) against atan2 of the exact inputs. Its cost is
 * mostly the 24-step division of the first-quadrant kernel: a coarser variant would save
 * little.
 */
fx_angle_t fx_atan2(int32_t y, int32_t x);

/**
 * atan(num / den) in [-quarter, +quarter] turn (read as int32_t: the signed angle), e.g. the
 * steering angle alpha = atan(L / r) with a signed turn radius. Any int32 operands in any
 * common scale; den == 0 gives +-quarter by the sign of num, 0/0 gives 0. Max error as
 * fx_atan2.
 */
fx_angle_t fx_atan_ratio(int32_t num, int32_t den);

/** atan(t) of a Q15.16 value, in (-quarter, +quarter); fx_atan_ratio(t, 1.0). */
fx_angle_t fx_atan_q16(fx_q16_t t);

/**
 * asin(s) of a Q1.30 value in [-quarter, +quarter] turn; inputs beyond +-2^30 are clamped to
 * +-1. Computed as atan2(s, sqrt(1 - s^2)) with an exact square root; max error 1.3e-6 rad
 * against asin of the exact input (the input's own LSB moves asin by up to 4.3e-5 rad next
 * to +-1: that is the format, not the function).
 */
fx_angle_t fx_asin(fx_q30_t s);

/** acos(c) of a Q1.30 value in [0, half] turn; clamped like fx_asin; same error. */
fx_angle_t fx_acos(fx_q30_t c);

/* ------------------------------------------------------------------ roots */

/**
 * floor(sqrt(x)), exact (error below 1 LSB, never above the root), for every x. In Q terms:
 * the root of a Q2n value is Qn (the root of a Q16.16 area is a Q8.8 length).
 */
uint16_t fx_sqrt32(uint32_t x);

/** floor(sqrt(x)), exact, for every x (the root of a Q30.32 value, e.g., is Q15.16). */
uint32_t fx_sqrt64(uint64_t x);

/**
 * sqrt(x^2 + y^2) rounded to nearest (max error 0.5 LSB), any int32 x, y: the 64-bit sum of
 * squares and its exact square root. The result fits: at most 3.04e9.
 */
uint32_t fx_hypot(int32_t x, int32_t y);

/* ------------------------------------------------------------------ multiply, divide */

/**
 * a * b / 2^30 rounded (scale a length or a count by a sin/cos), max error 0.5 LSB. Any a;
 * exact for |b| <= 2^30, where the result cannot overflow. Larger |b| may overflow: the
 * result then saturates to INT32_MIN / INT32_MAX.
 */
int32_t fx_mul_q30(int32_t a, fx_q30_t b);

/**
 * a * b / 2^16 rounded (a Q15.16 factor on a value of any format), max error 0.5 LSB; any
 * a, b; saturates to INT32_MIN / INT32_MAX when the result does not fit.
 */
int32_t fx_mul_q16(int32_t a, int32_t b);

/**
 * a * b / 2^shift rounded to nearest, into *out; false (and *out untouched) when the result
 * does not fit int32_t. 0 <= shift <= 62 (larger shifts are fine too and round to 0 or +-1).
 * Exact (max error 0.5 LSB).
 */
bool fx_mul_shift(int32_t a, int32_t b, uint8_t shift, int32_t *out);

/**
 * num / den rounded to nearest (ties away from zero), exact (max error 0.5 LSB), into *out;
 * any int32 operands; false (and *out untouched) when den is 0 or the quotient does not fit
 * int32_t (only INT32_MIN / -1).
 */
bool fx_div32(int32_t num, int32_t den, int32_t *out);

/**
 * num * 2^shift / den rounded to nearest (ties away from zero), exact, into *out: a quotient
 * in a finer format (shift 16: Q15.16 ratio of two lengths; shift 30: a Q1.30 ratio). Any
 * shift; false (and *out untouched) when den is 0 or the quotient does not fit int32_t.
 */
bool fx_div_shift(int32_t num, int32_t den, uint8_t shift, int32_t *out);

/**
 * Reciprocal 2^shift / den rounded to nearest (ties away from zero), exact, into *out
 * (shift 32 with a Q15.16 den gives a Q15.16 reciprocal); false (and *out untouched) when
 * den is 0 or the result does not fit int32_t. Any shift.
 */
bool fx_recip(int32_t den, uint8_t shift, int32_t *out);

#ifdef __cplusplus
}
#endif

#endif
