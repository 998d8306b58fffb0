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
 * floor((hi * 2^32 + lo) / d) and the remainder into *rem, for hi < d <= 2^31 (the quotient
 * fits 32 bits, which the caller checks first; every caller's d is a magnitude of an int32).
 */
uint32_t fx_udiv64_32(uint32_t hi, uint32_t lo, uint32_t d, uint32_t *rem);

/** floor(n / d) and the remainder into *rem, for (n >> 16) < d (the quotient fits 16 bits). */
uint16_t fx_udiv32_16(uint32_t n, uint16_t d, uint16_t *rem);

/**
 * v >> n and v << n for n < 64 as a few constant shifts (a variable 64-bit shift is a long
 * loop on the MSP430; these are byte and word moves plus at most seven bit steps).
 */
uint64_t fx_shr64(uint64_t v, uint8_t n);
uint64_t fx_shl64(uint64_t v, uint8_t n);

/** Angle of the vector (ax, ay) in the first quadrant, [0, quarter]; not both zero. */
fx_angle_t fx_atan_q1(uint32_t ay, uint32_t ax);

#endif
