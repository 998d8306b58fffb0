/*
 * scenario.h - agv-sim scenario files, read and checked as their JSON Schema says
 * (docs/schema/scenario.schema.json; the reader's tables are generated from it by
 * tools/gen_schema_c.py, and each key's "x-c" names the field below that holds it).
 * Units in the file: metres, seconds, degrees; in the struct: metres, seconds, radians.
 */
#ifndef SIM_SCENARIO_H
#define SIM_SCENARIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sim/scenario_keys.h" /* generated: SIM_SCENARIO_MODE_*, SIM_LINK_*, *_MAX_ITEMS */
#include "sim/world.h"

typedef struct {
    double x, y, heading; /* m, m, rad */
    double speed;         /* m/s, > 0 (absent in the file: the vehicle's speed) */
} sim_waypoint_t;

typedef struct {
    double max_cross_track_mean; /* m */
    double max_cross_track_max;  /* m */
    double max_final_error;      /* m */
    double max_fix_error;        /* m: no accepted fix further from the truth */
    double min_fix_ratio;        /* accepted / attempted */
    bool require_goal;           /* the run must reach the last point */
    char stop_reason[32];        /* the run must stop for this reason ("": no requirement) */
} sim_success_t;

/** A fault injected into the CAN bus model (scenario "link.faults"; hal_posix/can_bus.h). */
typedef struct {
    int kind;         /* SIM_LINK_FAULT_DROP, _CORRUPT, _DELAY, _BABBLE, _BUSOFF */
    double at;        /* s */
    double duration;  /* s */
    int node;         /* SIM_LINK_NODE_ANY, _MAIN, _NAV */
    char frame[32];   /* a frame's name in the DBC, "" = every frame */
    uint32_t count;   /* frames it hits, 0 = all within the duration */
    double delay_ms;  /* ms */
    uint32_t id;      /* babble: its id */
    uint32_t len;     /* babble: its data bytes */
    double period_ms; /* babble: ms from frame to frame, 0 = back to back */
} sim_link_fault_t;

/** The board link (scenario "link"): 0 for a setting means the boards' built-in one. */
typedef struct {
    int bus;               /* SIM_LINK_BUS_CAN */
    uint32_t bitrate_bps;  /* bit/s */
    uint32_t heartbeat_ms; /* ms */
    uint32_t silence_ms;   /* ms */
    sim_link_fault_t fault[SIM_SCENARIO_LINK_FAULTS_MAX_ITEMS];
    size_t n_faults;
} sim_link_t;

/** A window of simulated time: from t for duration seconds. */
typedef struct {
    double t, duration; /* s */
} sim_window_t;

/** A point, or a receiver's mounting (x forward, y left of the rear axle's centre). */
typedef struct {
    double x, y; /* m */
} sim_xy_t;

/** A span of time. */
typedef struct {
    double from, to; /* s */
} sim_span_t;

/** Seed 002's goal-point pursuit (mode pursuit). */
typedef struct {
    double speed, max_speed;       /* m/s */
    double k;                      /* smoothing constant */
    double activation;             /* s */
    double threshold_pct;          /* % */
    double min_update;             /* m */
    int heading;                   /* SIM_PURSUIT_HEADING_* */
    double slow_after, stop_after; /* s (slow_after 0: no error recovery) */
    bool regulate;
    double pair_tol; /* m */
} sim_pursuit_t;

/** The simulated laser positioning system. */
typedef struct {
    double rate_hz, lag;       /* Hz, s */
    double noise_rel, noise_m; /* relative to the farthest transmitter; m */
    double range, height;      /* m */
    uint32_t baud;
    double dropout, corrupt, garbage, zero, wild; /* chances */
    double wild_m;
    sim_xy_t transmitter[3];
    size_t n_transmitters; /* 0: the corners of the beacons' bounding box */
    sim_xy_t receiver[2];
    size_t n_receivers; /* 0: one on the rear axle's centre */
    sim_span_t outage[16];
    size_t n_outages;
} sim_position_source_t;

typedef struct {
    char name[64];
    int mode; /* SIM_SCENARIO_MODE_FULL, _SIMPLIFIED or _PURSUIT */
    sim_world_t world;
    double wheelbase, min_radius, speed; /* m, m, m/s */
    double start_x, start_y, start_heading;
    double start_err_x, start_err_y, start_err_heading; /* initial estimate minus truth */
    sim_waypoint_t path[SIM_SCENARIO_PATH_MAX_ITEMS];
    size_t n_path;
    double rev_per_s;
    uint32_t counts;
    double gonio_noise; /* rad */
    double gonio_range; /* m */
    double index_loss;  /* probability that an index pulse is lost */
    sim_window_t dropout[SIM_SCENARIO_SENSORS_GONIOMETER_DROPOUTS_MAX_ITEMS]; /* blinded */
    size_t n_dropouts;
    double dl;         /* m of front-wheel travel per odometer pulse */
    double odo_scale;  /* true travel per nominal dl (1 = perfect wheel) */
    double odo_missed; /* probability that a pulse is lost */
    double odo_extra;  /* probability that a pulse comes with an extra one */
    double gyro_step;  /* rad */
    double gyro_drift; /* rad/s */
    uint64_t seed;
    double duration;       /* s */
    double blind_distance; /* m without a fix before the stop (both boards) */
    sim_link_t link;
    sim_pursuit_t pursuit;
    sim_position_source_t src;
    sim_success_t success;
} sim_scenario_t;

/**
 * Parse a scenario from @p path. Returns 0, or -1 with a message naming the offending key and
 * value in @p err (the struct is then unspecified).
 */
int sim_scenario_load(const char *path, sim_scenario_t *sc, char *err, size_t errlen);

/** The same from a JSON text (for tests). */
int sim_scenario_parse(const char *text, sim_scenario_t *sc, char *err, size_t errlen);

/** The name of travel mode @p mode in the file ("full", "simplified"). */
const char *sim_scenario_mode_name(int mode);

#endif
