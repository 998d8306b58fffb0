/*
 * accept.c - the dead-reckoning uncertainty that optical_fix() gates every fix with (SPEC O6,
 * docs/optical.md "O6"): how much the approximate pose may be off after a stretch of travel
 * and turning since the last accepted fix. optical/optical.h documents the calls. The
 * arithmetic is 16-bit with 16 x 16 products (2^-8 m and 2^-16 turn, bounds rounded up; the
 * configuration's ranges in optical.h keep every product within 32 bits).
 */
#include <stdint.h>

#include "optical/optical.h"

/* ceil(v / 2^16) */
static uint32_t ceil16(uint32_t v)
{
    return (v >> 16) + ((v & 0xFFFFu) != 0u);
}

void optical_unc_grow(const optical_config_t *cfg, optical_unc_t *u, fx_q16_t travel,
                      fx_angle_t turn)
{
    /* 2^-8 m and 2^-16 turn, rounded up (bounds stay bounds; nothing grows standing still) */
    uint16_t t8 = travel <= 0           ? 0u
                  : travel >= 0xFFFF00l ? 0xFFFFu
                                        : (uint16_t)(((uint32_t)travel + 255u) >> 8);
    uint32_t tr = ceil16(turn >= 0x80000000ul ? 0x80000000ul : turn);
    uint32_t h = ceil16(u->heading), hmax = cfg->turn_max >> 16;
    /* heading: the gyro's scale on the turn, its drift per metre travelled (per metre in
     * 2^-24 turn, rounded up: t8 of them make 2^-32 turn) */
    uint32_t dh = ceil16(tr * (uint16_t)cfg->unc_turn) +
                  ceil16((uint32_t)t8 * (uint16_t)((cfg->unc_head_per_m + 255u) >> 8));
    h = h >= hmax || dh >= hmax - h ? hmax : h + dh;
    /* position: the odometer's scale on the travel, and the heading's error over it, h 2 pi /
     * 2^16 t8 in 2^-8 m, with 2 pi / 2^16 <= 202 / 2^21 (0.5 % high), each part rounded up */
    uint32_t ht = (uint32_t)h * t8; /* (h <= 2^15, t8 < 2^16) */
    uint32_t dp = ceil16((uint32_t)t8 * (uint16_t)cfg->unc_per_m) +
                  ((((ht >> 10) + ((ht & 1023u) != 0u)) * 202u + 2047u) >> 11);
    uint32_t p = (((uint32_t)u->pos + 255u) >> 8) + dp, pmax = (uint32_t)cfg->jump_max >> 8;
    u->heading = (fx_angle_t)h << 16;
    u->pos = p >= pmax ? cfg->jump_max : (fx_q16_t)(p << 8);
}

void optical_unc_after_fix(const optical_config_t *cfg, const optical_fix_t *fix, optical_unc_t *u)
{
    fx_q16_t p = fix->err > cfg->unc_pos_min ? fix->err : cfg->unc_pos_min;
    fx_angle_t h = fix->err_heading + cfg->unc_head_min; /* (both below a quarter turn) */
    u->pos = p < cfg->jump_max ? p : cfg->jump_max;
    u->heading = h > cfg->turn_max ? cfg->turn_max : h;
}
