/*
 * harness_internal.h - per-board HAL state shared by the hal/posix sources.
 */
#ifndef HAL_POSIX_HARNESS_INTERNAL_H
#define HAL_POSIX_HARNESS_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/capture.h"
#include "hal/edge.h"
#include "hal_posix/drive_port_posix.h"

typedef struct {
    hal_edge_cb_t cb;
    void *arg;
    int source;
} posix_edge_slot_t;

typedef struct {
    hal_capture_cb_t cb;
    void *arg;
    int source;
    uint16_t count;
    uint8_t rising;
    uint32_t overflows;
} posix_capture_slot_t;

typedef struct {
    posix_drive_sink_fn sink;
    void *ctx;
    uint32_t count;
    uint8_t last[HAL_DRIVE_REG_COUNT];
    posix_drive_write_t log[POSIX_DRIVE_PORT_LOG];
} posix_drive_port_state_t;

typedef struct {
    uint8_t critical_depth;
    bool critical_saved;
    posix_edge_slot_t edge[HAL_EDGE_COUNT];
    posix_capture_slot_t capture[HAL_CAPTURE_COUNT];
    posix_drive_port_state_t drive_port;
} posix_board_state_t;

posix_board_state_t *posix_board_state(int board);

/* The HAL's hot paths on the current board (posix_board_current()), without a board number. */
bool posix_current_set_gie(bool gie); /* returns GIE as it was */
bool posix_current_gie(void);
posix_board_state_t *posix_current_state(void);
void posix_current_dispatch(void); /* deliver what is pending and unmasked */

#endif
