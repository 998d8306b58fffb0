/*
 * gonio.c - photodetector edges from the geometry of a moving vehicle (see gonio.h).
 */
#include "sim/gonio.h"

#include "sim/scenario_keys.h" /* generated: SIM_BEACON_KIND_* */

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

uint16_t sim_gonio_count(const sim_gonio_cfg_t *cfg, double t)
{
    double c = floor(t * cfg->rev_per_s * (double)cfg->counts + 1e-9);
    return (uint16_t)(uint64_t)fmod(c, 65536.0);
}

/* Mirror angle (unwrapped) at t. */
static double mirror_at(const sim_gonio_cfg_t *cfg, double t_index, double t)
{
    return 2.0 * M_PI * cfg->rev_per_s * (t - t_index);
}

/*
 * F(t) = heading(t) + mirror(t) - bearing(t) - offset(t), unwrapped around an estimate:
 * the beam leads the target direction by -offset when F = 0 (mod 2 pi).
 */
typedef struct {
    const sim_gonio_cfg_t *cfg;
    const sim_segment_t *seg;
    double t_index;
    double tx, ty;
    double half; /* half of the apparent width (angle), < 0: a glint of fixed width */
    int flat;    /* a flat strip facing the vehicle (else a post) */
    double side; /* -1 rising edge (beam at centre - half), +1 falling (centre + half) */
} crossing_t;

static double target_half(const crossing_t *c, double px, double py)
{
    if (c->half < 0.0)
        return -c->half;
    double d = hypot(c->tx - px, c->ty - py);
    double r = c->half; /* diameter / 2 */
    if (c->flat)        /* a strip of width 2r facing the vehicle */
        return d > 0.0 ? atan(r / d) : 0.5 * M_PI;
    return d > r ? asin(r / d) : 0.5 * M_PI;
}

/* F at a time without the side's term, and the apparent half width; with their rates. */
typedef struct {
    double base, half;           /* F = base - side half */
    double bearing;              /* the target's direction, rad, (-pi, pi] */
    double base_rate, half_rate; /* dF/dt = base_rate - side half_rate (when asked for) */
} f_parts_t;

/* The vehicle at one instant: its pose, the cosine and sine of its heading and its speed. */
typedef struct {
    double t;
    sim_pose_t p;
    double cth, sth, v;
} vehicle_t;

/* The vehicle on @p seg at @p t; with @p rates the heading's trig and the speed too (else 0). */
static vehicle_t vehicle_at(const sim_segment_t *seg, double t, bool rates)
{
    vehicle_t m = {t, {0.0, 0.0, 0.0}, 0.0, 0.0, 0.0};
    if (!rates) {
        m.p = sim_segment_pose(seg, t);
        return m;
    }
    m.p = sim_segment_pose_trig(seg, t, &m.cth, &m.sth);
    m.v = sim_segment_speed(seg, t);
    return m;
}

/*
 * The parts of F with the vehicle at @p m (the crossing's side aside): heading, mirror and
 * bearing, and the apparent half width; with @p rates (m from vehicle_at() with rates) their
 * rates too, in closed form from the pose and the speed: the heading's, the mirror's, less the
 * bearing's and the half width's as the vehicle moves.
 */
static f_parts_t F_parts(const crossing_t *c, const vehicle_t *m, bool rates)
{
    f_parts_t f;
    sim_pose_t p = m->p;
    double dx = c->tx - p.x, dy = c->ty - p.y;
    double bearing = atan2(dy, dx);
    f.bearing = bearing;
    f.half = target_half(c, p.x, p.y);
    f.base = p.th + mirror_at(c->cfg, c->t_index, m->t) - bearing;
    f.base_rate = f.half_rate = 0.0;
    if (!rates)
        return f;
    double v = m->v;
    double vx = v * m->cth, vy = v * m->sth, r2 = dx * dx + dy * dy;
    double bearing_rate = r2 > 0.0 ? (dy * vx - dx * vy) / r2 : 0.0;
    if (c->half >= 0.0 && r2 > 0.0) {
        double d = sqrt(r2), d_rate = -(dx * vx + dy * vy) / d, r = c->half;
        if (c->flat)
            f.half_rate = -r / (r2 + r * r) * d_rate;
        else if (d > r)
            f.half_rate = -r / (d * sqrt(r2 - r * r)) * d_rate;
    }
    f.base_rate = c->seg->kappa * v + 2.0 * M_PI * c->cfg->rev_per_s - bearing_rate;
    return f;
}

