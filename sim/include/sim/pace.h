/*
 * pace.h - live runs (agv-sim --realtime[=FACTOR]): the run loop waits for the wall clock
 * before each simulated instant, so that LCM viewers, lcm-logger and candump see a run as it
 * happens. Pacing only sleeps: the wall clock never enters the simulation's state, and a paced
 * run gives the same report and logs as an unpaced one (wall time excepted).
 */
#ifndef SIM_PACE_H
#define SIM_PACE_H

#include <stdint.h>
#include <time.h>

#define SIM_PACE_MAX_FACTOR 1e6 /* simulated seconds per wall second, at most */

typedef struct {
    double factor;      /* simulated seconds per wall second; 0: not paced */
    struct timespec w0; /* the wall clock (CLOCK_MONOTONIC) when the simulation was at t0_ns */
    uint64_t t0_ns;     /* simulated time of w0, ns */
    uint64_t step_ns;   /* simulated time between two looks at the wall clock (1 ms of wall) */
    uint64_t next_ns;   /* the next simulated instant worth a look at the wall clock */
    uint64_t sleeps;    /* how often the loop waited (not part of any report) */
} sim_pace_t;

/**
 * Start pacing at simulated time @p t0_ns (ns) with @p factor simulated seconds per wall
 * second (1: real time, 10: ten times faster, 0.5: half speed; 0: not paced). Returns 0, or
 * -1 when @p factor is negative, not finite or above SIM_PACE_MAX_FACTOR (@p p then unpaced).
 */
int sim_pace_start(sim_pace_t *p, double factor, uint64_t t0_ns);

/**
 * Wait until the wall clock reaches the instant of simulated time @p sim_ns (ns): w0 +
 * (sim_ns - t0) / factor. Returns at once when not paced, when the run is behind the wall clock,
 * or when less than a millisecond of wall time has passed since the last look.
 */
void sim_pace_wait(sim_pace_t *p, uint64_t sim_ns);

#endif
