/*
 * fx_root.c - exact integer square roots and hypot (fx.h).
 */
#include "fx_internal.h"

#ifndef FX_ASM /* MSP430: msp430/fx_root.S */
/* floor(v / 2^n) of a signed value, without relying on >> of negative numbers. */
static int32_t asr32(int32_t v, uint8_t n)
{
    return v < 0 ? ~(~v >> n) : v >> n;
}

/*
 * floor(sqrt(x)) from a table and one Newton step, the steps of msp430/fx_root.S:
 *  - x = xn / 4^k with xn in [2^30, 2^32) (k pairs of leading zero bits shifted out);
 *  - the top byte j of xn picks S (within 144 of sqrt(xn), a multiple of 32) and R = 2^28 / S;
 *  - Newton: Y = S + e / (2 S) with e = xn - S^2 lies in [sqrt(xn), sqrt(xn) + 0.32];
 *    computed in sixteenths, h = floor(floor(e / 2^9) R / 2^16), and rounded up by 3/8:
 *    Y = S + floor((h + 6) / 16), which is floor(sqrt(xn)) or one more (the errors of the
 *    two floors and of R stay below 0.1; tests/unit/fx_test.cpp checks every xn, Y only
 *    changing every 512 xn as S^2 is a multiple of 1024);
 *  - one comparison Y^2 > xn makes it exact, and floor(Y / 2^k) = floor(sqrt(x)).
 */
uint16_t fx_sqrt32(uint32_t x)
{
    if (x == 0)
        return 0;
    uint8_t k = 0;
    while (x < 0x40000000u) {
        x <<= 2;
        k++;
    }
    uint16_t j = (uint16_t)((x >> 24) - 64u);
    uint16_t s = fx_sqrt_tab[2u * j], r = fx_sqrt_tab[2u * j + 1u];
    uint32_t e = x - (uint32_t)s * s;         /* signed, |e| < 2^24: two's complement */
    int16_t e9 = (int16_t)(uint16_t)(e >> 9); /* floor(e / 2^9) */
    int32_t h = asr32((int32_t)e9 * (int32_t)r, 16);
    uint16_t y = (uint16_t)(s + (uint16_t)asr32(h + 6, 4));
    if (y == 0) /* 65536 wrapped (x next to 2^32) */
        y = 0xFFFFu;
    if ((uint32_t)y * y > x)
        y--;
    return (uint16_t)(y >> k);
}
#endif

/*
 * floor(sqrt(x)) for 64 bits from the 32-bit root of the top half and one division:
 * x = xn / 4^k with xn in [2^62, 2^64); s = floor(sqrt(hi)) of its high word hi, r = hi - s^2;
 * then the root is s 2^16 + t with t <= t0 = floor((r 2^16 + lo / 2^16) / (2 s)) (dropping
 * t^2 only overestimates) and t >= t0 - 1, so Y = s 2^16 + t0 needs at most a step or two
 * down (Y^2 > xn), and floor(Y / 2^k) = floor(sqrt(x)).
 */
uint32_t fx_sqrt64(uint64_t x)
{
    if ((x >> 32) == 0)
        return fx_sqrt32((uint32_t)x);
    uint32_t hi = (uint32_t)(x >> 32);
    uint8_t k = 0; /* pairs of leading zero bits */
    if (hi < 0x10000u) {
        hi <<= 16;
        k = 8;
    }
    if (hi < 0x1000000u) {
        hi <<= 8;
        k += 4;
    }
    if (hi < 0x10000000u) {
        hi <<= 4;
        k += 2;
    }
    if (hi < 0x40000000u)
        k += 1;
    x = fx_shl64(x, (uint8_t)(2u * k));
    uint32_t lo = (uint32_t)x;
    hi = (uint32_t)(x >> 32);
    uint16_t s = fx_sqrt32(hi), rem;
    uint32_t r = hi - (uint32_t)s * s;      /* <= 2 s < 2^17 */
    uint32_t half = (r << 15) | (lo >> 17); /* floor((r 2^16 + lo / 2^16) / 2) */
    uint16_t t = (half >> 16) >= s ? 0xFFFFu : fx_udiv32_16(half, s, &rem);
    uint32_t y = ((uint32_t)s << 16) + t;
    while (fx_umul64(y, y) > x)
        y--;
    return (uint32_t)fx_shr64(y, k);
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
