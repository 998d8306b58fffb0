/*
 * nav_board.c - the navigation board application (see nav_board.h).
 */
#include "nav_board.h"

#include "hal/cpu.h"
#include "hal/irq.h"
#include "hal/link.h"
#include "link/linkmsg.h"

static gnav_t g;
static linkmsg_rx_t rx;
static nav_board_stats_t stats;

/* Mailboxes from the handlers to the main loop (guarded by critical sections). */
static volatile uint8_t coord_pending; /* written by the NMI, read by the main loop */
static uint8_t coord_request_no;
static uint8_t fix_pending;
static linkmsg_t fix_msg;
static uint8_t latch_pending;
static uint16_t latch_first;
static uint8_t latch_count;
static uint8_t stop_pending;
static uint16_t send_first; /* latches still to send */
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

static void on_frame(void *arg, const hal_link_frame_t *f)
{
    (void)arg;
    linkmsg_t m;
    if (!linkmsg_rx_feed(&rx, f, &m))
        return;
    switch (m.type) {
    case LINKMSG_FIX:
        fix_msg = m; /* a newer fix replaces one not yet applied */
        fix_pending = 1;
        break;
    case LINKMSG_LATCH_REQ:
        latch_first = m.u.latch_req.first;
        latch_count = m.u.latch_req.count;
        latch_pending = 1;
        break;
    case LINKMSG_DIR:
        gnav_set_reverse(&g, m.u.dir.reverse != 0);
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
    linkmsg_rx_init(&rx);
    hal_link_init(on_frame, 0);
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
    linkmsg_send(&m);
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
     * the next passes (15 latches are 30 frames: more than the UART's queue holds).
     */
    while (send_left) {
        gnav_latch_t l;
        int rc = gnav_latch_read(&g, send_first, &l);
        m.type = LINKMSG_LATCH;
        m.u.latch.seq = send_first;
        m.u.latch.status = (int8_t)rc;
        m.u.latch.pose.x = rc == GNAV_OK ? l.pose.x : 0;
        m.u.latch.pose.y = rc == GNAV_OK ? l.pose.y : 0;
        m.u.latch.pose.heading = rc == GNAV_OK ? l.pose.heading : 0;
        if (linkmsg_send(&m) != 0)
            break;
        stats.latches_sent++;
        send_first++;
        send_left--;
    }
    if (send_left)
        hal_cpu_wake(); /* come back when the link has drained */

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
        linkmsg_send(&m);
    }

    if (stop && !stats.stop_sent) {
        m.type = LINKMSG_STOP;
        m.u.stop.reason = 1;
        linkmsg_send(&m);
        stats.stop_sent = 1;
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
    out->link_errors = rx.errors;
    hal_critical_exit();
}
