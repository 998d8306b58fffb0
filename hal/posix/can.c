/*
 * can.c - hal/can.h on the harness: the CAN bus model (rules in hal_posix/can_bus.h).
 *
 * One transaction at a time per bus: arbitrate() picks the winner among the ready nodes and
 * decides at once how the transmission ends (delivered, or an error frame and why); its end
 * event applies the outcome (counters, states, receive buffers and interrupts, the next head
 * frame) and looks for the next winner. Everything runs on harness events, so the same
 * schedule gives the same bus.
 */
#include <stddef.h>
#include <string.h>

#include "hal/can.h"
#include "hal/pinmap.h"
#include "hal_posix/can_bus.h"

#define RX_BUFFERS       2
#define RECOVERY_RUNS    128u /* occurrences of 11 consecutive recessive bits */
#define RUN_BITS         11u
#define SUSPEND_BITS     8u
#define ERROR_FRAME_BITS (6u + 8u + 3u) /* flag, delimiter, intermission */
#define ARBITRATION_BITS 13u            /* SOF, 11 identifier bits, RTR */

typedef struct bus bus_t;

typedef struct {
    bool used;
    bus_t *bus;
    int index; /* node number: the board id, or POSIX_CAN_BABBLER */
    uint32_t gen;
    hal_can_config_t cfg;
    uint64_t bit_ns;
    int source; /* receive interrupt on its board (-1: the babbler has none) */
    /* transmit FIFO; the head may start from ready_ns */
    hal_can_frame_t txq[HAL_CAN_TX_QUEUE];
    uint64_t txq_at[HAL_CAN_TX_QUEUE];
    uint8_t tx_head, tx_n;
    uint64_t ready_ns;
    uint64_t suspend_until; /* error-passive: 8 more bits after its own transmission */
    /* receive buffers */
    hal_can_frame_t rxb[RX_BUFFERS];
    uint8_t rx_head, rx_n;
    /* fault confinement */
    uint16_t tec, rec;
    uint8_t state;
    bool recovering;
    uint32_t runs;          /* occurrences counted towards recovery */
    uint64_t count_from_ns; /* recovery counting began */
    uint64_t recover_event;
    bool tx_faulty;    /* POSIX_CAN_FAULT_BUSOFF in force */
    bool wake_on_room; /* hal_can_wake_on_room(): wake the board when room may have grown */
    hal_can_stats_t stats;
} node_t;

typedef struct {
    posix_can_fault_t f;
    uint32_t hits;
    bus_t *bus;
} fault_t;

struct bus {
    int index;
    node_t node[POSIX_CAN_NODES];
    /* the transaction on the bus */
    bool busy;
    struct {
        node_t *sender;
        uint32_t gen;
        hal_can_frame_t frame;
        uint64_t queued, start, end;
        uint8_t error;     /* posix_can_err_t */
        uint16_t rx_mask;  /* nodes that receive it (or see the error) */
        uint16_t bad_rate; /* nodes at another bit rate: a receive error to them */
        bool lost;         /* a DROP fault: acknowledged, then lost */
        uint32_t trailing; /* recessive bits it ends with */
    } cur;
    uint64_t run_from_ns; /* the current recessive run began */
    uint64_t run_epoch;   /* transactions started so far */
    uint64_t arb_event, arb_at;
    fault_t fault[POSIX_CAN_MAX_FAULTS];
    int n_faults;
    fault_t *babble; /* the babbling node's fault, when one is set */
    uint32_t kinds;  /* bit k: a fault of posix_can_fault_kind_t k is set */
    uint8_t babble_count;
    posix_can_bus_stats_t stats;
};

static bus_t buses[POSIX_CAN_BUSES];
static posix_can_tap_fn tap;
static void *tap_ctx;
static posix_can_carrier_fn carrier;
static void *carrier_ctx;

static void kick(bus_t *b);

/* ------------------------------------------------------------------ timing */

uint32_t posix_can_stuffable_bits(uint8_t len)
{
    return 34u + 8u * len;
}

uint32_t posix_can_stuff_bits(uint8_t len)
{
    return (posix_can_stuffable_bits(len) - 1u) / 4u;
}

uint32_t posix_can_frame_bits(uint8_t len)
{
    return posix_can_stuffable_bits(len) + posix_can_stuff_bits(len) + 13u;
}

