/*
 * linkmsg.c - inter-board messages as frames (see linkmsg.h).
 *
 * One table says where each message's fields go: their order on the wire and where they sit in
 * linkmsg_t. A message of up to 8 data bytes is one frame; a longer one (a pose and more) is
 * an A frame with its first 8 bytes and a B frame with the rest and the tag. Encoding and
 * decoding are the same byte copy in opposite directions. The tag of a B frame is the CRC-8 of
 * its A frame's data, the framer's CRC (hal/common/link_framer.h, in both HAL implementations).
 */
#include "link/linkmsg.h"

#include <stddef.h>

#include "hal/irq.h"
#include "link_framer.h"

/* The wire is little endian; fields are copied byte by byte from their place in memory. */
_Static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "linkmsg.c needs a little-endian CPU");
_Static_assert(LINKMSG_ID_DIR <= 0xFFu, "message ids are stored in a byte");
_Static_assert(sizeof(linkmsg_t) <= 32, "field offsets are stored in 5 bits");

/* A field: its offset in linkmsg_t (< 32) << 3 | its size in bytes (1, 2 or 4). */
#define FIELD(member)                                                                              \
    (uint8_t)(offsetof(linkmsg_t, u.member) << 3 | sizeof(((linkmsg_t *)NULL)->u.member))
#define POSE(msg) FIELD(msg.pose.x), FIELD(msg.pose.y), FIELD(msg.pose.heading)

typedef struct {
    uint8_t id;        /* of the frame, of the A frame of a pair (its B frame is id + 1) */
    uint8_t len;       /* data bytes; over 8: an A/B pair, the B frame adds the tag */
    uint8_t slot;      /* of a pair: its place in linkmsg_rx_t.have and .a */
    uint8_t fields[5]; /* in wire order */
} msg_desc_t;

/* Indexed by linkmsg_type_t - 1. */
static const msg_desc_t msgs[] = {
    {LINKMSG_ID_STOP, 1, 0, {FIELD(stop.reason)}},
    {LINKMSG_ID_POSE_A, 13, 0, {POSE(pose), FIELD(pose.request)}},
    {LINKMSG_ID_FIX_A, 15, 1, {POSE(fix), FIELD(fix.latch), FIELD(fix.flags)}},
    {LINKMSG_ID_FIX_ACK, 3, 0, {FIELD(fix_ack.status), FIELD(fix_ack.latch)}},
    {LINKMSG_ID_LATCH_REQ, 3, 0, {FIELD(latch_req.first), FIELD(latch_req.count)}},
    {LINKMSG_ID_LATCH_A, 15, 2, {POSE(latch), FIELD(latch.seq), FIELD(latch.status)}},
    {LINKMSG_ID_DIR, 1, 0, {FIELD(dir.reverse)}},
};
#define MSG_COUNT (sizeof msgs / sizeof msgs[0])

uint8_t linkmsg_encode(const linkmsg_t *m, hal_link_frame_t out[2])
{
    uint8_t t = (uint8_t)(m->type - 1u);
    if (t >= MSG_COUNT)
        return 0;
    const msg_desc_t *d = &msgs[t];
    const uint8_t *fp = d->fields;
    uint8_t k = 0; /* ends as the message's data bytes */
    while (k < d->len) {
        for (uint8_t i = 0; i < (*fp & 7u); i++, k++)
            *(k < 8 ? &out[0].data[k] : &out[1].data[k - 8]) = ((const uint8_t *)m)[(*fp >> 3) + i];
        fp++;
    }
    out[0].id = d->id;
    if (k <= 8) {
        out[0].len = k;
        return 1;
    }
    out[0].len = 8;
    out[1].id = (uint16_t)(d->id + 1u);
    out[1].len = (uint8_t)(k - 7u);
    out[1].data[k - 8u] = link_crc8(out[0].data, 8);
    return 2;
}

void linkmsg_rx_init(linkmsg_rx_t *rx)
{
    rx->have[0] = rx->have[1] = rx->have[2] = 0;
    rx->errors = 0;
}

static bool bad(linkmsg_rx_t *rx)
{
    rx->errors++;
    return false;
}

bool linkmsg_rx_feed(linkmsg_rx_t *rx, const hal_link_frame_t *f, linkmsg_t *out)
{
    const msg_desc_t *d = msgs;
    while (f->id != d->id && (d->len <= 8 || f->id != d->id + 1u))
        if (++d == msgs + MSG_COUNT)
            return false;           /* another id: traffic of others on a shared bus */
    const uint8_t *first = f->data; /* where the message's data bytes 0..7 are */
    if (d->len > 8) {
        uint8_t *a = rx->a[d->slot];
        uint8_t had = rx->have[d->slot];
        rx->have[d->slot] = 0;
        if (f->id == d->id) {
            /* An A frame: kept until its B frame. */
            if (f->len != 8)
                return bad(rx);
            for (uint8_t i = 0; i < 8; i++)
                a[i] = f->data[i];
            rx->have[d->slot] = 1;
            return false;
        }
        if (!had || f->len != (uint8_t)(d->len - 7u) || f->data[f->len - 1u] != link_crc8(a, 8))
            return bad(rx);
        first = a;
    } else if (f->len != d->len) {
        return bad(rx);
    }
    out->type = (uint8_t)(d - msgs + 1);
    const uint8_t *fp = d->fields;
    for (uint8_t k = 0; k < d->len; fp++)
        for (uint8_t i = 0; i < (*fp & 7u); i++, k++)
            ((uint8_t *)out)[(*fp >> 3) + i] = k < 8 ? first[k] : f->data[k - 8];
    return true;
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
