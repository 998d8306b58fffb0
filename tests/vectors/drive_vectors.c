/*
 * drive_vectors.c - firmware/drive on both worlds: the same inputs through the solver, the
 * nominal legs with turns over 90 degrees split, the drive-board command builder, both port
 * encoders, the decoder, path preparation and the travel state table, one line per result
 * (hex), compared line by line between the host build and the MSP430 image (bit-identical). On the
 * target the solver and the command builder are timed for build/msp430/cycles.json: "doublearc"
 * (the solve alone, in the domain and near straight; SPEC's floor of 20,000 cycles is
 * checked here), "doublearc_wide" (legs up to 70 m, refusals), "drive_cmd" (steering angles and
 * drive-board bytes) and "drive_leg_split" (a turn over 90 degrees: the inserted pose and two
 * solves).
 *
 * Inputs: pseudo-random configurations of the test domain (target ahead, heading
 * change under 90 degrees, 0.3 - 5 m, minimum radius 0.25 - 1 m, forward and reverse;
 * xorshift32, fixed seed) and of a wider domain with refusals, plus fixed edge cases.
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cy_test.h"
#include "drive/drive.h"
#include "drive/drive_cmd.h"
#include "drive/drive_path.h"
#include "drive/drive_proto.h"
#include "drive/drive_seq.h"
#include "fx/fx.h"

#define DOMAIN_N 300u
#define NEAR_N   100u
#define WIDE_N   100u
#define ANY_N    600u
#define POSE_N   300u
#define LEG_N    200u

static uint32_t rng = 0x2545F491u;

static uint32_t rnd32(void)
{
    return cy_rand32(&rng);
}

/* Uniform in [lo, lo + span) for span < 2^32. */
static uint32_t rnd_span(uint32_t span)
{
    return (uint32_t)(((uint64_t)rnd32() * span) >> 32);
}

/* A draw from rnd_span(span) shifted right by a random 0..mask bits (spread over orders of
 * magnitude). The draws of every helper here are sequenced, so that any compiler draws the
 * same numbers in the same order (C leaves the order of operands unspecified). */
static uint32_t rnd_spread(uint32_t span, uint32_t mask)
{
    uint32_t v = rnd_span(span);
    return v >> (rnd32() & mask);
}

/* A signed 32-bit draw shifted right (arithmetically) by @p base + a random 0..mask bits, at
 * most 31. */
static int32_t rnd_signed_spread(uint32_t base, uint32_t mask)
{
    int32_t v = (int32_t)rnd32();
    uint32_t n = base + (rnd32() & mask);
    return v >> (n < 31u ? n : 31u);
}

static void out_hex(uint32_t v)
{
    cy_print(" ");
    cy_print_hex32(v);
}

static cy_bench_stat_t st_solve = {"doublearc", 0, 0, 0};
static cy_bench_stat_t st_cmd = {"drive_cmd", 0, 0, 0};
static cy_bench_stat_t st_wide = {"doublearc_wide", 0, 0, 0};
static cy_bench_stat_t st_leg = {"drive_leg_split", 0, 0, 0};
static cy_stack_stat_t sk_solve = {"doublearc", 0}, sk_cmd = {"drive_cmd", 0};
static const drive_board_t board = DRIVE_BOARD_SEED;

/* Operands through volatiles so that the timed call cannot be hoisted. */
static volatile drive_pose_t v_from, v_to;
static volatile int32_t v_rmin;
static volatile uint8_t v_rev;

static drive_status_t solve_one(const drive_pose_t *f, const drive_pose_t *t, fx_q16_t rmin,
                                bool rev, drive_solution_t *sol, int32_t *need,
                                cy_bench_stat_t *timed)
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
        CY_STACK(&sk_solve,
                 CY_BENCH(timed, st = drive_solve(&a, &b, v_rmin, v_rev != 0, sol, need)));
    else
        CY_STACK(&sk_solve, st = drive_solve(&a, &b, v_rmin, v_rev != 0, sol, need));
    return st;
}

