// Tests of the host harness (hal/posix): the virtual interrupt controller, critical
// sections, simulated time and the peripherals' host side. Expected behaviour is the
// MSP430's (SLAU144: interrupt priorities, GIE handling, RETI) as hal_posix/harness.h states it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

extern "C" {
#include "hal/capture.h"
#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal/pinmap.h"
#include "hal/preempt.h"
#include "hal/signal.h"
#include "hal_posix/harness.h"
}

namespace
{

std::vector<std::string> g_log;

void log_isr(void *ctx)
{
    g_log.push_back(static_cast<const char *>(ctx));
}

class Harness : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        posix_reset();
        g_log.clear();
        board = posix_board_create("test");
        ASSERT_GE(board, 0);
        posix_board_select(board);
    }
    int board = -1;
};

TEST_F(Harness, HigherVectorFirstThenLowerBit)
{
    int low = posix_source_register(board, 2, 0, false, log_isr, (void *)"v2b0");
    int high = posix_source_register(board, 7, 0, false, log_isr, (void *)"v7b0");
    int mid1 = posix_source_register(board, 5, 6, false, log_isr, (void *)"v5b6");
    int mid0 = posix_source_register(board, 5, 4, false, log_isr, (void *)"v5b4");
    for (int s : {low, mid1, high, mid0})
        posix_source_raise(board, s);
    posix_dispatch(); // GIE is clear after reset, as on the chip
    EXPECT_TRUE(g_log.empty());
    hal_irq_enable();
    EXPECT_EQ(g_log, (std::vector<std::string>{"v7b0", "v5b4", "v5b6", "v2b0"}));
}

TEST_F(Harness, RegisterRejectsBadArguments)
{
    EXPECT_EQ(posix_source_register(board, -1, 0, false, log_isr, nullptr), -1);
    EXPECT_EQ(posix_source_register(board, HAL_VEC_COUNT, 0, false, log_isr, nullptr), -1);
    EXPECT_EQ(posix_source_register(board, 3, 8, false, log_isr, nullptr), -1);
    EXPECT_EQ(posix_source_register(board, 3, 0, false, nullptr, nullptr), -1);
    int a = posix_source_register(board, 3, 1, false, log_isr, (void *)"a");
    EXPECT_EQ(posix_source_register(board, 3, 1, false, log_isr, (void *)"b"), a);
}

struct GieProbe {
    bool gie_inside = true;
    bool in_isr = false;
    int board_inside = -1;
};

void probe_isr(void *ctx)
{
    auto *p = static_cast<GieProbe *>(ctx);
    p->gie_inside = hal_irq_enabled() != 0;
    p->in_isr = posix_in_isr(posix_board_current());
    p->board_inside = posix_board_current();
}

TEST_F(Harness, HandlerRunsWithGieClearOnItsOwnBoard)
{
    int other = posix_board_create("other");
    GieProbe probe;
    int s = posix_source_register(other, 5, 0, false, probe_isr, &probe);
    posix_board_select(other);
    hal_irq_enable();
    posix_board_select(board);
    posix_source_raise(other, s);
    posix_dispatch();
    EXPECT_FALSE(probe.gie_inside);
    EXPECT_TRUE(probe.in_isr);
    EXPECT_EQ(probe.board_inside, other);
    EXPECT_EQ(posix_board_current(), board); // selection restored after RETI
    EXPECT_TRUE(posix_gie(other));           // GIE restored by RETI
    EXPECT_EQ(posix_source_count(other, s), 1u);
}

TEST_F(Harness, MaskedSourceKeepsItsFlag)
{
    int s = posix_source_register(board, 5, 3, false, log_isr, (void *)"x");
    hal_irq_enable();
    posix_source_enable(board, s, false);
    posix_source_raise(board, s);
    posix_dispatch();
    EXPECT_TRUE(g_log.empty());
    EXPECT_TRUE(posix_source_pending(board, s));
    posix_source_enable(board, s, true);
    posix_dispatch();
    EXPECT_EQ(g_log.size(), 1u);
    EXPECT_FALSE(posix_source_pending(board, s));
}

// A handler on a later board raises a source on an earlier one: posix_dispatch() has passed
// that board, so the flag waits for the next dispatch, which must still see it.
struct CrossRaise {
    int board, source;
};

