/*
 * drive_board.h - the drive board and the vehicle it moves. The board decodes what the main
 * board writes to its port (firmware/drive's decoder), steers and drives each arc of a loaded
 * double arc at the commanded speed, raises delta-S SIM_DRIVE_DS_MARGIN before an arc's end
 * (only for arcs long enough to raise a clean pulse), stops when the double arc is done, and
 * brakes at SIM_DRIVE_BRAKE when told speed 0. The vehicle's true motion is one
 * constant-steering segment at a time, at constant speed or braking (sim/motion.h); every
 * change of segment is reported to the owner (the sensors reschedule their pulses along the
 * new motion).
 *
 * Seed 002's DAC style (firmware/drive/proto.c): the steering DAC turns the wheel at once
 * (within the vehicle's steering range, atan(wheelbase / minimum radius)), the speed DAC sets
 * the speed (128 + counts) while the drive motor is enabled and the brake released; speed 0,
 * a disabled motor or the brake brakes at SIM_DRIVE_BRAKE as the 8255's speed 0 does.
 *
 * Units: metres, seconds, radians. The drive board's units (length counts per metre of front
 * wheel, speed per count, shortest arc with a clean pulse, DAC centre) are the drive_board_t
 * the main board is configured with (firmware/drive/include/drive/drive_cmd.h).
 */
#ifndef SIM_DRIVE_BOARD_H
#define SIM_DRIVE_BOARD_H

#include <stdint.h>

#include "drive/drive_cmd.h"
#include "drive/drive_proto.h"
#include "sim/motion.h"

#define SIM_DRIVE_DS_MARGIN 0.02 /* m: delta-S comes this far before an arc ends */
#define SIM_DRIVE_BRAKE     0.5  /* m/s^2: braking when told speed 0 (a steady ramp) */

/** One loaded arc, as the board drives it. */
typedef struct {
    double alpha; /* steering angle, rad, left positive */
    double left;  /* rear-axle length still to drive, m */
    int pulse;    /* 1: no delta-S for this arc (too short for a clean pulse) or already raised */
} sim_drive_arc_t;

/** The segment changed at @p t (s): the owner reschedules what depends on the motion. */
typedef void (*sim_drive_motion_fn)(void *ctx, double t);
/** The board took a command at @p t (s) (logs, telemetry). */
typedef void (*sim_drive_command_fn)(void *ctx, double t, const drive_event_t *ev);

typedef struct {
    drive_board_t units; /* the board's units, as the main board knows them */
    double wheelbase;    /* m */
    int main_board;      /* harness board that gets delta-S */
    drive_decoder_t dec;
    sim_drive_arc_t arc[2];
    int cur;           /* arc being driven, 2 = none */
    int braking;       /* 1 while braking to a stop */
    double alpha, v;   /* commanded steering (rad) and speed (m/s) */
    int dac;           /* 1 once driven in seed 002's DAC style (no arcs: steering and speed) */
    double dac_v;      /* DAC style: the speed DAC's speed, m/s */
    uint8_t outputs;   /* DAC style: the digital outputs (DRIVE_OUT_*) */
    sim_segment_t seg; /* the vehicle's true motion now */
    uint64_t ev;       /* the board's next event (harness id), 0 = none */
    sim_drive_motion_fn on_motion;
    sim_drive_command_fn on_command;
    void *ctx;
} sim_drive_t;

/**
 * A standing vehicle at @p start (time 0) with wheelbase @p wheelbase (m), its drive board of
 * units @p units raising delta-S on harness board @p main_board. @p on_motion and @p on_command
 * (either may be NULL) get @p ctx.
 */
void sim_drive_init(sim_drive_t *d, const drive_board_t *units, double wheelbase, int main_board,
                    sim_pose_t start, sim_drive_motion_fn on_motion,
                    sim_drive_command_fn on_command, void *ctx);

/**
 * One write of the main board on the drive bus (register @p reg, byte @p value) at the
 * harness's current time: a completed command changes the motion at once.
 */
void sim_drive_write(sim_drive_t *d, uint8_t reg, uint8_t value);

/** Schedule the board's next event (a delta-S, an arc's end, the end of braking) from @p t (s). */
void sim_drive_schedule(sim_drive_t *d, double t);

/**
 * A command in SI units: each arc's steering angle (degrees, left positive) and front-wheel
 * length (m), and the speed (m/s, negative in reverse), in the board's units.
 */
void sim_drive_command_si(const sim_drive_t *d, const drive_cmd_t *cmd, double steer_deg[2],
                          double length_m[2], double *speed_mps);

/** The vehicle's true pose at @p t (s, not before the current segment began). */
sim_pose_t sim_drive_pose(const sim_drive_t *d, double t);

/** 1 when the vehicle stands and the board is not braking. */
int sim_drive_standing(const sim_drive_t *d);

#endif
