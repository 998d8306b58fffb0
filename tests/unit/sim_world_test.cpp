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

} // namespace
