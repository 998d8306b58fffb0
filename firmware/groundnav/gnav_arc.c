/*
 * gnav_arc.c - closing the arc between two gyro edges at the first pulse after the second
 * (seed situations 1 and 3; docs/groundnav.md): the deficit E(m) of the interval's pulses, the
 * correction of the provisional position, the next interval set up.
 */
#include "gnav_internal.h"
#include "gnav_tables.h"
#include "hal/preempt.h"

/*
 * Front-wheel deficit of a one-step arc over m >= n0 pulses, E(m) = m - sqrt(m^2 - M^2),
 * pulses Q16. Table below tab_end; beyond it x = M / m <= 1/2 and E = M * g(x), with the
 * x (Q16) and g (Q17) it used stored for the deficit per pulse rho = E / m = x * g.
 */
static int32_t deficit(gnav_t *g, uint32_t m)
{
    if (m < g->tab_end) {
        uint16_t i = (uint16_t)(m - g->n0);
        g->rho_p = (uint16_t)g->tab_rho[i];
        g->rho_due = 0;
        return g->tab_e[i];
    }
    uint32_t p;
    uint16_t x;
    if (m < GNAV_RECIP_HI) {
        p = gnav_umul16(g->m_q11, gnav_recip[m - GNAV_RECIP_LO]);
        x = (uint16_t)((p + 0x8000u) >> 16);
    } else if (m < ((uint32_t)GNAV_RECIP_HI << 4)) {
        uint16_t i = (uint16_t)((m + 8u) >> 4);
        p = gnav_umul16(g->m_q11,
                        gnav_recip[(i < GNAV_RECIP_HI ? i : GNAV_RECIP_HI - 1u) - GNAV_RECIP_LO]);
        x = (uint16_t)((p + 0x80000u) >> 20);
    } else if (m < ((uint32_t)GNAV_RECIP_HI << 8)) {
        uint16_t i = (uint16_t)((m + 128u) >> 8);
        p = gnav_umul16(g->m_q11,
                        gnav_recip[(i < GNAV_RECIP_HI ? i : GNAV_RECIP_HI - 1u) - GNAV_RECIP_LO]);
        x = (uint16_t)((p + 0x800000u) >> 24);
    } else if (m < ((uint32_t)GNAV_RECIP_HI << 12)) {
        uint16_t i = (uint16_t)((m + 2048u) >> 12);
        p = gnav_umul16(g->m_q11,
                        gnav_recip[(i < GNAV_RECIP_HI ? i : GNAV_RECIP_HI - 1u) - GNAV_RECIP_LO]);
        x = (uint16_t)((p + 0x8000000u) >> 28);
    } else {
        x = 0;
    }
    uint16_t i = (uint16_t)(x >> 8);
    uint16_t gl = gnav_g[i];
    uint16_t gv =
        (uint16_t)(gl +
                   (uint16_t)((gnav_umul16((uint16_t)(gnav_g[i + 1u] - gl), x & 0xFFu) + 128u) >>
                              8));
    /* E = M * g: m_q16 * g_q17 / 2^17, rounded */
    uint32_t a = gnav_umul16((uint16_t)(g->m_q16 >> 16), gv);
    uint32_t b = gnav_umul16((uint16_t)g->m_q16, gv);
    uint32_t hi = a + (b >> 16);
    g->x_p = x;
    g->g_p = gv;
    g->rho_due = 1;
    return (int32_t)((hi + 1u) >> 1);
}

static int32_t pulses_since_p(const gnav_t *g)
{
    return (int32_t)(((uint32_t)(uint16_t)g->n_hi << 16) | g->n_lo);
}

/*
 * The gyro left the interval's cell: close the arc at this pulse (seed situations 1 and 3).
 */
void gnav_close_arc(gnav_t *g)
{
    int32_t n = pulses_since_p(g);
    uint32_t m = n < 0 ? (uint32_t)(-n) : (uint32_t)n;
    int16_t k = (int16_t)(g->h_first - g->h_p);
    if (k < 0)
        k = (int16_t)-k;
    /* what the provisional pose assumed: min(m, n_p) pulses of rho_p */
    uint16_t nc = m < g->n_p ? (uint16_t)m : g->n_p;
    int32_t dprov = (int32_t)(gnav_umul16(nc, g->rho_p) << 1); /* Q15 -> Q16 */
    uint16_t np = m > 32000u ? 32000u : (uint16_t)m;
    int32_t e = 0;
    uint8_t sit1 = 0;
    if (k == 0) {
        /* back through the same threshold: the turn reversed inside one cell (an S-curve's
         * inflection). The last arc's curvature went on, over at most 2 n_p pulses (an
         * excursion below one step); a longer interval means the vehicle had straightened. */
        uint16_t n2 = (uint16_t)(2u * g->n_p);
        e = (int32_t)(gnav_umul16(m < n2 ? (uint16_t)m : n2, g->rho_p) << 1);
        if (m <= n2) {
            np = g->n_p; /* the curvature goes on */
        } else {
            np = 0;
            g->rho_p = 0;
        }
        g->rho_due = 0;
        g->closings[2]++;
    } else {
        uint32_t me = m;
        if (k == 1) /* first edge after init: half a step from the cell centre */
            me = m >= 0x40000000u ? 0x80000000u : m * 2u;
        if (me < g->n0) {
            sit1 = 1;
        } else {
            e = deficit(g, me);
            if (k == 1)
                e = (e + 1) >> 1;
            g->closings[1]++;
        }
    }
    if (sit1) {
        /* too few pulses for the heading change: the rear axle did not move */
        g->x = g->xp;
        HAL_PREEMPT_POINT();
        g->y = g->yp;
        g->rho_p = 32767;
        g->rho_due = 0;
        g->closings[0]++;
    } else {
        /* chord = m - E along the cell; the provisional pose assumed m - dprov. The
         * correction goes in Q10 pulses; its rounding is carried to the next closing. */
        int32_t delta = dprov - e;
        if (n < 0)
            delta = -delta;
        delta += g->resid;
        int32_t d10 = (delta + 32) >> 6;
        if (d10 > 32767)
            d10 = 32767;
        else if (d10 < -32767)
            d10 = -32767;
        g->resid = delta - d10 * 64;
        gnav_mac64(&g->x, (int16_t)d10, g->d15_c);
        HAL_PREEMPT_POINT();
        gnav_mac64(&g->y, (int16_t)d10, g->d15_s);
        HAL_PREEMPT_POINT();
        g->xp = g->x;
        g->yp = g->y;
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
