/*
 * gnav_dr.c - dead reckoning: the dl handler (gnav.h, docs/groundnav.md). At every odometer
 * pulse the step of the current interval (curved for its first n_p pulses, straight beyond)
 * is added to the provisional position; a gyro edge since the last pulse closes the arc
 * (gnav_arc.c); the travel without a fix counts down; the pose is published for the readers.
 * The 64-bit accumulation is a kernel (gnav_arith.h).
 */
#include "gnav_internal.h"
#include "hal/preempt.h"

/* rho (Q15, >= 0) * v (|v| < 2^31), same format as v, rounded. */
static int32_t mul_rho(int16_t rho, int32_t v)
{
    int16_t vh = (int16_t)(v >> 16);
    uint16_t vl = (uint16_t)v;
    int32_t a = gnav_smul16(rho, vh);
    uint32_t b = gnav_umul16((uint16_t)rho, vl);
    return a * 2 + (int32_t)((b + (1u << 14)) >> 15);
}

/* Fill the free slot, then flip: a reader (the NMI included) only ever sees complete slots. */
void gnav_publish(gnav_t *g)
{
    uint16_t s = g->pub_seq;
    gnav_pub_t *w = (s & 1u) ? &g->pub[0] : &g->pub[1];
    w->x = g->x;
    HAL_PREEMPT_POINT();
    w->y = g->y;
    HAL_PREEMPT_POINT();
    w->heading = g->heading;
    w->k = g->pending ? GNAV_K_EDGE : g->nq;
    w->rate = g->hrate;
    w->ival = g->ival;
    w->dir = g->hdir;
    HAL_PREEMPT_POINT();
    g->pub_seq = (uint16_t)(s + 1u);
}

/* Deferred from the closing to the next pulse: the deficit per pulse and the curved step.
 * (Not inlined: the plain pulse would pay for its registers.) */
__attribute__((noinline)) void gnav_finish_interval(gnav_t *g)
{
    if (g->rho_due) {
        uint32_t r = (gnav_umul16(g->x_p, g->g_p) + 0x20000u) >> 18; /* Q33 -> Q15 */
        g->rho_p = (uint16_t)(r > 32767u ? 32767u : r);
        g->rho_due = 0;
    }
    int16_t rho = (int16_t)g->rho_p;
    g->inc[0][0] = g->inc[1][0] - mul_rho(rho, g->inc[1][0]);
    HAL_PREEMPT_POINT();
    g->inc[0][1] = g->inc[1][1] - mul_rho(rho, g->inc[1][1]);
    g->dc_due = 0;
}

void gnav_on_delta_l(void *arg)
{
    gnav_t *g = arg;
    if (g->dc_due) {
        /* the closing point P of the last closing: the position it left */
        if (g->p_due) {
            g->xp = g->x;
            g->yp = g->y;
            g->p_due = 0;
        }
        /* an interval that closes at its first pulse has no curved part (its step is
         * replaced by the closing anyway); otherwise set the curved step up now */
        if (g->pending)
            g->n_p = 0;
        else
            gnav_finish_interval(g);
    }
    /* the step: curved for the first n_p pulses away from P, straight beyond (moving back,
     * the same steps in reverse order, so the pose is a function of n alone) */
    int16_t q = g->nq;
    uint16_t m = (uint16_t)q, lo = g->n_lo;
    if (!g->reverse) {
        if (q < 0) /* m = |q + 1/2| - 1/2: the pulse's distance from P */
            m = (uint16_t)~m;
        if (q < 32767)
            g->nq = (int16_t)(q + 1);
        g->n_lo = (uint16_t)(lo + 1u);
        if (lo == 0xFFFFu)
            g->n_hi++;
    } else {
        if (q > 0)
            m = (uint16_t)(m - 1u);
        else
            m = (uint16_t)(0u - m);
        if (q > -32767)
            g->nq = (int16_t)(q - 1);
        g->n_lo = (uint16_t)(lo - 1u);
        if (lo == 0u)
            g->n_hi--;
    }
    const int32_t *step = m >= g->n_p ? g->inc[1] : g->inc[0];
    if (g->pending) /* the closing takes the step along with its correction */
        gnav_close_arc(g, step);
    else if (!g->reverse)
        gnav_add64x2(&g->x, step);
    else
        gnav_sub64x2(&g->x, step);
    HAL_PREEMPT_POINT();
    /* travel without a fix: stop_hi * 2^16 + stop_lo pulses left (stop_lo 0 meaning 2^16) */
    if (--g->stop_lo == 0u && g->stop_armed) {
        if (g->stop_hi == 0u) {
            g->stop_armed = 0;
            g->stop = 1;
            if (g->stop_fn)
                g->stop_fn(g->stop_ctx);
        } else {
            g->stop_hi--;
        }
    }
    gnav_publish(g);
}
