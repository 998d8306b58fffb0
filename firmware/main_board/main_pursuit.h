/*
 * main_pursuit.h - the main board's third travel mode: seed 002's goal-point pursuit on the
 * serial position receiver (SPEC P2-P5; docs/pursuit.md).
 *
 * The laser positioning system's receiver sends positions on USCI_A1 (hal/uart.h instance
 * 0; a second receiver on instance 1); the receive handler frames them (firmware/posrx), the
 * main loop judges them, and every accepted position goes to the pursuit (firmware/pursuit),
 * whose steering and speed reach the drive board in seed 002's DAC style
 * (firmware/drive/proto.c: steering value around the centre, speed 128 + counts, digital
 * outputs for the motors and the brake). The heading is the direction between the last two
 * accepted positions (the seed), the vector between the two receivers, or the nav board's
 * dead-reckoned heading (asked for with the coordinate request at each update). The optical
 * fix and the double-arc sequencer stay idle in this mode; the nav board's stop request
 * (blind distance) does not apply: the receiver's own watchdog (error recovery) does.
 */
#ifndef MAIN_PURSUIT_H
#define MAIN_PURSUIT_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "optical/optical.h"
#include "posrx/posrx.h"
#include "pursuit/pursuit.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Where the heading of an update comes from. */
typedef enum {
    MAIN_HEADING_POSITIONS = 0, /**< the last two accepted positions (seed 002) */
    MAIN_HEADING_RECEIVERS,     /**< the two receivers (needs receivers == 2) */
    MAIN_HEADING_NAV            /**< the nav board's dead-reckoned heading */
} main_heading_t;

/** Pursuit mode's download. */
typedef struct {
    pursuit_config_t law; /**< the pursuit's parameters */
    posrx_config_t rx;    /**< the receivers' acceptance rules */
    uint32_t baud;        /**< the receivers' lines (hal/uart.h rates) */
    uint8_t receivers;    /**< 1 or 2 */
    uint8_t heading;      /**< main_heading_t */
} main_pursuit_config_t;

/** Outcome of a packet beyond posrx_reason_t: refused by the two receivers' check. */
#define MAIN_PURSUIT_PAIR POSRX_REASON_COUNT

/** One framed packet, as the observer sees it. */
typedef struct {
    uint8_t receiver;     /**< 0 or 1 */
    uint8_t reason;       /**< posrx_reason_t, or MAIN_PURSUIT_PAIR */
    posrx_pos_t pos;      /**< as received */
    bool used;            /**< fed to the pursuit: rec is valid */
    pursuit_record_t rec; /**< the pursuit's record of the update */
} main_pursuit_event_t;

/** Counters of pursuit mode. */
typedef struct {
    pursuit_stats_t law;
    posrx_stats_t rx[2];
    uint16_t unpaired;     /**< two receivers: updates without the other's position */
    uint16_t nav_timeouts; /**< nav heading: updates the nav board did not answer in time */
    uint16_t overruns[2];  /**< bytes the UARTs lost */
    bool done;
} main_pursuit_stats_t;

/** A copy of pursuit mode's counters (zero outside pursuit mode). */
void main_pursuit_stats(main_pursuit_stats_t *out);

/* ---- between main_board.c and main_pursuit.c ---- */

struct main_board_config;

/** Set pursuit mode up (from main_board_init): receivers, the pursuit, the drive board.
 * DRIVE_ERR_PARAM when its configuration is not acceptable. */
drive_status_t main_pursuit_init(const struct main_board_config *cfg);

/** The operator's go (from main_board_start). */
void main_pursuit_start(void);

/** One pass of the main loop (from main_board_poll). */
void main_pursuit_poll(void);

/** True once the path is finished. */
bool main_pursuit_done(void);

/** main_board.c: give @p ev to the observer (main_board_observer_t.on_pursuit), if any. */
void main_board_notify_pursuit(const main_pursuit_event_t *ev);

/** main_board.c: the nav board's pose, if one arrived since the last call (a coordinate
 * request answered). */
bool main_board_pose_take(optical_pose_t *out);

#ifdef __cplusplus
}
#endif

#endif