static void print_solution(const char *tag, const drive_pose_t *f, const drive_pose_t *t,
                           fx_q16_t rmin, bool rev, cy_bench_stat_t *timed)
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
        drive_cmd_t cmd;
        drive_status_t cs;
        if (timed == &st_solve)
            CY_STACK(&sk_cmd,
                     CY_BENCH(&st_cmd, cs = drive_cmd_build(&sol, &board, 32768, rev, &cmd)));
        else
            cs = drive_cmd_build(&sol, &board, 32768, rev, &cmd);
        cy_print(" cmd ");
        cy_print_dec((int32_t)cs);
        if (cs == DRIVE_OK) {
            for (uint8_t i = 0; i < 2u; i++) {
                out_hex(cmd.steer[i]);
                out_hex(cmd.arc[i]);
                out_hex(cmd.alpha[i]);
            }
            cy_print(" ");
            cy_print_dec(cmd.speed);
            cy_print(" ");
            cy_print_dec(cmd.pulses);
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
        print_solution("solve", &f, &t, rmin, rev, &st_solve);
    }
    /* Near straight, what full travel solves most: lateral offsets up to 5 cm, heading
     * errors up to 2 degrees, 0.3 - 1.5 m, timed too. */
    const uint32_t lat_span = (uint32_t)(0.1 * 65536), dth_span = (uint32_t)DEG(4.0);
    for (uint16_t i = 0; i < NEAR_N; i++) {
        uint32_t dist = (uint32_t)(0.3 * 65536) + rnd_span((uint32_t)(1.2 * 65536));
        int32_t lat = (int32_t)rnd_spread(lat_span, 15u) - (int32_t)(lat_span >> 1);
        int32_t bearing = (int32_t)fx_atan2(lat, (int32_t)dist);
        int32_t dth = (int32_t)rnd_span(dth_span) - DEG(2.0);
        dth >>= rnd32() & 15u;
        fx_q16_t rmin = (fx_q16_t)((uint32_t)(0.25 * 65536) + rnd_span((uint32_t)(0.75 * 65536)));
        bool rev = (rnd32() & 3u) == 0;
        drive_pose_t f, t;
        make_config(dist, bearing, dth, rev, &f, &t);
        print_solution("near", &f, &t, rmin, rev, &st_solve);
    }
    /* Wider: any bearing and heading change, 1 cm - 70 m, radii 0.1 - 120 m. */
    for (uint16_t i = 0; i < WIDE_N; i++) {
        uint32_t dist = rnd_spread(70ul << 16, 7u);
        int32_t bearing = (int32_t)rnd32();
        int32_t dth = rnd_signed_spread(0, 3u);
        fx_q16_t rmin = (fx_q16_t)rnd_spread(120ul << 16, 7u);
        bool rev = (rnd32() & 1u) != 0;
        drive_pose_t f, t;
        make_config(dist, bearing, dth, rev, &f, &t);
        print_solution("wide", &f, &t, rmin, rev, &st_wide);
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
        print_solution("edge", &f, &t, rmin, false, NULL);
        make_config(dist, bearing, dth, true, &f, &t);
        print_solution("edge", &f, &t, rmin, true, NULL);
    }
}

/* Anywhere (untimed): any bearing and heading change, 1.5 mm - 100 m, minimum radii 0.05 -
 * 200 m (a few out of range), near-straight targets, poses all over the Q16 plane, and
 * configurations that a search on the host found to take the rarer ways through the solver
 * (the long-leg length series, the minimum radius too large to scale, a case 4/5 arc just
 * below the minimum radius). */
static void solver_anywhere(void)
{
    static const struct {
        drive_pose_t f, t;
        int32_t rmin;
        uint8_t rev;
    } rare[] = {
        {{0x491dc8ec, (int32_t)0xb91f14f9, 0x6d6304d0},
         {0x48ebd4ad, (int32_t)0xb936fc4c, 0x6b5e1c5e},
         0x00002e64,
         0},
        {{(int32_t)0xde6995c8, (int32_t)0xf6b5b1fb, 0xba8e27ff},
         {(int32_t)0xde616318, (int32_t)0xf678b3ce, 0xb8f7fb87},
         0x000f587e,
         0},
        {{(int32_t)0xc2535b55, 0x4afa9a6d, 0x253c4a02},
         {(int32_t)0xc26ab4cd, 0x4b18e1dd, 0x238bebbc},
         0x002248e9,
         0},
        {{(int32_t)0xbdb79103, (int32_t)0xa559da1b, 0x91657167},
         {(int32_t)0xbdb7a816, (int32_t)0xa559e49a, 0x9147d0c1},
         0x000a6db1,
         1},
        {{(int32_t)0xfc75e331, 0x45a2a803, 0x2b613149},
         {(int32_t)0xfc75e01f, 0x45a2a279, 0x2b5c9d51},
         0x003f1b82,
         1},
        {{(int32_t)0xdf39df2a, 0x4f200ec6, 0x6ead3d2b},
         {(int32_t)0xdf02dccc, 0x4f38f73a, 0x6ec0fedc},
         0x0000a658,
         0},
        {{0x30370d64, 0x412360e1, 0x34767897}, {0x3045b988, 0x4155cd3a, 0x346f04b4}, 0x000c1e33, 0},
        {{0x0081f604, 0x16865631, 0x5f98188e}, {0x00620b2f, 0x16a6e575, 0x5f9e4a89}, 0x0005e8ad, 0},
        {{0x7ff00000, 0, 0}, {(int32_t)0x80100000, 0, 0}, 0x00010000, 0},
    };
    for (uint16_t i = 0; i < sizeof rare / sizeof rare[0]; i++)
        print_solution("rare", &rare[i].f, &rare[i].t, rare[i].rmin, rare[i].rev != 0, NULL);
    for (uint16_t i = 0; i < ANY_N; i++) {
        uint32_t dist = rnd_spread(100ul << 16, 15u);
        int32_t bearing = (int32_t)rnd32();
        int32_t dth = rnd_signed_spread(0, 7u);
        if (i % 4u == 1u) { /* near straight */
            bearing >>= 8u + (rnd32() & 15u);
            dth >>= 8u + (rnd32() & 15u);
        } else if (i % 4u == 2u) { /* the seed's domain: ahead, heading change under 90 degrees */
            bearing >>= 2;
            dth >>= 2;
        }
        fx_q16_t rmin = (fx_q16_t)rnd_spread(200ul << 16, 11u) + 7000;
        bool rev = (rnd32() & 1u) != 0;
        drive_pose_t f, t;
        make_config(dist, bearing, dth, rev, &f, &t);
        int32_t ox = (int32_t)rnd32() >> 2, oy = (int32_t)rnd32() >> 2; /* anywhere */
        f.x += ox;
        t.x += ox;
        f.y += oy;
        t.y += oy;
        print_solution("any", &f, &t, rmin, rev, NULL);
    }
}

