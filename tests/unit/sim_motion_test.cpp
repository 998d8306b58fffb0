// sim/motion: the tricycle's closed-form motion against a numerical integration of its
// differential equations (RK4).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include "sim/motion.h"
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

} // namespace
