/*
 * main_board.h - the main board (the original 8086 computer): goniometer capture and the
 * optical fix (firmware/optical), the drive routine and its travel sequence (firmware/drive),
 * the drive-board port, and the link to the nav board (firmware/link). Portable: the MSP430
 * main() and the host harness drive it through these calls.
 *
 * One revolution in full travel (seed 000, 5.1; docs/integration.md): the index pulse ends a
 * revolution; the sequencer asks for its fix; the board asks the nav board for the poses it
 * latched at the revolution's sightings (brought into one frame), runs optical_fix() with the
 * last sighting's latch as the reference instant, sends the fix (Buffer Full) referring to
 * that latch, waits for the nav board's acknowledgement, pulses the coordinate request,
 * predicts the pose at load time along the loaded arc, and the sequencer picks the next
 * target, solves the double arc and loads it at its time. Simplified travel stops at every
 * point and fixes standing still (5.2).
 *
 * Files: main_board.c is what every travel shares (this API, the configuration's dispatch, the
 * link and its messages, observers, counters); the beacon travel is main_beacon.c
 * (main_beacon.h), seed 002's pursuit main_pursuit.c (main_pursuit.h). The host links both;
 * an MSP430 image links one and the other's twin (main_beacon_none.c, main_pursuit_none.c),
 * which refuses its mode: the beacon image main_board.elf, the pursuit image
 * main_board_pursuit.elf (README, "The MCU").
 */
#ifndef MAIN_BOARD_H
#define MAIN_BOARD_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "drive/drive_cmd.h"
#include "drive/drive_path.h"
#include "drive/drive_seq.h"
#include "link/link.h"
#include "main_pursuit.h"
#include "optical/optical.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most primary path points (drive_path_prepare()'s limit; secondary points are computed on
 * the way, so a path needs points only where it bends). */
#define MAIN_BOARD_MAX_PATH 254

/** What the board is told before a run (the base station's download, seed 5.1 step 1). */
typedef struct main_board_config {
    optical_map_t map; /**< the beacon map, compiled (optical_map_compile) */
    /** Primary points with their speeds, prepared in place (the board writes each point's
     * nsub and reads the points while it drives): the storage must outlive the run, and
     * holding it is the caller's choice (RAM is 2 KB: 18 bytes a point). */
    drive_path_point_t *path;
    uint8_t n_path;               /**< 1..MAIN_BOARD_MAX_PATH */
    drive_pose_t start;           /**< the initial vector */
    drive_board_t board;          /**< the vehicle and its drive board */
    drive_path_config_t path_cfg; /**< nominal radius, point spacing, direction */
    drive_seq_config_t seq_cfg;   /**< travel mode and its times */
    uint16_t counts_per_turn;     /**< goniometer angle clock per mirror turn */
    optical_config_t optical;     /**< identification and checking parameters */
    link_config_t link;           /**< the board link (node LINKMSG_NODE_MAIN) */
    /** Pursuit mode (seed 002's goal-point pursuit on the serial position receiver,
     * main_pursuit.h) with its parameters, or NULL: the travel of seq_cfg.mode. */
    const main_pursuit_config_t *pursuit;
} main_board_config_t;

/** One fix attempt, as the observer sees it. */
typedef struct {
    int8_t status;               /**< optical_status_t; OPTICAL_E_REV also for missing latches */
    uint8_t n;                   /**< sightings of the revolution */
    uint16_t ref_latch;          /**< the latch (photodetector rising edge number) it refers to */
    optical_fix_t fix;           /**< the pipeline's result */
    optical_pose_t approx;       /**< the dead-reckoning pose at the reference instant */
    const optical_sighting_t *s; /**< the sightings (sorted by angle), valid during the call */
} main_board_fix_event_t;

/** Observers (host harness, telemetry); every member may be NULL. */
typedef struct {
    void *ctx;
    void (*on_fix)(void *ctx, const main_board_fix_event_t *ev);
    void (*on_load)(void *ctx, const drive_cmd_t *cmd);
    void (*on_state)(void *ctx, drive_state_t state);
    /** Pursuit mode: every packet the receivers framed, and what became of it. */
    void (*on_pursuit)(void *ctx, const main_pursuit_event_t *ev);
} main_board_observer_t;

