/*
 * path.c - path preparation, secondary points and the cursor (drive_path.h).
 */
#include <stddef.h>

#include "drive/drive_path.h"

/* The start of leg @p leg: the initial vector or the previous primary point. */
static const drive_pose_t *leg_start(const drive_path_t *path, uint8_t leg)
{
    return leg == 0 ? &path->start : &path->pts[leg - 1].pose;
}

drive_status_t drive_path_leg(drive_path_t *path, uint8_t leg, const drive_leg_t **out)
{
    if (path == NULL || leg >= path->n)
        return DRIVE_ERR_PARAM;
    if (path->cache_leg != (int16_t)leg) {
        path->cache_leg = -1;
        drive_status_t st =
            drive_leg_solve(leg_start(path, leg), &path->pts[leg].pose, path->cfg.nominal_radius,
                            path->cfg.reverse, &path->cache);
        if (st != DRIVE_OK)
            return st;
        path->cache_leg = (int16_t)leg;
    }
    *out = &path->cache;
    return DRIVE_OK;
}

/* Secondary points on the double arc @p sol: ceil(length / spacing), at least 1 (lengths and
 * spacing > 0, their sums < 2^31). */
static uint32_t points_on(const drive_solution_t *sol, fx_q16_t spacing)
{
    uint32_t len = (uint32_t)(sol->seg[0].length + sol->seg[1].length);
    uint32_t n = (len + (uint32_t)spacing - 1u) / (uint32_t)spacing;
    return n ? n : 1u;
}

/* Secondary point @p sub of the leg from @p from to @p pt (whose leg is cached) into *out:
 * equally spaced along each double arc of the leg, the inserted pose of a split leg at the
 * end of the first, the primary point itself for sub == nsub. */
static void secondary(const drive_path_t *path, const drive_pose_t *from,
                      const drive_path_point_t *pt, uint8_t sub, drive_pose_t *out)
{
    const drive_leg_t *leg = &path->cache;
    if (sub >= pt->nsub) {
        *out = pt->pose;
        return;
    }
    const drive_solution_t *sol = &leg->sol[0];
    uint8_t n = pt->nsub;
    if (leg->parts == 2) {
        uint8_t n0 = (uint8_t)points_on(sol, path->cfg.spacing);
        if (sub >= n0) { /* on the second double arc, from the inserted pose */
            from = &leg->via;
            sol = &leg->sol[1];
            sub -= n0;
            n -= n0;
        } else {
            n = n0;
        }
    }
    const drive_segment_t *g = sol->seg;
    int32_t frac = 0; /* sub / n, Q30 */
    (void)fx_div_shift(sub, n, 30, &frac);
    fx_q16_t t = fx_mul_q30(g[0].length + g[1].length, frac);
    drive_pose_t p = *from;
    if (t > g->length) { /* past the first segment */
        p = drive_pose_advance(&p, g->curvature, g->length, path->cfg.reverse);
        t -= g->length;
        g++;
    }
    *out = drive_pose_advance(&p, g->curvature, t, path->cfg.reverse);
}

drive_status_t drive_path_target(drive_path_t *path, drive_path_cursor_t cur, drive_pose_t *pose,
                                 fx_q16_t *speed)
{
    const drive_leg_t *leg;
    if (path == NULL || !path->ready || cur.leg >= path->n || cur.sub == 0 ||
        cur.sub > path->pts[cur.leg].nsub)
        return DRIVE_ERR_PARAM;
    drive_status_t st = drive_path_leg(path, cur.leg, &leg);
    if (st != DRIVE_OK)
        return st;
    const drive_path_point_t *pt = &path->pts[cur.leg];
    secondary(path, leg_start(path, cur.leg), pt, cur.sub, pose);
    *speed = pt->speed;
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

    const drive_pose_t *from = &path->start;
    drive_path_point_t *pt = pts;
    for (uint8_t leg = 0; leg < n; leg++, from = &pt->pose, pt++) {
        int8_t counts;
        drive_status_t st = drive_speed_counts(pt->speed, cfg->reverse, board, &counts);
        if (st == DRIVE_OK && counts == 0)
            st = DRIVE_ERR_PARAM; /* a speed that rounds to a stop */
        const drive_leg_t *nominal;
        if (st == DRIVE_OK)
            st = drive_path_leg(path, leg, &nominal);
        if (st != DRIVE_OK)
            return reject(path, leg, 0, st);
        uint32_t nsub = points_on(&nominal->sol[0], cfg->spacing);
        if (nominal->parts == 2)
            nsub += points_on(&nominal->sol[1], cfg->spacing);
        if (nsub > 255u)
            return reject(path, leg, 0, DRIVE_ERR_PATH);
        pt->nsub = (uint8_t)nsub;
        /* Every piece between secondary points, as the vehicle will drive it. */
        drive_pose_t a = *from, b;
        for (uint8_t sub = 1; sub <= pt->nsub; sub++) {
            secondary(path, from, pt, sub, &b);
            drive_solution_t piece;
            drive_cmd_t cmd;
            st = drive_solve(&a, &b, board->min_radius, cfg->reverse, &piece, NULL);
            if (st == DRIVE_OK)
                st = drive_cmd_build(&piece, board, pt->speed, cfg->reverse, &cmd);
            if (st != DRIVE_OK)
                return reject(path, leg, sub, st);
            a = b;
        }
    }
    path->ready = true;
    path->bad_why = DRIVE_OK;
    return DRIVE_OK;
}
