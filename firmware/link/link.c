/*
 * link.c - the board link on CAN (see link.h).
 */
#include "link/link.h"

#include <stddef.h>

#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/irq.h"

static bool due(uint32_t now, uint32_t deadline)
{
    return (int32_t)(now - deadline) >= 0;
}

static uint8_t peer_of(uint8_t node)
{
    return node == LINKMSG_NODE_MAIN ? LINKMSG_NODE_NAV : LINKMSG_NODE_MAIN;
}

/* Receive handler (interrupt context). */
static void on_frame(void *arg, const hal_can_frame_t *f)
{
    link_t *l = arg;
    int8_t sender = linkmsg_sender(f->id);
    if (sender < 0)
        return; /* not in the table: others' traffic on a shared bus (a babbler's too) */
    if (sender == (int8_t)peer_of(l->cfg.node)) {
        l->last_heard = hal_clock_ms();
        if (l->silent)
            hal_cpu_wake(); /* the peer is back: link_poll() says so at once */
    }
    linkmsg_t m;
    if (!linkmsg_rx_feed(&l->rx, f, &m))
        return;
    if (m.type == LINKMSG_MAIN_HEARTBEAT || m.type == LINKMSG_NAV_HEARTBEAT) {
        if (m.type !=
            (l->cfg.node == LINKMSG_NODE_MAIN ? LINKMSG_NAV_HEARTBEAT : LINKMSG_MAIN_HEARTBEAT))
            return; /* another board's with our id: not ours to count */
        if (l->peer_seen && m.u.heartbeat.counter != (uint8_t)(l->peer_counter + 1u))
            l->stats.peer_missed =
                (uint16_t)(l->stats.peer_missed +
                           (uint8_t)(m.u.heartbeat.counter - l->peer_counter - 1u));
        l->peer_counter = m.u.heartbeat.counter;
        l->peer_seen = 1;
        l->stats.peer_heartbeats++;
        return;
    }
    if (l->on_msg)
        l->on_msg(l->ctx, &m);
}

int link_init(link_t *l, const link_config_t *cfg, link_msg_fn on_msg, void *ctx)
{
    if (!l || !cfg || (cfg->node != LINKMSG_NODE_MAIN && cfg->node != LINKMSG_NODE_NAV) ||
        cfg->heartbeat_ms < LINK_HEARTBEAT_MS_MIN || cfg->heartbeat_ms > LINK_HEARTBEAT_MS_MAX ||
        cfg->silence_ms <= cfg->heartbeat_ms || cfg->silence_ms > LINK_SILENCE_MS_MAX)
        return LINK_E_CONFIG;
    hal_clock_init();
    hal_irq_state_t s = hal_irq_disable();
    l->cfg = *cfg;
    l->on_msg = on_msg;
    l->ctx = ctx;
    linkmsg_rx_init(&l->rx);
    l->counter = 0;
    l->peer_counter = 0;
    l->peer_seen = 0;
    l->silent = 0;
    l->flags = 0;
    l->up = 0;
    l->stats = (link_stats_t){0};
    uint32_t now = hal_clock_ms();
    l->last_heard = now;
    l->next_heartbeat = now;
    hal_clock_wake_at(now); /* the first heartbeat */
    /* The table's ids: the messages (0x000-0x0FF) and the heartbeats (0x700-0x703). */
    hal_can_config_t cc = {
        cfg->bitrate_bps, {{0x000u, 0x700u}, {0x700u, 0x7FCu}}, 2, 0, on_frame, l};
    int rc = hal_can_init(LINK_CAN, &cc);
    l->up = rc == 0;
    hal_irq_restore(s);
    return rc;
}

