/*
 * gnav_arith.h - the kernels of groundnav (docs/kernels.md): the 64-bit accumulations of the
 * dl handler and its arc closing. C twins in gnav_arith_k.c, MSP430 assembly in
 * msp430/gnav_arith.S (ADDC chains and the hardware multiplier: the compiler has no
 * add-with-carry and spends some 40 instructions on one 64-bit add); cy_kernels() builds one
 * side, the check images compare them call by call.
 */
#ifndef GROUNDNAV_GNAV_ARITH_H
#define GROUNDNAV_GNAV_ARITH_H

#include <stdint.h>

/** xy[0] += v[0], xy[1] += v[1] (sign-extended), modulo 2^64. */
void gnav_add64x2(int64_t *xy, const int32_t *v);

/** xy[0] -= v[0], xy[1] -= v[1] (sign-extended), modulo 2^64. */
void gnav_sub64x2(int64_t *xy, const int32_t *v);

/** *acc += a * b (the exact 32-bit product, sign-extended), modulo 2^64. */
void gnav_mac64(int64_t *acc, int16_t a, int16_t b);

#endif
