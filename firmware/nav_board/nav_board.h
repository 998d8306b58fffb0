/*
 * nav_board.h - the navigation board (the original 8085 ground navigator): dead reckoning at
 * every odometer pulse (firmware/groundnav), pose latches at beacon sightings, optical fixes
 * from the main board, the coordinate request, the stop request (SPEC G1-G6). Portable: the
 * MSP430 main() and the host harness drive it through these calls.
 *
 * Interrupts: odometer, gyro and beacon-sighted lines (groundnav's handlers), the coordinate
 * request on the non-maskable line (a consistent snapshot, answered from the main loop), and
 * the link's receive interrupt (messages queued for the main loop). The main loop answers
 * latch requests, applies fixes (gnav_fix takes about 2 ms on the MSP430), sends the pose
 * after a coordinate request and the stop request (docs/integration.md has the protocol).
 */
#ifndef NAV_BOARD_H
#define NAV_BOARD_H

#include <stdint.h>

#include "groundnav/gnav.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    gnav_config_t gnav; /**< wheelbase, odometer pulse, gyro step, stop distance */
    gnav_pose_t start;  /**< the initial vector (also sets the gyroscope) */
} nav_board_config_t;

/** Counters for diagnostics. */
typedef struct {
    uint32_t coord_requests; /**< coordinate requests answered */
    uint32_t fixes_applied;  /**< optical fixes installed */
    uint32_t fixes_refused;  /**< optical fixes gnav_fix() refused (latch gone, busy...) */
    uint32_t latches_sent;   /**< latches sent on request */
    uint16_t link_errors;    /**< malformed or orphan frames */
    uint8_t stop_sent;       /**< the stop request went out */
} nav_board_stats_t;

/**
 * Set the board up: dead reckoning from @p cfg, handlers registered, link started.
 * Interrupts stay disabled. Returns 0 or a gnav_err_t (configuration refused).
 */
int nav_board_init(const nav_board_config_t *cfg);

/** One pass of the main loop: answers what the handlers queued, then returns. */
void nav_board_poll(void);

/** The dead-reckoned pose now (consistent from any context). */
void nav_board_pose(gnav_pose_t *out);

/** A copy of the counters. */
void nav_board_stats(nav_board_stats_t *out);

#ifdef __cplusplus
}
#endif

#endif
