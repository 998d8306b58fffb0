// Tests of seed 002's goal-point pursuit (firmware/pursuit): the seed's own simulator record
// (its chapter 5: "Turn AGV 6.654644 degrees for 0.400000 seconds"), the law against a
// double-precision transcription of the seed's Navigate_Path written here, goal switching at
// the threshold, the end of the path, the held correction, the steering limit, and the future
// work: slowing down and stopping without updates, speed regulation against a drive whose
// speed per count is not the nominal one, two receivers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

extern "C" {
#include "fx/fx_host.h"
#include "pursuit/pursuit.h"
}

namespace
{

constexpr double kPi = 3.14159265358979323846;

struct Pt {
    double x, y;
};

double deg(double rad)
{
    return rad * 180.0 / kPi;
}

// Seed 002's Calc_Angle: the direction of the vector a -> b, (-pi, pi].
double calc_angle(Pt a, Pt b)
{
    return std::atan2(b.y - a.y, b.x - a.x);
}

// Seed 002's Navigate_Path, one update at a time, in double precision (its listing, with the
// heading error wrapped to (-pi, pi]: the seed's two special cases miss pairs such as -10 and
// 175 degrees; docs/pursuit.md).
struct SeedNav {
    std::vector<Pt> pts;
    size_t i = 1; // the goal: pts[i]
    Pt last{}, goal{}, prev{};
    double d = 0, theta = 0, thresh = 0.5, K = 1.0;
    bool done = false;
    void segment()
    {
        last = pts[i - 1];
        goal = pts[i];
        d = std::hypot(goal.x - last.x, goal.y - last.y);
        theta = calc_angle(last, goal);
    }
    struct Out {
        double dir, err, xdist, dphi, alpha;
        double margin; // nearest any comparison came to its edge, m
        size_t segment, goal;
        bool correct;
    };
    Out step(Pt agv)
    {
        Out o{};
        o.dir = calc_angle(prev, agv);
        double x = agv.x - last.x, y = agv.y - last.y;
        double xdist = x * std::cos(-theta) - y * std::sin(-theta);
        o.err = std::fabs(x * std::sin(-theta) + y * std::cos(-theta));
        o.xdist = xdist;
        o.segment = i;
        o.margin = std::fabs(xdist - d);
        if (i == pts.size() - 1 && xdist >= d)
            done = true;
        for (;;) {
            o.margin = std::min(o.margin, std::fabs(xdist - thresh * d));
            if (!(xdist >= thresh * d && i != pts.size() - 1))
                break;
            i++;
            segment();
            x = agv.x - last.x;
            y = agv.y - last.y;
            xdist = x * std::cos(-theta) - y * std::sin(-theta);
        }
        o.goal = i;
        double phi2 = calc_angle(agv, goal);
        o.dphi = std::remainder(phi2 - o.dir, 2 * kPi);
        int intphi = (int)(o.dphi * 180 / kPi);
        o.correct = intphi != 0 && !done;
        o.alpha = K * o.dphi;
        prev = agv;
        return o;
    }
};

fx_q16_t q(double v)
{
    return fx_q16_from_double(v);
}

pursuit_config_t seed_config()
{
    pursuit_config_t c{};
    c.speed = q(0.2);
    c.max_speed = q(1.0);
    c.k = q(1.0);
    c.activation_ms = 400;
    c.threshold = q(0.5);
    c.max_steer = fx_angle_from_deg(60.0);
    return c;
}

struct Drive {
    std::vector<drive_path_point_t> path;
    pursuit_t p{};
    explicit Drive(const std::vector<Pt> &pts, const pursuit_config_t &c)
    {
        for (size_t k = 1; k < pts.size(); k++) {
            drive_path_point_t dp{};
            dp.pose.x = q(pts[k].x);
            dp.pose.y = q(pts[k].y);
            path.push_back(dp);
        }
        EXPECT_TRUE(
            pursuit_init(&p, &c, q(pts[0].x), q(pts[0].y), path.data(), (uint16_t)path.size()));
    }
};

double signed_deg(fx_angle_t a)
{
    return fx_angle_to_deg(a) > 180.0 ? fx_angle_to_deg(a) - 360.0 : fx_angle_to_deg(a);
}

// The seed's simulator record (chapter 5, EVENTDAT.DAT), centimetres as metres / 100.
TEST(PursuitSeed, TheSimulatorRecordOfChapterFive)
{
    std::vector<Pt> pts;
    for (int k = 0; k < 8; k++)
        pts.push_back({(66.669998 + 20.0 * k) / 100, 933.330017 / 100});
    Drive r(pts, seed_config());
    pursuit_out_t out;
    pursuit_start(&r.p, 0, 0, &out);
    pursuit_record_t rec;
    // "AGV position: x=81.574493 y=932.242493 dir=-4.173383" (to 0.01 degrees: the firmware's
    // positions are Q16 metres, 15 um, on a 0.15 m baseline)
    pursuit_position(&r.p, q(0.81574493), q(9.32242493), nullptr, 400, &rec, &out);
    EXPECT_NEAR(signed_deg(rec.heading), -4.173383, 1e-2);
    // "Read path point: x=106.669998": past half of the first segment
    EXPECT_EQ(rec.goal, 2);
    // "xdist=-5.095505 d=20.000000 phi2=2.481567" (after the switch), "Turn AGV 6.654644
    // degrees for 0.400000 seconds"
    ASSERT_TRUE(out.actions & PURSUIT_ACT_STEER);
    EXPECT_NEAR(signed_deg(out.steer), 6.654644, 1e-2);
    EXPECT_NEAR(signed_deg(rec.dphi), 6.654644, 1e-2);
    // the hold ends 0.4 s later: straight ahead
    pursuit_tick(&r.p, 799, &out);
    EXPECT_EQ(out.actions, 0);
    pursuit_tick(&r.p, 800, &out);
    ASSERT_EQ(out.actions, PURSUIT_ACT_STEER);
    EXPECT_EQ(out.steer, 0u);
    // "AGV position: x=96.634926 y=931.440186 dir=-3.049498", "xdist=9.964928 d=20.000000
    // phi2=10.665968", "Turn AGV 13.714590 degrees for 0.400000 seconds"
    pursuit_position(&r.p, q(0.96634926), q(9.31440186), nullptr, 800, &rec, &out);
    EXPECT_NEAR(signed_deg(rec.heading), -3.049498, 1e-2);
    EXPECT_NEAR(fx_q16_to_double(rec.xdist), 0.09964928, 3e-5);
    EXPECT_EQ(rec.goal, 2);
    ASSERT_TRUE(out.actions & PURSUIT_ACT_STEER);
    EXPECT_NEAR(signed_deg(out.steer), 13.714590, 1e-2);
    // "AGV position: x=111.279488 y=932.331360 dir=3.482463", "Read path point: x=126.669998"
    pursuit_tick(&r.p, 1200, &out);
    pursuit_position(&r.p, q(1.11279488), q(9.32331360), nullptr, 1200, &rec, &out);
    EXPECT_NEAR(signed_deg(rec.heading), 3.482463, 1e-2);
    EXPECT_EQ(rec.goal, 3);
}

// The law against the seed's Navigate_Path on random paths and drives.
TEST(PursuitSeed, MatchesTheSeedsNavigationOnRandomPaths)
{
    std::mt19937 g(1993);
    std::uniform_real_distribution<double> u(0, 1);
    int corrections = 0, switches = 0, updates = 0;
    for (int trial = 0; trial < 300; trial++) {
        std::vector<Pt> pts = {{u(g) * 20 - 10, u(g) * 20 - 10}};
        double h = u(g) * 2 * kPi;
        for (int k = 0; k < 12; k++) {
            h += (u(g) - 0.5) * 2.0;
            double s = 0.3 + u(g) * 1.5;
            pts.push_back({pts.back().x + s * std::cos(h), pts.back().y + s * std::sin(h)});
        }
        for (Pt &pt : pts) // the points as the firmware holds them
            pt = {fx_q16_to_double(q(pt.x)), fx_q16_to_double(q(pt.y))};
        pursuit_config_t c = seed_config();
        SeedNav ref;
        ref.pts = pts;
        c.threshold = q(0.3 + 0.6 * u(g));
        c.k = q(0.5 + u(g));
        ref.thresh = fx_q16_to_double(c.threshold); // the parameters as the firmware holds them
        ref.K = fx_q16_to_double(c.k);
        c.max_steer = fx_angle_from_deg(89.0);
        ref.segment();
        ref.prev = pts[0];
        Drive r(pts, c);
        pursuit_out_t out;
        pursuit_start(&r.p, 0, 0, &out);
        // a vehicle somewhere near the path, moving on
        Pt agv = pts[0];
        uint32_t t = 0;
        for (int k = 0; k < 80 && !ref.done; k++) {
            size_t gi = ref.i;
            Pt target = ref.pts[gi];
            double a = calc_angle(agv, target) + (u(g) - 0.5) * 1.2;
            double step = 0.1 + 0.2 * u(g);
            agv = {agv.x + step * std::cos(a), agv.y + step * std::sin(a)};
            t += 500; // the correction before has been held and released
            pursuit_tick(&r.p, t, &out);
            Pt qa = {fx_q16_to_double(q(agv.x)), fx_q16_to_double(q(agv.y))};
            SeedNav::Out want = ref.step(qa);
            if (want.margin < 1e-4)
                break; // on an edge of the goal switch: the rounding decides, the runs part
            pursuit_record_t rec;
            pursuit_position(&r.p, q(agv.x), q(agv.y), nullptr, t, &rec, &out);
            updates++;
            ASSERT_NEAR(fx_q16_to_double(rec.err), want.err, 1e-4) << trial << " " << k;
            ASSERT_EQ(rec.segment, want.segment);
            ASSERT_EQ(rec.goal, want.goal) << trial << " " << k << " xdist " << want.xdist;
            ASSERT_EQ(pursuit_done(&r.p), ref.done);
            switches += want.goal != want.segment;
            if (std::fabs(deg(want.dphi)) > 0.999 && std::fabs(deg(want.dphi)) < 1.001)
                continue; // on the one-degree edge: rounding decides
            ASSERT_EQ((out.actions & PURSUIT_ACT_STEER) && out.steer != 0, want.correct)
                << trial << " " << k << " dphi " << deg(want.dphi);
            if (want.correct) {
                corrections++;
                double lim = std::max(-89.0, std::min(89.0, deg(want.alpha)));
                ASSERT_NEAR(signed_deg(out.steer), lim, 1e-3);
            }
        }
    }
    EXPECT_GT(corrections, 1000);
    EXPECT_GT(switches, 500);
    EXPECT_GT(updates, 3000);
}

TEST(Pursuit, SeveralGoalsInOneUpdateAndTheEnd)
{
    std::vector<Pt> pts = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}};
    Drive r(pts, seed_config());
    pursuit_out_t out;
    pursuit_start(&r.p, 0, 0, &out);
    EXPECT_EQ(out.actions, PURSUIT_ACT_SPEED | PURSUIT_ACT_STEER);
    EXPECT_EQ(out.speed, 25) << "0.2 of max: 128 + 25.4 counts";
    pursuit_record_t rec;
    pursuit_position(&r.p, q(2.6), q(0.05), nullptr, 1000, &rec, &out);
    EXPECT_EQ(rec.segment, 1);
    EXPECT_EQ(rec.goal, 4) << "2.6 m is past half of segments 1, 2 and 3";
    EXPECT_NEAR(fx_q16_to_double(rec.err), 0.05, 2e-5);
    EXPECT_FALSE(pursuit_done(&r.p));
    pursuit_tick(&r.p, 2000, &out);
    pursuit_position(&r.p, q(3.99), q(0.0), nullptr, 2000, &rec, &out);
    EXPECT_FALSE(pursuit_done(&r.p));
    pursuit_position(&r.p, q(4.0), q(0.01), nullptr, 2100, &rec, &out);
    EXPECT_TRUE(pursuit_done(&r.p));
    EXPECT_EQ(out.actions, PURSUIT_ACT_SPEED | PURSUIT_ACT_STEER | PURSUIT_ACT_DONE);
    EXPECT_EQ(out.speed, 0);
    EXPECT_EQ(out.steer, 0u);
    pursuit_tick(&r.p, 9000, &out);
    EXPECT_EQ(out.actions, 0) << "nothing after the end";
    EXPECT_EQ(r.p.st.updates, 3u);
    EXPECT_EQ(r.p.st.goals, 3);
}

