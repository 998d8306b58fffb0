/*
 * pursuit.c - seed 002's goal-point pursuit and its future work (see pursuit.h,
 * docs/pursuit.md).
 */
#include "pursuit/pursuit.h"

#include <stddef.h>

/* Regulation: the command must have stood this long before an interval is measured (the
 * positioning system's lag and the drive's response), and the interval must last this long. */
#define REG_SETTLE_MS   1000u
#define REG_INTERVAL_MS 100u
#define CAL_MIN         (FX_Q16_ONE / 4)
#define CAL_MAX         (4 * FX_Q16_ONE)
#define MIN_SEGMENT     (FX_Q16_ONE >> 8)

bool pursuit_config_ok(const pursuit_config_t *c)
{
    return c->max_speed > 0 && c->max_speed <= 65l * FX_Q16_ONE && c->speed > 0 &&
           c->speed <= c->max_speed && c->k > 0 && c->k <= 8 * FX_Q16_ONE && c->activation_ms > 0 &&
           c->threshold > 0 && c->threshold <= FX_Q16_ONE && c->max_steer > 0 &&
           c->max_steer < FX_ANGLE_QUARTER &&
           (c->slow_after_ms == 0 || c->stop_after_ms > c->slow_after_ms) && c->pair_sep >= 0 &&
           c->pair_tol >= 0;
}

static void point(const pursuit_t *p, uint16_t i, fx_q16_t *x, fx_q16_t *y)
{
    if (i == 0) {
        *x = p->x0;
        *y = p->y0;
    } else {
        *x = p->path[i - 1u].pose.x;
        *y = p->path[i - 1u].pose.y;
    }
}

/* Make point @p i the goal: the segment from point i - 1. */
static void set_goal(pursuit_t *p, uint16_t i)
{
    fx_q16_t gx, gy;
    point(p, (uint16_t)(i - 1u), &p->lx, &p->ly);
    point(p, i, &gx, &gy);
    p->goal = i;
    p->len = (fx_q16_t)fx_hypot(gx - p->lx, gy - p->ly);
    fx_sincos(fx_atan2(gy - p->ly, gx - p->lx), &p->uy, &p->ux);
}

bool pursuit_init(pursuit_t *p, const pursuit_config_t *cfg, fx_q16_t x0, fx_q16_t y0,
                  const drive_path_point_t *path, uint16_t n_path)
{
    if (!pursuit_config_ok(cfg) || path == NULL || n_path == 0 || n_path == UINT16_MAX)
        return false;
    *p = (pursuit_t){0};
    p->cfg = *cfg;
    p->x0 = x0;
    p->y0 = y0;
    p->path = path;
    p->n = (uint16_t)(n_path + 1u);
    for (uint16_t i = 1; i < p->n; i++) {
        set_goal(p, i);
        if (p->len < MIN_SEGMENT)
            return false;
    }
    set_goal(p, 1);
    p->factor = FX_Q16_ONE;
    p->cal = FX_Q16_ONE;
    return true;
}

/* Along the segment from its start (xdist) and across it (signed), of (x, y). */
static void project(const pursuit_t *p, fx_q16_t x, fx_q16_t y, fx_q16_t *along, fx_q16_t *across)
{
    int32_t rx = x - p->lx, ry = y - p->ly;
    *along = fx_mul_q30(rx, p->ux) + fx_mul_q30(ry, p->uy);
    *across = fx_mul_q30(ry, p->ux) - fx_mul_q30(rx, p->uy);
}

/* The speed command for the speed asked for, the recovery factor and the calibration. */
static int8_t counts_for(const pursuit_t *p)
{
    if (p->done || p->factor == 0)
        return 0;
    fx_q16_t target = fx_mul_q16(p->cfg.speed, p->factor);
    fx_q16_t unit = fx_mul_q16(p->cfg.max_speed, p->cal); /* true speed at 127 counts */
    int32_t c = 0;
    if (unit <= 0 || !fx_div32(target * PURSUIT_SPEED_COUNTS, unit, &c) || c > PURSUIT_SPEED_COUNTS)
        c = PURSUIT_SPEED_COUNTS;
    return (int8_t)(c < 0 ? 0 : c);
}

