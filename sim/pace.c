/*
 * pace.c - live runs: the run loop waits for the wall clock (see pace.h).
 */
#include "sim/pace.h"

#include <errno.h>
#include <math.h>

#define NS_PER_S 1000000000ull

int sim_pace_start(sim_pace_t *p, double factor, uint64_t t0_ns)
{
    p->factor = 0;
    p->t0_ns = t0_ns;
    p->next_ns = t0_ns;
    p->sleeps = 0;
    p->step_ns = 0;
    if (!(factor >= 0 && factor <= SIM_PACE_MAX_FACTOR)) /* NaN fails both */
        return -1;
    p->factor = factor;
    p->step_ns = (uint64_t)(factor * 1e6); /* one millisecond of wall time */
    if (p->step_ns == 0)
        p->step_ns = 1;
    clock_gettime(CLOCK_MONOTONIC, &p->w0);
    return 0;
}

void sim_pace_wait(sim_pace_t *p, uint64_t sim_ns)
{
    if (p->factor <= 0 || sim_ns < p->next_ns)
        return;
    p->next_ns = sim_ns + p->step_ns;
    double wall_s = (double)(sim_ns - p->t0_ns) / 1e9 / p->factor;
    uint64_t due = (uint64_t)p->w0.tv_sec * NS_PER_S + (uint64_t)p->w0.tv_nsec +
                   (uint64_t)llround(wall_s * 1e9);
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    if ((uint64_t)now.tv_sec * NS_PER_S + (uint64_t)now.tv_nsec >= due)
        return; /* behind the wall clock: go on at full speed */
    struct timespec until = {(time_t)(due / NS_PER_S), (long)(due % NS_PER_S)};
    p->sleeps++;
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, NULL) == EINTR)
        ;
}
