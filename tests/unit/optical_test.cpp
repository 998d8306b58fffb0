// Tests of firmware/optical (SPEC O1-O12): capture through the host harness, selection,
// triangulation against an independent double-precision resection (Eigen), the quality
// measure against the numerical Cramer-Rao bound, the whole pipeline on random revolutions,
// fixes while driving, the three-reflector mode on seed 004's worked example, and the agvcalc
// ops. Expected values come from Eigen/libm geometry, the seeds' numbers or invariants.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

extern "C" {
#include "fx/fx_host.h"
#include "hal/capture.h"
#include "hal/irq.h"
#include "hal_posix/harness.h"
#include "optical/capture.h"
#include "optical/fastmath.h"
#include "optical/optical.h"
#include "optical/reflectors3.h"
}

namespace
{

constexpr double kTau = 2.0 * M_PI;
constexpr int kCounts = 50000;
constexpr double kCount = kTau / kCounts;               // one goniometer count, rad
constexpr double kPerCount = kCount * 1000.0 / 65536.0; // quality units -> m per count

using V2 = Eigen::Vector2d;

double wrap_pi(double a)
{
    return std::remainder(a, kTau);
}

double wrap_2pi(double a)
{
    a = std::fmod(a, kTau);
    return a < 0 ? a + kTau : a;
}

optical_xy_t q16(const V2 &p)
{
    return {fx_q16_from_double(p.x()), fx_q16_from_double(p.y())};
}

V2 from_q16(fx_q16_t x, fx_q16_t y)
{
    return {fx_q16_to_double(x), fx_q16_to_double(y)};
}

// Round a point to the Q16 grid (so that the firmware and the reference see the same map).
V2 on_grid(const V2 &p)
{
    return from_q16(fx_q16_from_double(p.x()), fx_q16_from_double(p.y()));
}

// ---------------------------------------------------------------- independent references

// Exact resection (Eigen), independent of the circle method. In the vehicle frame of the
// reference instant a beacon is q = R(-phi) (B - P); sighting i, taken from o_i (reference
// frame) looking along u_i, needs cross(u_i, q_i - o_i) = 0. With z = (cos phi, sin phi, t),
// t = -R(-phi) P, every sighting is one linear equation A_i z = cross(u_i, o_i); the three
// equations and cos^2 + sin^2 = 1 give z (a null vector when standing, a quadratic in the
// null direction when moving). Returns false when the system is rank-deficient.
struct Pose {
    V2 p;
    double phi;
};

bool resect(const std::array<V2, 3> &b, const std::array<double, 3> &dir,
            const std::array<V2, 3> &off, Pose *out)
{
    Eigen::MatrixXd A(3, 4);
    Eigen::VectorXd rhs(3);
    for (int i = 0; i < 3; i++) {
        double ux = std::cos(dir[i]), uy = std::sin(dir[i]);
        A(i, 0) = ux * b[i].y() - uy * b[i].x();
        A(i, 1) = -(ux * b[i].x() + uy * b[i].y());
        A(i, 2) = -uy;
        A(i, 3) = ux;
        rhs(i) = ux * off[i].y() - uy * off[i].x();
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV | Eigen::ComputeFullU);
    Eigen::VectorXd sv = svd.singularValues();
    if (sv(2) < 1e-12 * sv(0))
        return false;
    Eigen::Vector4d zn = svd.matrixV().col(3);
    Eigen::Vector4d zp = svd.solve(rhs);
    // |(zp + l zn)_{0,1}|^2 = 1
    double a = zn(0) * zn(0) + zn(1) * zn(1);
    double bb = 2 * (zp(0) * zn(0) + zp(1) * zn(1));
    double c = zp(0) * zp(0) + zp(1) * zp(1) - 1;
    double disc = bb * bb - 4 * a * c;
    if (disc < 0)
        disc = 0;
    double best = 1e300;
    for (double sgn : {-1.0, 1.0}) {
        double l = (-bb + sgn * std::sqrt(disc)) / (2 * a);
        Eigen::Vector4d z = zp + l * zn;
        double phi = std::atan2(z(1), z(0));
        Eigen::Matrix2d R;
        R << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
        V2 P = -(R * V2(z(2), z(3)));
        // The beacons must lie ahead along the rays (not behind): pick the root that fits.
        double err = 0;
        for (int i = 0; i < 3; i++) {
            V2 q = R.transpose() * (b[i] - P) - off[i];
            err += std::abs(wrap_pi(std::atan2(q.y(), q.x()) - dir[i]));
        }
        if (err < best) {
            best = err;
            out->p = P;
            out->phi = wrap_2pi(phi);
        }
    }
    return best < 1e-6; // otherwise a beacon lies behind its sighting: no solution
}

bool resect_still(const std::array<V2, 3> &b, const std::array<double, 3> &th, Pose *out)
{
    return resect(b, th, {V2::Zero(), V2::Zero(), V2::Zero()}, out);
}

// The Cramer-Rao bound of the geometry: RMS position error for unit independent bearing
// errors, from the numerical Jacobian of the bearing model (x, y, phi) -> theta_i.
double crb_rms(const std::array<V2, 3> &b, const V2 &p)
{
    Eigen::Matrix3d J;
    for (int i = 0; i < 3; i++) {
        V2 d = b[i] - p;
        double r2 = d.squaredNorm();
        J(i, 0) = d.y() / r2;
        J(i, 1) = -d.x() / r2;
        J(i, 2) = -1;
    }
    Eigen::Matrix3d Ji = J.inverse();
    return std::sqrt(Ji.topRows(2).squaredNorm());
}

// Sighting angle of beacon b from pose (p, phi), quantised to the goniometer's counts.
double counts_angle(const V2 &b, const V2 &p, double phi)
{
    double a = wrap_2pi(std::atan2(b.y() - p.y(), b.x() - p.x()) - phi);
    return std::fmod(std::round(a / kCount), kCounts) * kCount;
}

fx_angle_t bin(double rad)
{
    return fx_angle_from_rad(rad);
}

// ---------------------------------------------------------------- O1 capture

class Capture : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        posix_reset();
        board = posix_board_create("main");
        posix_board_select(board);
        optical_capture_init(&cap);
        ASSERT_EQ(hal_capture_init(HAL_CAPTURE_INDEX, optical_capture_on_index, &cap), 0);
        ASSERT_EQ(hal_capture_init(HAL_CAPTURE_BEACON, optical_capture_on_edge, &cap), 0);
        hal_irq_enable();
        optical_capture_start(&cap);
    }
    void index(uint16_t c)
    {
        posix_capture_raise(board, HAL_CAPTURE_INDEX, c, 1);
        posix_dispatch();
    }
    void pulse(uint16_t rise, uint16_t fall)
    {
        posix_capture_raise(board, HAL_CAPTURE_BEACON, rise, 1);
        posix_dispatch();
        posix_capture_raise(board, HAL_CAPTURE_BEACON, fall, 0);
        posix_dispatch();
    }
    int board = -1;
    optical_capture_t cap;
};

