/*
 * sensors.c - odometer, gyro and goniometer pulses on the harness (see sensors.h).
 */
#include "sim/sensors.h"

#include <math.h>
#include <string.h>

#include "hal/capture.h"
#include "hal/edge.h"
#include "sim/clock.h"

static void on_dl(void *ctx, uint64_t t_ns);
static void on_gyro(void *ctx, uint64_t t_ns);
static void on_gonio(void *ctx, uint64_t t_ns);

void sim_sensors_init(sim_sensors_t *s, const sim_scenario_t *sc, const sim_segment_t *seg,
                      int main_board, int nav_board)
{
    memset(s, 0, sizeof *s);
    s->seg = seg;
    s->main_board = main_board;
    s->nav_board = nav_board;
    s->dl_source = posix_edge_source(nav_board, HAL_EDGE_DELTA_L); /* -1: no handler */
    s->dl = sc->dl * sc->odo_scale;
    s->gyro_step = sc->gyro_step;
    s->gyro_drift = sc->gyro_drift;
    s->heading0 = sc->start_heading;
    s->world = &sc->world;
    s->sc = sc;
    s->gonio.rev_per_s = sc->rev_per_s;
    s->gonio.counts = sc->counts;
    s->gonio.noise_rad = sc->gonio_noise;
    s->gonio.max_range = sc->gonio_range;
    s->gonio_off = sc->mode == SIM_SCENARIO_MODE_PURSUIT;
    sim_rng_seed(&s->rng_gonio, sc->seed, 1);
    sim_rng_seed(&s->rng_index, sc->seed, 3);
    sim_rng_seed(&s->rng_odo, sc->seed, 4);
    sim_photo_init(&s->photo);
    s->front_next = s->dl;
    sim_rng_t rng_phase;
    sim_rng_seed(&rng_phase, sc->seed, 2);
    s->t_index = -sim_rng_uniform(&rng_phase) / s->gonio.rev_per_s;
}

int sim_sensors_latch(const sim_sensors_t *s, uint16_t latch, double *t, sim_pose_t *pose)
{
    /* The nav board numbers its latches on 16 bits: the age is counted the same way. */
    uint16_t age = (uint16_t)(s->rises - 1u - latch);
    if (s->rises == 0 || age >= SIM_SENSORS_LATCHES)
        return -1;
    *t = s->rise_t[latch % SIM_SENSORS_LATCHES];
    *pose = s->rise_pose[latch % SIM_SENSORS_LATCHES];
    return 0;
}

int sim_sensors_beacons(const sim_sensors_t *s, uint16_t last, int n)
{
    uint8_t seen[SIM_MAX_BEACONS] = {0};
    int count = 0;
    for (int i = 0; i < n; i++) {
        double t;
        sim_pose_t p;
        uint16_t latch = (uint16_t)(last - i);
        if (sim_sensors_latch(s, latch, &t, &p) != 0)
            continue;
        int k = s->rise_target[latch % SIM_SENSORS_LATCHES];
        if (k >= 0 && k < SIM_MAX_BEACONS && !seen[k]) {
            seen[k] = 1;
            count++;
        }
    }
    return count;
}

/* In one of @p n windows at @p t? */
static int in_window(const sim_window_t *w, size_t n, double t)
{
    for (size_t i = 0; i < n; i++)
        if (t >= w[i].t && t < w[i].t + w[i].duration)
            return 1;
    return 0;
}

/* ------------------------------------------------------------------ odometer */

/* A spurious pulse, a little after a real one (the handler's flag would merge the two). */
#define GLITCH_DELAY_S 20e-6

static void on_glitch(void *ctx, uint64_t t_ns)
{
    sim_sensors_t *s = ctx;
    (void)t_ns;
    posix_edge_raise(s->nav_board, HAL_EDGE_DELTA_L);
}

static void schedule_dl(sim_sensors_t *s, double after)
{
    double t = sim_segment_time_at_front(s->seg, s->front_next, after);
    if (isfinite(t))
        s->ev_dl = sim_clock_schedule(t, on_dl, s);
}

/* A pulse at @p t_ns (s): lost, or raised, and then maybe a spurious one after it. */
static void pulse(sim_sensors_t *s, uint64_t t_ns)
{
    /* Glitches: a pulse lost, or a spurious one with it (both raise the same handler). */
    if (s->sc->odo_missed > 0 && sim_rng_uniform(&s->rng_odo) < s->sc->odo_missed) {
        s->odo_missed++;
        return;
    }
    if (s->dl_source >= 0)
        posix_source_raise(s->nav_board, s->dl_source);
    if (s->sc->odo_extra > 0 && sim_rng_uniform(&s->rng_odo) < s->sc->odo_extra) {
        s->odo_extra++;
        sim_clock_schedule(sim_clock_s(t_ns) + GLITCH_DELAY_S, on_glitch, s);
    }
}

