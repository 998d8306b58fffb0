// Tests of the inter-board link: the byte-stream framer (hal/common/link_framer.c) against an
// independent model of the wire format written here, corruption handling, and the harness's
// in-process bus (latency, order, overrun, malformed frames).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

extern "C" {
#include "hal/irq.h"
#include "hal/link.h"
#include "hal_posix/harness.h"
#include "link_framer.h"
#include "ref_crc8.h"
}

namespace
{

// The wire format of link_framer.h, built independently of the implementation (the CRC:
// ref_crc8.h).
std::vector<uint8_t> ref_encode(const hal_link_frame_t &f)
{
    std::vector<uint8_t> raw = {(uint8_t)(f.id >> 3), (uint8_t)(((f.id & 7) << 5) | f.len)};
    raw.insert(raw.end(), f.data, f.data + f.len);
    raw.push_back(ref_crc8(raw));
    std::vector<uint8_t> out = {0x7E};
    for (uint8_t b : raw) {
        if (b == 0x7E || b == 0x7D) {
            out.push_back(0x7D);
            out.push_back(b ^ 0x20);
        } else {
            out.push_back(b);
        }
    }
    out.push_back(0x7E);
    return out;
}

hal_link_frame_t random_frame(std::mt19937 &g)
{
    hal_link_frame_t f{};
    f.id = (uint16_t)(g() & 0x7FF);
    f.len = (uint8_t)(g() % 9);
    for (int i = 0; i < f.len; i++) // plenty of flag and escape bytes
        f.data[i] = (g() % 4 == 0) ? (uint8_t)(0x7D + (g() & 1)) : (uint8_t)g();
    return f;
}

std::vector<hal_link_frame_t> receive(const std::vector<uint8_t> &bytes, uint16_t *errors)
{
    link_framer_rx_t rx;
    link_framer_rx_init(&rx);
    std::vector<hal_link_frame_t> got;
    for (uint8_t b : bytes) {
        hal_link_frame_t f;
        if (link_framer_rx_byte(&rx, b, &f))
            got.push_back(f);
    }
    if (errors)
        *errors = rx.errors;
    return got;
}

bool same(const hal_link_frame_t &a, const hal_link_frame_t &b)
{
    return a.id == b.id && a.len == b.len && std::memcmp(a.data, b.data, a.len) == 0;
}

TEST(LinkFramer, CrcMatchesTheKnownCheckValue)
{
    const uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
    EXPECT_EQ(link_crc8(check, 9), 0xF4); // CRC-8/SMBUS check value
}

TEST(LinkFramer, EncodesLikeTheReferenceAndRoundTrips)
{
    std::mt19937 g(1);
    std::vector<uint8_t> stream;
    std::vector<hal_link_frame_t> sent;
    for (int i = 0; i < 5000; i++) {
        hal_link_frame_t f = random_frame(g);
        uint8_t out[LINK_FRAMER_MAX_BYTES];
        uint8_t n = link_framer_encode(&f, out);
        std::vector<uint8_t> ref = ref_encode(f);
        ASSERT_EQ(std::vector<uint8_t>(out, out + n), ref) << i;
        stream.insert(stream.end(), out, out + n);
        sent.push_back(f);
    }
    uint16_t errors = 1;
    std::vector<hal_link_frame_t> got = receive(stream, &errors);
    EXPECT_EQ(errors, 0);
    ASSERT_EQ(got.size(), sent.size());
    for (size_t i = 0; i < got.size(); i++)
        ASSERT_TRUE(same(got[i], sent[i])) << i;
}

TEST(LinkFramer, RejectsMalformedFrames)
{
    hal_link_frame_t f{};
    uint8_t out[LINK_FRAMER_MAX_BYTES];
    f.id = 0x800;
    EXPECT_EQ(link_framer_encode(&f, out), 0);
    f.id = 1;
    f.len = 9;
    EXPECT_EQ(link_framer_encode(&f, out), 0);
}

TEST(LinkFramer, EverySingleBitErrorIsCaughtAndTheNextFrameSurvives)
{
    hal_link_frame_t a{0x123, 8, {1, 2, 3, 0x7E, 0x7D, 6, 7, 8}};
    hal_link_frame_t b{0x456, 3, {9, 10, 11}};
    std::vector<uint8_t> wa = ref_encode(a), wb = ref_encode(b);
    for (size_t byte = 1; byte + 1 < wa.size(); byte++) {
        for (int bit = 0; bit < 8; bit++) {
            std::vector<uint8_t> s = wa;
            s[byte] ^= (uint8_t)(1u << bit);
            s.insert(s.end(), wb.begin(), wb.end());
            std::vector<hal_link_frame_t> got = receive(s, nullptr);
            // The damaged frame is never delivered as anything; b always is.
            ASSERT_FALSE(got.empty());
            EXPECT_TRUE(same(got.back(), b)) << byte << ":" << bit;
            for (size_t i = 0; i + 1 < got.size(); i++)
                EXPECT_TRUE(same(got[i], a)) << "a corrupted frame was accepted";
            EXPECT_LE(got.size(), 2u);
            if (got.size() == 2) // only possible if the flip was a no-op, which it never is
                ADD_FAILURE() << "bit error undetected at " << byte << ":" << bit;
        }
    }
}

TEST(LinkFramer, ResynchronisesAfterGarbage)
{
    hal_link_frame_t a{0x7FF, 2, {0x7E, 0x7E}};
    std::vector<uint8_t> s = {0x01, 0x7D, 0x7E, 0x55, 0x66, 0x7D};
    for (int i = 0; i < 40; i++)
        s.push_back((uint8_t)(i * 37));
    std::vector<uint8_t> w = ref_encode(a);
    s.insert(s.end(), w.begin(), w.end());
    std::vector<hal_link_frame_t> got = receive(s, nullptr);
    ASSERT_FALSE(got.empty());
    EXPECT_TRUE(same(got.back(), a));
}

// ---- the in-process bus ----

struct Rx {
    std::vector<std::pair<uint64_t, hal_link_frame_t>> got;
};

void on_rx(void *arg, const hal_link_frame_t *f)
{
    static_cast<Rx *>(arg)->got.push_back({posix_now_ns(), *f});
}

TEST(LinkBus, DeliversInOrderAfterTheLatencyAsAnInterrupt)
{
    posix_reset();
    int a = posix_board_create("a"), b = posix_board_create("b");
    Rx rxa, rxb;
    posix_board_select(a);
    ASSERT_EQ(hal_link_init(on_rx, &rxa), 0);
    hal_irq_enable();
    posix_board_select(b);
    ASSERT_EQ(hal_link_init(on_rx, &rxb), 0);
    hal_irq_enable();
    posix_link_set_latency(1000);
    posix_board_select(a);
    for (uint8_t i = 0; i < 5; i++) {
        hal_link_frame_t f{(uint16_t)(0x100 + i), 1, {i}};
        ASSERT_EQ(hal_link_send(&f), 0);
    }
    hal_link_frame_t bad{0x900, 0, {}};
    EXPECT_EQ(hal_link_send(&bad), -1);
    posix_run_until(999);
    EXPECT_TRUE(rxb.got.empty());
    posix_run_until(1000);
    ASSERT_EQ(rxb.got.size(), 5u);
    for (uint8_t i = 0; i < 5; i++) {
        EXPECT_EQ(rxb.got[i].second.id, 0x100 + i);
        EXPECT_EQ(rxb.got[i].first, 1000u);
    }
    EXPECT_TRUE(rxa.got.empty()); // a sender does not hear itself
}

TEST(LinkBus, OverrunWhileInterruptsAreOffIsCounted)
{
    posix_reset();
    int a = posix_board_create("a"), b = posix_board_create("b");
    Rx rxa, rxb;
    posix_board_select(a);
    hal_link_init(on_rx, &rxa);
    posix_board_select(b);
    hal_link_init(on_rx, &rxb); // b never enables interrupts: its buffer fills up
    posix_board_select(a);
    for (int i = 0; i < 20; i++) {
        hal_link_frame_t f{1, 0, {}};
        hal_link_send(&f);
    }
    posix_run_until(1000000);
    posix_board_select(b);
    EXPECT_EQ(hal_link_errors(), 4u); // 16 buffered, 4 lost
    hal_irq_enable();
    EXPECT_EQ(rxb.got.size(), 16u);
}

// A loss function drops frames in transit: the sender is not told, the receiver never sees
// them, the others arrive in order; without it every frame arrives.
TEST(LinkBus, FramesLostInTransitNeverArrive)
{
    posix_reset();
    int a = posix_board_create("a"), b = posix_board_create("b");
    Rx rxa, rxb;
    posix_board_select(a);
    hal_link_init(on_rx, &rxa);
    posix_board_select(b);
    hal_link_init(on_rx, &rxb);
    hal_irq_enable();
    int asked = 0;
    posix_link_set_loss(
        [](void *ctx, int from, const hal_link_frame_t *f) {
            ++*static_cast<int *>(ctx);
            return from >= 0 && f->data[0] % 3 == 0; // every third frame
        },
        &asked);
    posix_board_select(a);
    for (uint8_t i = 0; i < 9; i++) {
        hal_link_frame_t f{0x100, 1, {i}};
        EXPECT_EQ(hal_link_send(&f), 0);
        posix_run_until(posix_now_ns() + 1000000);
    }
    EXPECT_EQ(asked, 9);
    ASSERT_EQ(rxb.got.size(), 6u);
    for (size_t k = 0; k < rxb.got.size(); k++)
        EXPECT_NE(rxb.got[k].second.data[0] % 3, 0);
    posix_link_set_loss(nullptr, nullptr);
    hal_link_frame_t f{0x100, 1, {3}};
    hal_link_send(&f);
    posix_run_until(posix_now_ns() + 1000000);
    EXPECT_EQ(rxb.got.size(), 7u);
}

} // namespace