static void cross_raise_isr(void *ctx)
{
    auto *c = static_cast<CrossRaise *>(ctx);
    g_log.push_back("later");
    posix_source_raise(c->board, c->source);
}

TEST_F(Harness, FlagRaisedOnAnEarlierBoardWaitsForTheNextDispatch)
{
    int later = posix_board_create("later");
    ASSERT_GT(later, board);
    int s = posix_source_register(board, 5, 0, false, log_isr, (void *)"earlier");
    CrossRaise c = {board, s};
    int t = posix_source_register(later, 5, 0, false, cross_raise_isr, &c);
    hal_irq_enable();
    posix_board_select(later);
    hal_irq_enable();
    posix_board_select(board);
    posix_source_raise(later, t);
    posix_dispatch();
    ASSERT_EQ(g_log.size(), 1u);
    EXPECT_TRUE(posix_source_pending(board, s));
    posix_dispatch();
    ASSERT_EQ(g_log.size(), 2u);
    EXPECT_EQ(g_log[1], "earlier");
    EXPECT_FALSE(posix_source_pending(board, s));
}

TEST_F(Harness, CriticalSectionsNestAndReleaseAtTheOutermostExit)
{
    int s = posix_source_register(board, 5, 0, false, log_isr, (void *)"x");
    hal_irq_enable();
    hal_critical_enter();
    hal_critical_enter();
    EXPECT_EQ(hal_critical_depth(), 2);
    posix_source_raise(board, s);
    hal_preempt_point();
    EXPECT_TRUE(g_log.empty());
    hal_critical_exit();
    EXPECT_TRUE(g_log.empty());
    EXPECT_EQ(hal_irq_enabled(), 0u);
    hal_critical_exit();
    EXPECT_EQ(g_log.size(), 1u); // delivered right at the outermost exit
    EXPECT_NE(hal_irq_enabled(), 0u);
}

TEST_F(Harness, CriticalSectionEnteredWithInterruptsOffLeavesThemOff)
{
    EXPECT_EQ(hal_irq_enabled(), 0u);
    hal_critical_enter();
    hal_critical_exit();
    EXPECT_EQ(hal_irq_enabled(), 0u);
}

TEST_F(Harness, IrqDisableRestoreNests)
{
    hal_irq_enable();
    hal_irq_state_t outer = hal_irq_disable();
    hal_irq_state_t inner = hal_irq_disable();
    EXPECT_NE(outer, 0u);
    EXPECT_EQ(inner, 0u);
    hal_irq_restore(inner);
    EXPECT_EQ(hal_irq_enabled(), 0u);
    hal_irq_restore(outer);
    EXPECT_NE(hal_irq_enabled(), 0u);
}

TEST_F(Harness, CriticalExitWithoutEnterFaults)
{
    EXPECT_DEATH(hal_critical_exit(), "FAULT 0x0101");
}

TEST_F(Harness, CriticalNestingTooDeepFaults)
{
    EXPECT_DEATH(
        {
            for (unsigned i = 0; i <= HAL_CRITICAL_MAX_DEPTH; i++)
                hal_critical_enter();
        },
        "FAULT 0x0102");
}

TEST_F(Harness, NonMaskableIgnoresGieButDoesNotNestIntoItself)
{
    static int nmi_board;
    static int depth, max_depth;
    depth = max_depth = 0;
    nmi_board = board;
    auto nmi = [](void *ctx) {
        depth++;
        max_depth = std::max(max_depth, depth);
        if (max_depth == 1 && posix_source_count(nmi_board, *static_cast<int *>(ctx)) == 1) {
            posix_source_raise(nmi_board, *static_cast<int *>(ctx)); // again, inside itself
            hal_preempt_point();
        }
        depth--;
    };
    static int id;
    id = posix_source_register(board, 15, 0, true, nmi, &id);
    posix_source_raise(board, id);
    hal_preempt_point(); // GIE clear, yet the NMI is taken
    EXPECT_EQ(max_depth, 1);
    // The NMI raised inside itself was held and runs right after the first returned.
    EXPECT_EQ(posix_source_count(board, id), 2u);
}