/* Bits up to and including the ACK slot. */
static uint32_t to_ack_bits(uint8_t len)
{
    return posix_can_stuffable_bits(len) + posix_can_stuff_bits(len) + 2u;
}

/* ------------------------------------------------------------------ set-up */

void posix_can_reset(void)
{
    memset(buses, 0, sizeof buses);
    for (int i = 0; i < POSIX_CAN_BUSES; i++) {
        buses[i].index = i;
        for (int n = 0; n < POSIX_CAN_NODES; n++) {
            buses[i].node[n].bus = &buses[i];
            buses[i].node[n].index = n;
            buses[i].node[n].source = -1;
        }
    }
    tap = NULL;
    tap_ctx = NULL;
    carrier = NULL;
    carrier_ctx = NULL;
}

void posix_can_set_tap(posix_can_tap_fn fn, void *ctx)
{
    tap = fn;
    tap_ctx = ctx;
}

void posix_can_set_carrier(posix_can_carrier_fn fn, void *ctx)
{
    carrier = fn;
    carrier_ctx = ctx;
}

static bus_t *bus_at(hal_can_t can)
{
    if (can >= POSIX_CAN_BUSES)
        return NULL;
    if (buses[0].node[0].bus == NULL) /* first use without posix_reset() (unit tests) */
        posix_can_reset();
    return &buses[can];
}

static void sat16(uint16_t *c)
{
    if (*c < UINT16_MAX)
        (*c)++;
}

static void sat32(uint32_t *c)
{
    if (*c < UINT32_MAX)
        (*c)++;
}

/* ------------------------------------------------------------------ fault confinement */

static void emit_state(node_t *n, bool recovered)
{
    if (!tap)
        return;
    posix_can_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = POSIX_CAN_EV_STATE;
    ev.bus = (uint8_t)n->bus->index;
    ev.node = (int8_t)n->index;
    ev.state = n->state;
    ev.recovered = recovered;
    ev.start_ns = ev.end_ns = posix_now_ns();
    tap(tap_ctx, &ev);
}

static void flush_tx(node_t *n)
{
    for (uint8_t i = 0; i < n->tx_n; i++)
        sat16(&n->stats.tx_aborted);
    n->tx_n = 0;
    n->tx_head = 0;
}

static uint64_t run_start_for(const node_t *n)
{
    return n->bus->run_from_ns > n->count_from_ns ? n->bus->run_from_ns : n->count_from_ns;
}

static void recover_event(void *ctx, uint64_t t);

/* While the bus is recessive, a recovering node completes at the 128th occurrence. */
static void schedule_recovery(node_t *n)
{
    if (n->recover_event) {
        posix_cancel(n->recover_event);
        n->recover_event = 0;
    }
    if (!n->recovering || n->bus->busy)
        return;
    uint64_t t = run_start_for(n) + (uint64_t)(RECOVERY_RUNS - n->runs) * RUN_BITS * n->bit_ns;
    if (t < posix_now_ns())
        t = posix_now_ns();
    n->recover_event = posix_schedule(t, recover_event, n);
}

/* Room in @p n's transmit queue may have grown: the main loop waiting for it runs. */
static void room_grew(node_t *n)
{
    if (n->wake_on_room) {
        n->wake_on_room = false;
        posix_board_wake(n->index);
    }
}

/* The 128th occurrence: error-active again with both counters 0. */
static void recovered(node_t *n)
{
    n->recovering = false;
    n->state = HAL_CAN_ERROR_ACTIVE;
    n->tec = n->rec = 0;
    n->runs = 0;
    sat16(&n->stats.recoveries);
    emit_state(n, true);
    room_grew(n);
}

static void recover_event(void *ctx, uint64_t t)
{
    (void)t;
    node_t *n = ctx;
    n->recover_event = 0;
    if (!n->used || !n->recovering || n->bus->busy)
        return;
    recovered(n);
    kick(n->bus);
}

static void start_recovery(node_t *n)
{
    n->recovering = true;
    n->runs = 0;
    n->count_from_ns = posix_now_ns();
    schedule_recovery(n);
}