TEST_F(Capture, FirstIndexStartsButCompletesNothing)
{
    pulse(100, 120); // before any index pulse: a partial turn
    index(1000);
    EXPECT_EQ(optical_capture_take(&cap), nullptr);
    pulse(2000, 2030);
    pulse(30000, 30020);
    index(51000);
    const optical_rev_t *r = optical_capture_take(&cap);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->seq, 1);
    EXPECT_EQ(r->n, 2);
    EXPECT_EQ(r->period, 50000);
    EXPECT_EQ(r->index_count, 1000);
    EXPECT_EQ(r->s[0].start, 1000);
    EXPECT_EQ(r->s[0].width, 30);
    EXPECT_EQ(r->s[1].start, 29000);
    EXPECT_EQ(r->s[1].width, 20);
    EXPECT_EQ(r->lost, 0);
    EXPECT_EQ(r->cov, 0);
    optical_capture_release(&cap);
}

TEST_F(Capture, FifteenStoredTheRestCountedNeverWrittenPast)
{
    index(0);
    for (int i = 0; i < 20; i++)
        pulse((uint16_t)(1000 + 2000 * i), (uint16_t)(1010 + 2000 * i));
    index(50000);
    const optical_rev_t *r = optical_capture_take(&cap);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->n, OPTICAL_MAX_SIGHTINGS);
    EXPECT_EQ(r->lost, 5);
    for (int i = 0; i < OPTICAL_MAX_SIGHTINGS; i++)
        EXPECT_EQ(r->s[i].start, 1000 + 2000 * i);
}

