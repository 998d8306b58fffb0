/*
 * drive_vectors.c - firmware/drive on both worlds: the same inputs through the solver, the
 * drive-board command builder, both port encoders, the decoder, path preparation and the
 * travel state table, one line per result (hex), compared line by line between the host
 * build and the MSP430 image (bit-identical). On the target the solver is timed:
 * "@cycles doublearc max mean n" (the solve alone) and "@cycles doublearc_cmd" (solve plus
 * steering angles and drive-board bytes) for build/msp430/cycles.json.
 *
 * Inputs: pseudo-random configurations of the test domain (target ahead, heading
 * change under 90 degrees, 0.3 - 5 m, minimum radius 0.25 - 1 m, forward and reverse;
 * xorshift32, fixed seed) and of a wider domain with refusals, plus fixed edge cases.
 */
#include <stdbool.h>
#include <stdint.h>

#include "cy_test.h"
#include "drive/drive.h"
#include "fx/fx.h"

#define DOMAIN_N 300u
#define WIDE_N   100u

static uint32_t rng = 0x2545F491u;

static uint32_t rnd32(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

/* Uniform in [lo, lo + span) for span < 2^32. */
static uint32_t rnd_span(uint32_t span)
{
    return (uint32_t)(((uint64_t)rnd32() * span) >> 32);
}

static void out_hex(uint32_t v)
{
    cy_print(" ");
    cy_print_hex32(v);
}

static cy_bench_stat_t st_solve = {"doublearc", 0, 0, 0};

/* Operands through volatiles so that the timed call cannot be hoisted. */
static volatile drive_pose_t v_from, v_to;
static volatile int32_t v_rmin;
static volatile uint8_t v_rev;

static drive_status_t solve_one(const drive_pose_t *f, const drive_pose_t *t, fx_q16_t rmin,
                                bool rev, drive_solution_t *sol, int32_t *need, bool timed)
{
    v_from = *f;
    v_to = *t;
    v_rmin = rmin;
    v_rev = rev;
    drive_status_t st;
    drive_pose_t a, b;
    a.x = v_from.x;
    a.y = v_from.y;
    a.heading = v_from.heading;
    b.x = v_to.x;
    b.y = v_to.y;
    b.heading = v_to.heading;
    if (timed)
        CY_BENCH(&st_solve, st = drive_solve(&a, &b, v_rmin, v_rev != 0, sol, need));
    else
        st = drive_solve(&a, &b, v_rmin, v_rev != 0, sol, need);
    return st;
}

static void print_solution(const char *tag, const drive_pose_t *f, const drive_pose_t *t,
                           fx_q16_t rmin, bool rev, bool timed)
{
    drive_solution_t sol;
    int32_t need = 0;
    drive_status_t st = solve_one(f, t, rmin, rev, &sol, &need, timed);
    cy_print(tag);
    out_hex((uint32_t)f->x);
    out_hex((uint32_t)f->y);
    out_hex(f->heading);
    out_hex((uint32_t)t->x);
    out_hex((uint32_t)t->y);
    out_hex(t->heading);
    out_hex((uint32_t)rmin);
    cy_print(rev ? " r " : " f ");
    cy_print_dec((int32_t)st);
    if (st == DRIVE_OK) {
        cy_print(" case ");
        cy_print_dec((int32_t)sol.kase);
        for (uint8_t i = 0; i < 2u; i++) {
            out_hex((uint32_t)sol.seg[i].curvature);
            out_hex((uint32_t)sol.seg[i].length);
            out_hex(sol.seg[i].sweep);
        }
    } else if (st == DRIVE_ERR_RADIUS) {
        out_hex((uint32_t)need);
    }
    cy_println();
}

/* A target at distance dist (Q16) and bearing (from the direction of travel) with heading
 * change dth, from a pose near the origin. */
static void make_config(uint32_t dist, int32_t bearing, int32_t dth, bool rev, drive_pose_t *f,
                        drive_pose_t *t)
{
    f->x = (fx_q16_t)rnd_span(40ul << 16) - (20l << 16);
    f->y = (fx_q16_t)rnd_span(40ul << 16) - (20l << 16);
    f->heading = rnd32();
    fx_angle_t dir = f->heading + (rev ? FX_ANGLE_HALF : 0u) + (fx_angle_t)bearing;
    fx_q30_t s, c;
    fx_sincos(dir, &s, &c);
    t->x = f->x + fx_mul_q30((int32_t)dist, c);
    t->y = f->y + fx_mul_q30((int32_t)dist, s);
    t->heading = f->heading + (fx_angle_t)dth;
}

#define DEG(d) ((int32_t)((d)*11930464.7111)) /* degrees to a binary angle (constants only) */

static void solver_vectors(void)
{
    /* The domain, timed. */
    const uint32_t span89 = (uint32_t)DEG(179.8);
    for (uint16_t i = 0; i < DOMAIN_N; i++) {
        uint32_t dist = (uint32_t)(0.3 * 65536) + rnd_span((uint32_t)(4.7 * 65536));
        int32_t bearing = (int32_t)rnd_span(span89) - DEG(89.9);
        int32_t dth = (int32_t)rnd_span(span89) - DEG(89.9);
        fx_q16_t rmin = (fx_q16_t)((uint32_t)(0.25 * 65536) + rnd_span((uint32_t)(0.75 * 65536)));
        bool rev = (rnd32() & 3u) == 0;
        drive_pose_t f, t;
        make_config(dist, bearing, dth, rev, &f, &t);
        print_solution("solve", &f, &t, rmin, rev, true);
    }
    /* Wider: any bearing and heading change, 1 cm - 70 m, radii 0.1 - 120 m. */
    for (uint16_t i = 0; i < WIDE_N; i++) {
        uint32_t dist = rnd_span(70ul << 16) >> (rnd32() & 7u);
        int32_t bearing = (int32_t)rnd32();
        int32_t dth = (int32_t)rnd32() >> (rnd32() & 3u);
        fx_q16_t rmin = (fx_q16_t)(rnd_span(120ul << 16) >> (rnd32() & 7u));
        bool rev = (rnd32() & 1u) != 0;
        drive_pose_t f, t;
        make_config(dist, bearing, dth, rev, &f, &t);
        print_solution("wide", &f, &t, rmin, rev, false);
    }
    /* Edge cases: straight ahead, pure lateral offsets, exact single arcs, 90 degrees. */
    static const struct {
        int32_t dist_mm, bearing_mdeg, dth_mdeg, rmin_mm;
    } edges[] = {
        {1000, 0, 0, 250},
        {1000, 1, 0, 250},
        {1000, 0, 1, 250},
        {1000, 5000, 0, 250},
        {1000, -5000, 0, 250},
        {1000, 45000, 90000, 250},
        {1000, -45000, -90000, 250},
        {1000, 30000, 60000, 1000},
        {2000, 10000, 20000, 250},
        {500, 89000, 0, 250},
        {300, 0, 90000, 250},
        {5000, 0, -1, 1000},
        {15, 0, 0, 250},
        {64000, 0, 0, 250},
        {64000, 1000, 3000, 250},
        {1000, 90000, 0, 250},
        {1000, 0, 90001, 250},
        {1000, 0, 0, 124},
    };
    for (uint16_t i = 0; i < sizeof edges / sizeof edges[0]; i++) {
        drive_pose_t f, t;
        uint32_t dist = (uint32_t)(((int64_t)edges[i].dist_mm << 16) / 1000);
        int32_t bearing = (int32_t)(((int64_t)edges[i].bearing_mdeg * 11930465) / 1000);
        int32_t dth = (int32_t)(((int64_t)edges[i].dth_mdeg * 11930465) / 1000);
        fx_q16_t rmin = (fx_q16_t)(((int64_t)edges[i].rmin_mm << 16) / 1000);
        make_config(dist, bearing, dth, false, &f, &t);
        print_solution("edge", &f, &t, rmin, false, false);
        make_config(dist, bearing, dth, true, &f, &t);
        print_solution("edge", &f, &t, rmin, true, false);
    }
}

int main(void)
{
    cy_bench_init();
    solver_vectors();
    cy_bench_report(&st_solve);
    cy_test_end();
    return 0;
}
