/*
 * main_board.c - the main board application's common part (see main_board.h and
 * docs/integration.md): the configuration and its dispatch to the travel of its mode, the
 * board link and the nav board's messages, the drive board's port set-up, observers and
 * counters. The travels are rooms of their own: the beacon travel (main_beacon.c, optical
 * fixes and double arcs) and seed 002's pursuit (main_pursuit.c); an image without one of them
 * links its twin (main_beacon_none.c, main_pursuit_none.c), which refuses that mode.
 *
 * The link's receive interrupt only records and wakes the main loop: the nav board's pose and
 * stop request here, the latches and the fix's acknowledgement in the beacon travel.
 */
#include "main_board.h"

#include "drive/drive_proto.h"
#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/drive_port.h"
#include "hal/irq.h"
#include "hal/signal.h"
#include "link/link.h"
#include "main_beacon.h"

main_board_common_t main_board_common;

/* A message from the nav board (the link's receive interrupt). */
static void on_msg(void *arg, const linkmsg_t *m)
{
    (void)arg;
    switch (m->type) {
    case LINKMSG_POSE:
        main_board_common.pose.x = m->u.pose.pose.x;
        main_board_common.pose.y = m->u.pose.pose.y;
        main_board_common.pose.heading = m->u.pose.pose.heading;
        main_board_common.pose_in = 1;
        break;
    case LINKMSG_STOP:
        main_board_common.stop_in = m->u.stop.reason == LINKMSG_STOP_REASON_MAIN_SILENT
                                        ? MAIN_BOARD_STOP_NAV_LINK_SILENT
                                        : MAIN_BOARD_STOP_BLIND_DISTANCE;
        break;
    default:
        if (!main_beacon_on_msg(m))
            return;
    }
    hal_cpu_wake();
}

/* The drive board's port: its initialisation (every travel mode). Not inlined: the write
 * buffer stays off the stack of the travels' set-up. */
static __attribute__((noinline)) void port_init(void)
{
    drive_wseq_t w;
    drive_ppi_init(&w);
    drive_port_send(&w);
}

/* ------------------------------------------------------------------ API */

drive_status_t main_board_init(const main_board_config_t *cfg)
{
    if (!cfg || !cfg->path || cfg->n_path == 0 || cfg->n_path > MAIN_BOARD_MAX_PATH)
        return DRIVE_ERR_PARAM;
    if (!cfg->pursuit) {
        drive_status_t st = main_beacon_init(cfg);
        if (st != DRIVE_OK)
            return st;
    }
    main_board_common.cfg = cfg;
    hal_signal_init(HAL_SIGNAL_COORD_REQUEST);
    hal_clock_init();
    int rc = link_init(&main_board_common.link, &cfg->link, on_msg, 0);
    if (rc == LINK_E_CONFIG || rc == HAL_CAN_E_PARAM || rc == HAL_CAN_E_BITRATE)
        return DRIVE_ERR_PARAM;
    main_board_common.stats.can_error = (int8_t)rc; /* the controller does not answer: no link */
    hal_drive_port_init();
    port_init();

    if (cfg->pursuit)
        return main_pursuit_init(cfg);
    return main_beacon_prepare();
}

void main_board_start(void)
{
    if (main_board_common.cfg->pursuit) { /* the position receiver steers: no nav board needed */
        main_pursuit_start();
        return;
    }
    main_beacon_start();
}

void main_board_poll(void)
{
    if (main_board_common.cfg->pursuit) {
        /* The link's heartbeat goes on (the nav board hears the main board, and answers its
         * coordinate requests for the heading); a silent nav board does not stop pursuit,
         * whose watchdog is the receiver's (main_pursuit.h): the link counts the silence. */
        (void)link_poll(&main_board_common.link);
        main_pursuit_poll();
        return;
    }
    main_beacon_poll();
}

void main_board_set_observer(const main_board_observer_t *obs)
{
    if (obs)
        main_board_common.obs = *obs;
    else
        main_board_common.obs = (main_board_observer_t){0};
}

void main_board_stats(main_board_stats_t *out)
{
    hal_critical_enter();
    *out = main_board_common.stats;
    out->link_errors = main_board_common.link.rx.errors;
    hal_critical_exit();
    if (main_board_common.cfg && main_board_common.cfg->pursuit)
        out->done = main_pursuit_done();
}

void main_board_link_stats(link_stats_t *out)
{
    link_stats(&main_board_common.link, out);
}

drive_state_t main_board_state(void)
{
    if (main_board_common.cfg && main_board_common.cfg->pursuit)
        return main_pursuit_done() ? DRIVE_ST_DONE : DRIVE_ST_IDLE;
    return main_beacon_state();
}

void main_board_notify_pursuit(const main_pursuit_event_t *ev)
{
    if (main_board_common.obs.on_pursuit)
        main_board_common.obs.on_pursuit(main_board_common.obs.ctx, ev);
}

bool main_board_pose_take(optical_pose_t *out)
{
    hal_critical_enter();
    bool in = main_board_common.pose_in != 0;
    if (in)
        *out = main_board_common.pose;
    main_board_common.pose_in = 0;
    hal_critical_exit();
    return in;
}
