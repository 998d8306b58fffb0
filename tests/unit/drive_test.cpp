// drive_test.cpp - the drive module (SPEC D1-D9) against independent references:
//  - the seed's own case equations (thesis ch. 4, rebuilt with the acos form: psi =
//    acos((cos phi + K sin phi + 1) / (2 sqrt(1 + K^2))) +- beta, ...) in double precision,
//    a different derivation from the solver's closed forms, decide which configurations are
//    solvable and which case applies;
//  - every answer is proved by integrating its segments in double precision from `from`
//    (exact arc/straight geometry, written here, nothing shared with the firmware).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <vector>

extern "C" {
#include "drive/drive.h"
#include "drive/drive_cmd.h"
#include "drive/drive_path.h"
#include "drive/drive_proto.h"
#include "drive/drive_seq.h"
#include "fx/fx_host.h"
#include "hal_posix/drive_port_posix.h"
#include "hal_posix/harness.h"
}

namespace
{

constexpr double kPi = 3.14159265358979323846;

double wrap_pi(double a)
{
    a = std::fmod(a + kPi, 2 * kPi);
    if (a < 0)
        a += 2 * kPi;
    return a - kPi;
}

struct Pose {
    double x, y, th; // metres, radians (the vehicle's heading)
};

struct Seg {
    double k; // curvature 1/m, vehicle frame, left positive (0: straight)
    double s; // rear-axle length, m
};

// Follow segments from p in double precision. Forward: heading changes by s*k and the point
// moves along the heading; reverse: the point moves against the heading and the heading
// changes by -s*k (a rear-axle bicycle driven backwards with the same steering).
Pose follow(Pose p, const std::vector<Seg> &segs, bool reverse)
{
    for (const Seg &g : segs) {
        double dir = reverse ? -1.0 : 1.0;
        double mu = p.th + (reverse ? kPi : 0.0); // direction of travel
        double km = dir * g.k;                    // curvature along the travel
        if (g.k == 0.0) {
            p.x += g.s * std::cos(mu);
            p.y += g.s * std::sin(mu);
        } else {
            double mu2 = mu + g.s * km;
            p.x += (std::sin(mu2) - std::sin(mu)) / km;
            p.y += -(std::cos(mu2) - std::cos(mu)) / km;
            p.th += g.s * km;
        }
    }
    return p;
}

// ------------------------------------------------------------------ the seed's equations

struct SeedRef {
    std::string kase; // "1".."5", "straight", or "refuse"
    double r;         // the case's radius (inf for straight)
    double margin;    // relative distance of the decision from a boundary (small: ambiguous)
};

// Seed 000, ch. 4 and appendix B (COMPUTE_PARAMETERS, TWOC1/2/3, ONEC1/2, DRIVE), with the
// OCR damage repaired: case 1 psi = acos((cos phi + K sin phi + 1) / (2 sqrt(1 + K^2))) + beta,
// r = a / (cos phi - 2 cos psi + 1); case 2 the same acos - beta, r = a / (2 cos psi - cos phi
// - 1); case 3 psi = acos((K sin phi - cos phi - 1) / (2 sqrt(1 + K^2))) - beta, r = a / (2 cos
// psi + cos phi + 1); case 4 r = d / tan(phi/2); case 5 r = h / tan(phi/2); d = P - a cot phi,
// h = a / sin phi, a = |T|, K = tan beta = |T| / P.
SeedRef seed_reference(Pose from, Pose to, double rmin, bool reverse)
{
    double t1 = from.th + (reverse ? kPi : 0), t2 = to.th + (reverse ? kPi : 0);
    Eigen::Vector2d A(std::cos(t1), std::sin(t1)), B(std::cos(t2), std::sin(t2));
    Eigen::Vector2d D(to.x - from.x, to.y - from.y);
    double T = A.x() * D.y() - A.y() * D.x(), P = A.dot(D);
    double C = A.x() * B.y() - A.y() * B.x(), S = A.dot(B);
    if (P <= 0 || S < 0)
        return {"refuse", 0, std::min(std::fabs(P) / D.norm(), std::fabs(S))};
    if (std::fabs(T) < 1e-9 && std::fabs(C) < 1e-9) // the seed's THRESH test
        return {"straight", INFINITY, 1.0};
    double phi = std::atan2(std::fabs(C), S), beta = std::atan2(std::fabs(T), P);
    double a = std::fabs(T), K = std::tan(beta);
    double root = 2 * std::sqrt(1 + K * K);
    bool opposite = (T > 0 && C < 0) || (T < 0 && C > 0);
    auto dbl = [&](const char *k, double r, double m) {
        double mm = std::min(m, std::fabs(r - rmin) / rmin);
        if (r < rmin)
            return SeedRef{"refuse", r, mm};
        return SeedRef{k, r, mm};
    };
    if (opposite) {
        double psi = std::acos((K * std::sin(phi) - std::cos(phi) - 1) / root) - beta;
        double r = a / (2 * std::cos(psi) + std::cos(phi) + 1);
        return dbl("3", r, 1.0);
    }
    double m2 = std::fabs(phi - 2 * beta);
    if (phi < 2 * beta) {
        double d = P - a / std::tan(phi), r4 = d / std::tan(phi / 2);
        double m4 = std::fabs(r4 - rmin) / rmin;
        if (phi > 0 && r4 >= rmin)
            return {"4", r4, std::min(m2, m4)};
        double psi = std::acos((std::cos(phi) + K * std::sin(phi) + 1) / root) + beta;
        double r = a / (std::cos(phi) - 2 * std::cos(psi) + 1);
        return dbl("1", r, phi > 0 ? std::min(m2, m4) : m2);
    }
    double h = a / std::sin(phi), r5 = h / std::tan(phi / 2);
    double m5 = std::fabs(r5 - rmin) / rmin;
    if (r5 >= rmin)
        return {"5", r5, std::min(m2, m5)};
    double psi = std::acos((std::cos(phi) + K * std::sin(phi) + 1) / root) - beta;
    double r = a / (2 * std::cos(psi) - std::cos(phi) - 1);
    return dbl("2", r, std::min(m2, m5));
}

// ------------------------------------------------------------------ solver harness

drive_pose_t to_fx(Pose p)
{
    return {fx_q16_from_double(p.x), fx_q16_from_double(p.y), fx_angle_from_rad(p.th)};
}

Pose from_fx(drive_pose_t p)
{
    return {fx_q16_to_double(p.x), fx_q16_to_double(p.y), fx_angle_to_rad(p.heading)};
}

double curv_to_double(int32_t k)
{
    return (double)k / (double)DRIVE_CURV_ONE;
}

std::vector<Seg> segs_of(const drive_solution_t &sol)
{
    std::vector<Seg> v;
    for (const drive_segment_t &g : sol.seg)
        v.push_back({curv_to_double(g.curvature), fx_q16_to_double(g.length)});
    return v;
}

const char *case_name(drive_case_t c)
{
    static const char *names[] = {"straight", "1", "2", "3", "4", "5"};
    return names[c];
}

struct Miss {
    double pos, head; // m, degrees
};

// Integrate a solution from the (quantised) start and compare with the (quantised) target.
Miss miss_of(const drive_pose_t &from, const drive_pose_t &to, const drive_solution_t &sol,
             bool reverse)
{
    Pose f = from_fx(from), t = from_fx(to);
    Pose e = follow(f, segs_of(sol), reverse);
    return {std::hypot(e.x - t.x, e.y - t.y), std::fabs(wrap_pi(e.th - t.th)) * 180 / kPi};
}

// Poses every length / n along a double arc from `a`, in double precision (n + 1 of them).
std::vector<Pose> sample_solution(Pose a, const drive_solution_t &sol, bool reverse, int n)
{
    std::vector<Pose> v;
    double s0 = fx_q16_to_double(sol.seg[0].length), s1 = fx_q16_to_double(sol.seg[1].length);
    for (int j = 0; j <= n; j++) {
        double t = (s0 + s1) * j / n;
        std::vector<Seg> part = {{curv_to_double(sol.seg[0].curvature), std::min(t, s0)}};
        if (t > s0)
            part.push_back({curv_to_double(sol.seg[1].curvature), t - s0});
        v.push_back(follow(a, part, reverse));
    }
    return v;
}

// The same along every double arc of a nominal leg from `a` (a split leg's second part from
// its inserted pose, as the firmware lays its secondary points).
std::vector<Pose> sample_leg(Pose a, const drive_leg_t &leg, bool reverse, int n)
{
    std::vector<Pose> v = sample_solution(a, leg.sol[0], reverse, n);
    if (leg.parts == 2) {
        std::vector<Pose> w = sample_solution(from_fx(leg.via), leg.sol[1], reverse, n);
        v.insert(v.end(), w.begin(), w.end());
    }
    return v;
}

struct Config {
    Pose from, to;
    double rmin;
    bool reverse;
};

// The solvable test domain: target ahead (bearing within +-89.9 degrees of the
// direction of travel), heading change under 90 degrees, 0.3 - 5 m away, minimum radius
// 0.25 - 1 m, anywhere in a 200 m field, forward and reverse.
Config random_config(std::mt19937_64 &rng)
{
    std::uniform_real_distribution<double> U(0, 1);
    Config c;
    c.rmin = 0.25 + 0.75 * U(rng);
    double dist = 0.3 + 4.7 * U(rng);
    double bearing = (-89.9 + 179.8 * U(rng)) * kPi / 180;
    double dth = (-89.9 + 179.8 * U(rng)) * kPi / 180;
    c.reverse = U(rng) < 0.25;
    c.from = {-100 + 200 * U(rng), -100 + 200 * U(rng), 2 * kPi * U(rng)};
    double travel = c.from.th + (c.reverse ? kPi : 0);
    c.to = {c.from.x + dist * std::cos(travel + bearing),
            c.from.y + dist * std::sin(travel + bearing), c.from.th + dth};
    return c;
}

} // namespace

TEST(DriveSolve, RandomSolvableConfigurationsLandOnTarget)
{
    std::mt19937_64 rng(20240607);
    const int n_target = 100000;
    int n = 0, refused = 0, ambiguous = 0, case_mismatch = 0;
    int per_case[6] = {0};
    double worst_pos = 0, worst_head = 0, worst_rad = 1e9;
    while (n < n_target) {
        Config c = random_config(rng);
        drive_pose_t f = to_fx(c.from), t = to_fx(c.to);
        fx_q16_t rmin = fx_q16_from_double(c.rmin);
        SeedRef ref = seed_reference(from_fx(f), from_fx(t), fx_q16_to_double(rmin), c.reverse);
        if (ref.kase == "refuse") {
            refused++;
            continue; // not solvable by the seed's cases: the next test covers it
        }
        n++;
        drive_solution_t sol;
        drive_status_t st = drive_solve(&f, &t, rmin, c.reverse, &sol, nullptr);
        bool amb = ref.margin < 1e-6;
        if (amb)
            ambiguous++;
        if (st != DRIVE_OK) {
            ASSERT_TRUE(amb) << "refused a solvable configuration: " << drive_status_text(st)
                             << " case " << ref.kase << " r=" << ref.r;
            continue;
        }
        if (ref.kase != case_name(sol.kase)) {
            case_mismatch++;
            ASSERT_TRUE(amb) << "case " << case_name(sol.kase) << " vs seed " << ref.kase
                             << " margin " << ref.margin;
        }
        per_case[sol.kase]++;
        Miss m = miss_of(f, t, sol, c.reverse);
        worst_pos = std::max(worst_pos, m.pos);
        worst_head = std::max(worst_head, m.head);
        ASSERT_LT(m.pos, 5e-5) << "case " << case_name(sol.kase);   // drive.h: 0.05 mm
        ASSERT_LT(m.head, 0.005) << "case " << case_name(sol.kase); // and 0.005 degrees
        for (const drive_segment_t &g : sol.seg) {
            if (g.curvature == 0)
                continue;
            double r = 1.0 / std::fabs(curv_to_double(g.curvature));
            worst_rad = std::min(worst_rad, r / fx_q16_to_double(rmin));
            ASSERT_GE(r, fx_q16_to_double(rmin));
        }
    }
    std::printf("solvable configurations: %d (cases straight/1/2/3/4/5: %d/%d/%d/%d/%d/%d), "
                "seed refusals skipped: %d, near a case boundary: %d, case differs there: %d\n",
                n, per_case[0], per_case[1], per_case[2], per_case[3], per_case[4], per_case[5],
                refused, ambiguous, case_mismatch);
    std::printf("worst landing error: %.3g mm, %.3g deg; smallest radius / minimum: %.9f\n",
                worst_pos * 1e3, worst_head, worst_rad);
    RecordProperty("worst_pos_mm", std::to_string(worst_pos * 1e3));
    RecordProperty("worst_head_deg", std::to_string(worst_head));
}

