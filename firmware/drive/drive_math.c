/*
 * drive_math.c - the drive module's shared arithmetic (drive_math.h).
 */
#include "drive_math.h"

void drive_to_frame(int32_t x, int32_t y, fx_angle_t a, int32_t *u, int32_t *v)
{
    fx_q30_t s, c;
    fx_sincos(a, &s, &c);
    *u = fx_mul_q30(x, c) + fx_mul_q30(y, s);
    *v = fx_mul_q30(y, c) - fx_mul_q30(x, s);
}

int32_t drive_series(int32_t x, const int32_t k[3])
{
    int32_t x2 = fx_mul_q30(x, x);
    int32_t t = fx_mul_q30(x2, k[2]);
    t = fx_mul_q30(x2, k[1] + t);
    t = fx_mul_q30(x2, k[0] + t);
    return (int32_t)(FX_Q30_ONE + t);
}
