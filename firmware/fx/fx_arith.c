/*
 * fx_arith.c - multiply, divide and the goniometer angle conversion (fx.h).
 *
 * Signed results are computed on magnitudes and the sign applied last, which makes the
 * rounding symmetric (ties away from zero) and every function exactly odd.
 */
#include "fx_internal.h"

uint64_t fx_umul64(uint32_t a, uint32_t b)
{
    return (uint64_t)a * b;
}

uint32_t fx_udiv64_32(uint32_t hi, uint32_t lo, uint32_t d, uint32_t *rem)
{
    /* Restoring division: the dividend shifts through the remainder one bit per step; a
     * carry out of the remainder means it is certainly >= d. */
    uint32_t r = hi, q = 0;
    for (uint8_t k = 0; k < 32u; k++) {
        uint32_t carry = r >> 31;
        r = (r << 1) | (lo >> 31);
        lo <<= 1;
        q <<= 1;
        if (carry || r >= d) {
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

fx_angle_t fx_angle_from_counts(uint32_t counts, uint16_t counts_per_turn)
{
    uint16_t d = counts_per_turn, r;
    if (d == 0)
        return 0;
    /* counts mod d, then round(r * 2^32 / d) as two 16-bit quotient digits. */
    (void)fx_udiv32_16(counts >> 16, d, &r);
    (void)fx_udiv32_16(((uint32_t)r << 16) | (counts & 0xFFFFu), d, &r);
    uint16_t hi = fx_udiv32_16((uint32_t)r << 16, d, &r);
    uint16_t lo = fx_udiv32_16((uint32_t)r << 16, d, &r);
    fx_angle_t a = ((uint32_t)hi << 16) | lo;
    if (r >= (uint16_t)(d - r))
        a++;
    return a;
}

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
    else if (shift)
        p = (p + ((uint64_t)1 << (shift - 1u))) >> shift;
    return store_signed(p, (a < 0) != (b < 0), out);
}

static int32_t mul_saturated(int32_t a, int32_t b, uint8_t shift)
{
    int32_t r;
    if (!fx_mul_shift(a, b, shift, &r))
        r = (a < 0) != (b < 0) ? INT32_MIN : INT32_MAX;
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
    if (shift >= 64u)
        return false;
    if (shift >= 32u) {
        if (shift > 32u && (n >> (64u - shift)) != 0)
            return false;
        hi = n << (shift - 32u);
        lo = 0;
    } else {
        hi = shift ? n >> (32u - shift) : 0;
        lo = n << shift;
    }
    if (hi >= d)
        return false;
    uint64_t q = fx_udiv64_32(hi, lo, d, &rem);
    if (rem >= d - rem)
        q++;
    return store_signed(q, (num < 0) != (den < 0), out);
}

bool fx_div32(int32_t num, int32_t den, int32_t *out)
{
    return fx_div_shift(num, den, 0, out);
}

bool fx_recip(int32_t den, uint8_t shift, int32_t *out)
{
    return fx_div_shift(1, den, shift, out);
}
