/*
 * canbus.c - the board link's CAN bus in a run (see canbus.h).
 */
#include "sim/canbus.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <string.h>

#include "mission/mission.h"
#include "sim/clock.h"

/* The DBC's frames and messages (firmware/link/messages.toml, through linkmsg_ids.h). */
typedef struct {
    const char *name;
    uint16_t id;
    uint8_t sender;
} frame_t;

#define FRAME_ROW(name, id, sender, len) {#name, id, sender},
static const frame_t frames[] = {LINKMSG_FRAMES(FRAME_ROW)};
#undef FRAME_ROW
#define N_FRAMES (sizeof frames / sizeof frames[0])

typedef struct {
    const char *name;
    uint8_t type;
    uint16_t id;
    uint8_t n_frames;
} message_t;

#define MESSAGE_ROW(name, type, id, n) {#name, type, id, n},
static const message_t messages[] = {LINKMSG_MESSAGES(MESSAGE_ROW)};
#undef MESSAGE_ROW
#define N_MESSAGES (sizeof messages / sizeof messages[0])
_Static_assert(N_MESSAGES <= SIM_LINK_MESSAGES, "room for every message's latency");

static const char *const fault_names[] = {"drop", "corrupt", "delay", "babble", "busoff"};
_Static_assert(sizeof fault_names / sizeof fault_names[0] == SIM_LINK_FAULT_COUNT,
               "a name per fault kind");

static int fail(char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int fail(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return -1;
}

static const frame_t *frame_named(const char *name)
{
    for (size_t i = 0; i < N_FRAMES; i++)
        if (strcmp(frames[i].name, name) == 0)
            return &frames[i];
    return NULL;
}

int sim_canbus_check(const sim_scenario_t *sc, char *err, size_t errlen)
{
    const sim_link_t *l = &sc->link;
    link_config_t c = sim_canbus_link_config(sc, LINKMSG_NODE_MAIN);
    if (1000000000ul % c.bitrate_bps != 0)
        return fail(err, errlen,
                    "link.bitrate_bps: %" PRIu32 " bit/s: its bit time (%.3f ns) is not a whole "
                    "number of nanoseconds (125000, 250000, 500000, 1000000, ...)",
                    c.bitrate_bps, 1e9 / c.bitrate_bps);
    if (c.silence_ms <= c.heartbeat_ms)
        return fail(err, errlen,
                    "link.silence_ms: %u ms must be more than the heartbeat period (%u ms): a "
                    "board would find the other silent between two heartbeats",
                    c.silence_ms, c.heartbeat_ms);
    int babblers = 0;
    for (size_t i = 0; i < l->n_faults; i++) {
        const sim_link_fault_t *f = &l->fault[i];
        if (f->kind == SIM_LINK_FAULT_BUSOFF && f->node == SIM_LINK_NODE_ANY)
            return fail(err, errlen,
                        "link.faults[%zu].node: a busoff fault needs \"main\" or "
                        "\"nav\", not \"any\"",
                        i);
        if (f->frame[0] && !frame_named(f->frame)) {
            char list[512] = "";
            size_t n = 0;
            for (size_t k = 0; k < N_FRAMES && n < sizeof list; k++)
                n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", k ? ", " : "",
                                      frames[k].name);
            return fail(err, errlen,
                        "link.faults[%zu].frame: \"%s\" is not a frame of "
                        "firmware/link/cyclopion.dbc (%s)",
                        i, f->frame, list);
        }
        if (f->frame[0] && (f->kind == SIM_LINK_FAULT_BABBLE || f->kind == SIM_LINK_FAULT_BUSOFF))
            return fail(err, errlen,
                        "link.faults[%zu].frame: a %s fault hits no frame of the "
                        "boards (remove \"frame\")",
                        i, fault_names[f->kind]);
        if (f->kind == SIM_LINK_FAULT_BABBLE) {
            if (++babblers > 1)
                return fail(err, errlen,
                            "link.faults[%zu]: a second babble fault (the bus "
                            "model has one babbling node)",
                            i);
            if (f->duration <= 0)
                return fail(err, errlen,
                            "link.faults[%zu].duration_s: a babble needs a "
                            "duration above 0",
                            i);
        }
    }
    return 0;
}

