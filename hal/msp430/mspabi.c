/*
 * mspabi.c - the integer run-time helpers clang calls on the MSP430 (TI MSP430 EABI,
 * SLAA534, section 6): multiply, divide, remainder and 32-bit shifts. Debian ships no libgcc
 * for msp430-elf, so the project owns these.
 *
 * Calling conventions (as clang 16 emits them, checked against its code):
 *  - 16-bit: operands in R12, R13; result in R12.
 *  - 32-bit: operands in R12:R13 and R14:R15 (low word first); result in R12:R13.
 *    Shifts: value in R12:R13, count in R14.
 *  - 64-bit multiply: first operand in R12..R15, second on the stack (plain C convention).
 *  - Unsigned 16- and 32-bit divide and remainder and the signed 32-bit divide
 *    (__mspabi_divli, the most used one) are in mspabi_div.S (assembly: the shift-subtract
 *    loop costs a third of what clang makes of it in C, the sign handling half the flash).
 *  - 64-bit divide and remainder (__mspabi_divlli/divull/remlli/remull): the EABI's special
 *    convention, dividend in R8..R11 and divisor in R12..R15, result in R12..R15; the shims
 *    in mspabi_div64.S move the registers and call the C functions here.
 *
 * Semantics are C's (truncating division, remainder with the sign of the dividend) plus:
 *  - x / 0: unsigned gives all ones (the type's maximum), signed gives the maximum for x >= 0
 *    and the minimum for x < 0; x % 0 gives x. The divide never traps.
 *  - MIN / -1 gives MIN (two's complement wrap), MIN % -1 gives 0.
 *  - Shift counts are taken modulo the width (C leaves larger counts undefined).
 *
 * The _hw multiplies use the 16 x 16 hardware multiplier at 0x130 with interrupts disabled,
 * so an ISR that multiplies can never corrupt a multiply of the code it interrupted. The
 * 16- and 32-bit ones are in mspabi_mul.S.
 *
 * This file must not make clang call any helper it defines: it only shifts by one, adds,
 * subtracts and compares; tests/target/mspabi_test.c checks every helper on the target.
 */
#include <stdint.h>

#include "f2618.h"

/* Prototypes (the compiler knows these by name; -Wmissing-prototypes wants them here). */
int16_t __mspabi_mpyi(int16_t a, int16_t b);
int16_t __mspabi_mpyi_hw(int16_t a, int16_t b);
int32_t __mspabi_mpyl(int32_t a, int32_t b);
int32_t __mspabi_mpyl_hw(int32_t a, int32_t b);
int64_t __mspabi_mpyll(int64_t a, int64_t b);
int64_t __mspabi_mpyll_hw(int64_t a, int64_t b);
uint16_t __mspabi_divu(uint16_t a, uint16_t b);
uint16_t __mspabi_remu(uint16_t a, uint16_t b);
int16_t __mspabi_divi(int16_t a, int16_t b);
int16_t __mspabi_remi(int16_t a, int16_t b);
uint32_t __mspabi_divul(uint32_t a, uint32_t b);
uint32_t __mspabi_remul(uint32_t a, uint32_t b);
int32_t __mspabi_divli(int32_t a, int32_t b);
int32_t __mspabi_remli(int32_t a, int32_t b);
int64_t cy_mspabi_divlli(int64_t a, int64_t b);
int64_t cy_mspabi_remlli(int64_t a, int64_t b);
uint64_t cy_mspabi_divull(uint64_t a, uint64_t b);
uint64_t cy_mspabi_remull(uint64_t a, uint64_t b);
uint32_t __mspabi_slll(uint32_t x, int16_t n);
uint32_t __mspabi_srll(uint32_t x, int16_t n);
int32_t __mspabi_sral(int32_t x, int16_t n);

/* ---------------------------------------------------------------- multiply, software */

int16_t __mspabi_mpyi(int16_t a, int16_t b)
{
    uint16_t x = (uint16_t)a, y = (uint16_t)b, r = 0;
    while (y) {
        if (y & 1u)
            r = (uint16_t)(r + x);
        x = (uint16_t)(x << 1);
        y >>= 1;
    }
    return (int16_t)r;
}

int32_t __mspabi_mpyl(int32_t a, int32_t b)
{
    uint32_t x = (uint32_t)a, y = (uint32_t)b, r = 0;
    while (y) {
        if (y & 1u)
            r += x;
        x <<= 1;
        y >>= 1;
    }
    return (int32_t)r;
}

int64_t __mspabi_mpyll(int64_t a, int64_t b)
{
    uint64_t x = (uint64_t)a, y = (uint64_t)b, r = 0;
    while (y) {
        if (y & 1u)
            r += x;
        x <<= 1;
        y >>= 1;
    }
    return (int64_t)r;
}

/* ---------------------------------------------------------------- multiply, hardware */

