/*
 * drive_seq.h - travel sequencing as an explicit state table (SPEC D8, D1; seed 000 ch. 5,
 * whose conclusions recommend "State Table Control Systems" over tangled interrupt logic).
 *
 * Pure logic: the board integration feeds events (index pulse, fix ready or failed, pose
 * available, delta-S pulse, timer elapsed, start, stop) and executes the actions it gets back
 * (request a fix, correct the nav board, request a pose, load arcs, set a speed, stop, start
 * a timer, enable or disable the index pulse, report done or a fault). Every transition is a
 * row of one const table (drive_seq_table()); an event with no row in the current state is
 * ignored and counted (a spurious pulse on a noisy bus cannot derail the sequence).
 *
 * Full travel (seed 5.1): the first double arc is computed from the start pose and loaded
 * (that starts the run); the servo settles; at the next index pulse the optical fix of the
 * revolution is requested; when it is ready the nav board is corrected and the pose at load
 * time (now + load_ms) requested; from it the next target is picked and the double arc
 * computed; at load time it is loaded, and so on. The last target starts the stopping
 * routine: the speed drops to stop_speed at the end of the first arc and the vehicle stops
 * at the end of the second. A delta-S pulse that ends the loaded double arc while the next
 * one waits for its load time loads it at once (D1: the next segment must be ready).
 *
 * Dead reckoning through fix gaps (issue 16, docs/drive.md section 6): in full travel a failed
 * fix is no fault. The sequencer adds up the travel since the last accepted fix (the chords
 * between the poses it is given, from the fix's instant on) and scales the speed of every
 * double arc it builds by drive_blind_speed(): full speed for the first quarter of the blind
 * distance, then slower, down to a quarter at the blind distance, where the vehicle stops (a
 * controlled stop, DRIVE_STOP_BLIND). An accepted fix restores full speed. The nav board
 * watches the same distance on its odometer and asks for the stop (G6, DRIVE_EVT_STOP).
 *
 * Simplified travel (seed 5.2): stopped, the first index pulse is ignored, the second starts
 * a fix (the index pulse is disabled while it is computed), the double arc to the next point
 * is computed from the fix and loaded, the vehicle stops at the last delta-S pulse of the
 * double arc, and the cycle repeats until the last point.
 *
 * D7: the number of delta-S pulses of a loaded double arc is the command's `pulses`
 * (drive_cmd.h); extra pulses are ignored until the next load.
 */
#ifndef DRIVE_DRIVE_SEQ_H
#define DRIVE_DRIVE_SEQ_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "drive/drive_cmd.h"
#include "drive/drive_path.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Travel modes. */
typedef enum { DRIVE_MODE_FULL = 0, DRIVE_MODE_SIMPLIFIED = 1 } drive_mode_t;

/** States. */
typedef enum {
    DRIVE_ST_IDLE = 0,     /**< not started                                                */
    DRIVE_ST_F_START,      /**< full: waiting for the start pose                          */
    DRIVE_ST_F_SETTLE,     /**< full: arcs loaded, servo settling                         */
    DRIVE_ST_F_WAIT_INDEX, /**< full: waiting for the index pulse                         */
    DRIVE_ST_F_FIX,        /**< full: optical fix requested                               */
    DRIVE_ST_F_PREDICT,    /**< full: pose at load time requested                         */
    DRIVE_ST_F_LOAD,       /**< full: next double arc ready, waiting for the load time    */
    DRIVE_ST_F_STOP1,      /**< full: last double arc loaded, slow at the end of arc 1    */
    DRIVE_ST_F_STOP2,      /**< full: stop at the end of arc 2                            */
    DRIVE_ST_S_SKIP_INDEX, /**< simplified: stopped, the first index pulse is ignored     */
    DRIVE_ST_S_WAIT_INDEX, /**< simplified: the second index pulse starts the fix         */
    DRIVE_ST_S_FIX,        /**< simplified: optical fix requested                         */
    DRIVE_ST_S_ARC1,       /**< simplified: driving the first arc                         */
    DRIVE_ST_S_ARC2,       /**< simplified: driving the second arc                        */
    DRIVE_ST_DONE,         /**< path finished: waiting for orders                         */
    DRIVE_ST_FAULT,        /**< stopped on a fault                                        */
    DRIVE_ST_STOPPED,      /**< stopped short of the goal (seq.stop says why)             */
    DRIVE_ST_COUNT,
    DRIVE_ST_ANY = 0xFF /**< table wildcard */
} drive_state_t;

