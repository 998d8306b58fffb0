/*
 * gnav_fix.c - optical fixes and frames (gnav.h): a fix moves the whole dead-reckoning state
 * by the rigid transform that takes its reference pose onto it; the last GNAV_CORR_N
 * corrections bring older latches forward.
 */
#include "gnav_internal.h"
#include "hal/irq.h"

/* v * 2^n and round(v / 2^n) (ties up), 1 <= n < 32, for the cold paths (fixes, init): a
 * loop keeps the code small where the compiler would inline long 64-bit shift sequences. */
__attribute__((noinline)) int64_t gnav_shl64(int64_t v, uint8_t n)
{
    uint64_t u = (uint64_t)v;
    while (n--)
        u <<= 1;
    return (int64_t)u;
}

__attribute__((noinline)) int64_t gnav_sar64r(int64_t v, uint8_t n)
{
    v += gnav_shl64(1, (uint8_t)(n - 1u));
    while (n--)
        v >>= 1;
    return v;
}

static int64_t q4_to_q25(int32_t v)
{
    return gnav_shl64(v, 21);
}

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
int gnav_bring_forward(const gnav_t *g, uint8_t from, int32_t *x4, int32_t *y4, fx_angle_t *h)
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

/* p (Q25) -> F + R (p - L) with the parts below Q8 carried over unrotated. */
static bool transform_q25(const gnav_corr_t *k, int64_t *px, int64_t *py)
{
    int64_t dx = *px - q4_to_q25(k->lx4), dy = *py - q4_to_q25(k->ly4);
    const int64_t lim = (int64_t)1 << 47; /* 2^22 pulses: 1 km at 0.254 mm */
    if (dx >= lim || dx <= -lim || dy >= lim || dy <= -lim)
        return false;
    int32_t dx8 = (int32_t)gnav_sar64r(dx, 17), dy8 = (int32_t)gnav_sar64r(dy, 17);
    int64_t restx = dx - gnav_shl64(dx8, 17), resty = dy - gnav_shl64(dy8, 17);
    int32_t rx, ry;
    rotate(k->c, k->s, dx8, dy8, &rx, &ry);
    *px = q4_to_q25(k->fx4) + gnav_shl64(rx, 17) + restx;
    *py = q4_to_q25(k->fy4) + gnav_shl64(ry, 17) + resty;
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
          ((int64_t)(gnav_smul16(xh, c) - gnav_smul16(yh, s)) * (1l << 15)) + gnav_smul16(xl, c) -
          gnav_smul16(yl, s);
    *oy = (my - (int64_t)y10 * (1l << 15)) +
          ((int64_t)(gnav_smul16(xh, s) + gnav_smul16(yh, c)) * (1l << 15)) + gnav_smul16(xl, s) +
          gnav_smul16(yl, c);
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
        int64_t x = g->x, y = g->y;
        int64_t xp = g->p_due ? x : g->xp, yp = g->p_due ? y : g->yp; /* (P taken yet?) */
        uint64_t head = ((uint64_t)g->hd << 16) | g->hd_frac;
        uint16_t dcell = (uint16_t)(g->cell - g->cell_int);
        gnav_pub_t cur = g->pub[g->pub_seq & 1u];
        hal_critical_exit();
        /* 2. the correction, its reference brought into the current frame */
        gnav_corr_t kk = k;
        fx_angle_t lh;
        if (ref != NULL) {
            lh = ref_heading;
            int r = gnav_bring_forward(g, ref_gen, &kk.lx4, &kk.ly4, &lh);
            if (r != GNAV_OK)
                return r;
        } else {
            kk.lx4 = gnav_q25_to_q4(x);
            kk.ly4 = gnav_q25_to_q4(y);
            lh = cur.heading + (fx_angle_t)gnav_pub_offset(g, &cur);
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
        int16_t r15c = gnav_q30_to_q15(kk.c), r15s = gnav_q30_to_q15(kk.s);
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
        g->p_due = 0;
        g->hd = (uint32_t)(nhead >> 16);
        g->hd_frac = (uint16_t)nhead;
        g->heading = nh;
        g->nxt_c = gnav_q30_to_q25(nc);
        g->nxt_s = gnav_q30_to_q25(ns);
        g->n15_c = gnav_q30_to_q15(nc);
        g->n15_s = gnav_q30_to_q15(ns);
        g->inc[1][0] = gnav_q30_to_q25(ic);
        g->inc[1][1] = gnav_q30_to_q25(is);
        g->d15_c = gnav_q30_to_q15(ic);
        g->d15_s = gnav_q30_to_q15(is);
        g->dc_due = 1;
        g->gen = (uint8_t)(gen + 1u);
        g->corr[g->gen % GNAV_CORR_N] = kk;
        gnav_arm_stop(g);
        g->version++;
        gnav_publish(g);
        hal_critical_exit();
        return GNAV_OK;
    }
    return GNAV_ERR_BUSY;
}
