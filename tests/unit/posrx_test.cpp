// Tests of seed 002's serial position receiver (firmware/posrx): packet framing against the
// packet format written here from the seed (0x00, x, y, z as signed 32-bit big-endian
// millimetres, 0xFF), resynchronisation after garbage and torn packets, receive errors, the
// queue, and the acceptance rules (zero, jump, too close) against the geometry worked here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

extern "C" {
#include "hal/uart.h"
#include "posrx/posrx.h"
}

namespace
{

// Seed 002's packet, written from its description (INT.C ser_int, SPSI.C Update_Pos).
std::vector<uint8_t> packet(int32_t x, int32_t y, int32_t z)
{
    std::vector<uint8_t> p = {0x00};
    for (int32_t v : {x, y, z})
        for (int shift = 24; shift >= 0; shift -= 8)
            p.push_back((uint8_t)((uint32_t)v >> shift));
    p.push_back(0xFF);
    return p;
}

posrx_t make(uint16_t min_mm = 50, uint16_t vmax = 2000)
{
    posrx_t r;
    posrx_config_t c = {min_mm, vmax};
    EXPECT_TRUE(posrx_init(&r, &c));
    return r;
}

// Feed bytes at time t; collect what the main loop gets (taking after every byte).
std::vector<posrx_pos_t> feed(posrx_t &r, const std::vector<uint8_t> &bytes, uint32_t t = 0,
                              uint8_t flags = 0)
{
    std::vector<posrx_pos_t> got;
    for (uint8_t b : bytes) {
        posrx_rx_byte(&r, b, flags, t);
        posrx_pos_t p;
        while (posrx_take(&r, &p))
            got.push_back(p);
    }
    return got;
}

TEST(PosrxFrame, DecodesTheSeedsPacket)
{
    posrx_t r = make();
    // Path #1's start of seed 002 (250 cm, 200 cm), the receiver 1.2 m up.
    std::vector<uint8_t> p = {0x00, 0x00, 0x00, 0x09, 0xC4, 0x00, 0x00,
                              0x07, 0xD0, 0x00, 0x00, 0x04, 0xB0, 0xFF};
    EXPECT_EQ(packet(2500, 2000, 1200), p);
    auto got = feed(r, p, 1234);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].x, 2500);
    EXPECT_EQ(got[0].y, 2000);
    EXPECT_EQ(got[0].z, 1200);
    EXPECT_EQ(got[0].t_ms, 1234u);
    posrx_stats_t st;
    posrx_stats(&r, &st);
    EXPECT_EQ(st.framed, 1u);
    EXPECT_EQ(st.resyncs, 0u);
    EXPECT_EQ(st.bytes, 14u);
}

TEST(PosrxFrame, SignedBigEndianEverywhere)
{
    std::mt19937 g(7);
    posrx_t r = make();
    for (int i = 0; i < 2000; i++) {
        int32_t x = (int32_t)g(), y = (int32_t)g(), z = (int32_t)g();
        if (i < 6) { // the extremes and the values made of start and end bytes
            const int32_t ex[] = {INT32_MIN, INT32_MAX, -1, 0x00FF00FF, (int32_t)0xFF00FF00, 0};
            x = y = z = ex[i];
        }
        auto got = feed(r, packet(x, y, z));
        ASSERT_EQ(got.size(), 1u) << i;
        EXPECT_EQ(got[0].x, x);
        EXPECT_EQ(got[0].y, y);
        EXPECT_EQ(got[0].z, z);
    }
    posrx_stats_t st;
    posrx_stats(&r, &st);
    EXPECT_EQ(st.resyncs, 0u);
}

TEST(PosrxFrame, GarbageBeforeAPacketIsOneResync)
{
    posrx_t r = make();
    std::vector<uint8_t> s = {0x12, 0x34, 0xFF, 0x56, 0x00, 0x9A};
    auto p = packet(-1500, 32000, 800);
    s.insert(s.end(), p.begin(), p.end());
    auto got = feed(r, s);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].x, -1500);
    posrx_stats_t st;
    posrx_stats(&r, &st);
    EXPECT_EQ(st.resyncs, 1u);
    EXPECT_EQ(st.skipped, 6u);
}

TEST(PosrxFrame, TornPacketThenAWholeOne)
{
    posrx_t r = make();
    auto a = packet(1000, 2000, 3000), b = packet(4000, 5000, 6000);
    std::vector<uint8_t> s(a.begin(), a.begin() + 9); // the line dropped the rest
    s.insert(s.end(), b.begin(), b.end());
    auto got = feed(r, s);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].x, 4000);
    EXPECT_EQ(got[0].z, 6000);
    posrx_stats_t st;
    posrx_stats(&r, &st);
    EXPECT_EQ(st.resyncs, 1u);
    EXPECT_EQ(st.skipped, 9u);
}

