/*
 * gnav_arith.h - the two 64-bit accumulations of the dl handler's hot path (internal).
 * Portable C in gnav_arith.c defines the results; on the MSP430 msp430/gnav_arith.S does the
 * very same integer steps with ADDC chains and the hardware multiplier (the compiler spends
 * some 40 instructions on one 64-bit add); tests/vectors/groundnav_vectors.c checks both
 * worlds bit for bit.
 */
#ifndef GROUNDNAV_GNAV_ARITH_H
#define GROUNDNAV_GNAV_ARITH_H

#include <stdint.h>

/** *acc += v (v sign-extended), modulo 2^64. */
void gnav_add64(int64_t *acc, int32_t v);

/** *acc += a * b (the exact 32-bit product, sign-extended), modulo 2^64. */
void gnav_mac64(int64_t *acc, int16_t a, int16_t b);

#endif