/*
 * The crossing of F through 0 (mod 2 pi) in [t_from, t_to); NAN if none. @p from and @p to are
 * F's parts at t_from (with rates) and at t_to: F grows at about the mirror rate, so when it
 * stays below the next multiple of 2 pi up to t_to there is no crossing to look for.
 */
static double solve(const crossing_t *c, double t_from, double t_to, const f_parts_t *from,
                    const f_parts_t *to)
{
    double w = 2.0 * M_PI * c->cfg->rev_per_s;
    double f0 = from->base - c->side * from->half, df = from->base_rate - c->side * from->half_rate;
    /* Next multiple of 2 pi above f0. */
    double target = ceil(f0 / (2.0 * M_PI)) * 2.0 * M_PI;
    if (to->base - c->side * to->half < target)
        return NAN; /* not within the window */
    double t = t_from + (target - f0) / (df > 0.0 ? df : w);
    /* Newton with F's rate in closed form. */
    for (int i = 0; i < 8; i++) {
        vehicle_t m = vehicle_at(c->seg, t, true);
        f_parts_t f = F_parts(c, &m, true);
        df = f.base_rate - c->side * f.half_rate;
        if (df <= 0.0)
            df = w;
        double dt = (f.base - c->side * f.half - target) / df;
        t -= dt;
        if (fabs(dt) < 1e-12)
            break;
    }
    if (!(t >= t_from) || !(t < t_to))
        return NAN;
    return t;
}

static int by_time(const void *a, const void *b)
{
    const sim_gonio_event_t *x = a, *y = b;
    if (x->t < y->t)
        return -1;
    if (x->t > y->t)
        return 1;
    if (x->target != y->target)
        return x->target - y->target;
    return x->edge - y->edge; /* a rising edge before its falling edge at the same instant */
}

/*
 * A disk that holds the vehicle at every centre crossing of a pulse with an edge in the window:
 * centred on its position at t_from, with as radius the longest travel from there to an
 * instant up to a half width (pi/2 at most, or a glint's) of mirror turn outside the window.
 * The rear axle's chord is never longer than its travel, which is monotonic in time; the slack
 * covers the rounding of the poses (the arc's formula loses up to about 1e-7 of the travel when
 * nearly straight). Returns the radius, m.
 */
static double window_reach(const sim_gonio_cfg_t *cfg, const sim_world_t *w,
                           const sim_segment_t *seg, double t_from, double t_to)
{
    double half = 0.5 * M_PI;
    for (size_t i = 0; i < w->n_spurious; i++)
        half = fmax(half, 0.5 * w->spurious[i].width);
    double h = half / (2.0 * M_PI * cfg->rev_per_s);
    double d0 = sim_segment_travel(seg, t_from);
    double da = sim_segment_travel(seg, t_from - h), db = sim_segment_travel(seg, t_to + h);
    return fmax(fabs(da - d0), fabs(db - d0)) + 1e-3 + 1e-6 * (fabs(da) + fabs(db));
}

/*
 * How a target at (tx, ty) fares from every point within @p r of (px, py): CLEAR when in
 * range and in sight from all, BLOCKED when from none, else UNSURE. The range's margin covers
 * the rounding of the distances (hypot() in add_edges(), sqrt here).
 */
static sim_sight_t window_sight(const sim_gonio_cfg_t *cfg, const sim_world_t *w, double px,
                                double py, double r, double tx, double ty)
{
    double dx = tx - px, dy = ty - py, d = sqrt(dx * dx + dy * dy), slack = 1e-9 * cfg->max_range;
    if (d - r > cfg->max_range + slack)
        return SIM_SIGHT_BLOCKED;
    sim_sight_t s = sim_world_sight(w, px, py, r, tx, ty);
    if (s == SIM_SIGHT_CLEAR && !(d + r < cfg->max_range - slack))
        return SIM_SIGHT_UNSURE;
    return s;
}

/*
 * Both edges of one target's pulse. Range and line of sight are judged once per pulse, at the
 * beam's crossing of the target's centre (so a pulse is either seen whole or not at all), and
 * the noise never puts a falling edge before its rising edge. @p sight is window_sight()'s for
 * the window: CLEAR or BLOCKED give the judgement without finding the centre crossing.
 */