TEST(PosrxFrame, ABytesWithAReceiveErrorBreaksItsPacket)
{
    posrx_t r = make();
    auto a = packet(1000, 2000, 3000), b = packet(4000, 5000, 6000);
    std::vector<posrx_pos_t> got;
    for (size_t i = 0; i < a.size(); i++) {
        posrx_rx_byte(&r, a[i], i == 5 ? HAL_UART_RX_ERROR : 0, 0);
        posrx_pos_t p;
        while (posrx_take(&r, &p))
            got.push_back(p);
    }
    EXPECT_TRUE(got.empty());
    got = feed(r, b);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].y, 5000);
    posrx_stats_t st;
    posrx_stats(&r, &st);
    EXPECT_EQ(st.error_bytes, 1u);
    EXPECT_EQ(st.resyncs, 1u);
    EXPECT_EQ(st.skipped, 14u);
}

TEST(PosrxFrame, AFullQueueDropsTheOldest)
{
    posrx_t r = make();
    for (int i = 0; i < 6; i++)
        for (uint8_t b : packet(100 * i, 1, 1))
            posrx_rx_byte(&r, b, 0, (uint32_t)i);
    std::vector<int32_t> xs;
    posrx_pos_t p;
    while (posrx_take(&r, &p))
        xs.push_back(p.x);
    EXPECT_EQ(xs, (std::vector<int32_t>{200, 300, 400, 500}));
    posrx_stats_t st;
    posrx_stats(&r, &st);
    EXPECT_EQ(st.dropped, 2u);
}

// Every byte is in a packet, skipped before one, or after the last: whatever the stream.
TEST(PosrxFrame, RandomStreamsAccountForEveryByte)
{
    std::mt19937 g(2024);
    for (int trial = 0; trial < 200; trial++) {
        posrx_t r = make();
        std::vector<uint8_t> s;
        int n = (int)(g() % 3000);
        for (int i = 0; i < n; i++) {
            int kind = (int)(g() % 4);
            if (kind == 0) {
                auto p = packet((int32_t)g(), (int32_t)g(), (int32_t)g());
                s.insert(s.end(), p.begin(), p.end());
            } else {
                s.push_back(kind == 1 ? 0x00 : kind == 2 ? 0xFF : (uint8_t)g());
            }
        }
        uint32_t trailing = 0, framed_before;
        for (uint8_t b : s) {
            framed_before = r.st.framed;
            posrx_rx_byte(&r, b, (g() % 50 == 0) ? HAL_UART_RX_ERROR : 0, 0);
            trailing = r.st.framed != framed_before ? 0 : trailing + 1;
            posrx_pos_t p;
            while (posrx_take(&r, &p))
                (void)posrx_check(&r, &p, nullptr);
        }
        posrx_stats_t st;
        posrx_stats(&r, &st);
        EXPECT_EQ(st.bytes, s.size());
        EXPECT_EQ(st.skipped + 14u * st.framed + trailing, st.bytes) << trial;
        uint32_t judged = 0;
        for (uint32_t k : st.reason)
            judged += k;
        EXPECT_EQ(judged, st.framed);
    }
}

// Packets separated by garbage without a start byte are all found, each run one resync.
TEST(PosrxFrame, EveryPacketFoundWhenTheGarbageHasNoStartByte)
{
    std::mt19937 g(99);
    posrx_t r = make();
    std::vector<int32_t> want;
    std::vector<uint8_t> s;
    uint32_t runs = 0, skipped = 0;
    for (int i = 0; i < 3000; i++) {
        int len = (int)(g() % 4 == 0 ? g() % 40 : 0);
        runs += len > 0;
        skipped += (uint32_t)len;
        for (int k = 0; k < len; k++)
            s.push_back((uint8_t)(1 + g() % 255));
        int32_t x = (int32_t)g();
        want.push_back(x);
        auto p = packet(x, (int32_t)g(), (int32_t)g());
        s.insert(s.end(), p.begin(), p.end());
    }
    auto got = feed(r, s);
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < want.size(); i++)
        ASSERT_EQ(got[i].x, want[i]) << i;
    posrx_stats_t st;
    posrx_stats(&r, &st);
    EXPECT_EQ(st.resyncs, runs);
    EXPECT_EQ(st.skipped, skipped);
}

posrx_pos_t at(int32_t x, int32_t y, uint32_t t_ms, int32_t z = 1200)
{
    return posrx_pos_t{x, y, z, t_ms};
}

TEST(PosrxCheck, FirstNonZeroPositionIsTheReference)
{
    posrx_t r = make();
    posrx_pos_t z0 = at(0, 0, 0, 0), p = at(2500, 2000, 100);
    uint32_t d = 7;
    EXPECT_EQ(posrx_check(&r, &z0, &d), POSRX_ZERO);
    EXPECT_EQ(d, 0u);
    EXPECT_EQ(posrx_check(&r, &p, &d), POSRX_OK);
    EXPECT_TRUE(r.has_ref);
    EXPECT_EQ(r.ref.x, 2500);
    // a zero packet stays zero with a reference
    z0.t_ms = 200;
    EXPECT_EQ(posrx_check(&r, &z0, nullptr), POSRX_ZERO);
    // x = 0 alone is a position (the seed refused x == 0 || y == 0; CONTRACT: all zero)
    posrx_pos_t axis = at(0, 2000, 2000);
    EXPECT_EQ(posrx_check(&r, &axis, nullptr), POSRX_OK);
}

