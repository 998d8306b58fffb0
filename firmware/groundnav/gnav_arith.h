/*
 * gnav_arith.h - internals shared by gnav.c and the MSP430 assembly: the 64-bit accumulations
 * of the dl handler's hot path, the arc closing and its deferred part.
 * Portable C in gnav_arith.c defines the accumulations; on the MSP430 msp430/gnav_arith.S does the
 * very same integer steps with ADDC chains and the hardware multiplier (the compiler spends
 * some 40 instructions on one 64-bit add); tests/vectors/groundnav_vectors.c checks both
 * worlds bit for bit.
 */
#ifndef GROUNDNAV_GNAV_ARITH_H
#define GROUNDNAV_GNAV_ARITH_H

#include <stdint.h>

#include "groundnav/gnav.h"

/** xy[0] += v[0], xy[1] += v[1] (sign-extended), modulo 2^64. */
void gnav_add64x2(int64_t *xy, const int32_t *v);

/** xy[0] -= v[0], xy[1] -= v[1] (sign-extended), modulo 2^64. */
void gnav_sub64x2(int64_t *xy, const int32_t *v);

/** *acc += a * b (the exact 32-bit product, sign-extended), modulo 2^64. */
void gnav_mac64(int64_t *acc, int16_t a, int16_t b);

/**
 * Close the interval's arc at this pulse (seed situations 1 and 3): called by the dl handler
 * when a gyro edge came since the last pulse. Portable C in gnav.c, assembly on the MSP430
 * (msp430/gnav_dl.S).
 */
void gnav_close_arc(gnav_t *g);

/** The deferred part of a closing, at the next pulse: the deficit per pulse and the curved
 * step of the new interval (portable C in gnav.c, called by either dl handler). */
void gnav_finish_interval(gnav_t *g);

#endif
