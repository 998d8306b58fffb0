/*
 * drive_port.c - hal/drive_port.h on the harness: the writes of each board are recorded
 * (hal_posix/drive_port_posix.h) instead of reaching pins.
 */
#include <string.h>

#include "hal/drive_port.h"
#include "hal_posix/drive_port_posix.h"
#include "hal_posix/harness.h"
#include "harness_internal.h"

void hal_drive_port_init(void)
{
    (void)posix_board_current();
}

void hal_drive_port_write(hal_drive_reg_t reg, uint8_t value)
{
    if ((unsigned)reg >= HAL_DRIVE_REG_COUNT)
        return;
    int b = posix_board_current();
    posix_drive_port_state_t *st = &posix_board_state(b)->drive_port;
    posix_drive_write_t w = {posix_now_ns(), (uint8_t)reg, value};
    if (st->count < POSIX_DRIVE_PORT_LOG)
        st->log[st->count] = w;
    st->count++;
    st->last[reg] = value;
    if (st->sink)
        st->sink(st->ctx, b, &w);
}

void posix_drive_port_set_sink(int board, posix_drive_sink_fn fn, void *ctx)
{
    posix_drive_port_state_t *st = &posix_board_state(board)->drive_port;
    st->sink = fn;
    st->ctx = ctx;
}

uint32_t posix_drive_port_count(int board)
{
    return posix_board_state(board)->drive_port.count;
}

size_t posix_drive_port_log(int board, posix_drive_write_t *out, size_t max)
{
    const posix_drive_port_state_t *st = &posix_board_state(board)->drive_port;
    size_t n = st->count < POSIX_DRIVE_PORT_LOG ? st->count : POSIX_DRIVE_PORT_LOG;
    if (n > max)
        n = max;
    memcpy(out, st->log, n * sizeof *out);
    return n;
}

void posix_drive_port_clear(int board)
{
    posix_drive_port_state_t *st = &posix_board_state(board)->drive_port;
    st->count = 0;
    memset(st->last, 0, sizeof st->last);
}

uint8_t posix_drive_port_value(int board, hal_drive_reg_t reg)
{
    if ((unsigned)reg >= HAL_DRIVE_REG_COUNT)
        return 0;
    return posix_board_state(board)->drive_port.last[reg];
}
