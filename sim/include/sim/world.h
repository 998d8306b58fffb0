/*
 * world.h - the simulated building: retroreflective beacons (cylindrical posts or flat strips
 * facing the vehicle), mirror-like spurious reflectors (narrow glints), occluders (wall
 * segments that block the beam) and pillars (round obstacles that block it).
 */
#ifndef SIM_WORLD_H
#define SIM_WORLD_H

#include <stdbool.h>
#include <stddef.h>

#define SIM_MAX_BEACONS   64
#define SIM_MAX_SPURIOUS  16
#define SIM_MAX_OCCLUDERS 32
#define SIM_MAX_PILLARS   32

typedef struct {
    double x, y;
    double diameter; /* m: a post's diameter, a strip's width */
    int kind;        /* SIM_BEACON_KIND_CYLINDER or SIM_BEACON_KIND_FLAT (sim/scenario_keys.h) */
} sim_beacon_t;

typedef struct {
    double x, y;
    double width; /* apparent angular width of the glint, rad (range independent) */
} sim_spurious_t;

typedef struct {
    double x1, y1, x2, y2;
} sim_occluder_t;

typedef struct {
    double x, y;
    double diameter; /* m */
} sim_pillar_t;

typedef struct {
    sim_beacon_t beacon[SIM_MAX_BEACONS];
    size_t n_beacons;
    sim_spurious_t spurious[SIM_MAX_SPURIOUS];
    size_t n_spurious;
    sim_occluder_t occluder[SIM_MAX_OCCLUDERS];
    size_t n_occluders;
    sim_pillar_t pillar[SIM_MAX_PILLARS];
    size_t n_pillars;
} sim_world_t;

/**
 * The first pair of beacons that overlap (centres closer than the sum of their radii: an
 * impossible world): true with their indices in *i < *j, false when none do.
 */
bool sim_world_coincident(const sim_world_t *w, size_t *i, size_t *j);

/** True when the straight line from (ax, ay) to (bx, by) crosses no occluder and passes no
 * pillar nearer than its radius. */
bool sim_world_visible(const sim_world_t *w, double ax, double ay, double bx, double by);

/** What sim_world_sight() can say for a whole disk of viewpoints. */
typedef enum {
    SIM_SIGHT_UNSURE =
        0,            /* it may differ from one viewpoint to another (or be too close to call) */
    SIM_SIGHT_CLEAR,  /* sim_world_visible() is true from every viewpoint */
    SIM_SIGHT_BLOCKED /* sim_world_visible() is false from every viewpoint */
} sim_sight_t;

/**
 * The line of sight to (bx, by) from every point within @p r (m, >= 0) of (cx, cy), judged as
 * sim_world_visible() judges it (its rounding included, with a margin of about 1e-9 of the
 * distances squared): CLEAR or BLOCKED only when that holds for each point of the disk;
 * UNSURE otherwise. BLOCKED is claimed from a single occluder only (never from pillars).
 */
sim_sight_t sim_world_sight(const sim_world_t *w, double cx, double cy, double r, double bx,
                            double by);

#endif
