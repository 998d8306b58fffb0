/*
 * nav_board.h - the navigation board application (the original 8085 ground navigator):
 * dead reckoning at every odometer pulse. Portable: the MSP430 main() and the host harness
 * both drive it through these two calls.
 */
#ifndef NAV_BOARD_H
#define NAV_BOARD_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Counters kept by the interrupt handlers, for diagnostics. */
typedef struct {
    uint32_t delta_l;   /**< odometer pulses */
    int32_t gyro;       /**< gyro steps, counter-clockwise positive */
    uint32_t sightings; /**< beacon-sighted pulses from the main board */
} nav_board_stats_t;

/** Register the portable interrupt handlers; interrupts stay disabled. */
void nav_board_init(void);

/** One pass of the main loop: does the work the handlers left and returns. */
void nav_board_poll(void);

/** A consistent copy of the counters (taken with interrupts disabled). */
void nav_board_stats(nav_board_stats_t *out);

#ifdef __cplusplus
}
#endif

#endif
