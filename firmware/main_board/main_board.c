/*
 * main_board.c - the main board application (see main_board.h and docs/integration.md).
 *
 * Handlers (interrupt context) only count and queue: index pulses, photodetector rising edges
 * (numbered as the nav board numbers its latches), delta-S pulses, link messages. The main
 * loop turns them into travel-sequencer events, executes the sequencer's actions and runs the
 * long computations (the optical fix, the double arc).
 */
#include "main_board.h"

#include "drive/drive_proto.h"
#include "hal/capture.h"
#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/drive_port.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal/link.h"
#include "hal/signal.h"
#include "link/linkmsg.h"

/* Waiting for the nav board: latches, the fix's acknowledgement, the pose. */
#define LATCH_TIMEOUT_MS 100u
#define ACK_TIMEOUT_MS   50u
#define POSE_TIMEOUT_MS  50u
#define EVENT_QUEUE      4u

enum { FIX_IDLE = 0, FIX_WAIT_LATCHES };
enum { POSE_IDLE = 0, POSE_WAIT_ACK, POSE_WAIT_REPLY };

static struct {
    /* configuration */
    optical_map_t map;
    const optical_xy_t *beacons;
    drive_board_t board;
    drive_seq_config_t seq_cfg;
    optical_config_t optical;
    uint16_t counts_per_turn;
    drive_pose_t start;
    /* modules */
    optical_capture_t cap;
    drive_ds_t ds;
    drive_path_t path;
    drive_seq_t seq;
    linkmsg_rx_t rx;
    main_board_observer_t obs;
    main_board_stats_t stats;
    /* handlers -> main loop */
    uint16_t rises;            /* photodetector rising edges so far (= the nav board's latches) */
    uint16_t rise_at_rev[4];   /* rises when revolution (seq & 3) started */
    volatile uint16_t indexes; /* index pulses not yet fed to the sequencer */
    uint8_t ack_in;            /* FIX_ACK received */
    int8_t ack_status;
    uint8_t pose_in; /* POSE received */
    optical_pose_t pose;
    uint8_t stop_in;
    /* the fix in progress */
    uint8_t fix_state;
    uint32_t fix_deadline;
    int8_t n;                             /* sightings of the revolution */
    uint16_t latch_first;                 /* latch number of the first sighting in time */
    uint16_t latch_have;                  /* bit i: latch first + i arrived */
    const optical_rev_t *rev;             /* the revolution held while its fix runs */
    uint8_t order[OPTICAL_MAX_SIGHTINGS]; /* sorted position -> capture order */
    optical_sighting_t s[OPTICAL_MAX_SIGHTINGS];
    /* The nav board's latches: capture order at rising edges as they arrive, then (in place)
     * sorted order at the pulse centres for optical_fix(). */
    optical_pose_t latched[OPTICAL_MAX_SIGHTINGS];
    optical_pose_t approx; /* the last sighting's latch: the reference instant */
    optical_fix_t fix;
    uint16_t fix_ref; /* reference latch of the last good fix */
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
} mb;

/* ------------------------------------------------------------------ handlers */

static void on_index(void *arg, uint16_t count, uint8_t rising)
{
    uint16_t started = mb.cap.seq;
    optical_capture_on_index(arg, count, rising);
    if (mb.cap.seq != started)
        mb.rise_at_rev[mb.cap.seq & 3u] = mb.rises; /* the revolution that starts now */
    mb.indexes++;
    hal_cpu_wake();
}

static void on_edge(void *arg, uint16_t count, uint8_t rising)
{
    if (rising)
        mb.rises++; /* every edge, captured or not: the nav board latches every one */
    optical_capture_on_edge(arg, count, rising);
}

static void on_ds(void *arg)
{
    drive_ds_handler(arg);
    hal_cpu_wake();
}

