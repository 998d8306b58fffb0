/*
 * fastmath.c - optical/fastmath.h in portable C. On the MSP430 the two functions come from
 * msp430/optical_fast.S (OPTICAL_ASM), which performs the very same integer steps.
 */
#include "optical/fastmath.h"

#include <stdbool.h>

const uint16_t optical_atan_tab[65] = {
    0,    163,  326,  489,  651,  813,  975,  1136, 1297, 1457, 1617, 1775, 1933,
    2090, 2246, 2401, 2555, 2708, 2860, 3010, 3159, 3307, 3453, 3599, 3742, 3884,
    4025, 4164, 4302, 4438, 4572, 4705, 4836, 4966, 5094, 5220, 5344, 5467, 5589,
    5708, 5826, 5943, 6058, 6171, 6282, 6392, 6500, 6607, 6712, 6815, 6917, 7018,
    7117, 7214, 7310, 7405, 7498, 7589, 7679, 7768, 7856, 7942, 8026, 8110, 8192};

#ifndef OPTICAL_ASM

uint16_t optical_angle16(int32_t dx, int32_t dy)
{
    uint32_t ax = dx < 0 ? 0u - (uint32_t)dx : (uint32_t)dx;
    uint32_t ay = dy < 0 ? 0u - (uint32_t)dy : (uint32_t)dy;
    bool swap = ay > ax;
    if (swap) {
        uint32_t t = ax;
        ax = ay;
        ay = t;
    }
    if (ax == 0)
        return 0;
    while (ax >= 0x8000u) { /* both to 15 bits by the shift that brings the larger there */
        ax >>= 1;
        ay >>= 1;
    }
    uint16_t den = (uint16_t)ax, rem = (uint16_t)ay, a;
    if (rem >= den) {
        a = 8192;
    } else {
        uint16_t q = 0; /* floor(2^15 ay / ax), restoring division */
        for (uint8_t i = 0; i < 15; i++) {
            rem = (uint16_t)(rem << 1);
            q = (uint16_t)(q << 1);
            if (rem >= den) {
                rem = (uint16_t)(rem - den);
                q |= 1u;
            }
        }
        q = (uint16_t)((q + 1u) >> 1); /* 0..16384 */
        uint16_t i = q >> 8, f = q & 255u;
        a = optical_atan_tab[i];
        if (f)
            a = (uint16_t)(a + (((uint16_t)(optical_atan_tab[i + 1u] - a) * f + 128u) >> 8));
    }
    if (swap)
        a = (uint16_t)(16384u - a);
    if (dx < 0)
        a = (uint16_t)(32768u - a);
    if (dy < 0)
        a = (uint16_t)(0u - a);
    return a;
}

int32_t optical_dot2(int32_t a, int32_t b, int32_t c, int32_t d)
{
    int64_t s = (int64_t)a * b + (int64_t)c * d + (1l << 29);
    uint64_t m = s < 0 ? ~0ull : 0ull; /* floor division by 2^30 without a signed shift */
    return (int32_t)(int64_t)((((uint64_t)s ^ m) >> 30) ^ m);
}

#endif
