// sim/mission: a scenario turned into the boards' download: the values the seed and the
// mission header document, the start in the firmware's formats, a nominal path that is a
// connected chain of arcs through every prescribed pose, and refusals naming key and value;
// pursuit mode's download (seed 002's parameters in the firmware's formats) and its refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

extern "C" {
#include "sim/mission.h"
#include "sim/scenario.h"
}

namespace
{

const char *kScenario = R"({
 "name": "unit", "mode": "simplified",
 "beacons": [{"x":0,"y":0,"diameter_m":0.1},{"x":10,"y":0,"diameter_m":0.15,"kind":"flat"},
             {"x":10,"y":10,"diameter_m":0.05,"kind":"cylinder"}],
 "vehicle": {"wheelbase_m":0.762,"min_radius_m":0.5,"speed_mps":1.0},
 "start": {"x":1,"y":1,"heading_deg":90},
 "start_error": {"x":0.01,"heading_deg":-1},
 "path": [{"x":1,"y":4,"heading_deg":90},{"x":3,"y":6,"heading_deg":0,"speed_mps":0.5},
          {"x":6,"y":6,"heading_deg":0}],
 "sensors": {"goniometer":{"rev_per_s":2,"counts":50000,"noise_deg":0},
             "odometer":{"dl_m":0.000254},"gyro":{"step_deg":0.25,"drift_deg_per_s":0}},
 "seed": 7, "duration_s": 20, "blind_distance_m": 6.5})";

long q16(double v)
{
    return std::lround(v * 65536.0);
}

TEST(Mission, DownloadHoldsTheScenarioInTheFirmwaresFormats)
{
    static sim_scenario_t sc;
    static sim_mission_t m;
    char err[256];
    ASSERT_EQ(sim_scenario_parse(kScenario, &sc, err, sizeof err), 0) << err;
    ASSERT_EQ(sim_mission_build(&m, &sc, err, sizeof err), 0) << err;
    const main_board_config_t &mc = m.main;
    EXPECT_EQ(mc.n_path, 3);
    EXPECT_EQ(mc.start.x, q16(1.0));
    EXPECT_EQ(mc.start.heading, 0x40000000u); // 90 degrees of 2^32
    EXPECT_EQ(mc.path[1].speed, q16(0.5));
    EXPECT_EQ(mc.path[2].speed, q16(1.0)); // no speed: the vehicle's
    EXPECT_EQ(mc.board.wheelbase, q16(0.762));
    // Every beacon its own reflector, compiled: floor(d 10430 / 2^8) for d in Q16 m (2^8 2^16 /
    // 2 pi per metre), the flat strip flagged; the narrowest for O4.
    ASSERT_EQ(mc.map.n, 3);
    auto dk = [](double d) { return (uint32_t)((uint64_t)q16(d) * 10430u >> 8); };
    EXPECT_EQ(mc.map.dk[0], dk(0.1));
    EXPECT_EQ(mc.map.dk[1], dk(0.15) | OPTICAL_DK_FLAT);
    EXPECT_EQ(mc.map.dk[2], dk(0.05));
    EXPECT_EQ(mc.map.dkmin, dk(0.05));
    EXPECT_EQ(dk(0.1), 267024u); // 0.1 m 2^24 / (2 pi) = 267,018; 0.1 m in Q16 is 6554 / 65536
    EXPECT_EQ(mc.counts_per_turn, 50000);
    EXPECT_EQ(mc.seq_cfg.mode, DRIVE_MODE_SIMPLIFIED);
    // The mission's fixed part (mission/mission.h, the seed's values).
    EXPECT_EQ(mc.path_cfg.spacing, q16(0.8));
    EXPECT_EQ(mc.path_cfg.nominal_radius, q16(0.5));
    EXPECT_EQ(mc.seq_cfg.load_ms, 35);
    EXPECT_EQ(mc.seq_cfg.settle_ms, 50);
    EXPECT_EQ(mc.seq_cfg.stop_speed, q16(0.15));
    EXPECT_EQ(mc.seq_cfg.advance, q16(0.4));
    EXPECT_EQ(mc.seq_cfg.max_fix_failures, 3);
    // The blind distance: one value for both boards.
    EXPECT_EQ(mc.seq_cfg.blind_distance, q16(6.5));
    EXPECT_EQ(m.nav.gnav.stop_distance, mc.seq_cfg.blind_distance);
    // The nav board: odometer pulse in Q40 m, gyro step in Q48 turns, start plus its error.
    EXPECT_EQ(m.nav.gnav.dl_q40, (uint32_t)std::llround(0.000254 * std::ldexp(1.0, 40)));
    EXPECT_EQ(m.nav.gnav.gyro_step_q48, (uint64_t)std::llround(0.25 / 360 * std::ldexp(1.0, 48)));
    EXPECT_EQ(m.nav.start.x, q16(1.01));
    EXPECT_EQ(m.nav.start.heading, (uint32_t)std::llround(89.0 / 360 * std::ldexp(1.0, 32)));
}

