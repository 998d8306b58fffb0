/*
 * path.c - path preparation and secondary points (drive_path.h).
 */
#include <stddef.h>

#include "drive/drive_path.h"

/* The pose at @p t (metres Q16, 0 <= t <= the leg's length) along a leg's solution. */
static drive_pose_t along(const drive_pose_t *from, const drive_solution_t *sol, fx_q16_t t,
                          bool reverse)
{
    fx_q16_t s0 = sol->seg[0].length;
    if (t <= s0)
        return drive_pose_advance(from, sol->seg[0].curvature, t, reverse);
    drive_pose_t mid = drive_pose_advance(from, sol->seg[0].curvature, s0, reverse);
    return drive_pose_advance(&mid, sol->seg[1].curvature, t - s0, reverse);
}

static const drive_pose_t *leg_start(const drive_path_t *path, uint8_t leg)
{
    return leg == 0 ? &path->start : &path->pts[leg - 1].pose;
}

drive_status_t drive_path_leg(drive_path_t *path, uint8_t leg, const drive_solution_t **sol)
{
    if (path == NULL || leg >= path->n)
        return DRIVE_ERR_PARAM;
    if (path->cache_leg != (int16_t)leg) {
        drive_status_t st =
            drive_solve(leg_start(path, leg), &path->pts[leg].pose, path->cfg.nominal_radius,
                        path->cfg.reverse, &path->cache, NULL);
        if (st != DRIVE_OK) {
            path->cache_leg = -1;
            return st;
        }
        path->cache_leg = (int16_t)leg;
    }
    *sol = &path->cache;
    return DRIVE_OK;
}

/* Secondary point @p sub of leg @p leg whose nominal solution is @p sol. */
static drive_pose_t secondary(const drive_path_t *path, uint8_t leg, uint8_t sub,
                              const drive_solution_t *sol)
{
    uint8_t nsub = path->pts[leg].nsub;
    if (sub >= nsub)
        return path->pts[leg].pose;
    int32_t frac = 0; /* sub / nsub, Q30 */
    (void)fx_div_shift(sub, nsub, 30, &frac);
    fx_q16_t t = fx_mul_q30(sol->seg[0].length + sol->seg[1].length, frac);
    return along(leg_start(path, leg), sol, t, path->cfg.reverse);
}

drive_status_t drive_path_target(drive_path_t *path, drive_path_cursor_t cur, drive_pose_t *pose,
                                 fx_q16_t *speed)
{
    if (path == NULL || !path->ready || cur.leg >= path->n || cur.sub == 0 ||
        cur.sub > path->pts[cur.leg].nsub)
        return DRIVE_ERR_PARAM;
    const drive_solution_t *sol;
    drive_status_t st = drive_path_leg(path, cur.leg, &sol);
    if (st != DRIVE_OK)
        return st;
    *pose = secondary(path, cur.leg, cur.sub, sol);
    *speed = path->pts[cur.leg].speed;
    return DRIVE_OK;
}

drive_path_cursor_t drive_path_first(const drive_path_t *path)
{
    (void)path;
    drive_path_cursor_t c = {0, 1};
    return c;
}

bool drive_path_is_last(const drive_path_t *path, drive_path_cursor_t cur)
{
    return cur.leg + 1u >= path->n && cur.sub >= path->pts[cur.leg].nsub;
}

drive_path_cursor_t drive_path_next(const drive_path_t *path, drive_path_cursor_t cur)
{
    if (drive_path_is_last(path, cur))
        return cur;
    if (cur.sub < path->pts[cur.leg].nsub) {
        cur.sub++;
    } else {
        cur.leg++;
        cur.sub = 1;
    }
    return cur;
}

static drive_status_t reject(drive_path_t *path, uint8_t leg, uint8_t sub, drive_status_t why)
{
    path->ready = false;
    path->bad_leg = leg;
    path->bad_sub = sub;
    path->bad_why = why;
    return why;
}

drive_status_t drive_path_prepare(drive_path_t *path, const drive_pose_t *start,
                                  drive_path_point_t *pts, uint8_t n,
                                  const drive_path_config_t *cfg, const drive_board_t *board)
{
    if (path == NULL)
        return DRIVE_ERR_PARAM;
    path->pts = pts;
    path->n = n;
    path->cache_leg = -1;
    path->board = board;
    if (start == NULL || pts == NULL || cfg == NULL || board == NULL)
        return reject(path, 0, 0, DRIVE_ERR_PARAM);
    path->start = *start;
    path->cfg = *cfg;
    if (n == 0 || n > 254u || cfg->nominal_radius < board->min_radius ||
        cfg->nominal_radius > DRIVE_MIN_RADIUS_MAX || board->min_radius < DRIVE_MIN_RADIUS_MIN ||
        cfg->spacing < FX_Q16_ONE / 20 || cfg->spacing > 8 * FX_Q16_ONE)
        return reject(path, 0, 0, DRIVE_ERR_PARAM);

    for (uint8_t leg = 0; leg < n; leg++) {
        int8_t counts;
        drive_status_t st = drive_speed_counts(pts[leg].speed, cfg->reverse, board, &counts);
        if (st == DRIVE_OK && counts == 0)
            st = DRIVE_ERR_PARAM; /* a speed that rounds to a stop */
        if (st != DRIVE_OK)
            return reject(path, leg, 0, st);
        path->cache_leg = -1;
        const drive_solution_t *sol;
        st = drive_path_leg(path, leg, &sol);
        if (st != DRIVE_OK)
            return reject(path, leg, 0, st);
        int32_t len = sol->seg[0].length + sol->seg[1].length, nsub = 0;
        (void)fx_div_shift(len, cfg->spacing, 0, &nsub);
        if ((int64_t)nsub * cfg->spacing < len)
            nsub++;
        if (nsub < 1)
            nsub = 1;
        if (nsub > 255)
            return reject(path, leg, 0, DRIVE_ERR_PATH);
        pts[leg].nsub = (uint8_t)nsub;
        /* Every piece between secondary points, as the vehicle will drive it. */
        drive_pose_t a = *leg_start(path, leg);
        for (uint8_t sub = 1; sub <= (uint8_t)nsub; sub++) {
            drive_pose_t b = secondary(path, leg, sub, sol);
            drive_solution_t piece;
            drive_cmd_t cmd;
            st = drive_solve(&a, &b, board->min_radius, cfg->reverse, &piece, NULL);
            if (st == DRIVE_OK)
                st = drive_cmd_build(&piece, board, pts[leg].speed, cfg->reverse, &cmd);
            if (st != DRIVE_OK)
                return reject(path, leg, sub, st);
            a = b;
        }
    }
    path->ready = true;
    path->bad_why = DRIVE_OK;
    return DRIVE_OK;
}