/*
 * The pulses, one after the other while nothing else happens in between (posix_advance());
 * without glitches, each next pulse's interrupt is raised and taken by posix_advance_raise().
 */
static void on_dl(void *ctx, uint64_t t_ns)
{
    sim_sensors_t *s = ctx;
    s->ev_dl = 0;
    bool plain = s->sc->odo_missed <= 0 && s->sc->odo_extra <= 0 && s->dl_source >= 0;
    pulse(s, t_ns);
    for (;;) {
        s->front_next += s->dl;
        double t = sim_segment_time_at_front(s->seg, s->front_next, sim_clock_s(t_ns));
        if (!isfinite(t))
            return;
        uint64_t next = sim_clock_ns(t);
        if (next <= t_ns)
            next = t_ns + 1; /* as sim_clock_schedule() */
        if (plain ? !posix_advance_raise(next, s->nav_board, s->dl_source) : !posix_advance(next)) {
            s->ev_dl = posix_schedule(next, on_dl, s);
            return;
        }
        t_ns = next;
        if (!plain)
            pulse(s, t_ns);
    }
}

/* ------------------------------------------------------------------ gyro */

/* Measured heading: truth plus the gyro's drift. */
static double gyro_heading(const sim_sensors_t *s, double t)
{
    if (s->seg->decel > 0.0)
        return s->seg->p0.th + s->seg->kappa * sim_segment_travel(s->seg, t) + s->gyro_drift * t;
    return s->seg->p0.th + sim_segment_omega(s->seg) * (t - s->seg->t0) + s->gyro_drift * t;
}

/*
 * Smallest tau in [lo, hi] at which a tau^2 + b tau + c crosses 0 going the way of @p dir
 * (+1 upwards, -1 downwards), INFINITY if none; the roots in the forms that do not cancel.
 */
static double first_root(double a, double b, double c, int dir, double lo, double hi)
{
    double r[2] = {INFINITY, INFINITY};
    if (fabs(a) < 1e-15) {
        if (b != 0.0)
            r[0] = -c / b;
    } else {
        double disc = b * b - 4.0 * a * c;
        if (disc >= 0.0) {
            double q = -0.5 * (b + copysign(sqrt(disc), b));
            r[0] = q / a;
            r[1] = q != 0.0 ? c / q : INFINITY;
        }
    }
    double best = INFINITY;
    for (int i = 0; i < 2; i++)
        if (r[i] >= lo && r[i] <= hi && r[i] < best && dir * (2.0 * a * r[i] + b) > 0.0)
            best = r[i];
    return best;
}

/*
 * A braking segment: the first crossing of either step boundary from @p t0 by the measured
 * heading, quadratic in time until the stop and linear (the drift alone) after it. Its rate
 * may change sign on the way (the drift against a slowing turn), hence both boundaries; on a
 * constant-speed segment the rate keeps its sign and schedule_gyro() solves the line itself.
 */
static void schedule_gyro_braking(sim_sensors_t *s, double t0)
{
    const sim_segment_t *g = s->seg;
    double sgn = g->v < 0.0 ? -1.0 : 1.0, ts = sim_segment_stop_time(g), t1 = fmax(t0, ts);
    double best = INFINITY;
    int dir = 0;
    for (int k = 0; k < 2; k++) {
        int up = k == 0 ? 1 : -1;
        double level = s->heading0 + (s->gyro_count + 0.5 * up) * s->gyro_step;
        /* th0 + kappa sgn (|v| tau - decel tau^2 / 2) + drift (t0 + tau) = level */
        double a = -0.5 * g->kappa * sgn * g->decel, b = g->kappa * g->v + s->gyro_drift,
               c = g->p0.th + s->gyro_drift * g->t0 - level;
        double t = g->t0 + first_root(a, b, c, up, t0 - g->t0, ts - g->t0);
        if (!isfinite(t) && up * s->gyro_drift > 1e-12) {
            double after = t1 + (level - gyro_heading(s, t1)) / s->gyro_drift;
            if (after >= t1)
                t = after;
        }
        if (t < best) {
            best = t;
            dir = up;
        }
    }
    if (!isfinite(best))
        return;
    s->gyro_dir = dir;
    s->ev_gyro = sim_clock_schedule(best, on_gyro, s);
}

