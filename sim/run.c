/*
 * run.c - one closed-loop run on the harness (see run.h).
 */
#include "sim/run.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "fx/fx_host.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#include "hal/pinmap.h"
#include "hal_posix/drive_port_posix.h"
#include "hal_posix/harness.h"
#include "main_board.h"
#include "nav_board.h"
#include "sim/canbus.h"
#include "sim/clock.h"
#include "sim/drive_board.h"
#include "sim/pace.h"
#include "sim/path_index.h"
#include "sim/possrc.h"
#include "sim/sensors.h"
#include "sim/socketcan.h"
#include "sim/telemetry.h"

/* The report's stop_reason of each main_board_stop_t (main_board.h has the one list). */
#define STOP_NAME(name, text) text,
static const char *const stop_names[] = {MAIN_BOARD_STOP_REASONS(STOP_NAME)};
#undef STOP_NAME

/* Everything of one run; the harness and the boards' firmware are single instances anyway. */
typedef struct {
    int main_b, nav_b;
    sim_drive_t drive;
    sim_sensors_t sensors;
    sim_possrc_t src; /* mode pursuit: the laser positioning system */
    sim_telemetry_t tm;
    sim_path_index_t nominal;
    sim_canbus_t bus;
    sim_socketcan_t sock;
} run_t;

static run_t R;

/* How long the run goes on once the travel is done and the vehicle stands, ns. */
#define DONE_HOLD_NS 500000000ull

/* An event that only marks an instant for the run loop. */
static void nothing(void *ctx, uint64_t t_ns)
{
    (void)ctx;
    (void)t_ns;
}

/* The drive board moved the vehicle differently: the sensors follow. */
static void on_motion(void *ctx, double t)
{
    (void)ctx;
    (void)t;
    sim_sensors_motion(&R.sensors);
}

/* The drive board took a command: the telemetry logs it. */
static void on_command(void *ctx, double t, const drive_event_t *ev)
{
    (void)ctx;
    sim_telemetry_command(&R.tm, t, ev);
}

/* Every write the main board makes on its drive bus reaches the drive board here. */
static void drive_sink(void *ctx, int board, const posix_drive_write_t *w)
{
    (void)board;
    sim_drive_write(ctx, w->reg, w->value);
}

static double wall_since(const struct timespec *w0)
{
    struct timespec w1;
    clock_gettime(CLOCK_MONOTONIC, &w1);
    return (double)(w1.tv_sec - w0->tv_sec) + 1e-9 * (double)(w1.tv_nsec - w0->tv_nsec);
}

/* Both boards on the harness, configured and wired to the drive board and the vehicle. */
static int boards_up(const sim_scenario_t *sc, sim_mission_t *m, int ticks, char *err,
                     size_t errlen)
{
    posix_reset();
    posix_clock_set_tickless(!ticks);
    R.main_b = posix_board_create("main");
    R.nav_b = posix_board_create("nav");
    sim_pose_t start = {sc->start_x, sc->start_y, sc->start_heading};
    sim_drive_init(&R.drive, &m->main.board, sc->wheelbase, R.main_b, start, on_motion, on_command,
                   NULL);
    posix_board_select(R.nav_b);
    hal_cpu_init();
    int rc = nav_board_init(&m->nav);
    if (rc != 0) {
        if (rc == NAV_BOARD_E_LINK)
            snprintf(err, errlen, "the nav board refuses its link configuration");
        else
            snprintf(err, errlen, "the nav board refuses the vehicle: %s", gnav_strerror(rc));
        return -1;
    }
    posix_board_select(R.main_b);
    hal_cpu_init();
    posix_drive_port_set_sink(R.main_b, drive_sink, &R.drive);
    drive_status_t ds = main_board_init(&m->main);
    if (ds != DRIVE_OK && m->main.pursuit) {
        snprintf(err, errlen, "the main board refuses pursuit mode's configuration: %s",
                 drive_status_text(ds));
        return -1;
    }
    if (ds != DRIVE_OK) {
        const drive_path_t *pp = main_board_path();
        snprintf(err, errlen, "the main board refuses the path: leg %u piece %u: %s", pp->bad_leg,
                 pp->bad_sub, drive_status_text(pp->bad_why));
        return -1;
    }
    static main_board_observer_t obs;
    obs = (main_board_observer_t){&R.tm, sim_telemetry_fix, 0, sim_telemetry_state,
                                  sim_telemetry_pursuit};
    main_board_set_observer(&obs);
    posix_signal_connect(R.main_b, HAL_SIGNAL_COORD_REQUEST, R.nav_b, HAL_EDGE_COORD_REQUEST);
    return 0;
}

