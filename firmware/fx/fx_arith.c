/*
 * fx_arith.c - the multiplies and divides of fx.h that are not kernels, built on them (the
 * kernels fx_umul64 and fx_div_shift: fx_arith_k.c or msp430/fx_arith.S).
 */
#include "fx_internal.h"

bool fx_mul_shift(int32_t a, int32_t b, uint8_t shift, int32_t *out)
{
    uint64_t p = fx_umul64(fx_magnitude(a), fx_magnitude(b)); /* <= 2^62 */
    uint32_t hi = fx_hi32(p), lo = fx_lo32(p);
    if (shift >= 64u) {
        hi = 0;
        lo = 0;
    } else if (shift) {
        /* floor((p + 2^(shift-1)) / 2^shift) = ((p >> (shift - 1)) + 1) >> 1, the shift by
         * words and bytes first (a variable 64-bit shift is a long loop on the MSP430) */
        uint8_t n = (uint8_t)(shift - 1u);
        if (n & 32u) {
            lo = hi;
            hi = 0;
        }
        if (n & 16u) {
            lo = (lo >> 16) | (hi << 16);
            hi >>= 16;
        }
        if (n & 8u) {
            lo = (lo >> 8) | (hi << 24);
            hi >>= 8;
        }
        for (n &= 7u; n; n--) {
            lo = (lo >> 1) | (hi << 31);
            hi >>= 1;
        }
        if (++lo == 0u) /* p + 1 < 2^63: no carry out of hi */
            hi++;
        lo = (lo >> 1) | (hi << 31);
        hi >>= 1;
    }
    return fx_store_signed(hi, lo, (a < 0) != (b < 0), out);
}

/* n / d is n 2^0 / d. */
bool fx_div32(int32_t num, int32_t den, int32_t *out)
{
    return fx_div_shift(num, den, 0, out);
}

bool fx_recip(int32_t den, uint8_t shift, int32_t *out)
{
    return fx_div_shift(1, den, shift, out);
}
