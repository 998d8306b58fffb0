/*
 * gnav.c - ground navigation of the nav board (gnav.h; docs/groundnav.md).
 *
 * Formats inside:
 *  - positions: int64 in odometer pulses, Q25 (the dl handler adds the cell's unit vector in
 *    Q25 per pulse, so a straight run accumulates exactly n times the same step: the only
 *    drift is the step's rounding, 2^-26 pulse per pulse, 1.5 um per 100 m);
 *  - deficits (E, D, delta): int32 pulses Q16, applied in Q10 with the rounding carried to
 *    the next closing (so it never accumulates); deficit per pulse rho: Q15;
 *  - heading of the current gyro cell: a binary angle with 16 more fraction bits (the step is
 *    not a whole binary angle: 0.25 degrees is 2982616.18 LSB), published rounded;
 *  - latches and frame corrections: int32 pulses Q4 (8 um, +-34 km);
 *  - the outside world (gnav_pose_t): metres Q15.16.
 *
 * The dl handler uses 16 x 16 products only (the MSP430's multiplier); the one sin/cos per
 * gyro edge is in the gyro handler, which knows the new cell first. On the MSP430 the dl
 * handler, the arc closing and the 64-bit accumulations are assembly (the .S files in msp430/)
 * doing the very steps of the C here (GNAV_ASM leaves the C out there).
 */
#include "groundnav/gnav.h"

#include <stddef.h>

#include "gnav_arith.h"
#include "gnav_tables.h"
#include "hal/edge.h"
#include "hal/irq.h"
#include "hal/preempt.h"

#ifdef GNAV_ASM
/* msp430/gnav_dl.S addresses these fields by offset. */
#define GNAV_AT(field, off) _Static_assert(offsetof(gnav_t, field) == (off), #field)
GNAV_AT(x, 0);
GNAV_AT(y, 8);
GNAV_AT(xp, 16);
GNAV_AT(yp, 24);
GNAV_AT(inc, 32);
GNAV_AT(n_lo, 48);
GNAV_AT(n_hi, 50);
GNAV_AT(nq, 52);
GNAV_AT(n_p, 54);
GNAV_AT(rho_p, 56);
GNAV_AT(x_p, 58);
GNAV_AT(g_p, 60);
GNAV_AT(resid, 62);
GNAV_AT(d15_c, 66);
GNAV_AT(d15_s, 68);
GNAV_AT(pending, 74);
GNAV_AT(dc_due, 76);
GNAV_AT(rho_due, 77);
GNAV_AT(nxt_c, 80);
GNAV_AT(nxt_s, 84);
GNAV_AT(n15_c, 88);
GNAV_AT(n15_s, 90);
GNAV_AT(cell, 102);
GNAV_AT(cell_int, 104);
GNAV_AT(h_p, 106);
GNAV_AT(h_first, 108);
GNAV_AT(h_last, 110);
GNAV_AT(version, 112);
GNAV_AT(stop_lo, 70);
GNAV_AT(stop_hi, 72);
GNAV_AT(reverse, 75);
GNAV_AT(stop_armed, 78);
GNAV_AT(stop, 79);
GNAV_AT(heading, 92);
GNAV_AT(pub_seq, 120);
GNAV_AT(pub, 122);
GNAV_AT(stop_fn, 178);
GNAV_AT(stop_ctx, 180);
GNAV_AT(m_q16, 200);
GNAV_AT(m_q11, 204);
GNAV_AT(n0, 206);
GNAV_AT(tab_end, 208);
GNAV_AT(tab_e, 214);
GNAV_AT(tab_rho, 342);
GNAV_AT(closings, 406);
GNAV_AT(hdir, 118);
GNAV_AT(ival, 114);
GNAV_AT(hrate, 116);
_Static_assert(sizeof(gnav_pub_t) == 28, "gnav_pub_t");
_Static_assert(offsetof(gnav_pub_t, heading) == 16, "gnav_pub_t.heading");
_Static_assert(offsetof(gnav_pub_t, k) == 20, "gnav_pub_t.k");
_Static_assert(offsetof(gnav_pub_t, rate) == 22, "gnav_pub_t.rate");
_Static_assert(offsetof(gnav_pub_t, ival) == 24, "gnav_pub_t.ival");
_Static_assert(offsetof(gnav_pub_t, dir) == 26, "gnav_pub_t.dir");
#endif

/* ------------------------------------------------------------------ small arithmetic */

static uint32_t umul16(uint16_t a, uint16_t b)
{
    return (uint32_t)a * (uint32_t)b;
}

static int32_t smul16(int16_t a, int16_t b)
{
    return (int32_t)a * (int32_t)b;
}

/* v (Q25 int64) to Q4 int32, rounded; |v| < 2^52. */
static int32_t q25_to_q4(int64_t v)
{
    uint64_t u = (uint64_t)v + (1ul << 20);
    uint32_t hi = (uint32_t)(u >> 32), lo = (uint32_t)u;
    return (int32_t)((hi << 11) | (lo >> 21));
}

/* v * 2^n and round(v / 2^n) (ties up), 1 <= n < 32, for the cold paths (fixes, init): a
 * loop keeps the code small where the compiler would inline long 64-bit shift sequences. */
__attribute__((noinline)) static int64_t shl64(int64_t v, uint8_t n)
{
    uint64_t u = (uint64_t)v;
    while (n--)
        u <<= 1;
    return (int64_t)u;
}