// Anything goes: any bearing and heading change, 1 mm - 100 m, minimum radii in and out of
// range, near-straight and degenerate poses. Every answer is a refusal with a reason or a
// path that lands within the floors with every radius >= the minimum.
TEST(DriveSolve, OutsideTheDomainRefusesOrLands)
{
    std::mt19937_64 rng(77);
    std::uniform_real_distribution<double> U(0, 1);
    int ok = 0, refusals[DRIVE_ERR_TURN + 1] = {0};
    double worst_pos = 0, worst_head = 0;
    for (int i = 0; i < 100000; i++) {
        Config c;
        int kind = i % 4;
        double dist = std::exp(std::log(0.001) + (std::log(100.0) - std::log(0.001)) * U(rng));
        double bearing = (-180 + 360 * U(rng)) * kPi / 180;
        double dth = (-180 + 360 * U(rng)) * kPi / 180;
        c.rmin = std::exp(std::log(0.1) + (std::log(200.0) - std::log(0.1)) * U(rng));
        if (kind == 1) { // near straight: tiny lateral offsets and heading changes
            bearing = (U(rng) - 0.5) * 1e-4;
            dth = (U(rng) - 0.5) * std::pow(10.0, -2 - 6 * U(rng));
            if (U(rng) < 0.3)
                dth = 0;
        } else if (kind == 2) { // the seed's domain, wider distances and radii
            bearing = (-89 + 178 * U(rng)) * kPi / 180;
            dth = (-90 + 180 * U(rng)) * kPi / 180;
        } else if (kind == 3) { // exact degenerate geometry on the Q16 grid
            bearing = std::round(U(rng) * 8) * kPi / 4;
            dth = std::round((U(rng) - 0.5) * 4) * kPi / 4;
            dist = std::round(dist * 64) / 64;
        }
        c.reverse = U(rng) < 0.3;
        c.from = {-30000 + 60000 * U(rng), -30000 + 60000 * U(rng), 2 * kPi * U(rng)};
        if (kind == 3)
            c.from.th = std::round(U(rng) * 4) * kPi / 2;
        double travel = c.from.th + (c.reverse ? kPi : 0);
        c.to = {c.from.x + dist * std::cos(travel + bearing),
                c.from.y + dist * std::sin(travel + bearing), c.from.th + dth};
        drive_pose_t f = to_fx(c.from), t = to_fx(c.to);
        fx_q16_t rmin = fx_q16_from_double(c.rmin);
        drive_solution_t sol;
        drive_status_t st = drive_solve(&f, &t, rmin, c.reverse, &sol, nullptr);
        if (st != DRIVE_OK) {
            ASSERT_LE((int)st, (int)DRIVE_ERR_TURN);
            ASSERT_GT(std::string(drive_status_text(st)).size(), 3u);
            refusals[st]++;
            continue;
        }
        ok++;
        Miss m = miss_of(f, t, sol, c.reverse);
        worst_pos = std::max(worst_pos, m.pos);
        worst_head = std::max(worst_head, m.head);
        ASSERT_LT(m.pos, 5e-4) << "kind " << kind << " case " << case_name(sol.kase) << " dist "
                               << dist << " dth " << dth << " from " << f.x << " " << f.y << " "
                               << f.heading << " to " << t.x << " " << t.y << " " << t.heading
                               << " rmin " << rmin << " rev " << c.reverse << " segs "
                               << sol.seg[0].curvature << " " << sol.seg[0].length << " "
                               << sol.seg[1].curvature << " " << sol.seg[1].length;
        ASSERT_LT(m.head, 0.01) << "kind " << kind << " case " << case_name(sol.kase);
        for (const drive_segment_t &g : sol.seg) {
            if (g.curvature != 0) {
                ASSERT_GE(1.0 / std::fabs(curv_to_double(g.curvature)), fx_q16_to_double(rmin))
                    << "kind " << kind << " case " << case_name(sol.kase) << " dist " << dist
                    << " dth " << dth << " bearing " << bearing;
            }
        }
    }
    std::printf("answered %d, refused: param %d, too close %d, too far %d, behind %d, heading %d, "
                "radius %d, sweep %d\n",
                ok, refusals[DRIVE_ERR_PARAM], refusals[DRIVE_ERR_TOO_CLOSE],
                refusals[DRIVE_ERR_TOO_FAR], refusals[DRIVE_ERR_BEHIND],
                refusals[DRIVE_ERR_HEADING], refusals[DRIVE_ERR_RADIUS], refusals[DRIVE_ERR_SWEEP]);
    std::printf("worst landing error of the answers: %.3g mm, %.3g deg\n", worst_pos * 1e3,
                worst_head);
}

// Mirror images are solved as exact reflections (fx is exactly odd): reflecting the world
// across a line through the start gives exactly the reflected segments.
TEST(DriveSolve, MirrorImagesAreExact)
{
    std::mt19937_64 rng(5);
    int n = 0;
    for (int i = 0; i < 20000; i++) {
        Config c = random_config(rng);
        drive_pose_t f = to_fx(c.from), t = to_fx(c.to);
        // Reflect across the x axis: (x, y, heading) -> (x, -y, -heading).
        drive_pose_t fm = {f.x, -f.y, 0u - f.heading}, tm = {t.x, -t.y, 0u - t.heading};
        fx_q16_t rmin = fx_q16_from_double(c.rmin);
        drive_solution_t a, b;
        drive_status_t sa = drive_solve(&f, &t, rmin, c.reverse, &a, nullptr);
        drive_status_t sb = drive_solve(&fm, &tm, rmin, c.reverse, &b, nullptr);
        ASSERT_EQ(sa, sb);
        if (sa != DRIVE_OK)
            continue;
        n++;
        ASSERT_EQ(a.kase, b.kase);
        for (int j = 0; j < 2; j++) {
            ASSERT_EQ(a.seg[j].length, b.seg[j].length);
            ASSERT_EQ(a.seg[j].curvature, -b.seg[j].curvature);
            ASSERT_EQ(a.seg[j].sweep, 0u - b.seg[j].sweep);
        }
    }
    std::printf("mirrored pairs identical up to the sign: %d\n", n);
}

// Each case on a configuration whose answer is known from elementary geometry.
TEST(DriveSolve, CasesOnExactGeometry)
{
    struct Known {
        const char *what;
        Pose to;
        double rmin;
        drive_case_t kase;
        double k0, s0, k1, s1; // expected curvatures (1/m) and lengths (m)
    };
    const double r = 0.8, h = kPi / 2;
    const double t = 0.5; // S-curve half-sweep angle of each arc, rad
    const Known known[] = {
        // quarter circle of radius 0.8 to the left, then 1 m straight
        {"case 4", {r, r + 1.0, h}, 0.5, DRIVE_CASE_4, 1 / r, r * h, 0, 1.0},
        // 1 m straight, then the quarter circle to the right
        {"case 5", {1.0 + r, -r, -h}, 0.5, DRIVE_CASE_5, 0, 1.0, -1 / r, r * h},
        // single left arc of 60 degrees: d = h (case 4 with a zero straight)
        {"single arc",
         {r * std::sin(kPi / 3), r * (1 - std::cos(kPi / 3)), kPi / 3},
         0.5,
         DRIVE_CASE_4,
         1 / r,
         r * kPi / 3,
         0,
         0},
        // symmetric S-curve, left then right, no heading change: case 1 (limit)
        {"S-curve",
         {2 * r * std::sin(t), 2 * r * (1 - std::cos(t)), 0},
         0.5,
         DRIVE_CASE_1,
         1 / r,
         r * t,
         -1 / r,
         r * t},
        // the quarter circle of case 4 with a minimum radius above 0.8: the double arc
        // of the seed's fallback (case 1) with the radius of the quadratic
        {"case 4 -> 1", {r, r + 1.0, h}, 0.9, DRIVE_CASE_1, 0, 0, 0, 0},
    };
    for (const Known &k : known) {
        drive_pose_t f = to_fx({0, 0, 0}), t2 = to_fx(k.to);
        drive_solution_t sol;
        ASSERT_EQ(drive_solve(&f, &t2, fx_q16_from_double(k.rmin), false, &sol, nullptr), DRIVE_OK)
            << k.what;
        Miss m = miss_of(f, t2, sol, false);
        EXPECT_LT(m.pos, 1e-4) << k.what;
        if (k.k0 == 0 &&
            k.s0 == 0) {           // the fallback: equal radii from 4 s^2 r^2 + 4 c |q| r = |E|^2
            Pose tq = from_fx(t2); // the target as the solver sees it (Q16)
            double eta = wrap_pi(tq.th) / 2, s = std::sin(eta), c = std::cos(eta);
            double p = tq.x * c + tq.y * s, q = -tq.x * s + tq.y * c;
            double rr = (-4 * c * std::fabs(q) +
                         std::sqrt(16 * c * c * q * q + 16 * s * s * (p * p + q * q))) /
                        (8 * s * s);
            EXPECT_NEAR(1 / curv_to_double(sol.seg[0].curvature), rr, 1e-6) << k.what;
            EXPECT_NEAR(curv_to_double(sol.seg[1].curvature), -curv_to_double(sol.seg[0].curvature),
                        1e-9);
            EXPECT_EQ(sol.kase, k.kase) << k.what;
            continue;
        }
        // A single arc is case 4 with an empty straight, or case 5 if q rounds below zero.
        const drive_segment_t *g = sol.seg;
        if (k.s1 == 0 && sol.kase == DRIVE_CASE_5) {
            EXPECT_LE(sol.seg[0].length, 1) << k.what;
            g = &sol.seg[1];
        } else {
            EXPECT_EQ(sol.kase, k.kase) << k.what;
            EXPECT_NEAR(curv_to_double(sol.seg[1].curvature), k.k1, 2e-5 * std::fabs(k.k1))
                << k.what;
            EXPECT_NEAR(fx_q16_to_double(sol.seg[1].length), k.s1, 2e-5) << k.what;
        }
        // Arcs next to a straight are driven with a length rounded up to the next Q16 LSB
        // and the curvature that keeps the heading change exact: 1 LSB / s relative.
        EXPECT_NEAR(curv_to_double(g->curvature), k.k0, 2e-5 * std::fabs(k.k0)) << k.what;
        EXPECT_NEAR(fx_q16_to_double(g->length), k.s0, 2e-5) << k.what;
    }
    // Straight ahead: the straight case, two halves.
    drive_pose_t f = to_fx({1, 2, 0.3}),
                 t2 = to_fx({1 + 3 * std::cos(0.3), 2 + 3 * std::sin(0.3), 0.3});
    drive_solution_t sol;
    ASSERT_EQ(drive_solve(&f, &t2, fx_q16_from_double(0.5), false, &sol, nullptr), DRIVE_OK);
    EXPECT_EQ(sol.kase, DRIVE_CASE_STRAIGHT);
    EXPECT_EQ(sol.seg[0].curvature, 0);
    EXPECT_EQ(sol.seg[1].curvature, 0);
    EXPECT_NEAR(fx_q16_to_double(sol.seg[0].length + sol.seg[1].length), 3.0, 2e-5);
    // Reverse: backing straight into a spot 2 m behind.
    drive_pose_t b = to_fx({1 - 2 * std::cos(0.3), 2 - 2 * std::sin(0.3), 0.3});
    ASSERT_EQ(drive_solve(&f, &b, fx_q16_from_double(0.5), true, &sol, nullptr), DRIVE_OK);
    EXPECT_EQ(sol.kase, DRIVE_CASE_STRAIGHT);
    // The same spot going forward is behind: refused with the reason.
    EXPECT_EQ(drive_solve(&f, &b, fx_q16_from_double(0.5), false, &sol, nullptr), DRIVE_ERR_BEHIND);
}

// The seed's typical run (thesis table 6-1, inches): every leg between the prescribed poses
// is solvable with the seed's minimum radius of 10 in and lands.
TEST(DriveSolve, SeedTableRun)
{
    const double in = 0.0254;
    const double pts[][3] = {{36, 142, 270}, {42, 108, 300}, {36, 60, 270}, {48, 36, 315},
                             {72, 30, 0},    {108, 30, 0},   {144, 30, 0}};
    for (int i = 0; i + 1 < 7; i++) {
        Pose a = {pts[i][0] * in, pts[i][1] * in, pts[i][2] * kPi / 180};
        Pose b = {pts[i + 1][0] * in, pts[i + 1][1] * in, pts[i + 1][2] * kPi / 180};
        drive_pose_t f = to_fx(a), t = to_fx(b);
        drive_solution_t sol;
        int32_t need = 0;
        drive_status_t st = drive_solve(&f, &t, fx_q16_from_double(10 * in), false, &sol, &need);
        SeedRef ref = seed_reference(from_fx(f), from_fx(t), 10 * in, false);
        ASSERT_EQ(st, DRIVE_OK) << "leg " << i << " " << drive_status_text(st);
        EXPECT_EQ(ref.kase, case_name(sol.kase)) << "leg " << i;
        Miss m = miss_of(f, t, sol, false);
        EXPECT_LT(m.pos, 1e-4);
        std::printf(
            "seed leg %d: case %s, r = %.1f in, s = %.1f + %.1f in\n", i, case_name(sol.kase),
            sol.seg[0].curvature ? 1 / curv_to_double(sol.seg[0].curvature) / in
                                 : 1 / curv_to_double(sol.seg[1].curvature) / in,
            fx_q16_to_double(sol.seg[0].length) / in, fx_q16_to_double(sol.seg[1].length) / in);
    }
}

