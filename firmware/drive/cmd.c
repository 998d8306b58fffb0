/*
 * cmd.c - drive-board bytes of a solution (drive_cmd.h).
 */
#include <stddef.h>

#include "drive/drive_cmd.h"
#include "drive_math.h"

/* 89.6 degrees as a binary angle: the steering byte stays within 1..255 below it. */
#define STEER_LIMIT 1069547520l /* 127.5 * 2^23 */

fx_angle_t drive_steer_angle(int32_t curvature, fx_q16_t wheelbase)
{
    if (curvature == 0)
        return 0;
    /* L * curvature in Q4.28 (saturating: beyond 8 the angle is over 82.9 degrees anyway,
     * and fx_atan_ratio of the saturated value is still the right side of any limit). */
    return fx_atan_ratio(fx_mul_q16(curvature, wheelbase), DRIVE_CURV_ONE);
}

drive_status_t drive_steer_byte(fx_angle_t alpha, uint8_t *out)
{
    int32_t a = (int32_t)alpha;
    if (a >= STEER_LIMIT || a <= -STEER_LIMIT)
        return DRIVE_ERR_RANGE;
    /* round(a / 2^23): one count is pi / 256 = 2^23 binary-angle LSB. */
    int32_t counts = a >= 0 ? (a + (1l << 22)) >> 23 : -((-a + (1l << 22)) >> 23);
    *out = (uint8_t)(128 - counts);
    return DRIVE_OK;
}

uint8_t drive_dac_angle_byte(fx_angle_t alpha, uint8_t center)
{
    int32_t span = 255 - (int32_t)center, counts = 0;
    (void)fx_mul_shift((int32_t)alpha, span, 30, &counts); /* alpha / quarter turn * span */
    int32_t v = (int32_t)center - counts;
    return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
}

uint8_t drive_dac_speed_byte(int8_t speed)
{
    return (uint8_t)(128 + speed);
}

drive_status_t drive_speed_counts(fx_q16_t speed_mps, bool reverse, const drive_board_t *board,
                                  int8_t *out)
{
    int32_t counts;
    if (board == NULL || board->speed_lsb <= 0 || speed_mps < 0)
        return DRIVE_ERR_PARAM;
    if (!fx_div_shift(speed_mps, board->speed_lsb, 0, &counts) || counts > 127)
        return DRIVE_ERR_RANGE;
    *out = (int8_t)(reverse ? -counts : counts);
    return DRIVE_OK;
}

drive_status_t drive_cmd_build(const drive_solution_t *sol, const drive_board_t *board,
                               fx_q16_t speed_mps, bool reverse, drive_cmd_t *cmd)
{
    if (sol == NULL || board == NULL || cmd == NULL || board->wheelbase < (FX_Q16_ONE / 20) ||
        board->wheelbase > 4 * FX_Q16_ONE || board->counts_per_m <= 0)
        return DRIVE_ERR_PARAM;
    drive_cmd_t c;
    int32_t k_abs = 0, sec = 0;
    fx_angle_t alpha = 0;
    for (uint8_t i = 0; i < 2u; i++) {
        const drive_segment_t *g = &sol->seg[i];
        /* Steering alpha = atan(L k) and the front/rear length ratio sec = sqrt(1 + (L k)^2)
         * (Q4.28) of |k|, the sign applied after (both are exactly odd or even): the two arcs
         * of a double arc have one magnitude and need them once. */
        uint32_t a = drive_abs32(g->curvature);
        if (a == 0) {
            alpha = 0;
            sec = 0; /* a straight: the counts as they are */
        } else if ((int32_t)a != k_abs) {
            int32_t lk = fx_mul_q16((int32_t)a, board->wheelbase);
            alpha = fx_atan_ratio(lk, DRIVE_CURV_ONE);
            uint32_t h = fx_hypot(DRIVE_CURV_ONE, lk);
            if (h > (uint32_t)INT32_MAX)
                return DRIVE_ERR_RANGE;
            sec = (int32_t)h;
        }
        k_abs = (int32_t)a;
        c.alpha[i] = g->curvature < 0 ? 0u - alpha : alpha;
        if (drive_steer_byte(c.alpha[i], &c.steer[i]) != DRIVE_OK)
            return DRIVE_ERR_RANGE;
        /* Front-wheel counts: round(s counts_per_m sqrt(1 + (L k)^2)), at most 255. */
        int32_t counts = fx_mul_q16(g->length, board->counts_per_m); /* rear axle, Q16 */
        if (sec != 0 && !fx_mul_shift(counts, sec, 28, &counts))
            return DRIVE_ERR_RANGE;
        if (counts >= (255l << 16) + (1l << 15))
            return DRIVE_ERR_RANGE;
        c.arc[i] = (uint8_t)((uint32_t)(counts + (1l << 15)) >> 16);
    }
    drive_status_t st = drive_speed_counts(speed_mps, reverse, board, &c.speed);
    if (st != DRIVE_OK)
        return st;
    /* D7: arcs too short for a clean delta-S pulse. A short first arc is dropped (skipped by
     * the board without a pulse); a short second arc is driven but its pulse, if any, is not
     * waited for. */
    c.pulses = 2;
    if (c.arc[0] < board->min_pulse_counts) {
        c.arc[0] = 0;
        c.pulses--;
    }
    if (c.arc[1] < board->min_pulse_counts)
        c.pulses--;
    *cmd = c;
    return DRIVE_OK;
}