/** Events. */
typedef enum {
    DRIVE_EVT_START = 0,  /**< the operator's go (the path is ready)                        */
    DRIVE_EVT_INDEX,      /**< goniometer index pulse                                       */
    DRIVE_EVT_FIX_READY,  /**< the requested optical fix succeeded (pose: the fix)          */
    DRIVE_EVT_FIX_FAILED, /**< the requested optical fix failed                             */
    DRIVE_EVT_POSE,       /**< the requested pose (current or predicted) is available       */
    DRIVE_EVT_DELTA_S,    /**< drive board: the current arc is almost done                  */
    DRIVE_EVT_TIMER,      /**< the timer started by DRIVE_ACT_TIMER elapsed                 */
    DRIVE_EVT_STOP,       /**< stop request (the nav board's, G6)                           */
    DRIVE_EVT_COUNT
} drive_evt_t;

/** Actions (bits of drive_seq_out_t.actions), to be executed in this order. */
#define DRIVE_ACT_STOP         0x0001u /**< speed 0 (8255: drive_ppi_speed(0))            */
#define DRIVE_ACT_REQUEST_FIX  0x0002u /**< compute the fix of the revolution just ended   */
#define DRIVE_ACT_CORRECT_NAV  0x0004u /**< send the fix to the nav board                  */
#define DRIVE_ACT_REQUEST_POSE 0x0008u /**< ask the nav board for the pose at now + pose_ms */
#define DRIVE_ACT_LOAD         0x0010u /**< send out.cmd to the drive board                */
#define DRIVE_ACT_SET_SPEED    0x0020u /**< send out.speed alone                           */
#define DRIVE_ACT_TIMER        0x0040u /**< (re)start the timer: out.timer_ms              */
#define DRIVE_ACT_INDEX_ON     0x0080u /**< enable the index pulse                         */
#define DRIVE_ACT_INDEX_OFF    0x0100u /**< disable the index pulse                        */
#define DRIVE_ACT_DONE                                                                             \
    0x0200u                     /**< the travel is over: at the goal, or short of it               \
                                      (out.stop says why)                          */
#define DRIVE_ACT_FAULT 0x0400u /**< stopped on a fault: out.fault, out.status      */

/** Why the sequencer stopped on a fault. */
typedef enum {
    DRIVE_FAULT_NONE = 0,
    DRIVE_FAULT_NOT_READY, /**< started without a ready path                          */
    DRIVE_FAULT_SOLVE,     /**< no double arc (or drive-board command) to the target  */
    DRIVE_FAULT_FIXES      /**< simplified: too many optical fixes failed in a row    */
} drive_fault_t;

/** Why the travel stopped short of the goal without a fault. */
typedef enum {
    DRIVE_STOP_NONE = 0,
    DRIVE_STOP_REQUEST, /**< DRIVE_EVT_STOP: the nav board's request (G6)                   */
    DRIVE_STOP_BLIND    /**< full: cfg.blind_distance travelled without an accepted fix     */
} drive_stop_t;

/** Timing and stopping parameters. */
typedef struct {
    drive_mode_t mode;
    uint16_t load_ms;    /**< full: from the fix to the load (seed: t1 + dt1)        */
    uint16_t settle_ms;  /**< full: servo settling after a load (seed: dt2)           */
    fx_q16_t stop_speed; /**< full: speed on the last arc of the stopping routine     */
    /** full: move to the next target when the one ahead is nearer than this along its
     * direction (metres Q16). Double arcs then span up to spacing + advance; where that
     * exceeds the drive board's 8-bit arc length (1.47 m of front wheel, reached sooner in
     * tight turns, where the front wheel runs farther than the rear axle), the nearer target
     * is driven to instead. */
    fx_q16_t advance;
    uint8_t max_fix_failures; /**< simplified: consecutive failed fixes tolerated           */
    /** full: travel without an accepted fix after which the vehicle stops (metres Q16, >= 0;
     * 0 stops at the first pose after a failed fix); the speed falls as it nears it
     * (drive_blind_speed()). */
    fx_q16_t blind_distance;
} drive_seq_config_t;