TEST(DriveSolve, PoseAdvanceAndRadius)
{
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> U(0, 1);
    double worst = 0, worst_h = 0;
    for (int i = 0; i < 20000; i++) {
        Pose p = {-50 + 100 * U(rng), -50 + 100 * U(rng), 2 * kPi * U(rng)};
        double k = (U(rng) - 0.5) * 8 * (U(rng) < 0.2 ? 1e-4 : 1);
        if (U(rng) < 0.1)
            k = 0;
        double s = 5 * U(rng);
        if (std::fabs(s * k) > 7.9) // the documented range: under 8 rad per call
            s = 7.9 / std::fabs(k) * U(rng);
        bool rev = U(rng) < 0.5;
        drive_pose_t f = to_fx(p);
        int32_t kq = (int32_t)std::llround(k * DRIVE_CURV_ONE);
        fx_q16_t sq = fx_q16_from_double(s);
        drive_pose_t e = drive_pose_advance(&f, kq, sq, rev);
        Pose ref = follow(from_fx(f), {{curv_to_double(kq), fx_q16_to_double(sq)}}, rev);
        worst = std::max(worst,
                         std::hypot(fx_q16_to_double(e.x) - ref.x, fx_q16_to_double(e.y) - ref.y));
        worst_h = std::max(worst_h, std::fabs(wrap_pi(fx_angle_to_rad(e.heading) - ref.th)));
    }
    std::printf("drive_pose_advance: worst %.3g mm, %.3g rad over 5 m\n", worst * 1e3, worst_h);
    EXPECT_LT(worst, 5e-5);
    EXPECT_LT(worst_h, 5e-6);
    EXPECT_EQ(drive_radius_of(0), 0);
    EXPECT_NEAR(fx_q16_to_double(drive_radius_of(DRIVE_CURV_ONE / 4)), 4.0, 2e-5);
    EXPECT_NEAR(fx_q16_to_double(drive_radius_of(-DRIVE_CURV_ONE * 2)), -0.5, 2e-5);
    EXPECT_EQ(drive_radius_of(1), INT32_MAX);
}

// ------------------------------------------------------------------ drive-board bytes

namespace
{

const drive_board_t kSeedBoard = DRIVE_BOARD_SEED;

// Distance of x from the nearest rounding tie (x.5): 0 means a tie.
double from_tie(double x)
{
    return std::fabs(x - std::floor(x) - 0.5);
}

} // namespace

// The seed's DRIVE procedure in double precision, inches and its own signs (left radius
// negative): STEERING = 81.49 atan(30 / R) + 128 (81.49 = 256 / pi), ARC = 4.4 S sqrt(1 +
// 900 / R^2). Our bytes, from the fixed-point solution in metres, must match them (rounded).
TEST(DriveCmd, BytesMatchTheSeedFormulas)
{
    EXPECT_NEAR(fx_q16_to_double(kSeedBoard.wheelbase), 30 * 0.0254, 1e-5);
    EXPECT_NEAR(fx_q16_to_double(kSeedBoard.counts_per_m), 4.4 / 0.0254, 1e-4);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> U(0, 1);
    int checked = 0, ties = 0;
    for (int i = 0; i < 20000; i++) {
        double r_in = (U(rng) < 0.5 ? -1 : 1) * (10 + 500 * U(rng));     // ours: left positive
        double s_max = 250 / (4.4 * std::sqrt(1 + 900 / (r_in * r_in))); // inside the byte
        double s_in = 0.7 + (s_max - 0.7) * U(rng);
        drive_solution_t sol = {DRIVE_CASE_1,
                                {{(int32_t)std::llround(DRIVE_CURV_ONE / (r_in * 0.0254)),
                                  fx_q16_from_double(s_in * 0.0254), 0},
                                 {0, fx_q16_from_double(s_in * 0.0254), 0}}};
        drive_cmd_t cmd;
        ASSERT_EQ(drive_cmd_build(&sol, &kSeedBoard, fx_q16_from_double(0.7), false, &cmd),
                  DRIVE_OK);
        double R = -1 / (curv_to_double(sol.seg[0].curvature) * 0.0254); // inches, the seed's sign
        double S = fx_q16_to_double(sol.seg[0].length) / 0.0254;
        double L = fx_q16_to_double(kSeedBoard.wheelbase) / 0.0254; // 30 in, as stored
        double steer = 256 / kPi * std::atan(L / R) + 128;
        double arc = 4.4 * S * std::sqrt(1 + L * L / (R * R));
        if (from_tie(steer) < 1e-4 || from_tie(arc) < 1e-4) {
            ties++;
            continue;
        }
        checked++;
        ASSERT_EQ(cmd.steer[0], (int)std::lround(steer)) << "R " << R;
        ASSERT_EQ(cmd.arc[0], (int)std::lround(arc)) << "R " << R << " S " << S;
        ASSERT_EQ(cmd.steer[1], DRIVE_STEER_STRAIGHT);
        ASSERT_EQ(cmd.arc[1], (int)std::lround(4.4 * S));
        ASSERT_EQ(cmd.speed, (int)std::lround(0.7 / fx_q16_to_double(kSeedBoard.speed_lsb)));
        ASSERT_EQ(cmd.pulses, 2);
    }
    std::printf("steering and arc bytes equal to the seed's formulas: %d (ties skipped: %d)\n",
                checked, ties);
}

TEST(DriveCmd, RangesReverseAndShortArcs)
{
    drive_cmd_t cmd;
    // 1.47 m of front wheel is 255 counts: 1.48 m is out of the byte.
    drive_solution_t straight = {
        DRIVE_CASE_STRAIGHT, {{0, fx_q16_from_double(1.47), 0}, {0, fx_q16_from_double(0.5), 0}}};
    ASSERT_EQ(drive_cmd_build(&straight, &kSeedBoard, fx_q16_from_double(0.5), false, &cmd),
              DRIVE_OK);
    EXPECT_EQ(cmd.arc[0], 255);
    straight.seg[0].length = fx_q16_from_double(1.48);
    EXPECT_EQ(drive_cmd_build(&straight, &kSeedBoard, fx_q16_from_double(0.5), false, &cmd),
              DRIVE_ERR_RANGE);
    // Speed: 127 counts at most, negative when reversing.
    straight.seg[0].length = fx_q16_from_double(1.0);
    EXPECT_EQ(drive_cmd_build(&straight, &kSeedBoard, fx_q16_from_double(2.3), false, &cmd),
              DRIVE_ERR_RANGE);
    ASSERT_EQ(drive_cmd_build(&straight, &kSeedBoard, fx_q16_from_double(1.0), true, &cmd),
              DRIVE_OK);
    EXPECT_EQ(cmd.speed, -(int)std::lround(1.0 / fx_q16_to_double(kSeedBoard.speed_lsb)));
    // D7: a second arc under 3 counts is driven but not waited for; a short first arc is
    // dropped; both short: nothing to wait for.
    straight.seg[1].length = fx_q16_from_double(0.010); // 1.7 counts
    ASSERT_EQ(drive_cmd_build(&straight, &kSeedBoard, fx_q16_from_double(0.5), false, &cmd),
              DRIVE_OK);
    EXPECT_EQ(cmd.arc[1], 2);
    EXPECT_EQ(cmd.pulses, 1);
    drive_solution_t first = {DRIVE_CASE_5,
                              {{0, fx_q16_from_double(0.008), 0}, {0, fx_q16_from_double(0.5), 0}}};
    ASSERT_EQ(drive_cmd_build(&first, &kSeedBoard, fx_q16_from_double(0.5), false, &cmd), DRIVE_OK);
    EXPECT_EQ(cmd.arc[0], 0);
    EXPECT_EQ(cmd.pulses, 1);
    first.seg[1].length = fx_q16_from_double(0.004);
    ASSERT_EQ(drive_cmd_build(&first, &kSeedBoard, fx_q16_from_double(0.5), false, &cmd), DRIVE_OK);
    EXPECT_EQ(cmd.pulses, 0);
    // Steering bytes: 1 count = pi / 256; the range ends at 89.6 degrees.
    uint8_t b;
    ASSERT_EQ(drive_steer_byte(fx_angle_from_deg(45), &b), DRIVE_OK);
    EXPECT_EQ(b, 128 - 64);
    ASSERT_EQ(drive_steer_byte(fx_angle_from_deg(-45), &b), DRIVE_OK);
    EXPECT_EQ(b, 128 + 64);
    ASSERT_EQ(drive_steer_byte(fx_angle_from_deg(89.5), &b), DRIVE_OK);
    EXPECT_EQ(b, 1);
    EXPECT_EQ(drive_steer_byte(fx_angle_from_deg(89.7), &b), DRIVE_ERR_RANGE);
    // Seed 002's DAC: AGV_angle = CENTER + -(alpha) / 1.5707963 * (255 - CENTER), speed 128 + v.
    for (double deg = -90; deg <= 90; deg += 0.37) {
        double ref = 132 - (deg * kPi / 180) / 1.5707963 * (255 - 132);
        if (from_tie(ref) < 1e-3)
            continue;
        ASSERT_EQ(drive_dac_angle_byte(fx_angle_from_deg(deg), 132), (int)std::lround(ref)) << deg;
    }
    EXPECT_EQ(drive_dac_speed_byte(0), 128);
    EXPECT_EQ(drive_dac_speed_byte(127), 255);
    EXPECT_EQ(drive_dac_speed_byte(-20), 108);
    // The steering angle is atan(L / r), left positive.
    double L = fx_q16_to_double(kSeedBoard.wheelbase);
    EXPECT_NEAR(fx_angle_to_deg_signed(drive_steer_angle(DRIVE_CURV_ONE, kSeedBoard.wheelbase)),
                std::atan(L) * 180 / kPi, 1e-4);
    EXPECT_NEAR(
        fx_angle_to_deg_signed(drive_steer_angle(-DRIVE_CURV_ONE / 2, kSeedBoard.wheelbase)),
        -std::atan(L / 2) * 180 / kPi, 1e-4);
}

// ------------------------------------------------------------------ port protocols

namespace
{

std::vector<std::pair<int, int>> writes_of(const drive_wseq_t &s)
{
    std::vector<std::pair<int, int>> v;
    for (int i = 0; i < s.n; i++)
        v.push_back({s.w[i].reg, s.w[i].value});
    return v;
}

} // namespace

// OUTPUT_TO_PORTS of seed 000, write by write, for the seed's speed of 40.
TEST(DriveProto, SeedListingByteExact)
{
    const int A = HAL_DRIVE_PPI_A, B = HAL_DRIVE_PPI_B, C = HAL_DRIVE_PPI_C, W = HAL_DRIVE_PPI_CTRL;
    drive_cmd_t cmd = {{0x9C, 0x6E}, {0xAA, 0x10}, 40, 2, {0, 0}};
    drive_wseq_t s;
    drive_ppi_load(&cmd, &s);
    std::vector<std::pair<int, int>> expect = {
        {C, 0x02},        {W, 0x80},            // OUTPUT(PORTC) = 002H; OUTPUT(C8255) = 080H
        {A, 0x9C ^ 0xFF}, {B, 0x40}, {B, 0x00}, // steering angle 1
        {A, 0xAA ^ 0xFF}, {B, 0x20}, {B, 0x00}, // arc length 1
        {A, 0x6E ^ 0xFF}, {B, 0x50}, {B, 0x00}, // steering angle 2
        {A, 0x10 ^ 0xFF}, {B, 0x30}, {B, 0x00}, // arc length 2
        {A, 0x28 ^ 0xFF}, {B, 0x60}, {B, 0x00}, // speed 28H (40)
        {W, 0x90},        {C, 0x82}};           // OUTPUT(C8255) = 90H; OUTPUT(PORTC) = 82H
    EXPECT_EQ(writes_of(s), expect);
    drive_ppi_speed(0, &s);
    std::vector<std::pair<int, int>> stop = {{C, 0x02}, {W, 0x80}, {A, 0xFF}, {B, 0x60},
                                             {B, 0x00}, {W, 0x90}, {C, 0x82}};
    EXPECT_EQ(writes_of(s), stop);
    drive_ppi_init(&s);
    EXPECT_EQ(writes_of(s), (std::vector<std::pair<int, int>>{{W, 0x90}}));
    const int DA = HAL_DRIVE_DAC_ANGLE, DS = HAL_DRIVE_DAC_SPEED, DO = HAL_DRIVE_DIGITAL;
    drive_dac_start(132, &s); // seed 002's Init_AGV
    EXPECT_EQ(writes_of(s),
              (std::vector<std::pair<int, int>>{
                  {DO, 0x03}, {DS, 128}, {DA, 132}, {DO, 0x07}, {DO, 0x05}, {DO, 0x04}}));
    drive_dac_stop(132, &s);
    EXPECT_EQ(writes_of(s), (std::vector<std::pair<int, int>>{{DA, 132}, {DS, 128}, {DO, 0x03}}));
}