link_config_t sim_canbus_link_config(const sim_scenario_t *sc, uint8_t node)
{
    link_config_t c = MISSION_LINK_CONFIG(node);
    if (sc->link.bitrate_bps)
        c.bitrate_bps = sc->link.bitrate_bps;
    if (sc->link.heartbeat_ms)
        c.heartbeat_ms = (uint16_t)sc->link.heartbeat_ms;
    if (sc->link.silence_ms)
        c.silence_ms = (uint16_t)sc->link.silence_ms;
    return c;
}

static const char *node_name(const sim_canbus_t *cb, int node)
{
    return node == cb->main_b ? "main" : node == cb->nav_b ? "nav" : "babbler";
}

static const char *const state_names[] = {"error-active", "error-passive", "bus-off"};
static const char *const error_names[] = {"", "no acknowledgement", "CRC error", "bit error"};

/* The latency of a message whose last frame @p ev just went through. */
static void latency(sim_canbus_t *cb, const posix_can_event_t *ev)
{
    for (size_t i = 0; i < N_MESSAGES; i++) {
        const message_t *m = &messages[i];
        uint64_t queued;
        if (ev->frame.id == m->id && m->n_frames == 2) {
            cb->a_queued[m->type] = ev->queued_ns;
            cb->a_have[m->type] = 1;
            return;
        } else if (ev->frame.id == m->id) {
            queued = ev->queued_ns;
        } else if (ev->frame.id == m->id + 1u && m->n_frames == 2 && cb->a_have[m->type]) {
            queued = cb->a_queued[m->type];
            cb->a_have[m->type] = 0;
        } else {
            continue;
        }
        uint64_t l = ev->end_ns - queued;
        if (!cb->latency_seen[m->type] || l > cb->latency_max_ns[m->type])
            cb->latency_max_ns[m->type] = l;
        cb->latency_seen[m->type] = 1;
        return;
    }
}

static void on_event(void *ctx, const posix_can_event_t *ev)
{
    sim_canbus_t *cb = ctx;
    double t = sim_clock_s(ev->end_ns);
    switch (ev->kind) {
    case POSIX_CAN_EV_FRAME:
        if (cb->candump) {
            fprintf(cb->candump, "(%010" PRIu64 ".%06" PRIu64 ") %s %03X#",
                    ev->end_ns / 1000000000u, ev->end_ns / 1000u % 1000000u, cb->iface,
                    ev->frame.id);
            for (uint8_t i = 0; i < ev->frame.len; i++)
                fprintf(cb->candump, "%02X", ev->frame.data[i]);
            fputc('\n', cb->candump);
        }
        if (ev->node != POSIX_CAN_BABBLER)
            latency(cb, ev);
        if (cb->trace && ev->lost)
            fprintf(stderr, "t=%.6f can: frame %03X from %s lost by its receivers\n", t,
                    ev->frame.id, node_name(cb, ev->node));
        break;
    case POSIX_CAN_EV_ERROR:
        if (cb->trace)
            fprintf(stderr, "t=%.6f can: frame %03X from %s: %s, error frame\n", t, ev->frame.id,
                    node_name(cb, ev->node), error_names[ev->error]);
        break;
    case POSIX_CAN_EV_STATE:
        if (ev->state == HAL_CAN_BUS_OFF)
            cb->off_since[ev->node] = ev->end_ns;
        if (ev->recovered) {
            uint64_t d = ev->end_ns - cb->off_since[ev->node];
            if (d > cb->recovery_max_ns)
                cb->recovery_max_ns = d;
            cb->recoveries_seen++;
        }
        if (cb->trace)
            fprintf(stderr, "t=%.6f can: %s is %s%s\n", t, node_name(cb, ev->node),
                    state_names[ev->state], ev->recovered ? " again (recovered)" : "");
        break;
    default:
        break;
    }
}