/* drive_pose_advance: curvatures of either sign up to 8 /m, distances up to 10 m (some zero
 * or negative, some whose change saturates), forward and reverse. */
static void pose_vectors(void)
{
    for (uint16_t i = 0; i < POSE_N; i++) {
        drive_pose_t p;
        p.x = (int32_t)rnd32() >> 4;
        p.y = (int32_t)rnd32() >> 4;
        p.heading = rnd32();
        int32_t k = rnd_signed_spread(2u, 31u);
        fx_q16_t dist = (fx_q16_t)rnd_spread(10ul << 16, 7u);
        if (i % 16u == 3u)
            dist = -dist;
        else if (i % 16u == 7u)
            dist = (fx_q16_t)rnd32() & 0x7FFFFFFF; /* up to 32768 m: the change saturates */
        bool rev = (rnd32() & 1u) != 0;
        drive_pose_t r = drive_pose_advance(&p, k, dist, rev);
        cy_print("pose");
        out_hex((uint32_t)p.x);
        out_hex((uint32_t)p.y);
        out_hex(p.heading);
        out_hex((uint32_t)k);
        out_hex((uint32_t)dist);
        cy_print(rev ? " r" : " f");
        out_hex((uint32_t)r.x);
        out_hex((uint32_t)r.y);
        out_hex(r.heading);
        cy_println();
    }
}

static void print_leg(const char *tag, const drive_pose_t *f, const drive_pose_t *t,
                      fx_q16_t radius, bool rev, cy_bench_stat_t *timed)
{
    drive_leg_t leg;
    drive_status_t st;
    if (timed)
        CY_BENCH(timed, st = drive_leg_solve(f, t, radius, rev, &leg));
    else
        st = drive_leg_solve(f, t, radius, rev, &leg);
    cy_print(tag);
    out_hex((uint32_t)f->x);
    out_hex((uint32_t)f->y);
    out_hex(f->heading);
    out_hex((uint32_t)t->x);
    out_hex((uint32_t)t->y);
    out_hex(t->heading);
    out_hex((uint32_t)radius);
    cy_print(rev ? " r " : " f ");
    cy_print_dec((int32_t)st);
    if (st == DRIVE_OK) {
        cy_print(" parts ");
        cy_print_dec(leg.parts);
        if (leg.parts == 2) {
            out_hex((uint32_t)leg.via.x);
            out_hex((uint32_t)leg.via.y);
            out_hex(leg.via.heading);
        }
        for (uint8_t p = 0; p < leg.parts; p++) {
            cy_print(" case ");
            cy_print_dec((int32_t)leg.sol[p].kase);
            for (uint8_t i = 0; i < 2u; i++) {
                out_hex((uint32_t)leg.sol[p].seg[i].curvature);
                out_hex((uint32_t)leg.sol[p].seg[i].length);
                out_hex(leg.sol[p].seg[i].sweep);
            }
        }
    }
    cy_println();
}

/* Turns over 90 degrees (drive_leg_solve()): U-turns of exactly half a turn with the target
 * on either side, ahead or behind, corners of 90 - 180 degrees anywhere within 0.3 - 20 m
 * (split, or refused when no corner of the radius fits), forward and tail first; the split
 * ones timed. */
