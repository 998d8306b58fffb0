/*
 * gonio.h - the goniometer: a mirror turning counter-clockwise at rev_per_s on the rear axle,
 * an index pulse when it points straight ahead, an angle clock of `counts` per turn that
 * Timer_A counts (16 bits, wrapping), and a photodetector pulse while the beam sweeps across a
 * beacon (or a glint). The beam direction in the world is heading(t) + mirror(t); a post of
 * diameter D at range d is lit while the beam is within asin(D / 2d) of its centre, so the
 * pulse spans 2 asin(D / 2d) of mirror angle (docs/interfaces.md), measured while the vehicle
 * moves.
 */
#ifndef SIM_GONIO_H
#define SIM_GONIO_H

#include <stddef.h>
#include <stdint.h>

#include "sim/motion.h"
#include "sim/rng.h"
#include "sim/world.h"

typedef struct {
    double rev_per_s; /* mirror turns per second (2 in the seed) */
    uint32_t counts;  /* angle-clock counts per turn (50,000 in the seed) */
    double noise_rad; /* standard deviation of each edge's angle, rad */
    double max_range; /* beyond this the return is too weak to trigger, m */
} sim_gonio_cfg_t;

typedef enum { SIM_GEV_RISE = 0, SIM_GEV_FALL = 1 } sim_gonio_edge_t;

typedef struct {
    double t;       /* s */
    uint8_t edge;   /* sim_gonio_edge_t */
    int16_t target; /* beacon index, or -1 - spurious index */
    double mirror;  /* mirror angle at the edge, rad in [0, 2 pi), noise included */
} sim_gonio_event_t;

/** Timer_A count at time @p t (the angle clock, started at t = 0, 16 bits). */
uint16_t sim_gonio_count(const sim_gonio_cfg_t *cfg, double t);

/**
 * The edges of each target's pulse between @p t_from and @p t_to (t_to - t_from <= one turn), with
 * the mirror at angle 0 at @p t_index (any earlier index instant) and the vehicle moving along
 * @p seg, sorted by time. A pulse whose line of sight (judged at its centre) is blocked, or
 * beyond max_range, is left out. Pulses of different targets may overlap: sim_photo_feed()
 * turns them into the photodetector's signal. Returns the number written (at most @p max).
 */
size_t sim_gonio_edges(const sim_gonio_cfg_t *cfg, const sim_world_t *w, const sim_segment_t *seg,
                       double t_index, double t_from, double t_to, sim_rng_t *rng,
                       sim_gonio_event_t *out, size_t max);

/** Targets the photodetector tracks: beacons, then glints. */
#define SIM_PHOTO_TARGETS (SIM_MAX_BEACONS + SIM_MAX_SPURIOUS)

/** The photodetector: one output, lit while the beam is on any target (the OR of pulses). */
typedef struct {
    uint8_t lit[SIM_PHOTO_TARGETS];
    unsigned n_lit;
} sim_photo_t;

/** Dark, no target lit. */
void sim_photo_init(sim_photo_t *p);

/**
 * Feed one target edge (in time order). Returns 1 when the output changes: a rising edge that
 * lights the first target, or a falling edge that leaves none lit; 0 otherwise.
 */
int sim_photo_feed(sim_photo_t *p, const sim_gonio_event_t *e);

#endif
