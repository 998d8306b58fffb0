/*
 * drive_math.c - the drive module's arithmetic helpers (drive_internal.h).
 */
#include "drive_internal.h"

uint64_t drive_umul(uint32_t a, uint32_t b)
{
    /* Four 16 x 16 products (the MSP430's multiplier width) instead of a 64 x 64 multiply. */
    uint16_t a0 = (uint16_t)a, a1 = (uint16_t)(a >> 16);
    uint16_t b0 = (uint16_t)b, b1 = (uint16_t)(b >> 16);
    uint32_t lo = (uint32_t)a0 * b0, hi = (uint32_t)a1 * b1;
    uint32_t m1 = (uint32_t)a0 * b1, m2 = (uint32_t)a1 * b0;
    uint64_t mid = (uint64_t)m1 + m2;
    return ((uint64_t)hi << 32) + (mid << 16) + lo;
}

uint32_t drive_udiv64(uint64_t n, uint32_t d)
{
    uint32_t r = (uint32_t)(n >> 32), lo = (uint32_t)n;
    if (r >= d)
        return UINT32_MAX; /* the quotient needs more than 32 bits (or d == 0) */
    uint32_t q = 0;
    for (uint8_t i = 0; i < 32u; i++) {
        uint32_t out = r >> 31;
        r = (r << 1) | (lo >> 31);
        lo <<= 1;
        q <<= 1;
        if (out || r >= d) {
            r -= d;
            q |= 1u;
        }
    }
    /* Round to nearest: add one when 2r >= d. */
    if ((r >> 31) || (r << 1) >= d) {
        if (q == UINT32_MAX)
            return UINT32_MAX;
        q++;
    }
    return q;
}

uint32_t drive_udiv(uint32_t n, uint32_t d, uint8_t sh)
{
    if (sh >= 32u) {
        uint8_t more = (uint8_t)(sh - 32u);
        if (more && (n >> (32u - more)) != 0)
            return UINT32_MAX;
        return drive_udiv64((uint64_t)(n << more) << 32, d);
    }
    if (sh == 0)
        return drive_udiv64(n, d);
    return drive_udiv64(((uint64_t)(n >> (32u - sh)) << 32) | (n << sh), d);
}

uint32_t drive_hypot(int32_t a, int32_t b)
{
    uint32_t ua = drive_abs32(a), ub = drive_abs32(b);
    return fx_sqrt64(drive_umul(ua, ua) + drive_umul(ub, ub));
}

/* 2pi / 2^32 * 2^28 = pi / 8: a (binary angle) * pi/8 = a * (pi/8 * 2^31) / 2^31. */
#define PI_OVER_8_Q31     843314857l /* round(pi / 8 * 2^31) */
/* 2^32 / (2 pi) / 2^28 = 8 / pi, in Q29. */
#define EIGHT_OVER_PI_Q29 1367130551l /* round(8 / pi * 2^29) */

int32_t drive_angle_to_rad_q28(int32_t a)
{
    int32_t r = 0;
    (void)fx_mul_shift(a, PI_OVER_8_Q31, 31, &r); /* |a * pi/8| < 2^31: always fits */
    return r;
}

fx_angle_t drive_rad_q28_to_angle(int32_t r)
{
    /* |r| < 8 rad: r * 8/pi < 2^31 * 2.55 may not fit int32; split off whole turns first.
     * One turn is 2 pi rad = 1686629713 in Q28. */
    const int32_t turn = 1686629713l;
    while (r >= turn / 2)
        r -= turn;
    while (r < -(turn / 2))
        r += turn;
    int32_t a = 0;
    (void)fx_mul_shift(r, EIGHT_OVER_PI_Q29, 29, &a); /* |r| <= pi: fits */
    return (fx_angle_t)a;
}

int32_t drive_x_over_sin_small(int32_t x_q30)
{
    /* 1 + x^2 (1/6 + x^2 (7/360 + x^2 31/15120)), Horner in Q30 */
    int32_t x2 = fx_mul_q30(x_q30, x_q30);
    int32_t t = fx_mul_q30(x2, 2201455l); /* 31/15120 */
    t = fx_mul_q30(x2, 20878313l + t);    /* 7/360 */
    t = fx_mul_q30(x2, 178956971l + t);   /* 1/6 */
    return (int32_t)(FX_Q30_ONE + t);
}

int32_t drive_sin_over_x_small(int32_t x_q30)
{
    /* 1 - x^2 (1/6 - x^2 (1/120 - x^2 / 5040)) */
    int32_t x2 = fx_mul_q30(x_q30, x_q30);
    int32_t t = fx_mul_q30(x2, 213044l); /* 1/5040 */
    t = fx_mul_q30(x2, 8947849l - t);    /* 1/120 */
    t = fx_mul_q30(x2, 178956971l - t);  /* 1/6 */
    return (int32_t)(FX_Q30_ONE - t);
}