int link_send(link_t *l, const linkmsg_t *m)
{
    hal_can_frame_t f[2];
    uint8_t n = linkmsg_encode(m, f);
    if (n == 0)
        return LINK_E_MESSAGE;
    if (!l->up)
        return LINK_E_DOWN;
    int rc = 0;
    hal_irq_state_t s = hal_irq_disable();
    if (hal_can_tx_room(LINK_CAN) < n) {
        hal_can_status_t st;
        rc = hal_can_status(LINK_CAN, &st) == 0 && st.state == HAL_CAN_BUS_OFF ? LINK_E_BUS_OFF
                                                                               : LINK_E_FULL;
    } else {
        for (uint8_t i = 0; i < n && rc == 0; i++)
            rc = hal_can_send(LINK_CAN, &f[i]);
    }
    if (rc != 0)
        l->stats.send_refused++;
    hal_irq_restore(s);
    return rc;
}

uint8_t link_tx_room(const link_t *l)
{
    (void)l; /* one link per board: the instance is LINK_CAN */
    return hal_can_tx_room(LINK_CAN);
}

void link_wake_on_room(const link_t *l)
{
    (void)l;
    hal_can_wake_on_room(LINK_CAN);
}

static uint8_t sat8(uint16_t v)
{
    return v > 255u ? 255u : (uint8_t)v;
}

static void heartbeat(link_t *l, uint32_t now)
{
    if (!due(now, l->next_heartbeat))
        return;
    hal_can_status_t st = {0, 0, 0, 0};
    hal_can_status(LINK_CAN, &st);
    linkmsg_t m;
    m.type = l->cfg.node == LINKMSG_NODE_MAIN ? LINKMSG_MAIN_HEARTBEAT : LINKMSG_NAV_HEARTBEAT;
    m.u.heartbeat.counter = l->counter;
    m.u.heartbeat.flags = (uint8_t)((l->silent ? 0u : LINKMSG_HB_HEARS_PEER) | l->flags);
    m.u.heartbeat.tec = sat8(st.tec);
    m.u.heartbeat.rec = sat8(st.rec);
    if (link_send(l, &m) != 0)
        return; /* full or bus-off: the next pass tries again */
    l->counter++;
    l->stats.heartbeats_sent++;
    l->next_heartbeat += l->cfg.heartbeat_ms;
    if (due(now, l->next_heartbeat)) /* far behind (a long bus-off): no burst to catch up */
        l->next_heartbeat = now + l->cfg.heartbeat_ms;
}

link_event_t link_poll(link_t *l)
{
    if (!l->up)
        return LINK_EV_NONE;
    hal_irq_state_t s = hal_irq_disable();
    uint32_t heard = l->last_heard, now = hal_clock_ms(); /* both before a frame moves one */
    hal_irq_restore(s);
    heartbeat(l, now);
    hal_clock_wake_at(l->next_heartbeat); /* a refused heartbeat: the next millisecond */
    bool quiet = (uint32_t)(now - heard) >= l->cfg.silence_ms;
    if (!quiet && !l->silent)
        hal_clock_wake_at(heard + l->cfg.silence_ms); /* when the peer would fall silent */
    if (quiet && !l->silent) {
        l->silent = 1;
        l->stats.silences++;
        return LINK_EV_SILENT;
    }
    if (!quiet && l->silent) {
        l->silent = 0;
        return LINK_EV_HEARD;
    }
    return LINK_EV_NONE;
}

void link_set_stopped(link_t *l, uint8_t stopped)
{
    l->flags = stopped ? LINKMSG_HB_STOPPED : 0u;
}

bool link_up(const link_t *l)
{
    return l->up != 0;
}

bool link_peer_silent(const link_t *l)
{
    return l->silent != 0;
}

void link_stats(const link_t *l, link_stats_t *out)
{
    hal_irq_state_t s = hal_irq_disable();
    *out = l->stats;
    out->rx_errors = l->rx.errors;
    hal_irq_restore(s);
    out->can = (hal_can_stats_t){0};
    if (l->up)
        hal_can_stats(LINK_CAN, &out->can);
}
