// Tests of the harness's CAN bus model (hal/posix/can.c, hal/can.h on the host). Expected
// values come from the CAN rules themselves, worked out here independently of the model:
// frame lengths from the literature's worst case (Davis, Burns, Bril, Lukkien, "Controller Area
// Network (CAN) schedulability analysis: refuted, revisited and revised", 2007: a standard
// frame of s bytes takes at most 55 + 10 s bit times), the error frame (6 + 8 bits) and
// intermission (3 bits), the fault-confinement rules of ISO 11898-1 (TEC + 8 per transmit
// error, - 1 per success; REC + 1 / - 1; error-passive above 127, bus-off above 255; 128
// occurrences of 11 recessive bits to recover), and timing by hand at 250 kbit/s (4 us a bit).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

extern "C" {
#include "hal/can.h"
#include "hal/irq.h"
#include "hal/pinmap.h"
#include "hal_posix/can_bus.h"
#include "hal_posix/harness.h"
}

namespace
{

const uint64_t BIT = 4000; // ns at 250 kbit/s

struct Rx {
    std::vector<std::pair<uint64_t, hal_can_frame_t>> got;
    int refill = 0; // frames to queue again from the handler (a busy node)
    hal_can_frame_t again{};
};

void on_rx(void *arg, const hal_can_frame_t *f)
{
    static_cast<Rx *>(arg)->got.push_back({posix_now_ns(), *f});
}

hal_can_frame_t frame(uint16_t id, uint8_t len)
{
    hal_can_frame_t f{};
    f.id = id;
    f.len = len;
    for (uint8_t i = 0; i < len && i < HAL_CAN_MAX_DATA; i++) // a bad len is refused, not read
        f.data[i] = (uint8_t)(0xA0 + i);
    return f;
}

class Bus : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        posix_reset();
    }

    // A board on bus 0 at @p rate, interrupts enabled; returns its id.
    int node(Rx *rx, uint32_t rate = 250000, uint8_t manual = 0)
    {
        int b = posix_board_create("n");
        posix_board_select(b);
        hal_can_config_t c{};
        c.bitrate_bps = rate;
        c.manual_recovery = manual;
        c.rx_cb = on_rx;
        c.rx_arg = rx;
        EXPECT_EQ(hal_can_init(0, &c), 0);
        hal_irq_enable();
        return b;
    }

    int send(int board, uint16_t id, uint8_t len)
    {
        posix_board_select(board);
        hal_can_frame_t f = frame(id, len);
        return hal_can_send(0, &f);
    }

    hal_can_status_t status(int board)
    {
        hal_can_status_t st{};
        EXPECT_EQ(posix_can_node(0, board, nullptr, &st), 0);
        return st;
    }

    hal_can_stats_t stats(int board)
    {
        hal_can_stats_t st{};
        EXPECT_EQ(posix_can_node(0, board, &st, nullptr), 0);
        return st;
    }
};

TEST(CanTiming, WorstCaseFrameLengthsAreTheLiteraturesFiftyFivePlusTenPerByte)
{
    for (uint8_t s = 0; s <= 8; s++) {
        EXPECT_EQ(posix_can_frame_bits(s), 55u + 10u * s) << int(s);
        EXPECT_EQ(posix_can_stuffable_bits(s), 34u + 8u * s);
        EXPECT_EQ(posix_can_stuff_bits(s), (33u + 8u * s) / 4u);
    }
}

