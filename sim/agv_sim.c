/*
 * agv-sim - the closed-loop harness: a simulated vehicle in a simulated building whose sensors
 * raise the real firmware's interrupts on both boards (hal/posix), and whose drive board
 * executes what the main board writes to its port (CONTRACT.md "agv-sim").
 *
 *   agv-sim --scenario FILE [--seed N] [--report FILE.json] [--log-dir DIR] [--lcm URL]
 *           [--quiet] [--trace]
 *
 * Exit status: 0 the run met the scenario's success criteria, 1 it did not, 2 bad input.
 *
 * The world (sim/): truth motion of a tricycle on constant-steering segments, a goniometer
 * whose photodetector edges come from the beam's geometry while the vehicle moves, an
 * odometer pulse every dl of front-wheel travel, a gyro step whenever the measured heading
 * (truth plus drift) crosses a step boundary, and a drive board that decodes the port writes
 * (firmware/drive's decoder) and drives its arcs, raising delta-S 2 cm before each arc's end.
 * Everything runs on the harness's simulated time; the only wall clock read is for the
 * report's wall_time_s and the progress line.
 */
#include <errno.h>
#include <getopt.h>
#include <lcm/lcm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "drive/drive.h"
#include "drive/drive_path.h"
#include "drive/drive_proto.h"
#include "fx/fx_host.h"
#include "hal/capture.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#include "hal/pinmap.h"
#include "hal_posix/drive_port_posix.h"
#include "hal_posix/harness.h"
#include "lcmtypes/cyclopion_drive_command_t.h"
#include "lcmtypes/cyclopion_fix_t.h"
#include "lcmtypes/cyclopion_pose_t.h"
#include "lcmtypes/cyclopion_sightings_t.h"
#include "lcmtypes/cyclopion_truth_t.h"
#include "main_board.h"
#include "nav_board.h"
#include "sim/gonio.h"
#include "sim/motion.h"
#include "sim/path.h"
#include "sim/report.h"
#include "sim/rng.h"
#include "sim/scenario.h"

#define DEG           (M_PI / 180.0)
#define NS(t)         ((uint64_t)((t)*1e9 + 0.5)) /* t >= 0 */
#define SEC(ns)       ((double)(ns)*1e-9)
#define MAX_EDGES     256
#define RISE_RING     256u
#define SAMPLE_PERIOD 0.01 /* s: cross-track samples and telemetry decimation */
#define LOG_PERIOD    0.05 /* s: CSV and LCM pose/truth rows */
#define DS_MARGIN     0.02 /* m: the drive board's delta-S comes this far before an arc ends */
#define BRAKE         0.5  /* m/s^2: the drive board's braking when told speed 0 */
#define BRAKE_STEP    0.01 /* s: speed steps while braking */
#define STOP_DISTANCE 5.0  /* m: the nav board's stop request without a fix (G6) */
#define ARC_SPACING   0.8  /* m: secondary points on the path (the double-arc length) */

/* The drive board: what the main board loaded, and where it is in it. */
typedef struct {
    double k;     /* rear-axle curvature, 1/m */
    double alpha; /* steering angle, rad */
    double left;  /* rear-axle length still to drive, m */
    int pulse;    /* 1: no delta-S for this arc (short, D7) or already raised */
} arc_t;

typedef struct {
    sim_scenario_t sc;
    int main_b, nav_b;
    sim_world_t *world;
    sim_gonio_cfg_t gcfg;
    sim_rng_t rng_gonio;
    /* truth */
    sim_segment_t seg;
    double alpha, v;
    /* the drive board */
    drive_decoder_t dec;
    arc_t arc[2];
    int cur; /* arc being driven, 2 = none */
    int braking;
    /* sensors */
    double front_next; /* front-wheel total at the next odometer pulse */
    long gyro_count;   /* measured heading, in steps from the start */
    double t_index;    /* last index pulse */
    sim_gonio_event_t edges[MAX_EDGES];
    sim_photo_t photo;
    size_t n_edges, next_edge;
    uint32_t rises;
    double rise_t[RISE_RING];
    sim_pose_t rise_pose[RISE_RING];
    int16_t rise_target[RISE_RING];
    /* scheduled events */
    uint64_t ev_dl, ev_gyro, ev_gonio, ev_drive;
    /* metrics */
    sim_report_t rep;
    sim_path_t *nominal;
    sim_pose_t last_sample;
    double next_log;
    int done;
    /* outputs */
    FILE *f_truth, *f_est, *f_fix, *f_cmd;
    lcm_t *lcm;
    int quiet;
    int trace; /* --trace: every fix attempt and travel state on stderr */
} sim_t;

static sim_t S;

/* ------------------------------------------------------------------ helpers */

static double now_s(void)
{
    return SEC(posix_now_ns());
}

static double wrap_deg(double d)
{
    d = fmod(d, 360.0);
    return d < 0 ? d + 360.0 : d;
}

static sim_pose_t truth_at(double t)
{
    return sim_segment_pose(&S.seg, t);
}

static void die_input(const char *msg)
{
    fprintf(stderr, "agv-sim: %s\n", msg);
    exit(2);
}

static void run_board(int b)
{
    posix_board_select(b);
    if (b == S.main_b)
        main_board_poll();
    else
        nav_board_poll();
}

/* ------------------------------------------------------------------ sensor scheduling */

static void schedule_all(void);
static void on_gyro(void *ctx, uint64_t t_ns);

static void cancel(uint64_t *id)
{
    if (*id)
        posix_cancel(*id);
    *id = 0;
}

