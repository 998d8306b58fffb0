// groundnav_test.cpp - the nav board's ground navigation (issue 5, SPEC G1-G6).
//
// Independent references:
//  - exact tricycle kinematics (the rear-axle centre on arcs of constant curvature, the
//    steered front wheel L ahead; odometer pulses every dl of FRONT-wheel travel, gyro edges
//    where the heading crosses a threshold) generate the pulse streams and the true poses;
//  - a double-precision run of the same algorithm (RefNav below, written from the
//    description in docs/groundnav.md, not from the fixed-point code) gives the arithmetic
//    fidelity;
//  - the seed's own method (SeedNav: chapter 3 of seed 000, equations 3.5-3.8, in double
//    precision) is the accuracy to beat.
// The floors of the issue are asserted; the figures are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

extern "C" {
#include "fx/fx_host.h"
#include "groundnav/gnav.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal/preempt.h"
#include "hal_posix/harness.h"
}

namespace
{

constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------------ configuration

struct Cfg {
    double L = 0.762;     // 30 in
    double dl = 0.000254; // 0.01 in
    double step_deg = 0.25;
    double stop_m = 0.0;
};

gnav_config_t to_fx(const Cfg &c)
{
    gnav_config_t f{};
    f.wheelbase = (fx_q16_t)std::llround(c.L * 65536.0);
    f.dl_q40 = (uint32_t)std::llround(c.dl * 1099511627776.0);
    f.gyro_step_q48 = (uint64_t)std::llround(c.step_deg / 360.0 * 281474976710656.0);
    f.stop_distance = (fx_q16_t)std::llround(c.stop_m * 65536.0);
    return f;
}

// The parameters exactly as the firmware holds them (the same algorithm, the same inputs).
struct Params {
    double L, dl, beta;
};

Params params_of(const gnav_config_t &f)
{
    return {f.wheelbase / 65536.0, f.dl_q40 / 1099511627776.0,
            (double)f.gyro_step_q48 / 281474976710656.0 * 2.0 * kPi};
}

struct Pose {
    double x, y, th;
};

gnav_pose_t to_fx(const Pose &p)
{
    return {fx_q16_from_double(p.x), fx_q16_from_double(p.y), fx_angle_from_rad(p.th)};
}

double wrap(double a)
{
    return std::remainder(a, 2.0 * kPi);
}

// ------------------------------------------------------------------ exact kinematics

// SIGHT (a beacon sighting) and READ (a goniometer revolution ended: its latches are read)
// only when generate() is asked for sightings.
enum Ev { PULSE, UP, DOWN, REV_ON, REV_OFF, SIGHT, READ };

struct Segment {
    double front; // front-wheel travel, metres (> 0)
    double curv;  // rear-axle curvature, 1/m, left positive
    bool back;    // travelling backwards
};

struct Stream {
    std::vector<Ev> ev;
    std::vector<Pose> truth; // exact pose after each pulse
    std::vector<Pose> sight; // exact pose at each sighting
    std::vector<int> cell;   // the gyro's reading at each sighting
    double front = 0.0;      // total front-wheel travel
};

// Sightings for generate(): every `every` metres of front travel on average (a fixed
// pseudo-random jitter of +-40 %), revolutions of `rev` metres (their latches are read at the
// end); at 1 m/s and 2 rev/s 0.5 m, 15 sightings 0.033 m apart.
struct Sightings {
    double every = 0.0; // 0: none
    double rev = 0.5;
};

// An arc of heading change deg at radius r (r < 0: right), forwards or backwards.
Segment arc(double r, double deg, bool back = false, double L = 0.762)
{
    double k = 1.0 / r;
    double rear = std::fabs(deg) * kPi / 180.0 * std::fabs(r);
    return {rear * std::sqrt(1.0 + L * L * k * k), k, back};
}

Segment line(double m, bool back = false)
{
    return {m, 0.0, back};
}

// Thresholds of the gyro lie at start + (c + phase - 1) * beta between readings c - 1 and c
// (phase 0.5: the start heading is the centre of its cell). The first pulse comes after
// odo_phase * dl of front travel. At equal travel a gyro edge comes before a pulse.
Stream generate(const std::vector<Segment> &path, const Cfg &c, Pose start, double gyro_phase = 0.5,
                double odo_phase = 0.37, Sightings sights = {})
{
    const double L = c.L, dl = c.dl, beta = c.step_deg * kPi / 180.0;
    Stream s;
    Pose p = start;
    double travel = 0.0, next_pulse = odo_phase * dl, rel = 0.0; // heading relative to start
    int cell = 0;
    uint32_t jitter = 12345u;
    auto next_gap = [&]() {
        jitter = jitter * 1103515245u + 12345u;
        return sights.every * (0.6 + 0.8 * ((jitter >> 8) & 0xFFFF) / 65536.0);
    };
    double next_sight = sights.every > 0 ? next_gap() : INFINITY;
    double next_read = sights.every > 0 ? sights.rev : INFINITY;
    int in_rev = 0; // sightings of this revolution (at most 15, O1)
    bool back = false;
    for (const Segment &seg : path) {
        if (seg.back != back) {
            back = seg.back;
            s.ev.push_back(back ? REV_ON : REV_OFF);
        }
        const double ratio = 1.0 / std::sqrt(1.0 + L * L * seg.curv * seg.curv); // rear / front
        const double sgn = back ? -1.0 : 1.0;
        const double rate = sgn * seg.curv * ratio; // heading per front metre
        const Pose p0 = p;
        const double rel0 = rel, t0 = travel, end = travel + seg.front;
        auto pose_at = [&](double t) {
            double srear = sgn * (t - t0) * ratio;
            Pose q;
            if (seg.curv == 0.0) {
                q = {p0.x + srear * std::cos(p0.th), p0.y + srear * std::sin(p0.th), p0.th};
            } else {
                double th = p0.th + seg.curv * srear;
                q = {p0.x + (std::sin(th) - std::sin(p0.th)) / seg.curv,
                     p0.y - (std::cos(th) - std::cos(p0.th)) / seg.curv, th};
            }
            return q;
        };
        for (;;) {
            double rel_now = rel0 + rate * (travel - t0);
            double t_edge = INFINITY;
            if (rate > 0)
                t_edge = travel + ((cell + gyro_phase) * beta - rel_now) / rate;
            else if (rate < 0)
                t_edge = travel + ((cell - 1 + gyro_phase) * beta - rel_now) / rate;
            double t_other = std::min(next_sight, next_read);
            if (t_other < next_pulse && t_other < t_edge && t_other <= end) {
                travel = t_other;
                if (next_sight <= next_read) {
                    next_sight += next_gap();
                    if (in_rev < 15) {
                        in_rev++;
                        s.ev.push_back(SIGHT);
                        s.sight.push_back(pose_at(travel));
                        s.cell.push_back(cell);
                    }
                } else {
                    next_read += sights.rev;
                    in_rev = 0;
                    s.ev.push_back(READ);
                }
            } else if (next_pulse < t_edge && next_pulse <= end) {
                travel = next_pulse;
                next_pulse += dl;
                s.ev.push_back(PULSE);
                s.truth.push_back(pose_at(travel));
            } else if (t_edge <= end) {
                travel = t_edge;
                if (rate > 0) {
                    cell++;
                    s.ev.push_back(UP);
                } else {
                    cell--;
                    s.ev.push_back(DOWN);
                }
            } else {
                travel = end;
                break;
            }
        }
        p = pose_at(end);
        rel = rel0 + rate * (end - t0);
    }
    s.front = travel;
    return s;
}

// ------------------------------------------------------------------ the algorithm in double

// The firmware's algorithm (docs/groundnav.md) in double precision: cells of the gyro, arcs
// closed between thresholds with the chord m - E(m) along the cell's centre, E(m) = m -
// sqrt(m^2 - M^2) (half a step after init), provisional pose between edges continuing the
// last interval's deficit per pulse for at most its length.
struct RefNav {
    Params q;
    double M;
    double px, py, x, y, th0;
    long n = 0;
    long np = 0;
    double rho = 0;
    int cell = 0, cell_int = 0, hp = 0, hfirst = 0, hlast = 0;
    bool pending = false, fresh = false, reverse = false;