TEST(Pursuit, OnCourseHoldAndSteeringLimit)
{
    std::vector<Pt> pts = {{0, 0}, {10, 0}};
    pursuit_config_t c = seed_config();
    c.k = q(2.0);
    c.max_steer = fx_angle_from_deg(30.0);
    Drive r(pts, c);
    pursuit_out_t out;
    pursuit_start(&r.p, 0, 0, &out);
    pursuit_record_t rec;
    // heading 0, goal straight ahead: on course, no correction
    pursuit_position(&r.p, q(0.1), q(0.0), nullptr, 100, &rec, &out);
    EXPECT_EQ(out.actions, 0);
    // 0.9 degrees off: still on course (the seed's whole degrees)
    double y = 0.1 * std::tan(0.9 * kPi / 180);
    pursuit_position(&r.p, q(0.2), q(-y), nullptr, 200, &rec, &out);
    EXPECT_EQ(out.actions, 0);
    // 20 degrees off with K = 2: 40 degrees, limited to 30
    pursuit_position(&r.p, q(0.3), q(-y - 0.1 * std::tan(20 * kPi / 180)), nullptr, 300, &rec,
                     &out);
    ASSERT_TRUE(out.actions & PURSUIT_ACT_STEER);
    EXPECT_NEAR(signed_deg(out.steer), 30.0, 1e-6);
    // held: the next update records but does not steer
    pursuit_position(&r.p, q(0.4), q(-0.1), nullptr, 500, &rec, &out);
    EXPECT_EQ(out.actions, 0);
    EXPECT_EQ(r.p.st.updates, 4u);
    pursuit_tick(&r.p, 700, &out);
    EXPECT_EQ(out.actions, PURSUIT_ACT_STEER);
    EXPECT_EQ(r.p.st.corrections, 1);
}

