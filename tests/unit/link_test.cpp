// Tests of the board link (firmware/link/link.c) on the harness's CAN bus model: messages
// between two boards, both frames of a pair or neither, the heartbeat (period, rolling counter,
// flags, error counters), the watch on the other board (silent after silence_ms without a
// frame from it, heard again), missed heartbeats, bus-off and recovery, refused
// configurations. Timing expectations are worked out here from the configuration (and the
// frame lengths of the literature, 55 + 10 s bits, at 250 kbit/s).
#include <gtest/gtest.h>

#include <vector>

extern "C" {
#include "hal/clock.h"
#include "hal/irq.h"
#include "hal_posix/can_bus.h"
#include "hal_posix/harness.h"
#include "link/link.h"
}

namespace
{

struct Board {
    int id = -1;
    link_t link{};
    std::vector<linkmsg_t> got;
    std::vector<link_event_t> events;
    std::vector<uint32_t> event_ms;
    bool alive = true; // its main loop runs
};

void on_msg(void *ctx, const linkmsg_t *m)
{
    static_cast<Board *>(ctx)->got.push_back(*m);
}

struct Tap {
    std::vector<posix_can_event_t> ev;
};

void on_bus(void *ctx, const posix_can_event_t *ev)
{
    static_cast<Tap *>(ctx)->ev.push_back(*ev);
}

class Link : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        posix_reset();
        posix_can_set_tap(on_bus, &tap);
    }

    link_config_t config(uint8_t node)
    {
        return {node, 250000, 50, 250};
    }

    void up(Board &b, uint8_t node, const link_config_t *c = nullptr)
    {
        b.id = posix_board_create(node == LINKMSG_NODE_MAIN ? "main" : "nav");
        posix_board_select(b.id);
        link_config_t cfg = c ? *c : config(node);
        ASSERT_EQ(link_init(&b.link, &cfg, on_msg, &b), 0);
        hal_irq_enable();
    }

    // Run the boards' main loops every millisecond up to @p ms.
    void run_to(uint32_t ms, std::vector<Board *> boards)
    {
        while (posix_now_ns() < (uint64_t)ms * 1000000u) {
            posix_run_until(posix_now_ns() + 1000000u);
            for (Board *b : boards) {
                if (!b->alive)
                    continue;
                posix_board_select(b->id);
                link_event_t e = link_poll(&b->link);
                if (e != LINK_EV_NONE) {
                    b->events.push_back(e);
                    b->event_ms.push_back(hal_clock_ms());
                }
            }
        }
    }

    std::vector<posix_can_event_t> frames(uint16_t id)
    {
        std::vector<posix_can_event_t> out;
        for (auto &e : tap.ev)
            if (e.kind == POSIX_CAN_EV_FRAME && e.frame.id == id)
                out.push_back(e);
        return out;
    }

    // Queue @p n DIR messages (one frame each) on @p b's link.
    void queue_dirs(Board &b, int n)
    {
        posix_board_select(b.id);
        linkmsg_t dir{};
        dir.type = LINKMSG_DIR;
        for (int i = 0; i < n; i++)
            ASSERT_EQ(link_send(&b.link, &dir), 0);
    }

    link_stats_t stats(Board &b)
    {
        posix_board_select(b.id);
        link_stats_t s;
        link_stats(&b.link, &s);
        return s;
    }

    Tap tap;
};

TEST_F(Link, MessagesTravelBetweenTheBoards)
{
    Board m, n;
    up(m, LINKMSG_NODE_MAIN);
    up(n, LINKMSG_NODE_NAV);
    linkmsg_t fix{};
    fix.type = LINKMSG_FIX;
    fix.u.fix.pose = {100000, -200000, 0x40000000u};
    fix.u.fix.latch = 77;
    fix.u.fix.flags = LINKMSG_FIX_HAS_REF;
    posix_board_select(m.id);
    ASSERT_EQ(link_send(&m.link, &fix), 0);
    run_to(5, {&m, &n});
    ASSERT_EQ(n.got.size(), 1u); // heartbeats stay inside the link
    EXPECT_EQ(n.got[0].type, LINKMSG_FIX);
    EXPECT_EQ(n.got[0].u.fix.latch, 77);
    EXPECT_EQ(n.got[0].u.fix.pose.y, -200000);
    EXPECT_TRUE(m.got.empty());
    linkmsg_t bad{};
    bad.type = 0;
    EXPECT_EQ(link_send(&m.link, &bad), LINK_E_MESSAGE);
}