static void on_frame(void *arg, const hal_link_frame_t *f)
{
    (void)arg;
    linkmsg_t m;
    if (!linkmsg_rx_feed(&mb.rx, f, &m))
        return;
    switch (m.type) {
    case LINKMSG_LATCH: {
        uint16_t i = (uint16_t)(m.u.latch.seq - mb.latch_first);
        if (mb.fix_state == FIX_WAIT_LATCHES && i < (uint16_t)mb.n && m.u.latch.status == 0) {
            mb.latched[i].x = m.u.latch.pose.x;
            mb.latched[i].y = m.u.latch.pose.y;
            mb.latched[i].heading = m.u.latch.pose.heading;
            mb.latch_have |= (uint16_t)(1u << i);
        }
        break;
    }
    case LINKMSG_FIX_ACK:
        mb.ack_in = 1;
        mb.ack_status = m.u.fix_ack.status;
        break;
    case LINKMSG_POSE:
        mb.pose.x = m.u.pose.pose.x;
        mb.pose.y = m.u.pose.pose.y;
        mb.pose.heading = m.u.pose.pose.heading;
        mb.pose_in = 1;
        break;
    case LINKMSG_STOP:
        mb.stop_in = 1;
        break;
    default:
        return;
    }
    hal_cpu_wake();
}

/* ------------------------------------------------------------------ helpers */

static void push(drive_evt_t type, const optical_pose_t *p)
{
    if (mb.q_n >= EVENT_QUEUE)
        return; /* cannot happen: at most two follow-ups per action set */
    drive_seq_event_t *e = &mb.queue[(mb.q_head + mb.q_n) % EVENT_QUEUE];
    e->type = type;
    if (p) {
        e->pose.x = p->x;
        e->pose.y = p->y;
        e->pose.heading = p->heading;
    }
    mb.q_n++;
}

static void send_wseq(const drive_wseq_t *w)
{
    drive_port_send(w);
}

static void correct_nav(void);

static void fix_done(int8_t status)
{
    main_board_fix_event_t ev;
    ev.status = status;
    ev.n = mb.n > 0 ? (uint8_t)mb.n : 0u;
    ev.ref_latch = (uint16_t)(mb.latch_first + (mb.n > 0 ? mb.n - 1 : 0));
    ev.fix = mb.fix;
    ev.approx = mb.approx;
    ev.s = mb.s;
    mb.fix_state = FIX_IDLE;
    optical_capture_release(&mb.cap);
    if (status == OPTICAL_OK) {
        mb.stats.fixes_ok++;
        mb.fix_ref = ev.ref_latch;
        /* Simplified travel drives from the fix alone (seed 5.2, written when the ground
         * navigator did not work yet); the nav board is corrected all the same, so that its
         * stop request (G6) watches real dead reckoning. */
        if (mb.seq_cfg.mode == DRIVE_MODE_SIMPLIFIED)
            correct_nav();
        push(DRIVE_EVT_FIX_READY, &mb.fix.pose);
    } else {
        mb.stats.fixes_failed++;
        push(DRIVE_EVT_FIX_FAILED, 0);
    }
    if (mb.obs.on_fix)
        mb.obs.on_fix(mb.obs.ctx, &ev);
}

/* Start the fix of the revolution that just ended: ask for its latches. */
static void fix_start(void)
{
    const optical_rev_t *rev = optical_capture_take(&mb.cap);
    mb.fix.status = OPTICAL_E_REV;
    if (!rev) {
        mb.n = 0;
        main_board_fix_event_t ev = {OPTICAL_E_REV, 0, 0, mb.fix, {0, 0, 0}, mb.s};
        mb.stats.fixes_failed++;
        push(DRIVE_EVT_FIX_FAILED, 0);
        if (mb.obs.on_fix)
            mb.obs.on_fix(mb.obs.ctx, &ev);
        return;
    }
    mb.n = optical_rev_order(rev, mb.counts_per_turn, mb.s, mb.order);
    if (mb.n < 3) {
        mb.fix.status = mb.n < 0 ? OPTICAL_E_REV : OPTICAL_E_FEW;
        int8_t st = (int8_t)mb.fix.status;
        if (mb.n < 0)
            mb.n = 0;
        fix_done(st);
        return;
    }
    /* A pulse that began before the index pulse rose in the previous revolution. */
    uint16_t first = mb.rise_at_rev[rev->seq & 3u];
    if (rev->s[0].start >= mb.counts_per_turn)
        first--;
    mb.rev = rev;
    hal_critical_enter();
    mb.latch_first = first;
    mb.latch_have = 0;
    mb.fix_state = FIX_WAIT_LATCHES;
    hal_critical_exit();
    mb.fix_deadline = hal_clock_ms() + LATCH_TIMEOUT_MS;
    linkmsg_t m;
    m.type = LINKMSG_LATCH_REQ;
    m.u.latch_req.first = first;
    m.u.latch_req.count = (uint8_t)mb.n;
    linkmsg_send(&m);
}

