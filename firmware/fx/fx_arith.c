/*
 * fx_arith.c - multiply, divide and the goniometer angle conversion (fx.h).
 *
 * Signed results are computed on magnitudes and the sign applied last, which makes the
 * rounding symmetric (ties away from zero) and every function exactly odd.
 */
#include "fx_internal.h"

#ifndef FX_ASM /* MSP430: msp430/fx_arith.S */
uint64_t fx_umul64(uint32_t a, uint32_t b)
{
    return (uint64_t)a * b;
}

uint32_t fx_udiv64_32(uint32_t hi, uint32_t lo, uint32_t d, uint32_t *rem)
{
    /* Restoring division: the dividend shifts through the remainder one bit per step; the
     * remainder stays below d <= 2^31, so doubled it still fits 32 bits. */
    uint32_t r = hi, q = 0;
    for (uint8_t k = 0; k < 32u; k++) {
        r = (r << 1) | (lo >> 31);
        lo <<= 1;
        q <<= 1;
        if (r >= d) {
            r -= d;
            q |= 1u;
        }
    }
    *rem = r;
    return q;
}

uint16_t fx_udiv32_16(uint32_t n, uint16_t d, uint16_t *rem)
{
    uint16_t r = (uint16_t)(n >> 16), lo = (uint16_t)n, q = 0;
    for (uint8_t k = 0; k < 16u; k++) {
        uint16_t carry = (uint16_t)(r & 0x8000u);
        r = (uint16_t)((uint16_t)(r << 1) | (uint16_t)(lo >> 15));
        lo = (uint16_t)(lo << 1);
        q = (uint16_t)(q << 1);
        if (carry || r >= d) {
            r = (uint16_t)(r - d);
            q |= 1u;
        }
    }
    *rem = r;
    return q;
}
#endif

#ifndef FX_ASM /* MSP430: msp430/fx_arith.S */
uint64_t fx_shr64(uint64_t v, uint8_t n)
{
    if (n & 32u)
        v >>= 32;
    if (n & 16u)
        v >>= 16;
    if (n & 8u)
        v >>= 8;
    if (n & 4u)
        v >>= 4;
    if (n & 2u)
        v >>= 2;
    if (n & 1u)
        v >>= 1;
    return v;
}

uint64_t fx_shl64(uint64_t v, uint8_t n)
{
    if (n & 32u)
        v <<= 32;
    if (n & 16u)
        v <<= 16;
    if (n & 8u)
        v <<= 8;
    if (n & 4u)
        v <<= 4;
    if (n & 2u)
        v <<= 2;
    if (n & 1u)
        v <<= 1;
    return v;
}
#endif

fx_angle_t fx_angle_from_counts(uint32_t counts, uint16_t counts_per_turn)
{
    uint16_t d = counts_per_turn, r;
    if (d == 0)
        return 0;
    /* counts mod d (counts itself in the normal range), then round(r * 2^32 / d) as two
     * 16-bit quotient digits. */
    if (counts < d) {
        r = (uint16_t)counts;
    } else {
        (void)fx_udiv32_16(counts >> 16, d, &r);
        (void)fx_udiv32_16(((uint32_t)r << 16) | (counts & 0xFFFFu), d, &r);
    }
    uint16_t hi = fx_udiv32_16((uint32_t)r << 16, d, &r);
    uint16_t lo = fx_udiv32_16((uint32_t)r << 16, d, &r);
    fx_angle_t a = ((uint32_t)hi << 16) | lo;
    if (r >= (uint16_t)(d - r))
        a++;
    return a;
}

#ifndef FX_ASM /* MSP430: msp430/fx_arith.S */
static uint32_t magnitude(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

/* Store +-mag into *out when it fits int32_t. */
static bool store_signed(uint64_t mag, bool neg, int32_t *out)
{
    if (mag > (neg ? 0x80000000u : 0x7FFFFFFFu))
        return false;
    *out = neg ? (int32_t)(0u - (uint32_t)mag) : (int32_t)(uint32_t)mag;
    return true;
}

bool fx_mul_shift(int32_t a, int32_t b, uint8_t shift, int32_t *out)
{
    uint64_t p = fx_umul64(magnitude(a), magnitude(b)); /* <= 2^62 */
    if (shift >= 64u)
        p = 0;
    else if (shift) /* floor((p + 2^(shift-1)) / 2^shift) */
        p = (fx_shr64(p, (uint8_t)(shift - 1u)) + 1u) >> 1;
    return store_signed(p, (a < 0) != (b < 0), out);
}

/* a * b / 2^shift rounded, saturated; shift is a constant in each caller (inlined). */
static inline int32_t mul_saturated(int32_t a, int32_t b, uint8_t shift)
{
    uint64_t p = (fx_umul64(magnitude(a), magnitude(b)) >> (shift - 1u)) + 1u;
    bool neg = (a < 0) != (b < 0);
    int32_t r;
    if (!store_signed(p >> 1, neg, &r))
        r = neg ? INT32_MIN : INT32_MAX;
    return r;
}

int32_t fx_mul_q30(int32_t a, fx_q30_t b)
{
    return mul_saturated(a, b, 30);
}

int32_t fx_mul_q16(int32_t a, int32_t b)
{
    return mul_saturated(a, b, 16);
}

bool fx_div_shift(int32_t num, int32_t den, uint8_t shift, int32_t *out)
{
    if (den == 0)
        return false;
    uint32_t n = magnitude(num), d = magnitude(den), hi, lo, rem;
    if (n == 0) {
        *out = 0;
        return true;
    }
    /* The dividend n * 2^shift as hi:lo; a quotient of 2^32 or more cannot fit. */
    if (shift >= 64u || (shift > 32u && fx_shr64(n, (uint8_t)(64u - shift)) != 0))
        return false;
    uint64_t w = fx_shl64(n, shift);
    hi = (uint32_t)(w >> 32);
    lo = (uint32_t)w;
    if (hi >= d)
        return false;
    uint64_t q = fx_udiv64_32(hi, lo, d, &rem);
    if (rem >= d - rem)
        q++;
    return store_signed(q, (num < 0) != (den < 0), out);
}

/* n / d is n 2^0 / d: the MSP430 assembly has one body for both. */
bool fx_div32(int32_t num, int32_t den, int32_t *out)
{
    return fx_div_shift(num, den, 0, out);
}
#endif

bool fx_recip(int32_t den, uint8_t shift, int32_t *out)
{
    return fx_div_shift(1, den, shift, out);
}
