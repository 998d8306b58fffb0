/*
 * gnav_cell.c - the heading inside the gyro's cell (docs/groundnav.md, "The heading inside
 * the cell"): where between its thresholds the heading was, from the pulses since the
 * interval's entry edge and the rates the intervals showed. Readers only (main loop); the
 * handlers store pulse counts.
 */
#include "gnav_internal.h"

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
    return (uint16_t)(x - (uint16_t)(gnav_umul16(x, x) >> 16));
}

/* beta * f / 2^15 for a binary angle beta (the step, < 2^27) and f in Q15, [0, 1], rounded:
 * 16 x 16 products only. */
__attribute__((noinline)) static int32_t of_step(uint32_t beta, uint16_t f)
{
    if (f >= 0x8000u)
        return (int32_t)beta;
    return (int32_t)((gnav_umul16((uint16_t)(beta >> 16), f) << 1) +
                     ((gnav_umul16((uint16_t)beta, f) + 0x4000u) >> 15));
}

/* An excursion into the cell and back over len pulses: up at r_in pulses per step from the
 * entry threshold, down at r_out back to it (Q15 of a step), exact for two arcs; once it
 * lasted longer than those rates allow, with a plateau at an unknown height between. */
static uint16_t excursion(uint16_t a, uint16_t len, uint16_t r_in, uint16_t r_out)
{
    uint16_t up = frac15(a, r_in), down = frac15((uint16_t)(len - a), r_out);
    if ((uint32_t)len > (uint32_t)gnav_rate_limit(r_in) + gnav_rate_limit(r_out)) {
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
 *  - open: at the entry rate up to the far threshold; once the turn is gnav_overdue it ended
 *    somewhere in the interval, evenly likely: f = E[min(a / rate, u)], u uniform in [0, 1];
 *    rate unknown: the middle of what the tightest turn (one step in M pulses: L |d heading|
 *    <= dl) can have reached, min(a / M, 1) / 2;
 *  - closed by an edge in the entry direction: evenly between the edges (the mean rate),
 *    unless the interval outlasted its entry rate (then as an gnav_overdue open one, but not
 *    below the lower of a / len and 1 - (len - a) / rate_out: the exit it made);
 *  - closed back through the entry threshold (an excursion, an S-curve's inflection): up at
 *    the entry rate, down at the exit rate (either for both when one is unknown).
 */
int32_t gnav_cell_offset(const gnav_t *g, int8_t dir, uint16_t rate, uint16_t a, uint16_t a_now,
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
    } else if (exit == dir && (rate == 0u || !gnav_overdue(len, rate, false))) {
        f = frac15(a, len);
    } else if (rate == 0u) {
        f = frac15(a, g->n0) >> 1;
    } else {
        f = frac15(a, rate);
        if (exit != 0 || gnav_overdue(a_now, rate, false))
            f = ended_somewhere(f);
        if (exit == dir) {
            /* Closed in the entry direction after outlasting its entry rate: the turn slowed
             * (a double arc's wider second arc) or paused and went on. Either way the heading
             * reached the exit threshold at len, and it is not left below the lower of: the
             * chord a / len (a turn that only slowed lies above it) and the exit at rate_out,
             * 1 - (len - a) / rate_out (a turn that went on at the next interval's rate). */
            uint16_t low = frac15(a, len);
            if (rate_out != 0u) {
                uint16_t back = (uint16_t)(0x8000u - frac15((uint16_t)(len - a), rate_out));
                if (back < low)
                    low = back;
            }
            if (low > f)
                f = low;
        }
    }
    uint32_t beta = g->step_whole;
    int32_t off = of_step(beta, f) - (int32_t)(beta >> 1);
    return dir < 0 ? -off : off;
}

/* The published pose's offset (its interval is open: it is the current one). */
int32_t gnav_pub_offset(const gnav_t *g, const gnav_pub_t *p)
{
    uint16_t a = gnav_pulses_since_edge(p->k);
    return gnav_cell_offset(g, p->dir, p->rate, a, a, 0, 0, 0);
}