static void on_dl(void *ctx, uint64_t t_ns)
{
    (void)ctx;
    S.ev_dl = 0;
    posix_edge_raise(S.nav_b, HAL_EDGE_DELTA_L);
    S.front_next += S.sc.dl * S.sc.odo_scale;
    double t = sim_segment_time_at_front(&S.seg, S.front_next, SEC(t_ns));
    if (isfinite(t))
        S.ev_dl = posix_schedule(NS(t) > t_ns ? NS(t) : t_ns + 1, on_dl, 0);
}

/* Measured heading: truth (linear in time on a segment) plus the gyro's drift. */
static double gyro_heading(double t)
{
    return S.seg.p0.th + sim_segment_omega(&S.seg) * (t - S.seg.t0) + S.sc.gyro_drift * t;
}

static void schedule_gyro(double t0)
{
    cancel(&S.ev_gyro);
    double rate = sim_segment_omega(&S.seg) + S.sc.gyro_drift;
    if (fabs(rate) < 1e-12)
        return;
    double h0 = S.sc.start_heading;
    double m = gyro_heading(t0);
    /* Steps are counted around the start heading: count c covers (c -+ 1/2) steps. */
    double boundary = h0 + (S.gyro_count + (rate > 0 ? 0.5 : -0.5)) * S.sc.gyro_step;
    double t = t0 + (boundary - m) / rate;
    if (t < t0)
        t = t0;
    S.ev_gyro = posix_schedule(NS(t) > posix_now_ns() ? NS(t) : posix_now_ns() + 1, on_gyro,
                               (void *)(intptr_t)(rate > 0 ? 1 : -1));
}

static void on_gyro(void *ctx, uint64_t t_ns)
{
    S.ev_gyro = 0;
    int dir = (int)(intptr_t)ctx;
    S.gyro_count += dir;
    posix_edge_raise(S.nav_b, dir > 0 ? HAL_EDGE_GYRO_UP : HAL_EDGE_GYRO_DOWN);
    schedule_gyro(SEC(t_ns) + 1e-12);
}

static void on_gonio(void *ctx, uint64_t t_ns);

/* The goniometer's next event: an edge of this revolution, or the next index pulse. */
static void schedule_gonio(void)
{
    cancel(&S.ev_gonio);
    double t_next_index = S.t_index + 1.0 / S.gcfg.rev_per_s;
    double t = S.next_edge < S.n_edges ? S.edges[S.next_edge].t : t_next_index;
    uint64_t ns = NS(t);
    if (ns <= posix_now_ns())
        ns = posix_now_ns() + 1;
    S.ev_gonio = posix_schedule(ns, on_gonio, 0);
}

/* Edges of the rest of the revolution along the current motion. */
static void gonio_recompute(double from)
{
    double t_next_index = S.t_index + 1.0 / S.gcfg.rev_per_s;
    S.n_edges = sim_gonio_edges(&S.gcfg, S.world, &S.seg, S.t_index, from, t_next_index,
                                &S.rng_gonio, S.edges, MAX_EDGES);
    S.next_edge = 0;
    schedule_gonio();
}

static void on_gonio(void *ctx, uint64_t t_ns)
{
    (void)ctx;
    S.ev_gonio = 0;
    double t = SEC(t_ns);
    uint16_t count = sim_gonio_count(&S.gcfg, t);
    if (S.next_edge < S.n_edges) {
        const sim_gonio_event_t *e = &S.edges[S.next_edge++];
        int rising = e->edge == SIM_GEV_RISE;
        if (!sim_photo_feed(&S.photo, e)) {
            schedule_gonio(); /* overlapping pulses: the photodetector stays lit */
            return;
        }
        posix_capture_raise(S.main_b, HAL_CAPTURE_BEACON, count, (uint8_t)rising);
        if (rising) {
            /* The photodetector is wired to the nav board too: it latches its pose. */
            posix_edge_raise(S.nav_b, HAL_EDGE_BEACON_SIGHTED);
            uint32_t k = S.rises++ % RISE_RING;
            S.rise_t[k] = t;
            S.rise_pose[k] = truth_at(t);
            S.rise_target[k] = e->target;
        }
        schedule_gonio();
        return;
    }
    /* Index pulse: a new revolution. */
    S.t_index = t;
    posix_capture_raise(S.main_b, HAL_CAPTURE_INDEX, count, 1);
    gonio_recompute(t + 1e-9);
}

/* ------------------------------------------------------------------ the drive board */

static void on_drive(void *ctx, uint64_t t_ns);

/* Account the rear-axle travel since the segment began to the arc being driven. */
static void arc_progress(double t)
{
    if (S.cur < 2)
        S.arc[S.cur].left -= fabs(S.seg.v) * (t - S.seg.t0);
}

/* Start a new constant-steering, constant-speed piece of motion at time t (after
 * arc_progress). */
static void new_segment(double t)
{
    sim_pose_t p = truth_at(t);
    double front = sim_segment_front(&S.seg, t);
    double alpha = S.cur < 2 ? S.arc[S.cur].alpha : S.alpha;
    double v = S.cur < 2 ? S.v : 0.0;
    S.alpha = alpha;
    S.seg = sim_segment(t, p, front, alpha, v, S.sc.wheelbase);
    schedule_all();
}

/* When the drive board next has something to do: a delta-S, an arc's end, a braking step. */
static void schedule_drive(double t)
{
    cancel(&S.ev_drive);
    double v = fabs(S.seg.v);
    double next = INFINITY;
    if (S.braking)
        next = t + BRAKE_STEP;
    if (S.cur < 2 && v > 0) {
        const arc_t *a = &S.arc[S.cur];
        double ds = a->pulse ? a->left : a->left - DS_MARGIN;
        if (ds < 0)
            ds = 0;
        next = fmin(next, t + ds / v);
    }
    if (isfinite(next))
        S.ev_drive =
            posix_schedule(NS(next) > posix_now_ns() ? NS(next) : posix_now_ns() + 1, on_drive, 0);
}

