/*
 * main_beacon.c - the main board's beacon travel (see main_beacon.h, main_board.h and
 * docs/integration.md): goniometer capture, the optical fix with its gate, the travel
 * sequencer's double arcs and the drive board's port.
 *
 * Handlers (interrupt context) only count and queue: index pulses, photodetector rising edges
 * (numbered as the nav board numbers its latches), delta-S pulses, the nav board's latches and
 * acknowledgements (main_board.c hands them over from the link). The main loop turns them into
 * travel-sequencer events, executes the sequencer's actions and runs the long computations
 * (the optical fix, the double arc).
 */
#include "main_beacon.h"

#include "drive/drive_proto.h"
#include "hal/capture.h"
#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/drive_port.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal/signal.h"
#include "link/link.h"

/* Waiting for the nav board: latches, the fix's acknowledgement, the pose. */
#define LATCH_TIMEOUT_MS 100u
#define ACK_TIMEOUT_MS   50u
#define POSE_TIMEOUT_MS  50u
#define EVENT_QUEUE      2u /* at most one follow-up waits while an event is stepped */

enum { FIX_IDLE = 0, FIX_WAIT_LATCHES };
enum { POSE_IDLE = 0, POSE_WAIT_ACK, POSE_WAIT_REPLY };

static struct {
    /* configuration (by reference: a constant in flash on the target) */
    const main_board_config_t *cfg;
    /* modules */
    optical_capture_t cap;
    drive_ds_t ds;
    drive_path_t path;
    drive_seq_t seq;
    /* handlers -> main loop */
    uint16_t rises;            /* photodetector rising edges so far (= the nav board's latches) */
    uint16_t rise_at_rev[4];   /* rises when revolution (seq & 3) started */
    volatile uint16_t indexes; /* index pulses not yet fed to the sequencer */
    uint8_t ack_in;            /* FIX_ACK received */
    int8_t ack_status;
    /* the fix in progress */
    uint8_t fix_state;
    uint32_t fix_deadline;
    uint8_t n;                /* sightings of the revolution */
    uint16_t latch_first;     /* latch number of the first sighting in time */
    uint16_t latch_have;      /* bit i: latch first + i arrived */
    const optical_rev_t *rev; /* the revolution held while its fix runs */
    /* The nav board's latches: capture order at rising edges as they arrive, then (in place)
     * sorted order at the pulse centres for optical_fix(). */
    optical_pose_t latched[OPTICAL_MAX_SIGHTINGS];
    optical_pose_t approx; /* the last sighting's latch: the reference instant */
    optical_fix_t fix;
    uint16_t fix_ref; /* reference latch of the last good fix */
    /* What dead reckoning is worth (O6): its uncertainty since the last accepted fix, grown
     * from one attempt's reference pose to the next (last). */
    optical_unc_t unc;
    optical_pose_t last;
    /* the pose request */
    uint8_t pose_state;
    uint16_t pose_ms;
    uint32_t pose_deadline;
    /* timer and the loaded double arc */
    uint8_t timer_on;
    uint32_t timer_deadline;
    drive_cmd_t loaded;
    uint8_t reverse;
    /* events produced by actions, fed back in order */
    drive_seq_event_t queue[EVENT_QUEUE];
    uint8_t q_head, q_n;
} bt;

/* ------------------------------------------------------------------ handlers */

static void on_index(void *arg, uint16_t count, uint8_t rising)
{
    uint16_t started = bt.cap.seq;
    optical_capture_on_index(arg, count, rising);
    if (bt.cap.seq != started)
        bt.rise_at_rev[bt.cap.seq & 3u] = bt.rises; /* the revolution that starts now */
    bt.indexes++;
    hal_cpu_wake();
}

static void on_edge(void *arg, uint16_t count, uint8_t rising)
{
    if (rising)
        bt.rises++; /* every edge, captured or not: the nav board latches every one */
    optical_capture_on_edge(arg, count, rising);
}

static void on_ds(void *arg)
{
    drive_ds_handler(arg);
    hal_cpu_wake();
}

