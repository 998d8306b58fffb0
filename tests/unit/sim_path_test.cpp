// sim/path: the distance to the nominal path against dense sampling of its pieces; the
// shortcuts of sim_piece_geom_nearer() against exact geometry and against the distance's
// plain formulation (hypot, atan2, remainder), bit for bit.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cfloat>
#include <cmath>
#include <cstdint>
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

// Squared-distance shortcut against exact cases: (3, 4) is 5 from the origin.
TEST(Path, RingBeyondDecidesOnlyClearCases)
{
    EXPECT_EQ(sim_path_ring_beyond(25.0, 0.0, 4.9), 1); // 5 >= 4.9
    EXPECT_EQ(sim_path_ring_beyond(25.0, 0.0, 5.0), 0); // a tie is left to hypot()
    EXPECT_EQ(sim_path_ring_beyond(25.0, 0.0, 5.1), 0);
    EXPECT_EQ(sim_path_ring_beyond(25.0, 2.0, 2.9), 1); // 3 outside a circle of radius 2
    EXPECT_EQ(sim_path_ring_beyond(25.0, 2.0, 3.1), 0);
    EXPECT_EQ(sim_path_ring_beyond(1.0, 5.0, 3.9), 1); // 4 inside a circle of radius 5
    EXPECT_EQ(sim_path_ring_beyond(1.0, 5.0, 4.1), 0);
    EXPECT_EQ(sim_path_ring_beyond(1.0, 5.0, 4.0 * (1.0 - 1e-14)), 0); // within the slack
    EXPECT_EQ(sim_path_ring_beyond(25.0, 0.0, INFINITY), 0);
    EXPECT_EQ(sim_path_ring_beyond(25.0, 0.0, 1e-70), 0); // subnormal squares: no shortcut
    EXPECT_EQ(sim_path_ring_beyond(25.0, 0.0, NAN), 0);
    EXPECT_EQ(sim_path_ring_beyond(INFINITY, 0.0, 1.0), 1);
}

// Cross-product wedge test against exact directions.
TEST(Path, InWedgeSidesWithAMargin)
{
    // A quarter turn from +x to +y.
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, 1, 1), 1);
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, -1, 1), -1);
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, 1, -1), -1);
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, -1, -1), -1);
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, 1, 1e-6), 1);   // 1e-6 rad inside
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, 1, -1e-6), -1); // 1e-6 rad outside
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, 1, 1e-12), 0);  // nearer a side than 1e-9 rad
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, -1e-12, 1), 0);
    EXPECT_EQ(sim_path_in_wedge(2, 0, 0, 3, 5, 5), 1); // lengths do not matter
    // Half a turn from +x to -x: the upper half plane.
    EXPECT_EQ(sim_path_in_wedge(1, 0, -1, 0, 0, 1), 1);
    EXPECT_EQ(sim_path_in_wedge(1, 0, -1, 0, 0.3, -1), -1);
    // Degenerate vectors: not decided.
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, 0, 0), 0);
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, 1e-40, 1e-40), 0);
    EXPECT_EQ(sim_path_in_wedge(1, 0, 0, 1, NAN, 1), 0);
}

// The distance as plainly defined: the nearer end, the foot of the perpendicular on a
// straight, the radial distance where the arc covers the point's direction (atan2).
double plain_distance(const sim_piece_t *pc, const sim_piece_geom_t *g, double x, double y)
{
    double best = std::fmin(std::hypot(x - pc->x0, y - pc->y0), std::hypot(x - g->ex, y - g->ey));
    if (std::fabs(pc->kappa) < 1e-12) {
        double s = (x - pc->x0) * g->ux + (y - pc->y0) * g->uy;
        if (s > 0.0 && s < pc->length)
            best = std::fmin(best, std::fabs(-(x - pc->x0) * g->uy + (y - pc->y0) * g->ux));
        return best;
    }
    double rel = std::remainder(std::atan2(y - g->cy, x - g->cx) - g->a0, 2.0 * M_PI);
    bool covers = g->sw >= 0.0 ? (rel >= 0.0 ? rel <= g->sw : rel + 2.0 * M_PI <= g->sw)
                               : (rel <= 0.0 ? rel >= g->sw : rel - 2.0 * M_PI >= g->sw);
    if (covers)
        best = std::fmin(best, std::fabs(std::hypot(x - g->cx, y - g->cy) - std::fabs(g->r)));
    return best;
}

uint64_t bits(double d)
{
    uint64_t u;
    std::memcpy(&u, &d, sizeof u);
    return u;
}

// Random pieces (straights, arcs of every sweep up to beyond a turn, both senses, backwards)
// and points around them, many placed on the boundary directions of the arcs and on the
// circles: sim_piece_geom_nearer() equals fmin(best, plain_distance()) bit for bit.
TEST(Path, NearerEqualsThePlainDistanceBitForBit)
{
    uint32_t r = 12345;
    auto uni = [&r](double lo, double hi) {
        r = r * 1664525u + 1013904223u;
        return lo + (hi - lo) * (r >> 8) / 16777216.0;
    };
    long checks = 0;
    for (int piece = 0; piece < 400; piece++) {
        sim_piece_t pc;
        pc.x0 = uni(-300.0, 300.0);
        pc.y0 = uni(-300.0, 300.0);
        pc.th0 = uni(-4.0, 4.0);
        int kind = piece % 4;
        pc.kappa = kind == 0 ? 0.0 : (piece % 3 ? 1.0 : -1.0) / uni(0.2, 30.0);
        double sweep = kind == 3 ? uni(M_PI, 2.5 * M_PI) : uni(0.0, M_PI);
        if (kind == 2 && piece % 5 == 0)
            sweep = M_PI; // exactly half a turn
        pc.length = kind == 0 ? uni(0.0, 20.0) : sweep / std::fabs(pc.kappa);
        pc.reverse = piece % 7 == 0;
        sim_piece_geom_t g;
        sim_piece_geom(&pc, &g);
        for (int k = 0; k < 300; k++) {
            double x, y;
            if (kind == 0 || k % 3 == 0) {
                x = pc.x0 + uni(-25.0, 25.0);
                y = pc.y0 + uni(-25.0, 25.0);
            } else {
                // On a boundary direction give or take up to ~1e-6 rad, at various radii.
                double a = (k % 2 ? g.a0 : g.a0 + g.sw) + (k % 5 ? 1.0 : 1e-7) * uni(-1e-8, 1e-8);
                double rho = std::fabs(g.r) * (k % 4 ? uni(0.0, 2.0) : 1.0 + uni(-1e-9, 1e-9));
                x = g.cx + rho * std::cos(a);
                y = g.cy + rho * std::sin(a);
            }
            double plain = plain_distance(&pc, &g, x, y);
            const double bests[] = {INFINITY,    plain,       plain * (1.0 + 1e-15),
                                    plain * 0.5, plain * 2.0, uni(0.0, 5.0)};
            for (double best : bests) {
                double got = sim_piece_geom_nearer(&pc, &g, x, y, best);
                EXPECT_EQ(bits(got), bits(std::fmin(best, plain)))
                    << "piece " << piece << " point " << k << " best " << best;
                checks++;
            }
        }
    }
    EXPECT_GT(checks, 0);
}

} // namespace