/*
 * Run passes of the boards' main loops while their handlers left work. What a pass raises on
 * the other board (the coordinate request's line) is taken at once, as the pulse on the wire
 * would be, not at the next event.
 */
static void poll_boards(void)
{
    for (int pass = 0; pass < 8; pass++) {
        int any = 0;
        if (posix_board_take_wake(R.nav_b)) {
            posix_board_select(R.nav_b);
            nav_board_poll();
            posix_dispatch();
            any = 1;
        }
        if (posix_board_take_wake(R.main_b)) {
            posix_board_select(R.main_b);
            main_board_poll();
            posix_dispatch();
            any = 1;
        }
        if (!any)
            break;
    }
}

/* In the table below: the ticks the board's timer took, as on the MSP430 (tickless, the
 * harness raised only those a deadline asked for: posix_clock_ticks()). */
#define CLOCK_TICKS (-2)

/* The interrupt counts of the report: each handler of both boards, by name. */
static void count_isrs(sim_report_t *r)
{
    struct {
        const char *name;
        int board, source;
    } isrs[] = {
        {"main.index_pulse", R.main_b,
         posix_source_find(R.main_b, (int)hal_capture_vector(HAL_CAPTURE_INDEX),
                           HAL_CAPTURE_INDEX)},
        {"main.sighting_edge", R.main_b,
         posix_source_find(R.main_b, (int)hal_capture_vector(HAL_CAPTURE_BEACON),
                           HAL_CAPTURE_BEACON)},
        {"main.delta_s", R.main_b, posix_edge_source(R.main_b, HAL_EDGE_DELTA_S)},
        {"main.can_rx", R.main_b, posix_source_find(R.main_b, HAL_CAN0_VECTOR, HAL_CAN0_INT_PIN)},
        {"main.clock_tick", R.main_b, CLOCK_TICKS},
        {"main.uart0_rx", R.main_b, posix_uart_source(R.main_b, 0)},
        {"main.uart1_rx", R.main_b, posix_uart_source(R.main_b, 1)},
        {"nav.delta_l", R.nav_b, posix_edge_source(R.nav_b, HAL_EDGE_DELTA_L)},
        {"nav.gyro_up", R.nav_b, posix_edge_source(R.nav_b, HAL_EDGE_GYRO_UP)},
        {"nav.gyro_down", R.nav_b, posix_edge_source(R.nav_b, HAL_EDGE_GYRO_DOWN)},
        {"nav.beacon_sighted", R.nav_b, posix_edge_source(R.nav_b, HAL_EDGE_BEACON_SIGHTED)},
        {"nav.coord_request", R.nav_b, posix_edge_source(R.nav_b, HAL_EDGE_COORD_REQUEST)},
        {"nav.can_rx", R.nav_b, posix_source_find(R.nav_b, HAL_CAN0_VECTOR, HAL_CAN0_INT_PIN)},
        {"nav.clock_tick", R.nav_b, CLOCK_TICKS},
    };
    for (size_t i = 0; i < sizeof isrs / sizeof isrs[0] && i < SIM_MAX_ISR_NAMES; i++) {
        r->isr_name[r->n_isr] = isrs[i].name;
        r->isr_count[r->n_isr++] = isrs[i].source == CLOCK_TICKS ? posix_clock_ticks(isrs[i].board)
                                   : isrs[i].source >= 0
                                       ? posix_source_count(isrs[i].board, isrs[i].source)
                                       : 0;
    }
}