/* Rising edge of capture-order sighting i, counts after its revolution's index pulse. */
static int32_t rise_of(uint8_t i)
{
    uint16_t st = mb.rev->s[i].start;
    return st >= mb.counts_per_turn ? (int32_t)st - 65536l : (int32_t)st;
}

/*
 * The nav board latches at the pulse's rising edge; the sighting is the pulse's centre, half
 * a width later (up to a few ms: millimetres at 1 m/s). Each sighting's pose is interpolated
 * between its latch and the next one (extrapolated for the last) by the angle clock, which
 * is time; then the poses are put in the sightings' (angle) order. In place: RAM is short.
 */
static void centre_and_sort(void)
{
    optical_pose_t *l = mb.latched;
    uint8_t n = (uint8_t)mb.n;
    optical_pose_t before_last = l[n - 2]; /* the last one extrapolates from it */
    for (uint8_t i = 0; i < n; i++) {
        uint8_t a = i + 1u < n ? i : (uint8_t)(i - 1u), b = (uint8_t)(a + 1u);
        const optical_pose_t pa = i + 1u < n ? l[a] : before_last, pb = l[b];
        int32_t span = rise_of(b) - rise_of(a);
        int32_t half = (int32_t)((mb.rev->s[i].width + 1u) >> 1);
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
        while (mb.order[k] != j) {
            l[k] = l[mb.order[k]];
            done |= (uint16_t)(1u << k);
            k = mb.order[k];
        }
        l[k] = first;
        done |= (uint16_t)(1u << k);
    }
}

/* All latches in (or the wait is over): run the optical pipeline. */
static void fix_finish(void)
{
    uint16_t all = (uint16_t)((1u << mb.n) - 1u);
    if (mb.latch_have != all) {
        mb.stats.latch_timeouts++;
        mb.fix.status = OPTICAL_E_REV;
        fix_done(OPTICAL_E_REV);
        return;
    }
    /* Reference instant: the last sighting's rising edge; its latch is the approximate pose
     * and the nav board applies the fix to that latch. */
    mb.approx = mb.latched[mb.n - 1];
    centre_and_sort();
    int8_t st =
        optical_fix(&mb.map, &mb.optical, &mb.approx, mb.s, (uint8_t)mb.n, mb.latched, &mb.fix);
    fix_done(st);
}

/* Send the fix to the nav board (Buffer Full) for its reference latch. */
static void correct_nav(void)
{
    linkmsg_t m;
    m.type = LINKMSG_FIX;
    m.u.fix.pose.x = mb.fix.pose.x;
    m.u.fix.pose.y = mb.fix.pose.y;
    m.u.fix.pose.heading = mb.fix.pose.heading;
    m.u.fix.latch = mb.fix_ref;
    m.u.fix.flags = LINKMSG_FIX_HAS_REF;
    hal_critical_enter();
    mb.ack_in = 0;
    hal_critical_exit();
    linkmsg_send(&m);
}

static void request_pose(void)
{
    hal_critical_enter();
    mb.pose_in = 0;
    hal_critical_exit();
    hal_signal_pulse(HAL_SIGNAL_COORD_REQUEST);
    mb.pose_state = POSE_WAIT_REPLY;
    mb.pose_deadline = hal_clock_ms() + POSE_TIMEOUT_MS;
}

/*
 * Where the vehicle will be @p ms from now: along the loaded double arc, on the arc it is on
 * (the delta-S pulses seen tell which), at the loaded speed. Errors of this guess are what
 * the next revolution's fix corrects.
 */
