// Tests of the inter-board messages: every message round-trips through its frames (field by
// field, from independently chosen values), B frames never complete with a missing, damaged
// or foreign A frame, malformed frames are counted, and two boards exchange messages over the
// harness's bus.
#include <gtest/gtest.h>

#include <random>

extern "C" {
#include "hal/irq.h"
#include "hal_posix/harness.h"
#include "link/linkmsg.h"
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
        m.type = (uint8_t)(1 + i % 7);
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
        }
        hal_link_frame_t f[2];
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
    hal_link_frame_t fa[2], fb[2];
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
    hal_link_frame_t damaged = fb[0];
    damaged.data[3] ^= 0x10;
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &damaged, &out));
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &fb[1], &out)); // A damaged in a way the CRC let through
    EXPECT_EQ(rx.errors, 4);
    hal_link_frame_t shortf = fb[0];
    shortf.len = 7;
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &shortf, &out));
    EXPECT_EQ(rx.errors, 5);
    hal_link_frame_t other = {0x123, 2, {1, 2}};
    EXPECT_FALSE(linkmsg_rx_feed(&rx, &other, &out)); // someone else's traffic: ignored
    EXPECT_EQ(rx.errors, 5);
}

struct Inbox {
    linkmsg_rx_t rx;
    std::vector<linkmsg_t> got;
};

void on_frame(void *arg, const hal_link_frame_t *f)
{
    auto *in = static_cast<Inbox *>(arg);
    linkmsg_t m;
    if (linkmsg_rx_feed(&in->rx, f, &m))
        in->got.push_back(m);
}

TEST(LinkMsg, BoardsExchangeMessagesOverTheBus)
{
    posix_reset();
    int main_b = posix_board_create("main"), nav_b = posix_board_create("nav");
    Inbox at_main, at_nav;
    linkmsg_rx_init(&at_main.rx);
    linkmsg_rx_init(&at_nav.rx);
    posix_board_select(main_b);
    hal_link_init(on_frame, &at_main);
    hal_irq_enable();
    posix_board_select(nav_b);
    hal_link_init(on_frame, &at_nav);
    hal_irq_enable();
    linkmsg_t fix{};
    fix.type = LINKMSG_FIX;
    fix.u.fix.pose = {100000, -200000, 0x40000000u};
    fix.u.fix.latch = 77;
    fix.u.fix.flags = LINKMSG_FIX_HAS_REF;
    posix_board_select(main_b);
    ASSERT_EQ(linkmsg_send(&fix), 0);
    posix_run_until(1000000);
    ASSERT_EQ(at_nav.got.size(), 1u);
    EXPECT_EQ(at_nav.got[0].u.fix.latch, 77);
    EXPECT_TRUE(same_pose(at_nav.got[0].u.fix.pose, fix.u.fix.pose));
    EXPECT_TRUE(at_main.got.empty());
}

} // namespace
