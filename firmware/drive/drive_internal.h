/*
 * drive_internal.h - what the drive module's sources share (not public): the arithmetic
 * helpers and the little interpreter the solver's formulas run on. Also read by the MSP430
 * assembly (msp430/ sources): only #defines outside the __ASSEMBLER__ guard.
 *
 * The solver is a few dozen fx calls (products, angles, sincos) between a handful of
 * decisions. Compiled, each call costs about 28 bytes of MSP430 code (operands loaded from
 * and results stored to the stack frame); as a 4-byte instruction of a program run by
 * drive_vm_run() it costs 4. A program is a const table of instructions working on a frame of
 * int32 slots; the decisions between programs stay in code. Every instruction is exactly the
 * fx call (or the integer operation) it names, so a program gives bit for bit what the same
 * calls give in C, on both worlds (tests/vectors/drive_vectors.c).
 */
#ifndef DRIVE_INTERNAL_H
#define DRIVE_INTERNAL_H

/* ------------------------------------------------------------------ the interpreter */

/* An instruction is four bytes: opcode, destination, operand a, operand b. Slot operands are
 * byte offsets into the frame (DRIVE_S: slot index * 4, so a frame has at most 64 slots);
 * b is an immediate for SHL (the shift count) and a constant's byte offset into drive_vm_k
 * for MULK and POLY. Opcodes are even: the MSP430 interpreter jumps through a table with
 * them. Arithmetic wraps where C's int32 would overflow (binary angles). */
#define DRIVE_OP_END    0  /* end of the program                                  */
#define DRIVE_OP_ADD    2  /* d = a + b                                           */
#define DRIVE_OP_SUB    4  /* d = a - b                                           */
#define DRIVE_OP_NEG    6  /* d = -a                                              */
#define DRIVE_OP_ABS    8  /* d = |a| (INT32_MIN stays)                           */
#define DRIVE_OP_HALF   10 /* d = a / 2, toward zero (exactly odd)                */
#define DRIVE_OP_SHL    12 /* d = a << b, b an immediate count                    */
#define DRIVE_OP_MUL    14 /* d = fx_mul_q30(a, b)                                */
#define DRIVE_OP_MULK   16 /* d = fx_mul_q30(a, constant b)                       */
#define DRIVE_OP_POLY   18 /* d = drive_poly(a, series at constant b)             */
#define DRIVE_OP_ATAN2  20 /* d = fx_atan2(a, b)                                  */
#define DRIVE_OP_SINCOS 22 /* d = fx_sin(a), d + 1 = fx_cos(a)                    */
#define DRIVE_OP_ROT    24 /* d, d + 1 = drive_rot of (a, a + 1) by the angle b   */

#define DRIVE_S(slot)        ((slot)*4)
#define DRIVE_ADD(d, a, b)   DRIVE_OP_ADD, DRIVE_S(d), DRIVE_S(a), DRIVE_S(b)
#define DRIVE_SUB(d, a, b)   DRIVE_OP_SUB, DRIVE_S(d), DRIVE_S(a), DRIVE_S(b)
#define DRIVE_NEG(d, a)      DRIVE_OP_NEG, DRIVE_S(d), DRIVE_S(a), 0
#define DRIVE_ABS(d, a)      DRIVE_OP_ABS, DRIVE_S(d), DRIVE_S(a), 0
#define DRIVE_HALF(d, a)     DRIVE_OP_HALF, DRIVE_S(d), DRIVE_S(a), 0
#define DRIVE_SHL(d, a, n)   DRIVE_OP_SHL, DRIVE_S(d), DRIVE_S(a), (n)
#define DRIVE_MUL(d, a, b)   DRIVE_OP_MUL, DRIVE_S(d), DRIVE_S(a), DRIVE_S(b)
#define DRIVE_MULK(d, a, k)  DRIVE_OP_MULK, DRIVE_S(d), DRIVE_S(a), DRIVE_S(k)
#define DRIVE_POLY(d, a, k)  DRIVE_OP_POLY, DRIVE_S(d), DRIVE_S(a), DRIVE_S(k)
#define DRIVE_ATAN2(d, y, x) DRIVE_OP_ATAN2, DRIVE_S(d), DRIVE_S(y), DRIVE_S(x)
#define DRIVE_SINCOS(d, a)   DRIVE_OP_SINCOS, DRIVE_S(d), DRIVE_S(a), 0
#define DRIVE_ROT(d, xy, a)  DRIVE_OP_ROT, DRIVE_S(d), DRIVE_S(xy), DRIVE_S(a)
#define DRIVE_END            DRIVE_OP_END, 0, 0, 0 /* four bytes like any instruction */

/* Constants of MULK and POLY: indices into drive_vm_k. */
#define DRIVE_K_PI_2  0  /* pi / 2, Q30: binary angle -> radians Q30        */
#define DRIVE_K_PI_4  1  /* pi / 4, Q30                                     */
#define DRIVE_K_TINY  2  /* pi^2 / 24576, Q30 (solve.c, chord factors)      */
#define DRIVE_K_RAD   3  /* 8 / pi - 2, Q30: radians Q28 -> binary angle    */
#define DRIVE_K_XOS   4  /* x / sin x: 1/6, 7/360, 31/15120                 */
#define DRIVE_K_SEC   7  /* 1 / cos x: 1/2, 5/24, 61/720                    */
#define DRIVE_K_SOX   10 /* sin x / x: -1/6, 1/120, -1/5040                */
#define DRIVE_K_COUNT 13

#ifndef __ASSEMBLER__
#include <stdint.h>

#include "fx/fx.h"

/** |x| as uint32 (also for INT32_MIN). */
static inline uint32_t drive_abs32(int32_t x)
{
    return x < 0 ? (uint32_t)0 - (uint32_t)x : (uint32_t)x;
}

/** The constants of MULK and POLY (DRIVE_K_*). */
extern const int32_t drive_vm_k[DRIVE_K_COUNT];

/** Run @p prog (DRIVE_END terminated) on the frame @p v. */
void drive_vm_run(int32_t *v, const uint8_t *prog);

/**
 * Rotate (xy[0], xy[1]) by -a into out[0..1]: out[0] = x cos a + y sin a, out[1] =
 * y cos a - x sin a (fx_sincos and four fx_mul_q30, each rounded: error within 1 LSB +
 * |(x, y)| * 1.1e-7). With a the direction of a frame's x axis these are the coordinates in
 * that frame; with -a and (l, 0) it is the vector of length l in direction a (fx_sin is
 * exactly odd, fx_cos exactly even). out may not overlap xy.
 */
void drive_rot(int32_t out[2], const int32_t xy[2], fx_angle_t a);

/**
 * 1 + x^2 (k[0] + x^2 (k[1] + x^2 k[2])) in Q30 for x in Q30 (Horner with fx_mul_q30):
 * @p k one of the series of drive_vm_k, for |x| <= 0.2 rad. x / sin x (DRIVE_K_XOS) and
 * sin x / x (DRIVE_K_SOX) within 1e-9 of the function, 1 / cos x (DRIVE_K_SEC) within 1e-7,
 * plus the rounding of four products (4 LSB).
 */
int32_t drive_poly(int32_t x, const int32_t *k);
#endif

#endif
