// Tests of the inter-board messages: every message round-trips through its frames (field by
// field, from independently chosen values), every message has the bytes the protocol table
// (linkmsg.h, docs/integration.md) gives, B frames never complete with a missing, damaged or
// foreign A frame, malformed frames are counted, every frame has its sender.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

extern "C" {
#include "link/linkmsg.h"
#include "ref_crc8.h"
}

namespace
{

linkmsg_pose_t random_pose(std::mt19937 &g)
{
    return {(fx_q16_t)g(), (fx_q16_t)g(), (fx_angle_t)g()};
}

bool same_pose(const linkmsg_pose_t &a, const linkmsg_pose_t &b)
{
    return a.x == b.x && a.y == b.y && a.heading == b.heading;
}

TEST(LinkMsg, EveryMessageRoundTrips)
{
    std::mt19937 g(7);
    for (int i = 0; i < 2000; i++) {
        linkmsg_t m{};
        m.type = (uint8_t)(1 + i % (LINKMSG_TYPES - 1));
        switch (m.type) {
        case LINKMSG_STOP:
            m.u.stop.reason = (uint8_t)g();
            break;
        case LINKMSG_POSE:
            m.u.pose.pose = random_pose(g);
            m.u.pose.request = (uint8_t)g();
            break;
        case LINKMSG_FIX:
            m.u.fix.pose = random_pose(g);
            m.u.fix.latch = (uint16_t)g();
            m.u.fix.flags = (uint8_t)g();
            break;
        case LINKMSG_FIX_ACK:
            m.u.fix_ack.status = (int8_t)g();
            m.u.fix_ack.latch = (uint16_t)g();
            break;
        case LINKMSG_LATCH_REQ:
            m.u.latch_req.first = (uint16_t)g();
            m.u.latch_req.count = (uint8_t)g();
            break;
        case LINKMSG_LATCH:
            m.u.latch.pose = random_pose(g);
            m.u.latch.seq = (uint16_t)g();
            m.u.latch.status = (int8_t)g();
            break;
        case LINKMSG_DIR:
            m.u.dir.reverse = (uint8_t)(g() & 1);
            break;
        case LINKMSG_FIX_QUALITY:
            m.u.fix_quality = {(uint16_t)g(), (uint16_t)g(), (uint16_t)g(), (uint8_t)g(),
                               (uint8_t)g()};
            break;
        case LINKMSG_MAIN_HEARTBEAT:
        case LINKMSG_NAV_HEARTBEAT:
            m.u.heartbeat = {(uint8_t)g(), (uint8_t)g(), (uint8_t)g(), (uint8_t)g()};
            break;
        }
        hal_can_frame_t f[2];
        uint8_t n = linkmsg_encode(&m, f);
        ASSERT_GE(n, 1);
        linkmsg_rx_t rx;
        linkmsg_rx_init(&rx);
        linkmsg_t out{};
        for (uint8_t k = 0; k < n; k++) {
            ASSERT_LE(f[k].len, 8);
            ASSERT_LE(f[k].id, 0x7FF);
            bool done = linkmsg_rx_feed(&rx, &f[k], &out);
            ASSERT_EQ(done, k == n - 1);
        }
        ASSERT_EQ(out.type, m.type);
        switch (m.type) {
        case LINKMSG_STOP:
            EXPECT_EQ(out.u.stop.reason, m.u.stop.reason);
            break;
        case LINKMSG_POSE:
            EXPECT_TRUE(same_pose(out.u.pose.pose, m.u.pose.pose));
            EXPECT_EQ(out.u.pose.request, m.u.pose.request);
            break;
        case LINKMSG_FIX:
            EXPECT_TRUE(same_pose(out.u.fix.pose, m.u.fix.pose));
            EXPECT_EQ(out.u.fix.latch, m.u.fix.latch);
            EXPECT_EQ(out.u.fix.flags, m.u.fix.flags);
            break;
        case LINKMSG_FIX_ACK:
            EXPECT_EQ(out.u.fix_ack.status, m.u.fix_ack.status);
            EXPECT_EQ(out.u.fix_ack.latch, m.u.fix_ack.latch);
            break;
        case LINKMSG_LATCH_REQ:
            EXPECT_EQ(out.u.latch_req.first, m.u.latch_req.first);
            EXPECT_EQ(out.u.latch_req.count, m.u.latch_req.count);
            break;
        case LINKMSG_LATCH:
            EXPECT_TRUE(same_pose(out.u.latch.pose, m.u.latch.pose));
            EXPECT_EQ(out.u.latch.seq, m.u.latch.seq);
            EXPECT_EQ(out.u.latch.status, m.u.latch.status);
            break;
        case LINKMSG_DIR:
            EXPECT_EQ(out.u.dir.reverse, m.u.dir.reverse);
            break;
        case LINKMSG_FIX_QUALITY:
            EXPECT_EQ(out.u.fix_quality.latch, m.u.fix_quality.latch);
            EXPECT_EQ(out.u.fix_quality.quality, m.u.fix_quality.quality);
            EXPECT_EQ(out.u.fix_quality.err, m.u.fix_quality.err);
            EXPECT_EQ(out.u.fix_quality.resid, m.u.fix_quality.resid);
            EXPECT_EQ(out.u.fix_quality.agree, m.u.fix_quality.agree);
            break;
        case LINKMSG_MAIN_HEARTBEAT:
        case LINKMSG_NAV_HEARTBEAT:
            EXPECT_EQ(out.u.heartbeat.counter, m.u.heartbeat.counter);
            EXPECT_EQ(out.u.heartbeat.flags, m.u.heartbeat.flags);
            EXPECT_EQ(out.u.heartbeat.tec, m.u.heartbeat.tec);
            EXPECT_EQ(out.u.heartbeat.rec, m.u.heartbeat.rec);
            break;
        }
        EXPECT_EQ(rx.errors, 0);
    }
}

TEST(LinkMsg, BFrameNeedsItsOwnAFrame)
{
    linkmsg_t a{}, b{};
    a.type = b.type = LINKMSG_LATCH;
    a.u.latch.pose = {1, 2, 3};
    b.u.latch.pose = {4, 5, 6};
    hal_can_frame_t fa[2], fb[2];
    linkmsg_encode(&a, fa);
    linkmsg_encode(&b, fb);
    linkmsg_rx_t rx;
    linkmsg_rx_init(&rx);
    linkmsg_t out;
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fa[1], &out)); // B without A
    EXPECT_EQ(rx.errors, 1);
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fa[0], &out));
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fb[1], &out)); // B of another A: tag mismatch
    EXPECT_EQ(rx.errors, 2);
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fa[1], &out)); // the A was consumed by the failure
    EXPECT_EQ(rx.errors, 3);
    hal_can_frame_t damaged = fb[0];
    damaged.data[3] ^= 0x10;
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &damaged, &out));
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fb[1], &out)); // A damaged in a way the CRC let through
    EXPECT_EQ(rx.errors, 4);
    hal_can_frame_t shortf = fb[0];
    shortf.len = 7;
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &shortf, &out));
    EXPECT_EQ(rx.errors, 5);
    hal_can_frame_t other = {0x123, 2, {1, 2}};
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &other, &out)); // someone else's traffic: ignored
    EXPECT_EQ(rx.errors, 5);
}

