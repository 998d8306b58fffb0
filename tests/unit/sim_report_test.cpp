// sim/report: the statistics against direct computation, the verdict against each criterion,
// and the JSON report's keys and rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

extern "C" {
#include "sim/report.h"
}

namespace
{

TEST(Report, StatisticsAreTheirDefinitions)
{
    sim_stat_t s = {};
    std::vector<double> v;
    for (int i = 1; i <= 1000; i++) {
        double x = std::fmod(i * 0.618033988749895, 1.0) * 3.0;
        v.push_back(x);
        sim_stat_add(&s, x);
    }
    double sum = 0, sq = 0;
    for (double x : v) {
        sum += x;
        sq += x * x;
    }
    EXPECT_NEAR(sim_stat_mean(&s), sum / 1000, 1e-12);
    EXPECT_NEAR(sim_stat_rms(&s), std::sqrt(sq / 1000), 1e-12);
    std::sort(v.begin(), v.end());
    EXPECT_EQ(s.max, v.back());
    EXPECT_EQ(sim_stat_quantile(&s, 0.95), v[949]); // nearest rank: ceil(0.95 n)
    EXPECT_EQ(sim_stat_quantile(&s, 0.0), v[0]);
    sim_stat_free(&s);
    EXPECT_EQ(sim_stat_mean(&s), 0.0);
    EXPECT_EQ(sim_stat_quantile(&s, 0.5), 0.0);
}

sim_success_t criteria()
{
    sim_success_t c = {};
    c.max_cross_track_mean = 0.01;
    c.max_cross_track_max = 0.1;
    c.max_final_error = 0.05;
    c.max_fix_error = 0.05;
    c.min_fix_ratio = 0.5;
    c.require_goal = true;
    return c;
}

TEST(Report, EachCriterionIsJudgedWithItsFigure)
{
    sim_success_t c = criteria();
    auto fresh = [] {
        sim_report_t r = {};
        r.reached_goal = true;
        r.fixes_attempted = 10;
        r.fixes_accepted = 9;
        sim_stat_add(&r.cross_track, 0.005);
        sim_stat_add(&r.fix_error, 0.01);
        r.final_error = 0.01;
        return r;
    };
    char why[512];
    sim_report_t r = fresh();
    EXPECT_EQ(sim_report_judge(&r, &c, why, sizeof why), 1) << why;
    EXPECT_STREQ(why, "");
    sim_report_free(&r);

    struct Case {
        void (*spoil)(sim_report_t *);
        const char *text;
    } cases[] = {
        {[](sim_report_t *x) {
             x->reached_goal = false;
             x->stop_reason = "duration";
         },
         "goal not reached (stopped: duration)"},
        {[](sim_report_t *x) {
             x->reached_goal = false;
             x->stop_reason = "link_silent";
         },
         "(stopped: link_silent)"},
        {[](sim_report_t *x) { sim_stat_add(&x->cross_track, 0.2); }, "cross-track max 0.2000"},
        {[](sim_report_t *x) { sim_stat_add(&x->cross_track, 0.05); }, "cross-track mean 0.0275"},
        {[](sim_report_t *x) { x->final_error = 0.06; }, "final error 0.0600 m > 0.0500"},
        {[](sim_report_t *x) { sim_stat_add(&x->fix_error, 0.07); }, "fix error max 0.0700"},
        {[](sim_report_t *x) { x->fixes_accepted = 4; }, "40% of fixes accepted < 50%"},
    };
    // A scenario that must end stopped for a reason: met by that stop only.
    sim_success_t cs = c;
    cs.require_goal = false;
    snprintf(cs.stop_reason, sizeof cs.stop_reason, "blind_distance");
    r = fresh();
    EXPECT_EQ(sim_report_judge(&r, &cs, why, sizeof why), 0);
    EXPECT_NE(std::string(why).find("stop reason none (goal), expected blind_distance"),
              std::string::npos)
        << why;
    r.reached_goal = false;
    r.stop_reason = "duration";
    EXPECT_EQ(sim_report_judge(&r, &cs, why, sizeof why), 0);
    EXPECT_NE(std::string(why).find("stop reason duration, expected blind_distance"),
              std::string::npos)
        << why;
    r.stop_reason = "blind_distance";
    EXPECT_EQ(sim_report_judge(&r, &cs, why, sizeof why), 1) << why;
    sim_report_free(&r);

    for (const Case &k : cases) {
        r = fresh();
        k.spoil(&r);
        EXPECT_EQ(sim_report_judge(&r, &c, why, sizeof why), 0) << k.text;
        EXPECT_NE(std::string(why).find(k.text), std::string::npos) << why;
        // Without room for the reasons the verdict is the same.
        EXPECT_EQ(sim_report_judge(&r, &c, why, 0), 0);
        sim_report_free(&r);
    }
}

TEST(Report, JsonHasEveryKeyRounded)
{
    sim_report_t r = {};
    snprintf(r.scenario, sizeof r.scenario, "unit");
    r.mode = "full";
    r.seed = 42;
    r.sim_time = 1.23456789;
    sim_stat_add(&r.fix_error, 0.0012344);
    r.fixes_attempted = r.fixes_accepted = 1;
    r.isr_name[0] = "nav.delta_l";
    r.isr_count[0] = 7;
    r.n_isr = 1;
    r.stop_reason = "link_silent";
    r.stop_at = 2.5;
    r.standstill_at = 4.0000004;
    r.link.bitrate_bps = 250000;
    r.link.frames = 12;
    r.link.bus_load = 0.1234564;
    r.link.latency_name[0] = "FIX";
    r.link.latency_ms[0] = 1.0804;
    r.link.n_latency = 1;
    r.link.board[1].heartbeats_missed = 3;
    char *s = sim_report_json(&r);
    std::string j(s);
    free(s);
    for (const char *k : {"\"scenario\": \"unit\"",
                          "\"seed\": 42",
                          "\"mode\": \"full\"",
                          "\"sim_time_s\": 1.234568",
                          "\"max\": 0.001234",
                          "\"nav.delta_l\": 7",
                          "\"reached_goal\": false",
                          "\"cross_track_m\"",
                          "\"final_error_m\"",
                          "\"heading_error_deg\"",
                          "\"p95\"",
                          "\"wall_time_s\"",
                          "\"outcome\": \"stopped\"",
                          "\"stop_reason\": \"link_silent\"",
                          "\"stop_at_s\": 2.5",
                          "\"standstill_at_s\": 4.0",
                          "\"bitrate_bps\": 250000",
                          "\"frames\": 12",
                          "\"bus_load\": 0.123456",
                          "\"FIX\": 1.08",
                          "\"heartbeats_missed\": 3"})
        EXPECT_NE(j.find(k), std::string::npos) << k << " in " << j;
    sim_report_free(&r);
    // At the goal: no stop keys.
    sim_report_t g = {};
    g.mode = "full";
    g.reached_goal = true;
    s = sim_report_json(&g);
    j = s;
    free(s);
    EXPECT_NE(j.find("\"outcome\": \"goal\""), std::string::npos) << j;
    EXPECT_EQ(j.find("stop_reason"), std::string::npos) << j;
    EXPECT_EQ(j.find("standstill_at_s"), std::string::npos) << j;
}

} // namespace