TEST(DriveProto, DecoderRoundTripsEveryEncodableCommand)
{
    drive_decoder_t d;
    drive_decoder_init(&d, 132);
    drive_wseq_t s;
    drive_event_t ev;
    drive_ppi_init(&s);
    for (int i = 0; i < s.n; i++)
        ASSERT_FALSE(drive_decoder_feed(&d, s.w[i].reg, s.w[i].value, &ev));
    std::mt19937_64 rng(11);
    int n = 0;
    // Every value of every item (the others random), then random commands.
    for (int item = 0; item < 6; item++) {
        for (int v = 0; v < 256; v++) {
            for (int rep = 0; rep < (item == 5 ? 40 : 1); rep++) {
                drive_cmd_t cmd = {{(uint8_t)rng(), (uint8_t)rng()},
                                   {(uint8_t)rng(), (uint8_t)rng()},
                                   (int8_t)rng(),
                                   2,
                                   {0, 0}};
                if (item < 2)
                    cmd.steer[item] = (uint8_t)v;
                else if (item < 4)
                    cmd.arc[item - 2] = (uint8_t)v;
                else if (item == 4)
                    cmd.speed = (int8_t)v;
                drive_ppi_load(&cmd, &s);
                int events = 0;
                for (int i = 0; i < s.n; i++) {
                    if (drive_decoder_feed(&d, s.w[i].reg, s.w[i].value, &ev)) {
                        events++;
                        ASSERT_EQ(i, s.n - 1) << "event before the commit";
                        ASSERT_EQ(ev.type, DRIVE_EV_LOAD);
                        ASSERT_EQ(ev.mask, DRIVE_ITEM_ALL);
                        ASSERT_EQ(ev.cmd.steer[0], cmd.steer[0]);
                        ASSERT_EQ(ev.cmd.steer[1], cmd.steer[1]);
                        ASSERT_EQ(ev.cmd.arc[0], cmd.arc[0]);
                        ASSERT_EQ(ev.cmd.arc[1], cmd.arc[1]);
                        ASSERT_EQ(ev.cmd.speed, cmd.speed);
                        ASSERT_EQ(ev.cmd.alpha[0], (fx_angle_t)((128 - cmd.steer[0]) * (1 << 23)));
                    }
                }
                ASSERT_EQ(events, 1);
                n++;
                drive_ppi_speed(cmd.speed, &s);
                for (int i = 0; i < s.n; i++)
                    if (drive_decoder_feed(&d, s.w[i].reg, s.w[i].value, &ev)) {
                        ASSERT_EQ(ev.type, DRIVE_EV_SPEED);
                        ASSERT_EQ(ev.cmd.speed, cmd.speed);
                    }
            }
        }
    }
    // DAC style: values and the decoded steering angle.
    for (int v = 0; v < 256; v++) {
        drive_dac_set((uint8_t)v, (uint8_t)(255 - v), &s);
        ASSERT_TRUE(drive_decoder_feed(&d, s.w[0].reg, s.w[0].value, &ev));
        ASSERT_EQ(ev.type, DRIVE_EV_DAC_ANGLE);
        ASSERT_EQ(ev.value, v);
        ASSERT_NEAR(fx_angle_to_deg_signed(ev.alpha), (132.0 - v) / 123.0 * 90.0, 1e-6);
        ASSERT_EQ(drive_dac_angle_byte(ev.alpha, 132), v); // the encoder inverts it
        ASSERT_TRUE(drive_decoder_feed(&d, s.w[1].reg, s.w[1].value, &ev));
        ASSERT_EQ(ev.type, DRIVE_EV_DAC_SPEED);
        ASSERT_EQ(ev.cmd.speed, 255 - v - 128);
    }
    drive_dac_outputs(0x15, &s);
    ASSERT_TRUE(drive_decoder_feed(&d, s.w[0].reg, s.w[0].value, &ev));
    EXPECT_EQ(ev.type, DRIVE_EV_OUTPUTS);
    EXPECT_EQ(ev.value, 0x15);
    std::printf("8255 loads round-tripped: %d (and as many speed changes)\n", n);
}

TEST(DriveProto, DecoderFlagsViolations)
{
    drive_decoder_t d;
    drive_event_t ev;
    const int A = HAL_DRIVE_PPI_A, B = HAL_DRIVE_PPI_B, C = HAL_DRIVE_PPI_C, W = HAL_DRIVE_PPI_CTRL;
    struct Case {
        const char *what;
        std::vector<std::pair<int, int>> w;
        drive_perr_t err;
    } cases[] = {
        {"port A written while input (after reset)", {{A, 0x12}}, DRIVE_PERR_PORT_INPUT},
        {"mode 1", {{W, 0xA0}}, DRIVE_PERR_MODE},
        {"unknown strobe code", {{W, 0x80}, {A, 0x00}, {B, 0x70}}, DRIVE_PERR_STROBE_CODE},
        {"strobe without release",
         {{W, 0x80}, {A, 0x00}, {B, 0x40}, {B, 0x20}},
         DRIVE_PERR_STROBE_HELD},
        {"strobe with the data bus released", {{W, 0x90}, {B, 0x40}}, DRIVE_PERR_NO_DATA},
        {"register 7", {{7, 0x00}}, DRIVE_PERR_REGISTER},
        {"port C while input", {{C, 0x82}}, DRIVE_PERR_PORT_INPUT},
    };
    for (const Case &c : cases) {
        drive_decoder_init(&d, 132);
        bool got = false;
        for (auto &w : c.w) {
            if (drive_decoder_feed(&d, (uint8_t)w.first, (uint8_t)w.second, &ev)) {
                got = true;
                EXPECT_EQ(ev.type, DRIVE_EV_ERROR) << c.what;
                EXPECT_EQ(ev.error, c.err) << c.what;
            }
        }
        EXPECT_TRUE(got) << c.what;
    }
    // A transfer broken by an error is forgotten; the next complete one decodes.
    drive_decoder_init(&d, 132);
    drive_wseq_t s;
    drive_ppi_init(&s);
    for (int i = 0; i < s.n; i++)
        drive_decoder_feed(&d, s.w[i].reg, s.w[i].value, &ev);
    drive_cmd_t cmd = {{100, 150}, {20, 30}, 12, 2, {0, 0}};
    drive_ppi_load(&cmd, &s);
    for (int i = 0; i < 6; i++)
        drive_decoder_feed(&d, s.w[i].reg, s.w[i].value, &ev);
    EXPECT_TRUE(drive_decoder_feed(&d, B, 0x77, &ev));
    EXPECT_EQ(ev.type, DRIVE_EV_ERROR);
    int loads = 0;
    for (int i = 0; i < s.n; i++)
        if (drive_decoder_feed(&d, s.w[i].reg, s.w[i].value, &ev) && ev.type == DRIVE_EV_LOAD)
            loads++;
    EXPECT_EQ(loads, 1);
    // Port C bit set/reset: PC7 set by a control word commits too.
    drive_ppi_speed(5, &s);
    for (int i = 0; i + 1 < s.n; i++)
        drive_decoder_feed(&d, s.w[i].reg, s.w[i].value, &ev);
    ASSERT_TRUE(drive_decoder_feed(&d, W, 0x0F, &ev)); // bit 7 of C set
    EXPECT_EQ(ev.type, DRIVE_EV_SPEED);
    EXPECT_EQ(ev.cmd.speed, 5);
}

// hal/posix records every write of the board that makes it, with the simulated time, and
// hands it to the sink: the closed-loop simulator's drive-board model sits there.
TEST(DriveProto, HostPortRecordsAndFeedsTheDecoder)
{
    posix_reset();
    int b = posix_board_create("main");
    posix_board_select(b);
    struct Sink {
        drive_decoder_t d;
        std::vector<drive_event_t> events;
        int writes = 0;
    } sink;
    drive_decoder_init(&sink.d, 132);
    posix_drive_port_set_sink(
        b,
        [](void *ctx, int, const posix_drive_write_t *w) {
            Sink *k = static_cast<Sink *>(ctx);
            k->writes++;
            drive_event_t ev;
            if (drive_decoder_feed(&k->d, w->reg, w->value, &ev))
                k->events.push_back(ev);
        },
        &sink);
    hal_drive_port_init();
    drive_wseq_t s;
    drive_ppi_init(&s);
    drive_port_send(&s);
    drive_cmd_t cmd = {{90, 170}, {200, 15}, -30, 2, {0, 0}};
    drive_ppi_load(&cmd, &s);
    drive_port_send(&s);
    ASSERT_EQ(posix_drive_port_count(b), 20u);
    posix_drive_write_t log[32];
    ASSERT_EQ(posix_drive_port_log(b, log, 32), 20u);
    for (int i = 0; i < s.n; i++) {
        EXPECT_EQ(log[1 + i].reg, s.w[i].reg);
        EXPECT_EQ(log[1 + i].value, s.w[i].value);
    }
    EXPECT_EQ(posix_drive_port_value(b, HAL_DRIVE_PPI_C), 0x82);
    ASSERT_EQ(sink.events.size(), 1u);
    EXPECT_EQ(sink.events[0].type, DRIVE_EV_LOAD);
    EXPECT_EQ(sink.events[0].cmd.arc[0], 200);
    EXPECT_EQ(sink.events[0].cmd.speed, -30);
    EXPECT_EQ(sink.writes, 20);
    posix_drive_port_clear(b);
    EXPECT_EQ(posix_drive_port_count(b), 0u);
    posix_reset();
}

// ------------------------------------------------------------------ path preparation

namespace
{

// The seed's typical run (table 6-1), inches to metres: the start and six path points.
std::vector<drive_path_point_t> seed_path(double speed, drive_pose_t *start)
{
    const double in = 0.0254;
    const double pts[][3] = {{36, 142, 270}, {42, 108, 300}, {36, 60, 270}, {48, 36, 315},
                             {72, 30, 0},    {108, 30, 0},   {144, 30, 0}};
    *start = to_fx({pts[0][0] * in, pts[0][1] * in, pts[0][2] * kPi / 180});
    std::vector<drive_path_point_t> v;
    for (int i = 1; i < 7; i++)
        v.push_back({to_fx({pts[i][0] * in, pts[i][1] * in, pts[i][2] * kPi / 180}),
                     fx_q16_from_double(speed), 0});
    return v;
}

drive_path_config_t path_cfg(double nominal, double spacing, bool reverse)
{
    return {fx_q16_from_double(nominal), fx_q16_from_double(spacing), reverse};
}

} // namespace

TEST(DrivePath, SecondaryPointsLieOnTheNominalPath)
{
    drive_pose_t start;
    std::vector<drive_path_point_t> pts = seed_path(0.5, &start);
    drive_path_t path;
    drive_path_config_t cfg = path_cfg(0.4, 0.3, false);
    ASSERT_EQ(drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
              DRIVE_OK);
    ASSERT_TRUE(path.ready);
    int targets = 0;
    double worst_off = 0, worst_gap = 0;
    Pose prev = from_fx(start);
    for (uint8_t leg = 0; leg < pts.size(); leg++) {
        const drive_leg_t *nominal;
        ASSERT_EQ(drive_path_leg(&path, leg, &nominal), DRIVE_OK);
        ASSERT_EQ(nominal->parts, 1); // no turn over 90 degrees on the seed's path
        const drive_solution_t *sol = &nominal->sol[0];
        double len = fx_q16_to_double(sol->seg[0].length + sol->seg[1].length);
        int nsub = pts[leg].nsub;
        EXPECT_GE(nsub * 0.3, len - 1e-4);
        EXPECT_LT((nsub - 1) * 0.3, len);
        // The nominal leg, densely sampled in double precision.
        Pose a = prev;
        std::vector<Pose> dense = sample_leg(a, *nominal, false, 4000);
        Pose last = a;
        for (int sub = 1; sub <= nsub; sub++) {
            drive_path_cursor_t cur = {leg, (uint8_t)sub};
            drive_pose_t tp;
            fx_q16_t speed;
            ASSERT_EQ(drive_path_target(&path, cur, &tp, &speed), DRIVE_OK);
            EXPECT_EQ(speed, pts[leg].speed);
            Pose p = from_fx(tp);
            double off = 1e9;
            for (const Pose &d : dense)
                off = std::min(off, std::hypot(d.x - p.x, d.y - p.y));
            worst_off = std::max(worst_off, off);
            worst_gap = std::max(worst_gap, std::hypot(p.x - last.x, p.y - last.y));
            last = p;
            targets++;
            EXPECT_EQ(drive_path_is_last(&path, cur), leg + 1u == pts.size() && sub == nsub);
        }
        EXPECT_EQ(last.x, from_fx(pts[leg].pose).x); // the primary point itself
        EXPECT_EQ(last.y, from_fx(pts[leg].pose).y);
        prev = from_fx(pts[leg].pose);
    }
    // Walking the cursor visits every secondary point once.
    drive_path_cursor_t c = drive_path_first(&path);
    int walked = 1;
    while (!drive_path_is_last(&path, c)) {
        c = drive_path_next(&path, c);
        walked++;
    }
    EXPECT_EQ(walked, targets);
    std::printf("seed path: %d secondary points, farthest %.3g mm off the nominal path (sampling "
                "step included), largest gap %.3f m (spacing 0.3 m)\n",
                targets, worst_off * 1e3, worst_gap);
    EXPECT_LT(worst_off, 2e-3);
    EXPECT_LE(worst_gap, 0.3 + 1e-4);
}

TEST(DrivePath, UnacceptablePathsAreRejectedWithTheLeg)
{
    drive_pose_t start;
    std::vector<drive_path_point_t> pts = seed_path(0.5, &start);
    drive_path_t path;
    drive_path_config_t cfg = path_cfg(0.4, 0.8, false);
    struct Case {
        const char *what;
        int leg;
        std::function<void(std::vector<drive_path_point_t> &, drive_path_config_t &)> spoil;
        drive_status_t why;
    } cases[] = {
        {"turn over 90 degrees away from the target's side", 2,
         [](auto &p, auto &) { p[2].pose.heading += fx_angle_from_deg(120); }, DRIVE_ERR_TURN},
        {"point behind", 3,
         [](auto &p, auto &) {
             p[3].pose = p[2].pose;
             p[3].pose.x -= FX_Q16_ONE;
         },
         DRIVE_ERR_BEHIND},
        {"corner too tight for the nominal radius", 0,
         [](auto &, auto &c) { c.nominal_radius = fx_q16_from_double(1.5); }, DRIVE_ERR_RADIUS},
        {"speed zero", 4, [](auto &p, auto &) { p[4].speed = 0; }, DRIVE_ERR_PARAM},
        {"speed beyond the byte", 0, [](auto &p, auto &) { p[0].speed = 5 * FX_Q16_ONE; },
         DRIVE_ERR_RANGE},
        {"piece beyond the 8-bit arc length (1.47 m)", 5,
         [](auto &p, auto &c) {
             p[5].pose.x += fx_q16_from_double(2.5); // 3.4 m: two halves of 1.7 m
             c.spacing = fx_q16_from_double(8);
         },
         DRIVE_ERR_RANGE},
        {"nominal radius below the vehicle's", 0,
         [](auto &, auto &c) { c.nominal_radius = fx_q16_from_double(0.2); }, DRIVE_ERR_PARAM},
    };
    for (const Case &c : cases) {
        std::vector<drive_path_point_t> p = pts;
        drive_path_config_t k = cfg;
        c.spoil(p, k);
        EXPECT_EQ(drive_path_prepare(&path, &start, p.data(), (uint8_t)p.size(), &k, &kSeedBoard),
                  c.why)
            << c.what;
        EXPECT_FALSE(path.ready) << c.what;
        EXPECT_EQ(path.bad_leg, c.leg) << c.what;
        drive_pose_t tp;
        fx_q16_t sp;
        EXPECT_EQ(drive_path_target(&path, drive_path_first(&path), &tp, &sp), DRIVE_ERR_PARAM);
    }
    // The unspoilt path, also driven tail first (its headings then point away from travel).
    EXPECT_EQ(drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
              DRIVE_OK);
    std::vector<drive_path_point_t> back = pts;
    drive_pose_t bstart = start;
    bstart.heading += FX_ANGLE_HALF;
    for (auto &q : back)
        q.pose.heading += FX_ANGLE_HALF;
    drive_path_config_t rcfg = path_cfg(0.4, 0.8, true);
    EXPECT_EQ(
        drive_path_prepare(&path, &bstart, back.data(), (uint8_t)back.size(), &rcfg, &kSeedBoard),
        DRIVE_OK);
}