/*
 * &bt.latched[i] without a multiply: on_frame runs in the link's receive interrupt, and no
 * interrupt handler of the main board may use the hardware multiplier (the optical kernels use
 * it with interrupts enabled; tools/stack_bound.py --no-mpy-in-isr checks the image). The
 * empty asm hides one shift from the compiler, which would otherwise fold 8i + 4i into a
 * multiplication by 12.
 */
_Static_assert(sizeof(optical_pose_t) == 12, "latched_at: 12-byte poses");

static optical_pose_t *latched_at(uint16_t i)
{
    uint16_t i8 = (uint16_t)(i << 3);
    __asm__("" : "+r"(i8));
    return (optical_pose_t *)(void *)((uint8_t *)bt.latched + i8 + (uint16_t)(i << 2));
}

bool main_beacon_on_msg(const linkmsg_t *m)
{
    switch (m->type) {
    case LINKMSG_LATCH: {
        uint16_t i = (uint16_t)(m->u.latch.seq - bt.latch_first);
        if (bt.fix_state == FIX_WAIT_LATCHES && i < bt.n && m->u.latch.status == 0) {
            optical_pose_t *p = latched_at(i);
            p->x = m->u.latch.pose.x;
            p->y = m->u.latch.pose.y;
            p->heading = m->u.latch.pose.heading;
            bt.latch_have |= (uint16_t)(1u << i);
        }
        return true;
    }
    case LINKMSG_FIX_ACK:
        bt.ack_in = 1;
        bt.ack_status = m->u.fix_ack.status;
        return true;
    default:
        return false;
    }
}

/* ------------------------------------------------------------------ helpers */

static void push(drive_evt_t type, const optical_pose_t *p)
{
    if (bt.q_n >= EVENT_QUEUE)
        return; /* cannot happen: an event's actions push at most one follow-up */
    drive_seq_event_t *e = &bt.queue[(bt.q_head + bt.q_n) % EVENT_QUEUE];
    e->type = type;
    if (p) {
        e->pose.x = p->x;
        e->pose.y = p->y;
        e->pose.heading = p->heading;
    } else {
        e->pose = bt.cfg->start; /* DRIVE_EVT_START reads it; the others carry no pose */
    }
    bt.q_n++;
}

/* Queue an event without a pose (drain() steps it). */
static void post(drive_evt_t type)
{
    push(type, 0);
}

/*
 * The drive board's port: the double arc @p cmd, or the speed @p speed (main_board.c sets the
 * port up). Not inlined: the write buffer stays off the stack while the sequencer solves.
 */
enum { PORT_LOAD, PORT_SPEED };
static __attribute__((noinline)) void port(uint8_t what, const drive_cmd_t *cmd, int8_t speed)
{
    drive_wseq_t w;
    if (what == PORT_LOAD)
        drive_ppi_load(cmd, &w);
    else
        drive_ppi_speed(speed, &w);
    drive_port_send(&w);
}

/* Tell the observer (the host's telemetry) about a fix attempt; not inlined: the event
 * stays off the stack of the paths that do not report. */
static __attribute__((noinline)) void notify_fix(int8_t status, const optical_sighting_t *s,
                                                 uint8_t n, uint16_t ref_latch)
{
    if (!main_board_common.obs.on_fix)
        return;
    main_board_fix_event_t ev;
    ev.status = status;
    ev.n = n;
    ev.ref_latch = ref_latch;
    ev.fix = bt.fix;
    ev.approx = bt.approx;
    ev.s = s;
    main_board_common.obs.on_fix(main_board_common.obs.ctx, &ev);
}

static void correct_nav(void);

