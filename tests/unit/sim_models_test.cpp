// Tests of the simulator's world models: the tricycle's closed-form motion against a numerical
// integration of its differential equations, the goniometer's edges against the geometry of
// the beam and the post, line of sight, and scenario validation.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

extern "C" {
#include "sim/gonio.h"
#include "sim/motion.h"
#include "sim/path.h"
#include "sim/scenario.h"
#include "sim/world.h"
}

namespace
{

// RK4 of the tricycle ODE: x' = v cos th, y' = v sin th, th' = v tan(alpha) / L.
Eigen::Vector3d integrate(Eigen::Vector3d s, double alpha, double v, double L, double T)
{
    auto f = [&](const Eigen::Vector3d &q) {
        return Eigen::Vector3d(v * std::cos(q[2]), v * std::sin(q[2]), v * std::tan(alpha) / L);
    };
    const int n = 20000;
    double h = T / n;
    for (int i = 0; i < n; i++) {
        Eigen::Vector3d k1 = f(s), k2 = f(s + 0.5 * h * k1), k3 = f(s + 0.5 * h * k2),
                        k4 = f(s + h * k3);
        s += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    return s;
}

TEST(Motion, ClosedFormMatchesIntegration)
{
    const double L = 0.75;
    for (double alpha : {0.0, 0.3, -0.6, 1.2}) {
        for (double v : {1.0, -0.5}) {
            sim_pose_t p0 = {1.0, -2.0, 0.4};
            sim_segment_t seg = sim_segment(3.0, p0, 10.0, alpha, v, L);
            sim_pose_t p = sim_segment_pose(&seg, 5.0);
            Eigen::Vector3d ref = integrate(Eigen::Vector3d(1.0, -2.0, 0.4), alpha, v, L, 2.0);
            EXPECT_NEAR(p.x, ref[0], 1e-9) << alpha << " " << v;
            EXPECT_NEAR(p.y, ref[1], 1e-9);
            EXPECT_NEAR(p.th, ref[2], 1e-9);
            // Front wheel: |v| / cos(alpha) per second.
            EXPECT_NEAR(sim_segment_front(&seg, 5.0), 10.0 + 2.0 * std::fabs(v) / std::cos(alpha),
                        1e-12);
            double t = sim_segment_time_at_front(&seg, 10.5, 3.0);
            EXPECT_NEAR(sim_segment_front(&seg, t), 10.5, 1e-12);
        }
    }
}

TEST(World, OccludersBlockTheLineOfSight)
{
    sim_world_t w = {};
    w.n_occluders = 1;
    w.occluder[0] = {1.0, -1.0, 1.0, 1.0};
    EXPECT_FALSE(sim_world_visible(&w, 0, 0, 2, 0));
    EXPECT_TRUE(sim_world_visible(&w, 0, 0, 0.5, 0));
    EXPECT_TRUE(sim_world_visible(&w, 0, 0, 2, 3)); // crosses x = 1 at y = 1.5, above the wall
}

// The beam direction at an edge must graze the post: the angle between the beam and the
// direction to the post's centre is asin(D / 2d), before the centre on the rising edge.
void check_edges(const sim_world_t &w, const sim_segment_t &seg, const sim_gonio_cfg_t &cfg,
                 size_t expect)
{
    sim_rng_t rng;
    sim_rng_seed(&rng, 1, 0);
    sim_gonio_event_t ev[64];
    double t_index = seg.t0;
    size_t n = sim_gonio_edges(&cfg, &w, &seg, t_index, seg.t0, seg.t0 + 1.0 / cfg.rev_per_s, &rng,
                               ev, 64);
    ASSERT_EQ(n, expect);
    for (size_t i = 0; i < n; i++) {
        if (i) {
            EXPECT_LE(ev[i - 1].t, ev[i].t);
        }
        const sim_beacon_t &b = w.beacon[ev[i].target];
        sim_pose_t p = sim_segment_pose(&seg, ev[i].t);
        double beam = p.th + 2 * M_PI * cfg.rev_per_s * (ev[i].t - t_index);
        double centre = std::atan2(b.y - p.y, b.x - p.x);
        double diff = std::remainder(beam - centre, 2 * M_PI);
        double half = std::asin(b.diameter / 2 / std::hypot(b.x - p.x, b.y - p.y));
        EXPECT_NEAR(diff, ev[i].edge == SIM_GEV_RISE ? -half : half, 1e-9) << i;
        EXPECT_NEAR(ev[i].mirror,
                    std::fmod(2 * M_PI * cfg.rev_per_s * (ev[i].t - t_index), 2 * M_PI), 1e-9);
    }
}

TEST(Gonio, EdgesGrazeThePostsStandingAndMoving)
{
    sim_world_t w = {};
    w.n_beacons = 4;
    w.beacon[0] = {5, 0, 0.08};
    w.beacon[1] = {0, 7, 0.08};
    w.beacon[2] = {-6, -6, 0.2};
    w.beacon[3] = {3, -0.5, 0.08};
    sim_gonio_cfg_t cfg = {2.0, 50000, 0.0, 60.0};
    sim_segment_t still = sim_segment(0.25, {0.2, 0.1, 0.3}, 0, 0, 0, 0.75);
    check_edges(w, still, cfg, 8);
    sim_segment_t moving = sim_segment(0.25, {0.2, 0.1, 0.3}, 0, 0.5, 1.0, 0.75);
    check_edges(w, moving, cfg, 8);
    // An occluder hides one post: two edges fewer.
    w.n_occluders = 1;
    w.occluder[0] = {2.0, -1.0, 2.0, -0.2};
    check_edges(w, still, cfg, 6);
}

// Two posts almost in line: their pulses overlap and the photodetector gives one pulse from
// the first target's rising edge to the last one's falling edge.
TEST(Gonio, PhotodetectorIsTheUnionOfOverlappingPulses)
{
    sim_world_t w = {};
    w.n_beacons = 3;
    w.beacon[0] = {5, 0, 0.1};
    w.beacon[1] = {10, 0.05, 0.1}; // 0.29 deg beside beacon 0, 0.57 deg wide: overlaps it
    w.beacon[2] = {0, 6, 0.1};
    sim_gonio_cfg_t cfg = {2.0, 50000, 0.0, 60.0};
    sim_segment_t still = sim_segment(0.0, {0.0, 0.0, 0.0}, 0, 0, 0, 0.75);
    sim_rng_t rng;
    sim_rng_seed(&rng, 1, 0);
    sim_gonio_event_t ev[16];
    // From 0.1 s: the pulses around angle 0 are whole (beacon 0 is lit at t = 0).
    size_t n = sim_gonio_edges(&cfg, &w, &still, 0.0, 0.1, 0.6, &rng, ev, 16);
    ASSERT_EQ(n, 6u);
    sim_photo_t ph;
    sim_photo_init(&ph);
    std::vector<sim_gonio_event_t> out;
    for (size_t i = 0; i < n; i++)
        if (sim_photo_feed(&ph, &ev[i]))
            out.push_back(ev[i]);
    ASSERT_EQ(out.size(), 4u);
    // Beacon 2 alone at 90 degrees, then the union of 0 and 1 (beacon 0 is the wider).
    EXPECT_EQ(out[0].target, 2);
    EXPECT_EQ(out[1].target, 2);
    double h0 = std::asin(0.05 / 5.0), h1 = std::asin(0.05 / std::hypot(10.0, 0.05));
    double a1 = std::atan2(0.05, 10.0);
    double rise = std::min(-h0, a1 - h1) + 2 * M_PI, fall = std::max(h0, a1 + h1) + 2 * M_PI;
    EXPECT_EQ(out[2].edge, SIM_GEV_RISE);
    EXPECT_NEAR(out[2].t, rise / (4 * M_PI), 1e-9);
    EXPECT_EQ(out[3].edge, SIM_GEV_FALL);
    EXPECT_NEAR(out[3].t, fall / (4 * M_PI), 1e-9);
    // A falling edge whose rising edge came before the photodetector was watched: ignored.
    sim_photo_init(&ph);
    sim_gonio_event_t lone = {0.0, SIM_GEV_FALL, 0, 0.0};
    EXPECT_EQ(sim_photo_feed(&ph, &lone), 0);
    EXPECT_EQ(ph.n_lit, 0u);
}

TEST(Gonio, CountIsTheAngleClockOnSixteenBits)
{
    sim_gonio_cfg_t cfg = {2.0, 50000, 0.0, 60.0};
    EXPECT_EQ(sim_gonio_count(&cfg, 0.0), 0);
    EXPECT_EQ(sim_gonio_count(&cfg, 0.5), 50000); // one turn
    EXPECT_EQ(sim_gonio_count(&cfg, 1.0), (100000 % 65536));
    EXPECT_EQ(sim_gonio_count(&cfg, 0.25 + 1e-7), 25000);
}

// Distance to a path, against brute force: the minimum over dense samples of the path.
TEST(Path, DistanceMatchesDenseSampling)
{
    static sim_path_t p;
    p.n = 0;
    sim_pose_t s = {0.0, 0.0, 0.3};
    ASSERT_EQ(sim_path_append(&p, s, 0.0, 2.0, 0), 0);
    ASSERT_EQ(sim_path_append(&p, s, 1.0 / 1.5, 2.5, 0), 0);
    ASSERT_EQ(sim_path_append(&p, s, -1.0 / 0.8, 1.9, 0), 0);
    ASSERT_EQ(sim_path_append(&p, s, 0.5, 1.0, 1), 0); // backwards
    EXPECT_NEAR(sim_path_length(&p), 7.4, 1e-12);
    std::vector<Eigen::Vector2d> pts;
    for (size_t i = 0; i < p.n; i++) {
        const sim_piece_t &pc = p.piece[i];
        for (int k = 0; k <= 20000; k++) {
            sim_piece_t part = pc;
            part.length = pc.length * k / 20000.0;
            sim_pose_t e = sim_piece_end(&part);
            pts.emplace_back(e.x, e.y);
        }
    }
    uint32_t x = 99;
    for (int trial = 0; trial < 500; trial++) {
        x = x * 1664525u + 1013904223u;
        double qx = -2.0 + 8.0 * (x >> 8) / 16777216.0;
        x = x * 1664525u + 1013904223u;
        double qy = -3.0 + 8.0 * (x >> 8) / 16777216.0;
        double brute = 1e9;
        for (const auto &q : pts)
            brute = std::min(brute, (q - Eigen::Vector2d(qx, qy)).norm());
        // Dense samples are at most 0.125 mm apart: the true distance is within that.
        double d = sim_path_distance(&p, qx, qy);
        EXPECT_LE(d, brute + 1e-9) << qx << "," << qy;
        EXPECT_GE(d, brute - 1.3e-4) << qx << "," << qy;
    }
}

const char *kScenario = R"({
 "name": "unit", "mode": "full",
 "beacons": [{"x":0,"y":0,"diameter_m":0.08},{"x":10,"y":0,"diameter_m":0.08},
             {"x":10,"y":10,"diameter_m":0.08}],
 "vehicle": {"wheelbase_m":0.75,"min_radius_m":0.5,"speed_mps":1.0},
 "start": {"x":1,"y":1,"heading_deg":90},
 "path": [{"x":1,"y":5,"heading_deg":90,"speed_mps":1.0}],
 "sensors": {"goniometer":{"rev_per_s":2,"counts":50000,"noise_deg":0},
             "odometer":{"dl_m":0.000254},"gyro":{"step_deg":0.25,"drift_deg_per_s":0}},
 "seed": 7, "duration_s": 20})";

