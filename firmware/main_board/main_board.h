/*
 * main_board.h - the main board application (the original 8086 computer): goniometer,
 * optical fix, drive routine and drive-board I/O. Portable: the MSP430 main() and the host
 * harness both drive it through these two calls.
 */
#ifndef MAIN_BOARD_H
#define MAIN_BOARD_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Counters kept by the interrupt handlers, for diagnostics. */
typedef struct {
    uint32_t index_pulses; /**< goniometer index pulses (mirror revolutions) */
    uint32_t edges;        /**< photodetector edges captured */
    uint32_t delta_s;      /**< drive-board delta-S pulses */
} main_board_stats_t;

/** Register the portable interrupt handlers; interrupts stay disabled. */
void main_board_init(void);

/** One pass of the main loop: does the work the handlers left and returns. */
void main_board_poll(void);

/** A consistent copy of the counters (taken with interrupts disabled). */
void main_board_stats(main_board_stats_t *out);

#ifdef __cplusplus
}
#endif

#endif