/* The attempt on the held revolution ended with @p status; @p s: its @p n sightings. */
static void fix_done(int8_t status, const optical_sighting_t *s, uint8_t n)
{
    uint16_t ref_latch = (uint16_t)(bt.latch_first + (n > 0 ? n - 1u : 0u));
    if (status == OPTICAL_E_REV) /* (optical_fix did not run: no solution, nothing stale) */
        bt.fix.quality = UINT32_MAX;
    bt.fix_state = FIX_IDLE;
    optical_capture_release(&bt.cap);
    if (status == OPTICAL_OK) {
        main_board_common.stats.fixes_ok++;
        bt.fix_ref = ref_latch;
        /* Simplified travel drives from the fix alone (seed 5.2, written when the ground
         * navigator did not work yet); the nav board is corrected all the same, so that its
         * stop request (G6) watches real dead reckoning. */
        if (bt.cfg->seq_cfg.mode == DRIVE_MODE_SIMPLIFIED)
            correct_nav();
        push(DRIVE_EVT_FIX_READY, &bt.fix.pose);
    } else {
        main_board_common.stats.fixes_failed++;
        push(DRIVE_EVT_FIX_FAILED, 0);
    }
    notify_fix(status, s, n, ref_latch);
}

/* A revolution with too few sightings (or an implausible one) fails at once. */
static __attribute__((noinline)) void fix_too_few(void)
{
    optical_sighting_t s[OPTICAL_MAX_SIGHTINGS];
    int8_t n = optical_rev_sightings(bt.rev, bt.cfg->counts_per_turn, s);
    bt.fix.status = n < 0 ? OPTICAL_E_REV : OPTICAL_E_FEW;
    bt.fix.quality = UINT32_MAX; /* (optical_fix does not run: no solution) */
    fix_done((int8_t)bt.fix.status, s, n < 0 ? 0u : (uint8_t)n);
}

/*
 * Start the fix of the revolution that just ended: ask for its latches. Its sightings are
 * converted and sorted when the latches are in (fix_finish), on that call's stack: RAM is
 * short, and the main loop's deepest path (the double arc) never runs at the same time.
 */
static void fix_start(void)
{
    const optical_rev_t *rev = optical_capture_take(&bt.cap);
    bt.fix.status = OPTICAL_E_REV;
    if (!rev) {
        bt.n = 0;
        bt.approx = (optical_pose_t){0, 0, 0};
        main_board_common.stats.fixes_failed++;
        push(DRIVE_EVT_FIX_FAILED, 0);
        notify_fix(OPTICAL_E_REV, 0, 0, 0);
        return;
    }
    bt.rev = rev;
    bt.n = rev->n;
    if (bt.n < 3) {
        fix_too_few();
        return;
    }
    /* A pulse that began before the index pulse rose in the previous revolution. */
    uint16_t first = bt.rise_at_rev[rev->seq & 3u];
    if (rev->s[0].start >= bt.cfg->counts_per_turn)
        first--;
    hal_critical_enter();
    bt.latch_first = first;
    bt.latch_have = 0;
    bt.fix_state = FIX_WAIT_LATCHES;
    hal_critical_exit();
    bt.fix_deadline = hal_clock_ms() + LATCH_TIMEOUT_MS;
    linkmsg_t m;
    m.type = LINKMSG_LATCH_REQ;
    m.u.latch_req.first = first;
    m.u.latch_req.count = (uint8_t)bt.n;
    link_send(&main_board_common.link, &m);
}

/* Rising edge of capture-order sighting i, counts after its revolution's index pulse. */
static int32_t rise_of(uint8_t i)
{
    uint16_t st = bt.rev->s[i].start;
    return st >= bt.cfg->counts_per_turn ? (int32_t)st - 65536l : (int32_t)st;
}

/*
 * The nav board latches at the pulse's rising edge; the sighting is the pulse's centre, half
 * a width later (up to a few ms: millimetres at 1 m/s). Each sighting's pose is interpolated
 * between its latch and the next one (extrapolated for the last) by the angle clock, which
 * is time; then the poses are put in the sightings' (angle) order. In place: RAM is short.
 */