TEST_F(Harness, HandlerThatReenablesInterruptsCanBeNested)
{
    static int b;
    b = board;
    static int inner;
    inner = posix_source_register(board, 2, 0, false, log_isr, (void *)"inner");
    auto outer = [](void *) {
        g_log.push_back("outer-begin");
        hal_irq_enable(); // like EINT inside an ISR
        posix_source_raise(b, inner);
        hal_preempt_point();
        g_log.push_back("outer-end");
    };
    int o = posix_source_register(board, 7, 0, false, outer, nullptr);
    hal_irq_enable();
    posix_source_raise(board, o);
    posix_dispatch();
    EXPECT_EQ(g_log, (std::vector<std::string>{"outer-begin", "inner", "outer-end"}));
}

struct Ev {
    std::vector<std::pair<int, uint64_t>> *out;
    int tag;
};

void record_event(void *ctx, uint64_t t)
{
    auto *e = static_cast<Ev *>(ctx);
    e->out->push_back({e->tag, t});
}

TEST_F(Harness, EventsRunInTimeThenScheduleOrder)
{
    std::vector<std::pair<int, uint64_t>> seen;
    Ev e[5] = {{&seen, 0}, {&seen, 1}, {&seen, 2}, {&seen, 3}, {&seen, 4}};
    ASSERT_NE(posix_schedule(300, record_event, &e[0]), 0u);
    ASSERT_NE(posix_schedule(100, record_event, &e[1]), 0u);
    ASSERT_NE(posix_schedule(100, record_event, &e[2]), 0u);
    uint64_t cancelled = posix_schedule(200, record_event, &e[3]);
    ASSERT_NE(posix_schedule(300, record_event, &e[4]), 0u);
    EXPECT_TRUE(posix_cancel(cancelled));
    EXPECT_FALSE(posix_cancel(cancelled));
    EXPECT_EQ(posix_next_event_ns(), 100u);
    EXPECT_EQ(posix_run_until(250), 2u);
    EXPECT_EQ(posix_now_ns(), 250u);
    EXPECT_EQ(posix_schedule(249, record_event, &e[0]), 0u); // the past is refused
    EXPECT_EQ(posix_run_until(1000), 2u);
    EXPECT_EQ(seen,
              (std::vector<std::pair<int, uint64_t>>{{1, 100}, {2, 100}, {0, 300}, {4, 300}}));
    EXPECT_EQ(posix_next_event_ns(), UINT64_MAX);
}

TEST_F(Harness, QueueOrderHoldsForManyRandomEvents)
{
    std::vector<std::pair<int, uint64_t>> seen;
    std::vector<Ev> evs(2000);
    uint32_t x = 12345;
    for (int i = 0; i < 2000; i++) {
        x = x * 1103515245u + 12345u;
        evs[i] = {&seen, i};
        ASSERT_NE(posix_schedule((x >> 8) % 5000, record_event, &evs[i]), 0u);
    }
    posix_run_until(UINT64_MAX - 1);
    ASSERT_EQ(seen.size(), 2000u);
    for (size_t i = 1; i < seen.size(); i++) {
        bool ordered = seen[i - 1].second < seen[i].second ||
                       (seen[i - 1].second == seen[i].second && seen[i - 1].first < seen[i].first);
        ASSERT_TRUE(ordered) << "at " << i;
    }
}

void raise_line_event(void *ctx, uint64_t)
{
    posix_edge_raise(*static_cast<int *>(ctx), HAL_EDGE_DELTA_L);
}

struct Counter {
    int n = 0;
};

void count_cb(void *arg)
{
    static_cast<Counter *>(arg)->n++;
}

