// sim/drive_board: the drive board fed the 8255 writes the firmware's port code makes
// (drive_ppi_*): it drives each arc for its length at its speed in the seed's units
// (4.4 counts per inch of front wheel, 1.755 cm/s per speed count), raises delta-S 2 cm
// before an arc's end, stops after the double arc, and brakes at 0.5 m/s^2; fed seed 002's
// DAC style (drive_dac_*), it steers and drives at once (the wheel within the vehicle's range),
// only with the drive motor enabled and the brake released.
#include <gtest/gtest.h>

#include <cmath>

extern "C" {
#include "drive/drive_cmd.h"
#include "drive/drive_proto.h"
#include "fx/fx_host.h"
#include "hal/irq.h"
#include "hal/pinmap.h"
#include "hal_posix/harness.h"
#include "sim/drive_board.h"
}

namespace
{

int g_motions;
void on_motion(void *, double)
{
    g_motions++;
}

int g_pulses;
double g_pulse_t[8];
void on_delta_s(void *)
{
    g_pulse_t[g_pulses++ % 8] = posix_now_ns() * 1e-9;
}

struct Bench {
    int board;
    sim_drive_t d;
    Bench()
    {
        posix_reset();
        board = posix_board_create("main");
        posix_board_select(board);
        hal_edge_init(HAL_EDGE_DELTA_S, HAL_EDGE_RISING, on_delta_s, nullptr);
        hal_irq_enable();
        drive_board_t units = DRIVE_BOARD_SEED;
        sim_drive_init(&d, &units, 0.762, board, {0.0, 0.0, 0.0}, on_motion, nullptr, nullptr);
        g_motions = g_pulses = 0;
        drive_wseq_t s;
        drive_ppi_init(&s);
        send(s);
    }
    void send(const drive_wseq_t &s)
    {
        for (int i = 0; i < s.n; i++)
            sim_drive_write(&d, s.w[i].reg, s.w[i].value);
    }
    void run_until(double t)
    {
        posix_run_until((uint64_t)(t * 1e9));
    }
};

const double kCountsPerM = 4.4 / 0.0254;     // the seed's length unit
const double kSpeedLsb = 1150.0 / 65536.0;   // 1.755 cm/s as the board's Q16 value
const double kCpmQ16 = 11352693.0 / 65536.0; // 173.2283 counts/m as its Q16 value

TEST(DriveBoard, DrivesTwoStraightArcsAndStops)
{
    Bench b;
    drive_cmd_t cmd = {};
    cmd.steer[0] = cmd.steer[1] = DRIVE_STEER_STRAIGHT;
    cmd.arc[0] = 100;
    cmd.arc[1] = 60;
    cmd.speed = 57; // ~1 m/s
    drive_wseq_t s;
    drive_ppi_load(&cmd, &s);
    b.send(s);
    EXPECT_EQ(g_motions, 1);
    double v = 57 * kSpeedLsb, len = 160 / kCpmQ16;
    EXPECT_NEAR(std::fabs(len - 160 / kCountsPerM), 0.0, 1e-6); // the Q16 unit is the seed's
    b.run_until(len / v + 0.5);
    sim_pose_t p = sim_drive_pose(&b.d, len / v + 0.5);
    EXPECT_NEAR(p.x, len, 1e-9);
    EXPECT_NEAR(p.y, 0.0, 1e-12);
    EXPECT_TRUE(sim_drive_standing(&b.d));
    // One delta-S per arc, 2 cm before each arc's end.
    ASSERT_EQ(g_pulses, 2);
    EXPECT_NEAR(g_pulse_t[0], (100 / kCpmQ16 - 0.02) / v, 1e-8);
    EXPECT_NEAR(g_pulse_t[1], (len - 0.02) / v, 1e-8);
}

TEST(DriveBoard, ArcFollowsItsCircleAndShortArcsGiveNoPulse)
{
    Bench b;
    drive_cmd_t cmd = {};
    cmd.steer[0] = 128 - 32; // 22.5 degrees left
    cmd.arc[0] = 120;
    cmd.steer[1] = DRIVE_STEER_STRAIGHT;
    cmd.arc[1] = 2; // below the 3 counts of a clean pulse
    cmd.speed = 30;
    drive_wseq_t s;
    drive_ppi_load(&cmd, &s);
    b.send(s);
    double v = 30 * kSpeedLsb, alpha = 22.5 * M_PI / 180, L = 0.762;
    double k = std::tan(alpha) / L;
    double rear = 120 / kCpmQ16 * std::cos(alpha); // front-wheel length to rear-axle length
    double t_end = (rear + 2 / kCpmQ16) / v;
    b.run_until(t_end + 0.2);
    // Exact geometry: a circle of radius 1/k from (0, 0) heading east, then a short straight.
    double th = k * rear;
    double x = std::sin(th) / k + 2 / kCpmQ16 * std::cos(th);
    double y = (1 - std::cos(th)) / k + 2 / kCpmQ16 * std::sin(th);
    sim_pose_t p = sim_drive_pose(&b.d, t_end + 0.2);
    EXPECT_NEAR(p.x, x, 1e-9);
    EXPECT_NEAR(p.y, y, 1e-9);
    EXPECT_NEAR(p.th, th, 1e-9);
    EXPECT_EQ(g_pulses, 1); // only the first arc raises delta-S
}

TEST(DriveBoard, SpeedZeroBrakesAtHalfAMetrePerSecondSquared)
{
    Bench b;
    drive_cmd_t cmd = {};
    cmd.steer[0] = cmd.steer[1] = DRIVE_STEER_STRAIGHT;
    cmd.arc[0] = cmd.arc[1] = 250;
    cmd.speed = 30; // 0.53 m/s: the stop comes within the first arc
    drive_wseq_t s;
    drive_ppi_load(&cmd, &s);
    b.send(s);
    b.run_until(0.5);
    drive_ppi_speed(0, &s);
    b.send(s);
    double v = 30 * kSpeedLsb;
    b.run_until(0.5 + v / 0.5 + 0.05);
    EXPECT_TRUE(sim_drive_standing(&b.d));
    // Travel: 0.5 s at v, then a steady ramp down at 0.5 m/s^2: v^2 / (2 x 0.5) more.
    double dist = 0.5 * v + v * v / (2 * 0.5);
    sim_pose_t p = sim_drive_pose(&b.d, 0.5 + v / 0.5 + 0.05);
    EXPECT_NEAR(p.x, dist, 1e-6);
}

TEST(DriveBoard, DacStyleSteersAndDrivesAtOnce)
{
    Bench b;
    drive_wseq_t s;
    drive_dac_start(132, &s); // seed 002's Init_AGV: motors on, brake released
    b.send(s);
    // 20 degrees left: 132 - 20/90 x 123 = 104.7 -> 105; 57 counts: 1.0 m/s
    uint8_t angle = drive_dac_angle_byte(fx_angle_from_deg(20.0), 132);
    EXPECT_EQ(angle, 105);
    drive_dac_set(angle, drive_dac_speed_byte(57), &s);
    b.send(s);
    double alpha = (132.0 - 105.0) / 123.0 * M_PI / 2, v = 57 * kSpeedLsb, L = 0.762;
    EXPECT_NEAR(b.d.alpha, alpha, 1e-9);
    b.run_until(2.0);
    // a circle of radius L / tan(alpha) from (0, 0) heading east, for 2 s
    double k = std::tan(alpha) / L, th = k * v * 2.0;
    sim_pose_t p = sim_drive_pose(&b.d, 2.0);
    EXPECT_NEAR(p.x, std::sin(th) / k, 1e-9);
    EXPECT_NEAR(p.y, (1 - std::cos(th)) / k, 1e-9);
    EXPECT_NEAR(p.th, th, 1e-9);
    // beyond the vehicle's steering range (atan(L / r_min), r_min 10 in): held at the limit
    drive_dac_set(drive_dac_angle_byte(fx_angle_from_deg(-85.0), 132), drive_dac_speed_byte(57),
                  &s);
    b.send(s);
    EXPECT_NEAR(b.d.alpha, -std::atan(0.762 / 0.254), 1e-4);
    // the brake: the board brakes to a stop at 0.5 m/s^2 whatever the speed DAC says
    drive_dac_outputs(DRIVE_OUT_DRIVE_OFF | DRIVE_OUT_STEER_OFF, &s);
    b.send(s);
    b.run_until(2.0 + v / 0.5 + 0.05);
    EXPECT_TRUE(sim_drive_standing(&b.d));
    drive_dac_outputs(DRIVE_OUT_BRAKE_REL, &s);
    b.send(s);
    EXPECT_NEAR(b.d.v, v, 1e-12) << "released: on at the speed DAC's speed";
    drive_dac_stop(132, &s); // seed 002's End_Path
    b.send(s);
    b.run_until(10.0);
    EXPECT_TRUE(sim_drive_standing(&b.d));
    EXPECT_EQ(b.d.alpha, 0.0);
}

} // namespace
