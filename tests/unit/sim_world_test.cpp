// sim/world: line of sight through the walls.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
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

} // namespace