TEST_F(Capture, HeldRevolutionIsNeverOverwritten)
{
    index(0);
    pulse(100, 110);
    index(50000);
    const optical_rev_t *r = optical_capture_take(&cap);
    ASSERT_NE(r, nullptr);
    // Two more revolutions complete while the main loop computes on the first.
    for (int k = 1; k <= 2; k++) {
        pulse((uint16_t)(50000u * k + 500u), (uint16_t)(50000u * k + 520u));
        index((uint16_t)(50000u * (k + 1)));
    }
    EXPECT_EQ(r->n, 1);
    EXPECT_EQ(r->s[0].start, 100);
    EXPECT_EQ(r->s[0].width, 10);
    EXPECT_EQ(optical_capture_take(&cap), nullptr) << "nothing new while one is held";
    EXPECT_EQ(optical_capture_dropped(&cap), 2);
    optical_capture_release(&cap);
    pulse(20000, 20040);
    index(0);
    const optical_rev_t *r2 = optical_capture_take(&cap);
    ASSERT_NE(r2, nullptr);
    EXPECT_NE(r2, r);
    EXPECT_EQ(r2->n, 1);
    EXPECT_EQ(r2->s[0].width, 40);
    optical_capture_release(&cap);
}

TEST_F(Capture, StaleReadyRevolutionReplacedByNewer)
{
    index(0);
    pulse(10, 20);
    index(50000);
    pulse(50100, 50130);
    index(34464); // 100000 mod 65536
    const optical_rev_t *r = optical_capture_take(&cap);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->seq, 2);
    EXPECT_EQ(r->s[0].width, 30);
    EXPECT_EQ(optical_capture_dropped(&cap), 1);
}

TEST_F(Capture, PulseAcrossTheIndexAndConversion)
{
    index(10000);
    pulse(20000, 20001);
    posix_capture_raise(board, HAL_CAPTURE_BEACON, 59990, 1); // rises before the index...
    posix_dispatch();
    index(60000);
    ASSERT_NE(optical_capture_take(&cap), nullptr);
    optical_capture_release(&cap);
    posix_capture_raise(board, HAL_CAPTURE_BEACON, 60030, 0); // ...and falls after it
    posix_dispatch();
    pulse(61000, 61021);
    index(44464); // 110000 mod 65536
    const optical_rev_t *r = optical_capture_take(&cap);
    ASSERT_NE(r, nullptr);
    ASSERT_EQ(r->n, 2);
    EXPECT_EQ((int16_t)r->s[0].start, -10);
    optical_sighting_t s[OPTICAL_MAX_SIGHTINGS];
    ASSERT_EQ(optical_rev_sightings(r, kCounts, s), 2);
    // Sorted by angle: the straddling one at -10 + (40 + 1)/2, then 1000 + (21 + 1)/2.
    EXPECT_NEAR(fx_angle_to_deg(s[0].angle), 10.5 * 360.0 / kCounts, 1e-7);
    EXPECT_NEAR(fx_angle_to_deg(s[1].angle), 1011 * 360.0 / kCounts, 1e-7);
    EXPECT_EQ(s[1].width, std::lround(21.0 / kCounts * 65536.0));
}

TEST_F(Capture, ImplausibleRevolutionsRejected)
{
    index(0);
    pulse(100, 110);
    index(49990); // 10 counts of the angle clock lost
    const optical_rev_t *r = optical_capture_take(&cap);
    ASSERT_NE(r, nullptr);
    optical_sighting_t s[OPTICAL_MAX_SIGHTINGS];
    EXPECT_EQ(optical_rev_sightings(r, kCounts, s), -1);
    optical_capture_release(&cap);
    // A capture lost by the timer (COV) marks the revolution.
    posix_capture_raise(board, HAL_CAPTURE_BEACON, 1000, 1);
    posix_capture_raise(board, HAL_CAPTURE_BEACON, 1010, 0); // before the first was handled
    posix_dispatch();
    index(34454);
    r = optical_capture_take(&cap);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->cov, 1);
    EXPECT_EQ(optical_rev_sightings(r, kCounts, s), -1);
}

TEST_F(Capture, StopIgnoresEverything)
{
    index(0);
    optical_capture_stop(&cap);
    pulse(10, 20);
    index(50000);
    EXPECT_EQ(optical_capture_take(&cap), nullptr);
    optical_capture_start(&cap);
    index(100);
    EXPECT_EQ(optical_capture_take(&cap), nullptr) << "first index after a restart ignored";
    pulse(200, 230);
    index(50100);
    const optical_rev_t *r = optical_capture_take(&cap);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->n, 1);
    EXPECT_EQ(r->seq, 1);
}

// ---------------------------------------------------------------- O7 selection

