/*
 * telemetry.h - what a run shows while it goes: the measurements of the report (each fix
 * against the truth at its reference latch, the cross-track error sampled along the way), the
 * CSV logs of --log-dir, the LCM messages of --lcm (the types in sim/lcm/) and the --trace lines on
 * stderr; in mode pursuit also seed 002's position record and its path-error record with the
 * average (positions.csv, path_error.csv). The log files and their columns are described in
 * docs/interfaces.md.
 */
#ifndef SIM_TELEMETRY_H
#define SIM_TELEMETRY_H

#include <lcm/lcm.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "drive/drive_proto.h"
#include "main_board.h"
#include "sim/drive_board.h"
#include "sim/path_index.h"
#include "sim/possrc.h"
#include "sim/report.h"
#include "sim/scenario.h"
#include "sim/sensors.h"

#define SIM_TELEMETRY_SAMPLE 0.01 /* s: cross-track samples */
#define SIM_TELEMETRY_LOG    0.05 /* s: truth and estimate rows, LCM pose and truth messages */

/* The LCM channels, in the order of sim_telemetry_t.lcm_published[]. */
enum {
    SIM_LCM_TRUTH,
    SIM_LCM_POSE,
    SIM_LCM_FIX,
    SIM_LCM_SIGHTINGS,
    SIM_LCM_DRIVE,
    SIM_LCM_CHANNELS
};
/** The channel names: "CYCLOPION_TRUTH", ... (indexed by SIM_LCM_*). */
extern const char *const sim_telemetry_channel[SIM_LCM_CHANNELS];

typedef struct sim_telemetry {
    /* what it watches */
    const sim_drive_t *drive;
    const sim_sensors_t *sensors;
    sim_path_index_t *nominal;
    int nav_board;
    sim_report_t *report;     /* fixes and cross-track go here */
    const sim_possrc_t *src;  /* mode pursuit: the positioning system (receivers' truth) */
    const sim_scenario_t *sc; /* mode pursuit: its goal points */
    /* outputs */
    FILE *f_truth, *f_est, *f_fix, *f_cmd;
    FILE *f_pos, *f_err; /* mode pursuit: positions.csv, path_error.csv */
    double err_sum, true_sum;
    uint32_t err_n;
    lcm_t *lcm;
    uint64_t lcm_published[SIM_LCM_CHANNELS]; /* messages handed to LCM, per channel */
    uint64_t lcm_failed;                      /* messages LCM refused (sendto failed) */
    int trace;                                /* every fix attempt and travel state on stderr */
    /* state */
    sim_pose_t last_sample;
    double next_log;
    int done;        /* the run is over: no more cross-track samples */
    int travel_done; /* mode pursuit: the travel is done (the vehicle stops): no more samples */
} sim_telemetry_t;

/**
 * Open the outputs: with @p log_dir (may be NULL) the directory (and its parents) and the CSV
 * logs, including the static ones (beacons.csv, glints.csv and walls.csv of @p sc's world,
 * path.csv of @p nominal sampled every centimetre); with @p lcm_url (may be NULL) an LCM publisher.
 * Returns 0, or -1 with the reason (naming the file or URL) in @p err.
 */
int sim_telemetry_open(sim_telemetry_t *tm, const char *log_dir, const char *lcm_url,
                       const sim_scenario_t *sc, const sim_path_t *nominal, char *err,
                       size_t errlen);

/**
 * Watch @p drive, @p sensors, the nav board @p nav_board, measure the cross-track distance to
 * @p nominal, and count into @p report; schedules the first sample at the current time.
 */
void sim_telemetry_start(sim_telemetry_t *tm, const sim_drive_t *drive,
                         const sim_sensors_t *sensors, sim_path_index_t *nominal, int nav_board,
                         sim_report_t *report);

/** The main board's observer of fix attempts (main_board_observer_t.on_fix; ctx = tm). */
void sim_telemetry_fix(void *ctx, const main_board_fix_event_t *ev);

/** The main board's observer of travel states (main_board_observer_t.on_state; ctx = tm). */
void sim_telemetry_state(void *ctx, drive_state_t st);

/** Mode pursuit: watch the positioning system @p src of scenario @p sc (its receivers' truth,
 * the goal points); the report gets a pursuit section. */
void sim_telemetry_pursuit_start(sim_telemetry_t *tm, const sim_possrc_t *src,
                                 const sim_scenario_t *sc);

/** The main board's observer of framed packets (main_board_observer_t.on_pursuit; ctx = tm). */
void sim_telemetry_pursuit(void *ctx, const main_pursuit_event_t *ev);

/** The drive board took a command at @p t (s) (sim_drive_command_fn; ctx = tm). */
void sim_telemetry_command(void *ctx, double t, const drive_event_t *ev);

/** The run is over: stop sampling, flush and close every output. */
void sim_telemetry_close(sim_telemetry_t *tm);

#endif
