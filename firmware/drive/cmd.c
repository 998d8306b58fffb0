/*
 * cmd.c - drive-board bytes of a solution (drive_cmd.h).
 */
#include <stddef.h>

#include "drive/drive_cmd.h"
#include "drive_internal.h"

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

/* Front-wheel counts of a segment with front/rear length ratio @p sec (Q4.28, 0 for a
 * straight): round(s counts_per_m sqrt(1 + (L k)^2)). */
static drive_status_t front_counts(const drive_segment_t *g, const drive_board_t *b, int32_t sec,
                                   uint8_t *out)
{
    int32_t counts = fx_mul_q16(g->length, b->counts_per_m); /* rear-axle counts, Q16 */
    if (sec != 0 && !fx_mul_shift(counts, sec, 28, &counts))
        return DRIVE_ERR_RANGE;
    counts = (counts + (1l << 15)) >> 16;
    if (counts > 255)
        return DRIVE_ERR_RANGE;
    *out = (uint8_t)counts;
    return DRIVE_OK;
}

drive_status_t drive_cmd_build(const drive_solution_t *sol, const drive_board_t *board,
                               fx_q16_t speed_mps, bool reverse, drive_cmd_t *cmd)
{
    if (sol == NULL || board == NULL || cmd == NULL || board->wheelbase < (FX_Q16_ONE / 20) ||
        board->wheelbase > 4 * FX_Q16_ONE || board->counts_per_m <= 0)
        return DRIVE_ERR_PARAM;
    drive_cmd_t c;
    int32_t sec = 0, last_k = 0;
    for (uint8_t i = 0; i < 2u; i++) {
        const drive_segment_t *g = &sol->seg[i];
        /* The arcs of a double arc have opposite curvatures of one magnitude: their angles
         * and front/rear ratios are computed once. */
        if (i == 1 && g->curvature == -last_k && last_k != 0) {
            c.alpha[1] = 0u - c.alpha[0];
        } else {
            c.alpha[i] = drive_steer_angle(g->curvature, board->wheelbase);
            sec = 0;
            if (g->curvature != 0) {
                uint32_t h = fx_hypot(DRIVE_CURV_ONE, fx_mul_q16(g->curvature, board->wheelbase));
                if (h > (uint32_t)INT32_MAX)
                    return DRIVE_ERR_RANGE;
                sec = (int32_t)h; /* sqrt(1 + (L k)^2), Q4.28 */
            }
        }
        last_k = g->curvature;
        drive_status_t st = drive_steer_byte(c.alpha[i], &c.steer[i]);
        if (st == DRIVE_OK)
            st = front_counts(g, board, g->curvature != 0 ? sec : 0, &c.arc[i]);
        if (st != DRIVE_OK)
            return st;
    }
    drive_status_t st = drive_speed_counts(speed_mps, reverse, board, &c.speed);
    if (st != DRIVE_OK)
        return st;
    /* D7: arcs too short for a clean delta-S pulse. A short first arc is dropped (skipped by
     * the board without a pulse); a short second arc is driven but its pulse, if any, is not
     * waited for. */
    bool short0 = c.arc[0] < board->min_pulse_counts, short1 = c.arc[1] < board->min_pulse_counts;
    if (short0)
        c.arc[0] = 0;
    c.pulses = (uint8_t)((short0 ? 0u : 1u) + (short1 ? 0u : 1u));
    *cmd = c;
    return DRIVE_OK;
}
