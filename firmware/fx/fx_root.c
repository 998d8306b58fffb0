/*
 * fx_root.c - exact integer square roots and hypot (fx.h).
 */
#include "fx_internal.h"

#ifndef FX_ASM /* MSP430: msp430/fx_root.S */
/*
 * floor(sqrt(x)) digit by digit (base 2), the steps of msp430/fx_root.S: x is the remainder,
 * r the root so far and one = 4^j the square of the place of the next root bit, j = 15..0.
 * Where x >= r + one the bit is 1 (x -= r + one, r = r / 2 + one), else r = r / 2; at the end
 * r is the root. Exact by construction, no table, no multiply.
 */
uint16_t fx_sqrt32(uint32_t x)
{
    uint32_t r = 0;
    for (uint32_t one = 0x40000000u; one != 0; one >>= 2) {
        uint32_t t = r + one;
        r >>= 1;
        if (x >= t) {
            x -= t;
            r += one;
        }
    }
    return (uint16_t)r;
}

/* floor(sqrt(x)) for 64 bits, digit by digit as fx_sqrt32 (32 steps). */
uint32_t fx_sqrt64(uint64_t x)
{
    uint64_t r = 0;
    for (uint64_t one = (uint64_t)1 << 62; one != 0; one >>= 2) {
        uint64_t t = r + one;
        r >>= 1;
        if (x >= t) {
            x -= t;
            r += one;
        }
    }
    return (uint32_t)r;
}

uint32_t fx_hypot(int32_t x, int32_t y)
{
    uint32_t ax = x < 0 ? 0u - (uint32_t)x : (uint32_t)x;
    uint32_t ay = y < 0 ? 0u - (uint32_t)y : (uint32_t)y;
    uint64_t n = fx_umul64(ax, ax) + fx_umul64(ay, ay); /* <= 2^63 */
    uint32_t r = fx_sqrt64(n);
    /* Round: n >= r^2 + r + 1 > (r + 1/2)^2. */
    if (n - fx_umul64(r, r) > r)
        r++;
    return r;
}
#endif