// Half of max speed, slower after 0.5 s without an update, stopped after 2.5 s.
pursuit_config_t recovery_config()
{
    pursuit_config_t c = seed_config();
    c.speed = q(0.5);
    c.slow_after_ms = 500;
    c.stop_after_ms = 2500;
    return c;
}

TEST(PursuitRecovery, SlowDownStopAndResume)
{
    Drive r({{0, 0}, {10, 0}}, recovery_config());
    pursuit_out_t out;
    pursuit_start(&r.p, 0, 1000, &out);
    EXPECT_EQ(out.speed, 64) << "0.5 of max: 63.5 counts, rounded away from zero";
    pursuit_tick(&r.p, 1500, &out);
    EXPECT_EQ(out.actions, 0) << "0.5 s without an update: still full speed";
    // halfway between 0.5 s and 2.5 s without an update: half speed
    pursuit_tick(&r.p, 2500, &out);
    ASSERT_EQ(out.actions, PURSUIT_ACT_SPEED);
    EXPECT_EQ(out.speed, 32);
    pursuit_tick(&r.p, 3000, &out);
    EXPECT_EQ(out.speed, 16); // a quarter of 63.5 = 15.9
    pursuit_tick(&r.p, 3500, &out);
    ASSERT_EQ(out.actions, PURSUIT_ACT_SPEED);
    EXPECT_EQ(out.speed, 0);
    pursuit_tick(&r.p, 60000, &out);
    EXPECT_EQ(out.actions, 0) << "standing, waiting";
    // a plausible update (too close: the vehicle stands) brings the speed back
    pursuit_alive(&r.p, 60010);
    pursuit_tick(&r.p, 60011, &out);
    ASSERT_EQ(out.actions, PURSUIT_ACT_SPEED);
    EXPECT_EQ(out.speed, 64);
    EXPECT_EQ(r.p.st.slowdowns, 1);
    EXPECT_EQ(r.p.st.stops, 1);
    EXPECT_EQ(r.p.st.resumes, 1);
}