TEST(Scenario, ParsesTheContractExample)
{
    sim_scenario_t sc;
    char err[256];
    ASSERT_EQ(sim_scenario_parse(kScenario, &sc, err, sizeof err), 0) << err;
    EXPECT_STREQ(sc.name, "unit");
    EXPECT_EQ(sc.mode, SIM_SCENARIO_MODE_FULL);
    EXPECT_EQ(sc.world.n_beacons, 3u);
    EXPECT_NEAR(sc.start_heading, M_PI / 2, 1e-15);
    EXPECT_EQ(sc.counts, 50000u);
    EXPECT_NEAR(sc.gyro_step, 0.25 * M_PI / 180, 1e-15);
    EXPECT_EQ(sc.seed, 7u);
}

struct BadCase {
    const char *from, *to, *message;
};

TEST(Scenario, BadInputNamesTheKeyAndTheValue)
{
    const BadCase cases[] = {
        {"\"counts\":50000", "\"counts\":50000.5", "sensors.goniometer.counts: 50000.5"},
        {"\"dl_m\":0.000254", "\"dl_m\":-1", "sensors.odometer.dl_m: -1 is out of range"},
        {"\"mode\": \"full\"", "\"mode\": \"fast\"", "mode: \"fast\""},
        {"\"x\":10,\"y\":10,\"diameter_m\":0.08", "\"x\":10,\"y\":\"ten\",\"diameter_m\":0.08",
         "beacons[2].y: expected a number, got \"ten\""},
        {"\"speed_mps\":1.0}]", "\"speed_mps\":0}]", "path[0].speed_mps: 0 is out of range"},
        {"\"seed\": 7,", "", "missing \"seed\""},
        {"\"name\": \"unit\",", "\"name\": \"unit\",,", "line 2"},
    };
    for (const BadCase &c : cases) {
        std::string text = kScenario;
        size_t at = text.find(c.from);
        ASSERT_NE(at, std::string::npos) << c.from;
        text.replace(at, std::strlen(c.from), c.to);
        sim_scenario_t sc;
        char err[256] = "";
        EXPECT_EQ(sim_scenario_parse(text.c_str(), &sc, err, sizeof err), -1) << c.to;
        EXPECT_NE(std::string(err).find(c.message), std::string::npos)
            << "got: " << err << " / want: " << c.message;
    }
}

} // namespace
