/*
 * reflectors3.c - the three-reflector timing mode (optical/reflectors3.h, SPEC O12, seed 004).
 */
#include "optical/reflectors3.h"

#include <stddef.h>

/* An assignment fits when the fix reproduces every angle within this (0.01 degree); a wrong
 * one puts the vehicle on the other arc of a circle, off by about 180 degrees somewhere. */
#define FIT_TOL 119305ul

bool optical_r3_inside(const optical_xy_t *v, uint8_t n, const optical_xy_t *p)
{
    bool in = false;
    for (uint8_t i = 0, j = (uint8_t)(n - 1u); i < n; j = i++) {
        const optical_xy_t *a = &v[i], *b = &v[j];
        if ((a->y > p->y) == (b->y > p->y))
            continue;
        /* p.x < a.x + (p.y - a.y) (b.x - a.x) / (b.y - a.y), multiplied out by b.y - a.y. */
        int64_t l = (int64_t)(p->x - a->x) * (b->y - a->y);
        int64_t r = (int64_t)(p->y - a->y) * (b->x - a->x);
        if (b->y > a->y ? l < r : l > r)
            in = !in;
    }
    return in;
}

void optical_r3_goal(const optical_pose_t *pose, const optical_xy_t *goal, uint32_t *dist,
                     fx_angle_t *turn)
{
    int32_t dx = goal->x - pose->x, dy = goal->y - pose->y;
    *dist = fx_hypot(dx, dy);
    *turn = (dx | dy) ? fx_atan2(dy, dx) - pose->heading : 0u;
}

static bool in_range(const optical_xy_t *p)
{
    return p->x > -OPTICAL_COORD_LIMIT && p->x < OPTICAL_COORD_LIMIT &&
           p->y > -OPTICAL_COORD_LIMIT && p->y < OPTICAL_COORD_LIMIT;
}

static int8_t done(optical_r3_t *out, int8_t status)
{
    out->status = (uint8_t)status;
    return status;
}

int8_t optical_r3_fix(const optical_xy_t refl[3], uint32_t click, const uint32_t *t, uint8_t n,
                      uint32_t click_next, const optical_r3_config_t *cfg,
                      const optical_xy_t *approx, optical_r3_t *out)
{
    out->n_cand = 0;
    out->quality = UINT32_MAX;
    out->first = 0;
    out->pose.x = 0;
    out->pose.y = 0;
    out->pose.heading = 0;
    if (n != 3)
        return done(out, OPTICAL_R3_E_COUNT);
    uint32_t period = click_next - click;
    uint32_t dev = period > cfg->period ? period - cfg->period : cfg->period - period;
    if (period == 0 || period >= 0x80000000ul || dev > cfg->period_tol)
        return done(out, OPTICAL_R3_E_PERIOD);
    fx_angle_t th[3];
    uint32_t prev = 0;
    for (uint8_t i = 0; i < 3; i++) {
        uint32_t rel = t[i] - click;
        int32_t q;
        if (rel <= prev || rel >= period || !fx_div_shift((int32_t)rel, (int32_t)period, 31, &q))
            return done(out, OPTICAL_R3_E_ORDER);
        th[i] = (fx_angle_t)q << 1;
        prev = rel;
    }
    for (uint8_t i = 0; i < 3; i++)
        if (!in_range(&refl[i]))
            return done(out, OPTICAL_R3_E_ARG);
    if (cfg->field != NULL) {
        if (cfg->n_field < 3 || cfg->n_field > OPTICAL_R3_MAX_FIELD)
            return done(out, OPTICAL_R3_E_ARG);
        for (uint8_t i = 0; i < cfg->n_field; i++)
            if (!in_range(&cfg->field[i]))
                return done(out, OPTICAL_R3_E_ARG);
    }

    static const uint8_t perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                       {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    optical_pose_t pose[OPTICAL_R3_MAX_CAND];
    uint32_t qual[OPTICAL_R3_MAX_CAND];
    bool singular = false;
    for (uint8_t a = 0; a < 6; a++) {
        optical_xy_t b[3] = {refl[perm[a][0]], refl[perm[a][1]], refl[perm[a][2]]};
        optical_tri_t tri;
        int8_t st = optical_triangulate(b, th, cfg->quality_max, &tri);
        if (st == OPTICAL_E_SINGULAR)
            singular = true; /* (inconsistent: that assignment does not fit) */
        if (st != OPTICAL_OK)
            continue;
        const optical_xy_t p = {tri.pose.x, tri.pose.y};
        fx_angle_t h0 = fx_atan2(b[0].y - p.y, b[0].x - p.x) - th[0];
        bool fits = true;
        for (uint8_t i = 1; i < 3 && fits; i++) {
            fx_angle_t res = fx_atan2(b[i].y - p.y, b[i].x - p.x) - th[i] - h0;
            fits = (int32_t)res <= (int32_t)FIT_TOL && (int32_t)res >= -(int32_t)FIT_TOL;
        }
        if (!fits || (cfg->field != NULL && !optical_r3_inside(cfg->field, cfg->n_field, &p)))
            continue;
        uint8_t c = out->n_cand++;
        pose[c].x = p.x;
        pose[c].y = p.y;
        pose[c].heading = h0; /* from the first reflection after the click */
        qual[c] = tri.quality;
        out->cand[c] = p;
        out->cand_first[c] = perm[a][0];
    }
    if (out->n_cand == 0)
        return done(out, singular ? OPTICAL_E_SINGULAR : OPTICAL_R3_E_NONE);
    uint8_t best = 0;
    if (out->n_cand > 1) {
        if (approx == NULL)
            return done(out, OPTICAL_R3_E_AMBIGUOUS);
        uint32_t bd = UINT32_MAX;
        for (uint8_t c = 0; c < out->n_cand; c++) {
            uint32_t d = fx_hypot(out->cand[c].x - approx->x, out->cand[c].y - approx->y);
            if (d < bd) {
                bd = d;
                best = c;
            }
        }
    }
    out->pose = pose[best];
    out->quality = qual[best];
    out->first = out->cand_first[best];
    return done(out, OPTICAL_R3_OK);
}