static size_t add_edges(const sim_gonio_cfg_t *cfg, const sim_world_t *w, const sim_segment_t *seg,
                        double t_index, const vehicle_t *at_from, const vehicle_t *at_to,
                        sim_sight_t sight, sim_rng_t *rng, double tx, double ty, double half,
                        int flat, int16_t target, sim_gonio_event_t *out, size_t n, size_t max)
{
    if (sight == SIM_SIGHT_BLOCKED)
        return n;
    double wrate = 2.0 * M_PI * cfg->rev_per_s;
    double t_from = at_from->t, t_to = at_to->t;
    double te[2];
    crossing_t c0 = {cfg, seg, t_index, tx, ty, half, flat, 0.0};
    f_parts_t from = F_parts(&c0, at_from, true), to = F_parts(&c0, at_to, false);
    /* F unwrapped across the window: the bearing moves by less than half a turn in it */
    to.base += 2.0 * M_PI * round((to.bearing - from.bearing) / (2.0 * M_PI));
    for (int e = 0; e < 2; e++) {
        crossing_t c = {cfg, seg, t_index, tx, ty, half, flat, e == 0 ? -1.0 : 1.0};
        te[e] = solve(&c, t_from, t_to, &from, &to);
        if (isnan(te[e]))
            continue;
        if (sight == SIM_SIGHT_CLEAR) {
            if (cfg->noise_rad > 0.0)
                te[e] += cfg->noise_rad * sim_rng_normal(rng) / wrate;
            continue;
        }
        /* The centre crossing: half the apparent width after a rising edge, before a falling. */
        sim_pose_t p = sim_segment_pose(seg, te[e]);
        double tc = te[e] - c.side * target_half(&c, p.x, p.y) / wrate;
        p = sim_segment_pose(seg, tc);
        if (hypot(tx - p.x, ty - p.y) > cfg->max_range || !sim_world_visible(w, p.x, p.y, tx, ty))
            te[e] = NAN;
        else if (cfg->noise_rad > 0.0)
            te[e] += cfg->noise_rad * sim_rng_normal(rng) / wrate;
    }
    if (!isnan(te[0]) && !isnan(te[1]) && te[1] < te[0] && te[1] > te[0] - 0.5 / cfg->rev_per_s)
        te[1] = te[0]; /* the noise swapped the edges of a glint narrower than itself */
    for (int e = 0; e < 2; e++) {
        double t = te[e];
        if (isnan(t) || t < t_from || t >= t_to || n >= max)
            continue;
        double m = fmod(mirror_at(cfg, t_index, t), 2.0 * M_PI);
        if (m < 0.0)
            m += 2.0 * M_PI;
        out[n].t = t;
        out[n].edge = (uint8_t)e;
        out[n].target = target;
        out[n].mirror = m;
        n++;
    }
    return n;
}

size_t sim_gonio_edges(const sim_gonio_cfg_t *cfg, const sim_world_t *w, const sim_segment_t *seg,
                       double t_index, double t_from, double t_to, sim_rng_t *rng,
                       sim_gonio_event_t *out, size_t max)
{
    size_t n = 0;
    /* The window's ends are the same for every target. */
    vehicle_t at_from = vehicle_at(seg, t_from, true), at_to = vehicle_at(seg, t_to, false);
    double r = window_reach(cfg, w, seg, t_from, t_to), px = at_from.p.x, py = at_from.p.y;
    for (size_t i = 0; i < w->n_beacons; i++) {
        const sim_beacon_t *b = &w->beacon[i];
        n = add_edges(cfg, w, seg, t_index, &at_from, &at_to,
                      window_sight(cfg, w, px, py, r, b->x, b->y), rng, b->x, b->y,
                      0.5 * b->diameter, b->kind == SIM_BEACON_KIND_FLAT, (int16_t)i, out, n, max);
    }
    for (size_t i = 0; i < w->n_spurious; i++) {
        const sim_spurious_t *g = &w->spurious[i];
        n = add_edges(cfg, w, seg, t_index, &at_from, &at_to,
                      window_sight(cfg, w, px, py, r, g->x, g->y), rng, g->x, g->y, -0.5 * g->width,
                      0, (int16_t)(-1 - (int)i), out, n, max);
    }
    qsort(out, n, sizeof out[0], by_time);
    return n;
}

void sim_photo_init(sim_photo_t *p)
{
    memset(p, 0, sizeof *p);
}

int sim_photo_feed(sim_photo_t *p, const sim_gonio_event_t *e)
{
    int k = e->target >= 0 ? e->target : SIM_MAX_BEACONS - 1 - e->target;
    if (k < 0 || k >= SIM_PHOTO_TARGETS)
        return 0;
    if (e->edge == SIM_GEV_RISE) {
        if (p->lit[k])
            return 0;
        p->lit[k] = 1;
        return p->n_lit++ == 0;
    }
    if (!p->lit[k])
        return 0; /* its rising edge was not seen (before the simulation began) */
    p->lit[k] = 0;
    return --p->n_lit == 0;
}