static __attribute__((noinline)) void centre_and_sort(const uint8_t *order)
{
    optical_pose_t *l = bt.latched;
    uint8_t n = bt.n;
    optical_pose_t before_last = l[n - 2]; /* the last one extrapolates from it */
    for (uint8_t i = 0; i < n; i++) {
        uint8_t a = i + 1u < n ? i : (uint8_t)(i - 1u), b = (uint8_t)(a + 1u);
        const optical_pose_t pa = i + 1u < n ? l[a] : before_last, pb = l[b];
        int32_t span = rise_of(b) - rise_of(a);
        int32_t half = (int32_t)((bt.rev->s[i].width + 1u) >> 1);
        int32_t frac = 0; /* Q16 */
        if (span > 0 && fx_div_shift(half, span, 16, &frac)) {
            l[i].x += fx_mul_q16(pb.x - pa.x, frac);
            l[i].y += fx_mul_q16(pb.y - pa.y, frac);
            l[i].heading += (fx_angle_t)fx_mul_q16((int32_t)(pb.heading - pa.heading), frac);
        }
    }
    /* Permute in place: capture-order i goes to the sorted position j with order[j] == i. */
    uint16_t done = 0;
    for (uint8_t j = 0; j < n; j++) {
        if (done & (1u << j))
            continue;
        optical_pose_t first = l[j];
        uint8_t k = j;
        while (order[k] != j) {
            l[k] = l[order[k]];
            done |= (uint16_t)(1u << k);
            k = order[k];
        }
        l[k] = first;
        done |= (uint16_t)(1u << k);
    }
}

/* The dead reckoning's uncertainty grown from the last attempt's reference pose to this one's
 * (bt.approx): the straight distance and the heading change between them (revolutions come
 * half a second apart: the chord is the travel). */
static __attribute__((noinline)) void grow_unc(void)
{
    int32_t dx = bt.approx.x - bt.last.x, dy = bt.approx.y - bt.last.y;
    int32_t dh = (int32_t)(bt.approx.heading - bt.last.heading);
    uint32_t d = fx_hypot(dx, dy);
    optical_unc_grow(&bt.cfg->optical, &bt.unc, d > (uint32_t)INT32_MAX ? INT32_MAX : (fx_q16_t)d,
                     dh < 0 ? 0u - (uint32_t)dh : (uint32_t)dh);
}

/* All latches in (or the wait is over): run the optical pipeline. */
static __attribute__((noinline)) void fix_finish(void)
{
    optical_sighting_t s[OPTICAL_MAX_SIGHTINGS];
    uint8_t order[OPTICAL_MAX_SIGHTINGS]; /* sorted position -> capture order */
    int8_t n = optical_rev_order(bt.rev, bt.cfg->counts_per_turn, s, order);
    uint16_t all = (uint16_t)((1u << bt.n) - 1u);
    bt.fix.status = OPTICAL_E_REV;
    if (n != (int8_t)bt.n) { /* implausible: the period or a lost capture */
        fix_done(OPTICAL_E_REV, s, 0);
        return;
    }
    if (bt.latch_have != all) {
        main_board_common.stats.latch_timeouts++;
        fix_done(OPTICAL_E_REV, s, bt.n);
        return;
    }
    /* Reference instant: the last sighting's rising edge; its latch is the approximate pose
     * and the nav board applies the fix to that latch. */
    bt.approx = bt.latched[bt.n - 1];
    centre_and_sort(order);
    grow_unc();
    int8_t st = optical_fix(&bt.cfg->map, &bt.cfg->optical, &bt.approx, &bt.unc, s, bt.n,
                            bt.latched, &bt.fix);
    if (st == OPTICAL_OK) {
        optical_unc_after_fix(&bt.cfg->optical, &bt.fix, &bt.unc);
        bt.last = bt.fix.pose;
    } else {
        bt.last = bt.approx;
    }
    fix_done(st, s, bt.n);
}

/* @p v saturated to 16 bits */
static uint16_t sat16(uint32_t v)
{
    return v > 0xFFFFu ? 0xFFFFu : (uint16_t)v;
}