// pursuit_next_tick(): every tick before the millisecond it names does nothing (checked on a
// copy, millisecond by millisecond), and the one it names acts when the law is due.
static void expect_quiet_until(const pursuit_t &p, uint32_t now, uint32_t until)
{
    pursuit_t c = p;
    for (uint32_t t = now + 1; t < until; t++) {
        pursuit_out_t out;
        pursuit_tick(&c, t, &out);
        ASSERT_EQ(out.actions, 0) << "a tick at " << t << " ms acted, before " << until;
        ASSERT_EQ(std::memcmp(&c, &p, sizeof c), 0) << "a tick at " << t << " ms changed state";
    }
}

TEST(PursuitRecovery, NextTickIsTheFirstThatActs)
{
    Drive r({{0, 0}, {10, 0}}, recovery_config());
    uint32_t at = 0;
    EXPECT_FALSE(pursuit_next_tick(&r.p, 0, &at)) << "not started";
    pursuit_out_t out;
    pursuit_start(&r.p, 0, 1000, &out);
    // full speed until more than slow_after_ms without an update: the first slower ms is 1501
    ASSERT_TRUE(pursuit_next_tick(&r.p, 1000, &at));
    EXPECT_EQ(at, 1501u);
    expect_quiet_until(r.p, 1000, at);
    pursuit_tick(&r.p, at, &out);
    EXPECT_EQ(out.actions, PURSUIT_ACT_SPEED);
    // slowing down: the factor moves by the millisecond
    ASSERT_TRUE(pursuit_next_tick(&r.p, 1501, &at));
    EXPECT_EQ(at, 1502u);
    // stopped (2.5 s without an update): nothing falls due until a position comes
    pursuit_tick(&r.p, 3500, &out);
    ASSERT_EQ(out.speed, 0);
    EXPECT_FALSE(pursuit_next_tick(&r.p, 3500, &at));
    expect_quiet_until(r.p, 3500, 6000);
    pursuit_alive(&r.p, 6000);
    ASSERT_TRUE(pursuit_next_tick(&r.p, 6000, &at));
    EXPECT_LE(at, 6000u) << "the resume is due at once";
    pursuit_tick(&r.p, 6000, &out);
    ASSERT_EQ(out.actions, PURSUIT_ACT_SPEED);
    ASSERT_TRUE(pursuit_next_tick(&r.p, 6000, &at));
    EXPECT_EQ(at, 6501u);
    expect_quiet_until(r.p, 6000, at);
}

