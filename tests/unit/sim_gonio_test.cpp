// sim/gonio: the goniometer's edges against the geometry of the beam and the post, the
// photodetector, the angle clock.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include "sim/gonio.h"
#include "sim/motion.h"
#include "sim/rng.h"
#include "sim/world.h"
}

namespace
{

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

} // namespace