TEST_F(Bus, AFrameArrivesAfterItsWorstCaseLengthAsAnInterrupt)
{
    Rx ra, rb;
    int a = node(&ra), b = node(&rb);
    ASSERT_EQ(send(a, 0x123, 8), 0);
    posix_run_until(135 * BIT - 1);
    EXPECT_TRUE(rb.got.empty());
    posix_run_until(135 * BIT);
    ASSERT_EQ(rb.got.size(), 1u);
    EXPECT_EQ(rb.got[0].first, 135 * BIT);
    EXPECT_EQ(rb.got[0].second.id, 0x123);
    EXPECT_EQ(std::memcmp(rb.got[0].second.data, frame(0x123, 8).data, 8), 0);
    EXPECT_TRUE(ra.got.empty()); // no node hears itself
    EXPECT_EQ(posix_source_count(b, posix_source_find(b, HAL_CAN0_VECTOR, HAL_CAN0_INT_PIN)), 1u);
    EXPECT_EQ(stats(a).tx_frames, 1u);
    EXPECT_EQ(stats(b).rx_frames, 1u);
    posix_can_bus_stats_t bs;
    ASSERT_EQ(posix_can_bus_stats(0, &bs), 0);
    EXPECT_EQ(bs.frames, 1u);
    EXPECT_EQ(bs.busy_ns, 135 * BIT);
}

TEST_F(Bus, TheLowestPendingIdWinsAndANodesFramesKeepTheirOrder)
{
    Rx ra, rb, rc;
    int a = node(&ra), b = node(&rb), c = node(&rc);
    // All queued at the same instant on an idle bus: they contend for the first start of frame.
    ASSERT_EQ(send(a, 0x300, 0), 0);
    ASSERT_EQ(send(a, 0x100, 0), 0); // behind a's 0x300 in its FIFO
    ASSERT_EQ(send(b, 0x200, 0), 0);
    ASSERT_EQ(send(c, 0x050, 0), 0);
    posix_run_until(10 * 55 * BIT);
    // Heads 0x300, 0x200, 0x050: c's goes first; then 0x200 beats a's head 0x300; a's 0x100
    // comes last although it is lower than 0x200 and 0x300 (a node sends in order).
    ASSERT_EQ(ra.got.size(), 2u);
    EXPECT_EQ(ra.got[0].second.id, 0x050);
    EXPECT_EQ(ra.got[0].first, 55 * BIT);
    EXPECT_EQ(ra.got[1].second.id, 0x200);
    EXPECT_EQ(ra.got[1].first, 2 * 55 * BIT);
    ASSERT_EQ(rc.got.size(), 3u);
    EXPECT_EQ(rc.got[0].second.id, 0x200);
    EXPECT_EQ(rc.got[1].second.id, 0x300);
    EXPECT_EQ(rc.got[1].first, 3 * 55 * BIT);
    EXPECT_EQ(rc.got[2].second.id, 0x100);
    EXPECT_EQ(rc.got[2].first, 4 * 55 * BIT);
    ASSERT_EQ(rb.got.size(), 3u);
}

TEST_F(Bus, NobodyToAcknowledgeRaisesTecByEightUntilErrorPassiveThenItStays)
{
    Rx ra;
    int a = node(&ra);
    ASSERT_EQ(send(a, 0x10, 1), 0);
    // Each attempt: up to the ACK slot (42 + 10 stuff + 2), error flag 6, delimiter 8,
    // intermission 3 = 71 bits.
    posix_run_until(71 * BIT);
    EXPECT_EQ(status(a).tec, 8);
    EXPECT_EQ(status(a).state, HAL_CAN_ERROR_ACTIVE);
    posix_run_until(16 * 71 * BIT);
    EXPECT_EQ(status(a).tec, 128);
    EXPECT_EQ(status(a).state, HAL_CAN_ERROR_PASSIVE);
    posix_run_until(100 * 71 * BIT);
    EXPECT_EQ(status(a).tec, 128); // an error-passive sender alone: no increment (exception 1)
    EXPECT_EQ(stats(a).error_passive, 1u);
    EXPECT_GT(stats(a).tx_errors, 16u);
    EXPECT_EQ(stats(a).tx_frames, 0u);
    // A second node joins: the next attempt is acknowledged, TEC - 1, error-active again.
    Rx rb;
    int b = node(&rb);
    posix_run_until(posix_now_ns() + 2 * 79 * BIT);
    ASSERT_EQ(rb.got.size(), 1u);
    EXPECT_EQ(status(a).tec, 127);
    EXPECT_EQ(status(a).state, HAL_CAN_ERROR_ACTIVE);
    (void)b;
}