static void schedule_all(void)
{
    double t = now_s();
    cancel(&S.ev_dl);
    double tdl = sim_segment_time_at_front(&S.seg, S.front_next, t);
    if (isfinite(tdl))
        S.ev_dl = posix_schedule(NS(tdl) > posix_now_ns() ? NS(tdl) : posix_now_ns() + 1, on_dl, 0);
    schedule_gyro(t);
    gonio_recompute(t + 1e-9);
    schedule_drive(t);
}

static void on_drive(void *ctx, uint64_t t_ns)
{
    (void)ctx;
    S.ev_drive = 0;
    double t = SEC(t_ns);
    int changed = 0;
    arc_progress(t);
    if (S.cur < 2) {
        arc_t *a = &S.arc[S.cur];
        if (!a->pulse && a->left <= DS_MARGIN + 1e-9) {
            a->pulse = 1;
            posix_edge_raise(S.main_b, HAL_EDGE_DELTA_S);
        }
        if (a->left <= 1e-9) {
            S.cur++;
            if (S.cur == 1 && S.arc[1].left <= 0)
                S.cur = 2;
            if (S.cur == 2)
                S.v = 0; /* the double arc is done: the board stops */
            changed = 1;
        }
    }
    if (S.braking) {
        double m = fabs(S.v) - BRAKE * BRAKE_STEP;
        if (m <= 0) {
            m = 0;
            S.braking = 0;
        }
        S.v = S.v < 0 ? -m : m;
        changed = 1;
    }
    if (changed) {
        new_segment(t);
    } else {
        /* Only a delta-S went out: keep moving, restart the arc bookkeeping from here. */
        S.seg = sim_segment(t, truth_at(t), sim_segment_front(&S.seg, t), S.alpha, S.seg.v,
                            S.sc.wheelbase);
        schedule_drive(t);
    }
}

static void log_command(const drive_event_t *ev)
{
    double t = now_s();
    if (S.f_cmd) {
        if (ev->type == DRIVE_EV_LOAD)
            fprintf(S.f_cmd, "%.6f,load,%.4f,%.4f,%.4f,%.4f,%.4f\n", t,
                    (128 - ev->cmd.steer[0]) * 180.0 / 256, ev->cmd.arc[0] / 173.2283,
                    (128 - ev->cmd.steer[1]) * 180.0 / 256, ev->cmd.arc[1] / 173.2283,
                    ev->cmd.speed * 0.01755);
        else
            fprintf(S.f_cmd, "%.6f,speed,,,,,%.4f\n", t, ev->cmd.speed * 0.01755);
    }
    if (S.lcm) {
        cyclopion_drive_command_t m;
        double steer[2], len[2];
        memset(&m, 0, sizeof m);
        m.utime = (int64_t)(posix_now_ns() / 1000);
        m.kind = ev->type == DRIVE_EV_LOAD ? "arcs" : (ev->cmd.speed ? "speed" : "stop");
        m.n = ev->type == DRIVE_EV_LOAD ? 2 : 0;
        for (int i = 0; i < 2; i++) {
            steer[i] = (128 - ev->cmd.steer[i]) * 180.0 / 256;
            len[i] = ev->cmd.arc[i] / 173.2283;
        }
        m.steering_deg = steer;
        m.length_m = len;
        m.speed_mps = ev->cmd.speed * 0.01755;
        cyclopion_drive_command_t_publish(S.lcm, "CYCLOPION_DRIVE", &m);
    }
}

/* Every write the main board makes on its drive bus reaches the drive board here. */
static void drive_sink(void *ctx, int board, const posix_drive_write_t *w)
{
    (void)ctx;
    (void)board;
    drive_event_t ev;
    if (!drive_decoder_feed(&S.dec, w->reg, w->value, &ev))
        return;
    double t = now_s();
    double L = S.sc.wheelbase;
    /* Drive-board units: 4.4 counts per inch of front wheel, 1.755 cm/s per speed count. */
    const double cpm = 173.2283, lsb = 0.01755;
    if (ev.type == DRIVE_EV_LOAD) {
        log_command(&ev);
        arc_progress(t);
        for (int i = 0; i < 2; i++) {
            double alpha = (128 - ev.cmd.steer[i]) * M_PI / 256;
            double k = tan(alpha) / L;
            S.arc[i].alpha = alpha;
            S.arc[i].k = k;
            S.arc[i].left = ev.cmd.arc[i] / cpm / sqrt(1 + L * L * k * k);
            S.arc[i].pulse = ev.cmd.arc[i] < 3;
        }
        S.cur = S.arc[0].left > 0 ? 0 : (S.arc[1].left > 0 ? 1 : 2);
        S.braking = 0;
        S.v = ev.cmd.speed * lsb;
        if (S.cur == 2)
            S.v = 0;
        new_segment(t);
    } else if (ev.type == DRIVE_EV_SPEED) {
        log_command(&ev);
        arc_progress(t);
        if (ev.cmd.speed == 0 && S.v != 0) {
            S.braking = 1;
            new_segment(t);
        } else {
            S.braking = 0;
            S.v = ev.cmd.speed * lsb;
            new_segment(t);
        }
    } else if (ev.type == DRIVE_EV_ERROR) {
        fprintf(stderr, "agv-sim: drive board: protocol error %d at t=%.4f s\n", ev.error, t);
    }
}

/* ------------------------------------------------------------------ observers, logs */

