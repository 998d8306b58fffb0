/*
 * nav_board.c - the navigation board application (see nav_board.h).
 */
#include "nav_board.h"

#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/irq.h"

static gnav_t g;
static link_t nav_link;
static nav_board_stats_t stats;

/* Mailboxes from the handlers to the main loop (guarded by critical sections). */
static volatile uint8_t coord_pending; /* written by the NMI, read by the main loop */
static uint8_t coord_request_no;
static uint8_t fix_pending;
static linkmsg_t fix_msg;
static uint8_t latch_pending;
static uint16_t latch_first;
static uint8_t latch_count;
static uint8_t stop_pending; /* the blind distance was reached (G6) */
static uint8_t stop_want;    /* stop requests still to send: bit (reason - 1) */
static uint16_t send_first;  /* latches still to send */
static uint8_t send_left;

/* Coordinate request (NMI): gnav took a consistent pose; answer it from the main loop, where
 * converting it (gnav_coord multiplies) and sending cannot collide with anything (an NMI is
 * not held off). */
static void on_coord(void *ctx)
{
    (void)ctx;
    coord_pending = 1;
    hal_cpu_wake();
}

static void on_stop(void *ctx)
{
    (void)ctx;
    stop_pending = 1;
    hal_cpu_wake();
}

/* A message from the main board (the link's receive interrupt). */
static void on_msg(void *arg, const linkmsg_t *m)
{
    (void)arg;
    switch (m->type) {
    case LINKMSG_FIX:
        fix_msg = *m; /* a newer fix replaces one not yet applied */
        fix_pending = 1;
        break;
    case LINKMSG_LATCH_REQ:
        latch_first = m->u.latch_req.first;
        latch_count = m->u.latch_req.count;
        latch_pending = 1;
        break;
    case LINKMSG_DIR:
        gnav_set_reverse(&g, m->u.dir.reverse != 0);
        break;
    default:
        return;
    }
    hal_cpu_wake();
}

int nav_board_init(const nav_board_config_t *cfg)
{
    int rc = gnav_init(&g, &cfg->gnav, &cfg->start);
    if (rc != GNAV_OK)
        return rc;
    gnav_set_coord_callback(&g, on_coord, 0);
    gnav_set_stop_callback(&g, on_stop, 0);
    if (gnav_attach(&g) != 0)
        return GNAV_ERR_NULL;
    rc = link_init(&nav_link, &cfg->link, on_msg, 0);
    if (rc == LINK_E_CONFIG || rc == HAL_CAN_E_PARAM || rc == HAL_CAN_E_BITRATE)
        return NAV_BOARD_E_LINK;
    stats.can_error = (int8_t)rc; /* the controller does not answer: no link */
    return 0;
}

static void send_pose(const gnav_pose_t *p, uint8_t request)
{
    linkmsg_t m;
    m.type = LINKMSG_POSE;
    m.u.pose.pose.x = p->x;
    m.u.pose.pose.y = p->y;
    m.u.pose.pose.heading = p->heading;
    m.u.pose.request = request;
    link_send(&nav_link, &m);
}

void nav_board_poll(void)
{
    linkmsg_t m;
    if (coord_pending) {
        gnav_pose_t p;
        hal_critical_enter();
        coord_pending = 0;
        hal_critical_exit();
        gnav_coord(&g, &p); /* the snapshot the NMI took */
        send_pose(&p, ++coord_request_no);
        stats.coord_requests++;
    }

    hal_critical_enter();
    uint8_t have_fix = fix_pending;
    linkmsg_t fix = fix_msg;
    fix_pending = 0;
    uint8_t have_latch = latch_pending;
    uint16_t first = latch_first;
    uint8_t count = latch_count;
    latch_pending = 0;
    uint8_t stop = stop_pending;
    stop_pending = 0;
    hal_critical_exit();

    if (have_latch) {
        send_first = first; /* a new request replaces what is left of an older one */
        send_left = count;
    }
    /*
     * Latches brought into the current frame, so that one revolution's latches are comparable
     * even when a fix was applied in its middle; as many as the link takes now, the rest on
     * the next passes (15 latches are 30 frames: more than the CAN transmit queue holds).
     */
    while (send_left && link_tx_room(&nav_link) >= 2) {
        gnav_latch_t l;
        int rc = gnav_latch_read(&g, send_first, &l);
        m.type = LINKMSG_LATCH;
        m.u.latch.seq = send_first;
        m.u.latch.status = (int8_t)rc;
        m.u.latch.pose.x = rc == GNAV_OK ? l.pose.x : 0;
        m.u.latch.pose.y = rc == GNAV_OK ? l.pose.y : 0;
        m.u.latch.pose.heading = rc == GNAV_OK ? l.pose.heading : 0;
        if (link_send(&nav_link, &m) != 0)
            break;
        stats.latches_sent++;
        send_first++;
        send_left--;
    }
    if (send_left)
        link_wake_on_room(&nav_link); /* come back when the link has drained */

    if (have_fix) {
        gnav_pose_t pose = {fix.u.fix.pose.x, fix.u.fix.pose.y, fix.u.fix.pose.heading};
        int rc;
        if (fix.u.fix.flags & LINKMSG_FIX_HAS_REF) {
            gnav_latch_t ref;
            rc = gnav_latch_read(&g, fix.u.fix.latch, &ref);
            if (rc == GNAV_OK)
                rc = gnav_fix(&g, &pose, &ref);
        } else {
            rc = gnav_fix(&g, &pose, 0);
        }
        if (rc == GNAV_OK)
            stats.fixes_applied++;
        else
            stats.fixes_refused++;
        m.type = LINKMSG_FIX_ACK;
        m.u.fix_ack.status = (int8_t)rc;
        m.u.fix_ack.latch = fix.u.fix.latch;
        link_send(&nav_link, &m);
    }

    if (stop)
        stop_want |= 1u << (LINKMSG_STOP_REASON_BLIND_DISTANCE - 1);
    if (link_poll(&nav_link) == LINK_EV_SILENT)
        stop_want |= 1u << (LINKMSG_STOP_REASON_MAIN_SILENT - 1);
    /* Each reason asked once; a request the link cannot take now goes on a later pass. */
    static const uint8_t reasons[] = {LINKMSG_STOP_REASON_BLIND_DISTANCE,
                                      LINKMSG_STOP_REASON_MAIN_SILENT};
    for (uint8_t i = 0; i < sizeof reasons; i++) {
        uint8_t reason = reasons[i], bit = (uint8_t)(1u << (reason - 1u));
        if (!(stop_want & bit) || (stats.stop_sent & bit))
            continue;
        m.type = LINKMSG_STOP;
        m.u.stop.reason = reason;
        if (link_send(&nav_link, &m) == 0) {
            stats.stop_sent |= bit;
            link_set_stopped(&nav_link, 1);
        } else {
            hal_clock_wake_at(hal_clock_ms()); /* try again on the next millisecond */
        }
    }
}

void nav_board_pose(gnav_pose_t *out)
{
    gnav_pose(&g, out);
}

void nav_board_stats(nav_board_stats_t *out)
{
    hal_critical_enter();
    *out = stats;
    out->link_errors = nav_link.rx.errors;
    hal_critical_exit();
}

void nav_board_link_stats(link_stats_t *out)
{
    link_stats(&nav_link, out);
}
