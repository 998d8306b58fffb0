/*
 * linkmsg.c - inter-board messages as frames (see linkmsg.h).
 */
#include "link/linkmsg.h"

#include "hal/irq.h"

static void put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

static uint16_t get16(const uint8_t *p)
{
    return (uint16_t)(p[0] | ((uint16_t)p[1] << 8));
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

/* CRC-8 (polynomial 0x07) of an A frame's 8 data bytes: the tag of its B frame. */
static uint8_t tag_of(const uint8_t *a)
{
    uint8_t crc = 0;
    for (uint8_t i = 0; i < 8; i++) {
        crc ^= a[i];
        for (uint8_t b = 0; b < 8; b++)
            crc = (uint8_t)((crc & 0x80u) ? (uint8_t)(crc << 1) ^ 0x07u : (uint8_t)(crc << 1));
    }
    return crc;
}

/* A frame (x, y) and the first four bytes of the B frame (heading). */
static void pose_pair(uint16_t id_a, const linkmsg_pose_t *p, hal_link_frame_t out[2])
{
    out[0].id = id_a;
    out[0].len = 8;
    put32(out[0].data, (uint32_t)p->x);
    put32(out[0].data + 4, (uint32_t)p->y);
    out[1].id = (uint16_t)(id_a + 1u);
    put32(out[1].data, p->heading);
}

uint8_t linkmsg_encode(const linkmsg_t *m, hal_link_frame_t out[2])
{
    switch (m->type) {
    case LINKMSG_STOP:
        out[0].id = LINKMSG_ID_STOP;
        out[0].len = 1;
        out[0].data[0] = m->u.stop.reason;
        return 1;
    case LINKMSG_POSE:
        pose_pair(LINKMSG_ID_POSE_A, &m->u.pose.pose, out);
        out[1].data[4] = m->u.pose.request;
        out[1].data[5] = tag_of(out[0].data);
        out[1].len = 6;
        return 2;
    case LINKMSG_FIX:
        pose_pair(LINKMSG_ID_FIX_A, &m->u.fix.pose, out);
        put16(out[1].data + 4, m->u.fix.latch);
        out[1].data[6] = m->u.fix.flags;
        out[1].data[7] = tag_of(out[0].data);
        out[1].len = 8;
        return 2;
    case LINKMSG_FIX_ACK:
        out[0].id = LINKMSG_ID_FIX_ACK;
        out[0].len = 3;
        out[0].data[0] = (uint8_t)m->u.fix_ack.status;
        put16(out[0].data + 1, m->u.fix_ack.latch);
        return 1;
    case LINKMSG_LATCH_REQ:
        out[0].id = LINKMSG_ID_LATCH_REQ;
        out[0].len = 3;
        put16(out[0].data, m->u.latch_req.first);
        out[0].data[2] = m->u.latch_req.count;
        return 1;
    case LINKMSG_LATCH:
        pose_pair(LINKMSG_ID_LATCH_A, &m->u.latch.pose, out);
        put16(out[1].data + 4, m->u.latch.seq);
        out[1].data[6] = (uint8_t)m->u.latch.status;
        out[1].data[7] = tag_of(out[0].data);
        out[1].len = 8;
        return 2;
    case LINKMSG_DIR:
        out[0].id = LINKMSG_ID_DIR;
        out[0].len = 1;
        out[0].data[0] = m->u.dir.reverse;
        return 1;
    default:
        return 0;
    }
}

void linkmsg_rx_init(linkmsg_rx_t *rx)
{
    for (uint8_t i = 0; i < 3; i++)
        rx->have[i] = 0;
    rx->errors = 0;
}

/* Slot of an A/B pair by its A id (called with the three A ids only). */
static uint8_t slot_of(uint16_t id_a)
{
    return id_a == LINKMSG_ID_FIX_A ? 1u : id_a == LINKMSG_ID_LATCH_A ? 2u : 0u;
}

static bool bad(linkmsg_rx_t *rx)
{
    rx->errors++;
    return false;
}

bool linkmsg_rx_feed(linkmsg_rx_t *rx, const hal_link_frame_t *f, linkmsg_t *out)
{
    const uint8_t *d = f->data;
    uint8_t s;
    switch (f->id) {
    case LINKMSG_ID_STOP:
        if (f->len != 1)
            return bad(rx);
        out->type = LINKMSG_STOP;
        out->u.stop.reason = d[0];
        return true;
    case LINKMSG_ID_FIX_ACK:
        if (f->len != 3)
            return bad(rx);
        out->type = LINKMSG_FIX_ACK;
        out->u.fix_ack.status = (int8_t)d[0];
        out->u.fix_ack.latch = get16(d + 1);
        return true;
    case LINKMSG_ID_LATCH_REQ:
        if (f->len != 3)
            return bad(rx);
        out->type = LINKMSG_LATCH_REQ;
        out->u.latch_req.first = get16(d);
        out->u.latch_req.count = d[2];
        return true;
    case LINKMSG_ID_DIR:
        if (f->len != 1)
            return bad(rx);
        out->type = LINKMSG_DIR;
        out->u.dir.reverse = d[0];
        return true;
    case LINKMSG_ID_POSE_A:
    case LINKMSG_ID_FIX_A:
    case LINKMSG_ID_LATCH_A:
        s = slot_of(f->id);
        if (f->len != 8) {
            rx->have[s] = 0;
            return bad(rx);
        }
        for (uint8_t i = 0; i < 8; i++)
            rx->a[s][i] = d[i];
        rx->have[s] = 1;
        return false;
    case LINKMSG_ID_POSE_B:
    case LINKMSG_ID_FIX_B:
    case LINKMSG_ID_LATCH_B:
        s = slot_of((uint16_t)(f->id - 1u));
        if (!rx->have[s] || f->len != (s == 0 ? 6u : 8u) || d[f->len - 1u] != tag_of(rx->a[s])) {
            rx->have[s] = 0;
            return bad(rx);
        }
        rx->have[s] = 0;
        {
            linkmsg_pose_t p;
            p.x = (fx_q16_t)get32(rx->a[s]);
            p.y = (fx_q16_t)get32(rx->a[s] + 4);
            p.heading = get32(d);
            if (s == 0) {
                out->type = LINKMSG_POSE;
                out->u.pose.pose = p;
                out->u.pose.request = d[4];
            } else if (s == 1) {
                out->type = LINKMSG_FIX;
                out->u.fix.pose = p;
                out->u.fix.latch = get16(d + 4);
                out->u.fix.flags = d[6];
            } else {
                out->type = LINKMSG_LATCH;
                out->u.latch.pose = p;
                out->u.latch.seq = get16(d + 4);
                out->u.latch.status = (int8_t)d[6];
            }
        }
        return true;
    default:
        return false;
    }
}

int linkmsg_send(const linkmsg_t *m)
{
    hal_link_frame_t f[2];
    uint8_t n = linkmsg_encode(m, f);
    if (n == 0)
        return -1;
    hal_irq_state_t s = hal_irq_disable();
    if (hal_link_tx_room() < n) {
        hal_irq_restore(s);
        return -2;
    }
    int rc = hal_link_send(&f[0]);
    if (rc == 0 && n == 2)
        rc = hal_link_send(&f[1]);
    hal_irq_restore(s);
    return rc;
}