static void leg_vectors(void)
{
    for (uint16_t i = 0; i < LEG_N; i++) {
        uint32_t dist = (uint32_t)(0.3 * 65536) + rnd_span((uint32_t)(19.7 * 65536));
        int32_t bearing = (int32_t)rnd32();
        uint32_t turn = (uint32_t)DEG(90.01) + rnd_span((uint32_t)DEG(89.99));
        int32_t dth = (rnd32() & 1u) ? (int32_t)turn : -(int32_t)turn;
        if (i % 8u == 0u)
            dth = (int32_t)FX_ANGLE_HALF; /* a half turn exactly */
        fx_q16_t radius = (fx_q16_t)((uint32_t)(0.2 * 65536) + rnd_span((uint32_t)(2.0 * 65536)));
        bool rev = (rnd32() & 3u) == 0;
        drive_pose_t f, t;
        make_config(dist, bearing, dth, rev, &f, &t);
        print_leg("leg", &f, &t, radius, rev, &st_leg);
    }
    /* Exact ones: the aisle-end U-turn (2 m across, 2 m back), to the right, tail first,
     * across less than two radii, a 120-degree corner, and 90 degrees (one double arc). */
    static const struct {
        int32_t x_mm, y_mm, th_mdeg, r_mm;
        uint8_t rev;
    } exact[] = {
        {-2000, 2000, 180000, 500, 0}, {-2000, -2000, 180000, 500, 0},
        {2000, 2000, 180000, 500, 1},  {-2000, 2000, 180000, 1010, 0},
        {1366, 1500, 120000, 800, 0},  {1000, -1000, 120000, 300, 0},
        {1000, 1000, 90000, 500, 0},   {0, 0, 180000, 500, 0},
    };
    for (uint16_t i = 0; i < sizeof exact / sizeof exact[0]; i++) {
        drive_pose_t f = {0, 0, 0};
        drive_pose_t t = {(fx_q16_t)(((int64_t)exact[i].x_mm * 65536) / 1000),
                          (fx_q16_t)(((int64_t)exact[i].y_mm * 65536) / 1000),
                          (fx_angle_t)(((int64_t)exact[i].th_mdeg * 11930465) / 1000)};
        if (exact[i].th_mdeg == 180000)
            t.heading = FX_ANGLE_HALF;
        else if (exact[i].th_mdeg == 90000)
            t.heading = FX_ANGLE_QUARTER;
        print_leg("leg-exact", &f, &t, (fx_q16_t)(((int64_t)exact[i].r_mm << 16) / 1000),
                  exact[i].rev != 0, NULL);
    }
}

/* The command builder against boards at and beyond its limits, arcs beyond the bytes, and
 * missing arguments. */
static void cmd_edges(void)
{
    static const int32_t wheelbase[5] = {3275, 3276, 49938, 262144, 262145};
    static const struct {
        int32_t k0, len0, k1, len1;
    } segs[6] = {
        {DRIVE_CURV_ONE * 7, 6554, -DRIVE_CURV_ONE * 7, 6554},  /* 7 /m both ways, 0.1 m */
        {0, 131072, 0, 6554},                                   /* 2 m straight: no byte */
        {INT32_MAX, 655, INT32_MIN + 1, 655},                   /* the tightest curvature */
        {-DRIVE_CURV_ONE, 300, DRIVE_CURV_ONE / 3, 400},        /* short arcs (D7) */
        {DRIVE_CURV_ONE / 2, 65536, DRIVE_CURV_ONE / 2, 65536}, /* the same magnitude twice */
        {1, 1000, -1, 1000},                                    /* almost straight */
    };
    for (uint8_t w = 0; w < 5u; w++) {
        for (uint8_t i = 0; i < 6u; i++) {
            drive_board_t b = board;
            b.wheelbase = wheelbase[w];
            b.min_pulse_counts = (uint8_t)(i * 3u);
            if (i == 5u)
                b.counts_per_m = w == 2u ? 0 : -1;
            drive_solution_t sol = {DRIVE_CASE_1,
                                    {{segs[i].k0, segs[i].len0, 0}, {segs[i].k1, segs[i].len1, 0}}};
            drive_cmd_t cmd = {{0, 0}, {0, 0}, 0, 0, {0, 0}};
            drive_status_t st = drive_cmd_build(&sol, &b, (fx_q16_t)(w * 20000), i == 3u, &cmd);
            cy_print("cmd ");
            cy_print_dec(w);
            cy_print(" ");
            cy_print_dec(i);
            cy_print(" ");
            cy_print_dec((int32_t)st);
            if (st == DRIVE_OK) {
                for (uint8_t j = 0; j < 2u; j++) {
                    out_hex(cmd.steer[j]);
                    out_hex(cmd.arc[j]);
                    out_hex(cmd.alpha[j]);
                }
                out_hex((uint8_t)cmd.speed);
                out_hex(cmd.pulses);
            }
            cy_println();
        }
    }
    drive_solution_t sol = {DRIVE_CASE_STRAIGHT, {{0, 6554, 0}, {0, 6554, 0}}};
    drive_cmd_t cmd;
    drive_board_t slow = board;
    slow.speed_lsb = 0;
    cy_print("cmd-refuse ");
    cy_print_dec((int32_t)drive_cmd_build(NULL, &board, 0, false, &cmd));
    cy_print_dec((int32_t)drive_cmd_build(&sol, NULL, 0, false, &cmd));
    cy_print_dec((int32_t)drive_cmd_build(&sol, &board, 0, false, NULL));
    cy_print_dec((int32_t)drive_cmd_build(&sol, &slow, 0, false, &cmd));
    cy_print_dec((int32_t)drive_cmd_build(&sol, &board, -1, false, &cmd));
    cy_print_dec((int32_t)drive_cmd_build(&sol, &board, 3 * FX_Q16_ONE, true, &cmd));
    cy_println();
}