int sim_canbus_start(sim_canbus_t *cb, const sim_scenario_t *sc, int main_b, int nav_b,
                     const char *candump, const char *iface, int trace, char *err, size_t errlen)
{
    memset(cb, 0, sizeof *cb);
    cb->main_b = main_b;
    cb->nav_b = nav_b;
    cb->trace = trace;
    snprintf(cb->iface, sizeof cb->iface, "%s", iface);
    if (candump) {
        cb->candump = fopen(candump, "w");
        if (!cb->candump)
            return fail(err, errlen, "--candump: cannot write %s: %s", candump, strerror(errno));
    }
    for (size_t i = 0; i < sc->link.n_faults; i++) {
        const sim_link_fault_t *f = &sc->link.fault[i];
        posix_can_fault_t pf;
        memset(&pf, 0, sizeof pf);
        static const posix_can_fault_kind_t kinds[] = {
            POSIX_CAN_FAULT_DROP, POSIX_CAN_FAULT_CORRUPT, POSIX_CAN_FAULT_DELAY,
            POSIX_CAN_FAULT_BABBLE, POSIX_CAN_FAULT_BUSOFF};
        pf.kind = kinds[f->kind];
        pf.from_ns = sim_clock_ns(f->at);
        pf.until_ns = sim_clock_ns(f->at + f->duration);
        pf.sender = f->node == SIM_LINK_NODE_MAIN  ? main_b
                    : f->node == SIM_LINK_NODE_NAV ? nav_b
                                                   : -1;
        pf.id = -1;
        if (f->frame[0])
            pf.id = frame_named(f->frame)->id;
        if (f->kind == SIM_LINK_FAULT_BABBLE)
            pf.id = (int)f->id;
        pf.count = f->count;
        pf.delay_ns = (uint64_t)(f->delay_ms * 1e6 + 0.5);
        pf.len = (uint8_t)f->len;
        pf.period_ns = (uint64_t)(f->period_ms * 1e6 + 0.5);
        if (posix_can_add_fault(0, &pf) != 0)
            return fail(err, errlen, "link.faults[%zu]: the bus model refuses it", i);
    }
    posix_can_set_tap(on_event, cb);
    return 0;
}

static void board_figures(sim_link_board_t *b, const link_stats_t *s)
{
    b->tx_frames = s->can.tx_frames;
    b->rx_frames = s->can.rx_frames;
    b->tx_errors = s->can.tx_errors;
    b->rx_errors = s->can.rx_errors;
    b->rx_overruns = s->can.rx_overruns;
    b->tx_aborted = s->can.tx_aborted;
    b->error_passive = s->can.error_passive;
    b->bus_off = s->can.bus_off;
    b->recoveries = s->can.recoveries;
    b->heartbeats_sent = s->heartbeats_sent;
    b->heartbeats_missed = s->peer_missed;
    b->silences = s->silences;
    b->send_refused = s->send_refused;
    b->message_errors = s->rx_errors;
}

void sim_canbus_report(const sim_canbus_t *cb, const link_stats_t *main_link,
                       const link_stats_t *nav_link, double sim_time, sim_report_t *r)
{
    sim_link_report_t *l = &r->link;
    posix_can_bus_stats_t bs;
    posix_can_bus_stats(0, &bs);
    l->bitrate_bps = bs.bitrate_bps;
    l->frames = bs.frames;
    l->errors = bs.error_frames;
    l->lost = bs.lost;
    l->bus_load = sim_time > 0 ? (double)bs.busy_ns * 1e-9 / sim_time : 0.0;
    for (int n = 0; n < POSIX_CAN_NODES; n++) {
        hal_can_stats_t st;
        if (posix_can_node(0, n, &st, NULL) == 0) {
            l->bus_off += st.bus_off;
            l->recoveries += st.recoveries;
        }
    }
    l->recovery_ms_max = (double)cb->recovery_max_ns * 1e-6;
    l->n_latency = 0;
    for (size_t i = 0; i < N_MESSAGES; i++) {
        uint8_t t = messages[i].type;
        if (!cb->latency_seen[t])
            continue;
        l->latency_name[l->n_latency] = messages[i].name;
        l->latency_ms[l->n_latency++] = (double)cb->latency_max_ns[t] * 1e-6;
    }
    board_figures(&l->board[0], main_link);
    board_figures(&l->board[1], nav_link);
}

int sim_canbus_close(sim_canbus_t *cb)
{
    posix_can_set_tap(NULL, NULL);
    int rc = 0;
    if (cb->candump && fclose(cb->candump) != 0)
        rc = -1;
    cb->candump = NULL;
    return rc;
}