static void on_fix(void *ctx, const main_board_fix_event_t *ev)
{
    (void)ctx;
    double t = now_s();
    S.rep.fixes_attempted++;
    int accepted = ev->status == OPTICAL_OK;
    double err = -1, herr = -1, tref = t;
    uint32_t age = S.rises - ev->ref_latch - 1u; /* rises are numbered from 0 */
    if (ev->n > 0 && age < RISE_RING) {
        uint32_t k = ev->ref_latch % RISE_RING;
        tref = S.rise_t[k];
        sim_pose_t tp = S.rise_pose[k];
        double fx = fx_q16_to_double(ev->fix.pose.x), fy = fx_q16_to_double(ev->fix.pose.y);
        err = hypot(fx - tp.x, fy - tp.y);
        herr = fabs(remainder(fx_angle_to_deg(ev->fix.pose.heading) - tp.th / DEG, 360.0));
        if (S.trace) {
            fprintf(stderr,
                    "t=%.3f fix ref %u status %d: dead reckoning (%.4f %.4f %.3f) truth (%.4f "
                    "%.4f %.3f) fix (%.4f %.4f %.3f) error %.4f m\n",
                    t, ev->ref_latch, ev->status, fx_q16_to_double(ev->approx.x),
                    fx_q16_to_double(ev->approx.y), fx_angle_to_deg(ev->approx.heading), tp.x, tp.y,
                    wrap_deg(tp.th / DEG), fx, fy, fx_angle_to_deg(ev->fix.pose.heading), err);
            for (int i = 0; i < ev->n; i++)
                fprintf(stderr, "  sighting %2d at %8.3f deg, %.3f deg wide: beacon %d%s\n", i,
                        fx_angle_to_deg(ev->s[i].angle), ev->s[i].width * 360.0 / 65536.0,
                        ev->fix.ident[i],
                        ev->status == OPTICAL_OK && (ev->fix.ident[i] == ev->fix.used[0] ||
                                                     ev->fix.ident[i] == ev->fix.used[1] ||
                                                     ev->fix.ident[i] == ev->fix.used[2])
                            ? " (used)"
                            : "");
        }
    } else if (S.trace)
        fprintf(stderr, "t=%.3f fix status %d: no sightings to pair with latches\n", t, ev->status);
    if (accepted) {
        S.rep.fixes_accepted++;
        if (err >= 0) {
            sim_stat_add(&S.rep.fix_error, err);
            sim_stat_add(&S.rep.heading_error, herr);
        }
    } else {
        S.rep.fixes_rejected++;
    }
    if (S.f_fix)
        fprintf(S.f_fix, "%.6f,%.6f,%d,%.6f,%.6f,%.5f,%.6f,%.5f,%u,%d;%d;%d,%d\n", t, tref,
                accepted, fx_q16_to_double(ev->fix.pose.x), fx_q16_to_double(ev->fix.pose.y),
                fx_angle_to_deg(ev->fix.pose.heading), err, herr, ev->fix.quality,
                accepted ? ev->fix.used[0] : -1, accepted ? ev->fix.used[1] : -1,
                accepted ? ev->fix.used[2] : -1, ev->status);
    if (S.lcm) {
        cyclopion_fix_t m;
        memset(&m, 0, sizeof m);
        m.utime = (int64_t)(posix_now_ns() / 1000);
        m.ref_utime = (int64_t)llround(tref * 1e6);
        m.accepted = accepted;
        m.x = fx_q16_to_double(ev->fix.pose.x);
        m.y = fx_q16_to_double(ev->fix.pose.y);
        m.heading_deg = fx_angle_to_deg(ev->fix.pose.heading);
        m.quality = ev->fix.quality / 65536.0;
        m.error_m = err;
        for (int i = 0; i < 3; i++)
            m.used[i] = accepted ? ev->fix.used[i] : -1;
        char reason[32];
        snprintf(reason, sizeof reason, accepted ? "" : "status %d", ev->status);
        m.reason = reason;
        cyclopion_fix_t_publish(S.lcm, "CYCLOPION_FIX", &m);

        cyclopion_sightings_t sg;
        double ang[OPTICAL_MAX_SIGHTINGS], wid[OPTICAL_MAX_SIGHTINGS];
        int16_t idn[OPTICAL_MAX_SIGHTINGS], tru[OPTICAL_MAX_SIGHTINGS];
        sg.utime = m.utime;
        sg.n = ev->n;
        for (int i = 0; i < ev->n; i++) {
            ang[i] = fx_angle_to_deg(ev->s[i].angle);
            wid[i] = ev->s[i].width * 360.0 / 65536.0;
            idn[i] = ev->fix.ident[i];
            tru[i] = -100;
        }
        sg.angle_deg = ang;
        sg.width_deg = wid;
        sg.identified = idn;
        sg.truth = tru;
        cyclopion_sightings_t_publish(S.lcm, "CYCLOPION_SIGHTINGS", &sg);
    }
}

static void on_state(void *ctx, drive_state_t st)
{
    (void)ctx;
    if (S.trace) {
        sim_pose_t p = truth_at(now_s());
        fprintf(stderr, "t=%.3f state %s at (%.4f %.4f %.2f)\n", now_s(), drive_seq_state_name(st),
                p.x, p.y, wrap_deg(p.th / DEG));
    }
}