static void print_wseq(const char *tag, const drive_wseq_t *w)
{
    cy_print(tag);
    for (uint8_t i = 0; i < w->n; i++) {
        cy_print(" ");
        cy_print_dec(w->w[i].reg);
        cy_print(":");
        cy_print_dec(w->w[i].value);
    }
    cy_println();
}

/* Both port protocols and the decoder on the target. */
static void proto_vectors(void)
{
    drive_decoder_t d;
    drive_decoder_init(&d, board.dac_center);
    drive_wseq_t w;
    drive_event_t ev;
    drive_ppi_init(&w);
    print_wseq("ppi-init", &w);
    for (uint8_t i = 0; i < w.n; i++)
        (void)drive_decoder_feed(&d, w.w[i].reg, w.w[i].value, &ev);
    for (uint16_t n = 0; n < 40u; n++) {
        drive_cmd_t c = {{0, 0}, {0, 0}, 0, 2, {0, 0}};
        c.steer[0] = (uint8_t)rnd32();
        c.steer[1] = (uint8_t)rnd32();
        c.arc[0] = (uint8_t)rnd32();
        c.arc[1] = (uint8_t)rnd32();
        c.speed = (int8_t)rnd32();
        drive_ppi_load(&c, &w);
        print_wseq("ppi-load", &w);
        for (uint8_t i = 0; i < w.n; i++) {
            if (drive_decoder_feed(&d, w.w[i].reg, w.w[i].value, &ev)) {
                cy_print("event ");
                cy_print_dec(ev.type);
                out_hex(ev.mask);
                out_hex(ev.cmd.steer[0]);
                out_hex(ev.cmd.arc[0]);
                out_hex(ev.cmd.steer[1]);
                out_hex(ev.cmd.arc[1]);
                out_hex((uint8_t)ev.cmd.speed);
                out_hex(ev.cmd.alpha[0]);
                cy_println();
            }
        }
        fx_angle_t a = rnd32() >> 2;
        drive_dac_set(drive_dac_angle_byte(a, board.dac_center), drive_dac_speed_byte(c.speed), &w);
        print_wseq("dac", &w);
        for (uint8_t i = 0; i < w.n; i++) {
            if (drive_decoder_feed(&d, w.w[i].reg, w.w[i].value, &ev)) {
                cy_print("event ");
                cy_print_dec(ev.type);
                out_hex(ev.value);
                out_hex(ev.alpha);
                cy_println();
            }
        }
    }
    drive_ppi_speed(0, &w);
    print_wseq("ppi-stop", &w);
    drive_dac_start(board.dac_center, &w);
    print_wseq("dac-start", &w);
    drive_dac_stop(board.dac_center, &w);
    print_wseq("dac-stop", &w);
}

static void print_step(const drive_seq_t *seq, const drive_seq_out_t *out)
{
    cy_print("seq ");
    cy_print_dec(seq->state);
    out_hex(out->actions);
    if (out->actions & DRIVE_ACT_LOAD) {
        out_hex(out->cmd.steer[0]);
        out_hex(out->cmd.arc[0]);
        out_hex(out->cmd.steer[1]);
        out_hex(out->cmd.arc[1]);
        out_hex((uint8_t)out->cmd.speed);
        out_hex(out->cmd.pulses);
    }
    out_hex((uint8_t)out->speed);
    out_hex(out->timer_ms);
    out_hex(out->pose_ms);
    out_hex(out->fault);
    out_hex(out->stop);
    out_hex(out->status);
    out_hex(seq->target.leg);
    out_hex(seq->target.sub);
    out_hex(seq->ignored);
    out_hex(seq->underruns);
    out_hex(seq->loads);
    out_hex((uint32_t)seq->blind);
    cy_println();
}

/* Both travel modes through the state table with synthetic events: the vehicle reaches each
 * target it is loaded for, some fixes fail, spurious events come in between, one run is
 * stopped on request and one drives blind until its blind distance (1 m) is up. */