static void set_speed(pursuit_t *p, uint32_t now, pursuit_out_t *out)
{
    int8_t c = counts_for(p);
    if (c == p->counts)
        return;
    p->counts = c;
    p->counts_since = now;
    out->actions |= PURSUIT_ACT_SPEED;
    out->speed = c;
}

static void steer(fx_angle_t a, pursuit_out_t *out)
{
    out->actions |= PURSUIT_ACT_STEER;
    out->steer = a;
}

void pursuit_start(pursuit_t *p, fx_angle_t heading, uint32_t now_ms, pursuit_out_t *out)
{
    out->actions = 0;
    p->started = true;
    p->px = p->x0;
    p->py = p->y0;
    p->heading = heading;
    p->last_update = now_ms;
    p->last_pos_ms = now_ms;
    p->counts = -1;
    set_speed(p, now_ms, out);
    steer(0, out);
}

/*
 * Regulation: the true speed per count from the travel @p dist (m Q16) since the previous
 * accepted position, when the command stood still since REG_SETTLE_MS before it.
 */
static void regulate(pursuit_t *p, fx_q16_t dist, uint32_t t_ms, pursuit_out_t *out)
{
    uint32_t dt = t_ms - p->last_pos_ms;
    if (!p->cfg.regulate || p->done || p->counts <= 0 || dt < REG_INTERVAL_MS || dt > 60000u ||
        (int32_t)(p->last_pos_ms - p->counts_since) < (int32_t)REG_SETTLE_MS)
        return;
    int32_t v = 0, nominal = 0, f = 0; /* m/s Q16, m/s Q16, Q16 */
    if (!fx_mul_shift(dist, 1000, 0, &v) || !fx_div32(v, (int32_t)dt, &v) ||
        !fx_div32(p->cfg.max_speed * p->counts, PURSUIT_SPEED_COUNTS, &nominal) ||
        !fx_div_shift(v, nominal, 16, &f))
        return;
    f = f < CAL_MIN ? CAL_MIN : f > CAL_MAX ? CAL_MAX : f;
    p->cal += (f - p->cal) / 2;
    p->st.regulations++;
    set_speed(p, t_ms, out);
}

void pursuit_position(pursuit_t *p, fx_q16_t x, fx_q16_t y, const fx_angle_t *heading,
                      uint32_t t_ms, pursuit_record_t *rec, pursuit_out_t *out)
{
    out->actions = 0;
    pursuit_alive(p, t_ms);
    /* 1. heading */
    fx_q16_t dist = (fx_q16_t)fx_hypot(x - p->px, y - p->py);
    if (heading)
        p->heading = *heading;
    else if (dist > 0)
        p->heading = fx_atan2(y - p->py, x - p->px);
    regulate(p, dist, t_ms, out);
    p->last_pos_ms = t_ms;
    p->px = x;
    p->py = y;
    /* 2. along and across the segment: the seed's error record */
    fx_q16_t along, across;
    project(p, x, y, &along, &across);
    fx_q16_t err = across < 0 ? -across : across;
    rec->x = x;
    rec->y = y;
    rec->heading = p->heading;
    rec->err = err;
    rec->xdist = along;
    rec->segment = p->goal;
    p->st.updates++;
    p->st.err_sum += (uint64_t)err;
    if (err > p->st.err_max)
        p->st.err_max = err;
    /* 3. the end */
    if (!p->done && p->goal == p->n - 1u && along >= p->len) {
        p->done = true;
        p->holding = false;
        set_speed(p, t_ms, out);
        steer(0, out);
        out->actions |= PURSUIT_ACT_DONE;
    }
    /* 4. the next goal point(s) */
    while (!p->done && p->goal < p->n - 1u && along >= fx_mul_q16(p->len, p->cfg.threshold)) {
        set_goal(p, (uint16_t)(p->goal + 1u));
        p->st.goals++;
        project(p, x, y, &along, &across);
    }
    rec->goal = p->goal;
    /* 5. the heading error and the correction */
    fx_q16_t gx, gy;
    point(p, p->goal, &gx, &gy);
    int32_t dphi = (int32_t)(fx_atan2(gy - y, gx - x) - p->heading);
    rec->dphi = (fx_angle_t)dphi;
    uint32_t adphi = dphi < 0 ? 0u - (uint32_t)dphi : (uint32_t)dphi;
    if (p->done || p->holding || adphi < PURSUIT_ON_COURSE)
        return;
    int32_t alpha = fx_mul_q16(dphi, p->cfg.k); /* saturates beyond a half turn */
    int32_t lim = (int32_t)p->cfg.max_steer;
    alpha = alpha > lim ? lim : alpha < -lim ? -lim : alpha;
    steer((fx_angle_t)alpha, out);
    p->holding = true;
    p->hold_end = t_ms + p->cfg.activation_ms;
    p->st.corrections++;
}