    RefNav(const Params &qq, Pose start) : q(qq), M(qq.L * qq.beta / qq.dl)
    {
        px = x = start.x;
        py = y = start.y;
        th0 = start.th;
    }
    double heading(int c) const
    {
        return th0 + c * q.beta;
    }
    void gyro(int up)
    {
        cell += up;
        int h = up > 0 ? 2 * cell - 1 : 2 * cell + 1;
        if (!pending) {
            hfirst = h;
            pending = true;
        }
        hlast = h;
    }
    void provisional()
    {
        double m = std::fabs((double)n), d = std::min<double>(m, np) * rho;
        double s = n >= 0 ? n - d : n + d;
        x = px + s * std::cos(heading(cell_int));
        y = py + s * std::sin(heading(cell_int));
    }
    void pulse()
    {
        if (fresh && pending)
            np = 0; // an interval closing at its first pulse has no curved part
        fresh = false;
        n += reverse ? -1 : 1;
        provisional();
        if (pending)
            close();
    }
    void close()
    {
        long m = std::labs(n);
        int k = std::abs(hfirst - hp);
        double E = 0, rho_new = 0;
        bool sit1 = false;
        bool keep = false;
        if (k == 0) {
            // the turn reversed inside one cell: the last curvature went on, over at most 2 np
            E = std::min<double>(m, 2.0 * np) * rho;
            keep = m <= 2 * np;
        } else {
            double me = k == 1 ? 2.0 * m : (double)m;
            if (me < M) {
                sit1 = true;
            } else {
                double e = me - std::sqrt(me * me - M * M);
                rho_new = e / me;
                E = k == 1 ? e / 2 : e;
            }
        }
        if (sit1) {
            x = px;
            y = py;
            rho = 1.0;
        } else {
            double s = n >= 0 ? m - E : -(m - E);
            px += s * std::cos(heading(cell_int));
            py += s * std::sin(heading(cell_int));
            x = px;
            y = py;
            if (!keep)
                rho = rho_new;
        }
        if (!keep)
            np = std::min<long>(m, 32000);
        if (k == 0 && !keep)
            np = 0;
        if (hlast != hfirst)
            np = 0;
        hp = hlast;
        n = 0;
        cell_int = cell;
        pending = false;
        fresh = true;
    }
    Pose pose() const
    {
        return {x * q.dl, y * q.dl, heading(cell)};
    }
    void set_units_from(Pose start)
    {
        // positions inside are in pulses, like the firmware's
        px = x = start.x / q.dl;
        py = y = start.y / q.dl;
    }
};

// The seed's method (000, chapter 3) in double precision: the gyro's reading phi; at a change
// of the reading the arc closes with sqrt((n dl)^2 - (L dphi)^2) along (phi1 + phi2) / 2
// (eq. 3.7, 3.8), unless n dl < L |dphi| (the position stays; the interval goes on); without
// a change the pose continues along phi1 with the previous interval's ratio (eq. 3.5, 3.6).
struct SeedNav {
    Params q;
    double px, py, x, y, th0, phi1;
    long n = 0, np = 0;
    double dphi_p = 0;
    int cell = 0;
    bool have_p = false, reverse = false;

