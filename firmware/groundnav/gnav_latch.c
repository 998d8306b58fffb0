/*
 * gnav_latch.c - pose latches at beacon sightings (gnav.h): the Beacon Sighted handler takes
 * the published pose as it is; gnav_latch_read() brings a latch into the current frame and
 * places its heading inside the cell with what is known by then.
 */
#include "gnav_internal.h"
#include "hal/irq.h"

void gnav_on_beacon_sighted(void *arg)
{
    gnav_t *g = arg;
    /* a maskable handler: no writer runs now, the current slot is stable */
    const gnav_pub_t *p = &g->pub[g->pub_seq & 1u];
    gnav_latch_raw_t *l = &g->latch[g->latch_seq & (GNAV_LATCH_N - 1u)];
    l->x4 = gnav_q25_to_q4(p->x);
    l->y4 = gnav_q25_to_q4(p->y);
    l->heading = p->heading;
    l->k = p->k;
    l->rate = p->rate;
    l->ival = p->ival;
    l->dir = p->dir;
    l->gen = g->gen;
    g->latch_seq++;
}

uint16_t gnav_latch_next(const gnav_t *g)
{
    return g->latch_seq;
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
    uint16_t a = gnav_pulses_since_edge(l->k);
    if (age == 0u)
        return gnav_cell_offset(g, l->dir, l->rate, a, gnav_pulses_since_edge(k_now), 0, 0, 0);
    if (age > GNAV_RING_N)
        return gnav_cell_offset(g, l->dir, l->rate, a, a, 0, 0, 0);
    uint16_t len = ring_end & 0x7FFFu;
    int8_t exit = (ring_end & 0x8000u) ? 1 : -1;
    uint16_t rate_out = 0;
    if (age >= 2u && (int8_t)((next_end & 0x8000u) ? 1 : -1) == exit)
        rate_out = next_end & 0x7FFFu;
    return gnav_cell_offset(g, l->dir, l->rate, a < len ? a : len, a, exit, len, rate_out);
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
    int r = gnav_bring_forward(g, l.gen, &l.x4, &l.y4, &l.heading);
    if (r != GNAV_OK)
        return r;
    out->seq = seq;
    out->gen = gen;
    out->pose.x = gnav_q4_to_m(g, l.x4);
    out->pose.y = gnav_q4_to_m(g, l.y4);
    out->pose.heading = l.heading;
    return GNAV_OK;
}