TEST(Mission, NominalPathChainsThroughEveryPrescribedPose)
{
    static sim_scenario_t sc;
    static sim_mission_t m;
    char err[256];
    ASSERT_EQ(sim_scenario_parse(kScenario, &sc, err, sizeof err), 0) << err;
    ASSERT_EQ(sim_mission_build(&m, &sc, err, sizeof err), 0) << err;
    const sim_path_t &p = m.nominal;
    ASSERT_GE(p.n, 3u);
    EXPECT_EQ(p.piece[0].x0, 1.0);
    EXPECT_EQ(p.piece[0].y0, 1.0);
    // Connected (each leg starts at its prescribed pose; the solver lands within 0.05 mm).
    for (size_t i = 1; i < p.n; i++) {
        sim_pose_t e = sim_piece_end(&p.piece[i - 1]);
        EXPECT_NEAR(e.x, p.piece[i].x0, 5e-5) << i;
        EXPECT_NEAR(e.y, p.piece[i].y0, 5e-5) << i;
        EXPECT_NEAR(std::remainder(e.th - p.piece[i].th0, 2 * M_PI), 0.0, 1e-4) << i;
    }
    // Through every prescribed point (distance 0 within the solver's landing).
    for (size_t i = 0; i < sc.n_path; i++)
        EXPECT_LT(sim_path_distance(&p, sc.path[i].x, sc.path[i].y), 5e-5) << i;
    sim_pose_t end = sim_path_end(&p);
    EXPECT_NEAR(end.x, 6.0, 5e-5);
    EXPECT_NEAR(end.y, 6.0, 5e-5);
    // No turn tighter than the vehicle's minimum radius.
    for (size_t i = 0; i < p.n; i++)
        EXPECT_LE(std::fabs(p.piece[i].kappa), 1 / 0.5 + 1e-6) << i;
}

TEST(Mission, RefusalsNameTheKeyAndTheValue)
{
    static sim_scenario_t sc;
    static sim_mission_t m;
    char err[256];
    ASSERT_EQ(sim_scenario_parse(kScenario, &sc, err, sizeof err), 0) << err;
    sim_scenario_t many = sc;
    many.n_path = MAIN_BOARD_MAX_PATH + 1;
    for (size_t i = 0; i < many.n_path; i++)
        many.path[i] = sc.path[i % 3];
    EXPECT_EQ(sim_mission_build(&m, &many, err, sizeof err), -1);
    EXPECT_NE(std::string(err).find("path: 255 points"), std::string::npos) << err;
    // A point 3 m behind the start's side, facing east: no forward double arc reaches it.
    sim_scenario_t tight = sc;
    tight.path[0] = {-2.0, 1.0, 0.0, 1.0};
    EXPECT_EQ(sim_mission_build(&m, &tight, err, sizeof err), -1);
    EXPECT_NE(std::string(err).find("path[0]: no double arc"), std::string::npos) << err;
    // Beacons farther apart than the map's 256 m.
    sim_scenario_t wide = sc;
    wide.world.beacon[1].x = 300;
    EXPECT_EQ(sim_mission_build(&m, &wide, err, sizeof err), -1);
    EXPECT_NE(std::string(err).find("beacons: 3 of them"), std::string::npos) << err;
}

// The same scenario in pursuit mode, its parameters written out and defaulted.
std::string pursuit_scenario(const std::string &pursuit, const std::string &source)
{
    std::string s = kScenario;
    s.replace(s.find("\"simplified\""), 12, "\"pursuit\"");
    return s.substr(0, s.rfind('}')) + ", \"pursuit\": " + pursuit +
           ", \"position_source\": " + source + "}";
}

