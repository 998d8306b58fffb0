/*
 * periph.c - hal/edge.h and hal/capture.h on the harness: each logical line is a source at
 * the vector and bit of hal/pinmap.h, so priorities match the MSP430.
 */
#include <stddef.h>

#include "hal/capture.h"
#include "hal/edge.h"
#include "hal/pinmap.h"
#include "hal_posix/harness.h"
#include "harness_internal.h"

int hal_edge_init(hal_edge_line_t line, hal_edge_flank_t flank, hal_edge_cb_t cb, void *arg)
{
    (void)flank; /* the harness raises the edge the firmware asked for */
    if ((unsigned)line >= HAL_EDGE_COUNT || cb == NULL)
        return -1;
    int b = posix_board_current();
    posix_edge_slot_t *slot = &posix_board_state(b)->edge[line];
    slot->cb = cb;
    slot->arg = arg;
    /* the handler is the source's own (same signature): no trampoline on the hot path */
    slot->source = posix_source_register(b, (int)hal_edge_vector(line), (int)hal_edge_pin(line),
                                         line == HAL_EDGE_COORD_REQUEST, cb, arg);
    return slot->source < 0 ? -1 : 0;
}

void hal_edge_enable(hal_edge_line_t line, uint8_t enable)
{
    if ((unsigned)line >= HAL_EDGE_COUNT)
        return;
    int b = posix_board_current();
    posix_edge_slot_t *slot = &posix_board_state(b)->edge[line];
    if (slot->cb != NULL)
        posix_source_enable(b, slot->source, enable != 0);
}

int posix_edge_source(int board, hal_edge_line_t line)
{
    if ((unsigned)line >= HAL_EDGE_COUNT)
        return -1;
    posix_edge_slot_t *slot = &posix_board_state(board)->edge[line];
    return slot->cb != NULL ? slot->source : -1;
}

void posix_edge_raise(int board, hal_edge_line_t line)
{
    int s = posix_edge_source(board, line);
    if (s >= 0)
        posix_source_raise(board, s);
}

static void capture_trampoline(void *ctx)
{
    posix_capture_slot_t *slot = ctx;
    slot->cb(slot->arg, slot->count, slot->rising);
}

int hal_capture_init(hal_capture_channel_t ch, hal_capture_cb_t cb, void *arg)
{
    if ((unsigned)ch >= HAL_CAPTURE_COUNT || cb == NULL)
        return -1;
    int b = posix_board_current();
    posix_capture_slot_t *slot = &posix_board_state(b)->capture[ch];
    slot->cb = cb;
    slot->arg = arg;
    slot->source = posix_source_register(b, (int)hal_capture_vector(ch), (int)ch, false,
                                         capture_trampoline, slot);
    return slot->source < 0 ? -1 : 0;
}

void hal_capture_enable(hal_capture_channel_t ch, uint8_t enable)
{
    if ((unsigned)ch >= HAL_CAPTURE_COUNT)
        return;
    int b = posix_board_current();
    posix_capture_slot_t *slot = &posix_board_state(b)->capture[ch];
    if (slot->cb != NULL)
        posix_source_enable(b, slot->source, enable != 0);
}

void posix_capture_raise(int board, hal_capture_channel_t ch, uint16_t count, uint8_t rising)
{
    if ((unsigned)ch >= HAL_CAPTURE_COUNT)
        return;
    posix_capture_slot_t *slot = &posix_board_state(board)->capture[ch];
    if (slot->cb == NULL)
        return;
    if (posix_source_pending(board, slot->source)) {
        slot->overflows++; /* COV: the earlier capture is kept, this one is lost */
        return;
    }
    slot->count = count;
    slot->rising = rising;
    posix_source_raise(board, slot->source);
}

uint16_t hal_capture_overflows(hal_capture_channel_t ch)
{
    return (uint16_t)posix_capture_overflows(posix_board_current(), ch);
}

uint32_t posix_capture_overflows(int board, hal_capture_channel_t ch)
{
    if ((unsigned)ch >= HAL_CAPTURE_COUNT)
        return 0;
    return posix_board_state(board)->capture[ch].overflows;
}