TEST_F(Harness, EdgeLinesUseThePinMapAndAreDeliveredAfterEvents)
{
    Counter c;
    ASSERT_EQ(hal_edge_init(HAL_EDGE_DELTA_L, HAL_EDGE_RISING, count_cb, &c), 0);
    EXPECT_EQ(hal_edge_init(HAL_EDGE_COUNT, HAL_EDGE_RISING, count_cb, &c), -1);
    EXPECT_EQ(hal_edge_init(HAL_EDGE_TEST, HAL_EDGE_RISING, nullptr, &c), -1);
    int s = posix_edge_source(board, HAL_EDGE_DELTA_L);
    ASSERT_GE(s, 0);
    EXPECT_EQ(posix_source_find(board, (int)hal_edge_vector(HAL_EDGE_DELTA_L),
                                (int)hal_edge_pin(HAL_EDGE_DELTA_L)),
              s);
    EXPECT_EQ(posix_edge_source(board, HAL_EDGE_GYRO_UP), -1);
    hal_irq_enable();
    for (int i = 1; i <= 10; i++)
        posix_schedule((uint64_t)i * 1000, raise_line_event, &board);
    posix_run_until(10000);
    EXPECT_EQ(c.n, 10);
    hal_edge_enable(HAL_EDGE_DELTA_L, 0);
    posix_edge_raise(board, HAL_EDGE_DELTA_L);
    posix_dispatch();
    EXPECT_EQ(c.n, 10);
    hal_edge_enable(HAL_EDGE_DELTA_L, 1);
    posix_dispatch();
    EXPECT_EQ(c.n, 11);
}

struct Cap {
    std::vector<std::pair<uint16_t, uint8_t>> got;
};

void cap_cb(void *arg, uint16_t count, uint8_t rising)
{
    static_cast<Cap *>(arg)->got.push_back({count, rising});
}

TEST_F(Harness, CaptureOverflowKeepsTheFirstAndCountsTheLost)
{
    Cap cap;
    ASSERT_EQ(hal_capture_init(HAL_CAPTURE_BEACON, cap_cb, &cap), 0);
    hal_irq_enable();
    hal_critical_enter();
    posix_capture_raise(board, HAL_CAPTURE_BEACON, 1000, 1);
    posix_capture_raise(board, HAL_CAPTURE_BEACON, 1010, 0);
    hal_critical_exit();
    ASSERT_EQ(cap.got.size(), 1u);
    EXPECT_EQ(cap.got[0], (std::pair<uint16_t, uint8_t>{1000, 1}));
    EXPECT_EQ(hal_capture_overflows(HAL_CAPTURE_BEACON), 1u);
    posix_capture_raise(board, HAL_CAPTURE_BEACON, 1020, 0);
    posix_dispatch();
    EXPECT_EQ(cap.got.back(), (std::pair<uint16_t, uint8_t>{1020, 0}));
}

TEST_F(Harness, PreemptHookCanLandAnInterruptAtEveryPoint)
{
    // A writer updates two words with a preemption point between them; a reader interrupt
    // landing there would see them torn unless the writer protects the pair.
    static uint16_t a, b;
    static int torn;
    static int reader_source;
    static uint64_t target_point;
    auto reader = [](void *) {
        if (a != b)
            torn++;
    };
    auto hook = [](void *, int bd, uint64_t point) {
        if (point == target_point)
            posix_source_raise(bd, reader_source);
    };
    reader_source = posix_source_register(board, 15, 0, true, reader, nullptr);
    posix_set_preempt_hook(hook, nullptr);
    for (int protect = 0; protect < 2; protect++) {
        torn = 0;
        for (uint64_t k = 1; k <= 3; k++) {
            target_point = posix_preempt_points(board) + k;
            if (protect)
                hal_critical_enter();
            a++;
            hal_preempt_point();
            b++;
            hal_preempt_point();
            if (protect)
                hal_critical_exit();
            hal_preempt_point();
        }
        // An NMI ignores critical sections, so "protect" does not help against it: the
        // reader sees the torn pair once in both rounds (k = 1 lands between the writes).
        EXPECT_EQ(torn, 1) << "protect=" << protect;
    }
    posix_set_preempt_hook(nullptr, nullptr);
}

TEST_F(Harness, WakeIsTakenOnce)
{
    EXPECT_FALSE(posix_board_take_wake(board));
    hal_cpu_wake();
    EXPECT_TRUE(posix_board_take_wake(board));
    EXPECT_FALSE(posix_board_take_wake(board));
}

TEST_F(Harness, ClockTicksEveryMillisecondOnItsBoardAndWakesIt)
{
    hal_clock_init();
    hal_irq_enable();
    EXPECT_EQ(hal_clock_ms(), 0u);
    posix_run_until(999999);
    EXPECT_EQ(hal_clock_ms(), 0u);
    posix_run_until(1000000);
    EXPECT_EQ(hal_clock_ms(), 1u);
    EXPECT_TRUE(posix_board_take_wake(board));
    posix_run_until(250000000);
    EXPECT_EQ(hal_clock_ms(), 250u);
    int other = posix_board_create("other");
    posix_board_select(other);
    EXPECT_EQ(hal_clock_ms(), 0u); // not started there
}

