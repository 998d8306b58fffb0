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

// RK4 of the tricycle ODE with the rear-axle travel d as a fourth state: x' = v cos th,
// y' = v sin th, th' = v tan(alpha) / L, d' = v, the speed v(t) = v0 - decel t (toward zero,
// then 0) a function of time.
Eigen::Vector4d integrate4(Eigen::Vector3d s0, double alpha, double v0, double decel, double L,
                           double T)
{
    auto speed = [&](double t) {
        double m = std::fabs(v0) - decel * t;
        return m <= 0 ? 0.0 : std::copysign(m, v0);
    };
    auto f = [&](double t, const Eigen::Vector4d &q) {
        double v = speed(t);
        return Eigen::Vector4d(v * std::cos(q[2]), v * std::sin(q[2]), v * std::tan(alpha) / L, v);
    };
    Eigen::Vector4d s(s0[0], s0[1], s0[2], 0.0);
    const int n = 20000;
    double h = T / n;
    for (int i = 0; i < n; i++) {
        double t = i * h;
        Eigen::Vector4d k1 = f(t, s), k2 = f(t + 0.5 * h, s + 0.5 * h * k1),
                        k3 = f(t + 0.5 * h, s + 0.5 * h * k2), k4 = f(t + h, s + h * k3);
        s += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    return s;
}

Eigen::Vector3d integrate(Eigen::Vector3d s, double alpha, double v, double L, double T)
{
    return integrate4(s, alpha, v, 0.0, L, T).head<3>();
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

// Braking: the speed falls at a constant rate to zero and stays there. The stop lands on the
// integration's grid (1.6 s at 0.5 m/s^2 from 0.8 m/s), so RK4 stays exact to its order.
TEST(Motion, BrakingMatchesIntegration)
{
    const double L = 0.75, decel = 0.5;
    for (double alpha : {0.0, 0.3, -0.6}) {
        for (double v : {0.8, -0.8}) {
            sim_segment_t seg = sim_segment(3.0, {1.0, -2.0, 0.4}, 10.0, alpha, v, L);
            seg.decel = decel;
            EXPECT_DOUBLE_EQ(sim_segment_stop_time(&seg), 3.0 + 1.6);
            for (double T : {0.7, 1.6, 2.5}) {
                Eigen::Vector4d ref =
                    integrate4(Eigen::Vector3d(1.0, -2.0, 0.4), alpha, v, decel, L, T);
                sim_pose_t p = sim_segment_pose(&seg, 3.0 + T);
                EXPECT_NEAR(p.x, ref[0], 1e-9) << alpha << " " << v << " " << T;
                EXPECT_NEAR(p.y, ref[1], 1e-9);
                EXPECT_NEAR(p.th, ref[2], 1e-9);
                EXPECT_NEAR(sim_segment_travel(&seg, 3.0 + T), ref[3], 1e-9);
                double m = std::fabs(v) - decel * T;
                EXPECT_NEAR(sim_segment_speed(&seg, 3.0 + T), m > 0 ? std::copysign(m, v) : 0.0,
                            1e-12);
                EXPECT_NEAR(sim_segment_front(&seg, 3.0 + T),
                            10.0 + std::fabs(ref[3]) / std::cos(alpha), 1e-9);
            }
            // The whole stopping distance v^2 / (2 decel) is reached at the stop, never beyond.
            double stop = 0.8 * 0.8 / (2 * decel);
            EXPECT_NEAR(sim_segment_time_at_travel(&seg, stop), 4.6, 1e-6);
            EXPECT_EQ(sim_segment_time_at_travel(&seg, stop + 1e-6), INFINITY);
            double t = sim_segment_time_at_travel(&seg, 0.3);
            EXPECT_NEAR(std::fabs(sim_segment_travel(&seg, t)), 0.3, 1e-12);
            t = sim_segment_time_at_front(&seg, 10.5, 3.0);
            EXPECT_NEAR(sim_segment_front(&seg, t), 10.5, 1e-12);
        }
    }
}

} // namespace