/* Send the fix to the nav board (Buffer Full) for its reference latch. */
static void correct_nav(void)
{
    linkmsg_t m;
    m.type = LINKMSG_FIX;
    m.u.fix.pose.x = bt.fix.pose.x;
    m.u.fix.pose.y = bt.fix.pose.y;
    m.u.fix.pose.heading = bt.fix.pose.heading;
    m.u.fix.latch = bt.fix_ref;
    m.u.fix.flags = LINKMSG_FIX_HAS_REF;
    hal_critical_enter();
    bt.ack_in = 0;
    hal_critical_exit();
    link_send(&main_board_common.link, &m);
    /* and its quality (docs/optical.md O6) in the firmware's units, saturated */
    m.type = LINKMSG_FIX_QUALITY;
    m.u.fix_quality.latch = bt.fix_ref;
    m.u.fix_quality.quality = sat16(bt.fix.quality >> 2);   /* 2^-18 m per mrad */
    m.u.fix_quality.err = sat16((uint32_t)bt.fix.err >> 8); /* 2^-8 m */
    m.u.fix_quality.resid = bt.fix.resid > 0x3FFu ? 0xFFu : (uint8_t)(bt.fix.resid >> 2);
    m.u.fix_quality.agree = bt.fix.n_agree;
    link_send(&main_board_common.link, &m);
}

static void request_pose(void)
{
    hal_critical_enter();
    main_board_common.pose_in = 0;
    hal_critical_exit();
    hal_signal_pulse(HAL_SIGNAL_COORD_REQUEST);
    bt.pose_state = POSE_WAIT_REPLY;
    bt.pose_deadline = hal_clock_ms() + POSE_TIMEOUT_MS;
}

/*
 * Where the vehicle will be @p ms from now: along the loaded double arc, on the arc it is on
 * (the delta-S pulses seen tell which), at the loaded speed. Errors of this guess are what
 * the next revolution's fix corrects.
 */
static __attribute__((noinline)) optical_pose_t predict(const optical_pose_t *now, uint16_t ms)
{
    optical_pose_t p = *now;
    if (ms == 0 || bt.loaded.speed == 0)
        return p;
    uint8_t seg = bt.seq.pulses_seen >= 1 && bt.loaded.arc[1] ? 1u : 0u;
    int32_t k = 0;
    if (bt.loaded.alpha[seg] != 0) {
        fx_q16_t t = fx_tan(bt.loaded.alpha[seg]);
        if (!fx_div_shift(t, bt.cfg->board.wheelbase, 28, &k))
            k = 0;
    }
    int32_t v = bt.loaded.speed < 0 ? -bt.loaded.speed : bt.loaded.speed;
    fx_q16_t rate = v * bt.cfg->board.speed_lsb;              /* m/s, Q16 */
    fx_q16_t secs = (fx_q16_t)(((uint32_t)ms << 16) / 1000u); /* s, Q16 */
    fx_q16_t dist = fx_mul_q16(rate, secs);
    drive_pose_t d = {p.x, p.y, p.heading};
    d = drive_pose_advance(&d, k, dist, bt.loaded.speed < 0);
    p.x = d.x;
    p.y = d.y;
    p.heading = d.heading;
    return p;
}