struct Wire {
    uint16_t id;
    std::vector<uint8_t> data;
};

// A B frame's data: its fields, then the tag of the A frame's data.
std::vector<uint8_t> tagged(std::vector<uint8_t> fields, const std::vector<uint8_t> &a)
{
    fields.push_back(ref_crc8(a));
    return fields;
}

void expect_frames(const linkmsg_t &m, const std::vector<Wire> &want)
{
    hal_can_frame_t f[2];
    memset(f, 0xA5, sizeof f);
    ASSERT_EQ(linkmsg_encode(&m, f), want.size()) << "type " << (int)m.type;
    for (size_t k = 0; k < want.size(); k++) {
        EXPECT_EQ(f[k].id, want[k].id) << "type " << (int)m.type << " frame " << k;
        ASSERT_EQ(f[k].len, want[k].data.size()) << "type " << (int)m.type << " frame " << k;
        EXPECT_EQ(std::vector<uint8_t>(f[k].data, f[k].data + f[k].len), want[k].data)
            << "type " << (int)m.type << " frame " << k;
    }
    // And back: the hand-made frames decode to the message.
    linkmsg_rx_t rx;
    linkmsg_rx_init(&rx);
    linkmsg_t out{};
    for (size_t k = 0; k < want.size(); k++) {
        hal_can_frame_t w{want[k].id, (uint8_t)want[k].data.size(), {}};
        memcpy(w.data, want[k].data.data(), want[k].data.size());
        EXPECT_EQ(linkmsg_rx_feed(&rx, &w, &out), k + 1 == want.size());
    }
    EXPECT_EQ(rx.errors, 0);
    EXPECT_EQ(out.type, m.type);
}

