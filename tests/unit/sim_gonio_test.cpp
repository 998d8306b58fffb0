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
#include "sim/scenario_keys.h"
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
        // A post's edges graze it (asin); a flat strip facing the beam ends at its edges (atan).
        double r = std::hypot(b.x - p.x, b.y - p.y);
        double half = b.kind == SIM_BEACON_KIND_FLAT ? std::atan(b.diameter / 2 / r)
                                                     : std::asin(b.diameter / 2 / r);
        EXPECT_NEAR(diff, ev[i].edge == SIM_GEV_RISE ? -half : half, 1e-9) << i;
        EXPECT_NEAR(ev[i].mirror,
                    std::fmod(2 * M_PI * cfg.rev_per_s * (ev[i].t - t_index), 2 * M_PI), 1e-9);
    }
}

TEST(Gonio, EdgesGrazeThePostsStandingAndMoving)
{
    sim_world_t w = {};
    w.n_beacons = 4;
    w.beacon[0] = {5, 0, 0.08, SIM_BEACON_KIND_CYLINDER};
    w.beacon[1] = {0, 7, 0.08, SIM_BEACON_KIND_CYLINDER};
    w.beacon[2] = {-6, -6, 0.2, SIM_BEACON_KIND_CYLINDER};
    w.beacon[3] = {3, -0.5, 0.08, SIM_BEACON_KIND_CYLINDER};
    sim_gonio_cfg_t cfg = {2.0, 50000, 0.0, 60.0};
    sim_segment_t still = sim_segment(0.25, {0.2, 0.1, 0.3}, 0, 0, 0, 0.75);
    check_edges(w, still, cfg, 8);
    sim_segment_t moving = sim_segment(0.25, {0.2, 0.1, 0.3}, 0, 0.5, 1.0, 0.75);
    check_edges(w, moving, cfg, 8);
    // An occluder hides one post: two edges fewer.
    w.n_occluders = 1;
    w.occluder[0] = {2.0, -1.0, 2.0, -0.2};
    check_edges(w, still, cfg, 6);
    // A wide flat strip close by (1.5 m, 0.6 m wide: atan and asin differ by 0.26 degrees).
    w.n_occluders = 0;
    w.beacon[3] = {1.5, -0.2, 0.6, SIM_BEACON_KIND_FLAT};
    check_edges(w, still, cfg, 8);
    check_edges(w, moving, cfg, 8);
}

// Whether the beam's crossing of post @p b's centre in [t0, t0 + 1 / rev) is in range and in
// sight (the rule the edges follow): the crossing found by bisection on the beam's angle to the
// post along the pose, the walls crossed tested with exact 2-D cross products (Eigen).
bool centre_seen(const sim_world_t &w, const sim_segment_t &seg, const sim_gonio_cfg_t &cfg,
                 const sim_beacon_t &b)
{
    auto g = [&](double t) {
        sim_pose_t p = sim_segment_pose(&seg, t);
        double beam = p.th + 2 * M_PI * cfg.rev_per_s * (t - seg.t0);
        return std::remainder(beam - std::atan2(b.y - p.y, b.x - p.x), 2 * M_PI);
    };
    double step = 1e-3 / cfg.rev_per_s, lo = seg.t0, hi = lo + step;
    while (!(g(lo) < 0 && g(hi) >= 0 && g(hi) - g(lo) < 1.0)) {
        lo = hi;
        hi += step;
    }
    for (int i = 0; i < 60; i++)
        (g(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
    sim_pose_t p = sim_segment_pose(&seg, lo);
    Eigen::Vector2d v(p.x, p.y), t(b.x, b.y);
    if ((t - v).norm() > cfg.max_range)
        return false;
    auto cross = [](Eigen::Vector2d a, Eigen::Vector2d c) { return a.x() * c.y() - a.y() * c.x(); };
    for (size_t i = 0; i < w.n_occluders; i++) {
        Eigen::Vector2d a(w.occluder[i].x1, w.occluder[i].y1),
            c(w.occluder[i].x2, w.occluder[i].y2);
        if (cross(t - v, a - v) * cross(t - v, c - v) < 0 &&
            cross(c - a, v - a) * cross(c - a, t - a) < 0)
            return false;
    }
    return true;
}

// A vehicle driving 1 m in a turn past walls: one post hidden all the turn, one out of range,
// one in open view, one seen past a wall's end only from where the beam crosses it and one
// hidden only there (for the whole window: blocked, blocked by range, clear, unsure, unsure).
// The edges come from the posts whose centre crossing is in sight.
TEST(Gonio, WallsAndRangeAreJudgedAtTheCentreCrossingWhileMoving)
{
    sim_world_t w = {};
    w.n_beacons = 5;
    w.beacon[0] = {0, 5, 0.1, SIM_BEACON_KIND_CYLINDER};     // behind the wall y = 3
    w.beacon[1] = {-5, 0.3, 0.1, SIM_BEACON_KIND_CYLINDER};  // past the end of the wall x = -2
    w.beacon[2] = {0, -5, 0.1, SIM_BEACON_KIND_CYLINDER};    // behind y = -3 from x = 0.75
    w.beacon[3] = {-10, -10, 0.1, SIM_BEACON_KIND_CYLINDER}; // 14 m away
    w.beacon[4] = {5, 1.5, 0.1, SIM_BEACON_KIND_CYLINDER};   // open view
    w.n_occluders = 3;
    w.occluder[0] = {-3, 3, 3, 3};
    w.occluder[1] = {-2, -1, -2, 0.13};
    w.occluder[2] = {0.2, -3, 3, -3};
    sim_gonio_cfg_t cfg = {2.0, 50000, 0.0, 9.0};
    sim_segment_t seg = sim_segment(0.0, {0.0, 0.0, 0.0}, 0, 0.02, 2.0, 0.75);
    size_t seen = 0;
    for (size_t i = 0; i < w.n_beacons; i++)
        seen += centre_seen(w, seg, cfg, w.beacon[i]);
    EXPECT_EQ(seen, 2u);
    EXPECT_TRUE(centre_seen(w, seg, cfg, w.beacon[1]));
    EXPECT_TRUE(centre_seen(w, seg, cfg, w.beacon[4]));
    check_edges(w, seg, cfg, 2 * seen);
}

// Two posts almost in line: their pulses overlap and the photodetector gives one pulse from
// the first target's rising edge to the last one's falling edge.
TEST(Gonio, PhotodetectorIsTheUnionOfOverlappingPulses)
{
    sim_world_t w = {};
    w.n_beacons = 3;
    w.beacon[0] = {5, 0, 0.1, SIM_BEACON_KIND_CYLINDER};
    w.beacon[1] = {10, 0.05, 0.1, SIM_BEACON_KIND_CYLINDER}; // 0.29 deg beside beacon 0, 0.57
                                                             // deg wide: overlaps it
    w.beacon[2] = {0, 6, 0.1, SIM_BEACON_KIND_CYLINDER};
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