TEST(PosrxCheck, JumpIsMaxSpeedTimesTheElapsedTime)
{
    // 2 m/s for 2.5 s: 5000 mm; the 3-4-5 triangle is exactly 5000 mm away.
    posrx_t r = make(50, 2000);
    posrx_set_reference(&r, 1000, 1000, 10000);
    posrx_pos_t far = at(1000 + 3000, 1000 + 4001, 12500),
                edge = at(1000 + 3000, 1000 + 4000, 12500);
    uint32_t d = 0;
    EXPECT_EQ(posrx_check(&r, &far, &d), POSRX_JUMP);
    EXPECT_EQ(d, (uint32_t)std::lround(std::hypot(3000.0, 4001.0)));
    EXPECT_EQ(r.ref.x, 1000); // a jump leaves the reference alone
    EXPECT_EQ(posrx_check(&r, &edge, &d), POSRX_OK);
    EXPECT_EQ(d, 5000u);
    EXPECT_EQ(r.ref.x, 4000);
    EXPECT_EQ(r.ref.t_ms, 12500u);
    // after a long silence the allowance grows: 10 s at 2 m/s = 20 m
    posrx_pos_t later = at(4000 + 19999, 5000, 22500);
    EXPECT_EQ(posrx_check(&r, &later, nullptr), POSRX_OK);
    // and stops growing at ten minutes (1200 m at 2 m/s)
    posrx_pos_t way_later = at(24000 + 1200001, 5000, 22500 + 3600000);
    EXPECT_EQ(posrx_check(&r, &way_later, nullptr), POSRX_JUMP);
}

TEST(PosrxCheck, FractionOfASecondOfAllowance)
{
    // 1.5 m/s for 0.333 s: 499.5 mm, the vehicle reaches 499 mm but not 500
    posrx_t r = make(0, 1500);
    posrx_set_reference(&r, 0, 0, 0);
    posrx_pos_t a = at(500, 0, 333), b = at(499, 0, 333);
    EXPECT_EQ(posrx_check(&r, &a, nullptr), POSRX_JUMP);
    EXPECT_EQ(posrx_check(&r, &b, nullptr), POSRX_OK);
}

TEST(PosrxCheck, TooCloseBelowTheMinimumUpdateDistance)
{
    posrx_t r = make(50, 2000);
    posrx_set_reference(&r, 2500, 2000, 0);
    posrx_pos_t near = at(2500 + 30, 2000 + 39, 1000), min = at(2500 + 30, 2000 + 40, 1000);
    uint32_t d;
    EXPECT_EQ(posrx_check(&r, &near, &d), POSRX_TOO_CLOSE);
    EXPECT_EQ(d, 49u);                              // round(hypot(30, 39)) = 49.2
    EXPECT_EQ(r.ref.x, 2500);                       // not the reference
    EXPECT_EQ(posrx_check(&r, &min, &d), POSRX_OK); // exactly 50 mm is far enough
    posrx_stats_t st;
    posrx_stats(&r, &st);
    EXPECT_EQ(st.reason[POSRX_TOO_CLOSE], 1u);
    EXPECT_EQ(st.reason[POSRX_OK], 1u);
}

TEST(PosrxCheck, OutOfTheFirmwaresRangeIsAJump)
{
    posrx_t r = make(50, 65535);
    posrx_set_reference(&r, 0, 0, 0);
    posrx_pos_t a = at(POSRX_RANGE_MM + 1, 0, 600000), b = at(0, -POSRX_RANGE_MM - 1, 600000),
                c = at(INT32_MIN, INT32_MIN, 600000);
    for (posrx_pos_t *p : {&a, &b, &c}) {
        uint32_t d = 0;
        EXPECT_EQ(posrx_check(&r, p, &d), POSRX_JUMP);
        EXPECT_EQ(d, UINT32_MAX);
    }
}

TEST(PosrxCheck, ConfigAndNames)
{
    posrx_t r;
    posrx_config_t bad = {50, 0};
    r.w = 42;
    EXPECT_FALSE(posrx_init(&r, &bad));
    EXPECT_EQ(r.w, 42); // untouched
    EXPECT_STREQ(posrx_reason_name(POSRX_OK), "ok");
    EXPECT_STREQ(posrx_reason_name(POSRX_ZERO), "zero");
    EXPECT_STREQ(posrx_reason_name(POSRX_JUMP), "jump");
    EXPECT_STREQ(posrx_reason_name(POSRX_TOO_CLOSE), "too_close");
    EXPECT_STREQ(posrx_reason_name(POSRX_REASON_COUNT), "?");
}

} // namespace