// Every message type byte by byte against the layout of linkmsg.h (little endian fields).
TEST(LinkMsg, EveryMessageHasItsDocumentedBytes)
{
    const std::vector<uint8_t> pose_a = {0x04, 0x03, 0x02, 0x01, 0xF8, 0xF7, 0xF6, 0xF5};
    const linkmsg_pose_t pose = {0x01020304, (fx_q16_t)0xF5F6F7F8u, 0x8A7B6C5Du};
    linkmsg_t m{};

    m.type = LINKMSG_STOP;
    m.u.stop.reason = 0xC3;
    expect_frames(m, {{0x010, {0xC3}}});

    m = {};
    m.type = LINKMSG_POSE;
    m.u.pose.pose = pose;
    m.u.pose.request = 0x9E;
    expect_frames(m, {{0x020, pose_a}, {0x021, tagged({0x5D, 0x6C, 0x7B, 0x8A, 0x9E}, pose_a)}});

    m = {};
    m.type = LINKMSG_FIX;
    m.u.fix.pose = pose;
    m.u.fix.latch = 0xBEEF;
    m.u.fix.flags = LINKMSG_FIX_HAS_REF;
    expect_frames(
        m, {{0x030, pose_a}, {0x031, tagged({0x5D, 0x6C, 0x7B, 0x8A, 0xEF, 0xBE, 0x01}, pose_a)}});

    m = {};
    m.type = LINKMSG_FIX_ACK;
    m.u.fix_ack.status = -3;
    m.u.fix_ack.latch = 0x1234;
    expect_frames(m, {{0x032, {0xFD, 0x34, 0x12}}});

    m = {};
    m.type = LINKMSG_LATCH_REQ;
    m.u.latch_req.first = 0xA1B2;
    m.u.latch_req.count = 30;
    expect_frames(m, {{0x040, {0xB2, 0xA1, 30}}});

    m = {};
    m.type = LINKMSG_LATCH;
    m.u.latch.pose = pose;
    m.u.latch.seq = 0x7E7D;
    m.u.latch.status = -7;
    expect_frames(
        m, {{0x041, pose_a}, {0x042, tagged({0x5D, 0x6C, 0x7B, 0x8A, 0x7D, 0x7E, 0xF9}, pose_a)}});

    m = {};
    m.type = LINKMSG_DIR;
    m.u.dir.reverse = 1;
    expect_frames(m, {{0x050, {0x01}}});

    m = {};
    m.type = LINKMSG_FIX_QUALITY; // latch, quality, err (u16 each), resid, agree
    m.u.fix_quality = {0x1234, 0xBEEF, 0x0102, 0x99, 11};
    expect_frames(m, {{0x033, {0x34, 0x12, 0xEF, 0xBE, 0x02, 0x01, 0x99, 11}}});

    m = {};
    m.type = LINKMSG_MAIN_HEARTBEAT;
    m.u.heartbeat = {0xFE, 0x03, 0x80, 0x7F};
    expect_frames(m, {{0x701, {0xFE, 0x03, 0x80, 0x7F}}});
    m.type = LINKMSG_NAV_HEARTBEAT;
    expect_frames(m, {{0x702, {0xFE, 0x03, 0x80, 0x7F}}});

    hal_can_frame_t f[2];
    m = {};
    m.type = 0;
    EXPECT_EQ(linkmsg_encode(&m, f), 0);
    m.type = LINKMSG_NAV_HEARTBEAT + 1;
    EXPECT_EQ(linkmsg_encode(&m, f), 0);
}