/* The state the counters give; transitions counted and told. */
static void update_state(node_t *n)
{
    if (n->state == HAL_CAN_BUS_OFF)
        return; /* only the recovery leaves it */
    uint8_t s = n->tec > 255   ? HAL_CAN_BUS_OFF
                : n->tec > 127 ? HAL_CAN_ERROR_PASSIVE
                : n->rec > 127 ? HAL_CAN_ERROR_PASSIVE
                               : HAL_CAN_ERROR_ACTIVE;
    if (s == n->state)
        return;
    n->state = s;
    if (s == HAL_CAN_ERROR_PASSIVE)
        sat16(&n->stats.error_passive);
    if (s == HAL_CAN_BUS_OFF) {
        sat16(&n->stats.bus_off);
        n->tx_faulty = false; /* the broken transceiver is cut off: the fault ends */
        n->rx_n = 0;
        flush_tx(n);
        n->recovering = false;
        if (n->recover_event) {
            posix_cancel(n->recover_event);
            n->recover_event = 0;
        }
    }
    emit_state(n, false);
    if (s == HAL_CAN_BUS_OFF && !n->cfg.manual_recovery)
        start_recovery(n);
}

static void rec_error(node_t *n)
{
    sat16(&n->stats.rx_errors);
    if (n->rec < 255)
        n->rec++;
}

static void rec_success(node_t *n)
{
    if (n->rec > 127)
        n->rec = 119;
    else if (n->rec > 0)
        n->rec--;
}

/* ------------------------------------------------------------------ faults */

/* A fault of @p kind that hits a frame of node @p n with @p id now (its count consumed). */
static bool fault_hits(bus_t *b, posix_can_fault_kind_t kind, const node_t *n, uint16_t id,
                       uint64_t *delay)
{
    if (!(b->kinds & (1u << kind)))
        return false; /* none of that kind: most frames of most runs */
    uint64_t now = posix_now_ns();
    for (int i = 0; i < b->n_faults; i++) {
        fault_t *f = &b->fault[i];
        if (f->f.kind != kind || now < f->f.from_ns || now >= f->f.until_ns)
            continue;
        if ((f->f.sender >= 0 && f->f.sender != n->index) || (f->f.id >= 0 && f->f.id != id))
            continue;
        if (f->f.count && f->hits >= f->f.count)
            continue;
        f->hits++;
        if (delay)
            *delay = f->f.delay_ns;
        return true;
    }
    return false;
}

/* The head frame of @p n is new: when it may start. */
static void head_changed(node_t *n)
{
    uint64_t now = posix_now_ns();
    n->ready_ns = n->suspend_until > now ? n->suspend_until : now;
    uint64_t delay = 0;
    if (n->tx_n && fault_hits(n->bus, POSIX_CAN_FAULT_DELAY, n, n->txq[n->tx_head].id, &delay))
        n->ready_ns += delay;
}

static int queue_frame(node_t *n, const hal_can_frame_t *f)
{
    if (n->tx_n >= HAL_CAN_TX_QUEUE)
        return HAL_CAN_E_FULL;
    uint8_t slot = (uint8_t)((n->tx_head + n->tx_n) % HAL_CAN_TX_QUEUE);
    n->txq[slot] = *f;
    n->txq_at[slot] = posix_now_ns();
    n->tx_n++;
    if (n->tx_n == 1)
        head_changed(n);
    kick(n->bus);
    return 0;
}

/* The babbler's next frame: id, len bytes of a counter. */
static void babble_queue(bus_t *b)
{
    node_t *n = &b->node[POSIX_CAN_BABBLER];
    hal_can_frame_t f;
    memset(&f, 0, sizeof f);
    f.id = (uint16_t)b->babble->f.id;
    f.len = b->babble->f.len;
    for (uint8_t i = 0; i < f.len; i++)
        f.data[i] = (uint8_t)(b->babble_count + i);
    b->babble_count++;
    queue_frame(n, &f);
}

static uint32_t rate_of(const bus_t *b)
{
    for (int i = 0; i < POSIX_MAX_BOARDS; i++)
        if (b->node[i].used)
            return b->node[i].cfg.bitrate_bps;
    return 0;
}

static void babble_start(void *ctx, uint64_t t)
{
    (void)t;
    fault_t *f = ctx;
    bus_t *b = f->bus;
    node_t *n = &b->node[POSIX_CAN_BABBLER];
    uint32_t rate = rate_of(b);
    if (rate == 0)
        return; /* nobody on the bus to babble at */
    uint32_t gen = n->gen + 1;
    memset(n, 0, sizeof *n);
    n->bus = b;
    n->index = POSIX_CAN_BABBLER;
    n->gen = gen;
    n->source = -1;
    n->used = true;
    n->cfg.bitrate_bps = rate;
    n->bit_ns = 1000000000ull / rate;
    n->state = HAL_CAN_ERROR_ACTIVE;
    b->babble_count = 0;
    babble_queue(b);
}