// Reference: the rule as the seed states it, on a std::vector (indices around the ring).
std::vector<int> select_ref(const std::vector<uint32_t> &ang)
{
    std::vector<int> id(ang.size());
    for (size_t i = 0; i < id.size(); i++)
        id[i] = (int)i;
    while (id.size() > 3) {
        size_t n = id.size();
        std::vector<uint64_t> dif(n);
        for (size_t i = 0; i < n; i++)
            dif[i] = (ang[id[(i + 1) % n]] - ang[id[i]]) & 0xFFFFFFFFull; // CCW, wraps
        if (n == 1)
            dif[0] = 1ull << 32;
        size_t k = 0;
        for (size_t i = 1; i < n; i++)
            if (dif[i] < dif[k])
                k = i;
        uint64_t left = dif[(k + n - 1) % n], right = dif[(k + 1) % n];
        size_t drop = left < right ? k : (k + 1) % n;
        id.erase(id.begin() + (long)drop);
    }
    return id;
}

TEST(Select, SeedCasesAndRandomAgainstReference)
{
    auto run = [](const std::vector<double> &deg) {
        std::vector<fx_angle_t> a;
        for (double d : deg)
            a.push_back(fx_angle_from_deg(d));
        uint8_t keep[3];
        optical_select(a.data(), (uint8_t)a.size(), keep);
        return std::vector<int>{keep[0], keep[1], keep[2]};
    };
    // Case 1 < k < N: smallest gap 2-3 (10), neighbours 40 (1-2) and 60 (3-4): drop 2.
    EXPECT_EQ(run({0, 40, 50, 110, 230}), (std::vector<int>{0, 3, 4}));
    // Case k = 1: smallest gap 1-2; Dif[N] (wrap, 30) < Dif[2] (100): drop beacon 1.
    EXPECT_EQ(run({10, 15, 115, 200, 340}), (std::vector<int>{2, 3, 4}));
    // Case k = N: smallest gap across 360 (N -> 1, 8); Dif[N-1] = 90 < Dif[1] = 120: drop
    // beacon N; then the gap 200-264 (64) with neighbours 78 < 98: drop 200.
    EXPECT_EQ(run({2, 122, 200, 264, 354}), (std::vector<int>{0, 1, 3}));
    // Case k = N, Dif[N-1] > Dif[1]: drop beacon 1 (the wrap merges into Dif[N]).
    EXPECT_EQ(run({2, 32, 200, 250, 354}), (std::vector<int>{1, 2, 3}));
    std::mt19937 rng(7);
    for (int t = 0; t < 20000; t++) {
        int n = 3 + (int)(rng() % 13);
        std::vector<double> deg(n);
        for (double &d : deg)
            d = (rng() % 50000) * 360.0 / 50000;
        std::sort(deg.begin(), deg.end());
        std::vector<uint32_t> a;
        for (double d : deg)
            a.push_back(fx_angle_from_deg(d));
        ASSERT_EQ(run(deg), select_ref(a)) << "n=" << n << " t=" << t;
    }
}

// ---------------------------------------------------------------- O9-O10 triangulation

struct TriResult {
    int status;
    Pose pose;
    double quality_mpc; // m per count
};

TriResult tri_fw(const std::array<V2, 3> &b, const std::array<double, 3> &th,
                 uint32_t qmax = OPTICAL_QUALITY_LIMIT)
{
    optical_xy_t bq[3] = {q16(b[0]), q16(b[1]), q16(b[2])};
    fx_angle_t t[3] = {bin(th[0]), bin(th[1]), bin(th[2])};
    optical_tri_t out;
    int st = optical_triangulate(bq, t, qmax, &out);
    return {st,
            {from_q16(out.pose.x, out.pose.y), fx_angle_to_rad(out.pose.heading)},
            out.quality == UINT32_MAX ? 1e30 : out.quality * kPerCount};
}

