/*
 * main_beacon.h - between the main board's common part (main_board.c: configuration, the
 * board link and its messages, observers, counters, the main loop's dispatch) and its beacon
 * travel (main_beacon.c: goniometer capture, the optical fix and its gate, the double-arc
 * travel sequencer and the drive board's port; seed 000, 5.1 and 5.2).
 *
 * An image without the beacon travel (the pursuit image, main_board_pursuit.elf) links
 * main_beacon_none.c instead of main_beacon.c: main_board_init() then refuses a configuration
 * without pursuit mode (DRIVE_ERR_PARAM). The host links main_beacon.c.
 */
#ifndef MAIN_BEACON_H
#define MAIN_BEACON_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "drive/drive_seq.h"
#include "link/link.h"
#include "main_board.h"
#include "optical/optical.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What main_board.c keeps for every travel mode and the beacon travel reads and updates. */
typedef struct {
    const main_board_config_t *cfg; /**< kept by reference (main_board_init) */
    link_t link;                    /**< the board link (node LINKMSG_NODE_MAIN) */
    main_board_observer_t obs;
    main_board_stats_t stats;
    uint8_t pose_in;     /**< a POSE arrived (the link's receive interrupt sets it) */
    optical_pose_t pose; /**< ... the nav board's pose it carried */
    uint8_t stop_in;     /**< a STOP arrived: its main_board_stop_t, else 0 */
} main_board_common_t;

/** main_board.c: the board's common state. */
extern main_board_common_t main_board_common;

/**
 * Check the beacon travel's part of @p cfg (the beacon map: 3..OPTICAL_MAX_BEACONS beacons;
 * the goniometer's counts per turn > 0), set its state up and attach its inputs: the
 * goniometer's index and photodetector captures, the delta-S line. From main_board_init()
 * before the link; interrupts disabled. DRIVE_ERR_PARAM: the configuration is not acceptable
 * (nothing attached).
 */
drive_status_t main_beacon_init(const main_board_config_t *cfg);

/** Prepare the path and the travel sequencer (from main_board_init(), after the link and the
 * drive port): DRIVE_OK or why the path is not acceptable (main_board_path()). */
drive_status_t main_beacon_prepare(void);

/** The operator's go (from main_board_start()): the travel starts, or stops at once without
 * the board link (fault:can). */
void main_beacon_start(void);

/** One pass of the main loop (from main_board_poll()): delta-S, index pulses, the link's
 * pass and the nav board's stop request, the fix, the pose request, the timer. */
void main_beacon_poll(void);

/** A message from the nav board that only the beacon travel reads (LATCH, FIX_ACK), in the
 * link's receive interrupt: true when @p m was one of them (the main loop is woken). */
bool main_beacon_on_msg(const linkmsg_t *m);

/** The travel sequencer's state. */
drive_state_t main_beacon_state(void);

#ifdef __cplusplus
}
#endif

#endif
