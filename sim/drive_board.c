/*
 * drive_board.c - the drive board and the vehicle it moves (see drive_board.h).
 */
#include "sim/drive_board.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fx/fx_host.h"
#include "sim/clock.h"

static void on_event(void *ctx, uint64_t t_ns);

void sim_drive_init(sim_drive_t *d, const drive_board_t *units, double wheelbase, int main_board,
                    sim_pose_t start, sim_drive_motion_fn on_motion,
                    sim_drive_command_fn on_command, void *ctx)
{
    memset(d, 0, sizeof *d);
    d->units = *units;
    d->wheelbase = wheelbase;
    d->main_board = main_board;
    drive_decoder_init(&d->dec, units->dac_center);
    d->cur = 2;
    d->seg = sim_segment(0.0, start, 0.0, 0.0, 0.0, wheelbase);
    d->on_motion = on_motion;
    d->on_command = on_command;
    d->ctx = ctx;
}

void sim_drive_command_si(const sim_drive_t *d, const drive_cmd_t *cmd, double steer_deg[2],
                          double length_m[2], double *speed_mps)
{
    for (int i = 0; i < 2; i++) {
        steer_deg[i] = (128 - cmd->steer[i]) * 180.0 / 256;
        length_m[i] = cmd->arc[i] / fx_q16_to_double(d->units.counts_per_m);
    }
    *speed_mps = cmd->speed * fx_q16_to_double(d->units.speed_lsb);
}

sim_pose_t sim_drive_pose(const sim_drive_t *d, double t)
{
    return sim_segment_pose(&d->seg, t);
}

int sim_drive_standing(const sim_drive_t *d)
{
    return d->v == 0 && !d->braking;
}

/*
 * Account the rear-axle travel since the segment began to the arc being driven; while braking,
 * the commanded speed follows the ramp (the speed at @p t).
 */
static void arc_progress(sim_drive_t *d, double t)
{
    if (d->cur < 2)
        d->arc[d->cur].left -= fabs(sim_segment_travel(&d->seg, t));
    if (d->braking)
        d->v = sim_segment_speed(&d->seg, t);
}

/* A new constant-steering piece of motion from @p t, braking or not (after arc_progress). */
static void new_segment(sim_drive_t *d, double t)
{
    sim_pose_t p = sim_drive_pose(d, t);
    double front = sim_segment_front(&d->seg, t);
    if (d->cur < 2)
        d->alpha = d->arc[d->cur].alpha;
    double v = d->cur < 2 || d->dac ? d->v : 0.0;
    d->seg = sim_segment(t, p, front, d->alpha, v, d->wheelbase);
    d->seg.decel = d->braking ? SIM_DRIVE_BRAKE : 0.0;
    if (d->on_motion)
        d->on_motion(d->ctx, t);
    sim_drive_schedule(d, t);
}

void sim_drive_schedule(sim_drive_t *d, double t)
{
    sim_clock_cancel(&d->ev);
    double v = fabs(d->seg.v);
    double next = INFINITY;
    if (d->braking)
        next = sim_segment_stop_time(&d->seg);
    if (d->cur < 2 && v > 0) {
        const sim_drive_arc_t *a = &d->arc[d->cur];
        double ds = a->pulse ? a->left : a->left - SIM_DRIVE_DS_MARGIN;
        if (ds < 0)
            ds = 0;
        if (d->seg.decel > 0.0) /* the travel to go counts from t */
            next = fmin(next, sim_segment_time_at_travel(
                                  &d->seg, fabs(sim_segment_travel(&d->seg, t)) + ds));
        else
            next = fmin(next, t + ds / v);
    }
    if (isfinite(next))
        d->ev = sim_clock_schedule(next, on_event, d);
}