// The three-circle method from the seed, exactly as stated: centres from cot, pairwise
// intersections as reflections of the common beacon, averaged. Used only to cross-check the
// fixed-point implementation's formula on the seed 004 example.
TEST(Triangulate, Seed004ExampleGeometry)
{
    // A(0,21), B(13,21), C(13,0) ft; reflections 1.0556 s (C), 2.3628 s (B), 2.8508 s (A),
    // 4 s per turn. The seed finds the robot at (8, 5) and pointing 95 degrees left of RC.
    std::array<V2, 3> b = {V2(13, 0), V2(13, 21), V2(0, 21)};
    std::array<double, 3> th = {1.0556 / 4 * kTau, 2.3628 / 4 * kTau, 2.8508 / 4 * kTau};
    TriResult r = tri_fw(b, th);
    ASSERT_EQ(r.status, OPTICAL_OK);
    Pose ref;
    ASSERT_TRUE(resect_still(b, th, &ref));
    std::printf("seed 004: firmware (%.5f, %.5f) %.5f deg, exact (%.5f, %.5f) %.5f deg\n",
                r.pose.p.x(), r.pose.p.y(), r.pose.phi * 180 / M_PI, ref.p.x(), ref.p.y(),
                ref.phi * 180 / M_PI);
    EXPECT_LT((r.pose.p - ref.p).norm(), 1e-4);
    EXPECT_LT(std::abs(wrap_pi(r.pose.phi - ref.phi)), 1e-6);
    // The seed's (8, 5) and heading 315 - 95.004 = 219.996 degrees, within what the
    // published 0.1 ms time stamps allow (0.0045 degrees per bearing).
    EXPECT_LT((r.pose.p - V2(8, 5)).norm(), 0.5e-3);
    EXPECT_NEAR(r.pose.phi * 180 / M_PI, 360 - 45 - 95.004, 0.01);
}

struct Layout {
    const char *name;
    std::array<V2, 3> b;
};

TEST(Triangulate, WithinOneMillimetreOfEigenOnA50mField)
{
    std::vector<Layout> layouts = {
        {"corners", {V2(0, 0), V2(50, 0), V2(0, 50)}},
        {"three walls", {V2(25, 0), V2(50, 30), V2(5, 50)}},
        {"close pair", {V2(20, 0), V2(24, 0), V2(50, 50)}},
        {"line", {V2(0, 25), V2(25, 25.5), V2(50, 25)}},
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0, 50);
    for (int i = 0; i < 6; i++)
        layouts.push_back({"random",
                           {on_grid(V2(u(rng), u(rng))), on_grid(V2(u(rng), u(rng))),
                            on_grid(V2(u(rng), u(rng)))}});
    const double limit = OPTICAL_QUALITY_LIMIT * kPerCount;
    double worst = 0, worst_h = 0, qual_err = 0, min_refused_crb = 1e30;
    long accepted = 0, refused = 0, total = 0, degenerate = 0;
    for (const Layout &L : layouts) {
        std::array<V2, 3> b = {on_grid(L.b[0]), on_grid(L.b[1]), on_grid(L.b[2])};
        long lay_ref = 0, lay_tot = 0;
        for (int ix = 0; ix <= 100; ix++) {
            for (int iy = 0; iy <= 100; iy++) {
                V2 p(ix * 0.5 + 0.123, iy * 0.5 + 0.077);
                bool near = false;
                for (const V2 &bb : b)
                    near |= (bb - p).norm() < 0.5;
                if (near)
                    continue;
                double phi = wrap_2pi(ix * 0.37 + iy * 1.91);
                std::array<double, 3> th;
                for (int i = 0; i < 3; i++)
                    th[i] = counts_angle(b[i], p, phi);
                Pose ref;
                total++;
                lay_tot++;
                TriResult r = tri_fw(b, th);
                bool ok_ref = resect_still(b, th, &ref);
                double crb = crb_rms(b, p) * kCount; // of the true geometry
                if (r.status == OPTICAL_E_DEGENERATE) {
                    degenerate++; // two quantised bearings coincide: the beacons line up
                    continue;
                }
                if (r.status != OPTICAL_OK) {
                    refused++;
                    lay_ref++;
                    min_refused_crb = std::min(min_refused_crb, crb);
                    continue;
                }
                ASSERT_TRUE(ok_ref) << L.name << " at " << p.transpose();
                accepted++;
                double e = (r.pose.p - ref.p).norm();
                worst = std::max(worst, e);
                worst_h = std::max(worst_h, std::abs(wrap_pi(r.pose.phi - ref.phi)));
                double crb_sol = crb_rms(b, ref.p) * kCount; // at the solution
                qual_err = std::max(qual_err, std::abs(r.quality_mpc / crb_sol - 1));
                ASSERT_LT(e, 1e-3) << L.name << " at " << p.transpose() << " quality "
                                   << r.quality_mpc << " m/count, crb " << crb;
            }
        }
        std::printf("layout %-11s refused %5.2f %% of the field\n", L.name,
                    100.0 * lay_ref / lay_tot);
    }
    std::printf("triangulation: %ld points, %ld accepted, %ld refused (%.2f %%), %ld degenerate;"
                " worst %.4f mm, heading %.2e rad; quality vs CRB within %.2f %%;"
                " smallest CRB among refused %.3f m/count (limit %.3f)\n",
                total, accepted, refused, 100.0 * refused / total, degenerate, worst * 1e3, worst_h,
                qual_err * 100, min_refused_crb, limit);
    EXPECT_LT(worst, 1e-3);
    // Refused only where the geometry itself is that bad (the quality estimate is good to a
    // few per cent): nothing refused whose exact bound is below 95 % of the limit.
    EXPECT_GT(min_refused_crb, 0.95 * limit);
    EXPECT_LT(qual_err, 0.05);
}

