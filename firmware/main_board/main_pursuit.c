/*
 * main_pursuit.c - the main board's pursuit mode (see main_pursuit.h, docs/pursuit.md).
 *
 * Handlers (interrupt context): the UARTs' receive handlers frame bytes (posrx_rx_byte) with
 * the millisecond clock's time. Main loop: receiver 2's packets first (their positions wait
 * for receiver 1's of the same instant), then receiver 1's: each is judged (posrx_check);
 * a plausible one (accepted or too close) feeds the error recovery; an accepted one of
 * receiver 1 goes to the pursuit with its heading; the pursuit's answers go to the drive
 * board's DACs; time goes to pursuit_tick.
 */
#include "main_pursuit.h"

#include "drive/drive_cmd.h"
#include "drive/drive_proto.h"
#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#include "hal/signal.h"
#include "hal/uart.h"
#include "main_board.h"

/* Two receivers' positions belong to one update when they arrive this close together. */
#define PAIR_WINDOW_MS 20u
/* The nav board answers a coordinate request within this time, or the update goes on with
 * the heading from the positions. */
#define NAV_WAIT_MS    20u
typedef struct {
    const main_board_config_t *cfg;
    const main_pursuit_config_t *pc;
    posrx_t rx[2];
    pursuit_t law;
    uint8_t angle, speed; /* the DAC values on the drive board */
    /* receiver 2's last plausible position */
    bool has2;
    posrx_pos_t pos2;
    /* an accepted position waiting for the nav board's heading */
    bool waiting;
    uint32_t wait_end;
    main_pursuit_event_t pending;
    uint16_t unpaired, nav_timeouts;
} main_pursuit_state_t;

static main_pursuit_state_t mp;

/* The UARTs' receive handler (interrupt context): @p arg is the line's receiver. */
static void on_rx(void *arg, uint8_t byte, uint8_t flags)
{
    posrx_t *r = arg;
    uint32_t framed = r->st.framed;
    posrx_rx_byte(r, byte, flags, hal_clock_ms());
    if (r->st.framed != framed)
        hal_cpu_wake(); /* a packet for the main loop */
}

/* Packet millimetres to metres Q16 (the receiver keeps them within +-2^25 mm). */
static fx_q16_t q16_of_mm(int32_t mm)
{
    int32_t q = 0;
    (void)fx_div_shift(mm, 1000, 16, &q);
    return q;
}

static int32_t mm_of_q16(fx_q16_t v)
{
    int32_t mm = 0;
    (void)fx_mul_shift(v, 1000, 16, &mm);
    return mm;
}

/* The drive board: the steering and speed DACs (seed 002's set_angle, set_speed). */
static __attribute__((noinline)) void dac(void)
{
    drive_wseq_t w;
    drive_dac_set(mp.angle, mp.speed, &w);
    drive_port_send(&w);
}

static void apply(const pursuit_out_t *out)
{
    if (out->actions & PURSUIT_ACT_STEER)
        mp.angle = drive_dac_angle_byte(out->steer, mp.cfg->board.dac_center);
    if (out->actions & PURSUIT_ACT_SPEED)
        mp.speed = drive_dac_speed_byte(out->speed);
    if (out->actions & (PURSUIT_ACT_STEER | PURSUIT_ACT_SPEED))
        dac();
    if (out->actions & PURSUIT_ACT_DONE) {
        drive_wseq_t w;
        drive_dac_stop(mp.cfg->board.dac_center, &w); /* the seed's End_Path */
        drive_port_send(&w);
    }
}

drive_status_t main_pursuit_init(const main_board_config_t *cfg)
{
    const main_pursuit_config_t *pc = cfg->pursuit;
    mp = (main_pursuit_state_t){0};
    mp.cfg = cfg;
    mp.pc = pc;
    if (pc->receivers < 1u || pc->receivers > 2u ||
        (pc->heading == MAIN_HEADING_RECEIVERS && pc->receivers != 2u) ||
        pc->heading > MAIN_HEADING_NAV || !posrx_init(&mp.rx[0], &pc->rx) ||
        !posrx_init(&mp.rx[1], &pc->rx) ||
        !pursuit_init(&mp.law, &pc->law, cfg->start.x, cfg->start.y, cfg->path, cfg->n_path))
        return DRIVE_ERR_PARAM;
    /* The known start is the receivers' first reference (a position from elsewhere is a jump). */
    posrx_set_reference(&mp.rx[0], mm_of_q16(cfg->start.x), mm_of_q16(cfg->start.y),
                        hal_clock_ms());
    if (hal_uart_open(0, pc->baud, on_rx, &mp.rx[0]) != HAL_UART_OK)
        return DRIVE_ERR_PARAM;
    if (pc->receivers == 2u && hal_uart_open(1, pc->baud, on_rx, &mp.rx[1]) != HAL_UART_OK)
        return DRIVE_ERR_PARAM;
    mp.angle = cfg->board.dac_center;
    mp.speed = drive_dac_speed_byte(0);
    return DRIVE_OK;
}

