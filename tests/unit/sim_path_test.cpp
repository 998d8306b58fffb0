// sim/path: the distance to the nominal path against dense sampling of its pieces.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include "sim/motion.h"
#include "sim/path.h"
}

namespace
{

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

} // namespace