int64_t __mspabi_mpyll_hw(int64_t a, int64_t b)
{
    uint16_t x[4], y[4], r[4] = {0, 0, 0, 0};
    uint64_t ua = (uint64_t)a, ub = (uint64_t)b;
    for (int i = 0; i < 4; i++) {
        x[i] = (uint16_t)ua;
        y[i] = (uint16_t)ub;
        ua >>= 16;
        ub >>= 16;
    }
    uint16_t sr = cy_sr_read();
    cy_dint();
    for (int i = 0; i < 4; i++) {
        if (x[i] == 0)
            continue;
        uint16_t carry = 0;
        for (int j = 0; i + j < 4; j++) {
            MPY = x[i];
            OP2 = y[j];
            uint16_t plo = RESLO, phi = RESHI;
            uint32_t t = (uint32_t)r[i + j] + plo + carry;
            r[i + j] = (uint16_t)t;
            carry = (uint16_t)(phi + (uint16_t)(t >> 16));
        }
    }
    cy_gie_restore(sr);
    uint64_t out = 0;
    for (int i = 3; i >= 0; i--)
        out = (out << 16) | r[i];
    return (int64_t)out;
}

/* ---------------------------------------------------------------- divide */

/* Unsigned 32-bit quotient and remainder through the assembly helpers; d != 0. */
static uint32_t udivmod32(uint32_t n, uint32_t d, uint32_t *rem)
{
    uint32_t q = __mspabi_divul(n, d);
    *rem = n - q * d;
    return q;
}

static uint64_t udivmod64(uint64_t n, uint64_t d, uint64_t *rem)
{
    if (((n | d) & 0xFFFFFFFF00000000ull) == 0) {
        uint32_t r32;
        uint32_t q32 = udivmod32((uint32_t)n, (uint32_t)d, &r32);
        *rem = r32;
        return q32;
    }
    uint64_t q = 0, r = 0;
    for (int i = 0; i < 64; i++) {
        r = (r << 1) | ((n & 0x8000000000000000ull) ? 1u : 0u);
        n <<= 1;
        q <<= 1;
        if (r >= d) {
            r -= d;
            q |= 1u;
        }
    }
    *rem = r;
    return q;
}

int16_t __mspabi_divi(int16_t a, int16_t b)
{
    if (!b)
        return a < 0 ? INT16_MIN : INT16_MAX;
    uint16_t ua = a < 0 ? (uint16_t)(0u - (uint16_t)a) : (uint16_t)a;
    uint16_t ub = b < 0 ? (uint16_t)(0u - (uint16_t)b) : (uint16_t)b;
    uint16_t q = __mspabi_divu(ua, ub);
    return (int16_t)(((a < 0) != (b < 0)) ? (uint16_t)(0u - q) : q);
}

int16_t __mspabi_remi(int16_t a, int16_t b)
{
    if (!b)
        return a;
    uint16_t ua = a < 0 ? (uint16_t)(0u - (uint16_t)a) : (uint16_t)a;
    uint16_t ub = b < 0 ? (uint16_t)(0u - (uint16_t)b) : (uint16_t)b;
    uint16_t r = __mspabi_remu(ua, ub);
    return (int16_t)(a < 0 ? (uint16_t)(0u - r) : r);
}

int32_t __mspabi_remli(int32_t a, int32_t b)
{
    if (!b)
        return a;
    uint32_t ua = a < 0 ? 0u - (uint32_t)a : (uint32_t)a;
    uint32_t ub = b < 0 ? 0u - (uint32_t)b : (uint32_t)b;
    uint32_t r = __mspabi_remul(ua, ub);
    return (int32_t)(a < 0 ? 0u - r : r);
}

uint64_t cy_mspabi_divull(uint64_t a, uint64_t b)
{
    uint64_t r;
    return b ? udivmod64(a, b, &r) : 0xFFFFFFFFFFFFFFFFull;
}

uint64_t cy_mspabi_remull(uint64_t a, uint64_t b)
{
    uint64_t r;
    if (!b)
        return a;
    (void)udivmod64(a, b, &r);
    return r;
}

int64_t cy_mspabi_divlli(int64_t a, int64_t b)
{
    if (!b)
        return a < 0 ? INT64_MIN : INT64_MAX;
    uint64_t ua = a < 0 ? 0u - (uint64_t)a : (uint64_t)a;
    uint64_t ub = b < 0 ? 0u - (uint64_t)b : (uint64_t)b;
    uint64_t r, q = udivmod64(ua, ub, &r);
    return (int64_t)(((a < 0) != (b < 0)) ? 0u - q : q);
}

int64_t cy_mspabi_remlli(int64_t a, int64_t b)
{
    if (!b)
        return a;
    uint64_t ua = a < 0 ? 0u - (uint64_t)a : (uint64_t)a;
    uint64_t ub = b < 0 ? 0u - (uint64_t)b : (uint64_t)b;
    uint64_t r;
    (void)udivmod64(ua, ub, &r);
    return (int64_t)(a < 0 ? 0u - r : r);
}

/* ---------------------------------------------------------------- 32-bit shifts */

uint32_t __mspabi_slll(uint32_t x, int16_t n)
{
    n &= 31;
    if (n >= 16) {
        x = (uint32_t)(uint16_t)x << 16; /* a word move, not a helper call */
        n = (int16_t)(n - 16);
    }
    while (n--)
        x <<= 1;
    return x;
}

uint32_t __mspabi_srll(uint32_t x, int16_t n)
{
    n &= 31;
    if (n >= 16) {
        x >>= 16;
        n = (int16_t)(n - 16);
    }
    while (n--)
        x >>= 1;
    return x;
}

int32_t __mspabi_sral(int32_t x, int16_t n)
{
    n &= 31;
    if (n >= 16) {
        x = (int32_t)(int16_t)((uint32_t)x >> 16); /* high word, sign-extended */
        n = (int16_t)(n - 16);
    }
    while (n--)
        x >>= 1;
    return x;
}