static optical_pose_t predict(const optical_pose_t *now, uint16_t ms)
{
    optical_pose_t p = *now;
    if (ms == 0 || mb.loaded.speed == 0)
        return p;
    uint8_t seg = mb.seq.pulses_seen >= 1 && mb.loaded.arc[1] ? 1u : 0u;
    int32_t k = 0;
    if (mb.loaded.alpha[seg] != 0) {
        fx_q16_t t = fx_tan(mb.loaded.alpha[seg]);
        if (!fx_div_shift(t, mb.board.wheelbase, 28, &k))
            k = 0;
    }
    int32_t v = mb.loaded.speed < 0 ? -mb.loaded.speed : mb.loaded.speed;
    fx_q16_t rate = v * mb.board.speed_lsb;                   /* m/s, Q16 */
    fx_q16_t secs = (fx_q16_t)(((uint32_t)ms << 16) / 1000u); /* s, Q16 */
    fx_q16_t dist = fx_mul_q16(rate, secs);
    drive_pose_t d = {p.x, p.y, p.heading};
    d = drive_pose_advance(&d, k, dist, mb.loaded.speed < 0);
    p.x = d.x;
    p.y = d.y;
    p.heading = d.heading;
    return p;
}

static void execute(const drive_seq_out_t *out)
{
    drive_wseq_t w;
    uint16_t a = out->actions;
    if (a & DRIVE_ACT_STOP) {
        drive_ppi_speed(0, &w);
        send_wseq(&w);
        mb.loaded.speed = 0;
    }
    if (a & DRIVE_ACT_REQUEST_FIX)
        fix_start();
    if (a & DRIVE_ACT_CORRECT_NAV)
        correct_nav();
    if (a & DRIVE_ACT_REQUEST_POSE) {
        mb.pose_ms = out->pose_ms;
        if (a & DRIVE_ACT_CORRECT_NAV) {
            /* The pose must include the fix: ask once the nav board installed it. */
            mb.pose_state = POSE_WAIT_ACK;
            mb.pose_deadline = hal_clock_ms() + ACK_TIMEOUT_MS;
        } else {
            request_pose();
        }
    }
    if (a & DRIVE_ACT_LOAD) {
        uint8_t reverse = out->cmd.speed < 0 ? 1u : 0u;
        if (reverse != mb.reverse) {
            linkmsg_t m;
            m.type = LINKMSG_DIR;
            m.u.dir.reverse = reverse;
            linkmsg_send(&m);
            mb.reverse = reverse;
        }
        drive_ppi_load(&out->cmd, &w);
        send_wseq(&w);
        mb.loaded = out->cmd;
        mb.stats.loads++;
        if (mb.obs.on_load)
            mb.obs.on_load(mb.obs.ctx, &out->cmd);
    }
    if (a & DRIVE_ACT_SET_SPEED) {
        drive_ppi_speed(out->speed, &w);
        send_wseq(&w);
        mb.loaded.speed = out->speed;
    }
    if (a & DRIVE_ACT_TIMER) {
        mb.timer_on = 1;
        mb.timer_deadline = hal_clock_ms() + out->timer_ms;
    }
    if (a & DRIVE_ACT_INDEX_ON)
        optical_capture_start(&mb.cap);
    if (a & DRIVE_ACT_INDEX_OFF)
        optical_capture_stop(&mb.cap);
    if (a & DRIVE_ACT_DONE)
        mb.stats.done = 1;
    if (a & DRIVE_ACT_FAULT) {
        mb.stats.fault = 1;
        mb.stats.fault_why = (uint8_t)out->fault;
    }
}

static void step(const drive_seq_event_t *ev)
{
    drive_seq_out_t out;
    drive_state_t before = mb.seq.state;
    drive_seq_step(&mb.seq, ev, &out);
    if (out.actions)
        execute(&out);
    if (mb.seq.state != before && mb.obs.on_state)
        mb.obs.on_state(mb.obs.ctx, mb.seq.state);
}

static void step_type(drive_evt_t type)
{
    drive_seq_event_t ev;
    ev.type = type;
    ev.pose = mb.start;
    step(&ev);
}

/* Feed the events the actions produced, in order. */
static void drain(void)
{
    while (mb.q_n) {
        drive_seq_event_t ev = mb.queue[mb.q_head];
        mb.q_head = (uint8_t)((mb.q_head + 1u) % EVENT_QUEUE);
        mb.q_n--;
        step(&ev);
    }
}

static bool due(uint32_t now, uint32_t deadline)
{
    return (int32_t)(now - deadline) >= 0;
}

/* ------------------------------------------------------------------ API */

