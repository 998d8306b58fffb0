/*
 * possrc.c - the simulated laser positioning system (see possrc.h).
 */
#include "sim/possrc.h"

#include <math.h>
#include <string.h>

#include "hal/uart.h"
#include "sim/clock.h"

#define RNG_STREAM 7 /* sensors.c uses 1 and 2 */

static void update(void *ctx, uint64_t t_ns);
static void deliver(void *ctx, uint64_t t_ns);

void sim_possrc_init(sim_possrc_t *s, const sim_scenario_t *sc, const sim_drive_t *drive,
                     int main_board)
{
    memset(s, 0, sizeof *s);
    s->cfg = &sc->src;
    s->world = &sc->world;
    s->drive = drive;
    s->board = main_board;
    s->period = 1.0 / sc->src.rate_hz;
    sim_rng_seed(&s->rng, sc->seed, RNG_STREAM);
    if (sc->src.n_transmitters == 3) {
        memcpy(s->tx, sc->src.transmitter, sizeof s->tx);
    } else { /* the corners of the beacons' bounding box (the seed's Figure 6.1) */
        double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
        for (size_t i = 0; i < sc->world.n_beacons; i++) {
            x0 = fmin(x0, sc->world.beacon[i].x);
            y0 = fmin(y0, sc->world.beacon[i].y);
            x1 = fmax(x1, sc->world.beacon[i].x);
            y1 = fmax(y1, sc->world.beacon[i].y);
        }
        s->tx[0] = (sim_xy_t){x0, y0};
        s->tx[1] = (sim_xy_t){x1, y0};
        s->tx[2] = (sim_xy_t){x0, y1};
    }
    s->n_rcv = sc->src.n_receivers ? (int)sc->src.n_receivers : 1;
    for (int r = 0; r < s->n_rcv; r++)
        s->rcv[r] = sc->src.n_receivers ? sc->src.receiver[r] : (sim_xy_t){0, 0};
}

void sim_possrc_start(sim_possrc_t *s)
{
    sim_clock_schedule(sim_clock_now() + s->period, update, s);
}

sim_xy_t sim_possrc_truth(const sim_possrc_t *s, int r, double t)
{
    sim_pose_t p = sim_drive_pose(s->drive, t);
    double c = cos(p.th), sn = sin(p.th);
    return (sim_xy_t){p.x + c * s->rcv[r].x - sn * s->rcv[r].y,
                      p.y + sn * s->rcv[r].x + c * s->rcv[r].y};
}

static int32_t mm(double v)
{
    double r = round(v * 1000.0);
    return r > 2147483647.0 ? INT32_MAX : r < -2147483648.0 ? INT32_MIN : (int32_t)r;
}

static void put32(uint8_t *b, int32_t v)
{
    for (int k = 0; k < 4; k++)
        b[k] = (uint8_t)((uint32_t)v >> (24 - 8 * k));
}

/* Measure receiver @p r at @p t and queue its packet, troubles and all. */
static void measure(sim_possrc_t *s, int r, double t)
{
    const sim_position_source_t *c = s->cfg;
    sim_rng_t *g = &s->rng;
    /* every draw is made whatever the outcome, so that one trouble does not shift another */
    double u_drop = sim_rng_uniform(g), u_zero = sim_rng_uniform(g), u_wild = sim_rng_uniform(g);
    double u_garb = sim_rng_uniform(g), wild_dir = sim_rng_uniform(g), wild_k = sim_rng_uniform(g);
    double nx = sim_rng_normal(g), ny = sim_rng_normal(g), nz = sim_rng_normal(g);
    int n_garbage = 1 + (int)(sim_rng_uniform(g) * 20.0);
    if (u_drop < c->dropout) {
        s->st.dropouts++;
        return;
    }
    sim_xy_t p = sim_possrc_truth(s, r, t);
    double far = 0;
    for (int i = 0; i < 3; i++) {
        double d = hypot(p.x - s->tx[i].x, p.y - s->tx[i].y);
        if (d > c->range || !sim_world_visible(s->world, s->tx[i].x, s->tx[i].y, p.x, p.y)) {
            s->st.no_sight++;
            return;
        }
        far = fmax(far, d);
    }
    double sigma = c->noise_rel * far + c->noise_m;
    double x = p.x + sigma * nx, y = p.y + sigma * ny, z = c->height + sigma * nz;
    if (u_wild < c->wild) {
        double a = 2 * M_PI * wild_dir, m = c->wild_m * (0.5 + wild_k);
        x += m * cos(a);
        y += m * sin(a);
        s->st.wilds++;
    }
    if (s->q_n == SIM_POSSRC_QUEUE)
        return; /* cannot happen: the queue holds the longest lag at the highest rate */
    sim_possrc_packet_t *pk = &s->q[(s->q_head + s->q_n) % SIM_POSSRC_QUEUE];
    pk->t_ns = sim_clock_ns(t + c->lag);
    pk->receiver = (uint8_t)r;
    uint8_t *b = pk->bytes;
    size_t n = 0;
    if (u_garb < c->garbage) {
        for (int i = 0; i < n_garbage; i++)
            b[n++] = (uint8_t)sim_rng_next(g);
        s->st.garbage_bytes += (uint32_t)n_garbage;
    }
    b[n] = 0x00;
    if (u_zero < c->zero) {
        memset(b + n + 1, 0, 12);
        s->st.zeros++;
    } else {
        put32(b + n + 1, mm(x));
        put32(b + n + 5, mm(y));
        put32(b + n + 9, mm(z));
    }
    b[n + 13] = 0xFF;
    n += 14;
    for (size_t i = 0; i < n; i++) {
        if (sim_rng_uniform(g) < c->corrupt) {
            b[i] = (uint8_t)sim_rng_next(g);
            s->st.corrupt_bytes++;
        }
    }
    pk->len = (uint8_t)n;
    if (s->q_n++ == 0)
        sim_clock_schedule(sim_clock_s(pk->t_ns), deliver, s);
}

static void update(void *ctx, uint64_t t_ns)
{
    sim_possrc_t *s = ctx;
    double t = sim_clock_s(t_ns);
    s->k++;
    s->st.updates++;
    int out = 0;
    for (size_t i = 0; i < s->cfg->n_outages; i++)
        out |= t >= s->cfg->outage[i].from && t < s->cfg->outage[i].to;
    if (out)
        s->st.outage++;
    else
        for (int r = 0; r < s->n_rcv; r++)
            measure(s, r, t);
    sim_clock_schedule((double)(s->k + 1) * s->period, update, s);
}

static void deliver(void *ctx, uint64_t t_ns)
{
    sim_possrc_t *s = ctx;
    while (s->q_n && s->q[s->q_head].t_ns <= t_ns) {
        const sim_possrc_packet_t *pk = &s->q[s->q_head];
        s->q_head = (s->q_head + 1) % SIM_POSSRC_QUEUE;
        s->q_n--;
        /* a packet takes 140 bit times; more than one ahead on the line: not sent */
        uint64_t packet_ns = (uint64_t)(140e9 / s->cfg->baud + 0.5);
        if (posix_uart_idle_ns(s->board, pk->receiver) > t_ns + packet_ns) {
            s->st.line_busy++;
            continue;
        }
        if (posix_uart_send(s->board, pk->receiver, pk->bytes, pk->len, 0) == pk->len)
            s->st.sent++;
    }
    if (s->q_n)
        sim_clock_schedule(sim_clock_s(s->q[s->q_head].t_ns), deliver, s);
}