static void babble_stop(void *ctx, uint64_t t)
{
    (void)t;
    fault_t *f = ctx;
    node_t *n = &f->bus->node[POSIX_CAN_BABBLER];
    n->used = false;
    n->tx_n = 0;
    if (n->recover_event)
        posix_cancel(n->recover_event);
    n->recover_event = 0;
    kick(f->bus);
}

static void busoff_start(void *ctx, uint64_t t)
{
    (void)t;
    fault_t *f = ctx;
    node_t *n = &f->bus->node[f->f.sender];
    if (n->used && n->state != HAL_CAN_BUS_OFF)
        n->tx_faulty = true;
}

int posix_can_add_fault(hal_can_t can, const posix_can_fault_t *f)
{
    bus_t *b = bus_at(can);
    if (!b || !f || b->n_faults >= POSIX_CAN_MAX_FAULTS || f->until_ns < f->from_ns ||
        f->from_ns < posix_now_ns())
        return -1;
    switch (f->kind) {
    case POSIX_CAN_FAULT_DROP:
    case POSIX_CAN_FAULT_CORRUPT:
    case POSIX_CAN_FAULT_DELAY:
        if (f->sender < -1 || f->sender >= POSIX_CAN_NODES || f->id < -1 ||
            f->id > (int)HAL_CAN_MAX_ID)
            return -1;
        break;
    case POSIX_CAN_FAULT_BABBLE:
        if (b->babble || f->id < 0 || f->id > (int)HAL_CAN_MAX_ID || f->len > HAL_CAN_MAX_DATA ||
            f->until_ns == f->from_ns)
            return -1;
        break;
    case POSIX_CAN_FAULT_BUSOFF:
        if (f->sender < 0 || f->sender >= POSIX_MAX_BOARDS)
            return -1;
        break;
    default:
        return -1;
    }
    fault_t *slot = &b->fault[b->n_faults];
    slot->f = *f;
    slot->hits = 0;
    slot->bus = b;
    if (f->kind == POSIX_CAN_FAULT_BABBLE) {
        if (!posix_schedule(f->from_ns, babble_start, slot) ||
            !posix_schedule(f->until_ns, babble_stop, slot))
            return -1;
        b->babble = slot;
    } else if (f->kind == POSIX_CAN_FAULT_BUSOFF) {
        if (!posix_schedule(f->from_ns, busoff_start, slot))
            return -1;
    }
    b->n_faults++;
    b->kinds |= 1u << f->kind;
    return 0;
}

/* ------------------------------------------------------------------ the bus */

static bool accepts(const node_t *n, uint16_t id)
{
    if (n->cfg.n_filters == 0)
        return true;
    for (uint8_t i = 0; i < n->cfg.n_filters; i++) {
        const hal_can_filter_t *fl = &n->cfg.filters[i];
        if ((id & fl->mask) == (fl->id & fl->mask))
            return true;
    }
    return false;
}

static void end_event(void *ctx, uint64_t t);
static void arb_event(void *ctx, uint64_t t);

