/*
 * linkmsg.c - inter-board messages as CAN frames (see linkmsg.h).
 *
 * One table says where each message's fields go: their order on the wire and where they sit in
 * linkmsg_t. It is generated from firmware/link/messages.toml (linkmsg_table.h, with checks of
 * every member's size and signedness). A message of up to 8 data bytes is one frame; a longer
 * one (a pose and more) is an A frame with its first 8 bytes and a B frame with the rest and
 * the tag, the CRC-8 of the A frame's data. Encoding and decoding are the same byte copy in
 * opposite directions.
 */
#include "link/linkmsg.h"

#include <stddef.h>

/* The wire is little endian; fields are copied byte by byte from their place in memory. */
_Static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "linkmsg.c needs a little-endian CPU");
_Static_assert(sizeof(linkmsg_t) <= 32, "field offsets are stored in 5 bits");

/* A field: its offset in linkmsg_t (< 32) << 3 | its size in bytes (1, 2 or 4). */
#define FIELD(member)                                                                              \
    (uint8_t)(offsetof(linkmsg_t, u.member) << 3 | sizeof(((linkmsg_t *)NULL)->u.member))

typedef struct {
    uint16_t id;        /* of the frame, of the A frame of a pair (its B frame is id + 1) */
    uint8_t len;        /* data bytes; over 8: an A/B pair, the B frame adds the tag */
    uint8_t slot;       /* of a pair: its place in linkmsg_rx_t.have and .a */
    uint8_t sender;     /* LINKMSG_NODE_* */
    uint8_t fields[11]; /* in wire order (LINKMSG_MAX_FIELDS used at most) */
} msg_desc_t;

/* 16 bytes: the handlers index the table without a multiplication (the main board's handlers
 * must not use the hardware multiplier). */
_Static_assert(sizeof(msg_desc_t) == 16, "msg_desc_t: a power of two");
_Static_assert(LINKMSG_MAX_FIELDS <= 11, "msg_desc_t.fields: room for every field");

/* Indexed by linkmsg_type_t - 1; generated from firmware/link/messages.toml. */
#include "linkmsg_table.h"

#define MSG_COUNT (sizeof msgs / sizeof msgs[0])
_Static_assert(MSG_COUNT == LINKMSG_TYPES - 1, "one descriptor per message type");

/* CRC-8, polynomial x^8 + x^2 + x + 1, initial 0, not reflected: the B frames' tag. */
static uint8_t crc8(const uint8_t *p, uint8_t n)
{
    uint8_t crc = 0;
    while (n--) {
        crc ^= *p++;
        for (uint8_t b = 0; b < 8; b++)
            crc = (uint8_t)((crc & 0x80u) ? (uint8_t)(crc << 1) ^ 0x07u : (uint8_t)(crc << 1));
    }
    return crc;
}

uint8_t linkmsg_encode(const linkmsg_t *m, hal_can_frame_t out[2])
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
    out[1].data[k - 8u] = crc8(out[0].data, 8);
    return 2;
}

void linkmsg_rx_init(linkmsg_rx_t *rx)
{
    for (uint8_t i = 0; i < LINKMSG_PAIRS; i++)
        rx->have[i] = 0;
    rx->errors = 0;
}

static bool bad(linkmsg_rx_t *rx)
{
    rx->errors++;
    return false;
}

/* The descriptor of the message frame @p id belongs to, or NULL. */
static const msg_desc_t *desc_of(uint16_t id)
{
    for (const msg_desc_t *d = msgs; d != msgs + MSG_COUNT; d++)
        if (id == d->id || (d->len > 8 && id == d->id + 1u))
            return d;
    return NULL;
}

int8_t linkmsg_sender(uint16_t id)
{
    const msg_desc_t *d = desc_of(id);
    return d ? (int8_t)d->sender : -1;
}

bool linkmsg_rx_feed(linkmsg_rx_t *rx, const hal_can_frame_t *f, linkmsg_t *out)
{
    const msg_desc_t *d = desc_of(f->id);
    if (!d)
        return false;               /* another id: traffic of others on a shared bus */
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
        if (!had || f->len != (uint8_t)(d->len - 7u) || f->data[f->len - 1u] != crc8(a, 8))
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