TEST_F(Harness, TicklessClockWakesOnlyAtTheDeadlinesAndCountsTheSame)
{
    posix_reset();
    posix_clock_set_tickless(true);
    board = posix_board_create("test");
    posix_board_select(board);
    hal_clock_init();
    hal_irq_enable();
    EXPECT_EQ(posix_next_event_ns(), UINT64_MAX) << "no tick queued without a deadline";
    posix_run_until(7'300'000); // 7.3 ms
    EXPECT_EQ(hal_clock_ms(), 7u) << "the count is the time";
    EXPECT_EQ(posix_clock_ticks(board), 7u);
    EXPECT_FALSE(posix_board_take_wake(board));
    hal_clock_wake_at(20);
    hal_clock_wake_at(12); // the earlier one wins
    hal_clock_wake_at(30);
    EXPECT_EQ(posix_next_event_ns(), 12'000'000u);
    posix_run_until(11'999'999);
    EXPECT_FALSE(posix_board_take_wake(board));
    posix_run_until(12'000'000);
    EXPECT_TRUE(posix_board_take_wake(board)) << "woken at the boundary of millisecond 12";
    EXPECT_EQ(hal_clock_ms(), 12u);
    hal_clock_wake_at(5); // past: the next millisecond
    EXPECT_EQ(posix_next_event_ns(), 13'000'000u);
    posix_run_until(13'000'000);
    EXPECT_TRUE(posix_board_take_wake(board));
    EXPECT_EQ(posix_next_event_ns(), UINT64_MAX) << "a deadline wakes once";
}

// A source on @p board (vector 2, bit 0) whose handler notes the instant it runs at.
std::vector<uint64_t> g_isr_at;
int instant_recorder(int board)
{
    g_isr_at.clear();
    return posix_source_register(
        board, 2, 0, false, [](void *) { g_isr_at.push_back(posix_now_ns()); }, nullptr);
}

// A pulse train: from its handler, each next pulse comes by posix_advance() while no event
// is queued before it and nothing ended the instant; otherwise it is scheduled. Either way
// the handler sees the same instants, and an event between two pulses runs between them.
struct Train {
    int board, source;
    uint64_t period, last;
    std::vector<uint64_t> *seen;
    int advanced;
};

void train_pulse(void *ctx, uint64_t t)
{
    auto *tr = static_cast<Train *>(ctx);
    for (;;) {
        tr->seen->push_back(t);
        posix_source_raise(tr->board, tr->source);
        uint64_t next = t + tr->period;
        if (next > tr->last)
            return;
        if (!posix_advance(next)) {
            posix_schedule(next, train_pulse, tr);
            return;
        }
        EXPECT_EQ(posix_now_ns(), next);
        tr->advanced++;
        t = next;
    }
}

TEST_F(Harness, PulseTrainAdvancesOnlyWhileNothingComesBetween)
{
    std::vector<uint64_t> &isr_at = g_isr_at;
    int src = instant_recorder(board);
    ASSERT_GE(src, 0);
    posix_source_enable(board, src, true);
    hal_irq_enable();
    std::vector<uint64_t> seen;
    Train tr{board, src, 100, 1000, &seen, 0};
    std::vector<std::pair<int, uint64_t>> events;
    Ev between{&events, 7};
    posix_schedule(100, train_pulse, &tr);
    posix_schedule(450, record_event, &between);
    EXPECT_FALSE(posix_advance(200)) << "refused outside posix_run_steps()";
    posix_run_steps(UINT64_MAX, -1);
    std::vector<uint64_t> all = {100, 200, 300, 400, 500, 600, 700, 800, 900, 1000};
    EXPECT_EQ(seen, all);
    EXPECT_EQ(isr_at, all) << "each pulse's handler ran at its own instant";
    EXPECT_EQ(events, (std::vector<std::pair<int, uint64_t>>{{7, 450}}));
    EXPECT_EQ(tr.advanced, 8) << "every pulse but the first and the one after the event";
    // A board woken ends the run of instants: the pulse after it is queued, not advanced.
    posix_reset();
    board = posix_board_create("test");
    src = posix_source_register(
        board, 2, 0, false, [](void *) { hal_cpu_wake(); }, nullptr);
    posix_source_enable(board, src, true);
    posix_board_select(board);
    hal_irq_enable();
    seen.clear();
    tr = Train{board, src, 100, 300, &seen, 0};
    posix_schedule(100, train_pulse, &tr);
    posix_run_steps(UINT64_MAX, -1);
    EXPECT_EQ(seen, (std::vector<uint64_t>{100})) << "the run stops after the woken instant";
    EXPECT_EQ(posix_next_event_ns(), 200u);
    EXPECT_EQ(tr.advanced, 0);
}