TEST_F(Link, BothFramesOfAPairOrNeither)
{
    Board m, n;
    up(m, LINKMSG_NODE_MAIN);
    up(n, LINKMSG_NODE_NAV);
    queue_dirs(m, HAL_CAN_TX_QUEUE - 1);
    EXPECT_EQ(link_tx_room(&m.link), 1);
    linkmsg_t fix{};
    fix.type = LINKMSG_FIX;
    EXPECT_EQ(link_send(&m.link, &fix), LINK_E_FULL);
    EXPECT_EQ(link_tx_room(&m.link), 1); // nothing queued
    queue_dirs(m, 1);
    EXPECT_EQ(stats(m).send_refused, 1);
}

TEST_F(Link, EachBoardSendsItsHeartbeatEveryPeriodWithARollingCounter)
{
    Board m, n;
    up(m, LINKMSG_NODE_MAIN);
    up(n, LINKMSG_NODE_NAV);
    run_to(1000, {&m, &n});
    auto hb = frames(LINKMSG_ID_MAIN_HEARTBEAT);
    // Due from 0 ms of the board's clock every 50 ms; the first poll is at 1 ms, then on time:
    // 1, 50, 100, ..., 950 went through; the one of 1000 ms is queued at the end.
    ASSERT_EQ(hb.size(), 20u);
    for (size_t i = 0; i < hb.size(); i++) {
        EXPECT_EQ(hb[i].frame.len, 4);
        EXPECT_EQ(hb[i].frame.data[0], (uint8_t)i); // counter
        EXPECT_EQ(hb[i].queued_ns, (uint64_t)(i ? 50 * i : 1) * 1000000u) << i;
        EXPECT_EQ(hb[i].frame.data[1], LINKMSG_HB_HEARS_PEER);
        EXPECT_EQ(hb[i].frame.data[2], 0); // TEC
        EXPECT_EQ(hb[i].frame.data[3], 0); // REC
    }
    EXPECT_EQ(frames(LINKMSG_ID_NAV_HEARTBEAT).size(), 20u);
    link_stats_t s = stats(m);
    EXPECT_EQ(s.heartbeats_sent, 21u);
    EXPECT_EQ(s.peer_heartbeats, 20u);
    EXPECT_EQ(s.peer_missed, 0);
    EXPECT_EQ(s.silences, 0);
    EXPECT_TRUE(m.events.empty());
    // The counter rolls over after 255.
    run_to(13000, {&m, &n});
    hb = frames(LINKMSG_ID_MAIN_HEARTBEAT);
    ASSERT_EQ(hb.size(), 260u);
    EXPECT_EQ(hb[255].frame.data[0], 255);
    EXPECT_EQ(hb[256].frame.data[0], 0);
    EXPECT_EQ(stats(n).peer_missed, 0); // the roll-over is not a gap
}