// ------------------------------------------------------------------ turns over 90 degrees

namespace
{

// The widest corner (a straight along A, an arc, a straight along B) that takes the vehicle
// from `from` to `to`, in double precision with Eigen, built differently from the
// firmware's closed form: the arc's centre is C = S + cx a + R n_a = E_pt - s b + R n_b
// (a, b the directions of travel, n_a, n_b their normals toward the turn), a 2x2 linear
// system for the straights (cx, s) that is linear in R; the radius is the largest with both
// straights >= 0. The middle of the arc is where the firmware must insert its pose.
struct Corner {
    bool fits;         // a corner with a positive radius exists
    double r;          // its radius
    Eigen::Vector2d m; // the middle of its arc
    double m_th;       // the vehicle's heading there
};

Corner widest_corner(Pose from, Pose to, bool reverse)
{
    const double rev = reverse ? kPi : 0.0;
    double ta = from.th + rev, delta = wrap_pi(to.th - from.th);
    Eigen::Vector2d a(std::cos(ta), std::sin(ta)), b(std::cos(ta + delta), std::sin(ta + delta));
    Eigen::Vector2d e(to.x - from.x, to.y - from.y);
    double cross_ae = a.x() * e.y() - a.y() * e.x();
    double sigma = delta > 0 ? 1.0 : -1.0;
    if (std::fabs(std::fabs(delta) - kPi) < 1e-12) { // a half turn: toward the target's side
        sigma = cross_ae >= 0 ? 1.0 : -1.0;
        delta = sigma * kPi;
    }
    auto left = [](const Eigen::Vector2d &v) { return Eigen::Vector2d(-v.y(), v.x()); };
    Eigen::Vector2d na = sigma * left(a), nb = sigma * left(b);
    Corner c = {false, 0, {0, 0}, 0};
    double cx, s; // the straights at the chosen radius
    if (std::fabs(a.x() * b.y() - a.y() * b.x()) < 1e-9) {
        // Parallel and opposite: the arc's diameter is the lateral offset, the straights
        // make up the offset along a.
        c.r = sigma * cross_ae / 2;
        double along = a.dot(e);
        cx = std::max(along, 0.0);
        s = cx - along;
    } else {
        Eigen::Matrix2d m;
        m << a, b;
        Eigen::Matrix2d inv = m.inverse();       // a and b are not parallel
        Eigen::Vector2d base = inv * e;          // (cx, s) at R = 0
        Eigen::Vector2d slope = inv * (nb - na); // per metre of R
        double rmax = 1e300;
        for (int i = 0; i < 2; i++) {
            if (slope(i) < 0)
                rmax = std::min(rmax, -base(i) / slope(i));
            else if (base(i) < 0) // a straight negative at every radius
                rmax = -1;
        }
        c.r = rmax;
        cx = base(0) + c.r * slope(0);
        s = base(1) + c.r * slope(1);
    }
    (void)s;
    if (!(c.r > 0))
        return c;
    c.fits = true;
    Eigen::Vector2d centre = Eigen::Vector2d(from.x, from.y) + cx * a + c.r * na;
    double tm = ta + delta / 2;
    Eigen::Vector2d u(std::cos(tm), std::sin(tm));
    c.m = centre - c.r * sigma * left(u);
    c.m_th = from.th + delta / 2;
    return c;
}

// Follow a nominal leg from `from` in double precision, part after part (the second part
// from where the first one ended, not from the inserted pose); `at_via` gets the end of the
// first part. Checks every arc's radius against `rmin` (counted in *low).
Pose follow_leg(Pose from, const drive_leg_t &leg, bool reverse, double rmin, Pose *at_via,
                int *low)
{
    Pose p = from;
    for (int i = 0; i < leg.parts; i++) {
        for (const drive_segment_t &g : leg.sol[i].seg)
            if (g.curvature != 0 && 1.0 / std::fabs(curv_to_double(g.curvature)) < rmin)
                ++*low;
        p = follow(p, segs_of(leg.sol[i]), reverse);
        if (i == 0 && at_via)
            *at_via = p;
    }
    return p;
}

double head_deg(double a, double b)
{
    return std::fabs(wrap_pi(a - b)) * 180 / kPi;
}

} // namespace

// Turns of 90 - 180 degrees built from a known corner (radius at least the minimum, either
// straight possibly empty; left and right, forward and tail first, exact half turns): the
// leg is split in two, lands on the inserted pose and on the target, never below the
// minimum radius, and the inserted pose is the middle of the widest corner.
TEST(DriveLeg, TurnsOverNinetyDegreesLandOnEveryPose)
{
    std::mt19937_64 rng(1515);
    std::uniform_real_distribution<double> U(0, 1);
    double worst_via = 0, worst_to = 0, worst_head = 0, worst_mid = 0;
    int n = 0, halves = 0, low = 0;
    for (int i = 0; i < 20000; i++) {
        double rmin = 0.25 + 1.25 * U(rng), r = rmin * (1.001 + 3 * U(rng));
        double delta = (90.5 + 89.5 * U(rng)) * kPi / 180;
        if (i % 10 == 0) {
            delta = kPi;
            halves++;
        }
        double cx = U(rng) < 0.3 ? 0 : 3 * U(rng), s = U(rng) < 0.3 ? 0 : 3 * U(rng);
        double sigma = U(rng) < 0.5 ? 1 : -1;
        bool rev = U(rng) < 0.25;
        Pose from = {-50 + 100 * U(rng), -50 + 100 * U(rng), 2 * kPi * U(rng)};
        double ta = from.th + (rev ? kPi : 0), tb = ta + sigma * delta;
        // start, straight cx, arc of radius r turning sigma * delta, straight s
        double cxx = from.x + cx * std::cos(ta), cyy = from.y + cx * std::sin(ta);
        double ox = cxx - sigma * r * std::sin(ta), oy = cyy + sigma * r * std::cos(ta);
        double ex = ox + sigma * r * std::sin(tb) + s * std::cos(tb);
        double ey = oy - sigma * r * std::cos(tb) + s * std::sin(tb);
        Pose to = {ex, ey, from.th + sigma * delta};
        drive_pose_t f = to_fx(from), t = to_fx(to);
        if (delta == kPi) // exactly half a turn in binary angles too
            t.heading = f.heading + FX_ANGLE_HALF;
        drive_leg_t leg;
        drive_status_t st = drive_leg_solve(&f, &t, fx_q16_from_double(rmin), rev, &leg);
        ASSERT_EQ(st, DRIVE_OK) << "i " << i << " delta " << delta * 180 / kPi << " r " << r
                                << " cx " << cx << " s " << s << ": " << drive_status_text(st);
        ASSERT_EQ(leg.parts, 2);
        n++;
        Pose pf = from_fx(f), pt = from_fx(t), pv = from_fx(leg.via), at_via;
        Pose end =
            follow_leg(pf, leg, rev, fx_q16_to_double(fx_q16_from_double(rmin)), &at_via, &low);
        double dv = std::hypot(at_via.x - pv.x, at_via.y - pv.y);
        double dt = std::hypot(end.x - pt.x, end.y - pt.y);
        double dh = std::max(head_deg(at_via.th, pv.th), head_deg(end.th, pt.th));
        worst_via = std::max(worst_via, dv);
        worst_to = std::max(worst_to, dt);
        worst_head = std::max(worst_head, dh);
        ASSERT_LT(dv, 5e-5) << "i " << i;
        ASSERT_LT(dt, 1e-4) << "i " << i;
        ASSERT_LT(dh, 0.01) << "i " << i;
        Corner c = widest_corner(pf, pt, rev);
        ASSERT_TRUE(c.fits);
        ASSERT_GE(c.r, r - 1e-4); // the built corner fits: the widest is at least as wide
        double dm = std::hypot(pv.x - c.m.x(), pv.y - c.m.y());
        worst_mid = std::max(worst_mid, dm);
        ASSERT_LT(dm, 1e-4) << "i " << i << " r " << c.r;
        ASSERT_LT(head_deg(pv.th, c.m_th), 1e-4) << "i " << i;
    }
    EXPECT_EQ(low, 0);
    std::printf("turns over 90 degrees: %d (%d half turns), worst landing on the inserted pose "
                "%.3g mm, on the target %.3g mm, %.3g deg; inserted pose %.3g mm from the "
                "widest corner's middle\n",
                n, halves, worst_via * 1e3, worst_to * 1e3, worst_head, worst_mid * 1e3);
}

// Any turn of 90 - 180 degrees to a target anywhere within 0.3 - 20 m: split and landing
// when the widest corner (the independent construction) is wider than the radius, refused
// with DRIVE_ERR_TURN when it is narrower (or none fits).
TEST(DriveLeg, TurnsOverNinetyDegreesSplitOrRefuse)
{
    std::mt19937_64 rng(4242);
    std::uniform_real_distribution<double> U(0, 1);
    int split = 0, refused = 0, near = 0, low = 0;
    for (int i = 0; i < 50000; i++) {
        double rmin = 0.2 + 2 * U(rng), dist = 0.3 + 19.7 * U(rng);
        double bearing = 2 * kPi * U(rng), delta = (90.01 + 89.99 * U(rng)) * kPi / 180;
        if (U(rng) < 0.5)
            delta = -delta;
        bool rev = U(rng) < 0.25;
        Pose from = {-50 + 100 * U(rng), -50 + 100 * U(rng), 2 * kPi * U(rng)};
        double ta = from.th + (rev ? kPi : 0);
        Pose to = {from.x + dist * std::cos(ta + bearing), from.y + dist * std::sin(ta + bearing),
                   from.th + delta};
        drive_pose_t f = to_fx(from), t = to_fx(to);
        fx_q16_t rq = fx_q16_from_double(rmin);
        Pose pf = from_fx(f), pt = from_fx(t);
        Corner c = widest_corner(pf, pt, rev);
        double rr = fx_q16_to_double(rq);
        drive_leg_t leg;
        drive_status_t st = drive_leg_solve(&f, &t, rq, rev, &leg);
        if (c.fits && std::fabs(c.r / rr - 1) < 1e-4) {
            near++; // at the limit either answer is right
            continue;
        }
        if (!c.fits || c.r < rr) {
            ASSERT_EQ(st, DRIVE_ERR_TURN) << "i " << i << " widest " << c.r << " rmin " << rr;
            refused++;
            continue;
        }
        ASSERT_EQ(st, DRIVE_OK) << "i " << i << " widest " << c.r << " rmin " << rr << ": "
                                << drive_status_text(st);
        ASSERT_EQ(leg.parts, 2);
        Pose end = follow_leg(pf, leg, rev, rr, nullptr, &low);
        ASSERT_LT(std::hypot(end.x - pt.x, end.y - pt.y), 1e-4) << "i " << i;
        ASSERT_LT(head_deg(end.th, pt.th), 0.01) << "i " << i;
        split++;
    }
    EXPECT_EQ(low, 0);
    EXPECT_GT(split, 5000);
    EXPECT_GT(refused, 5000);
    std::printf("turns over 90 degrees anywhere: %d split and landed, %d refused (no corner of "
                "the radius), %d at the limit\n",
                split, refused, near);
}