TEST_F(Bus, ACorruptedFrameGetsAnErrorFrameAndIsSentAgain)
{
    Rx ra, rb;
    int a = node(&ra), b = node(&rb);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_CORRUPT;
    f.until_ns = UINT64_MAX;
    f.sender = -1;
    f.id = 0x123;
    f.count = 1;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    ASSERT_EQ(send(a, 0x123, 8), 0);
    // The corrupted attempt: 98 + 24 stuff + CRC delimiter + ACK slot, then 6 + 8 + 3; then the
    // whole frame again.
    uint64_t first = (98 + 24 + 2 + 17) * BIT;
    posix_run_until(first);
    EXPECT_EQ(status(a).tec, 8);
    EXPECT_EQ(status(b).rec, 1);
    EXPECT_TRUE(rb.got.empty());
    posix_run_until(first + 135 * BIT);
    ASSERT_EQ(rb.got.size(), 1u);
    EXPECT_EQ(rb.got[0].first, first + 135 * BIT);
    EXPECT_EQ(status(a).tec, 7);
    EXPECT_EQ(status(b).rec, 0);
    EXPECT_EQ(stats(a).tx_errors, 1u);
    EXPECT_EQ(stats(b).rx_errors, 1u);
    posix_can_bus_stats_t bs;
    posix_can_bus_stats(0, &bs);
    EXPECT_EQ(bs.error_frames, 1u);
    EXPECT_EQ(bs.busy_ns, first + 135 * BIT);
}

TEST_F(Bus, ADroppedFrameIsAcknowledgedAndLostWithoutARetry)
{
    Rx ra, rb;
    int a = node(&ra), b = node(&rb);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_DROP;
    f.until_ns = UINT64_MAX;
    f.sender = a;
    f.id = -1;
    f.count = 1;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    send(a, 0x10, 2);
    send(a, 0x11, 2);
    posix_run_until(2 * 75 * BIT);
    ASSERT_EQ(rb.got.size(), 1u);
    EXPECT_EQ(rb.got[0].second.id, 0x11);
    EXPECT_EQ(stats(a).tx_frames, 2u);
    EXPECT_EQ(stats(b).rx_overruns, 1u);
    EXPECT_EQ(status(a).tec, 0);
}

TEST_F(Bus, ADelayedFrameHoldsUpItsSendersQueueNotTheOthers)
{
    Rx ra, rb, rc;
    int a = node(&ra), b = node(&rb);
    node(&rc);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_DELAY;
    f.until_ns = UINT64_MAX;
    f.sender = a;
    f.id = 0x10;
    f.delay_ns = 1000000;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    send(a, 0x10, 0);
    send(a, 0x11, 0);
    send(b, 0x20, 0);
    posix_run_until(5000000);
    ASSERT_EQ(rc.got.size(), 3u);
    EXPECT_EQ(rc.got[0].second.id, 0x20);
    EXPECT_EQ(rc.got[0].first, 55 * BIT);
    EXPECT_EQ(rc.got[1].second.id, 0x10);
    EXPECT_EQ(rc.got[1].first, 1000000 + 55 * BIT);
    EXPECT_EQ(rc.got[2].second.id, 0x11);
    EXPECT_EQ(rc.got[2].first, 1000000 + 2 * 55 * BIT);
}

