/*
 * gnav_arith.h - the kernels of groundnav (docs/kernels.md): the dl handler's 64-bit step and
 * the numeric parts of a closing (the chord's correction; an arc's deficit with it). C twins in
 * gnav_arith_k.c, MSP430 assembly in msp430/gnav_arith.S (ADDC chains and the hardware multiplier:
 * the compiler has no add-with-carry and spends some 40 instructions on one 64-bit add);
 * cy_kernels() builds one side, the check images compare them call by call.
 */
#ifndef GROUNDNAV_GNAV_ARITH_H
#define GROUNDNAV_GNAV_ARITH_H

#include <stdint.h>

#include "groundnav/gnav.h"

/** xy[0] += v[0], xy[1] += v[1] (sign-extended), modulo 2^64. */
void gnav_add64x2(int64_t *xy, const int32_t *v);

/** xy[0] -= v[0], xy[1] -= v[1] (sign-extended), modulo 2^64. */
void gnav_sub64x2(int64_t *xy, const int32_t *v);

/**
 * The closing pulse's step and the chord's correction of the provisional position: the step
 * (@p step, Q25 per axis, subtracted when reverse is set), and delta = 2 rho_p nc - e, what the
 * provisional pose assumed (nc = min(m, n_p) pulses of rho_p, m = |n| the pulses since P)
 * against the closing's deficit @p e (pulses Q16), negated when the interval ran backwards
 * (n < 0), applied along the interval's cell (d15_c, d15_s) rounded to Q10 with the rounding
 * carried in resid (the caller takes the point reached as the closing point P). Reads n, n_p
 * and rho_p as they were before the closing.
 */
void gnav_chord(gnav_t *g, int32_t e, const int32_t *step);

/**
 * An arc's closing: gnav_chord() with e = the front-wheel deficit of a one-step arc over the
 * m pulses since P, E(m) = m - sqrt(m^2 - M^2), pulses Q16, from the table or the reciprocal
 * and g(x) tables, which leaves in g what the deficit per pulse needs (rho_p, or x_p, g_p and
 * rho_due). @p half (1: the first edge after init, half a step from the cell centre):
 * E(2 m) / 2 rounded up, 2 m saturating at 2^31. The arc's (2) m >= n0.
 */
void gnav_arc(gnav_t *g, uint16_t half, const int32_t *step);

#endif
