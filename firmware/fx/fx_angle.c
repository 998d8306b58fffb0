/*
 * fx_angle.c - the goniometer's counts as a binary angle (fx.h).
 */
#include "fx_internal.h"

fx_angle_t fx_angle_from_counts(uint32_t counts, uint16_t counts_per_turn)
{
    uint16_t d = counts_per_turn, r;
    if (d == 0)
        return 0;
    /* counts mod d (counts itself in the normal range), then round(r * 2^32 / d) as two
     * 16-bit quotient digits. */
    if (counts < d) {
        r = (uint16_t)counts;
    } else {
        (void)fx_udiv32_16(counts >> 16, d, &r);
        (void)fx_udiv32_16(((uint32_t)r << 16) | (counts & 0xFFFFu), d, &r);
    }
    uint16_t hi = fx_udiv32_16((uint32_t)r << 16, d, &r);
    uint16_t lo = fx_udiv32_16((uint32_t)r << 16, d, &r);
    fx_angle_t a = ((uint32_t)hi << 16) | lo;
    if (r >= (uint16_t)(d - r))
        a++;
    return a;
}