TEST_F(Link, ABoardThatHearsNothingForTheSilenceTimeSaysSoOnceThenHearsAgain)
{
    Board m, n;
    up(m, LINKMSG_NODE_MAIN);
    up(n, LINKMSG_NODE_NAV);
    run_to(200, {&m, &n});
    n.alive = false; // its main loop stops: no more heartbeats from it
    run_to(1000, {&m, &n});
    // n's last heartbeat was queued at 200 ms and heard behind m's own (2 x 95 bits: 0.76 ms),
    // in m's millisecond 200; silent 250 ms after: at 450 ms.
    ASSERT_EQ(m.events.size(), 1u);
    EXPECT_EQ(m.events[0], LINK_EV_SILENT);
    EXPECT_EQ(m.event_ms[0], 450u);
    EXPECT_TRUE(link_peer_silent(&m.link));
    EXPECT_EQ(stats(m).silences, 1);
    // m's own heartbeat says it no longer hears n.
    auto hb = frames(LINKMSG_ID_MAIN_HEARTBEAT);
    EXPECT_EQ(hb.back().frame.data[1] & LINKMSG_HB_HEARS_PEER, 0);
    n.alive = true;
    run_to(1100, {&m, &n});
    ASSERT_EQ(m.events.size(), 2u);
    EXPECT_EQ(m.events[1], LINK_EV_HEARD);
    EXPECT_FALSE(link_peer_silent(&m.link));
    EXPECT_TRUE(n.events.empty()); // n heard m all along
    // Every heartbeat n missed is a gap in its counter: none, it simply sent later.
    EXPECT_EQ(stats(m).peer_missed, 0);
}

// A babbling node with an id outside the table (0x000, inside the link's acceptance filter)
// wins every arbitration from 200 ms: both boards receive its frames, which neither hand on
// nor keep the other board heard, so each falls silent 250 ms after the last heartbeat it
// heard (queued at 150 ms: the 200 ms ones never win the bus).
TEST_F(Link, ABabblersFramesAreIgnoredAndDoNotKeepThePeerHeard)
{
    Board m, n;
    up(m, LINKMSG_NODE_MAIN);
    up(n, LINKMSG_NODE_NAV);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_BABBLE;
    f.from_ns = 200000000u;
    f.until_ns = 2000000000u;
    f.id = 0x000;
    f.len = 8;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    run_to(500, {&m, &n});
    EXPECT_TRUE(m.got.empty());
    EXPECT_TRUE(n.got.empty());
    ASSERT_EQ(m.events.size(), 1u);
    ASSERT_EQ(n.events.size(), 1u);
    EXPECT_EQ(m.events[0], LINK_EV_SILENT);
    EXPECT_EQ(n.events[0], LINK_EV_SILENT);
    EXPECT_EQ(m.event_ms[0], 400u);
    EXPECT_EQ(n.event_ms[0], 400u);
    EXPECT_EQ(stats(m).rx_errors, 0);
    EXPECT_EQ(stats(n).rx_errors, 0);
    EXPECT_GT(stats(n).can.rx_frames, 100u); // the babbler's frames did arrive
}

TEST_F(Link, LostHeartbeatsAreCountedAsGapsButAnyFrameKeepsThePeerHeard)
{
    Board m, n;
    up(m, LINKMSG_NODE_MAIN);
    up(n, LINKMSG_NODE_NAV);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_DROP;
    f.from_ns = 100000000;
    f.until_ns = UINT64_MAX;
    f.sender = n.id;
    f.id = LINKMSG_ID_NAV_HEARTBEAT;
    f.count = 8; // 400 ms of its heartbeats
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    // Meanwhile n sends a STOP every 100 ms: m still hears it.
    for (uint32_t t = 100; t < 600; t += 100) {
        run_to(t, {&m, &n});
        posix_board_select(n.id);
        linkmsg_t stop{};
        stop.type = LINKMSG_STOP;
        stop.u.stop.reason = LINKMSG_STOP_REASON_BLIND_DISTANCE;
        ASSERT_EQ(link_send(&n.link, &stop), 0);
    }
    run_to(1000, {&m, &n});
    EXPECT_TRUE(m.events.empty());
    EXPECT_EQ(stats(m).peer_missed, 8);
    EXPECT_EQ(m.got.size(), 5u);
}