drive_status_t main_board_init(const main_board_config_t *cfg)
{
    if (!cfg || !cfg->path || !cfg->beacons || cfg->n_path == 0 ||
        cfg->n_path > MAIN_BOARD_MAX_PATH || cfg->n_beacons < 3 ||
        cfg->n_beacons > OPTICAL_MAX_BEACONS || cfg->counts_per_turn == 0)
        return DRIVE_ERR_PARAM;
    mb.beacons = cfg->beacons;
    mb.map.b = cfg->beacons;
    mb.map.n = cfg->n_beacons;
    mb.board = cfg->board;
    mb.seq_cfg = cfg->seq_cfg;
    mb.optical = cfg->optical;
    mb.counts_per_turn = cfg->counts_per_turn;
    mb.start = cfg->start;

    optical_capture_init(&mb.cap);
    hal_capture_init(HAL_CAPTURE_INDEX, on_index, &mb.cap);
    hal_capture_init(HAL_CAPTURE_BEACON, on_edge, &mb.cap);
    mb.ds.count = 0;
    hal_edge_init(HAL_EDGE_DELTA_S, HAL_EDGE_RISING, on_ds, &mb.ds);
    linkmsg_rx_init(&mb.rx);
    hal_link_init(on_frame, 0);
    hal_signal_init(HAL_SIGNAL_COORD_REQUEST);
    hal_clock_init();
    hal_drive_port_init();
    drive_wseq_t w;
    drive_ppi_init(&w);
    send_wseq(&w);

    drive_status_t st =
        drive_path_prepare(&mb.path, &mb.start, cfg->path, cfg->n_path, &cfg->path_cfg, &mb.board);
    drive_seq_init(&mb.seq, &mb.path, &mb.seq_cfg);
    return st;
}

const drive_path_t *main_board_path(void)
{
    return &mb.path;
}

void main_board_start(void)
{
    step_type(DRIVE_EVT_START);
    drain();
}

void main_board_poll(void)
{
    uint32_t now = hal_clock_ms();

    /* delta-S first: a double arc that ends loads the next at once (D1). */
    for (uint16_t n = drive_ds_take(&mb.ds); n; n--) {
        step_type(DRIVE_EVT_DELTA_S);
        drain();
    }

    hal_critical_enter();
    uint16_t indexes = mb.indexes;
    mb.indexes = 0;
    uint8_t stop = mb.stop_in;
    mb.stop_in = 0;
    hal_critical_exit();
    mb.stats.revolutions += indexes;
    for (; indexes; indexes--) {
        step_type(DRIVE_EVT_INDEX);
        drain();
    }
    if (stop) {
        mb.stats.stop_requested = 1;
        step_type(DRIVE_EVT_STOP);
        drain();
    }

    if (mb.fix_state == FIX_WAIT_LATCHES) {
        uint16_t all = (uint16_t)((1u << mb.n) - 1u);
        if (mb.latch_have == all || due(now, mb.fix_deadline)) {
            fix_finish();
            drain();
        }
    }

    if (mb.pose_state == POSE_WAIT_ACK && (mb.ack_in || due(now, mb.pose_deadline))) {
        if (mb.ack_in && mb.ack_status == 0)
            mb.stats.fixes_acked++;
        request_pose();
    }
    if (mb.pose_state == POSE_WAIT_REPLY) {
        if (mb.pose_in) {
            hal_critical_enter();
            optical_pose_t p = mb.pose;
            hal_critical_exit();
            mb.pose_state = POSE_IDLE;
            optical_pose_t q = predict(&p, mb.pose_ms);
            push(DRIVE_EVT_POSE, &q);
            drain();
        } else if (due(now, mb.pose_deadline)) {
            request_pose(); /* the request or its answer was lost: ask again */
        }
    }

    if (mb.timer_on && due(now, mb.timer_deadline)) {
        mb.timer_on = 0;
        step_type(DRIVE_EVT_TIMER);
        drain();
    }
}

void main_board_set_observer(const main_board_observer_t *obs)
{
    if (obs)
        mb.obs = *obs;
    else
        mb.obs = (main_board_observer_t){0, 0, 0, 0};
}

void main_board_stats(main_board_stats_t *out)
{
    hal_critical_enter();
    *out = mb.stats;
    out->link_errors = mb.rx.errors;
    hal_critical_exit();
}

drive_state_t main_board_state(void)
{
    return mb.seq.state;
}
