/*
 * gnav_arith_k.c - the C twins of the groundnav kernels (gnav_arith.h, docs/kernels.md;
 * msp430/gnav_arith.S holds the same functions, built instead of this file there).
 */
#include "gnav_internal.h"
#include "gnav_tables.h"
#include "hal/preempt.h"

void gnav_add64x2(int64_t *xy, const int32_t *v)
{
    xy[0] = (int64_t)((uint64_t)xy[0] + (uint64_t)(int64_t)v[0]);
    HAL_PREEMPT_POINT(); /* the harness may land an interrupt between the two */
    xy[1] = (int64_t)((uint64_t)xy[1] + (uint64_t)(int64_t)v[1]);
}

void gnav_sub64x2(int64_t *xy, const int32_t *v)
{
    xy[0] = (int64_t)((uint64_t)xy[0] - (uint64_t)(int64_t)v[0]);
    HAL_PREEMPT_POINT();
    xy[1] = (int64_t)((uint64_t)xy[1] - (uint64_t)(int64_t)v[1]);
}

/*
 * Front-wheel deficit of a one-step arc over m >= n0 pulses, E(m) = m - sqrt(m^2 - M^2),
 * pulses Q16. Table below tab_end; beyond it x = M / m <= 1/2 and E = M * g(x), with the
 * x (Q16) and g (Q17) it used stored for the deficit per pulse rho = E / m = x * g. The
 * reciprocal of m comes from a table of 1/m for m < 1024, of m rounded to 2^4, 2^8 or 2^12
 * beyond (tier t: x = round(M_q11 recip / 2^(16 + 4 t))).
 */
/* E(m) itself (the twin's reference steps). */
static int32_t deficit(gnav_t *g, uint32_t m)
{
    if (m < g->tab_end) {
        uint16_t i = (uint16_t)(m - g->n0);
        g->rho_p = (uint16_t)g->tab_rho[i];
        g->rho_due = 0;
        return g->tab_e[i];
    }
    uint16_t x = 0;
    if (m < ((uint32_t)GNAV_RECIP_HI << 12)) {
        uint16_t i, tier; /* i = round(m / 2^(4 tier)) */
        uint16_t mh = (uint16_t)(m >> 16), ml = (uint16_t)m;
        if (m < GNAV_RECIP_HI) {
            i = ml;
            tier = 0;
        } else if (m < ((uint32_t)GNAV_RECIP_HI << 4)) {
            i = (uint16_t)((uint16_t)(ml + 8u) >> 4);
            tier = 1;
        } else {
            uint32_t v = m + (m < ((uint32_t)GNAV_RECIP_HI << 8) ? 128u : 2048u);
            uint16_t vh = (uint16_t)(v >> 16), vl = (uint16_t)v;
            (void)mh;
            if (m < ((uint32_t)GNAV_RECIP_HI << 8)) {
                i = (uint16_t)((uint16_t)(vh << 8) | (vl >> 8));
                tier = 2;
            } else {
                i = (uint16_t)((uint16_t)(vh << 4) | (vl >> 12));
                tier = 3;
            }
        }
        if (i >= GNAV_RECIP_HI)
            i = GNAV_RECIP_HI - 1u;
        uint32_t p = gnav_umul16(g->m_q11, gnav_recip[i - GNAV_RECIP_LO]);
        /* round at bit 16 + 4 tier: the high word of p + 2^(15 + 4 tier), then >> 4 tier */
        static const uint32_t half[4] = {0x8000u, 0x80000u, 0x800000u, 0x8000000u};
        x = (uint16_t)((p + half[tier]) >> 16);
        if (tier & 2u)
            x = (uint16_t)(x >> 8);
        if (tier & 1u)
            x = (uint16_t)(x >> 4);
    }
    uint16_t i = (uint16_t)(x >> 8);
    uint16_t gl = gnav_g[i];
    uint32_t d = gnav_umul16((uint16_t)(gnav_g[i + 1u] - gl), x & 0xFFu) + 128u; /* < 2^24 */
    uint16_t gv = (uint16_t)(gl + (uint16_t)((uint16_t)((uint16_t)(d >> 16) << 8) |
                                             (uint16_t)((uint16_t)d >> 8)));
    /* E = M * g: m_q16 * g_q17 / 2^17, rounded */
    uint32_t a = gnav_umul16((uint16_t)(g->m_q16 >> 16), gv);
    uint32_t b = gnav_umul16((uint16_t)g->m_q16, gv);
    uint32_t hi = a + (uint16_t)(b >> 16);
    g->x_p = x;
    g->g_p = gv;
    g->rho_due = 1;
    return gnav_half_up(hi);
}

/* m = |n|, the pulses since P, and what the provisional pose assumed of them: min(m, n_p)
 * pulses of rho_p, pulses Q16 (2 rho_p nc). */
static int32_t provisional(const gnav_t *g, uint32_t *m)
{
    int32_t n = (int32_t)(((uint32_t)(uint16_t)g->n_hi << 16) | g->n_lo);
    *m = n < 0 ? 0u - (uint32_t)n : (uint32_t)n;
    uint16_t nc = *m < g->n_p ? (uint16_t)*m : g->n_p;
    return (int32_t)gnav_umul16(nc, (uint16_t)(g->rho_p << 1));
}

/* The closing pulse's step and the correction delta = dprov - E of the provisional position,
 * negated backwards, in Q10 pulses, d10 = round(delta / 64) saturated; its rounding is
 * carried to the next closing (resid = delta - 64 d10). (The new closing point P is taken
 * at the next pulse: gnav_dr.c.) */
static void apply(gnav_t *g, int32_t delta, const int32_t *step)
{
    if (g->n_hi < 0)
        delta = -delta;
    delta += g->resid;
    uint32_t v = (uint32_t)delta + 32u;
    int16_t vh = (int16_t)(v >> 16);
    uint16_t vl = (uint16_t)v;
    int16_t d10;
    if (vh > -32 && vh < 32) { /* -2^21 + 2^16 <= delta + 32 < 2^21: no saturation */
        d10 = (int16_t)((uint16_t)((uint16_t)vh << 10) | (uint16_t)(vl >> 6));
        g->resid = (int32_t)(vl & 63u) - 32;
    } else {
        int32_t q = (int32_t)v >> 6;
        d10 = (int16_t)(q > 32767 ? 32767 : (q < -32767 ? -32767 : q));
        g->resid = delta - (int32_t)d10 * 64;
    }
    int32_t px = gnav_smul16(d10, g->d15_c), py = gnav_smul16(d10, g->d15_s); /* Q25 */
    if (g->reverse) { /* |step| < 2^26, |p| < 2^30: the sums fit */
        px -= step[0];
        py -= step[1];
    } else {
        px += step[0];
        py += step[1];
    }
    g->x = (int64_t)((uint64_t)g->x + (uint64_t)(int64_t)px);
    HAL_PREEMPT_POINT();
    g->y = (int64_t)((uint64_t)g->y + (uint64_t)(int64_t)py);
}

void gnav_chord(gnav_t *g, int32_t e, const int32_t *step)
{
    uint32_t m;
    apply(g, provisional(g, &m) - e, step);
}

void gnav_arc(gnav_t *g, uint16_t half, const int32_t *step)
{
    uint32_t m;
    int32_t dprov = provisional(g, &m), e;
    if (half) /* half a step: E(2 m) / 2, rounded up (2 m saturating at 2^31) */
        e = gnav_half_up((uint32_t)deficit(g, m >= 0x40000000u ? 0x80000000u : m * 2u));
    else
        e = deficit(g, m);
    apply(g, dprov - e, step);
}