TEST(Mission, PursuitDownloadHoldsTheSeedsParameters)
{
    static sim_scenario_t sc;
    static sim_mission_t m;
    char err[256];
    ASSERT_EQ(sim_scenario_parse(
                  pursuit_scenario("{\"threshold_pct\": 70, \"activation_s\": 0.4}", "{}").c_str(),
                  &sc, err, sizeof err),
              0)
        << err;
    ASSERT_EQ(sim_mission_build(&m, &sc, err, sizeof err), 0) << err;
    ASSERT_NE(m.main.pursuit, nullptr);
    const main_pursuit_config_t &p = *m.main.pursuit;
    // the seed's defaults (docs/pursuit.md): 1 m/s, K = 1, 5 cm; 127 x 1.755 cm/s at DAC 255
    EXPECT_EQ(p.law.speed, q16(1.0));
    EXPECT_EQ(p.law.max_speed, q16(2.229));
    EXPECT_EQ(p.law.k, q16(1.0));
    EXPECT_EQ(p.law.activation_ms, 400);
    EXPECT_EQ(p.law.threshold, q16(0.7));
    EXPECT_EQ(p.law.slow_after_ms, 1000);
    EXPECT_EQ(p.law.stop_after_ms, 3000);
    EXPECT_FALSE(p.law.regulate);
    EXPECT_NEAR(p.law.max_steer / 4294967296.0 * 360.0, std::atan(0.762 / 0.5) * 180 / M_PI, 1e-6);
    EXPECT_EQ(p.rx.min_update_mm, 50);
    EXPECT_EQ(p.rx.max_speed_mm_s, 2229);
    EXPECT_EQ(p.baud, 9600u);
    EXPECT_EQ(p.receivers, 1);
    EXPECT_EQ(p.heading, MAIN_HEADING_POSITIONS);
    // two receivers 0.3 m apart along the vehicle, 0.1 m across
    ASSERT_EQ(sim_scenario_parse(
                  pursuit_scenario("{\"heading\": \"receivers\"}",
                                   "{\"receivers\": [{\"forward_m\": 0.3, \"left_m\": 0.1}, "
                                   "{\"forward_m\": 0, \"left_m\": 0}], \"baud\": 115200}")
                      .c_str(),
                  &sc, err, sizeof err),
              0)
        << err;
    ASSERT_EQ(sim_mission_build(&m, &sc, err, sizeof err), 0) << err;
    EXPECT_EQ(m.pursuit.receivers, 2);
    EXPECT_EQ(m.pursuit.heading, MAIN_HEADING_RECEIVERS);
    EXPECT_EQ(m.pursuit.baud, 115200u);
    EXPECT_EQ(m.pursuit.law.pair_sep, q16(std::hypot(0.3, 0.1)));
    EXPECT_NEAR(m.pursuit.law.pair_angle / 4294967296.0 * 360.0, std::atan2(0.1, 0.3) * 180 / M_PI,
                1e-6);
}

TEST(Mission, PursuitRefusalsNameTheKeyAndTheValue)
{
    static sim_scenario_t sc;
    static sim_mission_t m;
    char err[256];
    const struct {
        const char *pursuit, *source, *want;
    } bad[] = {
        {"{\"speed_mps\": 3}", "{}", "pursuit.speed_mps: 3 is above max_speed_mps (2.229)"},
        {"{\"slow_after_s\": 2, \"stop_after_s\": 1}", "{}",
         "pursuit.stop_after_s: 1 is not after slow_after_s (2)"},
        {"{\"heading\": \"receivers\"}", "{}", "pursuit.heading: \"receivers\" needs two"},
        {"{}", "{\"baud\": 19200}", "position_source.baud: 19200"},
        {"{}", "{\"outages\": [{\"from_s\": 5, \"to_s\": 4}]}",
         "position_source.outages[0].to_s: 4 is before from_s (5)"},
    };
    for (const auto &b : bad) {
        ASSERT_EQ(
            sim_scenario_parse(pursuit_scenario(b.pursuit, b.source).c_str(), &sc, err, sizeof err),
            0)
            << err;
        EXPECT_EQ(sim_mission_build(&m, &sc, err, sizeof err), -1) << b.want;
        EXPECT_NE(std::string(err).find(b.want), std::string::npos) << err;
    }
    // a goal point on the one before
    ASSERT_EQ(sim_scenario_parse(pursuit_scenario("{}", "{}").c_str(), &sc, err, sizeof err), 0);
    sc.path[1] = sc.path[0];
    sc.path[1].heading = sc.path[0].heading;
    EXPECT_EQ(sim_mission_build(&m, &sc, err, sizeof err), -1);
}

} // namespace