// The two turns the issue names, on exact geometry: the U-turn at an aisle end (half a turn
// across two radii, the target behind the start) and a 120-degree corner; and what stays
// refused.
TEST(DriveLeg, AisleEndUTurnAndCornerOnExactGeometry)
{
    const drive_pose_t from = to_fx({0, 0, 0});
    drive_leg_t leg;
    // U-turn, aisles 2 m apart, 2 m back: quarter circle of 1 m to (1, 1, 90 deg), then a
    // quarter circle and 2 m straight.
    drive_pose_t to = to_fx({-2, 2, 0});
    to.heading = FX_ANGLE_HALF;
    ASSERT_EQ(drive_leg_solve(&from, &to, fx_q16_from_double(0.5), false, &leg), DRIVE_OK);
    ASSERT_EQ(leg.parts, 2);
    EXPECT_NEAR(fx_q16_to_double(leg.via.x), 1.0, 1e-4);
    EXPECT_NEAR(fx_q16_to_double(leg.via.y), 1.0, 1e-4);
    EXPECT_EQ(leg.via.heading, FX_ANGLE_QUARTER);
    double arc = 0, straight = 0;
    for (const drive_solution_t &sol : leg.sol)
        for (const drive_segment_t &g : sol.seg) {
            if (g.curvature != 0) {
                EXPECT_NEAR(curv_to_double(g.curvature), 1.0, 2e-4);
                arc += fx_q16_to_double(g.length);
            } else {
                straight += fx_q16_to_double(g.length);
            }
        }
    EXPECT_NEAR(arc, kPi, 2e-4);
    EXPECT_NEAR(straight, 2.0, 2e-4);
    // The same U-turn to the right (target on the right), and tail first.
    drive_pose_t to_r = to_fx({-2, -2, 0});
    to_r.heading = FX_ANGLE_HALF;
    ASSERT_EQ(drive_leg_solve(&from, &to_r, fx_q16_from_double(0.5), false, &leg), DRIVE_OK);
    EXPECT_NEAR(fx_q16_to_double(leg.via.y), -1.0, 1e-4);
    EXPECT_EQ(leg.via.heading, (fx_angle_t)(0u - FX_ANGLE_QUARTER));
    drive_pose_t to_b = to_fx({2, 2, 0});
    to_b.heading = FX_ANGLE_HALF;
    ASSERT_EQ(drive_leg_solve(&from, &to_b, fx_q16_from_double(0.5), true, &leg), DRIVE_OK);
    EXPECT_NEAR(fx_q16_to_double(leg.via.x), -1.0, 1e-4); // backing: the corner is behind
    EXPECT_NEAR(fx_q16_to_double(leg.via.y), 1.0, 1e-4);
    // A 120-degree corner of 1 m radius after 0.5 m straight, ending on the arc.
    const double r = 1.0, c60 = std::cos(kPi / 3), s60 = std::sin(kPi / 3);
    drive_pose_t corner = to_fx({0.5 + r * s60, r * (1 + c60), 2 * kPi / 3});
    ASSERT_EQ(drive_leg_solve(&from, &corner, fx_q16_from_double(0.8), false, &leg), DRIVE_OK);
    EXPECT_NEAR(fx_q16_to_double(leg.via.x), 0.5 + r * s60, 1e-4);
    EXPECT_NEAR(fx_q16_to_double(leg.via.y), r * (1 - c60), 1e-4);
    EXPECT_NEAR(fx_angle_to_deg_signed(leg.via.heading), 60.0, 1e-5);
    // Refused: a U-turn across less than two radii; a turn away from the target's side.
    EXPECT_EQ(drive_leg_solve(&from, &to, fx_q16_from_double(1.01), false, &leg), DRIVE_ERR_TURN);
    drive_pose_t away = to_fx({1, -1, 2 * kPi / 3});
    EXPECT_EQ(drive_leg_solve(&from, &away, fx_q16_from_double(0.3), false, &leg), DRIVE_ERR_TURN);
    EXPECT_EQ(drive_leg_solve(&from, &to, fx_q16_from_double(0.1), false, &leg), DRIVE_ERR_PARAM);
    EXPECT_EQ(drive_leg_solve(nullptr, &to, fx_q16_from_double(0.5), false, &leg), DRIVE_ERR_PARAM);
    // 90 degrees exactly is one double arc (the solver's domain).
    drive_pose_t quarter = to_fx({1, 1, kPi / 2});
    ASSERT_EQ(drive_leg_solve(&from, &quarter, fx_q16_from_double(0.5), false, &leg), DRIVE_OK);
    EXPECT_EQ(leg.parts, 1);
    std::printf("U-turn across 2 m: arcs %.6f m, straights %.6f m\n", arc, straight);
}

namespace
{

// A serpentine through three aisles 2.4 m apart, joined by U-turns at alternate ends (left,
// then right), then a 120-degree corner and a last straight.
std::vector<drive_path_point_t> aisle_path(double speed, drive_pose_t *start)
{
    *start = to_fx({0, 0, 0});
    const double pts[][3] = {{6, 0, 0},
                             {6, 2.4, 180},
                             {0, 2.4, 180},
                             {0, 4.8, 0},
                             {6, 4.8, 0},
                             {7.5, 6.5, 120},
                             {6.5, 6.5 + std::sqrt(3.0), 120}};
    std::vector<drive_path_point_t> v;
    for (const auto &p : pts)
        v.push_back({to_fx({p[0], p[1], p[2] * kPi / 180}), fx_q16_from_double(speed), 0});
    return v;
}

} // namespace

// Path preparation splits the turns over 90 degrees; following the nominal legs from the
// start in double precision (each part from where the last one ended) lands on every
// prescribed pose; the secondary points lie on that path, at most `spacing` apart, and the
// inserted poses are among them. Forward and tail first.
TEST(DrivePath, AisleUTurnsAndCornersArePrepared)
{
    for (int rev = 0; rev < 2; rev++) {
        drive_pose_t start;
        std::vector<drive_path_point_t> pts = aisle_path(0.5, &start);
        if (rev) {
            start.heading += FX_ANGLE_HALF;
            for (auto &q : pts)
                q.pose.heading += FX_ANGLE_HALF;
        }
        drive_path_t path;
        drive_path_config_t cfg = path_cfg(0.6, 0.5, rev != 0);
        ASSERT_EQ(
            drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
            DRIVE_OK)
            << "leg " << (int)path.bad_leg << " piece " << (int)path.bad_sub << ": "
            << drive_status_text(path.bad_why);
        Pose p = from_fx(start), prev = p;
        double worst = 0, worst_off = 0, worst_gap = 0;
        int low = 0, splits = 0;
        for (uint8_t leg = 0; leg < pts.size(); leg++) {
            const drive_leg_t *nominal;
            ASSERT_EQ(drive_path_leg(&path, leg, &nominal), DRIVE_OK);
            drive_leg_t l = *nominal; // the cache moves on with drive_path_target()
            splits += l.parts == 2;
            int32_t dl = (int32_t)(pts[leg].pose.heading -
                                   (leg ? pts[leg - 1].pose.heading : start.heading));
            EXPECT_EQ(l.parts,
                      (dl > (int32_t)FX_ANGLE_QUARTER || dl < -(int32_t)FX_ANGLE_QUARTER) ? 2 : 1);
            std::vector<Pose> dense = sample_leg(prev, l, cfg.reverse, 2000);
            p = follow_leg(p, l, cfg.reverse, 0.6, nullptr, &low);
            Pose goal = from_fx(pts[leg].pose);
            worst = std::max(worst, std::hypot(p.x - goal.x, p.y - goal.y));
            ASSERT_LT(head_deg(p.th, goal.th), 0.02) << "leg " << (int)leg;
            Pose last = prev;
            int n0 = -1;
            for (uint8_t sub = 1; sub <= pts[leg].nsub; sub++) {
                drive_pose_t tp;
                fx_q16_t sp;
                ASSERT_EQ(drive_path_target(&path, {leg, sub}, &tp, &sp), DRIVE_OK);
                if (l.parts == 2 && tp.x == l.via.x && tp.y == l.via.y &&
                    tp.heading == l.via.heading)
                    n0 = sub;
                Pose q = from_fx(tp);
                double off = 1e9;
                for (const Pose &d : dense)
                    off = std::min(off, std::hypot(d.x - q.x, d.y - q.y));
                worst_off = std::max(worst_off, off);
                worst_gap = std::max(worst_gap, std::hypot(q.x - last.x, q.y - last.y));
                last = q;
            }
            if (l.parts == 2) {
                EXPECT_GT(n0, 0) << "leg " << (int)leg << ": the inserted pose is a target";
            }
            prev = goal;
        }
        EXPECT_EQ(splits, 3); // two U-turns and the 120-degree corner
        EXPECT_EQ(low, 0);
        EXPECT_LT(worst, 5e-4); // every prescribed pose, following from the start
        EXPECT_LT(worst_off, 2e-3);
        EXPECT_LE(worst_gap, 0.5 + 1e-4);
        std::printf("aisle path%s: %d legs split, landing on every prescribed pose within %.3g "
                    "mm following from the start, secondary points within %.3g mm of the "
                    "nominal path\n",
                    rev ? " (tail first)" : "", splits, worst * 1e3, worst_off * 1e3);
    }
}

// ------------------------------------------------------------------ travel state table

namespace
{

// A vehicle and its drive board in double precision, driven by the sequencer's actions
// through the real port encoder and decoder, and a clock that raises index pulses, fixes,
// poses, timers and delta-S pulses. The drive board executes an arc from its bytes: steering
// alpha = (128 - byte) pi / 256, curvature tan(alpha) / L, rear-axle length = counts /
// counts_per_m / sqrt(1 + (L k)^2); it raises delta-S when `margin` of an arc is left, arcs
// shorter than min_pulse_counts raise none (the D7 worst case), a zero-length arc is
// skipped, and it stops at the end of the second arc. Speed 0 brakes at 0.5 m/s^2 (never
// beyond the end of the loaded arcs).
struct World {
    const drive_board_t *board;
    drive_path_t *path;
    drive_seq_t seq;
    drive_decoder_t dec;
    Pose pose;
    double t = 0, v = 0, margin = 0.02;
    bool braking = false;
    struct Arc {
        double k, len, left;
        bool pulse;
    } arc[2] = {};
    int cur = 2;
    bool index_on = false, reverse = false, fail_fixes = false;
    double odo = 0;                        // rear-axle travel so far, m
    double fail_from = 1e9, fail_to = 1e9; // fixes fail while odo is in [fail_from, fail_to)
    struct Load {
        double odo, blind; // odo at the load, and since the last accepted fix
        int counts;        // its speed
    };
    std::vector<Load> load_log;
    double stop_odo = -1; // odo when the sequencer stopped the vehicle
    double fix_odo = 0;   // odo at the last accepted fix (the start first)
    double next_index = 0.5, t_fix = -1, t_pose = -1, t_timer = -1, pose_ms = 0;
    std::vector<double> pulses;       // pending delta-S times
    std::vector<Pose> stops;          // where STOP left the vehicle
    std::vector<uint16_t> action_log; // every non-empty action set
    int set_speeds = 0, events = 0;
    bool done = false, fault = false;
    drive_fault_t fault_why = DRIVE_FAULT_NONE;
    double cross_max = 0, cross_sum = 0;
    int cross_n = 0;
    std::vector<Pose> nominal; // the nominal path, densely sampled
    size_t near = 0;           // the sample nearest to the vehicle at the last step

    // The seed's vehicle at @p start on the prepared @p p, the sequencer set up with @p sc
    // (which must outlive the run).
    void begin(drive_path_t *p, drive_pose_t start, const drive_seq_config_t &sc)
    {
        board = &kSeedBoard;
        path = p;
        pose = from_fx(start);
        drive_decoder_init(&dec, 132);
        drive_seq_init(&seq, p, &sc);
    }

    double L() const
    {
        return fx_q16_to_double(board->wheelbase);
    }

    void load_bytes(const drive_cmd_t &c)
    {
        double cpm = fx_q16_to_double(board->counts_per_m);
        for (int i = 0; i < 2; i++) {
            double alpha = (128 - c.steer[i]) * kPi / 256, k = std::tan(alpha) / L();
            double len = c.arc[i] / cpm / std::sqrt(1 + L() * L() * k * k);
            arc[i] = {k, len, len, c.arc[i] < board->min_pulse_counts};
        }
        cur = arc[0].len > 0 ? 0 : 1;
        set_speed(c.speed);
    }

    void set_speed(int8_t counts)
    {
        if (counts == 0 && v != 0) {
            braking = true;
            return;
        }
        braking = false;
        v = counts * fx_q16_to_double(board->speed_lsb);
    }

    void send(const drive_wseq_t &s)
    {
        drive_event_t ev;
        for (int i = 0; i < s.n; i++) {
            if (!drive_decoder_feed(&dec, s.w[i].reg, s.w[i].value, &ev))
                continue;
            if (ev.type == DRIVE_EV_LOAD)
                load_bytes(ev.cmd);
            else if (ev.type == DRIVE_EV_SPEED)
                set_speed(ev.cmd.speed);
            else
                ADD_FAILURE() << "unexpected drive-board event " << ev.type;
        }
    }

    // Move the vehicle by dt seconds.
    void move(double dt)
    {
        if (braking) {
            double m = std::max(0.0, std::fabs(v) - 0.5 * dt);
            v = v < 0 ? -m : m;
            if (m == 0)
                braking = false;
        }
        double ds = std::fabs(v) * dt;
        while (ds > 0 && cur < 2 && v != 0) {
            Arc &a = arc[cur];
            double step = std::min(ds, a.left);
            pose = follow(pose, {{a.k, step}}, v < 0);
            odo += step;
            a.left -= step;
            ds -= step;
            if (!a.pulse && a.left <= margin) {
                a.pulse = true;
                pulses.push_back(t);
            }
            if (a.left <= 0) {
                cur++;
                if (cur == 1 && arc[1].len <= 0)
                    cur = 2;
                if (cur == 2)
                    v = 0;
            }
        }
        if (!nominal.empty() && !done) {
            // The nearest sample, searched around the last one (the vehicle moves 1 mm per
            // step, the samples are about as far apart: the window holds the nearest).
            double d = 1e9;
            size_t lo = near > 50 ? near - 50 : 0, hi = std::min(nominal.size(), near + 200);
            for (size_t i = lo; i < hi; i++) {
                double di = std::hypot(nominal[i].x - pose.x, nominal[i].y - pose.y);
                if (di < d) {
                    d = di;
                    near = i;
                }
            }
            cross_max = std::max(cross_max, d);
            cross_sum += d;
            cross_n++;
        }
    }