/**
 * Why the main board stopped the travel: X(name, report name), one list for the enum below and
 * for agv-sim's report (its `stop_reason`): adding a reason is one line here and the code that
 * stops with it.
 */
#define MAIN_BOARD_STOP_REASONS(X)                                                                 \
    X(NONE, "")                           /* not stopped (or the goal reached) */                  \
    X(BLIND_DISTANCE, "blind_distance")   /* the nav board: too far without a fix (G6) */          \
    X(LINK_SILENT, "link_silent")         /* nothing heard from the nav board for silence_ms */    \
    X(NAV_LINK_SILENT, "nav_link_silent") /* the nav board heard nothing from this board */        \
    X(FAULT_NOT_READY, "fault:not_ready") /* the sequencer: started without a ready path */        \
    X(FAULT_SOLVE, "fault:solve")         /* the sequencer: no double arc to the target */         \
    X(FAULT_FIXES, "fault:fixes")         /* the sequencer: too many failed fixes in a row */      \
    X(FAULT_CAN, "fault:can")             /* the CAN controller did not start: no link */

#define MAIN_BOARD_STOP_ENUM(name, text) MAIN_BOARD_STOP_##name,
typedef enum {
    MAIN_BOARD_STOP_REASONS(MAIN_BOARD_STOP_ENUM) MAIN_BOARD_STOP_COUNT
} main_board_stop_t;
#undef MAIN_BOARD_STOP_ENUM

/** Counters for diagnostics. */
typedef struct {
    uint32_t revolutions; /**< index pulses */
    uint16_t fixes_ok, fixes_failed;
    uint16_t fixes_acked;    /**< fixes the nav board installed */
    uint16_t latch_timeouts; /**< fixes abandoned waiting for latches */
    uint16_t loads;          /**< double arcs loaded */
    uint16_t link_errors;
    uint8_t done, fault;
    uint8_t fault_why;   /**< drive_fault_t */
    uint8_t stop_reason; /**< main_board_stop_t: why the travel stopped (NONE: it did not) */
    int8_t can_error;    /**< hal_can_init()'s error when the controller did not start, else 0 */
} main_board_stats_t;

/**
 * Set the board up for @p cfg, kept by reference (on the target it is a constant in flash):
 * @p cfg and what it points to must outlive the run. Sets up the travel of its mode (the beacon
 * travel: capture handlers, delta-S line, the path prepared; pursuit mode with cfg->pursuit:
 * the receivers' lines and the pursuit), the drive port, the link on CAN (cfg->link), the
 * clock. Interrupts stay disabled. Returns DRIVE_OK, or why the path or the configuration is
 * not acceptable (DRIVE_ERR_PARAM also for a link configuration link_init() refuses, and for a
 * mode the image does not carry; the board then refuses to start). A CAN controller that does
 * not answer is no configuration error: the board comes up without its link (stats
 * can_error), and in the beacon travel main_board_start() stops the travel at once
 * (fault:can).
 */
drive_status_t main_board_init(const main_board_config_t *cfg);

/** Where the path preparation failed (valid after main_board_init() returned an error; the
 * beacon travel's, main_beacon.c: not in an image without it). */
const drive_path_t *main_board_path(void);

/** The operator's go: starts the travel sequence (needs interrupts enabled). */
void main_board_start(void);

/** One pass of the main loop: does the work the handlers left and returns. */
void main_board_poll(void);

/** Set the observers (NULL removes them). */
void main_board_set_observer(const main_board_observer_t *obs);

/** A copy of the counters. */
void main_board_stats(main_board_stats_t *out);

/** A copy of the link's counters (with the CAN controller's). */
void main_board_link_stats(link_stats_t *out);

/** The travel sequencer's state. */
drive_state_t main_board_state(void);

#ifdef __cplusplus
}
#endif

#endif
