/*
 * gnav_init.c - configuration and set-up (gnav.h): the derived constants and the deficit
 * table, the handlers' registration, the callbacks, the stop request's countdown, small
 * accessors and the error names.
 */
#include "gnav_internal.h"
#include "gnav_tables.h"
#include "hal/edge.h"
#include "hal/irq.h"

/* Count the stop distance down from now: N pulses as (N - 1) >> 16 and ((N - 1) & 0xFFFF) + 1
 * (so that the dl handler's 16-bit count reaches zero exactly at the N-th pulse). */
void gnav_arm_stop(gnav_t *g)
{
    uint32_t n1 = g->stop_pulses - 1u;
    g->stop_hi = (uint16_t)(n1 >> 16);
    g->stop_lo = (uint16_t)((n1 & 0xFFFFu) + 1u);
    g->stop_armed = g->stop_pulses != 0u;
    g->stop = 0;
}

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

/* Metres Q16 to pulses Q25: v * per_m / 2^7 (Q32 -> Q25), rounded. (A function of its own:
 * clang 16 crashes selecting the MSP430 instructions of gnav_init with both products inline.) */
__attribute__((noinline)) static int64_t m_to_q25(const gnav_t *g, fx_q16_t v)
{
    return gnav_sar64r((int64_t)v * g->per_m_q16, 7);
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
    gnav_arm_stop(g);
    /* the start pose: the gyro's reading is the centre of cell 0 */
    g->x = m_to_q25(g, start->x);
    g->y = m_to_q25(g, start->y);
    g->xp = g->x;
    g->yp = g->y;
    g->hd = start->heading;
    g->heading = start->heading;
    fx_q30_t s, c;
    fx_sincos(start->heading, &s, &c);
    g->inc[0][0] = g->inc[1][0] = g->nxt_c = gnav_q30_to_q25(c);
    g->inc[0][1] = g->inc[1][1] = g->nxt_s = gnav_q30_to_q25(s);
    g->d15_c = g->n15_c = gnav_q30_to_q15(c);
    g->d15_s = g->n15_s = gnav_q30_to_q15(s);
    g->pub[0].x = g->pub[1].x = g->x;
    g->pub[0].y = g->pub[1].y = g->y;
    g->pub[0].heading = g->pub[1].heading = start->heading;
    return GNAV_OK;
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
