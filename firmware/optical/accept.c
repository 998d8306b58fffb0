/*
 * accept.c - the dead-reckoning uncertainty that optical_fix() gates every fix with (SPEC O6,
 * docs/optical.md "O6"): how much the approximate pose may be off after a stretch of travel
 * and turning since the last accepted fix. optical/optical.h documents the calls. The
 * arithmetic is 16-bit with 16 x 16 products (2^-8 m and 2^-16 turn, bounds rounded up; the
 * configuration's ranges in optical.h keep every product within 32 bits).
 */
#include <stdint.h>

#include "optical/optical.h"

/* ceil(a b / 2^16), a and b below 2^16 */
static uint16_t mulc(uint16_t a, uint16_t b)
{
    uint32_t p = (uint32_t)a * b;
    return (uint16_t)((p + 0xFFFFu) >> 16);
}

/* ceil(v / 2^s) of a Q16 bound (>= 0) in 2^-(16-s) units, at most 0xFFFF */
static uint16_t up(uint32_t v, uint8_t s)
{
    v = (v + ((1ul << s) - 1u)) >> s;
    return v > 0xFFFFu ? 0xFFFFu : (uint16_t)v;
}

void optical_unc_grow(const optical_config_t *cfg, optical_unc_t *u, fx_q16_t travel,
                      fx_angle_t turn)
{
    /* 2^-8 m and 2^-16 turn, rounded up (bounds stay bounds; nothing grows standing still) */
    uint16_t t8 = up(travel < 0 ? 0u : (uint32_t)travel, 8);
    uint16_t tr = up(turn >= 0x80000000ul ? 0x80000000ul : turn, 16);
    uint32_t h = up(u->heading, 16), hmax = cfg->turn_max >> 16;
    /* heading: the gyro's scale on the turn, its drift per metre travelled (per metre in
     * 2^-24 turn, rounded up: t8 of them make 2^-32 turn) */
    h += (uint32_t)mulc(tr, (uint16_t)cfg->unc_turn) + mulc(t8, up(cfg->unc_head_per_m, 8));
    h = h > hmax ? hmax : h;
    /* position: the odometer's scale on the travel, and the heading's error over it, h 2 pi /
     * 2^16 t8 in 2^-8 m, with 2 pi / 2^16 <= 1609 / 2^24 (0.02 % high): (h 1609 / 2^8) t8 /
     * 2^16, each step rounded up; from 57 degrees on (h 1609 / 2^8 would pass 16 bits) 2 t8,
     * what any heading error can do (h <= 2^15: h 1609 within 32 bits) */
    uint32_t p = (uint32_t)up((uint32_t)u->pos, 8) + mulc(t8, (uint16_t)cfg->unc_per_m) +
                 (h > 10400u ? 2ul * t8 : mulc(t8, up(h * 1609u, 8)));
    uint32_t pmax = (uint32_t)cfg->jump_max >> 8;
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