/* Not inlined: its port-write buffer stays off the stack while the sequencer solves. */
static __attribute__((noinline)) void execute(const drive_seq_out_t *out)
{
    uint16_t a = out->actions;
    if (a & DRIVE_ACT_STOP) {
        port(PORT_SPEED, 0, 0);
        bt.loaded.speed = 0;
    }
    if (a & DRIVE_ACT_REQUEST_FIX)
        fix_start();
    if (a & DRIVE_ACT_CORRECT_NAV)
        correct_nav();
    if (a & DRIVE_ACT_REQUEST_POSE) {
        bt.pose_ms = out->pose_ms;
        if (a & DRIVE_ACT_CORRECT_NAV) {
            /* The pose must include the fix: ask once the nav board installed it. */
            bt.pose_state = POSE_WAIT_ACK;
            bt.pose_deadline = hal_clock_ms() + ACK_TIMEOUT_MS;
        } else {
            request_pose();
        }
    }
    if (a & DRIVE_ACT_LOAD) {
        uint8_t reverse = out->cmd.speed < 0 ? 1u : 0u;
        if (reverse != bt.reverse) {
            linkmsg_t m;
            m.type = LINKMSG_DIR;
            m.u.dir.reverse = reverse;
            link_send(&main_board_common.link, &m);
            bt.reverse = reverse;
        }
        port(PORT_LOAD, &out->cmd, 0);
        bt.loaded = out->cmd;
        main_board_common.stats.loads++;
        if (main_board_common.obs.on_load)
            main_board_common.obs.on_load(main_board_common.obs.ctx, &out->cmd);
    }
    if (a & DRIVE_ACT_SET_SPEED) {
        port(PORT_SPEED, 0, out->speed);
        bt.loaded.speed = out->speed;
    }
    if (a & DRIVE_ACT_TIMER) {
        bt.timer_on = 1;
        bt.timer_deadline = hal_clock_ms() + out->timer_ms;
    }
    if (a & DRIVE_ACT_INDEX_ON)
        optical_capture_start(&bt.cap);
    if (a & DRIVE_ACT_INDEX_OFF)
        optical_capture_stop(&bt.cap);
    if (a & DRIVE_ACT_DONE) {
        main_board_common.stats.done = 1;
        /* Short of the goal by the sequencer's own blind-distance stop (a stop asked for over
         * the link has its reason already: stop_travel()). */
        if (out->stop == DRIVE_STOP_BLIND &&
            main_board_common.stats.stop_reason == MAIN_BOARD_STOP_NONE) {
            main_board_common.stats.stop_reason = MAIN_BOARD_STOP_BLIND_DISTANCE;
            link_set_stopped(&main_board_common.link, 1);
        }
    }
    if (a & DRIVE_ACT_FAULT) {
        main_board_common.stats.fault = 1;
        main_board_common.stats.fault_why = (uint8_t)out->fault;
        if (main_board_common.stats.stop_reason == MAIN_BOARD_STOP_NONE)
            main_board_common.stats.stop_reason =
                (uint8_t)(MAIN_BOARD_STOP_FAULT_NOT_READY + (out->fault - DRIVE_FAULT_NOT_READY));
        link_set_stopped(&main_board_common.link, 1);
    }
}

_Static_assert(MAIN_BOARD_STOP_FAULT_SOLVE - MAIN_BOARD_STOP_FAULT_NOT_READY ==
                       DRIVE_FAULT_SOLVE - DRIVE_FAULT_NOT_READY &&
                   MAIN_BOARD_STOP_FAULT_FIXES - MAIN_BOARD_STOP_FAULT_NOT_READY ==
                       DRIVE_FAULT_FIXES - DRIVE_FAULT_NOT_READY,
               "the fault stop reasons follow drive_fault_t");

/* Step the queued events in order; an event's actions may queue one follow-up. */
static void drain(void)
{
    while (bt.q_n) {
        drive_seq_out_t out;
        drive_state_t before = bt.seq.state;
        drive_seq_step(&bt.seq, &bt.queue[bt.q_head], &out); /* read in place, then freed */
        bt.q_head = (uint8_t)((bt.q_head + 1u) % EVENT_QUEUE);
        bt.q_n--;
        if (out.actions)
            execute(&out);
        if (bt.seq.state != before && main_board_common.obs.on_state)
            main_board_common.obs.on_state(main_board_common.obs.ctx, bt.seq.state);
    }
}

/* Stop the travel for @p reason (main_board_stop_t) unless it has already ended. */
static void stop_travel(uint8_t reason)
{
    if (bt.seq.state == DRIVE_ST_DONE || bt.seq.state == DRIVE_ST_FAULT ||
        bt.seq.state == DRIVE_ST_STOPPED)
        return;
    main_board_common.stats.stop_reason = reason;
    link_set_stopped(&main_board_common.link, 1);
    post(DRIVE_EVT_STOP);
    drain();
}

static bool due(uint32_t now, uint32_t deadline)
{
    return (int32_t)(now - deadline) >= 0;
}

/* ------------------------------------------------------------------ main_beacon.h */