TEST_F(Bus, ABabblerWinsEveryArbitrationWhileItBabbles)
{
    Rx ra, rb;
    int a = node(&ra);
    node(&rb);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_BABBLE;
    f.from_ns = 0;
    f.until_ns = 10 * 135 * BIT + 1; // ten frames start before it ends, an eleventh too
    f.id = 0x000;
    f.len = 8;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    posix_run_until(1); // it has begun
    send(a, 0x010, 0);
    posix_run_until(40 * 135 * BIT);
    // b hears the babbler's eleven frames (back to back from 0), then a's frame.
    ASSERT_EQ(rb.got.size(), 12u);
    for (int i = 0; i < 11; i++) {
        EXPECT_EQ(rb.got[i].second.id, 0x000);
        EXPECT_EQ(rb.got[i].second.data[0], (uint8_t)i); // its counter
        EXPECT_EQ(rb.got[i].first, (uint64_t)(i + 1) * 135 * BIT);
    }
    EXPECT_EQ(rb.got[11].second.id, 0x010);
    EXPECT_EQ(rb.got[11].first, 11 * 135 * BIT + 55 * BIT);
    EXPECT_EQ(ra.got.size(), 11u);
}

TEST_F(Bus, ABrokenTransmitterGoesBusOffAndRecoversAfter128ElevenBitRuns)
{
    Rx ra, rb;
    int a = node(&ra), b = node(&rb);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_BUSOFF;
    f.from_ns = 0;
    f.until_ns = 0;
    f.sender = a;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    posix_run_until(1);
    ASSERT_EQ(send(a, 0x10, 8), 0);
    ASSERT_EQ(send(a, 0x11, 8), 0);
    // Every attempt: a bit error after the arbitration field (13 bits), then 6 + 8 + 3. Sixteen
    // attempts take TEC to 128 (error-passive: 8 bits of suspend transmission after each of its
    // own), sixteen more to 256: bus-off.
    uint64_t off = 1 + (32 * 30 + 16 * 8) * BIT;
    posix_run_until(off - 1);
    EXPECT_EQ(status(a).state, HAL_CAN_ERROR_PASSIVE);
    posix_run_until(off);
    EXPECT_EQ(status(a).state, HAL_CAN_BUS_OFF);
    EXPECT_EQ(status(b).rec, 32); // one receive error per attempt
    EXPECT_EQ(stats(a).tx_aborted, 2u);
    posix_board_select(a);
    hal_can_frame_t fr = frame(0x12, 1);
    EXPECT_EQ(hal_can_send(0, &fr), HAL_CAN_E_BUS_OFF);
    EXPECT_EQ(hal_can_tx_room(0), 0);
    // An idle bus: 128 x 11 bit times.
    posix_run_until(off + 1408 * BIT - 1);
    EXPECT_EQ(status(a).state, HAL_CAN_BUS_OFF);
    posix_run_until(off + 1408 * BIT);
    EXPECT_EQ(status(a).state, HAL_CAN_ERROR_ACTIVE);
    EXPECT_EQ(status(a).tec, 0);
    EXPECT_EQ(stats(a).bus_off, 1u);
    EXPECT_EQ(stats(a).recoveries, 1u);
    // The fault is over: a sends again.
    ASSERT_EQ(send(a, 0x13, 0), 0);
    posix_run_until(posix_now_ns() + 55 * BIT);
    ASSERT_EQ(rb.got.size(), 1u);
    EXPECT_EQ(rb.got[0].second.id, 0x13);
}

