// main_image: what a main board image builds in (firmware/main_board/main_image_beacon.c and
// main_image_pursuit.c over the header tools/gen_mission.py writes from a scenario) against what
// agv-sim builds from the same scenario (sim/mission.c): two implementations, Python and C, of
// one download, so that an image runs what the simulator ran. Built once per image
// (main_image_beacon_test, main_image_pursuit_test), CY_MAIN_IMAGE_SCENARIO naming its scenario.
#include <gtest/gtest.h>

extern "C" {
#include "main_image.h"
#include "sim/mission.h"
#include "sim/scenario.h"
}

namespace
{

struct Mission {
    sim_scenario_t sc;
    sim_mission_t m;
};

const Mission &mission()
{
    static Mission *x = [] {
        static Mission y;
        char err[256];
        if (sim_scenario_load(CY_MAIN_IMAGE_SCENARIO, &y.sc, err, sizeof err) != 0 ||
            sim_mission_build(&y.m, &y.sc, err, sizeof err) != 0)
            ADD_FAILURE() << CY_MAIN_IMAGE_SCENARIO << ": " << err;
        return &y;
    }();
    return *x;
}

TEST(MainImage, StartPathVehicleAndLinkAreAgvSims)
{
    const main_board_config_t &img = main_image_cfg, &sim = mission().m.main;
    EXPECT_EQ(img.start.x, sim.start.x);
    EXPECT_EQ(img.start.y, sim.start.y);
    EXPECT_EQ(img.start.heading, sim.start.heading);
    ASSERT_EQ(img.n_path, sim.n_path);
    for (unsigned i = 0; i < img.n_path; i++) {
        SCOPED_TRACE(i);
        EXPECT_EQ(img.path[i].pose.x, sim.path[i].pose.x);
        EXPECT_EQ(img.path[i].pose.y, sim.path[i].pose.y);
        EXPECT_EQ(img.path[i].pose.heading, sim.path[i].pose.heading);
        EXPECT_EQ(img.path[i].speed, sim.path[i].speed);
    }
    EXPECT_EQ(img.board.wheelbase, sim.board.wheelbase);
    EXPECT_EQ(img.board.min_radius, sim.board.min_radius);
    EXPECT_EQ(img.board.counts_per_m, sim.board.counts_per_m);
    EXPECT_EQ(img.board.speed_lsb, sim.board.speed_lsb);
    EXPECT_EQ(img.board.min_pulse_counts, sim.board.min_pulse_counts);
    EXPECT_EQ(img.board.dac_center, sim.board.dac_center);
    EXPECT_EQ(img.link.node, sim.link.node);
    EXPECT_EQ(img.link.bitrate_bps, sim.link.bitrate_bps);
    EXPECT_EQ(img.link.heartbeat_ms, sim.link.heartbeat_ms);
    EXPECT_EQ(img.link.silence_ms, sim.link.silence_ms);
}

// The travel of the image's mode: the pursuit image's pursuit and receiver parameters, or the
// beacon image's map, path preparation, sequencer and optical configuration.
TEST(MainImage, TravelIsAgvSims)
{
    const main_board_config_t &img = main_image_cfg, &sim = mission().m.main;
    ASSERT_EQ(img.pursuit != nullptr, sim.pursuit != nullptr);
    if (img.pursuit) {
        const pursuit_config_t &a = img.pursuit->law, &b = sim.pursuit->law;
        EXPECT_EQ(a.speed, b.speed);
        EXPECT_EQ(a.max_speed, b.max_speed);
        EXPECT_EQ(a.k, b.k);
        EXPECT_EQ(a.activation_ms, b.activation_ms);
        EXPECT_EQ(a.threshold, b.threshold);
        EXPECT_EQ(a.max_steer, b.max_steer);
        EXPECT_EQ(a.slow_after_ms, b.slow_after_ms);
        EXPECT_EQ(a.stop_after_ms, b.stop_after_ms);
        EXPECT_EQ(a.regulate, b.regulate);
        EXPECT_EQ(a.pair_sep, b.pair_sep);
        EXPECT_EQ(a.pair_angle, b.pair_angle);
        EXPECT_EQ(a.pair_tol, b.pair_tol);
        EXPECT_EQ(img.pursuit->rx.min_update_mm, sim.pursuit->rx.min_update_mm);
        EXPECT_EQ(img.pursuit->rx.max_speed_mm_s, sim.pursuit->rx.max_speed_mm_s);
        EXPECT_EQ(img.pursuit->baud, sim.pursuit->baud);
        EXPECT_EQ(img.pursuit->receivers, sim.pursuit->receivers);
        EXPECT_EQ(img.pursuit->heading, sim.pursuit->heading);
        return;
    }
    ASSERT_EQ(img.map.n, sim.map.n);
    for (unsigned i = 0; i < img.map.n; i++) {
        SCOPED_TRACE(i);
        EXPECT_EQ(img.map.b[i].x, sim.map.b[i].x);
        EXPECT_EQ(img.map.b[i].y, sim.map.b[i].y);
        EXPECT_EQ(img.map.b8[i].x, sim.map.b8[i].x);
        EXPECT_EQ(img.map.b8[i].y, sim.map.b8[i].y);
        EXPECT_EQ(img.map.dk[i], sim.map.dk[i]);
    }
    EXPECT_EQ(img.map.ox, sim.map.ox);
    EXPECT_EQ(img.map.oy, sim.map.oy);
    EXPECT_EQ(img.map.dkmin, sim.map.dkmin);
    EXPECT_EQ(img.path_cfg.nominal_radius, sim.path_cfg.nominal_radius);
    EXPECT_EQ(img.path_cfg.spacing, sim.path_cfg.spacing);
    EXPECT_EQ(img.path_cfg.reverse, sim.path_cfg.reverse);
    EXPECT_EQ(img.seq_cfg.mode, sim.seq_cfg.mode);
    EXPECT_EQ(img.seq_cfg.load_ms, sim.seq_cfg.load_ms);
    EXPECT_EQ(img.seq_cfg.settle_ms, sim.seq_cfg.settle_ms);
    EXPECT_EQ(img.seq_cfg.stop_speed, sim.seq_cfg.stop_speed);
    EXPECT_EQ(img.seq_cfg.advance, sim.seq_cfg.advance);
    EXPECT_EQ(img.seq_cfg.max_fix_failures, sim.seq_cfg.max_fix_failures);
    EXPECT_EQ(img.seq_cfg.blind_distance, sim.seq_cfg.blind_distance);
    EXPECT_EQ(img.counts_per_turn, sim.counts_per_turn);
    // the optical configuration: the defaults, with the bearing error bounds of the scenario's
    // goniometer and gyro
    EXPECT_EQ(img.optical.bearing_err, sim.optical.bearing_err);
    EXPECT_EQ(img.optical.bearing_err_moving, sim.optical.bearing_err_moving);
    EXPECT_EQ(img.optical.window, sim.optical.window);
    EXPECT_EQ(img.optical.jump_max, sim.optical.jump_max);
    EXPECT_EQ(img.optical.turn_max, sim.optical.turn_max);
    EXPECT_EQ(img.optical.err_max, sim.optical.err_max);
    EXPECT_EQ(img.optical.quality_max, sim.optical.quality_max);
    EXPECT_EQ(img.optical.motion_passes, sim.optical.motion_passes);
}

} // namespace