    Pose predict(double ms)
    {
        World w = *this;
        w.nominal.clear();
        for (int i = 0; i < (int)ms; i++)
            w.move(0.001);
        return w.pose;
    }

    void step(drive_evt_t type, Pose p = {})
    {
        drive_seq_event_t ev = {type, to_fx(p)};
        drive_seq_out_t out;
        drive_seq_step(&seq, &ev, &out);
        events++;
        if (out.actions)
            action_log.push_back(out.actions);
        drive_wseq_t s;
        if (out.actions & DRIVE_ACT_STOP) {
            drive_ppi_speed(0, &s);
            send(s);
            stops.push_back(pose);
            if (seq.state == DRIVE_ST_STOPPED && stop_odo < 0)
                stop_odo = odo;
        }
        if (out.actions & DRIVE_ACT_REQUEST_FIX)
            t_fix = t + 0.017;
        if (out.actions & DRIVE_ACT_REQUEST_POSE) {
            t_pose = t + 0.001;
            pose_ms = out.pose_ms;
        }
        if (out.actions & DRIVE_ACT_LOAD) {
            drive_ppi_load(&out.cmd, &s);
            send(s);
            load_log.push_back({odo, odo - fix_odo, out.cmd.speed});
        }
        if (out.actions & DRIVE_ACT_SET_SPEED) {
            drive_ppi_speed(out.speed, &s);
            send(s);
            set_speeds++;
        }
        if (out.actions & DRIVE_ACT_TIMER)
            t_timer = t + out.timer_ms / 1000.0;
        if (out.actions & DRIVE_ACT_INDEX_ON) {
            index_on = true;
            next_index = t + 0.5;
        }
        if (out.actions & DRIVE_ACT_INDEX_OFF)
            index_on = false;
        if (out.actions & DRIVE_ACT_DONE)
            done = true;
        if (out.actions & DRIVE_ACT_FAULT) {
            fault = true;
            fault_why = out.fault;
        }
    }

    // Run until done (or stopped), a fault or the time limit.
    void run(double limit)
    {
        drive_wseq_t s;
        drive_ppi_init(&s);
        send(s);
        step(DRIVE_EVT_START, from_fx(path->start));
        while (!done && !fault && t < limit) {
            t += 0.001;
            move(0.001);
            std::vector<double> due;
            for (double pt : pulses)
                if (pt <= t)
                    due.push_back(pt);
            for (size_t i = 0; i < due.size(); i++)
                step(DRIVE_EVT_DELTA_S);
            pulses.erase(
                std::remove_if(pulses.begin(), pulses.end(), [&](double x) { return x <= t; }),
                pulses.end());
            if (index_on && t >= next_index) {
                next_index += 0.5;
                step(DRIVE_EVT_INDEX);
            }
            if (t_fix >= 0 && t >= t_fix) {
                t_fix = -1;
                bool fail = fail_fixes || (odo >= fail_from && odo < fail_to);
                if (!fail)
                    fix_odo = odo;
                step(fail ? DRIVE_EVT_FIX_FAILED : DRIVE_EVT_FIX_READY, pose);
            }
            if (t_pose >= 0 && t >= t_pose) {
                t_pose = -1;
                step(DRIVE_EVT_POSE, pose_ms ? predict(pose_ms) : pose);
            }
            if (t_timer >= 0 && t >= t_timer) {
                t_timer = -1;
                step(DRIVE_EVT_TIMER);
            }
        }
        // Done: the vehicle brakes to a standstill.
        for (int i = 0; i < 5000 && v != 0; i++) {
            t += 0.001;
            move(0.001);
        }
    }
};

std::vector<Pose> nominal_of(drive_path_t *path)
{
    std::vector<Pose> v;
    Pose a = from_fx(path->start);
    for (uint8_t leg = 0; leg < path->n; leg++) {
        const drive_leg_t *nominal;
        if (drive_path_leg(path, leg, &nominal) != DRIVE_OK)
            return {};
        std::vector<Pose> d = sample_leg(a, *nominal, path->cfg.reverse, 400);
        v.insert(v.end(), d.begin(), d.end());
        a = from_fx(path->pts[leg].pose);
    }
    return v;
}

drive_seq_config_t seq_cfg(drive_mode_t mode, double blind = 8.0)
{
    return {mode,
            35,
            50,
            fx_q16_from_double(0.15),
            fx_q16_from_double(0.4),
            3,
            fx_q16_from_double(blind)};
}

} // namespace

TEST(DriveSeq, FullTravelDrivesTheSeedPathAndStops)
{
    for (int rev = 0; rev < 2; rev++) {
        drive_pose_t start;
        std::vector<drive_path_point_t> pts = seed_path(0.5, &start);
        if (rev) { // the same path tail first
            start.heading += FX_ANGLE_HALF;
            for (auto &q : pts)
                q.pose.heading += FX_ANGLE_HALF;
        }
        drive_path_t path;
        drive_path_config_t cfg = path_cfg(0.4, 0.8, rev != 0);
        ASSERT_EQ(
            drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
            DRIVE_OK);
        World w;
        drive_seq_config_t sc = seq_cfg(DRIVE_MODE_FULL);
        w.begin(&path, start, sc);
        w.nominal = nominal_of(&path);
        w.run(120);
        ASSERT_TRUE(w.done) << "state " << drive_seq_state_name(w.seq.state) << " fault "
                            << w.fault_why << " status " << w.seq.solve_status;
        Pose goal = from_fx(pts.back().pose);
        double miss = std::hypot(w.pose.x - goal.x, w.pose.y - goal.y);
        double hmiss = std::fabs(wrap_pi(w.pose.th - goal.th)) * 180 / kPi;
        std::printf("full travel%s: %.1f s, %u loads, %u underruns, %u ignored events, final miss "
                    "%.1f mm %.2f deg, cross-track mean %.1f mm max %.1f mm\n",
                    rev ? " (reverse)" : "", w.t, w.seq.loads, w.seq.underruns, w.seq.ignored,
                    miss * 1e3, hmiss, w.cross_sum / w.cross_n * 1e3, w.cross_max * 1e3);
        EXPECT_EQ(w.seq.state, DRIVE_ST_DONE);
        EXPECT_EQ(w.set_speeds, 1); // the stopping routine slowed down once
        EXPECT_GT(w.seq.loads, 8u);
        EXPECT_EQ(w.seq.underruns, 0u);
        EXPECT_LT(miss, 0.01);
        EXPECT_LT(hmiss, 1.0);
        EXPECT_LT(w.cross_max, 0.03);
    }
}

// Full travel through the aisles: both U-turns and the 120-degree corner are driven along
// their inserted poses, and the vehicle stops at the last point.
TEST(DriveSeq, FullTravelDrivesAisleUTurns)
{
    drive_pose_t start;
    std::vector<drive_path_point_t> pts = aisle_path(0.5, &start);
    drive_path_t path;
    drive_path_config_t cfg = path_cfg(0.6, 0.8, false);
    ASSERT_EQ(drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
              DRIVE_OK);
    World w;
    drive_seq_config_t sc = seq_cfg(DRIVE_MODE_FULL);
    w.begin(&path, start, sc);
    w.nominal = nominal_of(&path);
    w.run(200);
    ASSERT_TRUE(w.done) << "state " << drive_seq_state_name(w.seq.state) << " fault " << w.fault_why
                        << " status " << w.seq.solve_status;
    Pose goal = from_fx(pts.back().pose);
    double miss = std::hypot(w.pose.x - goal.x, w.pose.y - goal.y);
    double hmiss = std::fabs(wrap_pi(w.pose.th - goal.th)) * 180 / kPi;
    std::printf("aisle path, full travel: %.1f s, %u loads, %u underruns, final miss %.1f mm "
                "%.2f deg, cross-track mean %.1f mm max %.1f mm\n",
                w.t, w.seq.loads, w.seq.underruns, miss * 1e3, hmiss, w.cross_sum / w.cross_n * 1e3,
                w.cross_max * 1e3);
    EXPECT_EQ(w.seq.underruns, 0u);
    EXPECT_LT(miss, 0.01);
    EXPECT_LT(hmiss, 1.0);
    EXPECT_LT(w.cross_max, 0.03);
}

// A U-turn of 1 m radius at 1 m/s with secondary points 0.8 m apart: replanning from mid-arc
// toward the point after a nearly reached one would need more front-wheel counts than the
// byte holds (1.2 m of arc, 1.5 m of front wheel); the sequencer drives to the nearer point
// instead, and the run finishes (without that it stops on a range fault here).
TEST(DriveSeq, TightUTurnDrivesToTheNearerPoint)
{
    drive_pose_t start = to_fx({0.4, 0, 0}); // the index pulses' phase that needs the fallback
    std::vector<drive_path_point_t> pts = {
        {to_fx({4, 0, 0}), fx_q16_from_double(1.0), 0},
        {to_fx({4, 2, 0}), fx_q16_from_double(1.0), 0},
        {to_fx({0, 2, 0}), fx_q16_from_double(1.0), 0},
    };
    pts[1].pose.heading = pts[2].pose.heading = FX_ANGLE_HALF;
    drive_path_t path;
    drive_path_config_t cfg = path_cfg(0.5, 0.8, false);
    ASSERT_EQ(drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
              DRIVE_OK);
    World w;
    drive_seq_config_t sc = seq_cfg(DRIVE_MODE_FULL);
    w.begin(&path, start, sc);
    w.nominal = nominal_of(&path);
    w.run(60);
    ASSERT_TRUE(w.done) << "state " << drive_seq_state_name(w.seq.state) << " fault " << w.fault_why
                        << " status " << drive_status_text(w.seq.solve_status);
    Pose goal = from_fx(pts.back().pose);
    double miss = std::hypot(w.pose.x - goal.x, w.pose.y - goal.y);
    std::printf("U-turn of 1 m radius, full travel: %.1f s, %u loads, final miss %.1f mm, "
                "cross-track max %.1f mm\n",
                w.t, w.seq.loads, miss * 1e3, w.cross_max * 1e3);
    EXPECT_LT(miss, 0.01);
    EXPECT_LT(w.cross_max, 0.03);
}

TEST(DriveSeq, SimplifiedTravelStopsAtEveryPoint)
{
    drive_pose_t start;
    std::vector<drive_path_point_t> pts = seed_path(0.4, &start);
    drive_path_t path;
    drive_path_config_t cfg = path_cfg(0.4, 0.8, false);
    ASSERT_EQ(drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
              DRIVE_OK);
    World w;
    drive_seq_config_t sc = seq_cfg(DRIVE_MODE_SIMPLIFIED);
    w.begin(&path, start, sc);
    w.run(300);
    ASSERT_TRUE(w.done) << drive_seq_state_name(w.seq.state);
    int targets = 0;
    for (uint8_t leg = 0; leg < path.n; leg++)
        targets += pts[leg].nsub;
    Pose goal = from_fx(pts.back().pose);
    double miss = std::hypot(w.pose.x - goal.x, w.pose.y - goal.y);
    std::printf("simplified travel: %.1f s, %d stops for %d points, %u loads, final miss %.1f mm\n",
                w.t, (int)w.stops.size(), targets, w.seq.loads, miss * 1e3);
    EXPECT_EQ((int)w.stops.size(), targets);
    EXPECT_EQ((int)w.seq.loads, targets);
    EXPECT_LT(miss, 0.01);
    // Stop and go: every load is preceded by the fix of a clean revolution.
    int fixes = 0;
    for (uint16_t a : w.action_log)
        fixes += (a & DRIVE_ACT_REQUEST_FIX) != 0;
    EXPECT_EQ(fixes, targets);
}