void main_pursuit_start(void)
{
    drive_wseq_t w;
    drive_dac_start(mp.cfg->board.dac_center, &w); /* the seed's Init_AGV */
    drive_port_send(&w);
    uint32_t now = hal_clock_ms();
    posrx_set_reference(&mp.rx[0], mp.rx[0].ref.x, mp.rx[0].ref.y, now);
    pursuit_out_t out;
    pursuit_start(&mp.law, mp.cfg->start.heading, now, &out);
    apply(&out);
}

/* Feed an accepted position of receiver 1 (its event in @p ev) to the pursuit. */
static void navigate(main_pursuit_event_t *ev, const fx_angle_t *heading)
{
    if (pursuit_done(&mp.law)) { /* the seed's records end with the path */
        main_board_notify_pursuit(ev);
        return;
    }
    pursuit_out_t out;
    pursuit_position(&mp.law, q16_of_mm(ev->pos.x), q16_of_mm(ev->pos.y), heading, ev->pos.t_ms,
                     &ev->rec, &out);
    ev->used = true;
    apply(&out);
    main_board_notify_pursuit(ev);
}

static void receiver1(const posrx_pos_t *p)
{
    main_pursuit_event_t ev = {0};
    ev.pos = *p;
    fx_angle_t h = 0;
    bool paired = false;
    if (mp.pc->receivers == 2u && mp.has2 && p->t_ms - mp.pos2.t_ms <= PAIR_WINDOW_MS &&
        !(p->x == 0 && p->y == 0 && p->z == 0)) {
        /* two receivers: their distance checks the pair before the update is judged */
        mp.has2 = false;
        if (!pursuit_pair(&mp.law, q16_of_mm(p->x), q16_of_mm(p->y), q16_of_mm(mp.pos2.x),
                          q16_of_mm(mp.pos2.y), &h)) {
            ev.reason = MAIN_PURSUIT_PAIR;
            main_board_notify_pursuit(&ev);
            return;
        }
        paired = true;
    }
    ev.reason = (uint8_t)posrx_check(&mp.rx[0], p, 0);
    if (ev.reason == POSRX_OK || ev.reason == POSRX_TOO_CLOSE)
        pursuit_alive(&mp.law, p->t_ms);
    if (ev.reason != POSRX_OK) {
        main_board_notify_pursuit(&ev);
        return;
    }
    if (mp.pc->receivers == 2u && !paired)
        mp.unpaired++;
    if (paired && mp.pc->heading == MAIN_HEADING_RECEIVERS) {
        navigate(&ev, &h);
    } else if (mp.pc->heading == MAIN_HEADING_NAV) {
        /* ask the nav board for its heading; the update waits for the answer */
        optical_pose_t stale;
        (void)main_board_pose_take(&stale);
        hal_signal_pulse(HAL_SIGNAL_COORD_REQUEST);
        mp.pending = ev;
        mp.waiting = true;
        mp.wait_end = hal_clock_ms() + NAV_WAIT_MS;
    } else {
        navigate(&ev, 0);
    }
}

static void receiver2(const posrx_pos_t *p)
{
    main_pursuit_event_t ev = {0};
    ev.receiver = 1;
    ev.pos = *p;
    ev.reason = (uint8_t)posrx_check(&mp.rx[1], p, 0);
    if (ev.reason == POSRX_OK || ev.reason == POSRX_TOO_CLOSE) {
        mp.has2 = true;
        mp.pos2 = *p;
    }
    main_board_notify_pursuit(&ev);
}

void main_pursuit_poll(void)
{
    uint32_t now = hal_clock_ms();
    posrx_pos_t p;
    if (mp.waiting) {
        optical_pose_t pose;
        if (main_board_pose_take(&pose)) {
            mp.waiting = false;
            fx_angle_t h = pose.heading;
            navigate(&mp.pending, &h);
        } else if ((int32_t)(now - mp.wait_end) >= 0) {
            mp.waiting = false;
            mp.nav_timeouts++;
            navigate(&mp.pending, 0);
        }
    }
    if (mp.pc->receivers == 2u)
        while (posrx_take(&mp.rx[1], &p))
            receiver2(&p);
    while (!mp.waiting && posrx_take(&mp.rx[0], &p))
        receiver1(&p);
    pursuit_out_t out;
    pursuit_tick(&mp.law, now, &out);
    apply(&out);
    /* The deadlines (hal_clock_wake_at()): the law's, and the nav board's answer's. */
    uint32_t at;
    if (pursuit_next_tick(&mp.law, now, &at))
        hal_clock_wake_at(at);
    if (mp.waiting)
        hal_clock_wake_at(mp.wait_end);
}

bool main_pursuit_done(void)
{
    return mp.pc != 0 && pursuit_done(&mp.law);
}

void main_pursuit_stats(main_pursuit_stats_t *out)
{
    *out = (main_pursuit_stats_t){0};
    if (mp.pc == 0)
        return;
    out->law = mp.law.st;
    posrx_stats(&mp.rx[0], &out->rx[0]);
    posrx_stats(&mp.rx[1], &out->rx[1]);
    out->unpaired = mp.unpaired;
    out->nav_timeouts = mp.nav_timeouts;
    out->overruns[0] = hal_uart_overruns(0);
    out->overruns[1] = mp.pc->receivers == 2u ? hal_uart_overruns(1) : 0u;
    out->done = pursuit_done(&mp.law);
}
