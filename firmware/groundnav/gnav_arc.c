/*
 * gnav_arc.c - closing the arc between two gyro edges at the first pulse after the second
 * (seed situations 1 and 3; docs/groundnav.md): which situation, the deficit E(m) of the
 * interval's pulses and the chord's correction of the provisional position (the kernels
 * gnav_arc and gnav_chord), the next interval set up.
 */
#include "gnav_internal.h"
#include "hal/preempt.h"

/*
 * The gyro left the interval's cell: close the arc at this pulse (seed situations 1 and 3),
 * whose own step (@p step, added or subtracted as the travel goes) the chord's correction
 * takes along. m = |n| pulses since P, and |h_first - h_p| the half-steps from P to the first
 * edge: 0 (back through the same threshold), 1 (the first edge after init: half a step from
 * the cell centre) or 2. The provisional pose assumed min(m, n_p) pulses of rho_p (Q15;
 * 2 rho in Q16).
 */
void gnav_close_arc(gnav_t *g, const int32_t *step)
{
    uint16_t mlo = g->n_lo, mhi = (uint16_t)g->n_hi; /* m = |n| */
    if ((int16_t)mhi < 0) {
        mhi = (uint16_t)~mhi;
        if (mlo == 0u)
            mhi++;
        mlo = (uint16_t)(0u - mlo);
    }
    bool small = mhi == 0u;
    uint16_t dh = (uint16_t)(g->h_first - g->h_p);
    bool half = dh == 1u || dh == 0xFFFFu;
    uint16_t n_p = g->n_p;
    uint16_t np = small && mlo < 32000u ? mlo : 32000u; /* the next interval's curved part */
    if (dh == 0u) {
        /* back through the same threshold: the turn reversed inside one cell (an S-curve's
         * inflection). The last arc's curvature went on, over at most 2 n_p pulses (an
         * excursion below one step); a longer interval means the vehicle had straightened. */
        uint16_t n2 = (uint16_t)(2u * n_p);
        bool within = small && mlo <= n2;
        gnav_chord(g, (int32_t)gnav_umul16(within ? mlo : n2, (uint16_t)(g->rho_p << 1)), step);
        if (within) {
            np = n_p; /* the curvature goes on */
        } else {
            np = 0;
            g->rho_p = 0;
        }
        g->rho_due = 0;
        g->closings[2]++;
        g->p_due = 1;
    } else if (small && mlo < (half ? (uint16_t)((g->n0 + 1u) >> 1) : g->n0)) {
        /* too few pulses for the heading change (2 m or m below n0): the rear axle did not
         * move, this pulse's step included */
        g->x = g->xp;
        HAL_PREEMPT_POINT();
        g->y = g->yp;
        g->rho_p = 32767;
        g->rho_due = 0;
        g->closings[0]++;
    } else {
        g->closings[1]++;
        gnav_arc(g, half, step);
        g->p_due = 1;
    }
    HAL_PREEMPT_POINT();
    g->n_p = np;
    if (g->h_last != g->h_first) {
        /* more edges inside this pulse: zero-length intervals (situation 1) */
        g->n_p = 0;
        g->rho_due = 0;
        g->closings[3]++;
    }
    g->h_p = g->h_last;
    g->n_lo = 0;
    g->n_hi = 0;
    g->nq = 0;
    g->cell_int = g->cell;
    g->inc[1][0] = g->nxt_c;
    g->inc[1][1] = g->nxt_s;
    g->d15_c = g->n15_c;
    g->d15_s = g->n15_s;
    g->pending = 0;
    g->dc_due = 1;
    g->version++;
}