/** What the integration must do after a step. */
typedef struct {
    uint16_t actions;      /**< DRIVE_ACT_* bits                                        */
    drive_cmd_t cmd;       /**< DRIVE_ACT_LOAD: the double arc                          */
    int8_t speed;          /**< DRIVE_ACT_SET_SPEED / DRIVE_ACT_STOP: speed counts       */
    uint16_t timer_ms;     /**< DRIVE_ACT_TIMER                                         */
    uint16_t pose_ms;      /**< DRIVE_ACT_REQUEST_POSE: 0 = now, else predicted ahead   */
    drive_fault_t fault;   /**< DRIVE_ACT_FAULT                                         */
    drive_stop_t stop;     /**< DRIVE_ACT_DONE short of the goal: why                   */
    drive_status_t status; /**< DRIVE_ACT_FAULT for DRIVE_FAULT_SOLVE: the solver's say */
} drive_seq_out_t;

/** One event. */
typedef struct {
    drive_evt_t type;
    drive_pose_t pose; /**< DRIVE_EVT_POSE, DRIVE_EVT_FIX_READY */
} drive_seq_event_t;

/** The sequencer. */
typedef struct {
    drive_seq_config_t cfg;
    drive_path_t *path;
    drive_state_t state;
    drive_path_cursor_t target;  /**< the point driven to                                */
    drive_cmd_t loaded, pending; /**< on the drive board; computed, not yet loaded         */
    bool pending_last;           /**< pending targets the last point                       */
    bool loaded_last;            /**< loaded targets the last point                        */
    uint8_t pulses_seen;         /**< delta-S pulses since the last load                   */
    uint8_t fix_failures;        /**< consecutive failed fixes                             */
    fx_q16_t blind;              /**< travel since the last accepted fix (m Q16, saturates)  */
    drive_pose_t blind_from;     /**< where it is counted from: the fix, then each pose    */
    drive_stop_t stop;           /**< why the travel stopped short (DRIVE_ST_STOPPED)       */
    drive_status_t solve_status; /**< last solve (or command) status                       */
    uint16_t ignored;            /**< events without a row in their state                  */
    uint16_t underruns;          /**< double arcs that ended before the next was ready     */
    uint16_t loads;              /**< double arcs loaded                                   */
} drive_seq_t;

/** One row of the state table. */
typedef struct {
    uint8_t state; /**< drive_state_t or DRIVE_ST_ANY */
    uint8_t event; /**< drive_evt_t */
    uint8_t guard; /**< condition (seq.c: G_*) */
    uint8_t next;  /**< drive_state_t */
    uint16_t actions;
} drive_seq_row_t;

/** The state table (for documentation and tests); *n receives its length. */
const drive_seq_row_t *drive_seq_table(uint16_t *n);

/** Set up @p seq for @p path (prepared by drive_path_prepare) in state IDLE. */
void drive_seq_init(drive_seq_t *seq, drive_path_t *path, const drive_seq_config_t *cfg);

/**
 * Feed one event; returns the actions in @p out (0 when the event was ignored). Runs the
 * solver (and the path's secondary-point computation) for pose and fix events that pick a
 * target: up to a few solves, never from an interrupt handler in that case.
 */
void drive_seq_step(drive_seq_t *seq, const drive_seq_event_t *ev, drive_seq_out_t *out);

/**
 * The speed of a double arc built @p blind metres (Q16, >= 0) after the last accepted fix,
 * for a path speed @p speed (m/s Q16, >= 0) and the blind distance @p limit (m Q16): speed *
 * clamp(5/4 - blind / limit, 1/4, 1), i.e. full speed up to a quarter of the limit, then
 * falling linearly to a quarter of it at the limit (docs/drive.md, "Dead reckoning through fix
 * gaps"). Never below @p slowest (the drive board's one speed count), unless @p speed itself
 * is; @p limit <= 0: a quarter of the speed. Rounded to nearest (0.5 LSB of the factor).
 */
fx_q16_t drive_blind_speed(fx_q16_t speed, fx_q16_t blind, fx_q16_t limit, fx_q16_t slowest);

/** Short name of a state (for logs). */
const char *drive_seq_state_name(drive_state_t st);

/* ------------------------------------------------------------------ delta-S pulse (D1) */

/** Pulses counted by the delta-S handler, taken by the main loop. */
typedef struct {
    volatile uint16_t count;
} drive_ds_t;

/**
 * Register the delta-S line (HAL_EDGE_DELTA_S, rising edge) to count into @p ds.
 * Returns hal_edge_init()'s result.
 */
int drive_ds_init(drive_ds_t *ds);

/** The portable handler (what the MSP430's Port 2 ISR calls): counts one pulse. */
void drive_ds_handler(void *arg);

/** Pulses since the last call (interrupts held off while taking them). */
uint16_t drive_ds_take(drive_ds_t *ds);

#ifdef __cplusplus
}
#endif

#endif
