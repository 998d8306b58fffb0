/*
 * drive_math.c - the drive module's arithmetic helpers (drive_internal.h).
 */
#include "drive_internal.h"

#define PI_OVER_8_Q30     421657428l  /* round(pi / 8 * 2^30): binary angle -> rad Q28 */
#define PI_OVER_2_Q30     1686629713l /* round(pi / 2 * 2^30): binary angle -> rad Q30 */
/* 2^32 / (2 pi) / 2^28 = 8 / pi, in Q29. */
#define EIGHT_OVER_PI_Q29 1367130551l /* round(8 / pi * 2^29) */

int32_t drive_angle_to_rad_q28(int32_t a)
{
    return fx_mul_q30(a, PI_OVER_8_Q30);
}

int32_t drive_angle_to_rad_q30(int32_t a)
{
    return fx_mul_q30(a, PI_OVER_2_Q30);
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

int32_t drive_sec_small(int32_t x_q30)
{
    /* 1 + x^2 (1/2 + x^2 (5/24 + x^2 61/720)) */
    int32_t x2 = fx_mul_q30(x_q30, x_q30);
    int32_t t = fx_mul_q30(x2, 90969793l); /* 61/720 */
    t = fx_mul_q30(x2, 223696213l + t);    /* 5/24 */
    t = fx_mul_q30(x2, 536870912l + t);    /* 1/2 */
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