void pursuit_alive(pursuit_t *p, uint32_t t_ms)
{
    p->last_update = t_ms;
}

void pursuit_tick(pursuit_t *p, uint32_t now_ms, pursuit_out_t *out)
{
    out->actions = 0;
    if (!p->started || p->done)
        return;
    if (p->holding && (int32_t)(now_ms - p->hold_end) >= 0) {
        p->holding = false;
        steer(0, out);
    }
    if (p->cfg.slow_after_ms == 0)
        return;
    uint32_t age = now_ms - p->last_update;
    if (age >= 0x80000000ul)
        age = 0; /* an update stamped after now */
    fx_q16_t f = FX_Q16_ONE;
    if (age >= p->cfg.stop_after_ms) {
        f = 0;
    } else if (age > p->cfg.slow_after_ms) {
        int32_t q = 0;
        (void)fx_div_shift((int32_t)(p->cfg.stop_after_ms - age),
                           (int32_t)(p->cfg.stop_after_ms - p->cfg.slow_after_ms), 16, &q);
        f = q;
    }
    if (f == p->factor)
        return;
    if (p->factor == FX_Q16_ONE)
        p->st.slowdowns++;
    if (f == 0)
        p->st.stops++;
    if (f == FX_Q16_ONE)
        p->st.resumes++;
    p->factor = f;
    set_speed(p, now_ms, out);
}

bool pursuit_next_tick(const pursuit_t *p, uint32_t now_ms, uint32_t *at_ms)
{
    if (!p->started || p->done)
        return false;
    bool any = false;
    uint32_t at = 0;
    if (p->holding) {
        at = p->hold_end;
        any = true;
    }
    if (p->cfg.slow_after_ms == 0)
        goto out;
    uint32_t age = now_ms - p->last_update, next;
    if (age >= 0x80000000ul || age <= p->cfg.slow_after_ms) /* (stamped after now: age 0) */
        next = p->factor != FX_Q16_ONE ? now_ms             /* the resume is due */
                                       : p->last_update + p->cfg.slow_after_ms + 1u;
    else if (age < p->cfg.stop_after_ms)
        next = now_ms + 1u; /* slowing down: the factor changes by the millisecond */
    else if (p->factor != 0)
        next = now_ms; /* the stop is due */
    else
        goto out; /* stopped: only a position moves it on */
    if (!any || (int32_t)(next - at) < 0)
        at = next;
    any = true;
out:
    if (any)
        *at_ms = at;
    return any;
}

bool pursuit_pair(pursuit_t *p, fx_q16_t x1, fx_q16_t y1, fx_q16_t x2, fx_q16_t y2,
                  fx_angle_t *heading)
{
    int32_t d = (int32_t)fx_hypot(x1 - x2, y1 - y2) - p->cfg.pair_sep;
    if ((d < 0 ? -d : d) > p->cfg.pair_tol) {
        p->st.pair_rejects++;
        return false;
    }
    *heading = fx_atan2(y1 - y2, x1 - x2) - p->cfg.pair_angle;
    return true;
}

bool pursuit_done(const pursuit_t *p)
{
    return p->done;
}