/* Start the transmission of @p n's head frame now. */
static void transmit(bus_t *b, node_t *n)
{
    uint64_t now = posix_now_ns();
    /* A start of frame ends the recessive run: recovering nodes count what it gave (one that
     * reaches 128 occurrences just now is back before this frame). */
    for (int i = 0; i < POSIX_CAN_NODES; i++) {
        node_t *r = &b->node[i];
        if (!r->used || !r->recovering)
            continue;
        uint64_t from = run_start_for(r);
        if (now > from)
            r->runs += (uint32_t)((now - from) / (RUN_BITS * r->bit_ns));
        if (r->recover_event) {
            posix_cancel(r->recover_event);
            r->recover_event = 0;
        }
        if (r->runs >= RECOVERY_RUNS)
            recovered(r);
    }
    const hal_can_frame_t *f = &n->txq[n->tx_head];
    memset(&b->cur, 0, sizeof b->cur);
    b->cur.sender = n;
    b->cur.gen = n->gen;
    b->cur.frame = *f;
    b->cur.queued = n->txq_at[n->tx_head];
    b->cur.start = now;
    bool any_active = n->state == HAL_CAN_ERROR_ACTIVE;
    for (int i = 0; i < POSIX_CAN_NODES; i++) {
        node_t *r = &b->node[i];
        if (r == n || !r->used || r->state == HAL_CAN_BUS_OFF)
            continue;
        if (r->bit_ns != n->bit_ns) {
            b->cur.bad_rate |= (uint16_t)(1u << i);
            continue;
        }
        b->cur.rx_mask |= (uint16_t)(1u << i);
        any_active |= r->state == HAL_CAN_ERROR_ACTIVE;
    }
    uint32_t bits;
    if (n->tx_faulty) {
        b->cur.error = POSIX_CAN_ERR_BIT;
        bits = ARBITRATION_BITS + ERROR_FRAME_BITS;
        b->cur.trailing = any_active ? 11u : 17u;
    } else if (b->cur.rx_mask && fault_hits(b, POSIX_CAN_FAULT_CORRUPT, n, f->id, NULL)) {
        b->cur.error = POSIX_CAN_ERR_CRC;
        bits = to_ack_bits(f->len) + ERROR_FRAME_BITS;
        b->cur.trailing = any_active ? 11u : 19u;
    } else if (!b->cur.rx_mask) {
        b->cur.error = POSIX_CAN_ERR_ACK;
        bits = to_ack_bits(f->len) + ERROR_FRAME_BITS;
        b->cur.trailing = n->state == HAL_CAN_ERROR_ACTIVE ? 11u : 19u;
    } else {
        bits = posix_can_frame_bits(f->len);
        b->cur.trailing = 11u;
        b->cur.lost = fault_hits(b, POSIX_CAN_FAULT_DROP, n, f->id, NULL);
    }
    b->cur.end = now + bits * n->bit_ns;
    b->busy = true;
    b->run_epoch++;
    posix_schedule(b->cur.end, end_event, b);
}

static void deliver(bus_t *b, const hal_can_frame_t *f, uint16_t *delivered, uint16_t *lost)
{
    for (int i = 0; i < POSIX_CAN_NODES; i++) {
        if (!(b->cur.rx_mask & (1u << i)))
            continue;
        node_t *r = &b->node[i];
        rec_success(r);
        update_state(r);
        if (i == POSIX_CAN_BABBLER || !accepts(r, f->id))
            continue;
        if (b->cur.lost || r->rx_n >= RX_BUFFERS) {
            sat16(&r->stats.rx_overruns);
            *lost |= (uint16_t)(1u << i);
            continue;
        }
        r->rxb[(r->rx_head + r->rx_n) % RX_BUFFERS] = *f;
        r->rx_n++;
        *delivered |= (uint16_t)(1u << i);
        posix_source_raise(i, r->source);
    }
}

