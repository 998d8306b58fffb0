/*
 * posrx_fuzz.c - seed 002's serial position receiver (firmware/posrx): any byte stream into
 * the receive handler, one byte at a time as the UART interrupt feeds it, and every framed
 * packet through the acceptance rules, as the main loop runs them.
 *
 * Input: 4 bytes of configuration (the minimum update distance and the top speed, 16-bit
 * little-endian mm and mm/s; a top speed of 0 must be refused), then records of two bytes:
 * the received byte, and a control byte (bit 0: the UART flags the byte with a receive error;
 * bits 1-7: milliseconds that pass before it arrives).
 *
 * Properties beyond memory safety (ASan, UBSan): a packet is framed only on an 0xFF that ends
 * 14 bytes, all received without an error since the previous packet, the first 0x00; the main
 * loop gets exactly its coordinates (big-endian), at that byte's time; every byte is in a
 * packet, skipped before one, or after the last; every packet gets one verdict: zero exactly
 * for all-zero coordinates, accepted or too close only within +-2^25 mm and within the top
 * speed times the time since the reference, and only an accepted one becomes the reference.
 */
#include <string.h>

#include "fuzz_check.h"
#include "hal/uart.h"
#include "posrx/posrx.h"

static int32_t be32(const uint8_t *b)
{
    return (int32_t)(((uint32_t)b[0] << 24) | ((uint32_t)b[1] << 16) | ((uint32_t)b[2] << 8) |
                     (uint32_t)b[3]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 4)
        return 0;
    posrx_config_t cfg = {(uint16_t)(data[0] | data[1] << 8), (uint16_t)(data[2] | data[3] << 8)};
    posrx_t r;
    memset(&r, 0x5A, sizeof r);
    bool ok = posrx_init(&r, &cfg);
    FUZZ_CHECK(ok == (cfg.max_speed_mm_s != 0), "posrx_init(max speed %u) answered %d",
               cfg.max_speed_mm_s, ok);
    if (!ok)
        return 0;
    data += 4;
    size -= 4;
    uint8_t last[POSRX_PACKET_BYTES] = {0}; /* the bytes since the last packet (the newest last) */
    size_t since = 0, clean = 0, bytes = 0, trailing = 0;
    uint32_t now = 0;
    for (size_t i = 0; i + 1 < size; i += 2) {
        uint8_t b = data[i], ctrl = data[i + 1];
        uint8_t flags = (ctrl & 1u) ? HAL_UART_RX_ERROR : 0u;
        now += ctrl >> 1;
        memmove(last, last + 1, sizeof last - 1);
        last[sizeof last - 1] = b;
        since++;
        clean = flags ? 0 : clean + 1;
        bytes++;
        uint32_t framed = r.st.framed;
        posrx_rx_byte(&r, b, flags, now);
        int want =
            !flags && b == 0xFF && clean >= POSRX_PACKET_BYTES && since >= 14 && last[0] == 0x00;
        FUZZ_CHECK((r.st.framed != framed) == want, "byte %zu (0x%02x): framed %d, expected %d",
                   i / 2, b, r.st.framed != framed, want);
        trailing = want ? 0 : trailing + 1;
        posrx_pos_t p;
        int n = 0;
        while (posrx_take(&r, &p)) {
            n++;
            FUZZ_CHECK(want, "a packet taken without one framed");
            FUZZ_CHECK(p.x == be32(last + 1) && p.y == be32(last + 5) && p.z == be32(last + 9) &&
                           p.t_ms == now,
                       "packet decoded as (%d %d %d) at %u", (int)p.x, (int)p.y, (int)p.z,
                       (unsigned)p.t_ms);
            posrx_pos_t ref = r.ref;
            bool had_ref = r.has_ref;
            uint32_t d = 7;
            posrx_reason_t why = posrx_check(&r, &p, &d);
            FUZZ_CHECK((unsigned)why < POSRX_REASON_COUNT, "verdict %d", (int)why);
            FUZZ_CHECK((why == POSRX_ZERO) == (p.x == 0 && p.y == 0 && p.z == 0),
                       "zero verdict %d for (%d %d %d)", why == POSRX_ZERO, (int)p.x, (int)p.y,
                       (int)p.z);
            if (why == POSRX_OK || why == POSRX_TOO_CLOSE) {
                FUZZ_CHECK(p.x >= -POSRX_RANGE_MM && p.x <= POSRX_RANGE_MM &&
                               p.y >= -POSRX_RANGE_MM && p.y <= POSRX_RANGE_MM,
                           "a position beyond +-2^25 mm passed");
                if (had_ref) {
                    uint32_t dt = p.t_ms - ref.t_ms;
                    if (dt > POSRX_MAX_DT_MS)
                        dt = POSRX_MAX_DT_MS;
                    FUZZ_CHECK((uint64_t)d * 1000u <= (uint64_t)cfg.max_speed_mm_s * dt,
                               "%u mm in %u ms passed at %u mm/s", (unsigned)d, (unsigned)dt,
                               cfg.max_speed_mm_s);
                }
            }
            if (why == POSRX_TOO_CLOSE)
                FUZZ_CHECK(d < cfg.min_update_mm, "too close at %u mm", (unsigned)d);
            if (why == POSRX_OK)
                FUZZ_CHECK(r.ref.x == p.x && r.ref.y == p.y && r.ref.t_ms == p.t_ms && r.has_ref,
                           "accepted but not the reference");
            else
                FUZZ_CHECK(r.has_ref == had_ref &&
                               (!had_ref ||
                                (r.ref.x == ref.x && r.ref.y == ref.y && r.ref.t_ms == ref.t_ms)),
                           "refused but the reference moved");
        }
        FUZZ_CHECK(n == want, "%d packets taken for one byte", n);
        if (want)
            since = clean = 0;
    }
    posrx_stats_t st;
    posrx_stats(&r, &st);
    FUZZ_CHECK(st.bytes == bytes, "%u bytes counted, %zu fed", (unsigned)st.bytes, bytes);
    FUZZ_CHECK(st.skipped + 14u * st.framed + trailing == bytes,
               "bytes unaccounted: %u skipped + 14 x %u framed + %zu after != %zu",
               (unsigned)st.skipped, (unsigned)st.framed, trailing, bytes);
    uint32_t judged = 0;
    for (int k = 0; k < POSRX_REASON_COUNT; k++)
        judged += st.reason[k];
    FUZZ_CHECK(judged == st.framed && st.dropped == 0, "%u judged of %u framed, %u dropped",
               (unsigned)judged, (unsigned)st.framed, (unsigned)st.dropped);
    return 0;
}
