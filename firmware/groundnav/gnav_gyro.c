/*
 * gnav_gyro.c - the gyro handlers (gnav.h): the heading moved one step up or down; the new
 * cell's direction (the one sin/cos per edge), the interval that ended remembered for the
 * latches, the arc's closing left to the next pulse.
 */
#include "gnav_internal.h"
#include "hal/preempt.h"

static void gyro_edge(gnav_t *g, int8_t up)
{
    uint16_t h;
    if (up > 0) {
        uint32_t f = (uint32_t)g->hd_frac + g->step_frac;
        g->hd_frac = (uint16_t)f;
        g->hd += g->step_whole + (f >> 16);
        g->cell++;
        h = (uint16_t)(2u * g->cell - 1u);
    } else {
        uint16_t f = g->hd_frac;
        g->hd_frac = (uint16_t)(f - g->step_frac);
        g->hd -= g->step_whole + (f < g->step_frac ? 1u : 0u);
        g->cell--;
        h = (uint16_t)(2u * g->cell + 1u);
    }
    HAL_PREEMPT_POINT();
    /* The interval that ends here (none of its pulses when an edge already came since the last
     * pulse): remembered for the latches taken in it; a one-step interval gives the rate of
     * the next unless it outlasted the rate it entered at (the turn changed in it); a short
     * excursion back through its entry threshold leaves at the rate it went in. */
    int16_t n = g->pending ? 0 : g->nq;
    uint16_t a = (uint16_t)(n < 0 ? 1 - n : n + 1); /* 1 .. 32768 */
    g->ring[g->ival & (GNAV_RING_N - 1u)] =
        (uint16_t)((a > 0x7FFFu ? 0x7FFFu : a) | (up > 0 ? 0x8000u : 0u));
    if (g->hdir == up)
        g->hrate = g->hrate == 0u || !gnav_overdue(a, g->hrate, false) ? a : 0u;
    else if (g->hdir == 0 || gnav_overdue(a, g->hrate, true))
        g->hrate = 0u;
    g->hdir = up;
    g->ival++;
    if (!g->pending) {
        g->h_first = h;
        g->pending = 1;
    }
    g->h_last = h;
    g->heading = g->hd + (g->hd_frac >> 15);
    fx_q30_t s, c;
    fx_sincos(g->heading, &s, &c);
    g->nxt_c = gnav_q30_to_q25(c);
    g->nxt_s = gnav_q30_to_q25(s);
    HAL_PREEMPT_POINT();
    g->n15_c = gnav_q30_to_q15(c);
    g->n15_s = gnav_q30_to_q15(s);
    g->version++;
    gnav_publish(g);
}

void gnav_on_gyro_up(void *arg)
{
    gyro_edge(arg, 1);
}

void gnav_on_gyro_down(void *arg)
{
    gyro_edge(arg, -1);
}