static void end_event(void *ctx, uint64_t t)
{
    bus_t *b = ctx;
    node_t *n = b->cur.sender;
    bool sender_here = n->used && n->gen == b->cur.gen; /* not re-initialised meanwhile */
    posix_can_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.bus = (uint8_t)b->index;
    ev.node = (int8_t)n->index;
    ev.frame = b->cur.frame;
    ev.queued_ns = b->cur.queued;
    ev.start_ns = b->cur.start;
    ev.end_ns = t;
    b->busy = false;
    b->run_from_ns = t - b->cur.trailing * n->bit_ns;
    b->stats.busy_ns += t - b->cur.start;
    for (int i = 0; b->cur.bad_rate && i < POSIX_CAN_NODES; i++)
        if (b->cur.bad_rate & (1u << i))
            rec_error(&b->node[i]);

    if (b->cur.error == POSIX_CAN_ERR_NONE) {
        b->stats.frames++;
        ev.kind = POSIX_CAN_EV_FRAME;
        hal_can_frame_t got = b->cur.frame;
        if (carrier && carrier(carrier_ctx, (hal_can_t)b->index, &b->cur.frame, &got) != 0)
            got = b->cur.frame;
        ev.frame = got;
        deliver(b, &got, &ev.delivered, &ev.lost);
        b->stats.lost += (uint64_t)__builtin_popcount(ev.lost);
        if (sender_here) {
            sat32(&n->stats.tx_frames);
            if (n->tec > 0)
                n->tec--;
            n->tx_head = (uint8_t)((n->tx_head + 1u) % HAL_CAN_TX_QUEUE);
            n->tx_n--;
            room_grew(n);
        }
    } else {
        b->stats.error_frames++;
        ev.kind = POSIX_CAN_EV_ERROR;
        ev.error = b->cur.error;
        for (int i = 0; i < POSIX_CAN_NODES; i++)
            if (b->cur.rx_mask & (1u << i))
                rec_error(&b->node[i]);
        if (sender_here) {
            sat16(&n->stats.tx_errors);
            bool passive_ack = b->cur.error == POSIX_CAN_ERR_ACK &&
                               n->state == HAL_CAN_ERROR_PASSIVE; /* rule 3, exception 1 */
            if (!passive_ack)
                n->tec = (uint16_t)(n->tec + 8u);
        }
    }
    /* deliver() brought the receivers of a frame up to date already: their counters have
     * not moved since. */
    uint16_t changed = b->cur.bad_rate;
    if (b->cur.error != POSIX_CAN_ERR_NONE)
        changed |= b->cur.rx_mask;
    for (int i = 0; changed && i < POSIX_CAN_NODES; i++)
        if (changed & (1u << i))
            update_state(&b->node[i]);
    if (sender_here) {
        update_state(n);
        n->suspend_until = n->state == HAL_CAN_ERROR_PASSIVE ? t + SUSPEND_BITS * n->bit_ns : 0;
        if (n->index == POSIX_CAN_BABBLER && b->cur.error == POSIX_CAN_ERR_NONE && b->babble) {
            uint64_t next = b->cur.start + b->babble->f.period_ns;
            babble_queue(b);
            if (n->tx_n && next > n->ready_ns)
                n->ready_ns = next;
        } else if (b->cur.error == POSIX_CAN_ERR_NONE && n->tx_n) {
            head_changed(n);
        } else if (n->tx_n) {
            n->ready_ns = n->suspend_until > t ? n->suspend_until : t; /* retransmission */
        }
    }
    if (tap)
        tap(tap_ctx, &ev);
    for (int i = 0; i < POSIX_CAN_NODES; i++)
        if (b->node[i].recovering || b->node[i].recover_event) /* else nothing to schedule */
            schedule_recovery(&b->node[i]);
    kick(b);
}

/* The earliest instant a node's head frame may contend (UINT64_MAX: none). */
static uint64_t next_ready(const bus_t *b)
{
    uint64_t t = UINT64_MAX;
    for (int i = 0; i < POSIX_CAN_NODES; i++) {
        const node_t *n = &b->node[i];
        if (n->used && n->tx_n && n->state != HAL_CAN_BUS_OFF && n->ready_ns < t)
            t = n->ready_ns;
    }
    return t;
}

static void arb_event(void *ctx, uint64_t t)
{
    bus_t *b = ctx;
    b->arb_event = 0;
    if (b->busy)
        return;
    node_t *win = NULL;
    for (int i = 0; i < POSIX_CAN_NODES; i++) {
        node_t *n = &b->node[i];
        if (!n->used || !n->tx_n || n->state == HAL_CAN_BUS_OFF || n->ready_ns > t)
            continue;
        if (!win || n->txq[n->tx_head].id < win->txq[win->tx_head].id)
            win = n;
    }
    if (win)
        transmit(b, win);
    else
        kick(b);
}

/* Make sure an arbitration happens when the next frame is ready and the bus idle. */
static void kick(bus_t *b)
{
    if (b->busy)
        return;
    uint64_t t = next_ready(b), now = posix_now_ns();
    if (t < now)
        t = now;
    if (b->arb_event && b->arb_at == t)
        return;
    if (b->arb_event) {
        posix_cancel(b->arb_event);
        b->arb_event = 0;
    }
    if (t == UINT64_MAX)
        return;
    b->arb_at = t;
    b->arb_event = posix_schedule(t, arb_event, b);
}

/* ------------------------------------------------------------------ hal/can.h */

static void rx_isr(void *ctx)
{
    node_t *n = ctx;
    while (n->rx_n) {
        hal_can_frame_t f = n->rxb[n->rx_head];
        n->rx_head = (uint8_t)((n->rx_head + 1u) % RX_BUFFERS);
        n->rx_n--;
        sat32(&n->stats.rx_frames);
        n->cfg.rx_cb(n->cfg.rx_arg, &f);
    }
}

/* The current board's node on @p can, or NULL. */
static node_t *my_node(hal_can_t can)
{
    bus_t *b = bus_at(can);
    return b ? &b->node[posix_board_current()] : NULL;
}