// hal_can_wake_on_room(): the board's main loop runs when room may have grown, once per wait
// stated: at the end of each of its frames (55 + 10 s bits, the worst case), and at the end of
// a bus-off (128 x 11 bit times of idle bus); never for another node's frames.
TEST_F(Bus, AMainLoopWaitingForRoomRunsWhenItsFrameLeavesOrItsBusOffEnds)
{
    Rx ra, rb;
    int a = node(&ra), b = node(&rb);
    for (int i = 0; i < HAL_CAN_TX_QUEUE; i++)
        ASSERT_EQ(send(a, (uint16_t)(0x100 + i), 8), 0);
    posix_board_select(a);
    ASSERT_EQ(hal_can_tx_room(0), 0);
    hal_can_wake_on_room(0);
    posix_board_select(b);
    hal_can_wake_on_room(0); // b sends nothing: a's frames never wake it
    posix_run_until(135 * BIT - 1);
    EXPECT_FALSE(posix_board_take_wake(a));
    posix_run_until(135 * BIT);
    EXPECT_TRUE(posix_board_take_wake(a));
    posix_board_select(a);
    EXPECT_EQ(hal_can_tx_room(0), 1);
    posix_run_until(2 * 135 * BIT);
    EXPECT_FALSE(posix_board_take_wake(a)) << "one wake per wait stated";
    hal_can_wake_on_room(0);
    posix_run_until(3 * 135 * BIT - 1);
    EXPECT_FALSE(posix_board_take_wake(a));
    posix_run_until(3 * 135 * BIT);
    EXPECT_TRUE(posix_board_take_wake(a));
    EXPECT_FALSE(posix_board_take_wake(b));

    // Bus-off (every attempt of a's fails), then 128 x 11 bit times of idle bus.
    posix_run_until(HAL_CAN_TX_QUEUE * 135 * BIT);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_BUSOFF;
    f.from_ns = posix_now_ns();
    f.until_ns = f.from_ns;
    f.sender = a;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    ASSERT_EQ(send(a, 0x10, 8), 0);
    uint64_t off = f.from_ns + (32 * 30 + 16 * 8) * BIT;
    posix_run_until(off);
    ASSERT_EQ(status(a).state, HAL_CAN_BUS_OFF);
    posix_board_select(a);
    EXPECT_EQ(hal_can_tx_room(0), 0);
    hal_can_wake_on_room(0);
    posix_run_until(off + 1408 * BIT - 1);
    EXPECT_FALSE(posix_board_take_wake(a));
    posix_run_until(off + 1408 * BIT);
    EXPECT_EQ(status(a).state, HAL_CAN_ERROR_ACTIVE);
    EXPECT_TRUE(posix_board_take_wake(a));
    EXPECT_FALSE(posix_board_take_wake(b));
}

TEST_F(Bus, RecoveryCountsOneRunPerFrameWhileTheOthersTalk)
{
    Rx ra, rb, rc;
    int a = node(&ra, 250000, 1), b = node(&rb);
    node(&rc);
    posix_can_fault_t f{};
    f.kind = POSIX_CAN_FAULT_BUSOFF;
    f.sender = a;
    ASSERT_EQ(posix_can_add_fault(0, &f), 0);
    posix_run_until(1);
    send(a, 0x10, 0);
    posix_run_until(100000000);
    ASSERT_EQ(status(a).state, HAL_CAN_BUS_OFF); // manual recovery: it stays off
    posix_board_select(b);
    EXPECT_EQ(hal_can_recover(0), HAL_CAN_E_STATE); // b is not bus-off
    posix_board_select(a);
    uint64_t t0 = posix_now_ns();
    ASSERT_EQ(hal_can_recover(0), 0);
    // 55 idle bits (5 runs), then b sends back to back: each frame ends with 11 recessive bits
    // (ACK delimiter, EOF, intermission) before the next start of frame: one run per frame.
    posix_run_until(t0 + 55 * BIT);
    for (int i = 0; i < 8; i++)
        send(b, 0x100, 8);
    for (int k = 0; k < 20; k++) { // keep b's queue full
        posix_run_until(posix_now_ns() + 7 * 135 * BIT);
        while (send(b, 0x100, 8) == 0) {
        }
    }
    // 5 + 123 runs: a is back when the 124th frame starts.
    hal_can_status_t st = status(a);
    EXPECT_EQ(st.state, HAL_CAN_ERROR_ACTIVE);
    std::vector<uint64_t> ends;
    for (auto &g : rc.got)
        ends.push_back(g.first);
    ASSERT_GE(ends.size(), 124u);
    EXPECT_EQ(ends[122], t0 + 55 * BIT + 123 * 135 * BIT);
    // a received nothing while off, and takes frames again from the 124th on.
    ASSERT_FALSE(ra.got.empty());
    EXPECT_EQ(ra.got[0].first, t0 + 55 * BIT + 124 * 135 * BIT);
    EXPECT_EQ(stats(a).recoveries, 1u);
}

