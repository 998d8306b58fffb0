/*
 * fx_arith_k.c - the C twins of the arithmetic kernels (docs/kernels.md; msp430/fx_arith.S
 * holds the same functions, built instead of this file there): the 64-bit product, the
 * 32/16 division, and the rounded multiplies and the divide of fx.h.
 *
 * Signed results are computed on magnitudes and the sign applied last, which makes the
 * rounding symmetric (ties away from zero) and every function exactly odd.
 */
#include "fx_internal.h"

static uint32_t mul16(uint16_t a, uint16_t b)
{
    return (uint32_t)a * b;
}

/* a * b as the words *hi:*lo: four 16 x 16 products. */
static void umul32(uint32_t a, uint32_t b, uint32_t *hi, uint32_t *lo)
{
    uint16_t al = (uint16_t)a, ah = (uint16_t)(a >> 16), bl = (uint16_t)b, bh = (uint16_t)(b >> 16);
    uint32_t ll = mul16(al, bl), lh = mul16(al, bh), hl = mul16(ah, bl), hh = mul16(ah, bh);
    uint32_t mid = (ll >> 16) + (uint16_t)lh + (uint16_t)hl; /* < 3 * 2^16 */
    *hi = hh + (lh >> 16) + (hl >> 16) + (mid >> 16);
    *lo = (mid << 16) | (uint16_t)ll;
}

uint64_t fx_umul64(uint32_t a, uint32_t b)
{
    uint32_t hi, lo;
    umul32(a, b, &hi, &lo);
    return ((uint64_t)hi << 32) | lo;
}

uint16_t fx_udiv32_16(uint32_t n, uint16_t d, uint16_t *rem)
{
    /* Restoring division: n doubles 16 times, its high word the remainder, the quotient bits
     * entering at the bottom as the dividend's bits leave; a bit doubled out of the remainder
     * (17 bits) is certainly >= d. */
    uint32_t x = n;
    for (uint8_t k = 0; k < 16u; k++) {
        uint16_t out;
        x = fx_dbl32(x, 0, &out);
        if (out || (uint16_t)(x >> 16) >= d)
            x = x - ((uint32_t)d << 16) + 1u;
    }
    *rem = (uint16_t)(x >> 16);
    return (uint16_t)x;
}

/* a * b / 2^shift rounded to nearest (ties away from zero), saturated; shift 16 or 30 (a
 * constant in each caller). */
static inline int32_t mul_saturated(int32_t a, int32_t b, uint8_t shift)
{
    uint32_t hi, lo, m;
    bool neg = (a < 0) != (b < 0);
    umul32(fx_magnitude(a), fx_magnitude(b), &hi, &lo); /* <= 2^62 */
    uint32_t half = (uint32_t)1 << (shift - 1u);
    lo += half;
    if (lo < half)
        hi++;
    if (shift == 16u) {
        m = (hi << 16) | (lo >> 16);
        hi >>= 16;
    } else {
        m = (hi << 2) | (lo >> 30);
        hi >>= 30;
    }
    int32_t r;
    if (!fx_store_signed(hi, m, neg, &r))
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

/* floor((hi 2^32 + lo) / d) and the remainder into *rem, for hi < d <= 2^31: restoring
 * division, 32 steps (the remainder stays below d, so doubled it still fits 32 bits); 16 when
 * hi = 0 and lo >> 16 < d (the quotient's high word is 0). */
static uint32_t udiv64_32(uint32_t hi, uint32_t lo, uint32_t d, uint32_t *rem)
{
    uint32_t r = hi, q = lo; /* q: the dividend's bits leave at the top, the quotient's enter */
    uint8_t steps = 32;
    if (hi == 0u && (lo >> 16) < d) {
        r = lo >> 16;
        q = lo << 16;
        steps = 16;
    }
    for (uint8_t k = 0; k < steps; k++) {
        uint16_t bit, unused;
        q = fx_dbl32(q, 0, &bit);
        r = fx_dbl32(r, bit, &unused);
        if (r >= d) {
            r -= d;
            q |= 1u;
        }
    }
    *rem = r;
    return q;
}

bool fx_div_shift(int32_t num, int32_t den, uint8_t shift, int32_t *out)
{
    if (den == 0)
        return false;
    uint32_t n = fx_magnitude(num), d = fx_magnitude(den), hi = 0, lo = n, rem;
    if (n == 0) {
        *out = 0;
        return true;
    }
    if (shift >= 64u)
        return false;
    /* the dividend n 2^shift as hi:lo; a quotient of 2^32 or more cannot fit */
    if (shift >= 32u) {
        hi = lo;
        lo = 0;
    }
    uint8_t k = shift & 31u;
    if (k >= 16u) {
        if (hi >> 16)
            return false; /* n 2^shift >= 2^64 */
        hi = (hi << 16) | (lo >> 16);
        lo <<= 16;
        k = (uint8_t)(k - 16u);
    }
    for (; k; k--) {
        uint16_t bit;
        lo = fx_dbl32(lo, 0, &bit);
        hi = fx_dbl32(hi, bit, &bit);
        if (bit)
            return false; /* n 2^shift >= 2^64 */
    }
    if (hi >= d)
        return false;
    uint32_t q = udiv64_32(hi, lo, d, &rem);
    if (rem >= d - rem) {
        if (++q == 0u)
            return false;
    }
    return fx_store_signed(0, q, (num < 0) != (den < 0), out);
}