drive_status_t main_beacon_init(const main_board_config_t *cfg)
{
    if (!cfg->map.b || !cfg->map.b8 || cfg->map.n < 3 || cfg->map.n > OPTICAL_MAX_BEACONS ||
        cfg->counts_per_turn == 0)
        return DRIVE_ERR_PARAM;
    bt.cfg = cfg;
    /* Nothing known of the initial vector but the configuration's largest uncertainty. */
    bt.unc.pos = cfg->optical.jump_max;
    bt.unc.heading = cfg->optical.turn_max;
    bt.last.x = cfg->start.x;
    bt.last.y = cfg->start.y;
    bt.last.heading = cfg->start.heading;

    optical_capture_init(&bt.cap);
    hal_capture_init(HAL_CAPTURE_INDEX, on_index, &bt.cap);
    hal_capture_init(HAL_CAPTURE_BEACON, on_edge, &bt.cap);
    bt.ds.count = 0;
    hal_edge_init(HAL_EDGE_DELTA_S, HAL_EDGE_RISING, on_ds, &bt.ds);
    return DRIVE_OK;
}

drive_status_t main_beacon_prepare(void)
{
    const main_board_config_t *cfg = bt.cfg;
    drive_status_t st = drive_path_prepare(&bt.path, &cfg->start, cfg->path, cfg->n_path,
                                           &cfg->path_cfg, &cfg->board);
    drive_seq_init(&bt.seq, &bt.path, &cfg->seq_cfg);
    return st;
}

/* The deadlines the main loop waits on (hal_clock_wake_at()); the rest wakes it. */
static void deadlines(void)
{
    if (bt.fix_state == FIX_WAIT_LATCHES)
        hal_clock_wake_at(bt.fix_deadline);
    if (bt.pose_state == POSE_WAIT_ACK || bt.pose_state == POSE_WAIT_REPLY)
        hal_clock_wake_at(bt.pose_deadline);
    if (bt.timer_on)
        hal_clock_wake_at(bt.timer_deadline);
}

void main_beacon_start(void)
{
    if (!link_up(&main_board_common.link)) {
        stop_travel(MAIN_BOARD_STOP_FAULT_CAN); /* no nav board to drive with */
        return;
    }
    post(DRIVE_EVT_START);
    drain();
    deadlines();
}

void main_beacon_poll(void)
{
    uint32_t now = hal_clock_ms();

    /* delta-S first: a double arc that ends loads the next at once (D1). */
    for (uint16_t n = drive_ds_take(&bt.ds); n; n--) {
        post(DRIVE_EVT_DELTA_S);
        drain();
    }

    hal_critical_enter();
    uint16_t indexes = bt.indexes;
    bt.indexes = 0;
    uint8_t stop = main_board_common.stop_in;
    main_board_common.stop_in = 0;
    hal_critical_exit();
    main_board_common.stats.revolutions += indexes;
    for (; indexes; indexes--) {
        post(DRIVE_EVT_INDEX);
        drain();
    }
    if (link_poll(&main_board_common.link) == LINK_EV_SILENT)
        stop_travel(MAIN_BOARD_STOP_LINK_SILENT);
    if (stop)
        stop_travel(stop);

    if (bt.fix_state == FIX_WAIT_LATCHES) {
        uint16_t all = (uint16_t)((1u << bt.n) - 1u);
        if (bt.latch_have == all || due(now, bt.fix_deadline)) {
            fix_finish();
            drain();
        }
    }

    if (bt.pose_state == POSE_WAIT_ACK && (bt.ack_in || due(now, bt.pose_deadline))) {
        if (bt.ack_in && bt.ack_status == 0)
            main_board_common.stats.fixes_acked++;
        request_pose();
    }
    if (bt.pose_state == POSE_WAIT_REPLY) {
        if (main_board_common.pose_in) {
            hal_critical_enter();
            optical_pose_t p = main_board_common.pose;
            hal_critical_exit();
            bt.pose_state = POSE_IDLE;
            optical_pose_t q = predict(&p, bt.pose_ms);
            push(DRIVE_EVT_POSE, &q);
            drain();
        } else if (due(now, bt.pose_deadline)) {
            request_pose(); /* the request or its answer was lost: ask again */
        }
    }

    if (bt.timer_on && due(now, bt.timer_deadline)) {
        bt.timer_on = 0;
        post(DRIVE_EVT_TIMER);
        drain();
    }
    deadlines();
}

drive_state_t main_beacon_state(void)
{
    return bt.seq.state;
}

/* ------------------------------------------------------------------ main_board.h */

const drive_path_t *main_board_path(void)
{
    return &bt.path;
}
