/*
 * clock_signal.c - hal/clock.h and hal/signal.h on the harness: a per-board 1 ms tick on the
 * TIMERB0 vector, scheduled on simulated time (every millisecond, or tickless: at the main
 * loop's deadlines only), and output lines routed to another board's edge line.
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
    bool tickless;
    uint64_t t0_ns;   /* when the clock started: its count is the milliseconds since */
    uint64_t wake_id; /* tickless: the queued tick, 0 if none */
    uint32_t wake_ms; /* and its millisecond */
} tick_t;

static tick_t ticks[POSIX_MAX_BOARDS];
static bool tickless;

static struct {
    bool connected;
    int to_board;
    hal_edge_line_t line;
} routes[POSIX_MAX_BOARDS][HAL_SIGNAL_COUNT];

void posix_clock_signal_reset(void)
{
    for (int b = 0; b < POSIX_MAX_BOARDS; b++) {
        ticks[b] = (tick_t){0};
        for (int s = 0; s < HAL_SIGNAL_COUNT; s++)
            routes[b][s].connected = false;
    }
    tickless = false;
}

void posix_clock_set_tickless(bool on)
{
    tickless = on;
}

/* The count: whole milliseconds since the start (a function of time, so that both ways of
 * ticking read the same count at every instant, the boundary's own included). */
static uint32_t count_of(const tick_t *t)
{
    return t->started ? (uint32_t)((posix_now_ns() - t->t0_ns) / TICK_NS) : 0u;
}

uint32_t posix_clock_ticks(int board)
{
    return board >= 0 && board < POSIX_MAX_BOARDS ? count_of(&ticks[board]) : 0u;
}

static void tick_isr(void *ctx)
{
    (void)ctx;
    hal_cpu_wake();
}

static void tick_event(void *ctx, uint64_t now)
{
    tick_t *t = ctx;
    posix_source_raise(t->board, t->source);
    posix_schedule(now + TICK_NS, tick_event, t);
}

/* Tickless: the tick that a main loop's deadline asked for. */
static void wake_event(void *ctx, uint64_t now)
{
    tick_t *t = ctx;
    (void)now;
    t->wake_id = 0;
    posix_source_raise(t->board, t->source);
}

void hal_clock_wake_at(uint32_t ms)
{
    tick_t *t = &ticks[posix_board_current()];
    if (!t->started || !t->tickless)
        return; /* ticked: the next tick wakes the main loop anyway */
    uint32_t now = count_of(t);
    if ((int32_t)(ms - now) <= 0)
        ms = now + 1u;
    if (t->wake_id != 0) {
        if ((int32_t)(ms - t->wake_ms) >= 0)
            return; /* an earlier tick is queued already */
        posix_cancel(t->wake_id);
    }
    t->wake_ms = ms;
    /* ms counts from the start modulo 2^32: the tick falls @p ms - now milliseconds ahead */
    uint64_t at = posix_now_ns() - (posix_now_ns() - t->t0_ns) % TICK_NS +
                  (uint64_t)(uint32_t)(ms - now) * TICK_NS;
    t->wake_id = posix_schedule(at, wake_event, t);
}

void hal_clock_init(void)
{
    int b = posix_board_current();
    tick_t *t = &ticks[b];
    if (t->started)
        return;
    t->board = b;
    t->t0_ns = posix_now_ns();
    t->tickless = tickless;
    t->wake_id = 0;
    t->source = posix_source_register(b, HAL_VEC_TIMERB0, 0, false, tick_isr, t);
    t->started = t->source >= 0;
    if (t->started && !t->tickless)
        posix_schedule(t->t0_ns + TICK_NS, tick_event, t);
}

uint32_t hal_clock_ms(void)
{
    return count_of(&ticks[posix_board_current()]);
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