    SeedNav(const Params &qq, Pose start) : q(qq)
    {
        px = x = start.x;
        py = y = start.y;
        th0 = phi1 = start.th;
    }
    double reading() const
    {
        return th0 + cell * q.beta;
    }
    void gyro(int up)
    {
        cell += up;
    }
    void pulse()
    {
        n += reverse ? -1 : 1;
        double phi = reading();
        double an = std::fabs((double)n);
        if (phi != phi1) {
            double d = phi - phi1;
            if (an * q.dl < q.L * std::fabs(d)) {
                x = px; // situation 1: the position stays
                y = py;
                return;
            }
            double ds = std::sqrt(an * an * q.dl * q.dl - q.L * q.L * d * d) * (n < 0 ? -1 : 1);
            double mean = (phi1 + phi) / 2;
            px += ds * std::cos(mean);
            py += ds * std::sin(mean);
            x = px;
            y = py;
            phi1 = phi;
            np = (long)an;
            dphi_p = std::fabs(d);
            have_p = true;
            n = 0;
        } else {
            double f = 1.0;
            if (have_p) {
                double u = q.L * dphi_p / (np * q.dl);
                f = std::sqrt(std::max(0.0, 1.0 - u * u));
            }
            x = px + n * q.dl * f * std::cos(phi1);
            y = py + n * q.dl * f * std::sin(phi1);
        }
    }
    Pose pose() const
    {
        return {x, y, reading()};
    }
};

// ------------------------------------------------------------------ the firmware, driven

Pose fw_pose_exact(const gnav_t &g, const Params &q)
{
    // the internal position (pulses, Q25) in metres, without the output rounding
    const gnav_pub_t &p = g.pub[g.pub_seq & 1u];
    return {(double)p.x / 33554432.0 * q.dl, (double)p.y / 33554432.0 * q.dl,
            fx_angle_to_rad(p.heading)};
}

struct Errors {
    double max = 0, sum2 = 0, last = 0;
    size_t n = 0;
    void add(double e)
    {
        max = std::max(max, e);
        sum2 += e * e;
        last = e;
        n++;
    }
    double rms() const
    {
        return n ? std::sqrt(sum2 / n) : 0.0;
    }
};

struct RunResult {
    Errors fw_vs_ref, fw_vs_true, seed_vs_true, ref_vs_true;
    double front = 0;
};

RunResult run_all(const Stream &s, const Cfg &c, Pose start,
                  const std::function<void(size_t, gnav_t &)> &at_pulse = nullptr)
{
    gnav_config_t f = to_fx(c);
    Params q = params_of(f);
    static gnav_t g;
    gnav_pose_t st = to_fx(start);
    EXPECT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    // the references start where the firmware starts (its start pose after rounding)
    Pose s0 = {fx_q16_to_double(st.x), fx_q16_to_double(st.y), fx_angle_to_rad(st.heading)};
    RefNav ref(q, s0);
    ref.set_units_from(s0);
    SeedNav seed(q, s0);
    RunResult r;
    r.front = s.front;
    size_t k = 0;
    for (Ev e : s.ev) {
        switch (e) {
        case PULSE: {
            gnav_on_delta_l(&g);
            ref.pulse();
            seed.pulse();
            Pose pf = fw_pose_exact(g, q), pr = ref.pose(), ps = seed.pose();
            const Pose &t = s.truth[k];
            r.fw_vs_ref.add(std::hypot(pf.x - pr.x, pf.y - pr.y));
            r.fw_vs_true.add(std::hypot(pf.x - t.x, pf.y - t.y));
            r.seed_vs_true.add(std::hypot(ps.x - t.x, ps.y - t.y));
            r.ref_vs_true.add(std::hypot(pr.x - t.x, pr.y - t.y));
            EXPECT_NEAR(wrap(pf.th - pr.th), 0.0, 3e-9);
            if (at_pulse)
                at_pulse(k, g);
            k++;
            break;
        }
        case UP:
        case DOWN:
            if (e == UP)
                gnav_on_gyro_up(&g);
            else
                gnav_on_gyro_down(&g);
            ref.gyro(e == UP ? 1 : -1);
            seed.gyro(e == UP ? 1 : -1);
            break;
        case REV_ON:
        case REV_OFF:
            gnav_set_reverse(&g, e == REV_ON);
            ref.reverse = seed.reverse = e == REV_ON;
            break;
        case SIGHT:
        case READ:
            break;
        }
    }
    return r;
}

struct Scenario {
    const char *name;
    std::vector<Segment> path;
};

std::vector<Scenario> scenarios()
{
    std::vector<Scenario> v;
    v.push_back({"straight 20 m", {line(20.0)}});
    v.push_back({"arc R 5 m, 180 deg", {arc(5.0, 180)}});
    v.push_back({"arc R 1.5 m, 270 deg", {arc(-1.5, 270)}});
    v.push_back({"tight arc R 0.4 m, 360 deg", {arc(0.4, 360)}});
    std::vector<Segment> s;
    for (int i = 0; i < 10; i++)
        s.push_back(arc(i % 2 ? -2.0 : 2.0, 30));
    v.push_back({"S-curves R 2 m, 10 x 30 deg", s});
    v.push_back({"arc then straight", {arc(0.8, 90), line(5.0)}});
    v.push_back({"reverse: arcs and straights",
                 {line(1.0, true), arc(-1.5, 60, true), line(2.0, true), arc(2.5, 45, true)}});
    std::vector<Segment> ramp;
    for (int i = 1; i <= 40; i++)
        ramp.push_back({0.05, 0.05 * i, false}); // curvature ramping up (a clothoid in steps)
    for (int i = 40; i >= 1; i--)
        ramp.push_back({0.05, 0.05 * i, false});
    v.push_back({"clothoid-like ramp", ramp});
    std::vector<Segment> mix;
    for (int lap = 0; lap < 4; lap++) {
        mix.push_back(line(6.0));
        mix.push_back(arc(1.2, 90));
        mix.push_back(arc(-3.0, 45));
        mix.push_back(line(4.0));
        mix.push_back(arc(0.6, 120));
        mix.push_back(line(3.0, true));
        mix.push_back(arc(-2.0, 60, true));
        mix.push_back(arc(8.0, 20));
        mix.push_back(line(5.0));
        mix.push_back(arc(-1.0, 75));
    }
    v.push_back({"mixed path, 4 laps", mix});
    return v;
}

// ------------------------------------------------------------------ the floors

TEST(GroundNav, SeedMinimumPulseCount)
{
    // seed: L = 30 in, dl = 0.01 in, 0.25 degrees: L dphi / dl = 13.09, so n >= 14
    Cfg c;
    gnav_config_t f = to_fx(c);
    gnav_t g;
    gnav_pose_t st = {0, 0, 0};
    ASSERT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    double m = gnav_m_q24(&g) / 16777216.0;
    Params q = params_of(f);
    std::printf("M = L * step / dl = %.6f pulses (seed: 13.08; exact for 30 in: %.6f), minimum "
                "count %d\n",
                m, 0.762 * 0.25 * kPi / 180.0 / 0.000254, (int)std::ceil(m));
    EXPECT_NEAR(m, q.L * q.beta / q.dl, 1e-6); // of the configured (Q16) wheelbase
    EXPECT_EQ((int)std::ceil(m), 14);
}

TEST(GroundNav, FloorsOnExactKinematics)
{
    Cfg c;
    Pose start = {3.0, -2.0, 0.3};
    std::printf("%-30s %8s | %12s | %10s %10s | %10s %10s\n", "stream (exact kinematics)", "travel",
                "fw vs double", "fw max", "seed max", "fw rms", "seed rms");
    double total_front = 0, worst_fidelity_per_100m = 0;
    for (const Scenario &sc : scenarios()) {
        Stream s = generate(sc.path, c, start);
        RunResult r = run_all(s, c, start);
        double per100 = r.fw_vs_ref.max / (r.front / 100.0);
        worst_fidelity_per_100m = std::max(worst_fidelity_per_100m, per100);
        total_front += r.front;
        std::printf("%-30s %7.2fm | %8.2f um | %7.3f mm %7.3f mm | %7.3f mm %7.3f mm\n", sc.name,
                    r.front, r.fw_vs_ref.max * 1e6, r.fw_vs_true.max * 1e3,
                    r.seed_vs_true.max * 1e3, r.fw_vs_true.rms() * 1e3, r.seed_vs_true.rms() * 1e3);
        // arithmetic fidelity: <= 1 mm per 100 m of travel
        EXPECT_LE(r.fw_vs_ref.max, 1e-3 * r.front / 100.0) << sc.name;
        // accuracy: no worse than the seed's method in double precision (1 um for rounding)
        EXPECT_LE(r.fw_vs_true.max, r.seed_vs_true.max + 1e-6) << sc.name;
        EXPECT_LE(r.fw_vs_true.rms(), r.seed_vs_true.rms() + 1e-6) << sc.name;
        EXPECT_LE(r.fw_vs_true.last, r.seed_vs_true.last + 1e-6) << sc.name;
    }
    std::printf("worst fidelity: %.4f mm per 100 m (floor 1 mm), %.0f m of streams\n",
                worst_fidelity_per_100m * 1e3, total_front);
}

TEST(GroundNav, GyroPhaseOffCentre)
{
    // The physical gyro's thresholds need not straddle the start heading symmetrically: both
    // methods then carry the same offset; the firmware must still not be worse.
    Cfg c;
    Pose start = {0, 0, 1.0};
    for (double phase : {0.1, 0.3, 0.7, 0.95}) {
        Stream s = generate(scenarios()[8].path, c, start, phase);
        RunResult r = run_all(s, c, start);
        std::printf("gyro phase %.2f: fw max %.2f mm, seed max %.2f mm, fw vs double %.2f um\n",
                    phase, r.fw_vs_true.max * 1e3, r.seed_vs_true.max * 1e3, r.fw_vs_ref.max * 1e6);
        EXPECT_LE(r.fw_vs_ref.max, 1e-3 * r.front / 100.0);
        EXPECT_LE(r.fw_vs_true.max, r.seed_vs_true.max + 1e-6);
    }
}

// The seed continues between gyro edges with the previous interval's curvature (n_p) for as
// long as the heading does not change: after a tight turn the vehicle drives straight, and
// the seed keeps shortening every pulse. The firmware continues the curvature for at most
// the last interval's length, then straight.
TEST(GroundNav, StraightContinuationAfterATurn)
{
    Cfg c;
    Pose start = {0, 0, 0};
    Stream s = generate({arc(0.5, 90), line(3.0)}, c, start);
    const char *csv = std::getenv("GNAV_FIGURE_CSV");
    FILE *out = csv ? std::fopen(csv, "w") : nullptr;
    if (out)
        std::fprintf(out, "pulse,travel_m,fw_err_mm,seed_err_mm\n");
    gnav_config_t f = to_fx(c);
    Params q = params_of(f);
    gnav_t g;
    gnav_pose_t st = to_fx(start);
    ASSERT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    SeedNav seed(q, start);
    size_t k = 0;
    double fw_end = 0, seed_end = 0, fw_max_straight = 0;
    size_t turn_end = 0;
    for (Ev e : s.ev) {
        if (e == PULSE) {
            gnav_on_delta_l(&g);
            seed.pulse();
            Pose pf = fw_pose_exact(g, q), ps = seed.pose();
            const Pose &t = s.truth[k];
            double ef = std::hypot(pf.x - t.x, pf.y - t.y), es = std::hypot(ps.x - t.x, ps.y - t.y);
            if (out && k % 20 == 0)
                std::fprintf(out, "%zu,%.5f,%.4f,%.4f\n", k, (k + 0.37) * c.dl, ef * 1e3, es * 1e3);
            if (turn_end && k > turn_end)
                fw_max_straight = std::max(fw_max_straight, ef);
            fw_end = ef;
            seed_end = es;
            k++;
        } else {
            if (e == UP)
                gnav_on_gyro_up(&g);
            else
                gnav_on_gyro_down(&g);
            seed.gyro(e == UP ? 1 : -1);
            turn_end = k;
        }
    }
    if (out)
        std::fclose(out);
    std::printf("3 m straight after a 90 deg turn at R 0.5 m: error at the end fw %.2f mm, seed "
                "%.1f mm; fw worst on the straight %.2f mm\n",
                fw_end * 1e3, seed_end * 1e3, fw_max_straight * 1e3);
    // the seed loses (1 - sqrt(1 - (M / n_p)^2)) of every pulse: about 2 % here
    EXPECT_GT(seed_end, 20e-3);
    EXPECT_LT(fw_end, 5e-3);
    EXPECT_LT(fw_end * 10, seed_end);
}

// ------------------------------------------------------------------ heading inside the cell

// Lane keeping as the closed loop drives it: short arcs of large radius left and right,
// a few steps of heading each, with straight bits between.
std::vector<Segment> wiggles()
{
    std::vector<Segment> v;
    const double radius[] = {12.0, -20.0, 8.0, -9.0, 30.0, -15.0, 10.0, -25.0};
    const double deg[] = {1.5, 2.5, 0.9, 1.7, 0.6, 2.2, 1.2, 0.8};
    for (int i = 0; i < 24; i++) {
        v.push_back(arc(radius[i % 8], deg[(i * 3) % 8]));
        if (i % 3 == 2)
            v.push_back(line(0.15 + 0.1 * (i % 4)));
    }
    return v;
}

// Turns that slow down inside a cell, as the drive's lane-keeping double arcs make them: an
// arc, then a wider one turning the same way (the heading rate drops to a third), left and
// right. The latch of a sighting taken just after the slowing lies in an interval that
// outlasted its entry rate and then closed in the entry direction.
std::vector<Segment> slowing()
{
    std::vector<Segment> v;
    for (int i = 0; i < 12; i++) {
        double sign = i % 2 ? -1.0 : 1.0;
        v.push_back(arc(sign * 20.0, 1.1));
        v.push_back(arc(sign * 60.0, 0.9));
    }
    return v;
}

struct HeadingErrors {
    Errors latch, latch_now, pose, centre, pose_centre, rel, rel_centre; // degrees
};

// Latches taken at the sightings of a stream, read at the end of each revolution (as the
// main board asks for them) and, separately, at once (nothing known beyond the instant);
// the published pose at every pulse. Against the exact heading, and the cell-centre method
// (the centre of the gyro's cell at that instant) for comparison.
HeadingErrors heading_errors(const Stream &s, const Cfg &c, Pose start)
{
    gnav_config_t f = to_fx(c);
    static gnav_t g;
    gnav_pose_t st = to_fx(start);
    EXPECT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    const double beta = (double)f.gyro_step_q48 / 281474976710656.0 * 360.0;
    const double h0 = fx_angle_to_deg(st.heading);
    auto err = [](double a, double b) { return std::remainder(a - b, 360.0); };
    HeadingErrors r;
    size_t k = 0, j = 0, first = 0;
    int cell = 0;
    for (Ev e : s.ev) {
        switch (e) {
        case PULSE: {
            gnav_on_delta_l(&g);
            gnav_pose_t p;
            gnav_pose(&g, &p);
            double t = s.truth[k++].th * 180.0 / kPi;
            r.pose.add(std::fabs(err(fx_angle_to_deg(p.heading), t)));
            r.pose_centre.add(std::fabs(err(h0 + cell * beta, t)));
            break;
        }
        case UP:
            gnav_on_gyro_up(&g);
            cell++;
            break;
        case DOWN:
            gnav_on_gyro_down(&g);
            cell--;
            break;
        case REV_ON:
        case REV_OFF:
            gnav_set_reverse(&g, e == REV_ON);
            break;
        case SIGHT: {
            gnav_on_beacon_sighted(&g);
            gnav_latch_t l;
            EXPECT_EQ(gnav_latch_read(&g, (uint16_t)j, &l), GNAV_OK);
            r.latch_now.add(
                std::fabs(err(fx_angle_to_deg(l.pose.heading), s.sight[j].th * 180 / kPi)));
            j++;
            break;
        }
        case READ: {
            if (j == first)
                break;
            // the revolution's latches against the truth, and relative to its last one (the
            // reference of the fix)
            gnav_latch_t ref;
            EXPECT_EQ(gnav_latch_read(&g, (uint16_t)(j - 1), &ref), GNAV_OK);
            const double ref_t = s.sight[j - 1].th * 180 / kPi;
            const double ref_c = h0 + s.cell[j - 1] * beta;
            for (size_t i = first; i < j; i++) {
                gnav_latch_t l;
                EXPECT_EQ(gnav_latch_read(&g, (uint16_t)i, &l), GNAV_OK);
                double t = s.sight[i].th * 180 / kPi, lh = fx_angle_to_deg(l.pose.heading);
                double ch = h0 + s.cell[i] * beta;
                r.latch.add(std::fabs(err(lh, t)));
                r.centre.add(std::fabs(err(ch, t)));
                if (i + 1 < j) {
                    r.rel.add(std::fabs(err(lh - fx_angle_to_deg(ref.pose.heading), t - ref_t)));
                    r.rel_centre.add(std::fabs(err(ch - ref_c, t - ref_t)));
                }
            }
            first = j;
            break;
        }
        }
    }
    return r;
}

// The heading inside the gyro's cell (docs/groundnav.md): latches read at the end of their
// revolution, as the main board reads them, against the cell-centre method. Floors: on steady
// arcs at most half the centre method's RMS; better RMS (absolute and relative to the
// revolution's last latch, the fix's reference) on every stream; within half a step of the
// truth on the seed's kinds of path, and relative to the reference where turns slow inside a
// cell; the published pose's RMS better too. The estimate never
// leaves the cell, so no error exceeds one step; only the centre can promise half a step, and
// lane keeping (turns reversed inside a cell at other rates than they began) shows it.
TEST(GroundNav, LatchHeadingInsideTheCell)
{
    Cfg c;
    Pose start = {3.0, -2.0, 0.3};
    Sightings sights;
    sights.every = 0.5 / 15; // 15 sightings per revolution at 1 m/s, 2 rev/s
    const double half = c.step_deg / 2;
    struct Case {
        Scenario sc;
        bool steady; // one steady arc: RMS at most half the centre method's
        bool seed;   // the seed's kinds of path: within half a step
        bool slows;  // turns that slow inside a cell: relative to the reference within half a
                     // step too (the estimate stays above the exit's chord)
    };
    std::vector<Scenario> base = scenarios();
    std::vector<Case> v;
    for (size_t i = 0; i < base.size(); i++)
        v.push_back({base[i], i >= 1 && i <= 3, true, false});
    v.push_back(
        {{"arc to 90.08 deg then straight", {arc(0.8, 90.08), line(5.0)}}, false, true, false});
    v.push_back({{"lane keeping (wiggles)", wiggles()}, false, false, false});
    v.push_back({{"turns that slow (double arcs)", slowing()}, false, true, true});
    std::printf("%-30s | %15s %15s | %15s | %15s %15s | %15s %15s  (deg, rms/max)\n", "stream",
                "latch", "centre", "latch at once", "pose", "centre", "rel. latch", "rel. centre");
    for (const Case &k : v) {
        Stream s = generate(k.sc.path, c, start, 0.5, 0.37, sights);
        HeadingErrors r = heading_errors(s, c, start);
        std::printf("%-30s | %7.4f %7.4f %7.4f %7.4f | %7.4f %7.4f | %7.4f %7.4f %7.4f %7.4f | "
                    "%7.4f %7.4f %7.4f %7.4f\n",
                    k.sc.name, r.latch.rms(), r.latch.max, r.centre.rms(), r.centre.max,
                    r.latch_now.rms(), r.latch_now.max, r.pose.rms(), r.pose.max,
                    r.pose_centre.rms(), r.pose_centre.max, r.rel.rms(), r.rel.max,
                    r.rel_centre.rms(), r.rel_centre.max);
        EXPECT_GT(r.latch.n, 0u) << k.sc.name;
        EXPECT_LE(r.latch.rms(), r.centre.rms() + 1e-9) << k.sc.name;
        EXPECT_LE(r.rel.rms(), r.rel_centre.rms() + 1e-9) << k.sc.name;
        EXPECT_LE(r.pose.rms(), r.pose_centre.rms() + 1e-9) << k.sc.name;
        if (k.steady) {
            EXPECT_LE(r.latch.rms(), 0.5 * r.centre.rms()) << k.sc.name;
        }
        EXPECT_LE(r.latch.max, (k.seed ? 1.0 : 2.0) * half + 1e-6) << k.sc.name;
        if (k.slows) {
            EXPECT_LE(r.rel.max, half) << k.sc.name;
        }
        EXPECT_LE(r.latch_now.max, 2.0 * half + 1e-6) << k.sc.name;
        EXPECT_LE(r.pose.max, 2.0 * half + 1e-6) << k.sc.name;
    }
}

// ------------------------------------------------------------------ fixes

// A fix for an earlier instant (a latch) carries the motion since then forward: the pose
// after a fix delivered 0.3 s late at 1 m/s (300 mm of travel) lands within 1 mm of the pose
// after the same fix applied at its instant.
TEST(GroundNav, LateFixLandsWhereAnInstantFixLands)
{
    Cfg c;
    Pose start = {1.0, 1.0, 0.2};
    Stream s = generate({line(0.5), arc(1.5, 60), arc(-0.9, 50), line(1.0)}, c, start);
    gnav_config_t f = to_fx(c);
    const size_t latch_at = 1500, late = 1181; // 0.3 m of travel after the latch
    double worst = 0;
    for (int variant = 0; variant < 3; variant++) {
        // the fix: the true pose at the latch, while dead reckoning is off by cm and degrees
        gnav_t a, b;
        gnav_pose_t st = to_fx(start);
        gnav_pose_t wrong = st;
        wrong.x += 3000 * (variant + 1); // 4.6 .. 14 cm
        wrong.y -= 2000;
        wrong.heading += 0x01000000u * (variant + 1); // 1.4 .. 4.2 degrees
        ASSERT_EQ(gnav_init(&a, &f, &wrong), GNAV_OK);
        ASSERT_EQ(gnav_init(&b, &f, &wrong), GNAV_OK);
        gnav_latch_t la{}, lb{};
        gnav_pose_t fix{};
        size_t k = 0;
        double diff = 0;
        for (Ev e : s.ev) {
            for (gnav_t *g : {&a, &b}) {
                if (e == PULSE)
                    gnav_on_delta_l(g);
                else if (e == UP)
                    gnav_on_gyro_up(g);
                else if (e == DOWN)
                    gnav_on_gyro_down(g);
            }
            if (e != PULSE)
                continue;
            k++;
            if (k == latch_at) {
                fix = to_fx(s.truth[k - 1]);
                gnav_on_beacon_sighted(&a);
                gnav_on_beacon_sighted(&b);
                ASSERT_EQ(gnav_latch_read(&a, 0, &la), GNAV_OK);
                ASSERT_EQ(gnav_latch_read(&b, 0, &lb), GNAV_OK);
                ASSERT_EQ(gnav_fix(&a, &fix, &la), GNAV_OK); // at its instant
            }
            if (k == latch_at + late) {
                ASSERT_EQ(gnav_fix(&b, &fix, &lb), GNAV_OK); // 0.3 s late
            }
            if (k >= latch_at + late) {
                gnav_pose_t pa, pb;
                gnav_pose(&a, &pa);
                gnav_pose(&b, &pb);
                diff = std::max(
                    diff, std::hypot(fx_q16_to_double(pa.x - pb.x), fx_q16_to_double(pa.y - pb.y)));
                EXPECT_LE(std::fabs(fx_angle_to_deg_signed(pa.heading - pb.heading)), 1e-6);
            }
        }
        // and the instant fix itself is right: the pose at the end against the truth
        gnav_pose_t pa;
        gnav_pose(&a, &pa);
        const Pose &t = s.truth.back();
        double err = std::hypot(fx_q16_to_double(pa.x) - t.x, fx_q16_to_double(pa.y) - t.y);
        std::printf("fix 0.3 s late vs at its instant (variant %d): %.4f mm apart; instant fix "
                    "then %.1f m of dead reckoning: %.2f mm from the truth\n",
                    variant, diff * 1e3, (s.truth.size() - latch_at) * c.dl, err * 1e3);
        worst = std::max(worst, diff);
        EXPECT_LT(err, 10e-3);
    }
    EXPECT_LE(worst, 1e-3);
}

TEST(GroundNav, FixNowSetsPoseAndGyro)
{
    Cfg c;
    gnav_config_t f = to_fx(c);
    gnav_t g;
    gnav_pose_t st = {0, 0, 0};
    ASSERT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    for (int i = 0; i < 500; i++)
        gnav_on_delta_l(&g);
    gnav_on_gyro_up(&g);
    for (int i = 0; i < 300; i++)
        gnav_on_delta_l(&g);
    gnav_pose_t fix = {fx_q16_from_double(12.5), fx_q16_from_double(-7.25),
                       fx_angle_from_deg(123.4)};
    ASSERT_EQ(gnav_fix(&g, &fix, nullptr), GNAV_OK);
    gnav_pose_t p;
    gnav_pose(&g, &p);
    EXPECT_LE(std::abs(p.x - fix.x), 1);
    EXPECT_LE(std::abs(p.y - fix.y), 1);
    EXPECT_EQ(p.heading, fix.heading); // "set the gyroscope"
    // straight on: along the new heading
    for (int i = 0; i < 3937; i++)
        gnav_on_delta_l(&g);
    gnav_pose(&g, &p);
    double d = 3937 * c.dl, h = 123.4 * kPi / 180.0;
    EXPECT_NEAR(fx_q16_to_double(p.x), 12.5 + d * std::cos(h), 1e-4);
    EXPECT_NEAR(fx_q16_to_double(p.y), -7.25 + d * std::sin(h), 1e-4);
    // a gyro step turns from the fixed heading: at the edge the heading is on the threshold,
    // half a step down; with no rate known (the last edge went the other way) the estimate
    // reaches the cell's centre once the tightest turn could have got there (M = 13.09 pulses)
    gnav_on_gyro_down(&g);
    gnav_pose(&g, &p);
    EXPECT_NEAR(fx_angle_to_deg(p.heading), 123.275, 1e-6);
    for (int i = 0; i < 14; i++)
        gnav_on_delta_l(&g);
    gnav_pose(&g, &p);
    EXPECT_NEAR(fx_angle_to_deg(p.heading), 123.15, 1e-6);
}

TEST(GroundNav, LatchesAcrossFixes)
{
    Cfg c;
    gnav_config_t f = to_fx(c);
    gnav_t g;
    gnav_pose_t st = {0, 0, 0};
    ASSERT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    gnav_latch_t l;
    EXPECT_EQ(gnav_latch_read(&g, 0, &l), GNAV_ERR_LATCH); // not yet taken
    for (int i = 0; i < 20; i++) {
        for (int j = 0; j < 100; j++)
            gnav_on_delta_l(&g);
        gnav_on_beacon_sighted(&g);
    }
    EXPECT_EQ(gnav_latch_next(&g), 20);
    EXPECT_EQ(gnav_latch_read(&g, 3, &l), GNAV_ERR_LATCH); // overwritten (16 kept)
    ASSERT_EQ(gnav_latch_read(&g, 19, &l), GNAV_OK);
    EXPECT_EQ(l.seq, 19);
    EXPECT_NEAR(fx_q16_to_double(l.pose.x), 2000 * c.dl, 2e-5);
    ASSERT_EQ(gnav_latch_read(&g, 4, &l), GNAV_OK);
    EXPECT_NEAR(fx_q16_to_double(l.pose.x), 500 * c.dl, 2e-5);
    // a fix moves the frame: latch 4 read again is in the new frame, latch 19 agrees with it
    gnav_pose_t fix = {fx_q16_from_double(1.0), fx_q16_from_double(2.0), fx_angle_from_deg(90)};
    ASSERT_EQ(gnav_fix(&g, &fix, &l), GNAV_OK);
    gnav_latch_t l4, l19;
    ASSERT_EQ(gnav_latch_read(&g, 4, &l4), GNAV_OK);
    ASSERT_EQ(gnav_latch_read(&g, 19, &l19), GNAV_OK);
    EXPECT_EQ(l4.gen, 1);
    EXPECT_LE(std::abs(l4.pose.x - fix.x), 1);
    EXPECT_LE(std::abs(l4.pose.y - fix.y), 1);
    EXPECT_EQ(l4.pose.heading, fix.heading);
    EXPECT_NEAR(fx_q16_to_double(l19.pose.x), 1.0, 2e-5); // 1500 pulses further north
    EXPECT_NEAR(fx_q16_to_double(l19.pose.y), 2.0 + 1500 * c.dl, 2e-5);
    // a fix referring to the latch as read before the first fix (generation 0) still works
    gnav_pose_t fix2 = {fx_q16_from_double(1.0), fx_q16_from_double(2.01), fx_angle_from_deg(90)};
    ASSERT_EQ(gnav_fix(&g, &fix2, &l), GNAV_OK);
    gnav_pose_t p;
    gnav_pose(&g, &p);
    EXPECT_NEAR(fx_q16_to_double(p.y), 2.01 + 1500 * c.dl, 2e-5);
    // too many fixes since: stale
    for (int i = 0; i < 4; i++)
        ASSERT_EQ(gnav_fix(&g, &fix2, nullptr), GNAV_OK);
    EXPECT_EQ(gnav_fix(&g, &fix2, &l), GNAV_ERR_STALE);
    EXPECT_EQ(gnav_latch_read(&g, 4, &l4), GNAV_ERR_STALE);
}

TEST(GroundNav, StopRequestAfterDistanceWithoutFix)
{
    Cfg c;
    c.stop_m = 2.0;
    gnav_config_t f = to_fx(c);
    gnav_t g;
    gnav_pose_t st = {0, 0, 0};
    ASSERT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    static int calls;
    calls = 0;
    gnav_set_stop_callback(
        &g, [](void *ctx) { (*static_cast<int *>(ctx))++; }, &calls);
    const long n = (long)std::ceil(2.0 / c.dl); // 7875 pulses
    for (long i = 1; i < n; i++) {
        gnav_set_reverse(&g, (i / 1000) % 2 == 1); // backwards travel counts too
        gnav_on_delta_l(&g);
    }
    EXPECT_FALSE(gnav_stop_requested(&g));
    gnav_on_delta_l(&g);
    EXPECT_TRUE(gnav_stop_requested(&g));
    EXPECT_EQ(calls, 1);
    for (int i = 0; i < 70000; i++)
        gnav_on_delta_l(&g);
    EXPECT_EQ(calls, 1); // once
    gnav_pose_t fix = {0, 0, 0};
    ASSERT_EQ(gnav_fix(&g, &fix, nullptr), GNAV_OK);
    EXPECT_FALSE(gnav_stop_requested(&g)); // a fix clears it and restarts the count
    for (long i = 1; i < n; i++)
        gnav_on_delta_l(&g);
    EXPECT_FALSE(gnav_stop_requested(&g));
    gnav_on_delta_l(&g);
    EXPECT_TRUE(gnav_stop_requested(&g));
    EXPECT_EQ(calls, 2);
    // beyond 2^16 pulses (the count's high word)
    c.stop_m = 40.0;
    f = to_fx(c);
    ASSERT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    const long n40 = (long)std::ceil(40.0 / c.dl);
    for (long i = 1; i < n40; i++)
        gnav_on_delta_l(&g);
    EXPECT_FALSE(gnav_stop_requested(&g));
    gnav_on_delta_l(&g);
    EXPECT_TRUE(gnav_stop_requested(&g));
}

TEST(GroundNav, HeadingModuloOneTurn)
{
    Cfg c;
    gnav_config_t f = to_fx(c);
    gnav_t g;
    gnav_pose_t st = {0, 0, fx_angle_from_deg(359.9)};
    ASSERT_EQ(gnav_init(&g, &f, &st), GNAV_OK);
    gnav_pose_t p;
    // without pulses after them, the heading sits on the threshold the last edge crossed:
    // half a step behind the gyro's reading
    for (int i = 0; i < 14400; i++) // ten turns counter-clockwise, 0.25 degrees a step
        gnav_on_gyro_up(&g);
    gnav_pose(&g, &p);
    EXPECT_NEAR(fx_angle_to_deg_signed(p.heading - st.heading), -0.125, 1e-7);
    gnav_on_gyro_up(&g);
    gnav_pose(&g, &p);
    EXPECT_NEAR(fx_angle_to_deg(p.heading), 0.025, 1e-7); // wrapped past 360
    for (int i = 0; i < 14401; i++)
        gnav_on_gyro_down(&g);
    gnav_pose(&g, &p);
    EXPECT_NEAR(fx_angle_to_deg_signed(p.heading - st.heading), 0.125, 1e-7);
}

TEST(GroundNav, ConfigurationErrors)
{
    gnav_t g;
    gnav_pose_t st = {0, 0, 0};
    Cfg c;
    gnav_config_t f = to_fx(c);
    f.wheelbase = 0;
    EXPECT_EQ(gnav_init(&g, &f, &st), GNAV_ERR_WHEELBASE);
    f = to_fx(c);
    f.dl_q40 = 1u << 25;
    EXPECT_EQ(gnav_init(&g, &f, &st), GNAV_ERR_DL);
    f = to_fx(c);
    f.gyro_step_q48 = 0;
    EXPECT_EQ(gnav_init(&g, &f, &st), GNAV_ERR_GYRO_STEP);
    f = to_fx(c);
    f.stop_distance = -1;
    EXPECT_EQ(gnav_init(&g, &f, &st), GNAV_ERR_STOP);
    Cfg big = c;
    big.dl = 0.00005; // M = 66.5 pulses: beyond the table
    f = to_fx(big);
    EXPECT_EQ(gnav_init(&g, &f, &st), GNAV_ERR_STEERING);
    f = to_fx(c);
    gnav_pose_t far = {fx_q16_from_double(31000.0), 0, 0};
    EXPECT_EQ(gnav_init(&g, &f, &far), GNAV_ERR_POSE);
    EXPECT_EQ(gnav_init(&g, nullptr, &st), GNAV_ERR_NULL);
    EXPECT_STREQ(gnav_strerror(GNAV_ERR_STEERING),
                 "wheelbase * gyro step / dl must stay below 32 pulses");
    // other configurations work and keep the fidelity (M from 0.3 to 31)
    for (double dl : {0.0095, 0.001, 0.00012, 0.00011}) {
        Cfg o = c;
        o.dl = dl;
        o.L = dl < 0.0002 ? 0.762 : 1.5;
        Pose start = {0, 0, 0};
        Stream s = generate({arc(1.0, 90), line(1.0), arc(-0.6, 45, true)}, o, start);
        RunResult r = run_all(s, o, start);
        std::printf("dl %.4f mm, L %.3f m: fw vs double %.3f um over %.1f m; fw max %.2f mm, seed "
                    "%.2f mm\n",
                    dl * 1e3, o.L, r.fw_vs_ref.max * 1e6, r.front, r.fw_vs_true.max * 1e3,
                    r.seed_vs_true.max * 1e3);
        EXPECT_LE(r.fw_vs_ref.max, 1e-3 * r.front / 100.0);
    }
}

// ------------------------------------------------------------------ G5: the harness

// All published poses of a run (the reference of "consistent": a reader sees one of them).
struct Published {
    std::vector<gnav_pose_t> poses;
    bool has(const gnav_pose_t &p) const
    {
        for (const gnav_pose_t &q : poses)
            if (q.x == p.x && q.y == p.y && q.heading == p.heading)
                return true;
        return false;
    }
};

class GroundNavHarness : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        posix_reset();
        board = posix_board_create("nav");
        ASSERT_GE(board, 0);
        posix_board_select(board);
        Cfg c;
        cfg = to_fx(c);
        gnav_pose_t st = {fx_q16_from_double(2.0), fx_q16_from_double(1.0), fx_angle_from_deg(10)};
        ASSERT_EQ(gnav_init(&g, &cfg, &st), GNAV_OK);
        ASSERT_EQ(gnav_attach(&g), 0);
        hal_irq_enable();
        stream =
            generate({line(0.01), arc(0.5, 3), arc(-0.3, 2), line(0.004, true), arc(0.7, 1, true)},
                     c, {2.0, 1.0, 10 * kPi / 180.0});
    }
    void TearDown() override
    {
        posix_set_preempt_hook(nullptr, nullptr);
    }
    void deliver(Ev e)
    {
        if (e == PULSE)
            posix_edge_raise(board, HAL_EDGE_DELTA_L);
        else if (e == UP)
            posix_edge_raise(board, HAL_EDGE_GYRO_UP);
        else if (e == DOWN)
            posix_edge_raise(board, HAL_EDGE_GYRO_DOWN);
        else
            gnav_set_reverse(&g, e == REV_ON);
        posix_dispatch();
    }
    Published record()
    {
        Published pub;
        gnav_t saved = g;
        gnav_pose_t p;
        gnav_pose(&g, &p);
        pub.poses.push_back(p);
        for (Ev e : stream.ev) {
            deliver(e);
            gnav_pose(&g, &p);
            pub.poses.push_back(p);
        }
        g = saved;
        return pub;
    }
    int board = -1;
    gnav_config_t cfg{};
    gnav_t g{};
    Stream stream;
};

