/*
 * link_framer_fuzz.c - the board link's frame coder (hal/common/link_framer.c): any byte
 * stream into the receiver, one byte at a time as the UART interrupt feeds it.
 *
 * Properties beyond memory safety (ASan, UBSan): a frame handed out is well formed (id within
 * 11 bits, at most 8 data bytes); encoding it again and feeding those bytes to a fresh
 * receiver gives back the same frame, once, on the closing flag; the receiver's fill level
 * never passes its buffer. The input's first bytes are also taken as a frame to encode: any
 * well-formed frame survives encoding and decoding unchanged.
 */
#include <string.h>

#include "fuzz_check.h"
#include "link_framer.h"

/* Encode @p f and decode it with a fresh receiver: the same frame, once, on the last byte. */
static void round_trip(const hal_link_frame_t *f)
{
    uint8_t bytes[LINK_FRAMER_MAX_BYTES];
    uint8_t n = link_framer_encode(f, bytes);
    FUZZ_CHECK(n >= 5 && n <= LINK_FRAMER_MAX_BYTES, "encoded frame of %u bytes", n);
    link_framer_rx_t rx;
    link_framer_rx_init(&rx);
    hal_link_frame_t g;
    for (uint8_t i = 0; i < n; i++) {
        int got = link_framer_rx_byte(&rx, bytes[i], &g);
        FUZZ_CHECK(got == (i == n - 1), "re-encoded frame: frame completed at byte %u of %u", i, n);
    }
    FUZZ_CHECK(rx.errors == 0, "re-encoded frame counted as an error");
    FUZZ_CHECK(g.id == f->id && g.len == f->len && memcmp(g.data, f->data, f->len) == 0,
               "round trip changed the frame (id 0x%x len %u -> id 0x%x len %u)", f->id, f->len,
               g.id, g.len);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size >= 3) {
        hal_link_frame_t f = {.id = (uint16_t)((data[0] << 8 | data[1]) & HAL_LINK_MAX_ID),
                              .len = (uint8_t)(data[2] % (HAL_LINK_MAX_DATA + 1))};
        for (uint8_t i = 0; i < f.len; i++)
            f.data[i] = 3u + i < size ? data[3 + i] : 0u;
        round_trip(&f);
    }
    link_framer_rx_t rx;
    link_framer_rx_init(&rx);
    for (size_t i = 0; i < size; i++) {
        hal_link_frame_t f;
        memset(&f, 0xA5, sizeof f);
        uint16_t errors = rx.errors;
        if (link_framer_rx_byte(&rx, data[i], &f)) {
            FUZZ_CHECK(data[i] == 0x7E, "frame completed on byte 0x%02x, not a flag", data[i]);
            FUZZ_CHECK(f.id <= HAL_LINK_MAX_ID && f.len <= HAL_LINK_MAX_DATA,
                       "malformed frame out: id 0x%x len %u", f.id, f.len);
            FUZZ_CHECK(rx.errors == errors, "a good frame also counted as an error");
            round_trip(&f);
        }
        FUZZ_CHECK(rx.n <= sizeof rx.buf, "receiver fill %u past its buffer", rx.n);
        FUZZ_CHECK(rx.errors - errors <= 1, "one byte counted as %d errors", rx.errors - errors);
    }
    return 0;
}
