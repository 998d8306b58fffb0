/*
 * nav_board.h - the navigation board (the original 8085 ground navigator): dead reckoning at
 * every odometer pulse (firmware/groundnav), pose latches at beacon sightings, optical fixes
 * from the main board, the coordinate request, the stop request (SPEC G1-G6). Portable: the
 * MSP430 main() and the host harness drive it through these calls.
 *
 * Interrupts: odometer, gyro and beacon-sighted lines (groundnav's handlers), the coordinate
 * request on the non-maskable line (a consistent snapshot, answered from the main loop), the
 * CAN receive interrupt (messages queued for the main loop) and the 1 ms clock. The main loop
 * answers latch requests, applies fixes (gnav_fix takes about 2 ms on the MSP430), sends the
 * pose after a coordinate request, its heartbeat, and the stop request: after the blind
 * distance (G6), or when it hears nothing from the main board (docs/integration.md).
 */
#ifndef NAV_BOARD_H
#define NAV_BOARD_H

#include <stdint.h>

#include "groundnav/gnav.h"
#include "link/link.h"

#ifdef __cplusplus
extern "C" {
#endif

/** nav_board_init(): the link configuration was refused. */
#define NAV_BOARD_E_LINK (-100)

typedef struct {
    gnav_config_t gnav; /**< wheelbase, odometer pulse, gyro step, stop distance */
    gnav_pose_t start;  /**< the initial vector (also sets the gyroscope) */
    link_config_t link; /**< the board link (node LINKMSG_NODE_NAV) */
} nav_board_config_t;

/** Counters for diagnostics. */
typedef struct {
    uint32_t coord_requests; /**< coordinate requests answered */
    uint32_t fixes_applied;  /**< optical fixes installed */
    uint32_t fixes_refused;  /**< optical fixes gnav_fix() refused (latch gone, busy...) */
    uint32_t latches_sent;   /**< latches sent on request */
    uint16_t link_errors;    /**< malformed or orphan frames */
    uint8_t stop_sent;       /**< stop requests sent: bit (reason - 1), LINKMSG_STOP_REASON_* */
    int8_t can_error;        /**< hal_can_init()'s error when the controller did not start */
} nav_board_stats_t;

/**
 * Set the board up: dead reckoning from @p cfg, handlers registered, the clock and the link on
 * CAN (cfg->link) started. Interrupts stay disabled. Returns 0, a gnav_err_t (configuration
 * refused) or NAV_BOARD_E_LINK (link_init() refused cfg->link). A CAN controller that does not
 * answer is no configuration error: the board dead-reckons without its link (stats can_error).
 */
int nav_board_init(const nav_board_config_t *cfg);

/** One pass of the main loop: answers what the handlers queued, then returns. */
void nav_board_poll(void);

/** The dead-reckoned pose now (consistent from any context). */
void nav_board_pose(gnav_pose_t *out);

/** A copy of the counters. */
void nav_board_stats(nav_board_stats_t *out);

/** A copy of the link's counters (with the CAN controller's). */
void nav_board_link_stats(link_stats_t *out);

#ifdef __cplusplus
}
#endif

#endif
