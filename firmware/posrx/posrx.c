/*
 * posrx.c - the serial position receiver (see posrx.h, docs/posrx.md).
 */
#include "posrx/posrx.h"

#include <stddef.h>

#include "fx/fx.h"
#include "hal/irq.h"
#include "hal/uart.h"

#define RING_MASK (POSRX_RING - 1u)
_Static_assert((POSRX_RING & RING_MASK) == 0 && POSRX_RING >= POSRX_PACKET_BYTES,
               "the ring is a power of two that holds a packet");
_Static_assert((POSRX_QUEUE & (POSRX_QUEUE - 1u)) == 0, "the queue is a power of two");

bool posrx_init(posrx_t *r, const posrx_config_t *cfg)
{
    if (cfg->max_speed_mm_s == 0)
        return false;
    *r = (posrx_t){0};
    r->cfg = *cfg;
    return true;
}

void posrx_set_reference(posrx_t *r, int32_t x_mm, int32_t y_mm, uint32_t t_ms)
{
    r->ref = (posrx_pos_t){x_mm, y_mm, 0, t_ms};
    r->has_ref = true;
}

void posrx_rx_byte(posrx_t *r, uint8_t byte, uint8_t flags, uint32_t now_ms)
{
    uint8_t w = r->w;
    r->ring[w & RING_MASK] = byte;
    r->w = (uint8_t)(w + 1u);
    r->st.bytes++;
    if (r->since != UINT16_MAX)
        r->since++;
    if (flags & HAL_UART_RX_ERROR) {
        r->st.error_bytes++;
        r->run = 0; /* no packet may hold this byte */
        return;
    }
    if (r->run != UINT8_MAX)
        r->run++;
    /* The seed's test: the newest byte ends a packet and the one 13 before starts it. */
    uint8_t first = (uint8_t)(w - (POSRX_PACKET_BYTES - 1u));
    if (byte != POSRX_END_BYTE || r->run < POSRX_PACKET_BYTES ||
        r->ring[first & RING_MASK] != POSRX_START_BYTE)
        return;
    if (r->since > POSRX_PACKET_BYTES) {
        r->st.resyncs++;
        r->st.skipped += (uint32_t)(r->since - POSRX_PACKET_BYTES);
    }
    r->st.framed++;
    r->since = 0;
    r->run = 0;
    if (r->q_n == POSRX_QUEUE) { /* the main loop is late: the oldest goes */
        r->q_head = (uint8_t)((r->q_head + 1u) & (POSRX_QUEUE - 1u));
        r->q_n--;
        r->st.dropped++;
    }
    posrx_raw_t *q = &r->q[(r->q_head + r->q_n) & (POSRX_QUEUE - 1u)];
    for (uint8_t i = 0; i < 12u; i++)
        q->raw[i] = r->ring[(uint8_t)(first + 1u + i) & RING_MASK];
    q->t_ms = now_ms;
    r->q_n++;
}

static int32_t be32(const uint8_t *b)
{
    return (int32_t)(((uint32_t)b[0] << 24) | ((uint32_t)b[1] << 16) | ((uint32_t)b[2] << 8) |
                     (uint32_t)b[3]);
}

bool posrx_take(posrx_t *r, posrx_pos_t *out)
{
    posrx_raw_t q;
    hal_critical_enter();
    bool any = r->q_n != 0;
    if (any) {
        q = r->q[r->q_head];
        r->q_head = (uint8_t)((r->q_head + 1u) & (POSRX_QUEUE - 1u));
        r->q_n--;
    }
    hal_critical_exit();
    if (!any)
        return false;
    out->x = be32(q.raw);
    out->y = be32(q.raw + 4);
    out->z = be32(q.raw + 8);
    out->t_ms = q.t_ms;
    return true;
}

static uint32_t abs32(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

/* How far the vehicle can go in @p dt_ms at the configured speed, mm. */
static uint32_t reach_mm(const posrx_t *r, uint32_t dt_ms)
{
    if (dt_ms > POSRX_MAX_DT_MS)
        dt_ms = POSRX_MAX_DT_MS;
    uint32_t v = r->cfg.max_speed_mm_s;
    return v * (dt_ms / 1000u) + v * (dt_ms % 1000u) / 1000u;
}

posrx_reason_t posrx_check(posrx_t *r, const posrx_pos_t *p, uint32_t *dist_mm)
{
    posrx_reason_t why = POSRX_OK;
    uint32_t d = 0;
    if (p->x == 0 && p->y == 0 && p->z == 0) {
        why = POSRX_ZERO;
    } else if (abs32(p->x) > (uint32_t)POSRX_RANGE_MM || abs32(p->y) > (uint32_t)POSRX_RANGE_MM) {
        why = POSRX_JUMP; /* beyond any place the firmware can hold */
        d = UINT32_MAX;
    } else if (r->has_ref) {
        /* both within +-2^25 mm: the differences fit, and so does their length */
        d = fx_hypot(p->x - r->ref.x, p->y - r->ref.y);
        if (d > reach_mm(r, p->t_ms - r->ref.t_ms))
            why = POSRX_JUMP;
        else if (d < r->cfg.min_update_mm)
            why = POSRX_TOO_CLOSE;
    }
    if (why == POSRX_OK) {
        r->ref = *p;
        r->has_ref = true;
    }
    r->st.reason[why]++;
    if (dist_mm)
        *dist_mm = d;
    return why;
}

const char *posrx_reason_name(posrx_reason_t reason)
{
    static const char *const names[POSRX_REASON_COUNT] = {"ok", "zero", "jump", "too_close"};
    return (unsigned)reason < POSRX_REASON_COUNT ? names[reason] : "?";
}

void posrx_stats(const posrx_t *r, posrx_stats_t *out)
{
    hal_critical_enter();
    *out = r->st;
    hal_critical_exit();
}
