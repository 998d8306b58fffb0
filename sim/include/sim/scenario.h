/*
 * scenario.h - agv-sim scenario files (CONTRACT.md "Scenario file"), parsed and validated.
 * Units at this interface: metres, seconds, degrees (converted to radians in the struct).
 */
#ifndef SIM_SCENARIO_H
#define SIM_SCENARIO_H

#include <stddef.h>
#include <stdint.h>

#include "sim/world.h"

#define SIM_MAX_PATH 1024

typedef struct {
    double x, y, heading; /* m, m, rad */
    double speed;         /* m/s, > 0 */
} sim_waypoint_t;

typedef struct {
    double max_cross_track_mean; /* m */
    double max_cross_track_max;  /* m */
    double max_final_error;      /* m */
    double max_fix_error;        /* m: no accepted fix further from the truth */
    double min_fix_ratio;        /* accepted / attempted */
    int require_goal;            /* the run must reach the last point */
} sim_success_t;

typedef struct {
    char name[64];
    int full_travel; /* mode: 1 full, 0 simplified */
    sim_world_t world;
    double wheelbase, min_radius, speed; /* m, m, m/s */
    double steer_rate;                   /* rad/s, 0 = instantaneous */
    double start_x, start_y, start_heading;
    double start_err_x, start_err_y, start_err_heading; /* initial estimate minus truth */
    sim_waypoint_t path[SIM_MAX_PATH];
    size_t n_path;
    double rev_per_s;
    uint32_t counts;
    double gonio_noise; /* rad */
    double gonio_range; /* m */
    double dl;          /* m of front-wheel travel per odometer pulse */
    double odo_scale;   /* true travel per nominal dl (1 = perfect wheel) */
    double gyro_step;   /* rad */
    double gyro_drift;  /* rad/s */
    uint64_t seed;
    double duration; /* s */
    sim_success_t success;
} sim_scenario_t;

/**
 * Parse a scenario from @p path. Returns 0, or -1 with a message naming the offending key and
 * value in @p err (the struct is then unspecified).
 */
int sim_scenario_load(const char *path, sim_scenario_t *sc, char *err, size_t errlen);

/** The same from a JSON text (for tests). */
int sim_scenario_parse(const char *text, sim_scenario_t *sc, char *err, size_t errlen);

#endif