static void sample(void *ctx, uint64_t t_ns)
{
    (void)ctx;
    double t = SEC(t_ns);
    sim_pose_t p = truth_at(t);
    double ct = sim_path_distance(S.nominal, p.x, p.y);
    if (hypot(p.x - S.last_sample.x, p.y - S.last_sample.y) >= 1e-3 && !S.done) {
        sim_stat_add(&S.rep.cross_track, ct); /* while moving: the mean is over distance */
        S.last_sample = p;
    }
    if (t >= S.next_log - 1e-9) {
        S.next_log += LOG_PERIOD;
        gnav_pose_t e;
        posix_board_select(S.nav_b);
        nav_board_pose(&e);
        double ex = fx_q16_to_double(e.x), ey = fx_q16_to_double(e.y);
        double eh = fx_angle_to_deg(e.heading);
        if (S.f_truth)
            fprintf(S.f_truth, "%.4f,%.6f,%.6f,%.5f,%.4f,%.4f,%.6f\n", t, p.x, p.y,
                    wrap_deg(p.th / DEG), S.seg.v, S.alpha / DEG, ct);
        if (S.f_est)
            fprintf(S.f_est, "%.4f,%.6f,%.6f,%.5f\n", t, ex, ey, eh);
        if (S.lcm) {
            cyclopion_truth_t tm = {(int64_t)(t_ns / 1000), p.x, p.y, wrap_deg(p.th / DEG), S.seg.v,
                                    S.alpha / DEG,          ct};
            cyclopion_truth_t_publish(S.lcm, "CYCLOPION_TRUTH", &tm);
            int src = posix_source_find(S.nav_b, (int)hal_edge_vector(HAL_EDGE_DELTA_L),
                                        (int)hal_edge_pin(HAL_EDGE_DELTA_L));
            cyclopion_pose_t pm = {(int64_t)(t_ns / 1000), ex, ey, eh,
                                   src >= 0 ? (int64_t)posix_source_count(S.nav_b, src) : 0};
            cyclopion_pose_t_publish(S.lcm, "CYCLOPION_POSE", &pm);
        }
    }
    posix_schedule(t_ns + NS(SAMPLE_PERIOD), sample, 0);
}

/* ------------------------------------------------------------------ set-up */

static fx_q16_t q16(double v)
{
    return fx_q16_from_double(v);
}

static drive_pose_t dpose(double x, double y, double th)
{
    drive_pose_t p = {q16(x), q16(y), fx_angle_from_rad(th)};
    return p;
}

static void build_nominal(const main_board_config_t *mc)
{
    /* CONTRACT.md: the chain of double arcs the board's path preparation gives between
     * consecutive prescribed poses (the start first; a turn over 90 degrees as two, through
     * the pose it inserts), computed once from them. */
    drive_pose_t from = mc->start;
    sim_pose_t s0 = {S.sc.start_x, S.sc.start_y, S.sc.start_heading};
    S.nominal->n = 0;
    for (size_t i = 0; i < S.sc.n_path; i++) {
        drive_pose_t to = mc->path[i].pose;
        drive_leg_t leg;
        drive_status_t st =
            drive_leg_solve(&from, &to, mc->path_cfg.nominal_radius, mc->path_cfg.reverse, &leg);
        if (st != DRIVE_OK) {
            char msg[384];
            snprintf(msg, sizeof msg,
                     "path[%zu]: no double arc from the previous point: %s (min_radius_m %.3f)", i,
                     drive_status_text(st), S.sc.min_radius);
            die_input(msg);
        }
        for (int k = 0; k < 2 * leg.parts; k++) {
            const drive_segment_t *g = &leg.sol[k / 2].seg[k % 2];
            double len = fx_q16_to_double(g->length);
            if (len <= 0)
                continue;
            double kap = (double)g->curvature / (double)(1l << DRIVE_CURV_SHIFT);
            /* Each leg starts at its prescribed pose (the solver lands within 0.05 mm). */
            if (k == 0 || S.nominal->n == 0)
                sim_path_append_from(S.nominal, s0, kap, len, mc->path_cfg.reverse);
            else
                sim_path_append(S.nominal, s0, kap, len, mc->path_cfg.reverse);
        }
        from = to;
        s0 = (sim_pose_t){S.sc.path[i].x, S.sc.path[i].y, S.sc.path[i].heading};
    }
}

static FILE *open_log(const char *dir, const char *name, const char *header)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "agv-sim: cannot write %s: %s\n", path, strerror(errno));
        exit(2);
    }
    fputs(header, f);
    return f;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: agv-sim --scenario FILE [--seed N] [--report FILE.json] [--log-dir DIR]\n"
            "               [--lcm URL] [--quiet] [--trace]\n"
            "Runs both boards' firmware against a simulated vehicle and building.\n"
            "  --scenario FILE   scenario (JSON, CONTRACT.md; examples in sim/scenarios/)\n"
            "  --seed N          override the scenario's seed\n"
            "  --report FILE     write the report (JSON) there (default: stdout)\n"
            "  --log-dir DIR     write truth.csv, estimate.csv, fixes.csv, commands.csv,\n"
            "                    path.csv, beacons.csv\n"
            "  --lcm URL         publish telemetry on LCM (e.g. udpm://239.255.76.67:7667?ttl=0)\n"
            "  --quiet           no progress on stderr\n"
            "  --trace           every fix attempt (dead-reckoning pose, truth and fix at the\n"
            "                    reference latch, sightings, status) and travel state on stderr\n"
            "Exit status: 0 criteria met, 1 criteria missed, 2 bad input.\n");
}

