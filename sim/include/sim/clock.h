/*
 * clock.h - the simulator's view of the harness clock: seconds (double) outside, the harness's
 * nanoseconds inside, and scheduling that never lands in the past.
 */
#ifndef SIM_CLOCK_H
#define SIM_CLOCK_H

#include <stdint.h>

#include "hal_posix/harness.h"

/** Nanoseconds of @p t seconds (t >= 0), rounded. */
static inline uint64_t sim_clock_ns(double t)
{
    return (uint64_t)(t * 1e9 + 0.5);
}

/** Seconds of @p ns nanoseconds. */
static inline double sim_clock_s(uint64_t ns)
{
    return (double)ns * 1e-9;
}

/** Simulated time now, s. */
static inline double sim_clock_now(void)
{
    return sim_clock_s(posix_now_ns());
}

/**
 * Schedule @p fn at @p t seconds, or 1 ns from now when @p t is not in the future (so an
 * event never runs twice at one instant). Returns the harness's event id (0: queue full).
 */
static inline uint64_t sim_clock_schedule(double t, posix_event_fn fn, void *ctx)
{
    uint64_t ns = sim_clock_ns(t), now = posix_now_ns();
    return posix_schedule(ns > now ? ns : now + 1, fn, ctx);
}

/** Cancel the event @p *id if one is queued, and clear it. */
static inline void sim_clock_cancel(uint64_t *id)
{
    if (*id)
        posix_cancel(*id);
    *id = 0;
}

#endif
