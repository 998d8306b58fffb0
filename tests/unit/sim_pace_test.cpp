// sim/pace: live runs wait for the wall clock (never less than the simulated time divided by
// the factor), never when not paced, and refuse factors out of range. Only lower bounds of
// the wall time are asserted: a loaded machine may always be slower.
#include <gtest/gtest.h>

#include <cmath>
#include <ctime>

extern "C" {
#include "sim/pace.h"
}

namespace
{

double wall_now()
{
    timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

// Walk simulated time from t0 to t0 + span in steps of step_ns, pacing each step.
double paced_walk(double factor, uint64_t t0, uint64_t span, uint64_t step_ns, sim_pace_t *p)
{
    EXPECT_EQ(sim_pace_start(p, factor, t0), 0);
    double w0 = wall_now();
    for (uint64_t t = t0; t <= t0 + span; t += step_ns)
        sim_pace_wait(p, t);
    return wall_now() - w0;
}

TEST(Pace, TakesAtLeastTheSimulatedTimeOverTheFactor)
{
    sim_pace_t p;
    // 0.2 s simulated at 4x: at least 50 ms of wall time, from any simulated start.
    double w = paced_walk(4.0, 123456789, 200000000, 100000, &p);
    EXPECT_GE(w, 0.2 / 4.0 - 1e-3) << "the last instant waited for";
    EXPECT_GT(p.sleeps, 0u);
    // At 1x, 30 ms simulated in 1 ms steps: at least 29 ms.
    w = paced_walk(1.0, 0, 30000000, 1000000, &p);
    EXPECT_GE(w, 0.029);
}

TEST(Pace, NotPacedNeverWaits)
{
    sim_pace_t p;
    ASSERT_EQ(sim_pace_start(&p, 0.0, 0), 0);
    for (uint64_t t = 0; t <= 3600ull * 1000000000ull; t += 1000000000ull)
        sim_pace_wait(&p, t); // an hour of simulated time
    EXPECT_EQ(p.sleeps, 0u);
}

TEST(Pace, BehindTheWallClockGoesOnAtOnce)
{
    sim_pace_t p;
    ASSERT_EQ(sim_pace_start(&p, 1000.0, 0), 0);
    timespec ts = {0, 20000000}; // 20 ms of wall = 20 s simulated at 1000x
    nanosleep(&ts, nullptr);
    sim_pace_wait(&p, 10000000000ull); // 10 s simulated: already past
    EXPECT_EQ(p.sleeps, 0u);
}

TEST(Pace, FactorsOutOfRangeAreRefused)
{
    sim_pace_t p;
    for (double f : {-1.0, std::nan(""), (double)INFINITY, SIM_PACE_MAX_FACTOR * 2}) {
        EXPECT_EQ(sim_pace_start(&p, f, 0), -1) << f;
        EXPECT_EQ(p.factor, 0.0) << "left unpaced";
    }
    EXPECT_EQ(sim_pace_start(&p, SIM_PACE_MAX_FACTOR, 0), 0);
}

} // namespace
