/*
 * fx_root.c - exact integer square roots and hypot (fx.h).
 *
 * Digit by digit (base 2), with the remainder x, the root so far r and one = 4^j, the square
 * of the place of the next root bit, for j from the top down: t = r + one; r >>= 1; where
 * x >= t the bit is 1 (x -= t, r += one). Before step j, r = q 4^(j+1) (q the root's bits
 * above j), so t = r + one and r / 2 + one never carry, and r ends as the root, x as the
 * remainder x - root^2 (<= 2 root). Exact by construction, no table, no multiply.
 *
 * The values are kept in 16-bit words, the lowest first (the MSP430 compiler has no
 * add-with-carry: a 32-bit shift by one bit costs it 15 instructions). While one is in word
 * w, r and x are below 2^(16 w + 34), and r has no bits below word w: a step touches words
 * w..w+2 only.
 */
#include "fx_internal.h"

/* One step on the words w..w+2 (x, r point at word w), one in word w. */
static void step(uint16_t *x, uint16_t *r, uint16_t one)
{
    uint16_t t0 = (uint16_t)(r[0] | one); /* t = r + one */
    bool ge;                              /* x >= t, from the top word down */
    if (x[2] != r[2])
        ge = x[2] > r[2];
    else if (x[1] != r[1])
        ge = x[1] > r[1];
    else
        ge = x[0] >= t0;
    if (ge) {
        uint16_t b0 = x[0] < t0, d1;
        x[0] = (uint16_t)(x[0] - t0);
        uint16_t b1 = __builtin_sub_overflow(x[1], r[1], &d1);
        b1 = (uint16_t)(b1 | __builtin_sub_overflow(d1, b0, &d1));
        x[1] = d1;
        x[2] = (uint16_t)(x[2] - r[2] - b1);
    }
    r[0] = (uint16_t)((r[0] >> 1) | ((r[1] & 1u) ? 0x8000u : 0u)); /* r >>= 1 */
    r[1] = (uint16_t)((r[1] >> 1) | ((r[2] & 1u) ? 0x8000u : 0u));
    r[2] >>= 1;
    if (ge)
        r[0] |= one;
}

/* floor(sqrt(x)) of the n-word x (n = 2 or 4, two words of zeros after it); x becomes the
 * remainder. */
static uint32_t sqrtrem(uint16_t *x, uint8_t n)
{
    uint16_t r[6] = {0, 0, 0, 0, 0, 0};
    for (uint8_t w = n; w-- > 0u;)
        for (uint16_t one = 0x4000u; one != 0u; one >>= 2)
            step(&x[w], &r[w], one);
    return ((uint32_t)r[1] << 16) | r[0];
}

uint16_t fx_sqrt32(uint32_t x)
{
    uint16_t w[4] = {(uint16_t)x, (uint16_t)(x >> 16), 0, 0};
    return (uint16_t)sqrtrem(w, 2);
}

/* The words of v, the lowest first, and two of zeros. */
static void words(uint64_t v, uint16_t w[6])
{
    uint32_t hi = fx_hi32(v), lo = fx_lo32(v);
    w[0] = (uint16_t)lo;
    w[1] = (uint16_t)(lo >> 16);
    w[2] = (uint16_t)hi;
    w[3] = (uint16_t)(hi >> 16);
    w[4] = 0;
    w[5] = 0;
}

uint32_t fx_sqrt64(uint64_t x)
{
    uint16_t w[6];
    words(x, w);
    return sqrtrem(w, 4);
}

uint32_t fx_hypot(int32_t x, int32_t y)
{
    uint32_t ax = fx_magnitude(x), ay = fx_magnitude(y);
    uint16_t w[6];
    words(fx_umul64(ax, ax) + fx_umul64(ay, ay), w); /* <= 2^63 */
    uint32_t r = sqrtrem(w, 4);
    /* Round: n >= r^2 + r + 1 > (r + 1/2)^2, the remainder n - r^2 above r. */
    if (w[2] != 0u || (((uint32_t)w[1] << 16) | w[0]) > r)
        r++;
    return r;
}