struct LandAt {
    int board;
    hal_edge_line_t line;
    uint64_t point;
    hal_edge_line_t line2; // a second one at the next point (HAL_EDGE_COUNT: none)
    int landed;
};

// A hook that only lets the harness count the points (they are counted under a hook).
void count_only(void *, int, uint64_t) {}

void land_hook(void *ctx, int board, uint64_t point)
{
    auto *l = static_cast<LandAt *>(ctx);
    if (board != l->board)
        return;
    if (point == l->point) {
        posix_edge_raise(board, l->line);
        l->landed++;
    } else if (point == l->point + 1 && l->line2 != HAL_EDGE_COUNT) {
        posix_edge_raise(board, l->line2);
        l->landed++;
    }
}

bool same(const gnav_pose_t &a, const gnav_pose_t &b)
{
    return a.x == b.x && a.y == b.y && a.heading == b.heading;
}

// The coordinate request (NMI) lands at every preemption point of every handler of the
// stream: dl pulses (closings included), gyro edges. It must hand out a published pose.
TEST_F(GroundNavHarness, CoordinateRequestAtEveryPointIsNeverTorn)
{
    Published pub = record();
    gnav_pose_t handed{};
    size_t taken = 0; /* the NMI's callback counts; the main loop reads the pose after it */
    gnav_set_coord_callback(
        &g, [](void *ctx) { ++*static_cast<size_t *>(ctx); }, &taken);
    size_t requests = 0, points_total = 0, max_points = 0;
    for (Ev e : stream.ev) {
        if (e == REV_ON || e == REV_OFF) {
            deliver(e);
            continue;
        }
        // how many points does this event pass? (a dry run on a copy)
        gnav_t saved = g;
        posix_set_preempt_hook(count_only, nullptr); /* points are counted under a hook */
        uint64_t p0 = posix_preempt_points(board);
        deliver(e);
        uint64_t points = posix_preempt_points(board) - p0;
        posix_set_preempt_hook(nullptr, nullptr);
        g = saved;
        max_points = std::max<size_t>(max_points, points);
        for (uint64_t k = 1; k <= points; k++) {
            g = saved;
            LandAt land{board, HAL_EDGE_COORD_REQUEST, posix_preempt_points(board) + k,
                        HAL_EDGE_COUNT, 0};
            posix_set_preempt_hook(land_hook, &land);
            size_t before = taken;
            deliver(e);
            posix_set_preempt_hook(nullptr, nullptr);
            ASSERT_EQ(land.landed, 1);
            ASSERT_EQ(taken, before + 1);
            gnav_coord(&g, &handed);
            ASSERT_TRUE(pub.has(handed)) << "torn pose at point " << k;
            requests++;
        }
        points_total += points;
    }
    std::printf("coordinate request landed at %zu points (%zu events, up to %zu points in one "
                "handler): never torn\n",
                requests, stream.ev.size(), max_points);
    EXPECT_GT(requests, 1000u);
}

