/*
 * run.h - one closed-loop run: both boards' firmware on the harness (hal/posix), the drive
 * board and the vehicle (sim/drive_board.h), its sensors (sim/sensors.h) and the telemetry
 * (sim/telemetry.h) and the board link's CAN bus (sim/canbus.h, sim/socketcan.h), from the start
 * to the end of the scenario's time or, once the travel is done, has stopped or has faulted,
 * half a second after the vehicle stands.
 */
#ifndef SIM_RUN_H
#define SIM_RUN_H

#include <stddef.h>
#include <stdint.h>

#include "sim/mission.h"
#include "sim/report.h"
#include "sim/scenario.h"
#include "sim/telemetry.h"

typedef struct {
    const char *log_dir; /* CSV logs there (created with its parents), or NULL */
    const char *lcm_url; /* LCM telemetry there, or NULL */
    int quiet;           /* no progress lines on stderr */
    int trace;           /* every fix attempt, travel state and CAN error on stderr */
    const char *can;     /* carry the bus's frames through this SocketCAN interface, or NULL */
    const char *candump; /* the bus traffic in candump's log format there, or NULL */
    double realtime;     /* simulated s per wall s (sim/pace.h), 0: as fast as it goes */
    int ticks;           /* the boards' clock interrupts every millisecond (else tickless:
                          * posix_clock_set_tickless(); the run is the same, only faster) */
} sim_run_options_t;

/** Work counters of a run: deterministic (the same scenario and seed give the same), and the
 * processor time the run took (which is not). */
typedef struct {
    double cpu_time_s;        /* processor time of the run's loop, s (varies) */
    uint64_t events;          /* harness events run */
    uint64_t samples;         /* cross-track samples */
    uint64_t pieces;          /* pieces of the nominal path */
    uint64_t pieces_indexed;  /* of them, distinct (a repeated route is indexed once) */
    uint64_t pieces_examined; /* piece distances computed by the samples */
    uint64_t lcm_published[SIM_LCM_CHANNELS]; /* LCM messages published, per channel */
    uint64_t lcm_failed;                      /* LCM messages that could not be sent */
} sim_run_stats_t;

/**
 * Run scenario @p sc with its download @p m (sim_mission_build()) under options @p o; fill
 * @p r (zeroed first; the caller frees it with sim_report_free()) and @p stats. With
 * @p o->realtime the loop waits for the wall clock before each instant (sim/pace.h): the run
 * is the same, only slower. Returns 0 when the run went to its end, or -1 with the reason in
 * @p err when it could not start (a board refused its configuration, an output or the
 * SocketCAN interface could not be opened, a pacing factor out of range) or --can failed on
 * the way.
 */
int sim_run(const sim_scenario_t *sc, sim_mission_t *m, const sim_run_options_t *o, sim_report_t *r,
            sim_run_stats_t *stats, char *err, size_t errlen);

#endif