static void on_event(void *ctx, uint64_t t_ns)
{
    sim_drive_t *d = ctx;
    d->ev = 0;
    posix_run_stop(); /* the run loop looks at the vehicle's standing */
    double t = sim_clock_s(t_ns);
    int changed = 0;
    arc_progress(d, t);
    if (d->cur < 2) {
        sim_drive_arc_t *a = &d->arc[d->cur];
        if (!a->pulse && a->left <= SIM_DRIVE_DS_MARGIN + 1e-9) {
            a->pulse = 1;
            posix_edge_raise(d->main_board, HAL_EDGE_DELTA_S);
        }
        if (a->left <= 1e-9) {
            d->cur++;
            if (d->cur == 1 && d->arc[1].left <= 0)
                d->cur = 2;
            if (d->cur == 2)
                d->v = 0; /* the double arc is done: the board stops */
            changed = 1;
        }
    }
    if (d->braking && t >= sim_segment_stop_time(&d->seg) - 1e-9) {
        d->v = 0; /* braked to a stand */
        d->braking = 0;
        changed = 1;
    }
    if (changed) {
        new_segment(d, t);
    } else {
        /* Only a delta-S went out: keep moving, restart the arc bookkeeping from here. */
        double decel = d->seg.decel;
        d->seg = sim_segment(t, sim_drive_pose(d, t), sim_segment_front(&d->seg, t), d->alpha,
                             sim_segment_speed(&d->seg, t), d->wheelbase);
        d->seg.decel = decel;
        sim_drive_schedule(d, t);
    }
}

void sim_drive_write(sim_drive_t *d, uint8_t reg, uint8_t value)
{
    drive_event_t ev;
    if (!drive_decoder_feed(&d->dec, reg, value, &ev))
        return;
    double t = sim_clock_now();
    if (d->braking)
        d->v = sim_segment_speed(&d->seg, t); /* the ramp's speed now */
    double L = d->wheelbase;
    double cpm = fx_q16_to_double(d->units.counts_per_m),
           lsb = fx_q16_to_double(d->units.speed_lsb);
    if (ev.type == DRIVE_EV_LOAD) {
        if (d->on_command)
            d->on_command(d->ctx, t, &ev);
        arc_progress(d, t);
        for (int i = 0; i < 2; i++) {
            double alpha = (128 - ev.cmd.steer[i]) * M_PI / 256;
            double k = tan(alpha) / L;
            d->arc[i].alpha = alpha;
            d->arc[i].left = ev.cmd.arc[i] / cpm / sqrt(1 + L * L * k * k);
            d->arc[i].pulse = ev.cmd.arc[i] < d->units.min_pulse_counts;
        }
        d->cur = d->arc[0].left > 0 ? 0 : (d->arc[1].left > 0 ? 1 : 2);
        d->braking = 0;
        d->v = ev.cmd.speed * lsb;
        if (d->cur == 2)
            d->v = 0;
        new_segment(d, t);
    } else if (ev.type == DRIVE_EV_SPEED) {
        if (d->on_command)
            d->on_command(d->ctx, t, &ev);
        arc_progress(d, t);
        if (ev.cmd.speed == 0 && d->v != 0) {
            d->braking = 1;
        } else {
            d->braking = 0;
            d->v = ev.cmd.speed * lsb;
        }
        new_segment(d, t);
    } else if (ev.type == DRIVE_EV_DAC_ANGLE || ev.type == DRIVE_EV_DAC_SPEED ||
               ev.type == DRIVE_EV_OUTPUTS) {
        if (d->on_command)
            d->on_command(d->ctx, t, &ev);
        double alpha = d->alpha, v = d->v;
        int braking = d->braking;
        if (ev.type == DRIVE_EV_DAC_ANGLE) {
            double lim = atan(L / fx_q16_to_double(d->units.min_radius));
            double a = (double)(int32_t)ev.alpha * (M_PI / 2147483648.0);
            alpha = a > lim ? lim : a < -lim ? -lim : a;
        } else if (ev.type == DRIVE_EV_DAC_SPEED) {
            d->dac_v = ev.cmd.speed * lsb;
        } else {
            d->outputs = ev.value;
        }
        int moving = !(d->outputs & DRIVE_OUT_DRIVE_OFF) && (d->outputs & DRIVE_OUT_BRAKE_REL);
        double want = moving ? d->dac_v : 0.0;
        if (want == 0.0 && v != 0.0) {
            braking = 1;
        } else {
            braking = 0;
            v = want;
        }
        if (d->dac && d->cur == 2 && alpha == d->alpha && v == d->v && braking == d->braking)
            return; /* the same motion: nothing to reschedule */
        arc_progress(d, t);
        d->dac = 1;
        d->cur = 2; /* no arcs in this style */
        d->alpha = alpha;
        d->v = v;
        d->braking = braking;
        new_segment(d, t);
    } else if (ev.type == DRIVE_EV_ERROR) {
        fprintf(stderr, "agv-sim: drive board: protocol error %d at t=%.4f s\n", ev.error, t);
    }
}
