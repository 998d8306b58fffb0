/*
 * clock_signal.c - hal/clock.h and hal/signal.h on the harness: a per-board 1 ms tick on the
 * TIMERB0 vector, scheduled on simulated time, and output lines routed to another board's
 * edge line.
 */
#include <stdbool.h>

#include "hal/clock.h"
#include "hal/cpu.h"
#include "hal/pinmap.h"
#include "hal/signal.h"
#include "hal_posix/harness.h"
#include "harness_internal.h"

#define TICK_NS 1000000ull

typedef struct {
    int board;
    int source;
    bool started;
    uint32_t ms;
} tick_t;

static tick_t ticks[POSIX_MAX_BOARDS];

static struct {
    bool connected;
    int to_board;
    hal_edge_line_t line;
} routes[POSIX_MAX_BOARDS][HAL_SIGNAL_COUNT];

void posix_clock_signal_reset(void)
{
    for (int b = 0; b < POSIX_MAX_BOARDS; b++) {
        ticks[b].started = false;
        ticks[b].ms = 0;
        for (int s = 0; s < HAL_SIGNAL_COUNT; s++)
            routes[b][s].connected = false;
    }
}

static void tick_isr(void *ctx)
{
    tick_t *t = ctx;
    t->ms++;
    hal_cpu_wake();
}

static void tick_event(void *ctx, uint64_t now)
{
    tick_t *t = ctx;
    if (!t->started)
        return;
    posix_source_raise(t->board, t->source);
    posix_schedule(now + TICK_NS, tick_event, t);
}

void hal_clock_init(void)
{
    int b = posix_board_current();
    tick_t *t = &ticks[b];
    if (t->started)
        return;
    t->board = b;
    t->ms = 0;
    t->source = posix_source_register(b, HAL_VEC_TIMERB0, 0, false, tick_isr, t);
    t->started = t->source >= 0;
    if (t->started)
        posix_schedule(posix_now_ns() + TICK_NS, tick_event, t);
}

uint32_t hal_clock_ms(void)
{
    return ticks[posix_board_current()].ms;
}

void posix_signal_connect(int from_board, hal_signal_t s, int to_board, hal_edge_line_t line)
{
    if ((unsigned)s >= HAL_SIGNAL_COUNT)
        return;
    routes[from_board][s].connected = true;
    routes[from_board][s].to_board = to_board;
    routes[from_board][s].line = line;
}

void hal_signal_init(hal_signal_t s)
{
    (void)s;
}

void hal_signal_pulse(hal_signal_t s)
{
    if ((unsigned)s >= HAL_SIGNAL_COUNT)
        return;
    int b = posix_board_current();
    if (routes[b][s].connected)
        posix_edge_raise(routes[b][s].to_board, routes[b][s].line);
}