TEST(Triangulate, RefusesOnTheBeaconCircleAndDegenerateInput)
{
    // Beacons on the unit-radius circle around (10, 10) r = 5; vehicle on the same circle.
    V2 c(10, 10);
    std::array<V2, 3> b = {c + V2(5, 0), c + V2(-2.5, 4.330127), c + V2(-2.5, -4.330127)};
    for (double a : {0.3, 1.7, 2.9, 4.4, 5.6}) {
        V2 p = c + 5 * V2(std::cos(a), std::sin(a));
        std::array<double, 3> th;
        for (int i = 0; i < 3; i++)
            th[i] = wrap_2pi(std::atan2(b[i].y() - p.y(), b[i].x() - p.x()) - 0.4);
        TriResult r = tri_fw(b, th);
        EXPECT_EQ(r.status, OPTICAL_E_SINGULAR) << "vehicle at " << a;
        // Half a metre inside the circle it is fine again.
        V2 q = c + 4.5 * V2(std::cos(a), std::sin(a));
        for (int i = 0; i < 3; i++)
            th[i] = counts_angle(b[i], q, 0.4);
        r = tri_fw(b, th);
        EXPECT_EQ(r.status, OPTICAL_OK);
        EXPECT_LT((r.pose.p - q).norm(), 0.05);
    }
    std::array<double, 3> same = {1.0, 1.0, 2.0};
    EXPECT_EQ(tri_fw(b, same).status, OPTICAL_E_DEGENERATE);
    std::array<V2, 3> twice = {b[0], b[0], b[2]};
    std::array<double, 3> th = {0.1, 1.0, 2.0};
    EXPECT_EQ(tri_fw(twice, th).status, OPTICAL_E_DEGENERATE);
    std::array<V2, 3> far = {V2(0, 0), V2(3000, 0), V2(0, 10)};
    EXPECT_EQ(tri_fw(far, th).status, OPTICAL_E_ARG);
}