static void seq_vectors(drive_path_t *path, const drive_pose_t *start)
{
    static const drive_seq_config_t modes[4] = {
        {DRIVE_MODE_SIMPLIFIED, 35, 50, 9830, 26214, 3, 524288l},
        {DRIVE_MODE_FULL, 35, 50, 9830, 26214, 3, 524288l},
        {DRIVE_MODE_FULL, 40, 60, 0, 0, 0, 65536l},         /* every fix fails: blind 1 m */
        {DRIVE_MODE_FULL, 35, 50, 6554, 13107, 2, 524288l}, /* stopped on request */
    };
    for (uint8_t m = 0; m < 4u; m++) {
        drive_seq_t seq;
        drive_seq_init(&seq, path, &modes[m]);
        drive_seq_event_t ev = {DRIVE_EVT_START, *start};
        drive_seq_out_t out;
        drive_pose_t here = *start;
        uint8_t spurious = 0;
        for (uint16_t step = 0; step < 300u && seq.state != DRIVE_ST_DONE &&
                                seq.state != DRIVE_ST_FAULT && seq.state != DRIVE_ST_STOPPED;
             step++) {
            drive_seq_step(&seq, &ev, &out);
            print_step(&seq, &out);
            if (out.actions & DRIVE_ACT_LOAD) { /* the vehicle gets where it was sent */
                fx_q16_t sp;
                (void)drive_path_target(path, seq.target, &here, &sp);
            }
            /* The next event the world would raise. */
            ev.pose = here;
            drive_state_t s = seq.state;
            if (step % 7u == 3u) {
                ev.type = (drive_evt_t)(spurious++ % DRIVE_EVT_COUNT);
                if (ev.type == DRIVE_EVT_STOP && m != 3u)
                    ev.type = DRIVE_EVT_START;
            } else if (m == 3u && step == 40u) {
                ev.type = DRIVE_EVT_STOP;
            } else if (s == DRIVE_ST_F_FIX || s == DRIVE_ST_S_FIX) {
                ev.type = (m == 2u || step % 5u == 0u) ? DRIVE_EVT_FIX_FAILED : DRIVE_EVT_FIX_READY;
            } else if (s == DRIVE_ST_F_START || s == DRIVE_ST_F_PREDICT) {
                ev.type = DRIVE_EVT_POSE;
            } else if (s == DRIVE_ST_S_SKIP_INDEX || s == DRIVE_ST_S_WAIT_INDEX ||
                       s == DRIVE_ST_F_WAIT_INDEX) {
                ev.type = DRIVE_EVT_INDEX;
            } else if (s == DRIVE_ST_F_SETTLE || (s == DRIVE_ST_F_LOAD && step % 3u != 0u)) {
                ev.type = DRIVE_EVT_TIMER;
            } else {
                ev.type = DRIVE_EVT_DELTA_S;
            }
        }
    }
}

/* The seed's typical run (thesis table 6-1, inches) as a path, prepared and driven through
 * the state table with the vehicle placed exactly on each pose it is asked for. */
#define IN(v) ((int32_t)((v)*1664.6016)) /* inches to Q16 metres (0.0254 * 65536) */
static drive_path_point_t pts[6];

/* Paths that preparation refuses, each with where and why, and the cursor calls that must
 * refuse; the seed path (pts, start, cfg) is spoilt one way at a time. */
static void path_refusals(const drive_pose_t *start, const drive_path_config_t *good)
{
    drive_path_point_t p[6];
    drive_path_t path;
    for (uint8_t k = 0; k < 17u; k++) {
        drive_path_config_t cfg = *good;
        drive_board_t b = board;
        const drive_pose_t *s = start;
        drive_path_point_t *q = p;
        uint8_t n = 6;
        for (uint8_t i = 0; i < 6u; i++)
            p[i] = pts[i];
        switch (k) {
        case 0:
            s = NULL;
            break;
        case 1:
            q = NULL;
            break;
        case 2:
            n = 0;
            break;
        case 3:
            n = 255;
            break;
        case 4:
            cfg.nominal_radius = b.min_radius - 1;
            break;
        case 5:
            cfg.nominal_radius = DRIVE_MIN_RADIUS_MAX + 1;
            break;
        case 6:
            b.min_radius = DRIVE_MIN_RADIUS_MIN - 1;
            cfg.nominal_radius = b.min_radius;
            break;
        case 7:
            cfg.spacing = FX_Q16_ONE / 20 - 1;
            break;
        case 8:
            cfg.spacing = 8 * FX_Q16_ONE + 1;
            break;
        case 9:
            p[4].speed = 0;
            break;
        case 10:
            p[0].speed = 5 * FX_Q16_ONE;
            break;
        case 11:
            p[2].pose.heading += 1431655765u;
            break; /* 120 degrees */
        case 12:
            p[3].pose = p[2].pose;
            p[3].pose.x -= FX_Q16_ONE;
            break; /* behind */
        case 13:
            cfg.nominal_radius = 3 * FX_Q16_ONE / 2;
            break; /* too tight */
        case 14:
            p[5].pose.x += 5 * FX_Q16_ONE / 2;
            cfg.spacing = 8 * FX_Q16_ONE;
            break;
        case 15:
            p[5].pose.x += 14 * FX_Q16_ONE;
            cfg.spacing = FX_Q16_ONE / 20;
            break;
        default:
            b.speed_lsb = 0;
            break;
        }
        drive_status_t st = drive_path_prepare(&path, s, q, n, &cfg, &b);
        cy_print("refuse ");
        cy_print_dec(k);
        cy_print(" ");
        cy_print_dec((int32_t)st);
        cy_print(path.ready ? " ready" : " not-ready");
        if (st != DRIVE_OK) {
            cy_print(" ");
            cy_print_dec(path.bad_leg);
            cy_print(" ");
            cy_print_dec(path.bad_sub);
            cy_print(" ");
            cy_print_dec((int32_t)path.bad_why);
        }
        cy_println();
    }
    /* The cursor calls on a ready path and on a refused one. */
    cy_print("prepare-null ");
    cy_print_dec((int32_t)drive_path_prepare(NULL, start, p, 6, good, &board));
    cy_println();
    for (uint8_t r = 0; r < 2u; r++) {
        drive_path_config_t cfg = *good;
        if (r)
            cfg.spacing = 0;
        (void)drive_path_prepare(&path, start, p, 6, &cfg, &board);
        static const drive_path_cursor_t curs[6] = {{0, 0}, {0, 1}, {0, 9},
                                                    {5, 2}, {6, 1}, {255, 1}};
        for (uint8_t i = 0; i < 6u; i++) {
            drive_pose_t tp = {0, 0, 0};
            fx_q16_t sp = 0;
            const drive_leg_t *leg = NULL;
            cy_print("cursor ");
            cy_print_dec(r);
            cy_print(" ");
            cy_print_dec(i);
            cy_print(" ");
            cy_print_dec((int32_t)drive_path_target(&path, curs[i], &tp, &sp));
            out_hex((uint32_t)tp.x);
            out_hex((uint32_t)sp);
            cy_print(" ");
            cy_print_dec((int32_t)drive_path_leg(&path, curs[i].leg, &leg));
            if (leg != NULL)
                out_hex((uint32_t)leg->sol[0].seg[0].length);
            if (curs[i].leg < 6u) {
                drive_path_cursor_t nx = drive_path_next(&path, curs[i]);
                cy_print(drive_path_is_last(&path, curs[i]) ? " last " : " more ");
                cy_print_dec(nx.leg);
                cy_print(" ");
                cy_print_dec(nx.sub);
            }
            cy_println();
        }
    }
    cy_print("leg-null ");
    cy_print_dec((int32_t)drive_path_leg(NULL, 0, NULL));
    cy_println();
}