// posix_advance_raise(): the train's next pulse raised and taken at its own instant, as an
// event's would be; held pending while interrupts are off, delivered when they come back.
struct RaisingTrain {
    int board, source;
    uint64_t period, last;
    std::vector<uint64_t> *seen;
};

void raising_pulse(void *ctx, uint64_t t)
{
    auto *tr = static_cast<RaisingTrain *>(ctx);
    tr->seen->push_back(t);
    posix_source_raise(tr->board, tr->source);
    for (uint64_t next = t + tr->period; next <= tr->last; next += tr->period) {
        if (!posix_advance_raise(next, tr->board, tr->source)) {
            posix_schedule(next, raising_pulse, tr);
            return;
        }
        tr->seen->push_back(next);
    }
}

TEST_F(Harness, AdvanceRaiseDeliversEachPulseAtItsInstant)
{
    std::vector<uint64_t> &isr_at = g_isr_at;
    int src = instant_recorder(board);
    ASSERT_GE(src, 0);
    hal_irq_enable();
    std::vector<uint64_t> seen;
    RaisingTrain tr{board, src, 100, 600, &seen};
    std::vector<std::pair<int, uint64_t>> events;
    Ev between{&events, 7};
    posix_schedule(100, raising_pulse, &tr);
    posix_schedule(350, record_event, &between);
    posix_run_steps(UINT64_MAX, -1);
    std::vector<uint64_t> all = {100, 200, 300, 400, 500, 600};
    EXPECT_EQ(seen, all);
    EXPECT_EQ(isr_at, all);
    EXPECT_EQ(posix_source_count(board, src), 6u);
    EXPECT_EQ(events, (std::vector<std::pair<int, uint64_t>>{{7, 350}}));
    // Interrupts off: the pulse stays pending (a second one merges into the same flag) and
    // is taken when they come back on.
    isr_at.clear();
    hal_irq_disable();
    seen.clear();
    tr = RaisingTrain{board, src, 100, 900, &seen};
    posix_schedule(700, raising_pulse, &tr);
    posix_run_steps(UINT64_MAX, -1);
    EXPECT_EQ(seen, (std::vector<uint64_t>{700, 800, 900}));
    EXPECT_TRUE(isr_at.empty());
    EXPECT_TRUE(posix_source_pending(board, src));
    hal_irq_enable();
    EXPECT_EQ(isr_at, (std::vector<uint64_t>{900}));
    EXPECT_FALSE(posix_advance_raise(1000, board, src)) << "outside posix_run_steps()";
}

TEST_F(Harness, SignalPulseReachesTheWiredLineOfTheOtherBoard)
{
    int nav = posix_board_create("nav");
    static int requests;
    requests = 0;
    posix_board_select(nav);
    ASSERT_EQ(hal_edge_init(
                  HAL_EDGE_COORD_REQUEST, HAL_EDGE_FALLING, [](void *) { requests++; }, nullptr),
              0);
    posix_board_select(board);
    hal_signal_init(HAL_SIGNAL_COORD_REQUEST);
    hal_signal_pulse(HAL_SIGNAL_COORD_REQUEST); // not wired yet: nothing
    posix_dispatch();
    EXPECT_EQ(requests, 0);
    posix_signal_connect(board, HAL_SIGNAL_COORD_REQUEST, nav, HAL_EDGE_COORD_REQUEST);
    hal_signal_pulse(HAL_SIGNAL_COORD_REQUEST);
    posix_dispatch(); // non-maskable: taken although the nav board never enabled interrupts
    EXPECT_EQ(requests, 1);
}

} // namespace