// Who sends each frame (the protocol table), and nobody for other ids.
TEST(LinkMsg, EveryFrameHasItsSender)
{
    const uint16_t from_nav[] = {0x010, 0x020, 0x021, 0x032, 0x041, 0x042, 0x702};
    const uint16_t from_main[] = {0x030, 0x031, 0x033, 0x040, 0x050, 0x701};
    for (uint16_t id : from_nav)
        EXPECT_EQ(linkmsg_sender(id), LINKMSG_NODE_NAV) << std::hex << id;
    for (uint16_t id : from_main)
        EXPECT_EQ(linkmsg_sender(id), LINKMSG_NODE_MAIN) << std::hex << id;
    for (uint16_t id : {0x000, 0x011, 0x022, 0x034, 0x043, 0x051, 0x700, 0x703, 0x7FF})
        EXPECT_EQ(linkmsg_sender(id), -1) << std::hex << id;
}

// Every id with a wrong length is counted and leaves the message alone; a lone A frame of the
// wrong length drops the waiting A frame of its pair only.
TEST(LinkMsg, WrongLengthsAreCountedForEveryId)
{
    linkmsg_rx_t rx;
    linkmsg_rx_init(&rx);
    linkmsg_t out;
    memset(&out, 0x5A, sizeof out);
    linkmsg_t untouched = out;
    uint16_t errors = 0;
    const uint16_t ids[] = {0x010, 0x020, 0x021, 0x030, 0x031, 0x032, 0x033,
                            0x040, 0x041, 0x042, 0x050, 0x701, 0x702};
    const uint8_t good[] = {1, 8, 6, 8, 8, 3, 8, 3, 8, 8, 1, 4, 4};
    for (size_t i = 0; i < sizeof ids / sizeof ids[0]; i++)
        for (uint8_t len = 0; len <= 8; len++) {
            if (len == good[i])
                continue;
            hal_can_frame_t f{ids[i], len, {}};
            EXPECT_FALSE(linkmsg_rx_feed(&rx, &f, &out)) << std::hex << ids[i] << " len " << +len;
            EXPECT_EQ(rx.errors, ++errors) << std::hex << ids[i] << " len " << +len;
        }
    EXPECT_EQ(memcmp(&out, &untouched, sizeof out), 0);

    // Pairs keep their own A frames: a bad FIX A frame does not drop a waiting POSE A frame.
    linkmsg_t pose{}, fix{};
    pose.type = LINKMSG_POSE;
    pose.u.pose.pose = {5, 6, 7};
    fix.type = LINKMSG_FIX;
    hal_can_frame_t fp[2], ff[2];
    linkmsg_encode(&pose, fp);
    linkmsg_encode(&fix, ff);
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fp[0], &out));
    hal_can_frame_t bad_a = ff[0];
    bad_a.len = 4;
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &bad_a, &out));
    EXPECT_EQ(rx.errors, ++errors);
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &ff[1], &out)); // its A frame is gone
    EXPECT_EQ(rx.errors, ++errors);
    EXPECT_TRUE(linkmsg_rx_feed(&rx, &fp[1], &out));
    EXPECT_EQ(out.type, LINKMSG_POSE);
    EXPECT_EQ(out.u.pose.pose.heading, 7u);
    EXPECT_EQ(rx.errors, errors);
    // A B frame of the right length but a wrong tag drops its A frame.
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fp[0], &out));
    hal_can_frame_t bad_tag = fp[1];
    bad_tag.data[5] ^= 1;
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &bad_tag, &out));
    EXPECT_EQ(rx.errors, ++errors);
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fp[1], &out));
    EXPECT_EQ(rx.errors, ++errors);
    // So does a B frame of the wrong length.
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fp[0], &out));
    hal_can_frame_t bad_len = fp[1];
    bad_len.len = 8;
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &bad_len, &out));
    EXPECT_EQ(rx.errors, ++errors);
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fp[1], &out));
    EXPECT_EQ(rx.errors, ++errors);
}

} // namespace