/* The rarer rows: arriving at once, no double arc to any target, a target the path cannot
 * give (its preparation redone and refused under way), a loaded double arc that ends while
 * the next waits (underrun). */
static void seq_edges(drive_path_t *path, const drive_pose_t *start, const drive_path_config_t *cfg)
{
    static const drive_seq_config_t full = {DRIVE_MODE_FULL, 35, 50, 9830, 26214, 3, 524288l};
    for (uint8_t k = 0; k < 4u; k++) {
        (void)drive_path_prepare(path, start, pts, 6, cfg, &board);
        drive_seq_t seq;
        drive_seq_init(&seq, path, &full);
        drive_seq_event_t ev = {DRIVE_EVT_START, *start};
        drive_seq_out_t out;
        drive_seq_step(&seq, &ev, &out);
        print_step(&seq, &out);
        ev.type = DRIVE_EVT_POSE;
        if (k == 0) {
            ev.pose = pts[5].pose; /* already at the last point */
        } else if (k == 1) {
            ev.pose.x += 2000l * FX_Q16_ONE; /* every target too far */
        } else if (k == 2) {
            drive_path_config_t bad = *cfg;
            bad.spacing = 0;
            (void)drive_path_prepare(path, start, pts, 6, &bad, &board);
        }
        drive_seq_step(&seq, &ev, &out);
        print_step(&seq, &out);
        for (uint8_t i = 0; k == 3u && i < 3u; i++) { /* the loaded arc ends while settling */
            ev.type = DRIVE_EVT_DELTA_S;
            drive_seq_step(&seq, &ev, &out);
            print_step(&seq, &out);
        }
    }
}

/* A path with turns over 90 degrees (the unit test's aisles: two U-turns, a 120-degree
 * corner), prepared, every target printed, and driven through the state table. */