int main(int argc, char **argv)
{
    static const struct option opts[] = {{"scenario", required_argument, 0, 's'},
                                         {"seed", required_argument, 0, 'S'},
                                         {"report", required_argument, 0, 'r'},
                                         {"log-dir", required_argument, 0, 'l'},
                                         {"lcm", required_argument, 0, 'L'},
                                         {"quiet", no_argument, 0, 'q'},
                                         {"trace", no_argument, 0, 't'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    const char *scenario = NULL, *report = NULL, *log_dir = NULL, *lcm_url = NULL;
    long long seed = -1;
    int c;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        switch (c) {
        case 's':
            scenario = optarg;
            break;
        case 'S': {
            char *end;
            errno = 0;
            seed = strtoll(optarg, &end, 10);
            if (errno || *end || seed < 0) {
                fprintf(stderr, "agv-sim: --seed: \"%s\" is not a non-negative integer\n", optarg);
                return 2;
            }
            break;
        }
        case 'r':
            report = optarg;
            break;
        case 'l':
            log_dir = optarg;
            break;
        case 'L':
            lcm_url = optarg;
            break;
        case 'q':
            S.quiet = 1;
            break;
        case 't':
            S.trace = 1;
            break;
        case 'h':
            usage(stdout);
            return 0;
        default:
            usage(stderr);
            return 2;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "agv-sim: unexpected argument \"%s\"\n", argv[optind]);
        usage(stderr);
        return 2;
    }
    if (!scenario) {
        fprintf(stderr, "agv-sim: --scenario is required\n");
        usage(stderr);
        return 2;
    }
    char err[512];
    if (sim_scenario_load(scenario, &S.sc, err, sizeof err))
        die_input(err);
    if (seed >= 0)
        S.sc.seed = (uint64_t)seed;
    if (S.sc.n_path > MAIN_BOARD_MAX_PATH) {
        snprintf(err, sizeof err, "path: %zu points, the main board holds at most %d", S.sc.n_path,
                 MAIN_BOARD_MAX_PATH);
        die_input(err);
    }
    if (S.sc.world.n_beacons > OPTICAL_MAX_BEACONS) {
        snprintf(err, sizeof err, "beacons: %zu, the main board's map holds at most %d",
                 S.sc.world.n_beacons, OPTICAL_MAX_BEACONS);
        die_input(err);
    }

    /* ---- the world ---- */
    static sim_path_t nominal;
    S.nominal = &nominal;
    S.world = &S.sc.world;
    S.gcfg.rev_per_s = S.sc.rev_per_s;
    S.gcfg.counts = S.sc.counts;
    S.gcfg.noise_rad = S.sc.gonio_noise;
    S.gcfg.max_range = S.sc.gonio_range;
    sim_rng_seed(&S.rng_gonio, S.sc.seed, 1);
    sim_photo_init(&S.photo);
    sim_pose_t start = {S.sc.start_x, S.sc.start_y, S.sc.start_heading};
    S.seg = sim_segment(0.0, start, 0.0, 0.0, 0.0, S.sc.wheelbase);
    S.cur = 2;
    S.front_next = S.sc.dl * S.sc.odo_scale;
    S.last_sample = start;
    drive_decoder_init(&S.dec, 132);

    /* ---- the main board's download: map, path, vehicle (seed 000's drive board units) ---- */
    static optical_xy_t beacons[OPTICAL_MAX_BEACONS];
    for (size_t i = 0; i < S.sc.world.n_beacons; i++) {
        beacons[i].x = q16(S.sc.world.beacon[i].x);
        beacons[i].y = q16(S.sc.world.beacon[i].y);
    }
    static drive_path_point_t pts[MAIN_BOARD_MAX_PATH];
    for (size_t i = 0; i < S.sc.n_path; i++) {
        pts[i].pose = dpose(S.sc.path[i].x, S.sc.path[i].y, S.sc.path[i].heading);
        pts[i].speed = q16(S.sc.path[i].speed);
        pts[i].nsub = 0;
    }
    static main_board_config_t mc; /* the board keeps it by reference */
    static optical_xy8_t beacons8[OPTICAL_MAX_BEACONS];
    if (!optical_map_compile(&mc.map, beacons, (uint8_t)S.sc.world.n_beacons, beacons8)) {
        snprintf(err, sizeof err,
                 "beacons: %zu of them; the main board needs 3..%d within +-128 m of one "
                 "point (a site of at most 256 m by 256 m)",
                 S.sc.world.n_beacons, OPTICAL_MAX_BEACONS);
        die_input(err);
    }
    mc.path = pts;
    mc.n_path = (uint8_t)S.sc.n_path;
    mc.start = dpose(S.sc.start_x, S.sc.start_y, S.sc.start_heading);
    drive_board_t seed_board = DRIVE_BOARD_SEED;
    mc.board = seed_board;
    mc.board.wheelbase = q16(S.sc.wheelbase);
    mc.board.min_radius = q16(S.sc.min_radius);
    mc.path_cfg.nominal_radius = q16(S.sc.min_radius);
    mc.path_cfg.spacing = q16(ARC_SPACING);
    mc.path_cfg.reverse = false;
    mc.seq_cfg.mode = S.sc.full_travel ? DRIVE_MODE_FULL : DRIVE_MODE_SIMPLIFIED;
    mc.seq_cfg.load_ms = 35;
    mc.seq_cfg.settle_ms = 50;
    mc.seq_cfg.stop_speed = q16(0.15);
    mc.seq_cfg.advance = q16(0.4);
    mc.seq_cfg.max_fix_failures = 3;
    mc.counts_per_turn = (uint16_t)S.sc.counts;
    optical_config_default(&mc.optical);
    mc.optical.beacon_diameter = q16(S.sc.world.beacon[0].diameter);
    build_nominal(&mc);

    nav_board_config_t nc;
    memset(&nc, 0, sizeof nc);
    nc.gnav.wheelbase = q16(S.sc.wheelbase);
    nc.gnav.dl_q40 = (uint32_t)llround(S.sc.dl * 1099511627776.0);
    nc.gnav.gyro_step_q48 = (uint64_t)llround(S.sc.gyro_step / (2 * M_PI) * 281474976710656.0);
    nc.gnav.stop_distance = q16(STOP_DISTANCE);
    nc.start.x = q16(S.sc.start_x + S.sc.start_err_x);
    nc.start.y = q16(S.sc.start_y + S.sc.start_err_y);
    nc.start.heading = fx_angle_from_rad(S.sc.start_heading + S.sc.start_err_heading);

    /* ---- the boards on the harness ---- */
    posix_reset();
    S.main_b = posix_board_create("main");
    S.nav_b = posix_board_create("nav");
    posix_board_select(S.nav_b);
    hal_cpu_init();
    int rc = nav_board_init(&nc);
    if (rc != 0) {
        snprintf(err, sizeof err, "nav board refuses the vehicle: %s", gnav_strerror(rc));
        die_input(err);
    }
    posix_board_select(S.main_b);
    hal_cpu_init();
    posix_drive_port_set_sink(S.main_b, drive_sink, 0); /* the drive board sees every write */
    drive_status_t ds = main_board_init(&mc);
    if (ds != DRIVE_OK) {
        const drive_path_t *pp = main_board_path();
        snprintf(err, sizeof err, "the main board refuses the path: leg %u piece %u: %s",
                 pp->bad_leg, pp->bad_sub, drive_status_text(pp->bad_why));
        die_input(err);
    }
    main_board_observer_t obs = {0, on_fix, 0, on_state};
    main_board_set_observer(&obs);
    posix_signal_connect(S.main_b, HAL_SIGNAL_COORD_REQUEST, S.nav_b, HAL_EDGE_COORD_REQUEST);

    /* ---- outputs ---- */
    if (log_dir) {
        if (mkdir(log_dir, 0777) && errno != EEXIST) {
            fprintf(stderr, "agv-sim: cannot create %s: %s\n", log_dir, strerror(errno));
            return 2;
        }
        S.f_truth = open_log(log_dir, "truth.csv",
                             "t_s,x_m,y_m,heading_deg,speed_mps,steering_deg,cross_track_m\n");
        S.f_est = open_log(log_dir, "estimate.csv", "t_s,x_m,y_m,heading_deg\n");
        S.f_fix = open_log(log_dir, "fixes.csv",
                           "t_s,ref_t_s,accepted,x_m,y_m,heading_deg,error_m,heading_error_deg,"
                           "quality,used,status\n");
        S.f_cmd = open_log(log_dir, "commands.csv",
                           "t_s,kind,steering1_deg,length1_m,steering2_deg,length2_m,speed_mps\n");
        FILE *f = open_log(log_dir, "beacons.csv", "x_m,y_m,diameter_m\n");
        for (size_t i = 0; i < S.sc.world.n_beacons; i++)
            fprintf(f, "%.4f,%.4f,%.4f\n", S.sc.world.beacon[i].x, S.sc.world.beacon[i].y,
                    S.sc.world.beacon[i].diameter);
        fclose(f);
        f = open_log(log_dir, "path.csv", "s_m,x_m,y_m\n");
        double sacc = 0;
        for (size_t i = 0; i < nominal.n; i++) {
            sim_piece_t part = nominal.piece[i];
            int steps = (int)ceil(part.length / 0.01);
            for (int k = 0; k <= steps; k++) {
                sim_piece_t q = part;
                q.length = part.length * k / (steps ? steps : 1);
                sim_pose_t e = sim_piece_end(&q);
                fprintf(f, "%.4f,%.6f,%.6f\n", sacc + q.length, e.x, e.y);
            }
            sacc += part.length;
        }
        fclose(f);
    }
    if (lcm_url) {
        S.lcm = lcm_create(lcm_url);
        if (!S.lcm) {
            fprintf(stderr, "agv-sim: cannot open LCM at %s\n", lcm_url);
            return 2;
        }
    }

    /* ---- run ---- */
    struct timespec w0, w1;
    clock_gettime(CLOCK_MONOTONIC, &w0);
    posix_board_select(S.nav_b);
    hal_irq_enable();
    posix_board_select(S.main_b);
    hal_irq_enable();
    /* The mirror turns from t = 0: the first index pulse comes after a random part of a turn. */
    sim_rng_t rng_phase;
    sim_rng_seed(&rng_phase, S.sc.seed, 2);
    S.t_index = -sim_rng_uniform(&rng_phase) / S.gcfg.rev_per_s;
    S.next_log = 0.0;
    posix_schedule(0, sample, 0);
    schedule_all();
    main_board_start();

    uint64_t end_ns = NS(S.sc.duration);
    double done_at = -1, next_progress = 0.1;
    double wall_next = 0;
    main_board_stats_t ms;
    while (posix_next_event_ns() <= end_ns) {
        posix_run_until(posix_next_event_ns());
        for (int pass = 0; pass < 8; pass++) {
            int any = 0;
            if (posix_board_take_wake(S.nav_b)) {
                run_board(S.nav_b);
                any = 1;
            }
            if (posix_board_take_wake(S.main_b)) {
                run_board(S.main_b);
                any = 1;
            }
            if (!any)
                break;
        }
        drive_state_t st = main_board_state();
        if ((st == DRIVE_ST_DONE || st == DRIVE_ST_FAULT) && done_at < 0)
            done_at = now_s();
        if (done_at >= 0 && S.v == 0 && !S.braking && now_s() > done_at + 0.5)
            break; /* finished and standing */
        if (!S.quiet) {
            double frac = now_s() / S.sc.duration;
            clock_gettime(CLOCK_MONOTONIC, &w1);
            double wall =
                (double)(w1.tv_sec - w0.tv_sec) + 1e-9 * (double)(w1.tv_nsec - w0.tv_nsec);
            if (frac >= next_progress || wall >= wall_next) {
                fprintf(stderr, "agv-sim: %s t=%.1f/%.0f s, fixes %u/%u accepted, state %s\n",
                        S.sc.name, now_s(), S.sc.duration, S.rep.fixes_accepted,
                        S.rep.fixes_attempted, drive_seq_state_name(main_board_state()));
                while (next_progress <= frac)
                    next_progress += 0.1;
                wall_next = wall + 2.0;
            }
        }
    }
    S.done = 1;
    clock_gettime(CLOCK_MONOTONIC, &w1);

    /* ---- report ---- */
    sim_report_t *r = &S.rep;
    snprintf(r->scenario, sizeof r->scenario, "%s", S.sc.name);
    r->seed = S.sc.seed;
    r->full_travel = S.sc.full_travel;
    r->sim_time = now_s();
    r->wall_time = (double)(w1.tv_sec - w0.tv_sec) + 1e-9 * (double)(w1.tv_nsec - w0.tv_nsec);
    posix_board_select(S.main_b);
    main_board_stats(&ms);
    r->reached_goal = ms.done && !ms.fault && !ms.stop_requested;
    sim_pose_t end = truth_at(now_s());
    const sim_waypoint_t *goal = &S.sc.path[S.sc.n_path - 1];
    r->final_error = hypot(end.x - goal->x, end.y - goal->y);
    struct {
        const char *name;
        int board, vector, bit;
    } isrs[] = {
        {"main.index_pulse", S.main_b, HAL_VEC_TIMERA0, HAL_CAPTURE_INDEX},
        {"main.sighting_edge", S.main_b, HAL_VEC_TIMERA1, HAL_CAPTURE_BEACON},
        {"main.delta_s", S.main_b, HAL_VEC_PORT2, 0},
        {"main.link_rx", S.main_b, HAL_VEC_LINK_RX, 0},
        {"main.clock_tick", S.main_b, HAL_VEC_TIMERB0, 0},
        {"nav.delta_l", S.nav_b, HAL_VEC_PORT1, 4},
        {"nav.gyro_up", S.nav_b, HAL_VEC_PORT1, 5},
        {"nav.gyro_down", S.nav_b, HAL_VEC_PORT1, 6},
        {"nav.beacon_sighted", S.nav_b, HAL_VEC_PORT1, 7},
        {"nav.coord_request", S.nav_b, HAL_VEC_NMI, 0},
        {"nav.link_rx", S.nav_b, HAL_VEC_LINK_RX, 0},
    };
    for (size_t i = 0; i < sizeof isrs / sizeof isrs[0] && i < SIM_MAX_ISR_NAMES; i++) {
        int src = posix_source_find(isrs[i].board, isrs[i].vector, isrs[i].bit);
        r->isr_name[r->n_isr] = isrs[i].name;
        r->isr_count[r->n_isr++] = src >= 0 ? posix_source_count(isrs[i].board, src) : 0;
    }
    if (report) {
        if (sim_report_write(r, report)) {
            fprintf(stderr, "agv-sim: cannot write %s: %s\n", report, strerror(errno));
            return 2;
        }
    } else {
        char *text = sim_report_json(r);
        puts(text);
        free(text);
    }
    if (S.f_truth)
        fclose(S.f_truth);
    if (S.f_est)
        fclose(S.f_est);
    if (S.f_fix)
        fclose(S.f_fix);
    if (S.f_cmd)
        fclose(S.f_cmd);
    if (S.lcm)
        lcm_destroy(S.lcm);

    /* ---- success criteria ---- */
    const sim_success_t *sc = &S.sc.success;
    int ok = 1;
    char why[512] = "";
    size_t wl = 0;
#define MISS(...)                                                                                  \
    do {                                                                                           \
        ok = 0;                                                                                    \
        wl += (size_t)snprintf(why + wl, sizeof why - (wl < sizeof why ? wl : sizeof why),         \
                               __VA_ARGS__);                                                       \
    } while (0)
    if (sc->require_goal && !r->reached_goal)
        MISS(" goal not reached (%s);", ms.fault            ? "fault"
                                        : ms.stop_requested ? "stop request: no fix for too long"
                                                            : "time out");
    if (sim_stat_mean(&r->cross_track) > sc->max_cross_track_mean)
        MISS(" cross-track mean %.4f m > %.4f;", sim_stat_mean(&r->cross_track),
             sc->max_cross_track_mean);
    if (r->cross_track.n && r->cross_track.max > sc->max_cross_track_max)
        MISS(" cross-track max %.4f m > %.4f;", r->cross_track.max, sc->max_cross_track_max);
    if (r->final_error > sc->max_final_error)
        MISS(" final error %.4f m > %.4f;", r->final_error, sc->max_final_error);
    if (r->fix_error.n && r->fix_error.max > sc->max_fix_error)
        MISS(" fix error max %.4f m > %.4f;", r->fix_error.max, sc->max_fix_error);
    double ratio = r->fixes_attempted ? (double)r->fixes_accepted / r->fixes_attempted : 0.0;
    if (ratio < sc->min_fix_ratio)
        MISS(" %.0f%% of fixes accepted < %.0f%%;", 100 * ratio, 100 * sc->min_fix_ratio);
    if (!S.quiet)
        fprintf(stderr, "agv-sim: %s: %s%s (%.1f s simulated in %.2f s, %.0fx real time)\n",
                S.sc.name, ok ? "criteria met" : "criteria missed:", ok ? "" : why, r->sim_time,
                r->wall_time, r->wall_time > 0 ? r->sim_time / r->wall_time : 0.0);
    else if (!ok)
        fprintf(stderr, "agv-sim: %s: criteria missed:%s\n", S.sc.name, why);
    sim_stat_free(&r->fix_error);
    sim_stat_free(&r->heading_error);
    sim_stat_free(&r->cross_track);
    return ok ? 0 : 1;
}