__attribute__((noinline)) static int64_t sar64r(int64_t v, uint8_t n)
{
    v += shl64(1, (uint8_t)(n - 1u));
    while (n--)
        v >>= 1;
    return v;
}

static int64_t q4_to_q25(int32_t v)
{
    return shl64(v, 21);
}

/* Q1.30 to Q1.15, rounded, +1 saturating at 32767. */
static int16_t q30_to_q15(fx_q30_t v)
{
    int32_t r = (v + (1l << 14)) >> 15;
    return (int16_t)(r > 32767 ? 32767 : r);
}

/* Q1.30 to the per-pulse step in Q25, rounded. */
static int32_t q30_to_q25(fx_q30_t v)
{
    return (v + 16) >> 5;
}

/* rho (Q15, >= 0) * v (|v| < 2^31), same format as v, rounded. */
static int32_t mul_rho(int16_t rho, int32_t v)
{
    int16_t vh = (int16_t)(v >> 16);
    uint16_t vl = (uint16_t)v;
    int32_t a = smul16(rho, vh);
    uint32_t b = umul16((uint16_t)rho, vl);
    return a * 2 + (int32_t)((b + (1u << 14)) >> 15);
}

/* The heading inside the cell (gyro edge, readers): a one-step interval entered at @p rate
 * pulses per step (<= 2^15) that lasts longer than the rate plus 1/8 and 2 pulses (a steady
 * arc's intervals differ by a pulse) has seen its turn change. */
static uint16_t rate_limit(uint16_t rate)
{
    return (uint16_t)(rate + (rate >> 3) + 2u);
}

/* ... overdue: the one-step limit passed, or twice it for an excursion into the cell and back
 * (@p twice). */
static bool overdue(uint16_t pulses, uint16_t rate, bool twice)
{
    uint16_t limit = rate_limit(rate);
    if (pulses <= limit)
        return false;
    return !twice || (uint16_t)(pulses - limit) > limit;
}

/* ------------------------------------------------------------------ the arc's deficit */

#ifndef GNAV_ASM

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
        p = umul16(g->m_q11, gnav_recip[m - GNAV_RECIP_LO]);
        x = (uint16_t)((p + 0x8000u) >> 16);
    } else if (m < ((uint32_t)GNAV_RECIP_HI << 4)) {
        uint16_t i = (uint16_t)((m + 8u) >> 4);
        p = umul16(g->m_q11,
                   gnav_recip[(i < GNAV_RECIP_HI ? i : GNAV_RECIP_HI - 1u) - GNAV_RECIP_LO]);
        x = (uint16_t)((p + 0x80000u) >> 20);
    } else if (m < ((uint32_t)GNAV_RECIP_HI << 8)) {
        uint16_t i = (uint16_t)((m + 128u) >> 8);
        p = umul16(g->m_q11,
                   gnav_recip[(i < GNAV_RECIP_HI ? i : GNAV_RECIP_HI - 1u) - GNAV_RECIP_LO]);
        x = (uint16_t)((p + 0x800000u) >> 24);
    } else if (m < ((uint32_t)GNAV_RECIP_HI << 12)) {
        uint16_t i = (uint16_t)((m + 2048u) >> 12);
        p = umul16(g->m_q11,
                   gnav_recip[(i < GNAV_RECIP_HI ? i : GNAV_RECIP_HI - 1u) - GNAV_RECIP_LO]);
        x = (uint16_t)((p + 0x8000000u) >> 28);
    } else {
        x = 0;
    }
    uint16_t i = (uint16_t)(x >> 8);
    uint16_t gl = gnav_g[i];
    uint16_t gv =
        (uint16_t)(gl +
                   (uint16_t)((umul16((uint16_t)(gnav_g[i + 1u] - gl), x & 0xFFu) + 128u) >> 8));
    /* E = M * g: m_q16 * g_q17 / 2^17, rounded */
    uint32_t a = umul16((uint16_t)(g->m_q16 >> 16), gv);
    uint32_t b = umul16((uint16_t)g->m_q16, gv);
    uint32_t hi = a + (b >> 16);
    g->x_p = x;
    g->g_p = gv;
    g->rho_due = 1;
    return (int32_t)((hi + 1u) >> 1);
}
#endif

/* ------------------------------------------------------------------ publishing */

/* Fill the free slot, then flip: a reader (the NMI included) only ever sees complete slots. */
static void publish(gnav_t *g)
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

/* ------------------------------------------------------------------ dl handler */

/* Deferred from the closing to the next pulse: the deficit per pulse and the curved step. */
void gnav_finish_interval(gnav_t *g)
{
    if (g->rho_due) {
        uint32_t r = (umul16(g->x_p, g->g_p) + 0x20000u) >> 18; /* Q33 -> Q15 */
        g->rho_p = (uint16_t)(r > 32767u ? 32767u : r);
        g->rho_due = 0;
    }
    int16_t rho = (int16_t)g->rho_p;
    g->inc[0][0] = g->inc[1][0] - mul_rho(rho, g->inc[1][0]);
    HAL_PREEMPT_POINT();
    g->inc[0][1] = g->inc[1][1] - mul_rho(rho, g->inc[1][1]);
    g->dc_due = 0;
}

#ifndef GNAV_ASM
static int32_t pulses_since_p(const gnav_t *g)
{
    return (int32_t)(((uint32_t)(uint16_t)g->n_hi << 16) | g->n_lo);
}