static void aisle_vectors(void)
{
    static const int32_t mm[7][3] = {{6000, 0, 0},     {6000, 2400, 180}, {0, 2400, 180},
                                     {0, 4800, 0},     {6000, 4800, 0},   {7500, 6500, 120},
                                     {6500, 8232, 120}};
    static drive_path_point_t aisle[7];
    for (uint8_t i = 0; i < 7u; i++) {
        aisle[i].pose.x = (fx_q16_t)(((int64_t)mm[i][0] << 16) / 1000);
        aisle[i].pose.y = (fx_q16_t)(((int64_t)mm[i][1] << 16) / 1000);
        aisle[i].pose.heading =
            mm[i][2] == 180 ? FX_ANGLE_HALF : (fx_angle_t)(mm[i][2] * 11930465l);
        aisle[i].speed = 32768;
    }
    drive_pose_t start = {0, 0, 0};
    drive_path_config_t cfg = {39322 /* 0.6 m */, 52429 /* 0.8 m */, false};
    drive_path_t path;
    drive_status_t st = drive_path_prepare(&path, &start, aisle, 7, &cfg, &board);
    cy_print("aisle ");
    cy_print_dec((int32_t)st);
    for (uint8_t i = 0; i < 7u; i++) {
        cy_print(" ");
        cy_print_dec(aisle[i].nsub);
    }
    cy_println();
    for (drive_path_cursor_t c = drive_path_first(&path);; c = drive_path_next(&path, c)) {
        drive_pose_t tp;
        fx_q16_t sp;
        st = drive_path_target(&path, c, &tp, &sp);
        cy_print("aisle-target ");
        cy_print_dec(c.leg);
        cy_print(" ");
        cy_print_dec(c.sub);
        cy_print(" ");
        cy_print_dec((int32_t)st);
        out_hex((uint32_t)tp.x);
        out_hex((uint32_t)tp.y);
        out_hex(tp.heading);
        cy_println();
        if (drive_path_is_last(&path, c))
            break;
    }
    seq_vectors(&path, &start);
    /* Too narrow for its U-turns: refused at the first one. */
    cfg.nominal_radius = 85197; /* 1.3 m */
    st = drive_path_prepare(&path, &start, aisle, 7, &cfg, &board);
    cy_print("aisle-narrow ");
    cy_print_dec((int32_t)st);
    cy_print(" ");
    cy_print_dec(path.bad_leg);
    cy_print(" ");
    cy_print_dec((int32_t)path.bad_why);
    cy_println();
}

static void path_vectors(void)
{
    static const int16_t seed[7][3] = {{36, 142, 270}, {42, 108, 300}, {36, 60, 270}, {48, 36, 315},
                                       {72, 30, 0},    {108, 30, 0},   {144, 30, 0}};
    drive_pose_t start = {IN(seed[0][0]), IN(seed[0][1]), (fx_angle_t)(270ul * 11930465ul)};
    for (uint8_t i = 0; i < 6u; i++) {
        pts[i].pose.x = IN(seed[i + 1][0]);
        pts[i].pose.y = IN(seed[i + 1][1]);
        pts[i].pose.heading = (fx_angle_t)((uint32_t)seed[i + 1][2] * 11930465ul);
        pts[i].speed = 32768; /* 0.5 m/s */
    }
    drive_path_config_t cfg = {26214 /* 0.4 m */, 52429 /* 0.8 m */, false};
    drive_path_t path;
    drive_status_t st = drive_path_prepare(&path, &start, pts, 6, &cfg, &board);
    cy_print("path ");
    cy_print_dec((int32_t)st);
    for (uint8_t i = 0; i < 6u; i++) {
        cy_print(" ");
        cy_print_dec(pts[i].nsub);
    }
    cy_println();
    path_refusals(&start, &cfg);
    st = drive_path_prepare(&path, &start, pts, 6, &cfg, &board);
    drive_path_cursor_t c = drive_path_first(&path);
    for (;;) {
        drive_pose_t tp;
        fx_q16_t sp;
        st = drive_path_target(&path, c, &tp, &sp);
        cy_print("target ");
        cy_print_dec(c.leg);
        cy_print(" ");
        cy_print_dec(c.sub);
        cy_print(" ");
        cy_print_dec((int32_t)st);
        out_hex((uint32_t)tp.x);
        out_hex((uint32_t)tp.y);
        out_hex(tp.heading);
        cy_println();
        if (drive_path_is_last(&path, c))
            break;
        c = drive_path_next(&path, c);
    }
    seq_vectors(&path, &start);
    seq_edges(&path, &start, &cfg);

    /* The same path tail first, and a path that is not ready. */
    drive_pose_t bstart = start;
    bstart.heading += FX_ANGLE_HALF;
    for (uint8_t i = 0; i < 6u; i++)
        pts[i].pose.heading += FX_ANGLE_HALF;
    cfg.reverse = true;
    st = drive_path_prepare(&path, &bstart, pts, 6, &cfg, &board);
    cy_print("path-reverse ");
    cy_print_dec((int32_t)st);
    cy_println();
    seq_vectors(&path, &bstart);
    cfg.spacing = 1; /* out of range */
    (void)drive_path_prepare(&path, &bstart, pts, 6, &cfg, &board);
    seq_vectors(&path, &bstart);
    aisle_vectors();
}

int main(void)
{
    cy_bench_init();
    solver_vectors();
    solver_anywhere();
    pose_vectors();
    leg_vectors();
    cmd_edges();
    proto_vectors();
    path_vectors();
    cy_bench_report(&st_solve);
    cy_bench_report(&st_cmd);
    cy_bench_report(&st_wide);
    cy_bench_report(&st_leg);
    cy_stack_report(&sk_solve);
    cy_stack_report(&sk_cmd);
    if (!cy_kernel_check_mode()) /* (a check image runs both sides of every fx kernel) */
        cy_check(st_solve.max <= 20000u, "doublearc within 20,000 cycles (0 on the host)");
    cy_test_end();
    return 0;
}
