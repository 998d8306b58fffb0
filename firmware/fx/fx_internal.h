/*
 * fx_internal.h - helpers shared by the fx sources (not part of the API).
 */
#ifndef FX_INTERNAL_H
#define FX_INTERNAL_H

#include <stdint.h>

#include "fx/fx.h"
#include "fx_tables.h"

/** a * b, the full 64-bit product. */
uint64_t fx_umul64(uint32_t a, uint32_t b);

/**
 * floor((hi * 2^32 + lo) / d) and the remainder into *rem, for hi < d (the quotient fits 32
 * bits, which the caller checks first).
 */
uint32_t fx_udiv64_32(uint32_t hi, uint32_t lo, uint32_t d, uint32_t *rem);

/** floor(n / d) and the remainder into *rem, for (n >> 16) < d (the quotient fits 16 bits). */
uint16_t fx_udiv32_16(uint32_t n, uint16_t d, uint16_t *rem);

/** Angle of the vector (ax, ay) in the first quadrant, [0, quarter]; not both zero. */
fx_angle_t fx_atan_q1(uint32_t ay, uint32_t ax);

#endif