/* Mode pursuit: the main board's counters and the positioning system's (main board selected). */
static void pursuit_report(sim_pursuit_report_t *p)
{
    main_pursuit_stats_t ps;
    main_pursuit_stats(&ps);
    p->updates = ps.law.updates;
    p->error_mean = ps.law.updates ? (double)ps.law.err_sum / 65536.0 / ps.law.updates : 0.0;
    p->error_max = fx_q16_to_double(ps.law.err_max);
    p->n_receivers = (uint32_t)R.src.n_rcv;
    for (int k = 0; k < 2; k++) {
        p->rx[k].framed = ps.rx[k].framed;
        for (int i = 0; i < POSRX_REASON_COUNT; i++)
            p->rx[k].reason[i] = ps.rx[k].reason[i];
        p->rx[k].resyncs = ps.rx[k].resyncs;
        p->rx[k].skipped = ps.rx[k].skipped;
        p->rx[k].error_bytes = ps.rx[k].error_bytes;
        p->rx[k].dropped = ps.rx[k].dropped;
        p->rx[k].overruns = ps.overruns[k];
    }
    /* refused by the pair check: framed and judged by neither rule of the receiver */
    p->rx[0].reason[4] = ps.law.pair_rejects;
    const sim_possrc_stats_t *s = &R.src.st;
    const uint32_t src[10] = {s->updates,       s->sent,         s->outage, s->dropouts,
                              s->no_sight,      s->line_busy,    s->zeros,  s->wilds,
                              s->garbage_bytes, s->corrupt_bytes};
    memcpy(p->src, src, sizeof src);
    p->corrections = ps.law.corrections;
    p->goals = ps.law.goals;
    p->slowdowns = ps.law.slowdowns;
    p->stops = ps.law.stops;
    p->resumes = ps.law.resumes;
    p->regulations = ps.law.regulations;
    p->pair_rejects = ps.law.pair_rejects;
    p->unpaired = ps.unpaired;
    p->nav_timeouts = ps.nav_timeouts;
}

