// sim/world: line of sight through the walls.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include "sim/world.h"
}

namespace
{

TEST(World, OccludersBlockTheLineOfSight)
{
    sim_world_t w = {};
    w.n_occluders = 1;
    w.occluder[0] = {1.0, -1.0, 1.0, 1.0};
    EXPECT_FALSE(sim_world_visible(&w, 0, 0, 2, 0));
    EXPECT_TRUE(sim_world_visible(&w, 0, 0, 0.5, 0));
    EXPECT_TRUE(sim_world_visible(&w, 0, 0, 2, 3)); // crosses x = 1 at y = 1.5, above the wall
}

// A pillar hides what lies behind it: the line of sight is blocked when it passes nearer to
// the centre than the radius. Reference: the distance from the centre to the segment with
// Eigen (projection clamped to the segment).
TEST(World, PillarsBlockTheLineOfSight)
{
    sim_world_t w = {};
    w.n_pillars = 1;
    w.pillar[0] = {1.0, 0.0, 0.4};
    EXPECT_FALSE(sim_world_visible(&w, 0, 0, 2, 0));
    EXPECT_FALSE(sim_world_visible(&w, 0, 0.15, 2, 0.15));
    EXPECT_TRUE(sim_world_visible(&w, 0, 0.25, 2, 0.25));
    EXPECT_TRUE(sim_world_visible(&w, 0, 0, 0.7, 0)); // ends before it
    std::srand(5);
    auto u = [] { return std::rand() / (double)RAND_MAX; };
    int blocked = 0;
    for (int i = 0; i < 20000; i++) {
        Eigen::Vector2d a(4 * u() - 2, 4 * u() - 2), b(4 * u() - 2, 4 * u() - 2), c(1.0, 0.0);
        double t = std::clamp((c - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        double d = (a + t * (b - a) - c).norm();
        if (std::fabs(d - 0.2) < 1e-9)
            continue;
        EXPECT_EQ(sim_world_visible(&w, a.x(), a.y(), b.x(), b.y()), d >= 0.2);
        blocked += d < 0.2;
    }
    EXPECT_GT(blocked, 1000);
}

// sim_world_sight() on cases worked by hand: a wall x = 1, |y| <= 1, and a pillar.
TEST(World, SightFromADiskByHand)
{
    sim_world_t w = {};
    w.n_occluders = 1;
    w.occluder[0] = {1.0, -1.0, 1.0, 1.0};
    // Every line from |p| <= 0.2 to (2, 0) crosses x = 1 at |y| <= 0.1: behind the wall.
    EXPECT_EQ(sim_world_sight(&w, 0, 0, 0.2, 2, 0), SIM_SIGHT_BLOCKED);
    // Viewpoint and target on the same side of the wall.
    EXPECT_EQ(sim_world_sight(&w, 0, 0, 0.2, -2, 0), SIM_SIGHT_CLEAR);
    // From (0, 1.5..2.5) to (2, 0) the line crosses x = 1 at y in [0.75, 1.25]: past the wall's
    // end for some viewpoints only.
    EXPECT_EQ(sim_world_sight(&w, 0, 2, 0.5, 2, 0), SIM_SIGHT_UNSURE);
    // From (0, 3) +- 0.5 the crossing is at y >= 1.25: above the wall.
    EXPECT_EQ(sim_world_sight(&w, 0, 3, 0.5, 2, 0), SIM_SIGHT_CLEAR);
    // A disk reaching the wall's line: some viewpoints are beside the target, some not.
    EXPECT_EQ(sim_world_sight(&w, 0.5, 0, 0.6, 2, 0), SIM_SIGHT_UNSURE);
    // A pillar of radius 0.2 at (1, 0): the line from (0, 1) to (2, 0) passes 1 / sqrt(5) =
    // 0.447 from its centre, so a disk of 0.1 around (0, 1) clears it and one of 0.3 may not.
    w.n_occluders = 0;
    w.n_pillars = 1;
    w.pillar[0] = {1.0, 0.0, 0.4};
    EXPECT_EQ(sim_world_sight(&w, 0, 1, 0.1, 2, 0), SIM_SIGHT_CLEAR);
    EXPECT_EQ(sim_world_sight(&w, 0, 1, 0.3, 2, 0), SIM_SIGHT_UNSURE);
    // Pillars never make it BLOCKED, even straight behind one.
    EXPECT_EQ(sim_world_sight(&w, 0, 0, 0.01, 2, 0), SIM_SIGHT_UNSURE);
}

// Invariant: CLEAR means sim_world_visible() from every point of the disk, BLOCKED from none.
// Random walls, pillars, disks and targets; each verdict checked at 300 viewpoints (the rim
// included); and the verdicts are not all UNSURE.
TEST(World, SightFromADiskHoldsAtEveryViewpoint)
{
    std::srand(11);
    auto u = [] { return std::rand() / (double)RAND_MAX; };
    int count[3] = {0, 0, 0};
    for (int k = 0; k < 3000; k++) {
        sim_world_t w = {};
        w.n_occluders = 1 + k % 3;
        for (size_t i = 0; i < w.n_occluders; i++)
            w.occluder[i] = {20 * u() - 10, 20 * u() - 10, 20 * u() - 10, 20 * u() - 10};
        w.n_pillars = k % 2;
        w.pillar[0] = {20 * u() - 10, 20 * u() - 10, 2 * u()};
        double cx = 20 * u() - 10, cy = 20 * u() - 10, r = 2 * u() * u();
        double bx = 20 * u() - 10, by = 20 * u() - 10;
        sim_sight_t s = sim_world_sight(&w, cx, cy, r, bx, by);
        count[s]++;
        if (s == SIM_SIGHT_UNSURE)
            continue;
        for (int i = 0; i < 300; i++) {
            double a = 2 * M_PI * u(), rho = i < 100 ? r : r * std::sqrt(u());
            bool v = sim_world_visible(&w, cx + rho * std::cos(a), cy + rho * std::sin(a), bx, by);
            ASSERT_EQ(v, s == SIM_SIGHT_CLEAR) << k << " " << i;
        }
    }
    EXPECT_GT(count[SIM_SIGHT_CLEAR], 300);
    EXPECT_GT(count[SIM_SIGHT_BLOCKED], 300);
    EXPECT_GT(count[SIM_SIGHT_UNSURE], 100);
}

} // namespace
