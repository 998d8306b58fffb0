/*
 * fx_internal.h - what the fx sources share (not part of the API): the kernels that are not
 * public functions, and the word-sized helpers the C is written with.
 *
 * The MSP430 compiler (clang 16) has no add-with-carry: a 32-bit shift by one bit, for one,
 * becomes a dozen instructions. The C here therefore works on 16- and 32-bit words and takes
 * carries with __builtin_add_overflow (an ADD and a read of the carry).
 */
#ifndef FX_INTERNAL_H
#define FX_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "fx/fx.h"
#include "fx_tables.h"

/* ------------------------------------------------------------------ kernels (docs/kernels.md) */

/** a * b, the full 64-bit product (fx_arith_k.c, msp430/fx_arith.S). */
uint64_t fx_umul64(uint32_t a, uint32_t b);

/**
 * floor(n / d) and the remainder into *rem, for (n >> 16) < d (the quotient fits 16 bits)
 * (fx_arith_k.c, msp430/fx_arith.S).
 */
uint16_t fx_udiv32_16(uint32_t n, uint16_t d, uint16_t *rem);

/**
 * Angle of the vector (ax, ay) in the first quadrant, [0, quarter], for 0 <= ax, ay <= 2^31,
 * not both zero (fx_trig_k.c, msp430/fx_trig.S): the octant, a Q24 ratio by division, the
 * arctangent table.
 */
fx_angle_t fx_atan_q1(uint32_t ay, uint32_t ax);

/* ------------------------------------------------------------------ word helpers */

/** |v| as an unsigned magnitude (2^31 for INT32_MIN). */
static inline uint32_t fx_magnitude(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

/** 2 v modulo 2^32 plus @p carry_in (0 or 1); the bit shifted out into *carry_out. */
static inline uint32_t fx_dbl32(uint32_t v, uint16_t carry_in, uint16_t *carry_out)
{
    uint16_t lo = (uint16_t)v, hi = (uint16_t)(v >> 16);
    uint16_t c0 = __builtin_add_overflow(lo, lo, &lo);
    uint16_t c1 = __builtin_add_overflow(hi, hi, &hi);
    lo = (uint16_t)(lo + carry_in); /* bit 0 is free after the doubling */
    hi = (uint16_t)(hi + c0);
    *carry_out = c1;
    return ((uint32_t)hi << 16) | lo;
}

/** The words of a 64-bit value. */
static inline uint32_t fx_hi32(uint64_t v)
{
    return (uint32_t)(v >> 32);
}

static inline uint32_t fx_lo32(uint64_t v)
{
    return (uint32_t)v;
}

/** Store +-mag into *out when it fits int32_t (mag given as its words hi:lo). */
static inline bool fx_store_signed(uint32_t hi, uint32_t lo, bool neg, int32_t *out)
{
    if (hi != 0u || lo > (neg ? 0x80000000u : 0x7FFFFFFFu))
        return false;
    *out = neg ? (int32_t)(0u - lo) : (int32_t)lo;
    return true;
}

#endif
