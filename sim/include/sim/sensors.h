/*
 * sensors.h - the vehicle's pulse sources, scheduled on the harness along the true motion:
 *  - the odometer: one delta-l pulse to the nav board per dl of front-wheel travel (times the
 *    wheel's scale error); a pulse may be lost, or come with a spurious extra one (glitches);
 *  - the gyro: a step up or down to the nav board whenever the measured heading (truth plus
 *    drift) crosses a step boundary, steps counted around the start heading;
 *  - the goniometer: the index pulse at every mirror turn (one may be lost) and the
 *    photodetector's edges (sim/gonio.h) as captures on the main board, none while the
 *    photodetector is blinded (dropout windows); each rising edge also reaches the nav board
 *    (it latches its pose there) and is recorded with the true pose of its instant and the
 *    target that lit it, so that a fix referring to that latch can be compared with the truth.
 * The random disturbances draw from their own streams of the scenario's seed.
 * Every change of motion reschedules them (sim_sensors_motion()). In mode pursuit the mirror
 * stands still (no index pulse, no edge): the main board navigates on the position receiver
 * and leaves the goniometer off, and seed 002's vehicle had none.
 */
#ifndef SIM_SENSORS_H
#define SIM_SENSORS_H

#include <stddef.h>
#include <stdint.h>

#include "sim/gonio.h"
#include "sim/motion.h"
#include "sim/rng.h"
#include "sim/scenario.h"

#define SIM_SENSORS_MAX_EDGES 256 /* photodetector edges of one revolution */
#define SIM_SENSORS_LATCHES   256 /* rising edges remembered (divides 2^16) */

typedef struct {
    const sim_segment_t *seg; /* the true motion (the drive board's) */
    int main_board, nav_board;
    int dl_source;     /* the nav board's odometer interrupt source (-1: none registered) */
    double dl;         /* m of true front-wheel travel per odometer pulse */
    double gyro_step;  /* rad */
    double gyro_drift; /* rad/s */
    double heading0;   /* rad: the start heading, centre of gyro step 0 */
    const sim_world_t *world;
    const sim_scenario_t *sc; /* the disturbances: losses, glitches, dropout windows */
    sim_gonio_cfg_t gonio;
    int gonio_off; /* mode pursuit: the mirror stands still */
    sim_rng_t rng_gonio;
    sim_rng_t rng_index, rng_odo; /* index pulse losses, odometer glitches */
    /* state */
    double front_next; /* front-wheel total at the next odometer pulse, m */
    long gyro_count;   /* measured heading, in steps from the start */
    int gyro_dir;      /* direction of the scheduled step, +-1 */
    double t_index;    /* last index pulse, s */
    sim_gonio_event_t edges[SIM_SENSORS_MAX_EDGES];
    size_t n_edges, next_edge;
    sim_photo_t photo;
    uint8_t dark[SIM_PHOTO_TARGETS]; /* a pulse that began in a dropout window: not seen */
    uint32_t index_lost, odo_missed, odo_extra; /* disturbances so far */
    uint32_t rises; /* rising edges so far (the nav board's latch numbers count them) */
    double rise_t[SIM_SENSORS_LATCHES];
    sim_pose_t rise_pose[SIM_SENSORS_LATCHES];
    int16_t rise_target[SIM_SENSORS_LATCHES]; /* beacon index, or -1 - glint index */
    uint64_t ev_dl, ev_gyro, ev_gonio;        /* harness event ids, 0 = none */
} sim_sensors_t;

/**
 * The sensors of scenario @p sc on a vehicle moving along @p *seg (read at every event; its
 * owner calls sim_sensors_motion() when it changes), pulses going to harness boards
 * @p main_board and @p nav_board. The mirror turns from t = 0, its first index pulse a
 * random part of a turn later (seeded from the scenario's seed). Nothing is scheduled yet.
 * Call it after the boards' firmware registered its handlers (the odometer's is looked up).
 */
void sim_sensors_init(sim_sensors_t *s, const sim_scenario_t *sc, const sim_segment_t *seg,
                      int main_board, int nav_board);

/** The motion changed at the current time: schedule every pulse source along the new one. */
void sim_sensors_motion(sim_sensors_t *s);

/**
 * The instant (s) and true pose of rising edge number @p latch (counted from 0, modulo 2^16 as
 * the nav board numbers its latches). Returns 0, or -1 when that edge has not happened or is
 * one of the last SIM_SENSORS_LATCHES no more.
 */
int sim_sensors_latch(const sim_sensors_t *s, uint16_t latch, double *t, sim_pose_t *pose);

/**
 * How many distinct map beacons lit the @p n rising edges up to and including @p last (latch
 * numbers as in sim_sensors_latch(); the truth of a revolution's sightings). Edges no longer
 * remembered count as none.
 */
int sim_sensors_beacons(const sim_sensors_t *s, uint16_t last, int n);

#endif