/*
 * The gyro left the interval's cell: close the arc at this pulse (seed situations 1 and 3).
 * On the MSP430 msp430/gnav_dl.S performs the very same steps (GNAV_ASM).
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
    int32_t dprov = (int32_t)(umul16(nc, g->rho_p) << 1); /* Q15 -> Q16 */
    uint16_t np = m > 32000u ? 32000u : (uint16_t)m;
    int32_t e = 0;
    uint8_t sit1 = 0;
    if (k == 0) {
        /* back through the same threshold: the turn reversed inside one cell (an S-curve's
         * inflection). The last arc's curvature went on, over at most 2 n_p pulses (an
         * excursion below one step); a longer interval means the vehicle had straightened. */
        uint16_t n2 = (uint16_t)(2u * g->n_p);
        e = (int32_t)(umul16(m < n2 ? (uint16_t)m : n2, g->rho_p) << 1);
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
#endif

#ifndef GNAV_ASM
/* The dl handler. On the MSP430 msp430/gnav_dl.S performs the very same steps (GNAV_ASM). */
void gnav_on_delta_l(void *arg)
{
    gnav_t *g = arg;
    if (g->dc_due) {
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
    uint16_t m;
    if (!g->reverse) {
        m = q >= 0 ? (uint16_t)q : (uint16_t)~q;
        if (q < 32767)
            g->nq = (int16_t)(q + 1);
        if (++g->n_lo == 0u)
            g->n_hi++;
        gnav_add64x2(&g->x, g->inc[m >= g->n_p]);
    } else {
        m = q > 0 ? (uint16_t)(q - 1) : (uint16_t)-q;
        if (q > -32767)
            g->nq = (int16_t)(q - 1);
        if (g->n_lo-- == 0u)
            g->n_hi--;
        gnav_sub64x2(&g->x, g->inc[m >= g->n_p]);
    }
    HAL_PREEMPT_POINT();
    if (g->pending)
        gnav_close_arc(g);
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
    publish(g);
}
#endif

/* ------------------------------------------------------------------ gyro handlers */

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
        g->hrate = g->hrate == 0u || !overdue(a, g->hrate, false) ? a : 0u;
    else if (g->hdir == 0 || overdue(a, g->hrate, true))
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
    g->nxt_c = q30_to_q25(c);
    g->nxt_s = q30_to_q25(s);
    HAL_PREEMPT_POINT();
    g->n15_c = q30_to_q15(c);
    g->n15_s = q30_to_q15(s);
    g->version++;
    publish(g);
}

void gnav_on_gyro_up(void *arg)
{
    gyro_edge(arg, 1);
}

void gnav_on_gyro_down(void *arg)
{
    gyro_edge(arg, -1);
}

/* ------------------------------------------------------------------ latches, requests */

void gnav_on_beacon_sighted(void *arg)
{
    gnav_t *g = arg;
    /* a maskable handler: no writer runs now, the current slot is stable */
    const gnav_pub_t *p = &g->pub[g->pub_seq & 1u];
    gnav_latch_raw_t *l = &g->latch[g->latch_seq & (GNAV_LATCH_N - 1u)];
    l->x4 = q25_to_q4(p->x);
    l->y4 = q25_to_q4(p->y);
    l->heading = p->heading;
    l->k = p->k;
    l->rate = p->rate;
    l->ival = p->ival;
    l->dir = p->dir;
    l->gen = g->gen;
    g->latch_seq++;
}

/* Pulses Q4 to metres Q15.16: round(v dl_q40 / 2^28), saturating; 16 x 16 products only
 * (the coordinate request runs this in the NMI). */
static fx_q16_t q4_to_m(const gnav_t *g, int32_t v)
{
    uint32_t a = v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
    uint16_t ah = (uint16_t)(a >> 16), al = (uint16_t)a;
    uint16_t dh = (uint16_t)(g->dl_q40 >> 16), dlo = (uint16_t)g->dl_q40;
    uint64_t p = ((uint64_t)umul16(ah, dh) << 32) + ((uint64_t)umul16(ah, dlo) << 16) +
                 ((uint64_t)umul16(al, dh) << 16) + umul16(al, dlo);
    uint64_t r = (p + (1ul << 27)) >> 28;
    if (r > 0x7FFFFFFFu)
        return v < 0 ? INT32_MIN : INT32_MAX;
    return v < 0 ? -(int32_t)r : (int32_t)r;
}

/* num / den in Q15 (truncated), at most 1.0 = 2^15; 0 < den <= 2^15. A restoring division
 * of 15 bits in 16-bit registers (the coordinate request runs it). */
__attribute__((noinline)) static uint16_t frac15(uint16_t num, uint16_t den)
{
    if (num >= den)
        return 0x8000u;
    uint16_t q = 0;
    for (uint8_t i = 0; i < 15u; i++) {
        num = (uint16_t)(num << 1); /* num < den <= 2^15: no overflow */
        q = (uint16_t)(q << 1);
        if (num >= den) {
            num = (uint16_t)(num - den);
            q |= 1u;
        }
    }
    return q;
}

/* E[min(x, u)] for u uniform in [0, 1], Q15: x - x^2 / 2 up to 1, then 1/2. */
__attribute__((noinline)) static uint16_t ended_somewhere(uint16_t x)
{
    if (x >= 0x8000u)
        return 0x4000u;
    return (uint16_t)(x - (uint16_t)(umul16(x, x) >> 16));
}

/* beta * f / 2^15 for a binary angle beta (the step, < 2^27) and f in Q15, [0, 1], rounded:
 * 16 x 16 products only. */
__attribute__((noinline)) static int32_t of_step(uint32_t beta, uint16_t f)
{
    if (f >= 0x8000u)
        return (int32_t)beta;
    return (int32_t)((umul16((uint16_t)(beta >> 16), f) << 1) +
                     ((umul16((uint16_t)beta, f) + 0x4000u) >> 15));
}

/* Pulses since the interval's entry edge for a published k (1 .. 2^15): the edge came between
 * the pulse before P and P, a sighting comes between pulse k and the next (half a pulse
 * each, on average). */
static uint16_t pulses_since_edge(int16_t k)
{
    if (k == GNAV_K_EDGE)
        return 0;
    return (uint16_t)(k < 0 ? 1 - k : k + 1);
}

/* An excursion into the cell and back over len pulses: up at r_in pulses per step from the
 * entry threshold, down at r_out back to it (Q15 of a step), exact for two arcs; once it
 * lasted longer than those rates allow, with a plateau at an unknown height between. */
static uint16_t excursion(uint16_t a, uint16_t len, uint16_t r_in, uint16_t r_out)
{
    uint16_t up = frac15(a, r_in), down = frac15((uint16_t)(len - a), r_out);
    if ((uint32_t)len > (uint32_t)rate_limit(r_in) + rate_limit(r_out)) {
        up = ended_somewhere(up);
        down = ended_somewhere(down);
    }
    return up < down ? up : down;
}

/*
 * The heading inside the cell, as the offset from its centre (binary angle, within +-half a
 * step): @p a pulses after the interval's entry edge (direction @p dir; 0 = the start at the
 * cell centre), entered at @p rate pulses per step (0 = unknown). @p exit = the edge that
 * closed the interval @p len pulses after its entry edge (a <= len), 0 while it is open
 * (then @p a_now pulses have passed since the entry); @p rate_out = the rate of the interval
 * after it when that was one step on in the exit direction (0 = unknown). In fractions f of
 * a step from the entry threshold:
 *  - open: at the entry rate up to the far threshold; once the turn is overdue it ended
 *    somewhere in the interval, evenly likely: f = E[min(a / rate, u)], u uniform in [0, 1];
 *    rate unknown: the middle of what the tightest turn (one step in M pulses: L |d heading|
 *    <= dl) can have reached, min(a / M, 1) / 2;
 *  - closed by an edge in the entry direction: evenly between the edges (the mean rate),
 *    unless the interval outlasted its entry rate (then as an overdue open one);
 *  - closed back through the entry threshold (an excursion, an S-curve's inflection): up at
 *    the entry rate, down at the exit rate (either for both when one is unknown).
 */
static int32_t cell_offset(const gnav_t *g, int8_t dir, uint16_t rate, uint16_t a, uint16_t a_now,
                           int8_t exit, uint16_t len, uint16_t rate_out)
{
    uint16_t f;
    if (dir == 0) {
        /* from the cell centre (init) towards the exit threshold, evenly */
        if (exit == 0)
            return 0;
        dir = exit;
        f = (uint16_t)(0x4000u + (frac15(a, len) >> 1));
    } else if (exit == -dir) {
        if (rate == 0u)
            rate = rate_out;
        if (rate == 0u)
            f = frac15(a < (uint16_t)(len - a) ? a : (uint16_t)(len - a), g->n0) >> 1;
        else
            f = excursion(a, len, rate, rate_out != 0u ? rate_out : rate);
    } else if (exit == dir && (rate == 0u || !overdue(len, rate, false))) {
        f = frac15(a, len);
    } else if (rate == 0u) {
        f = frac15(a, g->n0) >> 1;
    } else {
        f = frac15(a, rate);
        if (exit != 0 || overdue(a_now, rate, false))
            f = ended_somewhere(f);
    }
    uint32_t beta = g->step_whole;
    int32_t off = of_step(beta, f) - (int32_t)(beta >> 1);
    return dir < 0 ? -off : off;
}

/* The published pose's offset (its interval is open: it is the current one). */
static int32_t pub_offset(const gnav_t *g, const gnav_pub_t *p)
{
    uint16_t a = pulses_since_edge(p->k);
    return cell_offset(g, p->dir, p->rate, a, a, 0, 0, 0);
}

static void pub_to_pose(const gnav_t *g, const gnav_pub_t *p, gnav_pose_t *out)
{
    out->x = q4_to_m(g, q25_to_q4(p->x));
    out->y = q4_to_m(g, q25_to_q4(p->y));
    out->heading = p->heading + (fx_angle_t)pub_offset(g, p);
}

void gnav_on_coord_request(void *arg)
{
    gnav_t *g = arg;
    /* The NMI may preempt a writer anywhere: the writer never touches the current slot. */
    gnav_pub_t snap = g->pub[g->pub_seq & 1u];
    pub_to_pose(g, &snap, &g->coord);
    if (g->coord_fn)
        g->coord_fn(&g->coord, g->coord_ctx);
}

/* Copy the published pose from any context (seqlock: a writer fills the other slot, so the
 * copy is good unless two writers ran under it). */
static void read_pub(gnav_t *g, gnav_pub_t *out)
{
    for (;;) {
        uint16_t s1 = g->pub_seq;
        const gnav_pub_t *p = &g->pub[s1 & 1u];
        out->x = p->x;
        HAL_PREEMPT_POINT();
        out->y = p->y;
        HAL_PREEMPT_POINT();
        out->heading = p->heading;
        out->k = p->k;
        out->rate = p->rate;
        out->ival = p->ival;
        out->dir = p->dir;
        HAL_PREEMPT_POINT();
        uint16_t s2 = g->pub_seq;
        if ((uint16_t)(s2 - s1) <= 1u)
            return;
    }
}

void gnav_pose(gnav_t *g, gnav_pose_t *out)
{
    gnav_pub_t snap;
    read_pub(g, &snap);
    pub_to_pose(g, &snap, out);
}

void gnav_coord(const gnav_t *g, gnav_pose_t *out)
{
    *out = g->coord;
}

void gnav_set_reverse(gnav_t *g, bool reverse)
{
    g->reverse = reverse ? 1u : 0u;
}

void gnav_set_coord_callback(gnav_t *g, gnav_coord_fn fn, void *ctx)
{
    hal_irq_state_t st = hal_irq_disable();
    g->coord_fn = fn;
    g->coord_ctx = ctx;
    hal_irq_restore(st);
}

void gnav_set_stop_callback(gnav_t *g, gnav_stop_fn fn, void *ctx)
{
    hal_irq_state_t st = hal_irq_disable();
    g->stop_fn = fn;
    g->stop_ctx = ctx;
    hal_irq_restore(st);
}

bool gnav_stop_requested(const gnav_t *g)
{
    return g->stop != 0u;
}

uint32_t gnav_closings(const gnav_t *g, unsigned kind)
{
    return kind < 4u ? g->closings[kind] : 0u;
}

uint32_t gnav_m_q24(const gnav_t *g)
{
    return g->m_q24;
}

uint16_t gnav_latch_next(const gnav_t *g)
{
    return g->latch_seq;
}

int gnav_attach(gnav_t *g)
{
    int r = 0;
    r |= hal_edge_init(HAL_EDGE_DELTA_L, HAL_EDGE_RISING, gnav_on_delta_l, g);
    r |= hal_edge_init(HAL_EDGE_GYRO_UP, HAL_EDGE_RISING, gnav_on_gyro_up, g);
    r |= hal_edge_init(HAL_EDGE_GYRO_DOWN, HAL_EDGE_RISING, gnav_on_gyro_down, g);
    r |= hal_edge_init(HAL_EDGE_BEACON_SIGHTED, HAL_EDGE_RISING, gnav_on_beacon_sighted, g);
    r |= hal_edge_init(HAL_EDGE_COORD_REQUEST, HAL_EDGE_FALLING, gnav_on_coord_request, g);
    return r ? -1 : 0;
}

const char *gnav_strerror(int err)
{
    switch (err) {
    case GNAV_OK:
        return "ok";
    case GNAV_ERR_WHEELBASE:
        return "wheelbase outside (0, 32] m";
    case GNAV_ERR_DL:
        return "odometer pulse outside 30.5 um .. 1.95 mm";
    case GNAV_ERR_GYRO_STEP:
        return "gyro step outside (0, 10] degrees";
    case GNAV_ERR_STEERING:
        return "wheelbase * gyro step / dl must stay below 32 pulses";
    case GNAV_ERR_STOP:
        return "negative stop distance";
    case GNAV_ERR_POSE:
        return "position outside the +-30000 m working range";
    case GNAV_ERR_LATCH:
        return "latch not in the buffer";
    case GNAV_ERR_STALE:
        return "latch older than the fixes kept";
    case GNAV_ERR_BUSY:
        return "fix overtaken by gyro edges 8 times";
    case GNAV_ERR_NULL:
        return "missing argument";
    default:
        return "unknown error";
    }
}

/* ------------------------------------------------------------------ frames and fixes */

/* Count the stop distance down from now: N pulses as (N - 1) >> 16 and ((N - 1) & 0xFFFF) + 1
 * (so that the dl handler's 16-bit count reaches zero exactly at the N-th pulse). */
static void arm_stop(gnav_t *g)
{
    uint32_t n1 = g->stop_pulses - 1u;
    g->stop_hi = (uint16_t)(n1 >> 16);
    g->stop_lo = (uint16_t)((n1 & 0xFFFFu) + 1u);
    g->stop_armed = g->stop_pulses != 0u;
    g->stop = 0;
}

#define GNAV_POS_LIMIT_Q16 (30000l * 65536l)

/* metres Q16 to pulses Q4: v * per_m / 2^28, rounded */
static bool m_to_q4(const gnav_t *g, fx_q16_t v, int32_t *out)
{
    if (v > GNAV_POS_LIMIT_Q16 || v < -GNAV_POS_LIMIT_Q16)
        return false;
    return fx_mul_shift(v, g->per_m_q16, 28, out);
}

/* Rotate (dx, dy) (any int32 scale) by (c, s) Q30. */
static void rotate(fx_q30_t c, fx_q30_t s, int32_t dx, int32_t dy, int32_t *ox, int32_t *oy)
{
    *ox = fx_mul_q30(dx, c) - fx_mul_q30(dy, s);
    *oy = fx_mul_q30(dx, s) + fx_mul_q30(dy, c);
}

/* Apply correction k to a Q4 point and heading. */
static void corr_apply(const gnav_corr_t *k, int32_t *x4, int32_t *y4, fx_angle_t *h)
{
    int32_t rx, ry;
    rotate(k->c, k->s, *x4 - k->lx4, *y4 - k->ly4, &rx, &ry);
    *x4 = k->fx4 + rx;
    *y4 = k->fy4 + ry;
    *h += k->turn;
}

/* Bring a Q4 pose of generation @p from forward to the current generation. */
static int bring_forward(const gnav_t *g, uint8_t from, int32_t *x4, int32_t *y4, fx_angle_t *h)
{
    uint8_t lag = (uint8_t)(g->gen - from);
    if (lag > GNAV_CORR_N)
        return GNAV_ERR_STALE;
    for (uint8_t j = 1; j <= lag; j++) {
        uint8_t gj = (uint8_t)(from + j);
        corr_apply(&g->corr[gj % GNAV_CORR_N], x4, y4, h);
    }
    return GNAV_OK;
}

/*
 * The latch's offset from its cell's centre: between the edges of its interval when that has
 * closed since and is still in the ring (@p ring_end: the ring's entry for it, @p next_end
 * the one after), else from its entry edge, with @p k_now the pulses of the current interval.
 */
static int32_t latch_offset(const gnav_t *g, const gnav_latch_raw_t *l, uint16_t ival,
                            uint16_t ring_end, uint16_t next_end, int16_t k_now)
{
    uint16_t age = (uint16_t)(ival - l->ival);
    uint16_t a = pulses_since_edge(l->k);
    if (age == 0u)
        return cell_offset(g, l->dir, l->rate, a, pulses_since_edge(k_now), 0, 0, 0);
    if (age > GNAV_RING_N)
        return cell_offset(g, l->dir, l->rate, a, a, 0, 0, 0);
    uint16_t len = ring_end & 0x7FFFu;
    int8_t exit = (ring_end & 0x8000u) ? 1 : -1;
    uint16_t rate_out = 0;
    if (age >= 2u && (int8_t)((next_end & 0x8000u) ? 1 : -1) == exit)
        rate_out = next_end & 0x7FFFu;
    return cell_offset(g, l->dir, l->rate, a < len ? a : len, a, exit, len, rate_out);
}

int gnav_latch_read(gnav_t *g, uint16_t seq, gnav_latch_t *out)
{
    if (out == NULL)
        return GNAV_ERR_NULL;
    hal_irq_state_t st = hal_irq_disable();
    uint16_t next = g->latch_seq;
    gnav_latch_raw_t l = g->latch[seq & (GNAV_LATCH_N - 1u)];
    uint8_t gen = g->gen;
    uint16_t ival = g->ival;
    uint16_t ring_end = g->ring[l.ival & (GNAV_RING_N - 1u)];
    uint16_t next_end = g->ring[(l.ival + 1u) & (GNAV_RING_N - 1u)];
    int16_t k_now = g->pub[g->pub_seq & 1u].k;
    hal_irq_restore(st);
    /* the slot holds latch seq when it is one of the last GNAV_LATCH_N */
    if ((uint16_t)(next - seq) == 0u || (uint16_t)(next - seq) > GNAV_LATCH_N)
        return GNAV_ERR_LATCH;
    l.heading += (fx_angle_t)latch_offset(g, &l, ival, ring_end, next_end, k_now);
    int r = bring_forward(g, l.gen, &l.x4, &l.y4, &l.heading);
    if (r != GNAV_OK)
        return r;
    out->seq = seq;
    out->gen = gen;
    out->pose.x = q4_to_m(g, l.x4);
    out->pose.y = q4_to_m(g, l.y4);
    out->pose.heading = l.heading;
    return GNAV_OK;
}

/* p (Q25) -> F + R (p - L) with the parts below Q8 carried over unrotated. */
static bool transform_q25(const gnav_corr_t *k, int64_t *px, int64_t *py)
{
    int64_t dx = *px - q4_to_q25(k->lx4), dy = *py - q4_to_q25(k->ly4);
    const int64_t lim = (int64_t)1 << 47; /* 2^22 pulses: 1 km at 0.254 mm */
    if (dx >= lim || dx <= -lim || dy >= lim || dy <= -lim)
        return false;
    int32_t dx8 = (int32_t)sar64r(dx, 17), dy8 = (int32_t)sar64r(dy, 17);
    int64_t restx = dx - shl64(dx8, 17), resty = dy - shl64(dy8, 17);
    int32_t rx, ry;
    rotate(k->c, k->s, dx8, dy8, &rx, &ry);
    *px = q4_to_q25(k->fx4) + shl64(rx, 17) + restx;
    *py = q4_to_q25(k->fy4) + shl64(ry, 17) + resty;
    return true;
}

/* Rotate a small motion (Q25, |m| < 2^15 pulses) by (c, s) Q1.15, keeping the sub-Q10 rest. */
__attribute__((noinline)) static void rotate_small(int16_t c, int16_t s, int64_t mx, int64_t my,
                                                   int64_t *ox, int64_t *oy)
{
    int32_t x10 = (int32_t)((mx + (1l << 14)) >> 15), y10 = (int32_t)((my + (1l << 14)) >> 15);
    int16_t xh = (int16_t)(x10 >> 15), yh = (int16_t)(y10 >> 15);
    int16_t xl = (int16_t)(x10 & 0x7FFF), yl = (int16_t)(y10 & 0x7FFF);
    /* (x10 * c - y10 * s) in Q25 = Q10 * Q15 */
    *ox = (mx - (int64_t)x10 * (1l << 15)) +
          ((int64_t)(smul16(xh, c) - smul16(yh, s)) * (1l << 15)) + smul16(xl, c) - smul16(yl, s);
    *oy = (my - (int64_t)y10 * (1l << 15)) +
          ((int64_t)(smul16(xh, s) + smul16(yh, c)) * (1l << 15)) + smul16(xl, s) + smul16(yl, c);
}

int gnav_fix(gnav_t *g, const gnav_pose_t *fix, const gnav_latch_t *ref)
{
    if (g == NULL || fix == NULL)
        return GNAV_ERR_NULL;
    gnav_corr_t k;
    if (!m_to_q4(g, fix->x, &k.fx4) || !m_to_q4(g, fix->y, &k.fy4))
        return GNAV_ERR_POSE;
    fx_angle_t ref_heading = 0;
    uint8_t ref_gen = 0;
    if (ref != NULL) {
        if (!m_to_q4(g, ref->pose.x, &k.lx4) || !m_to_q4(g, ref->pose.y, &k.ly4))
            return GNAV_ERR_POSE;
        ref_heading = ref->pose.heading;
        ref_gen = ref->gen;
    }
    for (int attempt = 0; attempt < 8; attempt++) {
        /* 1. snapshot (short critical section) */
        hal_critical_enter();
        uint16_t version = g->version;
        uint8_t gen = g->gen;
        int64_t x = g->x, y = g->y, xp = g->xp, yp = g->yp;
        uint64_t head = ((uint64_t)g->hd << 16) | g->hd_frac;
        uint16_t dcell = (uint16_t)(g->cell - g->cell_int);
        gnav_pub_t cur = g->pub[g->pub_seq & 1u];
        hal_critical_exit();
        /* 2. the correction, its reference brought into the current frame */
        gnav_corr_t kk = k;
        fx_angle_t lh;
        if (ref != NULL) {
            lh = ref_heading;
            int r = bring_forward(g, ref_gen, &kk.lx4, &kk.ly4, &lh);
            if (r != GNAV_OK)
                return r;
        } else {
            kk.lx4 = q25_to_q4(x);
            kk.ly4 = q25_to_q4(y);
            lh = cur.heading + (fx_angle_t)pub_offset(g, &cur);
        }
        kk.turn = fix->heading - lh;
        fx_sincos(kk.turn, &kk.s, &kk.c);
        /* 3. the new state, computed with interrupts on */
        int64_t nx = x, ny = y, nxp = xp, nyp = yp;
        if (!transform_q25(&kk, &nx, &ny) || !transform_q25(&kk, &nxp, &nyp))
            return GNAV_ERR_POSE;
        uint64_t nhead = head + ((uint64_t)kk.turn << 16);
        uint64_t step = ((uint64_t)g->step_whole << 16) | g->step_frac;
        uint64_t ihead = nhead - (uint64_t)(int64_t)(int16_t)dcell * step;
        fx_angle_t nh = (fx_angle_t)(nhead >> 16) + (fx_angle_t)((nhead >> 15) & 1u);
        fx_angle_t ih = (fx_angle_t)(ihead >> 16) + (fx_angle_t)((ihead >> 15) & 1u);
        fx_q30_t ns, nc, is, ic;
        fx_sincos(nh, &ns, &nc);
        fx_sincos(ih, &is, &ic);
        int16_t r15c = q30_to_q15(kk.c), r15s = q30_to_q15(kk.s);
        /* 4. install, unless a closing or a gyro edge came in between */
        hal_critical_enter();
        if (g->version != version || g->gen != gen) {
            hal_critical_exit();
            continue;
        }
        /* pulses since the snapshot moved x, y in the old frame: rotate that motion */
        int64_t mx, my;
        rotate_small(r15c, r15s, g->x - x, g->y - y, &mx, &my);
        g->x = nx + mx;
        g->y = ny + my;
        g->xp = nxp;
        g->yp = nyp;
        g->hd = (uint32_t)(nhead >> 16);
        g->hd_frac = (uint16_t)nhead;
        g->heading = nh;
        g->nxt_c = q30_to_q25(nc);
        g->nxt_s = q30_to_q25(ns);
        g->n15_c = q30_to_q15(nc);
        g->n15_s = q30_to_q15(ns);
        g->inc[1][0] = q30_to_q25(ic);
        g->inc[1][1] = q30_to_q25(is);
        g->d15_c = q30_to_q15(ic);
        g->d15_s = q30_to_q15(is);
        g->dc_due = 1;
        g->gen = (uint8_t)(gen + 1u);
        g->corr[g->gen % GNAV_CORR_N] = kk;
        arm_stop(g);
        g->version++;
        publish(g);
        hal_critical_exit();
        return GNAV_OK;
    }
    return GNAV_ERR_BUSY;
}

/* ------------------------------------------------------------------ init */

/* M = L * step * 2 pi / dl in pulses, Q24; 0 when out of range. */
static uint32_t steering_m(fx_q16_t wheelbase, uint64_t step_q48, uint32_t dl_q40)
{
    const uint64_t two_pi_q29 = 3373259426u; /* 2 pi * 2^29 */
    uint64_t sh = step_q48 >> 32, sl = step_q48 & 0xFFFFFFFFu;
    uint64_t rad_q40 = ((sh * two_pi_q29) >> 5) + ((sl * two_pi_q29) >> 37);
    uint64_t u = (uint64_t)(uint32_t)wheelbase * rad_q40; /* m * rad, Q56 */
    uint64_t q = u / dl_q40, r = u % dl_q40;
    if (q >= ((uint64_t)GNAV_TABLE_N << 16))
        return 0xFFFFFFFFu;
    return (uint32_t)((q << 8) + ((r << 8) + dl_q40 / 2u) / dl_q40);
}

int gnav_init(gnav_t *g, const gnav_config_t *cfg, const gnav_pose_t *start)
{
    if (g == NULL || cfg == NULL || start == NULL)
        return GNAV_ERR_NULL;
    if (cfg->wheelbase <= 0 || cfg->wheelbase > 32l * 65536l)
        return GNAV_ERR_WHEELBASE;
    if (cfg->dl_q40 <= (1ul << 25) || cfg->dl_q40 >= (1ul << 31))
        return GNAV_ERR_DL;
    if (cfg->gyro_step_q48 == 0u || cfg->gyro_step_q48 > ((uint64_t)1 << 48) / 36u)
        return GNAV_ERR_GYRO_STEP;
    if (cfg->stop_distance < 0)
        return GNAV_ERR_STOP;
    uint32_t m = steering_m(cfg->wheelbase, cfg->gyro_step_q48, cfg->dl_q40);
    if (m == 0u || m >= ((uint32_t)GNAV_TABLE_N << 24) - (1ul << 13))
        return GNAV_ERR_STEERING;
    if (start->x > GNAV_POS_LIMIT_Q16 || start->x < -GNAV_POS_LIMIT_Q16 ||
        start->y > GNAV_POS_LIMIT_Q16 || start->y < -GNAV_POS_LIMIT_Q16)
        return GNAV_ERR_POSE;

    uint8_t *raw = (uint8_t *)g;
    for (size_t i = 0; i < sizeof *g; i++)
        raw[i] = 0;
    g->dl_q40 = cfg->dl_q40;
    g->per_m_q16 = (int32_t)((((uint64_t)1 << 56) + cfg->dl_q40 / 2u) / cfg->dl_q40);
    g->step_whole = (uint32_t)(cfg->gyro_step_q48 >> 16);
    g->step_frac = (uint16_t)cfg->gyro_step_q48;
    g->m_q24 = m;
    g->m_q16 = (m + 128u) >> 8;
    g->m_q11 = (uint16_t)((m + 4096u) >> 13);
    g->n0 = (uint16_t)((m + 0xFFFFFFu) >> 24);
    uint16_t two_m = (uint16_t)((2u * m + 0xFFFFFFu) >> 24);
    uint16_t end = two_m > GNAV_RECIP_LO ? two_m : (uint16_t)GNAV_RECIP_LO;
    if (end <= g->n0)
        end = (uint16_t)(g->n0 + 1u);
    g->tab_end = end;
    /* E(n) = n - sqrt(n^2 - M^2) and E(n) / n for the pulse counts near the singularity */
    uint64_t m2 = (uint64_t)m * m; /* Q48 */
    for (uint16_t n = g->n0; n < end; n++) {
        uint64_t n2 = (uint64_t)n * n << 48;
        uint64_t root2 = fx_sqrt64((n2 - m2) << 2); /* floor(2 sqrt), Q24 */
        uint64_t root = (root2 + 1u) >> 1;
        uint64_t e24 = ((uint64_t)n << 24) - root;
        g->tab_e[n - g->n0] = (int32_t)((e24 + 128u) >> 8);
        uint64_t rho = (e24 + (uint64_t)n * 256u) / ((uint64_t)n * 512u); /* Q15 */
        g->tab_rho[n - g->n0] = (uint16_t)(rho > 32767u ? 32767u : rho);
    }
    if (cfg->stop_distance > 0) {
        /* pulses = distance / dl, rounded up */
        uint64_t d = (uint64_t)(uint32_t)cfg->stop_distance << 24; /* Q40 */
        g->stop_pulses = (uint32_t)((d + cfg->dl_q40 - 1u) / cfg->dl_q40);
    }
    arm_stop(g);
    /* the start pose: the gyro's reading is the centre of cell 0 */
    g->x = sar64r((int64_t)start->x * g->per_m_q16, 7); /* Q32 -> Q25 */
    g->y = sar64r((int64_t)start->y * g->per_m_q16, 7);
    g->xp = g->x;
    g->yp = g->y;
    g->hd = start->heading;
    g->heading = start->heading;
    fx_q30_t s, c;
    fx_sincos(start->heading, &s, &c);
    g->inc[0][0] = g->inc[1][0] = g->nxt_c = q30_to_q25(c);
    g->inc[0][1] = g->inc[1][1] = g->nxt_s = q30_to_q25(s);
    g->d15_c = g->n15_c = q30_to_q15(c);
    g->d15_s = g->n15_s = q30_to_q15(s);
    g->pub[0].x = g->pub[1].x = g->x;
    g->pub[0].y = g->pub[1].y = g->y;
    g->pub[0].heading = g->pub[1].heading = start->heading;
    return GNAV_OK;
}