TEST_F(Bus, FiltersChooseWhatReachesTheHandlerButEveryFrameIsAcknowledged)
{
    Rx ra, rb;
    int a = node(&ra);
    int b = posix_board_create("filtered");
    posix_board_select(b);
    hal_can_config_t c{};
    c.bitrate_bps = 250000;
    c.filters[0] = {0x000, 0x700}; // 0x000-0x0FF
    c.filters[1] = {0x701, 0x7FF}; // 0x701 only
    c.n_filters = 2;
    c.rx_cb = on_rx;
    c.rx_arg = &rb;
    ASSERT_EQ(hal_can_init(0, &c), 0);
    hal_irq_enable();
    for (uint16_t id : {0x010, 0x123, 0x701, 0x702, 0x0FF})
        send(a, id, 0);
    posix_run_until(6 * 55 * BIT);
    ASSERT_EQ(rb.got.size(), 3u);
    EXPECT_EQ(rb.got[0].second.id, 0x010);
    EXPECT_EQ(rb.got[1].second.id, 0x701);
    EXPECT_EQ(rb.got[2].second.id, 0x0FF);
    EXPECT_EQ(stats(a).tx_frames, 5u);
    EXPECT_EQ(status(a).tec, 0);
}

TEST_F(Bus, TwoReceiveBuffersThenOverruns)
{
    Rx ra, rb;
    int a = node(&ra);
    int b = posix_board_create("slow");
    posix_board_select(b);
    hal_can_config_t c{};
    c.bitrate_bps = 250000;
    c.rx_cb = on_rx;
    c.rx_arg = &rb;
    ASSERT_EQ(hal_can_init(0, &c), 0); // interrupts stay off: nobody empties the buffers
    for (uint8_t i = 0; i < 3; i++)
        send(a, (uint16_t)(0x10 + i), 0);
    posix_run_until(4 * 55 * BIT);
    EXPECT_TRUE(rb.got.empty());
    EXPECT_EQ(stats(b).rx_overruns, 1u);
    EXPECT_EQ(stats(a).tx_frames, 3u); // acknowledged all the same
    posix_board_select(b);
    hal_irq_enable();
    ASSERT_EQ(rb.got.size(), 2u);
    EXPECT_EQ(rb.got[0].second.id, 0x10);
    EXPECT_EQ(rb.got[1].second.id, 0x11);
}

TEST_F(Bus, ANodeAtAnotherBitRateNeitherAcknowledgesNorReceives)
{
    Rx ra, rb;
    int a = node(&ra, 250000), b = node(&rb, 500000);
    send(a, 0x10, 0);
    posix_run_until(10 * 71 * BIT);
    EXPECT_TRUE(rb.got.empty());
    EXPECT_GT(stats(a).tx_errors, 0u); // no acknowledgement
    EXPECT_GT(status(b).rec, 0);
    EXPECT_EQ(stats(b).rx_errors, status(b).rec);
}

TEST_F(Bus, TheCarrierDecidesWhatTheReceiversGet)
{
    Rx ra, rb;
    int a = node(&ra), b = node(&rb);
    (void)b;
    posix_can_set_carrier(
        [](void *, hal_can_t, const hal_can_frame_t *sent, hal_can_frame_t *got) {
            *got = *sent;
            got->data[0] ^= 0xFF;
            return 0;
        },
        nullptr);
    send(a, 0x10, 1);
    posix_run_until(65 * BIT);
    ASSERT_EQ(rb.got.size(), 1u);
    EXPECT_EQ(rb.got[0].second.data[0], (uint8_t)(0xA0 ^ 0xFF));
}