int sim_run(const sim_scenario_t *sc, sim_mission_t *m, const sim_run_options_t *o, sim_report_t *r,
            sim_run_stats_t *stats, char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    memset(stats, 0, sizeof *stats);
    memset(&R, 0, sizeof R);
    sim_pace_t check;
    if (sim_pace_start(&check, o->realtime, 0)) {
        snprintf(err, errlen, "--realtime: %g is not a factor from 0 to %g", o->realtime,
                 SIM_PACE_MAX_FACTOR);
        return -1;
    }
    if (boards_up(sc, m, o->ticks, err, errlen))
        return -1;
    sim_sensors_init(&R.sensors, sc, &R.drive.seg, R.main_b, R.nav_b);
    if (sim_path_index_build(&R.nominal, &m->nominal)) {
        snprintf(err, errlen, "out of memory for the nominal path's index");
        return -1;
    }
    R.tm.trace = o->trace;
    R.sock.fd = -1;
    if (sim_telemetry_open(&R.tm, o->log_dir, o->lcm_url, sc, &m->nominal, err, errlen)) {
        sim_path_index_free(&R.nominal);
        return -1;
    }
    if ((o->can && sim_socketcan_open(&R.sock, o->can, err, errlen)) ||
        sim_canbus_start(&R.bus, sc, R.main_b, R.nav_b, o->candump, o->can ? o->can : "vcan0",
                         o->trace, err, errlen)) {
        sim_canbus_close(&R.bus);
        sim_socketcan_close(&R.sock);
        sim_telemetry_close(&R.tm);
        sim_path_index_free(&R.nominal);
        return -1;
    }
    if (o->can)
        posix_can_set_carrier(sim_socketcan_carry, &R.sock);

    struct timespec w0, c0, c1;
    clock_gettime(CLOCK_MONOTONIC, &w0);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
    posix_board_select(R.nav_b);
    hal_irq_enable();
    posix_board_select(R.main_b);
    hal_irq_enable();
    sim_telemetry_start(&R.tm, &R.drive, &R.sensors, &R.nominal, R.nav_b, r);
    sim_sensors_motion(&R.sensors);
    sim_drive_schedule(&R.drive, sim_clock_now());
    int pursuit = m->main.pursuit != NULL;
    if (pursuit) {
        sim_possrc_init(&R.src, sc, &R.drive, R.main_b);
        sim_telemetry_pursuit_start(&R.tm, &R.src, sc);
        sim_possrc_start(&R.src);
    }
    main_board_start();

    uint64_t end_ns = sim_clock_ns(sc->duration), next_ns, done_ns = 0;
    double done_at = -1, standstill_at = -1, next_progress = 0.1, wall_next = 0;
    int ended = 0;
    sim_pace_t pace;
    sim_pace_start(&pace, o->realtime, posix_now_ns()); /* the factor was checked above */
    while ((next_ns = posix_next_event_ns()) <= end_ns) {
        if (o->realtime > 0 || done_at >= 0) {
            /* instant by instant: --realtime paces each, the end comes 0.5 s after done */
            sim_pace_wait(&pace, next_ns); /* the wall clock catches up (waits only) */
            stats->events += posix_run_until(next_ns);
        } else {
            /* the instants at which no board wakes and the main board takes no interrupt
             * change nothing this loop looks at (the drive board's events say so too) */
            stats->events += posix_run_steps(end_ns, R.main_b);
        }
        poll_boards();
        if (R.sock.failed)
            break;
        double now = sim_clock_now();
        drive_state_t st = main_board_state();
        if ((st == DRIVE_ST_DONE || st == DRIVE_ST_FAULT || st == DRIVE_ST_STOPPED) &&
            done_at < 0) {
            done_at = now;
            done_ns = posix_now_ns();
            /* the instant the run may end on: not left to whatever event comes next */
            posix_schedule(done_ns + DONE_HOLD_NS + 1u, nothing, NULL);
            R.tm.travel_done = pursuit; /* pursuit stops when it is done: no more samples */
        }
        if (done_at >= 0 && standstill_at < 0 && sim_drive_standing(&R.drive))
            standstill_at = now;
        if (done_at >= 0 && sim_drive_standing(&R.drive) &&
            posix_now_ns() > done_ns + DONE_HOLD_NS) {
            ended = 1;
            break; /* finished and standing */
        }
        if (!o->quiet) {
            double frac = now / sc->duration, wall = wall_since(&w0);
            if (frac >= next_progress || wall >= wall_next) {
                fprintf(stderr, "agv-sim: %s t=%.1f/%.0f s, fixes %u/%u accepted, state %s\n",
                        sc->name, now, sc->duration, r->fixes_accepted, r->fixes_attempted,
                        pursuit ? (st == DRIVE_ST_DONE ? "done" : "pursuit")
                                : drive_seq_state_name(st));
                while (next_progress <= frac)
                    next_progress += 0.1;
                wall_next = wall + 2.0;
            }
        }
    }
    if (!ended && !R.sock.failed)
        (void)posix_run_until(end_ns); /* time is up: the run ends at the scenario's duration */
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
    stats->cpu_time_s = (double)(c1.tv_sec - c0.tv_sec) + 1e-9 * (double)(c1.tv_nsec - c0.tv_nsec);
    memcpy(stats->lcm_published, R.tm.lcm_published, sizeof stats->lcm_published);
    stats->lcm_failed = R.tm.lcm_failed;
    sim_telemetry_close(&R.tm);
    link_stats_t main_link, nav_link;
    posix_board_select(R.main_b);
    main_board_link_stats(&main_link);
    posix_board_select(R.nav_b);
    nav_board_link_stats(&nav_link);
    sim_canbus_report(&R.bus, &main_link, &nav_link, sim_clock_now(), r);
    int closed = sim_canbus_close(&R.bus);
    sim_socketcan_close(&R.sock);
    if (R.sock.failed || closed) {
        snprintf(err, errlen, "%s", R.sock.failed ? R.sock.err : "--candump: writing failed");
        sim_path_index_free(&R.nominal);
        return -1;
    }

    snprintf(r->scenario, sizeof r->scenario, "%s", sc->name);
    r->seed = sc->seed;
    r->mode = sim_scenario_mode_name(sc->mode);
    r->sim_time = sim_clock_now();
    r->wall_time = wall_since(&w0);
    main_board_stats_t ms;
    posix_board_select(R.main_b);
    main_board_stats(&ms);
    r->reached_goal = ms.done && !ms.fault && ms.stop_reason == MAIN_BOARD_STOP_NONE;
    r->stop_reason = "";
    r->stop_at = r->standstill_at = -1;
    if (!r->reached_goal) {
        /* The main board's reason; a travel still going at the end ran out of time. */
        r->stop_reason =
            ms.stop_reason != MAIN_BOARD_STOP_NONE ? stop_names[ms.stop_reason] : SIM_STOP_DURATION;
        r->stop_at = done_at >= 0 ? done_at : r->sim_time;
        r->standstill_at = standstill_at;
    }
    sim_pose_t end = sim_drive_pose(&R.drive, r->sim_time);
    const sim_waypoint_t *goal = &sc->path[sc->n_path - 1];
    r->final_error = hypot(end.x - goal->x, end.y - goal->y);
    if (pursuit)
        pursuit_report(&r->pursuit);
    count_isrs(r);

    stats->samples = R.nominal.queries;
    stats->pieces = m->nominal.n;
    stats->pieces_indexed = R.nominal.n_distinct;
    stats->pieces_examined = R.nominal.examined;
    sim_path_index_free(&R.nominal);
    return 0;
}
