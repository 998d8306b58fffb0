// sim/scenario: scenario files read through the tables generated from the JSON Schema.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include "sim/scenario.h"
}

namespace
{

const char *kScenario = R"({
 "name": "unit", "mode": "full",
 "beacons": [{"x":0,"y":0,"diameter_m":0.08},{"x":10,"y":0,"diameter_m":0.08},
             {"x":10,"y":10,"diameter_m":0.08}],
 "vehicle": {"wheelbase_m":0.75,"min_radius_m":0.5,"speed_mps":1.0},
 "start": {"x":1,"y":1,"heading_deg":90},
 "path": [{"x":1,"y":5,"heading_deg":90,"speed_mps":1.0}],
 "sensors": {"goniometer":{"rev_per_s":2,"counts":50000,"noise_deg":0},
             "odometer":{"dl_m":0.000254},"gyro":{"step_deg":0.25,"drift_deg_per_s":0}},
 "seed": 7, "duration_s": 20})";

TEST(Scenario, ParsesTheContractExample)
{
    sim_scenario_t sc;
    char err[256];
    ASSERT_EQ(sim_scenario_parse(kScenario, &sc, err, sizeof err), 0) << err;
    EXPECT_STREQ(sc.name, "unit");
    EXPECT_EQ(sc.mode, SIM_SCENARIO_MODE_FULL);
    EXPECT_EQ(sc.world.n_beacons, 3u);
    EXPECT_NEAR(sc.start_heading, M_PI / 2, 1e-15);
    EXPECT_EQ(sc.counts, 50000u);
    EXPECT_NEAR(sc.gyro_step, 0.25 * M_PI / 180, 1e-15);
    EXPECT_EQ(sc.seed, 7u);
}

struct BadCase {
    const char *from, *to, *message;
};

TEST(Scenario, BadInputNamesTheKeyAndTheValue)
{
    const BadCase cases[] = {
        {"\"counts\":50000", "\"counts\":50000.5", "sensors.goniometer.counts: 50000.5"},
        {"\"dl_m\":0.000254", "\"dl_m\":-1", "sensors.odometer.dl_m: -1 is out of range"},
        {"\"mode\": \"full\"", "\"mode\": \"fast\"", "mode: \"fast\""},
        {"\"x\":10,\"y\":10,\"diameter_m\":0.08", "\"x\":10,\"y\":\"ten\",\"diameter_m\":0.08",
         "beacons[2].y: expected a number, got \"ten\""},
        {"\"speed_mps\":1.0}]", "\"speed_mps\":0}]", "path[0].speed_mps: 0 is out of range"},
        {"\"seed\": 7,", "", "missing \"seed\""},
        {"\"name\": \"unit\",", "\"name\": \"unit\",,", "line 2"},
    };
    for (const BadCase &c : cases) {
        std::string text = kScenario;
        size_t at = text.find(c.from);
        ASSERT_NE(at, std::string::npos) << c.from;
        text.replace(at, std::strlen(c.from), c.to);
        sim_scenario_t sc;
        char err[256] = "";
        EXPECT_EQ(sim_scenario_parse(text.c_str(), &sc, err, sizeof err), -1) << c.to;
        EXPECT_NE(std::string(err).find(c.message), std::string::npos)
            << "got: " << err << " / want: " << c.message;
    }
}

} // namespace