TEST(DriveSeq, RejectedPathFixFailuresAndSpuriousEvents)
{
    drive_pose_t start;
    std::vector<drive_path_point_t> pts = seed_path(0.5, &start);
    pts[2].pose.heading += fx_angle_from_deg(120); // a turn no corner fits: unacceptable
    drive_path_t path;
    drive_path_config_t cfg = path_cfg(0.4, 0.8, false);
    ASSERT_NE(drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
              DRIVE_OK);
    drive_seq_t seq;
    drive_seq_config_t sc = seq_cfg(DRIVE_MODE_FULL);
    drive_seq_init(&seq, &path, &sc);
    drive_seq_event_t ev = {DRIVE_EVT_START, start};
    drive_seq_out_t out;
    drive_seq_step(&seq, &ev, &out);
    EXPECT_EQ(out.actions, DRIVE_ACT_FAULT);
    EXPECT_EQ(out.fault, DRIVE_FAULT_NOT_READY);
    EXPECT_EQ(seq.state, DRIVE_ST_FAULT);

    // Simplified travel, every fix fails: it retries max_fix_failures times, then faults.
    pts = seed_path(0.5, &start);
    ASSERT_EQ(drive_path_prepare(&path, &start, pts.data(), (uint8_t)pts.size(), &cfg, &kSeedBoard),
              DRIVE_OK);
    World w;
    drive_seq_config_t simple = seq_cfg(DRIVE_MODE_SIMPLIFIED);
    w.begin(&path, start, simple);
    w.fail_fixes = true;
    w.run(60);
    EXPECT_TRUE(w.fault);
    EXPECT_EQ(w.fault_why, DRIVE_FAULT_FIXES);
    EXPECT_EQ(w.seq.loads, 0u);

    // Events that have no row in the current state are ignored: nothing happens.
    uint16_t nrows;
    const drive_seq_row_t *rows = drive_seq_table(&nrows);
    World z;
    z.begin(&path, start, sc);
    std::mt19937_64 rng(4);
    int injected = 0;
    drive_wseq_t s;
    drive_ppi_init(&s);
    z.send(s);
    z.step(DRIVE_EVT_START, from_fx(start));
    while (!z.done && !z.fault && z.t < 120) {
        z.t += 0.001;
        z.move(0.001);
        if (rng() % 50 == 0) {
            drive_evt_t e = (drive_evt_t)(rng() % DRIVE_EVT_STOP); // never STOP
            bool has_row = false;
            for (uint16_t i = 0; i < nrows; i++)
                has_row |= (rows[i].state == z.seq.state || rows[i].state == DRIVE_ST_ANY) &&
                           rows[i].event == e;
            if (!has_row) {
                drive_state_t before = z.seq.state;
                uint16_t ign = z.seq.ignored;
                drive_seq_event_t sev = {e, to_fx(z.pose)};
                drive_seq_out_t o;
                drive_seq_step(&z.seq, &sev, &o);
                ASSERT_EQ(o.actions, 0);
                ASSERT_EQ(z.seq.state, before);
                ASSERT_EQ(z.seq.ignored, ign + 1);
                injected++;
            }
        }
        std::vector<double> due;
        for (double pt : z.pulses)
            if (pt <= z.t)
                due.push_back(pt);
        for (size_t i = 0; i < due.size(); i++)
            z.step(DRIVE_EVT_DELTA_S);
        z.pulses.erase(
            std::remove_if(z.pulses.begin(), z.pulses.end(), [&](double x) { return x <= z.t; }),
            z.pulses.end());
        if (z.index_on && z.t >= z.next_index) {
            z.next_index += 0.5;
            z.step(DRIVE_EVT_INDEX);
        }
        if (z.t_fix >= 0 && z.t >= z.t_fix) {
            z.t_fix = -1;
            z.step(DRIVE_EVT_FIX_READY, z.pose);
        }
        if (z.t_pose >= 0 && z.t >= z.t_pose) {
            z.t_pose = -1;
            z.step(DRIVE_EVT_POSE, z.pose_ms ? z.predict(z.pose_ms) : z.pose);
        }
        if (z.t_timer >= 0 && z.t >= z.t_timer) {
            z.t_timer = -1;
            z.step(DRIVE_EVT_TIMER);
        }
    }
    std::printf("spurious events injected and ignored: %d; the run still finished: %s\n", injected,
                z.done ? "yes" : "no");
    EXPECT_TRUE(z.done);
    EXPECT_GT(injected, 100);

    // A stop request ends any running state, and is ignored once the travel has ended.
    drive_seq_init(&seq, &path, &sc);
    ev = {DRIVE_EVT_START, start};
    drive_seq_step(&seq, &ev, &out);
    ev.type = DRIVE_EVT_STOP;
    drive_seq_step(&seq, &ev, &out);
    EXPECT_EQ(out.actions, DRIVE_ACT_STOP | DRIVE_ACT_DONE);
    EXPECT_EQ(out.stop, DRIVE_STOP_REQUEST);
    EXPECT_EQ(seq.state, DRIVE_ST_STOPPED);
    uint16_t ignored = seq.ignored;
    drive_seq_step(&seq, &ev, &out);
    EXPECT_EQ(out.actions, 0);
    EXPECT_EQ(seq.ignored, ignored + 1);
}

// D7 in the stopping routine: when the last double arc's second arc is too short for a
// pulse, the vehicle stops at the first (and only) pulse instead of waiting forever.
TEST(DriveSeq, ShortSecondArcStopsAtTheOnlyPulse)
{
    drive_pose_t start = to_fx({0, 0, 0});
    // Case 4: a left arc of 0.5 m radius over 30 degrees, then 8 mm straight (1.4 counts).
    double r = 0.5, a = kPi / 6;
    Pose end = {r * std::sin(a) + 0.008 * std::cos(a), r * (1 - std::cos(a)) + 0.008 * std::sin(a),
                a};
    std::vector<drive_path_point_t> pts = {{to_fx(end), fx_q16_from_double(0.3), 0}};
    drive_path_t path;
    drive_path_config_t cfg = path_cfg(0.4, 1.0, false);
    ASSERT_EQ(drive_path_prepare(&path, &start, pts.data(), 1, &cfg, &kSeedBoard), DRIVE_OK);
    World w;
    drive_seq_config_t sc = seq_cfg(DRIVE_MODE_FULL);
    w.begin(&path, start, sc);
    w.run(20);
    ASSERT_TRUE(w.done) << drive_seq_state_name(w.seq.state);
    EXPECT_EQ(w.seq.loaded.pulses, 1);
    EXPECT_EQ(w.set_speeds, 0); // no second pulse to slow down for
    double miss = std::hypot(w.pose.x - end.x, w.pose.y - end.y);
    std::printf("short second arc: stopped %.1f mm from the point\n", miss * 1e3);
    EXPECT_LT(miss, 0.01);
}

// The speed law of blind travel against its formula in double precision: speed * clamp(5/4 -
// blind / limit, 1/4, 1), never below the board's one speed count unless the path's speed is.
TEST(DriveSeq, BlindSpeedLawIsItsFormula)
{
    auto q = [](double v) { return fx_q16_from_double(v); };
    const fx_q16_t lsb = kSeedBoard.speed_lsb;
    const double lsb_m = fx_q16_to_double(lsb);
    std::mt19937_64 rng(16);
    std::uniform_real_distribution<double> u(0, 1);
    double worst = 0;
    for (int i = 0; i < 200000; i++) {
        double speed = u(rng) * 2.2, limit = 0.2 + u(rng) * 60, b = u(rng) * 1.5 * limit;
        if (i % 8 == 0)
            b = limit * (i % 48) / 32.0; // on and around the breakpoints
        fx_q16_t vs = q(speed), bs = q(b), ls = q(limit);
        double f = std::clamp(1.25 - fx_q16_to_double(bs) / fx_q16_to_double(ls), 0.25, 1.0);
        double v = fx_q16_to_double(vs);
        double want = std::max(v * f, std::min(v, lsb_m));
        double got = fx_q16_to_double(drive_blind_speed(vs, bs, ls, lsb));
        worst = std::max(worst, std::fabs(got - want) * 65536);
        // The factor is rounded to 2^-16 (up to 2.2 LSB of the speed), the product to 1/2 LSB.
        ASSERT_LE(std::fabs(got - want) * 65536, 3.0)
            << "speed " << speed << " blind " << b << " limit " << limit;
    }
    std::printf("blind speed law: worst difference from the formula %.2f LSB\n", worst);
    EXPECT_EQ(drive_blind_speed(q(1), q(2), q(8), lsb), q(1));       // full up to a quarter
    EXPECT_EQ(drive_blind_speed(q(1), q(4), q(8), lsb), q(0.75));    // 5/4 - 1/2
    EXPECT_EQ(drive_blind_speed(q(1), q(8), q(8), lsb), q(0.25));    // a quarter at the limit
    EXPECT_EQ(drive_blind_speed(q(1), q(800), q(8), lsb), q(0.25));  // and beyond
    EXPECT_EQ(drive_blind_speed(q(1), 0, 0, lsb), q(0.25));          // no blind distance
    EXPECT_EQ(drive_blind_speed(q(0.04), q(8), q(8), lsb), lsb);     // not below one count...
    EXPECT_EQ(drive_blind_speed(q(0.01), q(8), q(8), lsb), q(0.01)); // ...unless the path is
}

namespace
{

// A straight route of 30 m at 1 m/s in full travel (points every 10 m).
drive_status_t straight_route(drive_path_t *path, std::vector<drive_path_point_t> *pts,
                              drive_pose_t *start)
{
    *start = to_fx({0, 0, 0});
    *pts = {{to_fx({10, 0, 0}), fx_q16_from_double(1.0), 0},
            {to_fx({20, 0, 0}), fx_q16_from_double(1.0), 0},
            {to_fx({30, 0, 0}), fx_q16_from_double(1.0), 0}};
    drive_path_config_t cfg = path_cfg(0.5, 0.8, false);
    return drive_path_prepare(path, start, pts->data(), (uint8_t)pts->size(), &cfg, &kSeedBoard);
}

// The speed counts the law gives @p blind metres after the last fix at 1 m/s (the World's own
// odometer, a reference independent of the sequencer's chords).
int law_counts(double blind, double limit)
{
    double v = std::clamp(1.25 - blind / limit, 0.25, 1.0);
    return (int)std::lround(v / fx_q16_to_double(kSeedBoard.speed_lsb));
}

} // namespace

// Every fix fails from 2 m on: the vehicle drives on dead reckoning, slower as the blind
// distance (4 m) nears, and stops when it is up (a controlled stop, not a fault).
TEST(DriveSeq, BlindTravelSlowsDownAndStopsAtTheBlindDistance)
{
    drive_path_t path;
    std::vector<drive_path_point_t> pts;
    drive_pose_t start;
    ASSERT_EQ(straight_route(&path, &pts, &start), DRIVE_OK);
    const double limit = 4.0;
    World w;
    drive_seq_config_t sc = seq_cfg(DRIVE_MODE_FULL, limit);
    w.begin(&path, start, sc);
    w.fail_from = 2.0;
    w.run(60);
    ASSERT_TRUE(w.done) << drive_seq_state_name(w.seq.state);
    EXPECT_FALSE(w.fault);
    EXPECT_EQ(w.seq.state, DRIVE_ST_STOPPED);
    EXPECT_EQ(w.seq.stop, DRIVE_STOP_BLIND);
    EXPECT_EQ(w.v, 0.0); // braked to a standstill
    double blind = w.stop_odo - w.fix_odo;
    std::printf("blind travel: last fix at %.2f m, stopped at %.2f m (%.2f m blind of %.1f m), "
                "at rest at %.2f m\n",
                w.fix_odo, w.stop_odo, blind, limit, w.odo);
    // The stop comes at the first pose past the limit: at most one cycle at a quarter speed
    // later; the pose it judges is predicted 35 ms ahead.
    EXPECT_GE(blind, limit - 0.05);
    EXPECT_LE(blind, limit + 0.2);
    // Each double arc's speed follows the law of the travel since the fix.
    int prev = 1000, slowed = 0;
    for (const World::Load &l : w.load_log) {
        EXPECT_NEAR(l.counts, law_counts(l.blind, limit), 1) << "blind " << l.blind;
        if (l.odo > w.fix_odo) {
            EXPECT_LE(l.counts, prev);
            prev = l.counts;
            slowed += l.counts < law_counts(0, limit);
        }
    }
    EXPECT_GT(slowed, 4);
}

// A 2.5 m gap without fixes on the way (blind distance 4 m): the vehicle slows down in it,
// takes full speed again at the first fix after it and reaches its goal.
TEST(DriveSeq, BlindTravelThroughAGapReachesTheGoal)
{
    drive_path_t path;
    std::vector<drive_path_point_t> pts;
    drive_pose_t start;
    ASSERT_EQ(straight_route(&path, &pts, &start), DRIVE_OK);
    const double limit = 4.0;
    World w;
    drive_seq_config_t sc = seq_cfg(DRIVE_MODE_FULL, limit);
    w.begin(&path, start, sc);
    w.fail_from = 8.0;
    w.fail_to = 10.5;
    w.run(90);
    ASSERT_TRUE(w.done) << drive_seq_state_name(w.seq.state);
    EXPECT_EQ(w.seq.state, DRIVE_ST_DONE);
    EXPECT_EQ(w.seq.stop, DRIVE_STOP_NONE);
    EXPECT_NEAR(w.pose.x, 30.0, 0.01);
    int slowest = 1000, after = 0;
    double longest = 0;
    for (const World::Load &l : w.load_log) {
        if (l.odo < 27.0) { // before the stopping routine
            EXPECT_NEAR(l.counts, law_counts(l.blind, limit), 1)
                << "at " << l.odo << " m, blind " << l.blind;
        }
        if (l.odo > 8.0 && l.odo < 12.0 && l.counts < slowest) {
            slowest = l.counts;
            longest = l.blind;
        }
        after += l.odo > 12.0 && l.odo < 27.0 && l.counts == law_counts(0, limit);
    }
    std::printf(
        "a 2.5 m gap: slowest %d counts %.2f m after the last fix (full speed %d), %d loads "
        "at full speed after it\n",
        slowest, longest, law_counts(0, limit), after);
    EXPECT_LT(slowest, law_counts(0, limit));
    EXPECT_GT(longest, 2.5);
    EXPECT_GT(after, 10);
}

TEST(DriveSeq, TableIsConsistent)
{
    uint16_t n;
    const drive_seq_row_t *rows = drive_seq_table(&n);
    std::set<drive_state_t> reached = {DRIVE_ST_IDLE};
    for (uint16_t i = 0; i < n; i++) {
        ASSERT_TRUE(rows[i].state < DRIVE_ST_COUNT || rows[i].state == DRIVE_ST_ANY);
        ASSERT_LT(rows[i].event, DRIVE_EVT_COUNT);
        ASSERT_TRUE(rows[i].next < DRIVE_ST_COUNT || rows[i].next == 0xFE);
        if (rows[i].next < DRIVE_ST_COUNT)
            reached.insert((drive_state_t)rows[i].next);
        for (uint16_t j = 0; j < i; j++) // no duplicate (state, event, guard)
            ASSERT_FALSE(rows[j].state == rows[i].state && rows[j].event == rows[i].event &&
                         rows[j].guard == rows[i].guard)
                << "rows " << j << " and " << i;
    }
    EXPECT_EQ(reached.size(), (size_t)DRIVE_ST_COUNT); // every state is entered somewhere
    std::printf("state table: %u rows, %d states, %d events\n", n, (int)DRIVE_ST_COUNT,
                (int)DRIVE_EVT_COUNT);
}
