/*
 * accept.c - the dead-reckoning uncertainty that optical_fix() gates every fix with (SPEC O6,
 * docs/optical.md "O6"): how much the approximate pose may be off after a stretch of travel
 * and turning since the last accepted fix. optical/optical.h documents the calls. The
 * arithmetic is 16-bit with 16 x 16 products (2^-8 m and 2^-16 turn, bounds rounded up; the
 * configuration's ranges in optical.h keep every product within 32 bits).
 */
#include <stdint.h>

#include "optical/optical.h"

void optical_unc_grow(const optical_config_t *cfg, optical_unc_t *u, fx_q16_t travel,
                      fx_angle_t turn)
{
    /* 2^-8 m and 2^-16 turn, one unit more than their floor (bounds: rounded up) */
    uint16_t t8 = travel <= 0 ? 0u : travel >= 0xFFFF00l ? 0xFFFFu : (uint16_t)(travel >> 8) + 1u;
    uint16_t tr = (uint16_t)((turn >= 0x80000000ul ? 0x80000000ul : turn) >> 16) + 1u;
    uint16_t h = (uint16_t)(u->heading >> 16) + 1u, hmax = (uint16_t)(cfg->turn_max >> 16);
    /* heading: the gyro's scale on the turn, its drift per metre travelled (per metre in
     * 2^-24 turn, rounded up: t8 of them make 2^-32 turn); each floored term rounded up */
    uint32_t dh = (((uint32_t)tr * (uint16_t)cfg->unc_turn) >> 16) +
                  (((uint32_t)t8 * (uint16_t)((cfg->unc_head_per_m >> 8) + 1u)) >> 16) + 2u;
    h = h >= hmax || dh >= (uint32_t)(hmax - h) ? hmax : (uint16_t)(h + dh);
    /* position: the odometer's scale on the travel, and the heading's error over it, h 2 pi /
     * 2^16 t8 in 2^-8 m (2 pi / 2^16 = 201 / 2^21 within 0.03 %, low: within 0.02 units at
     * the cap of 0.5 m); three floors, each rounded up */
    uint32_t dp = (((uint32_t)t8 * (uint16_t)cfg->unc_per_m) >> 16) +
                  ((((uint32_t)h * t8) >> 10) * 201u >> 11) + 3u;
    uint32_t p = ((uint32_t)u->pos >> 8) + 1u + dp, pmax = (uint32_t)cfg->jump_max >> 8;
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
