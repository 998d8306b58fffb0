/*
 * fx_root.c - exact integer square roots and hypot (fx.h).
 */
#include "fx_internal.h"

uint16_t fx_sqrt32(uint32_t x)
{
    /* Digit by digit: each step decides one bit of the root from two bits of x. */
    uint32_t root = 0, bit = 1ul << 30;
    while (bit > x)
        bit >>= 2;
    while (bit) {
        if (x >= root + bit) {
            x -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (uint16_t)root;
}

uint32_t fx_sqrt64(uint64_t x)
{
    uint64_t root = 0, bit = (uint64_t)1 << 62;
    while (bit > x)
        bit >>= 2;
    while (bit) {
        if (x >= root + bit) {
            x -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (uint32_t)root;
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