TEST(Pursuit, NextTickEndsAHeldCorrection)
{
    std::vector<Pt> pts = {{0, 0}, {10, 0}};
    pursuit_config_t c = seed_config();
    c.k = q(2.0);
    Drive r(pts, c);
    pursuit_out_t out;
    pursuit_start(&r.p, 0, 0, &out);
    pursuit_record_t rec;
    pursuit_position(&r.p, q(0.1), q(0.0), nullptr, 100, &rec, &out);
    pursuit_position(&r.p, q(0.2), q(-0.05), nullptr, 200, &rec, &out);
    ASSERT_TRUE(out.actions & PURSUIT_ACT_STEER) << "a correction, held for activation_ms";
    uint32_t at = 0;
    ASSERT_TRUE(pursuit_next_tick(&r.p, 200, &at));
    EXPECT_EQ(at, 200u + c.activation_ms);
    expect_quiet_until(r.p, 200, at);
    pursuit_tick(&r.p, at, &out);
    EXPECT_EQ(out.actions, PURSUIT_ACT_STEER) << "the hold ends: straight again";
    EXPECT_FALSE(pursuit_next_tick(&r.p, at, &at)) << "no slow-down configured, nothing held";
}

// A drive board whose true speed per count is 1.3 times what max_speed says: regulation
// brings the measured speed to the one asked for.
TEST(PursuitRegulation, MeasuredSpeedMatchesTheAskedSpeed)
{
    std::vector<Pt> pts = {{0, 0}, {100, 0}};
    pursuit_config_t c = seed_config();
    c.speed = q(1.0);
    c.max_speed = q(2.0);
    c.regulate = true;
    Drive r(pts, c);
    pursuit_out_t out;
    pursuit_start(&r.p, 0, 0, &out);
    int counts = out.speed;
    const double true_per_count = 1.3 * 2.0 / 127;
    double x = 0, v = 0;
    for (uint32_t t = 1; t <= 40000; t++) {
        x += v * 0.001;
        pursuit_tick(&r.p, t, &out);
        if (out.actions & PURSUIT_ACT_SPEED)
            counts = out.speed;
        if (t % 100 == 0) {
            pursuit_record_t rec;
            pursuit_position(&r.p, q(x), 0, nullptr, t, &rec, &out);
            if (out.actions & PURSUIT_ACT_SPEED)
                counts = out.speed;
        }
        v = counts * true_per_count;
    }
    EXPECT_NEAR(v, 1.0, 0.012) << "within one count (0.02 m/s) of the asked speed";
    EXPECT_NEAR(fx_q16_to_double(r.p.cal), 1.3, 0.03);
    EXPECT_GT(r.p.st.regulations, 10);
    // without regulation the same drive runs 30 % fast
    c.regulate = false;
    Drive r2(pts, c);
    pursuit_start(&r2.p, 0, 0, &out);
    EXPECT_NEAR(out.speed * true_per_count, 1.3, 0.02);
}

