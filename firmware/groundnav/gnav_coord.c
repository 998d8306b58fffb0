/*
 * gnav_coord.c - the coordinate request (NMI) and the pose readers (gnav.h). The NMI only
 * copies the published pose (no multiply: it may land inside one, and DINT does not hold it
 * off); the conversion to metres happens when the main loop reads it (gnav_coord()).
 */
#include "gnav_internal.h"
#include "hal/preempt.h"

/* Pulses Q4 to metres Q15.16: round(v dl_q40 / 2^28), saturating (main loop only). */
fx_q16_t gnav_q4_to_m(const gnav_t *g, int32_t v)
{
    uint32_t a = v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
    uint16_t ah = (uint16_t)(a >> 16), al = (uint16_t)a;
    uint16_t dh = (uint16_t)(g->dl_q40 >> 16), dlo = (uint16_t)g->dl_q40;
    uint64_t p = ((uint64_t)gnav_umul16(ah, dh) << 32) + ((uint64_t)gnav_umul16(ah, dlo) << 16) +
                 ((uint64_t)gnav_umul16(al, dh) << 16) + gnav_umul16(al, dlo);
    uint64_t r = (p + (1ul << 27)) >> 28;
    if (r > 0x7FFFFFFFu)
        return v < 0 ? INT32_MIN : INT32_MAX;
    return v < 0 ? -(int32_t)r : (int32_t)r;
}

static void pub_to_pose(const gnav_t *g, const gnav_pub_t *p, gnav_pose_t *out)
{
    out->x = gnav_q4_to_m(g, gnav_q25_to_q4(p->x));
    out->y = gnav_q4_to_m(g, gnav_q25_to_q4(p->y));
    out->heading = p->heading + (fx_angle_t)gnav_pub_offset(g, p);
}

void gnav_on_coord_request(void *arg)
{
    gnav_t *g = arg;
    /* The NMI may preempt a writer anywhere: the writer never touches the current slot. The
     * copy goes into the free one of the two coordinate slots, then they flip (the main loop
     * reads them as it reads the published pose). A copy, no conversion: nothing here may
     * use the hardware multiplier (an NMI can land inside any multiply; DINT does not hold it
     * off), and the metres come out the same when gnav_coord() converts later. */
    uint16_t s = g->coord_seq;
    /* (the slots chosen by branches: an index would be multiplied by the slot's size) */
    gnav_pub_t *to = (s & 1u) ? &g->coord[0] : &g->coord[1];
    const gnav_pub_t *from = (g->pub_seq & 1u) ? &g->pub[1] : &g->pub[0];
    *to = *from;
    g->coord_seq = (uint16_t)(s + 1u);
    if (g->coord_fn)
        g->coord_fn(g->coord_ctx);
}

/* Copy the current one of two slots whose writer fills the other one, then bumps *seq (the
 * published pose, the coordinate snapshot): the copy is good unless two writers ran under it,
 * else again. */
static void read_slots(const gnav_pub_t slot[2], const volatile uint16_t *seq, gnav_pub_t *out)
{
    for (;;) {
        uint16_t s1 = *seq;
        const gnav_pub_t *p = &slot[s1 & 1u];
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
        uint16_t s2 = *seq;
        if ((uint16_t)(s2 - s1) <= 1u)
            return;
    }
}

void gnav_pose(gnav_t *g, gnav_pose_t *out)
{
    gnav_pub_t snap;
    read_slots(g->pub, &g->pub_seq, &snap);
    pub_to_pose(g, &snap, out);
}

void gnav_coord(const gnav_t *g, gnav_pose_t *out)
{
    gnav_pub_t snap;
    read_slots(g->coord, &g->coord_seq, &snap);
    pub_to_pose(g, &snap, out);
}