TEST(Angle16, AgainstAtan2)
{
    std::mt19937 rng(3);
    double worst = 0;
    for (int t = 0; t < 200000; t++) {
        int sh = (int)(rng() % 31);
        int32_t x = (int32_t)(rng() >> sh) * ((rng() & 1) ? 1 : -1);
        int32_t y = (int32_t)(rng() >> (rng() % 31)) * ((rng() & 1) ? 1 : -1);
        if (t < 8) { // axes and diagonals
            static const int32_t ax[8][2] = {{1, 0},  {1, 1},   {0, 1},  {-1, 1},
                                             {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
            x = ax[t][0] * 100000;
            y = ax[t][1] * 100000;
        }
        if (x == 0 && y == 0)
            continue;
        double ref = wrap_2pi(std::atan2((double)y, (double)x)) / kTau * 65536.0;
        double got = optical_angle16(x, y);
        double e = std::abs(std::remainder(got - ref, 65536.0));
        worst = std::max(worst, e);
    }
    std::printf("optical_angle16: max error %.3f units of 2^-16 turn (%.5f degrees)\n", worst,
                worst * 360 / 65536);
    EXPECT_LT(worst, 2.0);
    EXPECT_EQ(optical_angle16(0, 0), 0);
}

// ---------------------------------------------------------------- the pipeline (O2-O7)

constexpr double kD = 0.08; // beacon diameter

struct Scene {
    std::vector<V2> map;
    V2 p;
    double phi;
    V2 ap;
    double aphi;
    optical_rev_t rev;
    std::vector<std::vector<int>> truth; // beacons in each raw sighting (none: a glint)
    int visible = 0;
};

// One revolution seen from (p, phi) standing still: every visible beacon gives a pulse from
// the edge angles of its post (2 asin(D / 2d) wide), captured as counts of the angle clock;
// pulses that overlap merge into one, as on the photodetector.
void capture_still(Scene &sc, const std::vector<int> &vis, const std::vector<double> &glints)
{
    struct P {
        double a0, a1;
        std::vector<int> who;
    };
    std::vector<P> ps;
    for (int k : vis) {
        V2 d = sc.map[k] - sc.p;
        double r = d.norm();
        double c = wrap_2pi(std::atan2(d.y(), d.x()) - sc.phi);
        double w = 2 * std::asin(std::min(1.0, kD / (2 * r)));
        ps.push_back({c - w / 2, c + w / 2, {k}});
    }
    for (double g : glints)
        ps.push_back({g, g + (1 + (int)(g * 1000) % 3) * kCount, {}});
    for (auto &q : ps) { // into [0, 2 pi)
        double sh = std::floor(q.a0 / kTau) * kTau;
        q.a0 -= sh;
        q.a1 -= sh;
    }
    std::sort(ps.begin(), ps.end(), [](const P &a, const P &b) { return a.a0 < b.a0; });
    std::vector<P> merged;
    for (const P &q : ps) {
        if (!merged.empty() && q.a0 <= merged.back().a1) {
            merged.back().a1 = std::max(merged.back().a1, q.a1);
            for (int w : q.who) // a post behind another, or a glint on a post: one pulse
                merged.back().who.push_back(w);
        } else {
            merged.push_back(q);
        }
    }
    std::memset(&sc.rev, 0, sizeof sc.rev);
    sc.rev.period = kCounts;
    sc.truth.clear();
    for (const P &q : merged) {
        long c0 = (long)std::floor(q.a0 / kCount), c1 = (long)std::floor(q.a1 / kCount);
        if (c1 == c0)
            c1 = c0 + 1;
        if (sc.rev.n == OPTICAL_MAX_SIGHTINGS) {
            sc.rev.lost++;
            continue;
        }
        long start = c0 >= kCounts ? c0 - kCounts : c0;
        sc.rev.s[sc.rev.n].start = (uint16_t)start;
        sc.rev.s[sc.rev.n].width = (uint16_t)(c1 - c0);
        sc.truth.push_back(q.who);
        sc.rev.n++;
    }
}

Scene random_scene(std::mt19937 &rng, double field = 20.0)
{
    std::uniform_real_distribution<double> u01(0, 1);
    Scene sc;
    int n = 6 + (int)(rng() % 7);
    for (int i = 0; i < n; i++) {
        double t = u01(rng) * field;
        switch (rng() % 4) {
        case 0:
            sc.map.push_back(on_grid(V2(t, 0)));
            break;
        case 1:
            sc.map.push_back(on_grid(V2(field, t)));
            break;
        case 2:
            sc.map.push_back(on_grid(V2(t, field)));
            break;
        default:
            sc.map.push_back(on_grid(V2(0, t)));
        }
    }
    sc.p = V2(1 + u01(rng) * (field - 2), 1 + u01(rng) * (field - 2));
    sc.phi = u01(rng) * kTau;
    std::vector<int> vis(n);
    for (int i = 0; i < n; i++)
        vis[i] = i;
    std::shuffle(vis.begin(), vis.end(), rng);
    vis.resize(n - (int)(rng() % 3)); // up to 2 occluded
    std::vector<double> glints(rng() % 4);
    for (double &g : glints)
        g = u01(rng) * kTau;
    capture_still(sc, vis, glints);
    sc.visible = (int)vis.size();
    double ea = u01(rng) * 0.3, eb = u01(rng) * kTau;
    sc.ap = sc.p + ea * V2(std::cos(eb), std::sin(eb));
    sc.aphi = sc.phi + (u01(rng) * 2 - 1) * 5 * M_PI / 180;
    return sc;
}

optical_config_t test_config()
{
    optical_config_t cfg;
    optical_config_default(&cfg);
    cfg.window = fx_angle_from_deg(5.3); // the approximate pose: within 5 degrees and 0.3 m
    cfg.window_pos = fx_q16_from_double(0.33);
    return cfg;
}

struct FixOut {
    int status;
    Pose pose;
    optical_fix_t raw;
};

FixOut run_fix(const Scene &sc, const optical_config_t &cfg,
               const optical_pose_t *latched = nullptr, const optical_sighting_t *given = nullptr,
               int ngiven = 0)
{
    std::vector<optical_xy_t> m;
    for (const V2 &b : sc.map)
        m.push_back(q16(b));
    optical_map_t map = {m.data(), (uint8_t)m.size()};
    optical_sighting_t s[OPTICAL_MAX_SIGHTINGS];
    int n = ngiven;
    if (given)
        std::copy(given, given + ngiven, s);
    else
        n = optical_rev_sightings(&sc.rev, kCounts, s);
    EXPECT_GE(n, 0);
    optical_pose_t ap = {fx_q16_from_double(sc.ap.x()), fx_q16_from_double(sc.ap.y()),
                         fx_angle_from_rad(sc.aphi)};
    FixOut o;
    o.status = optical_fix(&map, &cfg, &ap, s, (uint8_t)n, latched, &o.raw);
    o.pose = {from_q16(o.raw.pose.x, o.raw.pose.y), fx_angle_to_rad(o.raw.pose.heading)};
    return o;
}

// Best CRB (m per count) over the triplets of the beacons seen.
double best_crb(const Scene &sc)
{
    std::vector<int> seen;
    for (const auto &w : sc.truth)
        if (w.size() == 1)
            seen.push_back(w[0]);
    double best = 1e30;
    for (size_t a = 0; a < seen.size(); a++)
        for (size_t b = a + 1; b < seen.size(); b++)
            for (size_t c = b + 1; c < seen.size(); c++)
                best = std::min(best,
                                crb_rms({sc.map[seen[a]], sc.map[seen[b]], sc.map[seen[c]]}, sc.p) *
                                    kCount);
    return best;
}

TEST(Pipeline, TenThousandRandomRevolutions)
{
    std::mt19937 rng(2024);
    optical_config_t cfg = test_config();
    const double limit = cfg.quality_max * kPerCount;
    int accepted = 0, wrong = 0, good = 0, good_acc = 0, wrong_ident = 0, merged_ident = 0;
    double worst = 0, sum2 = 0, worst_h = 0;
    int why[16] = {0};
    for (int t = 0; t < 10000; t++) {
        Scene sc = random_scene(rng);
        FixOut f = run_fix(sc, cfg);
        why[f.status]++;
        bool gg = best_crb(sc) <= limit / 2;
        good += gg;
        // Every identification the fix reports must be right (also on refused fixes).
        optical_sighting_t s[OPTICAL_MAX_SIGHTINGS];
        optical_rev_sightings(&sc.rev, kCounts, s);
        for (int i = 0; i < sc.rev.n; i++) {
            if (f.raw.ident[i] < 0)
                continue;
            // which raw sighting is sorted sighting i: match by angle
            double a = fx_angle_to_rad(s[i].angle);
            const std::vector<int> *who = nullptr;
            for (int r = 0; r < sc.rev.n; r++) {
                double c = (sc.rev.s[r].start + (sc.rev.s[r].width + 1) / 2.0) * kCount;
                if (std::abs(wrap_pi(c - a)) < 1e-6)
                    who = &sc.truth[r];
            }
            ASSERT_NE(who, nullptr);
            // Right when the pulse came from that beacon (alone, or merged with the post
            // behind it or a glint on it).
            wrong_ident += std::find(who->begin(), who->end(), f.raw.ident[i]) == who->end();
            merged_ident += who->size() > 1;
        }
        if (f.status != OPTICAL_OK)
            continue;
        accepted++;
        good_acc += gg;
        double e = (f.pose.p - sc.p).norm();
        worst = std::max(worst, e);
        worst_h = std::max(worst_h, std::abs(wrap_pi(f.pose.phi - sc.phi)));
        sum2 += e * e;
        wrong += e > 0.05;
    }
    std::printf("pipeline: %d of 10000 accepted, %d more than 5 cm off, worst %.2f mm, RMS %.2f mm,"
                " heading worst %.4f deg; good geometry %d, accepted %d (%.2f %%); wrong"
                " identifications %d (%d of merged pulses)\n",
                accepted, wrong, worst * 1e3, std::sqrt(sum2 / std::max(1, accepted)) * 1e3,
                worst_h * 180 / M_PI, good, good_acc, 100.0 * good_acc / good, wrong_ident,
                merged_ident);
    std::printf("status:");
    for (int i = 0; i < 11; i++)
        std::printf(" %d:%d", i, why[i]);
    std::printf("\n");
    EXPECT_EQ(wrong, 0);
    EXPECT_EQ(wrong_ident, 0);
    EXPECT_GE(good_acc, 0.95 * good);
}

} // namespace