// The other way round: dl pulses and gyro edges interrupt a main-loop reader at each of its
// points, one handler or two (the second landing inside the first: the reader must retry);
// it still returns a pose that was published: before, between or after them.
TEST_F(GroundNavHarness, HandlersInterruptingAReaderAtEveryPoint)
{
    size_t reads = 0, retries_forced = 0;
    for (Ev e : stream.ev) {
        if (e == REV_ON || e == REV_OFF) {
            deliver(e);
            continue;
        }
        hal_edge_line_t line = e == PULSE ? HAL_EDGE_DELTA_L
                               : e == UP  ? HAL_EDGE_GYRO_UP
                                          : HAL_EDGE_GYRO_DOWN;
        gnav_t saved = g;
        posix_set_preempt_hook(count_only, nullptr); /* points are counted under a hook */
        uint64_t p0 = posix_preempt_points(board);
        gnav_pose_t p;
        gnav_pose(&g, &p);
        uint64_t points = posix_preempt_points(board) - p0;
        posix_set_preempt_hook(nullptr, nullptr);
        for (int two = 0; two <= 1; two++) {
            // the poses a consistent reader may return
            gnav_pose_t expect[3];
            g = saved;
            gnav_pose(&g, &expect[0]);
            deliver(e);
            gnav_pose(&g, &expect[1]);
            deliver(PULSE);
            gnav_pose(&g, &expect[2]);
            for (uint64_t k = 1; k <= points; k++) {
                g = saved;
                LandAt land{board, line, posix_preempt_points(board) + k,
                            two ? HAL_EDGE_DELTA_L : HAL_EDGE_COUNT, 0};
                posix_set_preempt_hook(land_hook, &land);
                gnav_pose(&g, &p);
                posix_set_preempt_hook(nullptr, nullptr);
                ASSERT_EQ(land.landed, two ? 2 : 1);
                ASSERT_TRUE(same(p, expect[0]) || same(p, expect[1]) || (two && same(p, expect[2])))
                    << "torn read at point " << k;
                reads++;
                retries_forced += two;
            }
        }
        g = saved;
        deliver(e);
    }
    std::printf("reader interrupted at every point: %zu reads, %zu of them with two handlers "
                "under it (a retry): all consistent\n",
                reads, retries_forced);
    EXPECT_GT(reads, 100u);
}

// Beacon Sighted through the harness: latches at the sighting instant.
TEST_F(GroundNavHarness, BeaconSightedLatchesThePoseOfItsInstant)
{
    gnav_pose_t before;
    for (int i = 0; i < 100; i++)
        deliver(PULSE);
    gnav_pose(&g, &before);
    posix_edge_raise(board, HAL_EDGE_BEACON_SIGHTED);
    posix_dispatch();
    for (int i = 0; i < 100; i++)
        deliver(PULSE);
    gnav_latch_t l;
    ASSERT_EQ(gnav_latch_read(&g, 0, &l), GNAV_OK);
    EXPECT_EQ(l.pose.x, before.x);
    EXPECT_EQ(l.pose.y, before.y);
    EXPECT_EQ(l.pose.heading, before.heading);
}

} // namespace