TEST(PursuitPair, HeadingFromTwoReceiversAndTheDistanceCheck)
{
    std::vector<Pt> pts = {{0, 0}, {10, 0}};
    pursuit_config_t c = seed_config();
    // receiver 1 0.3 m ahead of receiver 2 and 0.1 m to the left of it
    c.pair_sep = q(std::hypot(0.3, 0.1));
    c.pair_angle = fx_angle_from_rad(std::atan2(0.1, 0.3));
    c.pair_tol = q(0.05);
    Drive r(pts, c);
    std::mt19937 g(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int k = 0; k < 1000; k++) {
        double h = u(g) * 2 * kPi, x2 = u(g) * 40 - 20, y2 = u(g) * 40 - 20;
        double x1 = x2 + 0.3 * std::cos(h) - 0.1 * std::sin(h);
        double y1 = y2 + 0.3 * std::sin(h) + 0.1 * std::cos(h);
        fx_angle_t got = 0;
        ASSERT_TRUE(pursuit_pair(&r.p, q(x1), q(y1), q(x2), q(y2), &got));
        double e = std::remainder(fx_angle_to_rad(got) - h, 2 * kPi);
        ASSERT_LT(std::fabs(e), 2e-4) << "heading within 0.01 degrees";
        // a bad update of either receiver: 8 cm off
        double a = u(g) * 2 * kPi;
        ASSERT_FALSE(pursuit_pair(&r.p, q(x1 + 0.08 * std::cos(h)), q(y1 + 0.08 * std::sin(h)),
                                  q(x2), q(y2), &got));
        (void)a;
    }
    EXPECT_EQ(r.p.st.pair_rejects, 1000);
}

TEST(Pursuit, ConfigurationChecks)
{
    pursuit_config_t c = seed_config();
    EXPECT_TRUE(pursuit_config_ok(&c));
    pursuit_config_t bad[] = {c, c, c, c, c, c, c, c};
    bad[0].speed = 0;
    bad[1].speed = q(1.5); // above max_speed
    bad[2].k = 0;
    bad[3].activation_ms = 0;
    bad[4].threshold = q(1.01);
    bad[5].max_steer = FX_ANGLE_QUARTER;
    bad[6].slow_after_ms = 500;
    bad[6].stop_after_ms = 500;
    bad[7].k = 9 * FX_Q16_ONE;
    for (auto &b : bad)
        EXPECT_FALSE(pursuit_config_ok(&b));
    std::vector<Pt> dup = {{0, 0}, {1, 0}, {1, 0}};
    std::vector<drive_path_point_t> path(2);
    path[0].pose.x = q(1);
    path[1].pose.x = q(1);
    pursuit_t p;
    EXPECT_FALSE(pursuit_init(&p, &c, 0, 0, path.data(), 2)) << "a segment of no length";
    EXPECT_FALSE(pursuit_init(&p, &c, 0, 0, path.data(), 0));
    EXPECT_TRUE(pursuit_init(&p, &c, 0, 0, path.data(), 1));
}

} // namespace
