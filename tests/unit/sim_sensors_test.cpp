// sim/sensors: odometer pulses every dl of front-wheel travel and gyro steps at each step
// boundary of the measured heading, counted on a nav board of the harness against the
// closed-form travel and turn; the disturbances: odometer glitches and lost index pulses
// (binomial counts), photodetector dropout windows (no edge inside), the truth of which
// beacons lit a revolution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

extern "C" {
#include "hal/capture.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal_posix/harness.h"
#include "sim/motion.h"
#include "sim/scenario.h"
#include "sim/sensors.h"
}

namespace
{

int g_dl, g_up, g_down, g_index;
std::vector<double> g_edges; // beacon capture times, s
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
void on_index(void *, uint16_t, uint8_t)
{
    g_index++;
}
void on_edge(void *, uint16_t, uint8_t)
{
    g_edges.push_back(posix_now_ns() * 1e-9);
}

struct Bench {
    int main_b, nav_b;
    sim_scenario_t sc;
    sim_segment_t seg;
    sim_sensors_t s;
    Bench(double alpha, double v, double drift_deg_per_s,
          void (*disturb)(sim_scenario_t *) = nullptr)
    {
        posix_reset();
        main_b = posix_board_create("main");
        nav_b = posix_board_create("nav");
        posix_board_select(nav_b);
        hal_edge_init(HAL_EDGE_DELTA_L, HAL_EDGE_RISING, on_dl, nullptr);
        hal_edge_init(HAL_EDGE_GYRO_UP, HAL_EDGE_RISING, on_up, nullptr);
        hal_edge_init(HAL_EDGE_GYRO_DOWN, HAL_EDGE_RISING, on_down, nullptr);
        hal_irq_enable();
        posix_board_select(main_b);
        hal_capture_init(HAL_CAPTURE_INDEX, on_index, nullptr);
        hal_capture_init(HAL_CAPTURE_BEACON, on_edge, nullptr);
        hal_irq_enable();
        g_dl = g_up = g_down = g_index = 0;
        g_edges.clear();
        std::memset(&sc, 0, sizeof sc);
        sc.dl = 0.000254;
        sc.odo_scale = 1.0;
        sc.gyro_step = 0.25 * M_PI / 180;
        sc.gyro_drift = drift_deg_per_s * M_PI / 180;
        sc.start_heading = 0.3;
        sc.rev_per_s = 2;
        sc.counts = 50000;
        sc.gonio_range = 60;
        sc.seed = 3;
        sc.world.n_beacons = 1;
        sc.world.beacon[0] = {5.0, 1.0, 0.1, SIM_BEACON_KIND_CYLINDER};
        if (disturb)
            disturb(&sc);
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

// Braking on a curve: the heading moves kappa v^2 / (2 decel) in all, then only the drift
// moves it; the odometer counts the front wheel's v^2 / (2 decel cos alpha).
TEST(Sensors, GyroAndOdometerFollowABrakingCurve)
{
    for (double alpha : {0.3, -0.3}) {
        for (double drift : {0.0, 0.5, -0.5}) {
            Bench b(alpha, 0.8, drift);
            b.seg.decel = 0.5;
            sim_sensors_motion(&b.s);
            posix_run_until(3'000'000'000ull); // stops at 1.6 s, then stands
            double kappa = std::tan(alpha) / 0.75, travel = 0.8 * 0.8 / (2 * 0.5);
            double turn = kappa * travel + drift * M_PI / 180 * 3.0;
            double step = 0.25 * M_PI / 180;
            // Net, the measured heading passes turn / step boundaries; one way only unless the
            // drift turns it back once the vehicle slows.
            EXPECT_EQ(g_up - g_down, (int)std::floor(turn / step + 0.5)) << alpha << " " << drift;
            if (kappa * drift >= 0) {
                EXPECT_EQ(std::min(g_up, g_down), 0) << alpha << " " << drift;
            }
            EXPECT_EQ(g_dl, (int)std::floor(travel / std::cos(alpha) / 0.000254));
        }
    }
}

// Glitches: every pulse lost with probability `missed`, or followed by an extra one with
// probability `extra`; the handler sees what is left.
TEST(Sensors, OdometerGlitchesLoseAndAddPulses)
{
    Bench b(0.0, 1.0, 0.0, [](sim_scenario_t *sc) {
        sc->odo_missed = 0.01;
        sc->odo_extra = 0.02;
    });
    posix_run_until(2'000'000'000ull);
    int n = (int)std::floor(2.0 / 0.000254); // pulses of the wheel
    EXPECT_EQ(g_dl, n - (int)b.s.odo_missed + (int)b.s.odo_extra);
    double m = n * 0.01, sm = std::sqrt(n * 0.01 * 0.99);
    double k = (n - m) * 0.02, sk = std::sqrt((n - m) * 0.02 * 0.98);
    EXPECT_LT(std::fabs(b.s.odo_missed - m), 5 * sm) << b.s.odo_missed;
    EXPECT_LT(std::fabs(b.s.odo_extra - k), 5 * sk) << b.s.odo_extra;
}

TEST(Sensors, IndexPulsesAreLostWithTheirProbability)
{
    Bench b(0.0, 0.0, 0.0, [](sim_scenario_t *sc) { sc->index_loss = 0.25; });
    posix_run_until(100'000'000'000ull); // 200 mirror turns
    int turns = g_index + (int)b.s.index_lost;
    EXPECT_GE(turns, 199);
    EXPECT_LE(turns, 200);
    double sd = std::sqrt(turns * 0.25 * 0.75);
    EXPECT_LT(std::fabs(b.s.index_lost - turns * 0.25), 5 * sd) << b.s.index_lost;
}

// Blinded from 1 s to 3 s: the beacon's pulse (two edges a turn) is not seen in the window.
TEST(Sensors, DropoutWindowsBlindThePhotodetector)
{
    Bench b(0.0, 0.0, 0.0, [](sim_scenario_t *sc) {
        sc->n_dropouts = 1;
        sc->dropout[0] = {1.0, 2.0};
    });
    posix_run_until(5'000'000'000ull);
    int before = 0, after = 0;
    for (double t : g_edges) {
        EXPECT_FALSE(t >= 1.0 && t < 3.0) << t;
        before += t < 1.0;
        after += t >= 3.0;
    }
    EXPECT_GE(before, 2 * 1);
    EXPECT_GE(after, 2 * 3);
    EXPECT_EQ(before % 2, 0); // whole pulses
}

TEST(Sensors, BeaconsCountTheDistinctBeaconsOfTheLatches)
{
    Bench b(0.0, 0.0, 0.0);
    const int16_t targets[] = {0, 1, 1, -1, 2, 5};
    b.s.rises = 6;
    for (int i = 0; i < 6; i++)
        b.s.rise_target[i] = targets[i];
    EXPECT_EQ(sim_sensors_beacons(&b.s, 5, 6), 4); // 0, 1, 2, 5; the glint is none
    EXPECT_EQ(sim_sensors_beacons(&b.s, 4, 3), 2); // latches 2..4: 1, glint, 2
    EXPECT_EQ(sim_sensors_beacons(&b.s, 1, 4), 2); // latches 0, 1 only: older ones unknown
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
