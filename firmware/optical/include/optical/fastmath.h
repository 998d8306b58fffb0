/*
 * optical/fastmath.h - the two arithmetic helpers the optical fix spends most of its time
 * in, in assembly on the MSP430 (firmware/optical/msp430/optical_fast.S) and in portable C
 * (fastmath.c) elsewhere; the two give bit-identical results (tests/vectors/optical_vectors.c).
 */
#ifndef OPTICAL_FASTMATH_H
#define OPTICAL_FASTMATH_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Direction of the vector (dx, dy) in 2^-16 turn (65536 = 360 degrees, CCW from +x), cheap:
 * the identification's expected angles. Any int32 components (any common scale); max error
 * 2 units (0.011 degrees); (0, 0) gives 0.
 */
uint16_t optical_angle16(int32_t dx, int32_t dy);

/**
 * floor((a b + c d + 2^29) / 2^30): a two-term dot product of Q1.30 factors, rounded once,
 * exact (max error 0.5 LSB). The caller keeps the result within int32 (|a b + c d| < 2^61).
 */
int32_t optical_dot2(int32_t a, int32_t b, int32_t c, int32_t d);

/** round(atan(i / 64) * 2^16 / (2 pi)), i = 0..64 (used by optical_angle16). */
extern const uint16_t optical_atan_tab[65];

#ifdef __cplusplus
}
#endif

#endif