int hal_can_init(hal_can_t can, const hal_can_config_t *cfg)
{
    node_t *n = my_node(can);
    if (!n || !cfg || !cfg->rx_cb || cfg->n_filters > HAL_CAN_FILTERS)
        return HAL_CAN_E_PARAM;
    for (uint8_t i = 0; i < cfg->n_filters; i++)
        if (cfg->filters[i].id > HAL_CAN_MAX_ID || cfg->filters[i].mask > HAL_CAN_MAX_ID)
            return HAL_CAN_E_PARAM;
    if (cfg->bitrate_bps < HAL_CAN_BITRATE_MIN || cfg->bitrate_bps > HAL_CAN_BITRATE_MAX ||
        1000000000ul % cfg->bitrate_bps != 0)
        return HAL_CAN_E_BITRATE;
    int board = posix_board_current();
    int source = posix_source_register(
        board, HAL_CAN0_VECTOR, can == 0 ? HAL_CAN0_INT_PIN : POSIX_CAN1_INT_PIN, false, rx_isr, n);
    if (source < 0)
        return HAL_CAN_E_HARDWARE;
    if (n->recover_event)
        posix_cancel(n->recover_event);
    bus_t *b = n->bus;
    uint32_t gen = n->gen + 1;
    memset(n, 0, sizeof *n);
    n->bus = b;
    n->index = board;
    n->gen = gen;
    n->used = true;
    n->cfg = *cfg;
    n->bit_ns = 1000000000ull / cfg->bitrate_bps;
    n->source = source;
    n->state = HAL_CAN_ERROR_ACTIVE;
    if (b->stats.bitrate_bps == 0)
        b->stats.bitrate_bps = cfg->bitrate_bps;
    return 0;
}

int hal_can_send(hal_can_t can, const hal_can_frame_t *f)
{
    node_t *n = my_node(can);
    if (!n || !f || f->id > HAL_CAN_MAX_ID || f->len > HAL_CAN_MAX_DATA)
        return HAL_CAN_E_PARAM;
    if (!n->used)
        return HAL_CAN_E_STATE;
    if (n->state == HAL_CAN_BUS_OFF)
        return HAL_CAN_E_BUS_OFF;
    return queue_frame(n, f);
}

uint8_t hal_can_tx_room(hal_can_t can)
{
    node_t *n = my_node(can);
    if (!n || !n->used || n->state == HAL_CAN_BUS_OFF)
        return 0;
    return (uint8_t)(HAL_CAN_TX_QUEUE - n->tx_n);
}

void hal_can_wake_on_room(hal_can_t can)
{
    node_t *n = my_node(can);
    if (n && n->used)
        n->wake_on_room = true;
}

static void status_of(const node_t *n, hal_can_status_t *out)
{
    out->state = n->state;
    out->recovering = n->recovering;
    out->tec = n->tec;
    out->rec = n->rec;
}

int hal_can_status(hal_can_t can, hal_can_status_t *out)
{
    node_t *n = my_node(can);
    if (!n || !out)
        return HAL_CAN_E_PARAM;
    if (!n->used)
        return HAL_CAN_E_STATE;
    status_of(n, out);
    return 0;
}

int hal_can_stats(hal_can_t can, hal_can_stats_t *out)
{
    node_t *n = my_node(can);
    if (!n || !out)
        return HAL_CAN_E_PARAM;
    if (!n->used)
        return HAL_CAN_E_STATE;
    *out = n->stats;
    return 0;
}

int hal_can_recover(hal_can_t can)
{
    node_t *n = my_node(can);
    if (!n)
        return HAL_CAN_E_PARAM;
    if (!n->used || n->state != HAL_CAN_BUS_OFF)
        return HAL_CAN_E_STATE;
    if (!n->recovering)
        start_recovery(n);
    return 0;
}

/* ------------------------------------------------------------------ host side */

int posix_can_bus_stats(hal_can_t can, posix_can_bus_stats_t *out)
{
    bus_t *b = bus_at(can);
    if (!b || !out)
        return -1;
    *out = b->stats;
    return 0;
}

int posix_can_node(hal_can_t can, int node, hal_can_stats_t *stats, hal_can_status_t *status)
{
    bus_t *b = bus_at(can);
    if (!b || node < 0 || node >= POSIX_CAN_NODES || (!b->node[node].used && !b->node[node].gen))
        return -1;
    if (stats)
        *stats = b->node[node].stats;
    if (status)
        status_of(&b->node[node], status);
    return 0;
}