TEST_F(Bus, TheObserverSeesFramesErrorsAndStates)
{
    struct Seen {
        std::vector<posix_can_event_t> ev;
    } seen;
    posix_can_set_tap(
        [](void *ctx, const posix_can_event_t *ev) { static_cast<Seen *>(ctx)->ev.push_back(*ev); },
        &seen);
    Rx ra;
    int a = node(&ra);
    send(a, 0x10, 0);
    posix_run_until(16 * (34 + 8 + 2 + 17) * BIT); // sixteen ACK errors: error-passive
    ASSERT_GE(seen.ev.size(), 17u);
    EXPECT_EQ(seen.ev[0].kind, POSIX_CAN_EV_ERROR);
    EXPECT_EQ(seen.ev[0].error, POSIX_CAN_ERR_ACK);
    EXPECT_EQ(seen.ev[0].node, a);
    EXPECT_EQ(seen.ev[0].queued_ns, 0u);
    bool passive = false;
    for (auto &e : seen.ev)
        passive |= e.kind == POSIX_CAN_EV_STATE && e.state == HAL_CAN_ERROR_PASSIVE;
    EXPECT_TRUE(passive);
}

TEST_F(Bus, BadArgumentsAreRefusedAndChangeNothing)
{
    Rx ra;
    int a = node(&ra);
    posix_board_select(a);
    hal_can_config_t c{};
    c.bitrate_bps = 250000;
    c.rx_cb = on_rx;
    c.rx_arg = &ra;
    EXPECT_EQ(hal_can_init(2, &c), HAL_CAN_E_PARAM);
    EXPECT_EQ(hal_can_init(0, nullptr), HAL_CAN_E_PARAM);
    hal_can_config_t bad = c;
    bad.rx_cb = nullptr;
    EXPECT_EQ(hal_can_init(0, &bad), HAL_CAN_E_PARAM);
    bad = c;
    bad.n_filters = 3;
    EXPECT_EQ(hal_can_init(0, &bad), HAL_CAN_E_PARAM);
    bad = c;
    bad.n_filters = 1;
    bad.filters[0] = {0x800, 0x7FF};
    EXPECT_EQ(hal_can_init(0, &bad), HAL_CAN_E_PARAM);
    bad = c;
    bad.bitrate_bps = 300000; // 3333.3 ns a bit
    EXPECT_EQ(hal_can_init(0, &bad), HAL_CAN_E_BITRATE);
    bad.bitrate_bps = 2000000;
    EXPECT_EQ(hal_can_init(0, &bad), HAL_CAN_E_BITRATE);
    hal_can_frame_t f = frame(0x800, 0);
    EXPECT_EQ(hal_can_send(0, &f), HAL_CAN_E_PARAM);
    f = frame(0x10, 9);
    EXPECT_EQ(hal_can_send(0, &f), HAL_CAN_E_PARAM);
    EXPECT_EQ(hal_can_send(1, &f), HAL_CAN_E_PARAM);
    f = frame(0x10, 0);
    EXPECT_EQ(hal_can_send(1, &f), HAL_CAN_E_STATE); // bus 1 not initialised here
    EXPECT_EQ(hal_can_recover(0), HAL_CAN_E_STATE);
    // The node is as it was: error-active, an empty queue of 8.
    EXPECT_EQ(hal_can_tx_room(0), HAL_CAN_TX_QUEUE);
    for (int i = 0; i < HAL_CAN_TX_QUEUE; i++)
        EXPECT_EQ(send(a, 0x10, 0), 0);
    EXPECT_EQ(send(a, 0x10, 0), HAL_CAN_E_FULL);
    posix_can_fault_t fl{};
    fl.kind = POSIX_CAN_FAULT_BUSOFF;
    fl.sender = -1;
    EXPECT_EQ(posix_can_add_fault(0, &fl), -1);
    fl.kind = POSIX_CAN_FAULT_BABBLE;
    fl.until_ns = 10;
    fl.id = 0x800;
    EXPECT_EQ(posix_can_add_fault(0, &fl), -1);
}

} // namespace
