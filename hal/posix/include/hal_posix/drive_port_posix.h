/*
 * hal_posix/drive_port_posix.h - the host side of hal/drive_port.h: every write a board
 * makes on its drive bus is recorded with the simulated time, kept in a per-board log and
 * passed to an optional sink (the closed-loop simulator's drive-board model feeds the sink's
 * writes to drive_decoder_feed()). The state lives with the board: posix_reset() and
 * posix_board_create() clear it.
 */
#ifndef HAL_POSIX_DRIVE_PORT_POSIX_H
#define HAL_POSIX_DRIVE_PORT_POSIX_H

#include <stddef.h>
#include <stdint.h>

#include "hal/drive_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Writes kept in each board's log (later writes are counted and passed to the sink only). */
#define POSIX_DRIVE_PORT_LOG 1024

/** One recorded bus write. */
typedef struct {
    uint64_t t_ns; /**< simulated time of the write */
    uint8_t reg;   /**< hal_drive_reg_t */
    uint8_t value;
} posix_drive_write_t;

/** Receives every write of @p board as it happens (in the writer's context). */
typedef void (*posix_drive_sink_fn)(void *ctx, int board, const posix_drive_write_t *w);

/** Route the writes of @p board to @p fn (NULL removes the sink). */
void posix_drive_port_set_sink(int board, posix_drive_sink_fn fn, void *ctx);

/** Writes @p board made since its creation or the last posix_drive_port_clear(). */
uint32_t posix_drive_port_count(int board);

/** Copy up to @p max of the logged writes (oldest first) to @p out; returns how many. */
size_t posix_drive_port_log(int board, posix_drive_write_t *out, size_t max);

/** Forget the log and the count of @p board (the sink stays). */
void posix_drive_port_clear(int board);

/** Last value written to @p reg on @p board (0 before any write; 0 for a bad register). */
uint8_t posix_drive_port_value(int board, hal_drive_reg_t reg);

#ifdef __cplusplus
}
#endif

#endif