static void schedule_gyro(sim_sensors_t *s, double t0)
{
    sim_clock_cancel(&s->ev_gyro);
    if (s->seg->decel > 0.0) {
        schedule_gyro_braking(s, t0);
        return;
    }
    double rate = sim_segment_omega(s->seg) + s->gyro_drift;
    if (fabs(rate) < 1e-12)
        return;
    double m = gyro_heading(s, t0);
    /* Steps are counted around the start heading: count c covers (c -+ 1/2) steps. */
    double boundary = s->heading0 + (s->gyro_count + (rate > 0 ? 0.5 : -0.5)) * s->gyro_step;
    double t = t0 + (boundary - m) / rate;
    if (t < t0)
        t = t0;
    s->gyro_dir = rate > 0 ? 1 : -1;
    s->ev_gyro = sim_clock_schedule(t, on_gyro, s);
}

static void on_gyro(void *ctx, uint64_t t_ns)
{
    sim_sensors_t *s = ctx;
    s->ev_gyro = 0;
    s->gyro_count += s->gyro_dir;
    posix_edge_raise(s->nav_board, s->gyro_dir > 0 ? HAL_EDGE_GYRO_UP : HAL_EDGE_GYRO_DOWN);
    schedule_gyro(s, sim_clock_s(t_ns) + 1e-12);
}

/* ------------------------------------------------------------------ goniometer */

/* The goniometer's next event: an edge of this revolution, or the next index pulse. */
static void schedule_gonio(sim_sensors_t *s)
{
    sim_clock_cancel(&s->ev_gonio);
    double t_next_index = s->t_index + 1.0 / s->gonio.rev_per_s;
    double t = s->next_edge < s->n_edges ? s->edges[s->next_edge].t : t_next_index;
    s->ev_gonio = sim_clock_schedule(t, on_gonio, s);
}

/* Edges of the rest of the revolution along the current motion. */
static void gonio_recompute(sim_sensors_t *s, double from)
{
    double t_next_index = s->t_index + 1.0 / s->gonio.rev_per_s;
    s->n_edges = sim_gonio_edges(&s->gonio, s->world, s->seg, s->t_index, from, t_next_index,
                                 &s->rng_gonio, s->edges, SIM_SENSORS_MAX_EDGES);
    s->next_edge = 0;
    schedule_gonio(s);
}

static void on_gonio(void *ctx, uint64_t t_ns)
{
    sim_sensors_t *s = ctx;
    s->ev_gonio = 0;
    double t = sim_clock_s(t_ns);
    uint16_t count = sim_gonio_count(&s->gonio, t);
    if (s->next_edge < s->n_edges) {
        const sim_gonio_event_t *e = &s->edges[s->next_edge++];
        int rising = e->edge == SIM_GEV_RISE;
        /* Dropout windows: a pulse that begins in one is not seen, both its edges. */
        int tg = e->target >= 0 ? e->target : SIM_MAX_BEACONS - 1 - e->target;
        if (tg >= 0 && tg < SIM_PHOTO_TARGETS) {
            if (rising && in_window(s->sc->dropout, s->sc->n_dropouts, t))
                s->dark[tg] = 1;
            if (s->dark[tg]) {
                if (!rising)
                    s->dark[tg] = 0;
                schedule_gonio(s);
                return;
            }
        }
        if (!sim_photo_feed(&s->photo, e)) {
            schedule_gonio(s); /* overlapping pulses: the photodetector stays lit */
            return;
        }
        posix_capture_raise(s->main_board, HAL_CAPTURE_BEACON, count, (uint8_t)rising);
        if (rising) {
            /* The photodetector is wired to the nav board too: it latches its pose. */
            posix_edge_raise(s->nav_board, HAL_EDGE_BEACON_SIGHTED);
            uint32_t k = s->rises++ % SIM_SENSORS_LATCHES;
            s->rise_t[k] = t;
            s->rise_pose[k] = sim_segment_pose(s->seg, t);
            s->rise_target[k] = e->target;
        }
        schedule_gonio(s);
        return;
    }
    /* Index pulse: a new revolution (the main board may not see it). */
    s->t_index = t;
    if (s->sc->index_loss > 0 && sim_rng_uniform(&s->rng_index) < s->sc->index_loss)
        s->index_lost++;
    else
        posix_capture_raise(s->main_board, HAL_CAPTURE_INDEX, count, 1);
    gonio_recompute(s, t + 1e-9);
}

/* ------------------------------------------------------------------ all of them */

void sim_sensors_motion(sim_sensors_t *s)
{
    double t = sim_clock_now();
    sim_clock_cancel(&s->ev_dl);
    schedule_dl(s, t);
    schedule_gyro(s, t);
    if (!s->gonio_off)
        gonio_recompute(s, t + 1e-9);
}
