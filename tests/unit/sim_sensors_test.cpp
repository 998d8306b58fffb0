// sim/sensors: odometer pulses every dl of front-wheel travel and gyro steps at each step
// boundary of the measured heading, counted on a nav board of the harness against the
// closed-form travel and turn.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

extern "C" {
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal_posix/harness.h"
#include "sim/motion.h"
#include "sim/scenario.h"
#include "sim/sensors.h"
}

namespace
{

int g_dl, g_up, g_down;
void on_dl(void *)
{
    g_dl++;
}
void on_up(void *)
{
    g_up++;
}
void on_down(void *)
{
    g_down++;
}

struct Bench {
    int main_b, nav_b;
    sim_scenario_t sc;
    sim_segment_t seg;
    sim_sensors_t s;
    Bench(double alpha, double v, double drift_deg_per_s)
    {
        posix_reset();
        main_b = posix_board_create("main");
        nav_b = posix_board_create("nav");
        posix_board_select(nav_b);
        hal_edge_init(HAL_EDGE_DELTA_L, HAL_EDGE_RISING, on_dl, nullptr);
        hal_edge_init(HAL_EDGE_GYRO_UP, HAL_EDGE_RISING, on_up, nullptr);
        hal_edge_init(HAL_EDGE_GYRO_DOWN, HAL_EDGE_RISING, on_down, nullptr);
        hal_irq_enable();
        g_dl = g_up = g_down = 0;
        std::memset(&sc, 0, sizeof sc);
        sc.dl = 0.000254;
        sc.odo_scale = 1.0;
        sc.gyro_step = 0.25 * M_PI / 180;
        sc.gyro_drift = drift_deg_per_s * M_PI / 180;
        sc.start_heading = 0.3;
        sc.rev_per_s = 2;
        sc.counts = 50000;
        sc.gonio_range = 60;
        seg = sim_segment(0.0, {0.0, 0.0, 0.3}, 0.0, alpha, v, 0.75);
        sim_sensors_init(&s, &sc, &seg, main_b, nav_b);
        sim_sensors_motion(&s);
    }
};

TEST(Sensors, OdometerPulsesEveryDlOfFrontWheelTravel)
{
    Bench b(0.4, 1.0, 0.0);
    posix_run_until(2'000'000'000ull); // 2 s
    double front = 2.0 / std::cos(0.4);
    EXPECT_EQ(g_dl, (int)std::floor(front / 0.000254));
}

TEST(Sensors, GyroStepsAtEachBoundaryOfTheMeasuredHeading)
{
    // Turning left at v tan(alpha) / L rad/s, plus a drift of 0.5 deg/s.
    Bench b(0.3, 0.8, 0.5);
    posix_run_until(3'000'000'000ull);
    double turn = 0.8 * std::tan(0.3) / 0.75 * 3.0 + 0.5 * M_PI / 180 * 3.0;
    double step = 0.25 * M_PI / 180;
    // Step c covers (c -+ 1/2) steps around the start heading.
    EXPECT_EQ(g_up, (int)std::floor(turn / step + 0.5));
    EXPECT_EQ(g_down, 0);
    // A right turn counts down.
    Bench r(-0.3, 0.8, 0.0);
    posix_run_until(1'000'000'000ull);
    EXPECT_EQ(g_down, (int)std::floor(0.8 * std::tan(0.3) / 0.75 / step + 0.5));
    EXPECT_EQ(g_up, 0);
}

TEST(Sensors, LatchesAreRememberedWhileRecent)
{
    Bench b(0.0, 0.0, 0.0);
    double t;
    sim_pose_t p;
    EXPECT_EQ(sim_sensors_latch(&b.s, 0, &t, &p), -1); // no rising edge yet
    b.s.rises = 300;
    b.s.rise_t[299 % SIM_SENSORS_LATCHES] = 1.5;
    EXPECT_EQ(sim_sensors_latch(&b.s, 299, &t, &p), 0);
    EXPECT_EQ(t, 1.5);
    EXPECT_EQ(sim_sensors_latch(&b.s, 300 - SIM_SENSORS_LATCHES, &t, &p), 0);
    EXPECT_EQ(sim_sensors_latch(&b.s, 299 - SIM_SENSORS_LATCHES, &t, &p), -1); // too old
    EXPECT_EQ(sim_sensors_latch(&b.s, 300, &t, &p), -1);                       // not yet
    // The nav board counts latches on 16 bits: rise 65536 + 5 is latch 5.
    b.s.rises = 65536 + 6;
    b.s.rise_t[5] = 2.5;
    EXPECT_EQ(sim_sensors_latch(&b.s, 5, &t, &p), 0);
    EXPECT_EQ(t, 2.5);
}

} // namespace