// link_wake_on_room(): a main loop that found too little room runs again when a frame of its
// board has left (a DIR message is one frame of 1 byte: 65 bit times at most).
TEST_F(Link, AMainLoopWaitingForRoomRunsWhenAFrameLeaves)
{
    Board m, n;
    up(m, LINKMSG_NODE_MAIN);
    up(n, LINKMSG_NODE_NAV);
    queue_dirs(m, HAL_CAN_TX_QUEUE);
    ASSERT_EQ(link_tx_room(&m.link), 0);
    link_wake_on_room(&m.link);
    uint64_t t0 = posix_now_ns(), bit = 1000000000u / 250000u;
    posix_run_until(t0 + 65 * bit - 1);
    EXPECT_FALSE(posix_board_take_wake(m.id));
    posix_run_until(t0 + 65 * bit);
    EXPECT_TRUE(posix_board_take_wake(m.id));
    posix_board_select(m.id);
    EXPECT_EQ(link_tx_room(&m.link), 1);
    EXPECT_FALSE(posix_board_take_wake(n.id));
}

TEST_F(Link, BusOffAndRecoveryAreCountedAndTheLinkGoesOn)
{
    Board m, n;
    up(m, LINKMSG_NODE_MAIN);
    up(n, LINKMSG_NODE_NAV);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_BUSOFF;
    f.from_ns = 120000000;
    f.sender = n.id;
    f.until_ns = f.from_ns;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    // n's heartbeat of 150 ms (behind m's) fails 32 times: bus-off after 32 x 30 + 16 x 8
    // bits, 4.35 ms at 250 kbit/s.
    run_to(156, {&m, &n});
    linkmsg_t dir{};
    dir.type = LINKMSG_DIR;
    hal_can_status_t st;
    posix_board_select(n.id);
    ASSERT_EQ(hal_can_status(0, &st), 0);
    ASSERT_EQ(st.state, HAL_CAN_BUS_OFF);
    EXPECT_EQ(link_send(&n.link, &dir), LINK_E_BUS_OFF);
    EXPECT_EQ(link_tx_room(&n.link), 0);
    run_to(1000, {&m, &n});
    link_stats_t s = stats(n);
    EXPECT_EQ(s.can.bus_off, 1);
    EXPECT_EQ(s.can.recoveries, 1);
    EXPECT_EQ(s.can.tx_aborted, 1);     // the heartbeat in the queue
    EXPECT_TRUE(m.events.empty());      // 250 ms of silence never came
    EXPECT_EQ(stats(m).peer_missed, 1); // the heartbeat of 150 ms
    auto hb = frames(LINKMSG_ID_NAV_HEARTBEAT);
    EXPECT_EQ(hb.back().queued_ns / 1000000u, 950u); // back on its period
}

TEST_F(Link, ConfigurationsOutOfRangeAreRefused)
{
    int b = posix_board_create("main");
    posix_board_select(b);
    link_t l;
    link_config_t c = {LINKMSG_NODE_MAIN, 250000, 50, 50};
    EXPECT_EQ(link_init(&l, &c, on_msg, nullptr), LINK_E_CONFIG); // silence not above heartbeat
    c = {LINKMSG_NODE_MAIN, 250000, 0, 250};
    EXPECT_EQ(link_init(&l, &c, on_msg, nullptr), LINK_E_CONFIG);
    c = {LINKMSG_NODE_MAIN, 250000, 50, 60001};
    EXPECT_EQ(link_init(&l, &c, on_msg, nullptr), LINK_E_CONFIG);
    c = {2, 250000, 50, 250};
    EXPECT_EQ(link_init(&l, &c, on_msg, nullptr), LINK_E_CONFIG);
    c = {LINKMSG_NODE_MAIN, 300000, 50, 250};
    EXPECT_EQ(link_init(&l, &c, on_msg, nullptr), HAL_CAN_E_BITRATE);
    c = {LINKMSG_NODE_MAIN, 250000, 50, 250};
    EXPECT_EQ(link_init(&l, &c, nullptr, nullptr), 0); // no handler: allowed
}

} // namespace
