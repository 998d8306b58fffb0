/*
 * linkmsg_fuzz.c - the link messages (firmware/link/linkmsg.c): any sequence of well-formed
 * frames (11-bit id, 0..8 bytes: what a CAN controller hands over) into the reassembly, as a
 * board's receive handler feeds it.
 *
 * Input: records of [id selector, id byte, length byte, data...]: a selector below 0xC0 picks
 * one of the message table's ids (so that most frames are of interest), otherwise the id is any
 * 11-bit value; the length is taken modulo 9; missing data bytes are zero.
 * Properties beyond memory safety: a completed message has a known type and encodes back to
 * exactly the frames that made it (the frame just fed, and for a pair the A frame fed last
 * with its id); frames of other ids are ignored without an error; a frame is at most one error.
 */
#include <string.h>

#include "fuzz_check.h"
#include "link/linkmsg.h"

/* The message table's ids (messages.toml, through linkmsg_sender()), gathered once. */
static uint16_t ids[2 * (LINKMSG_TYPES + 1)];
static size_t n_ids;

static bool same(const hal_can_frame_t *a, const hal_can_frame_t *b)
{
    return a->id == b->id && a->len == b->len && memcmp(a->data, b->data, a->len) == 0;
}

static bool known(uint16_t id)
{
    return linkmsg_sender(id) >= 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (n_ids == 0)
        for (uint16_t id = 0; id <= HAL_CAN_MAX_ID && n_ids < sizeof ids / sizeof ids[0]; id++)
            if (known(id))
                ids[n_ids++] = id;
    linkmsg_rx_t rx;
    linkmsg_rx_init(&rx);
    hal_can_frame_t last[HAL_CAN_MAX_ID + 1]; /* the last frame fed per id */
    bool seen[HAL_CAN_MAX_ID + 1] = {false};
    size_t i = 0;
    while (i + 3 <= size) {
        hal_can_frame_t f = {0};
        f.id = data[i] < 0xC0 ? ids[data[i] % n_ids]
                              : (uint16_t)(((data[i] & 7u) << 8 | data[i + 1]) & HAL_CAN_MAX_ID);
        f.len = (uint8_t)(data[i + 2] % (HAL_CAN_MAX_DATA + 1));
        i += 3;
        for (uint8_t k = 0; k < f.len; k++, i++)
            f.data[k] = i < size ? data[i] : 0u;

        uint16_t errors = rx.errors;
        linkmsg_t m;
        memset(&m, 0x5A, sizeof m);
        bool done = linkmsg_rx_feed(&rx, &f, &m);
        FUZZ_CHECK(rx.errors - errors <= 1, "one frame counted as %d errors", rx.errors - errors);
        if (!known(f.id))
            FUZZ_CHECK(!done && rx.errors == errors, "frame of foreign id 0x%x taken", f.id);
        if (done) {
            FUZZ_CHECK(m.type >= LINKMSG_STOP && m.type < LINKMSG_TYPES, "message type %u", m.type);
            hal_can_frame_t out[2];
            uint8_t n = linkmsg_encode(&m, out);
            FUZZ_CHECK(n == 1 || n == 2, "message of type %u encodes to %u frames", m.type, n);
            FUZZ_CHECK(same(&out[n - 1], &f),
                       "message of type %u does not encode back to its "
                       "frame 0x%x",
                       m.type, f.id);
            if (n == 2)
                FUZZ_CHECK(seen[out[0].id] && same(&out[0], &last[out[0].id]),
                           "message of type %u does not encode back to its A frame 0x%x", m.type,
                           out[0].id);
        }
        last[f.id] = f;
        seen[f.id] = true;
    }
    return 0;
}
