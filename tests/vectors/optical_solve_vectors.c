/*
 * optical_solve_vectors.c - firmware/optical's solve on both worlds: the triangulation kernels
 * (optical_tri_core, optical_tri_quality) on offsets of every span and at the edges of their
 * ranges, optical_triangulate on random geometries, O7's selection on random and tied sets, and
 * the three-reflector mode on seed 004's example and variants. One line per result (hex),
 * compared line by line between the host build and the MSP430 image: bit-identical results.
 * (optical_vectors.c: capture, identification and the fix.) On the target also the cycle
 * report (build/msp430/cycles.json) of the kernels and of optical_select.
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cy_test.h"
#include "fx/fx.h"
#include "optical/fastmath.h"
#include "optical/optical.h"
#include "optical/reflectors3.h"
#include "optical_vectors.h"

#ifdef __MSP430__
#include "hal/cpu.h"
#else
#include "hal_posix/harness.h"
#endif

/* The inscribed angles alpha1, alpha2 at which a vehicle at @p p (relative to beacon 2) sees
 * the beacons at offsets @p v (fx_atan2). */
static void seen_from(const int32_t v[4], const int32_t p[2], fx_angle_t *a1, fx_angle_t *a2)
{
    fx_angle_t h2 = fx_atan2(-p[1], -p[0]);
    *a1 = h2 - fx_atan2(v[1] - p[1], v[0] - p[0]);
    *a2 = fx_atan2(v[3] - p[1], v[2] - p[0]) - h2;
}

/* The triangulation kernels on one case, printed; timed into @p core, @p qual (or not). */
static void tri_kernels(uint8_t t, int32_t v[4], fx_angle_t a1, fx_angle_t a2,
                        cy_bench_stat_t *core, cy_bench_stat_t *qual)
{
    int32_t sc[4];
    fx_sincos(a1, &sc[0], &sc[1]);
    fx_sincos(a2, &sc[2], &sc[3]);
    optical_tsol_t ts = {{0, 0}, {0, 0}, {0, 0, 0}, 0, 0};
    uint16_t t0 = cy_bench_now();
    int8_t st = optical_tri_core(v, sc, &ts);
    uint16_t t1 = cy_bench_now();
    if (core)
        cy_bench_add(core, (uint16_t)(t1 - t0));
    cy_print("tri ");
    cy_print_dec(t);
    cy_print(" ");
    cy_print_dec(st);
    for (uint8_t i = 0; i < 4; i++)
        field("v", (uint32_t)v[i]);
    if (st == OPTICAL_OK) {
        field("o", (uint32_t)ts.off[0]);
        field("o", (uint32_t)ts.off[1]);
        field("w", (uint32_t)ts.w[0]);
        field("w", (uint32_t)ts.w[1]);
        for (uint8_t i = 0; i < 3; i++)
            field("l", (uint32_t)ts.l[i]);
        field("r", ts.r);
        field("x", (uint32_t)(int32_t)ts.x);
        t0 = cy_bench_now();
        uint32_t q = optical_tri_quality(v, &ts);
        t1 = cy_bench_now();
        if (qual)
            cy_bench_add(qual, (uint16_t)(t1 - t0));
        field("q", q);
    }
    cy_println();
}

/* The triangulation kernels: beacon offsets from beacon 2 of every span (Q16), the inscribed
 * angles of a vehicle among them (fx_atan2) or random ones (near 0 and 180 degrees too: most
 * of them inconsistent or beyond the circles' range); the edges; the quality on solutions of
 * every scale. */
static void tri_core_cases(void)
{
    static cy_bench_stat_t st_core = {"optical_tri_core", 0, 0, 0};
    static cy_bench_stat_t st_qual = {"optical_tri_quality", 0, 0, 0};
    for (uint8_t t = 0; t < 120; t++) {
        int32_t v[4];
        static const uint32_t span[4] = {0x07FFFFFFu, 0x00FFFFFFu, 0x0003FFFFu, 0x00000FFFu};
        uint32_t lim = span[t & 3];
        for (uint8_t i = 0; i < 4; i++)
            v[i] = rnd_in(lim);
        if ((v[0] | v[1]) == 0 || (v[2] | v[3]) == 0 || (v[0] == v[2] && v[1] == v[3]))
            continue;
        fx_angle_t a1, a2;
        if (t % 3) {
            int32_t p[2] = {rnd_in(lim), rnd_in(lim)};
            seen_from(v, p, &a1, &a2);
        } else {
            a1 = rnd32();
            a2 = rnd32();
            if (t % 5 == 0)
                a1 = (fx_angle_t)rnd_in(3000) + (t & 8 ? 0x80000000u : 0u);
        }
        tri_kernels(t, v, a1, a2, &st_core, &st_qual);
    }
    /* And the edges (metres, Q16): a vehicle 20 and 3 times the beacons' span away, one on
     * their circle, one whose beacon 3 is sighted on the wrong side, offsets beyond 2048 m,
     * coincident beacons. */
    static const int32_t edge[6][6] = {
        {-2 * 65536l, 0, 2 * 65536l, 0, 19661, -40 * 65536l},
        {-2 * 65536l, 0, 2 * 65536l, 0, 19661, -6 * 65536l},
        {-5 * 65536l, 5 * 65536l, 5 * 65536l, 5 * 65536l, 3 * 65536l, 9 * 65536l},
        {-5 * 65536l, 5 * 65536l, 5 * 65536l, 5 * 65536l, 65536l, -3 * 65536l},
        {1l << 27, 0, 5 * 65536l, 5 * 65536l, 65536l, -3 * 65536l},
        {-5 * 65536l, 5 * 65536l, -5 * 65536l, 5 * 65536l, 65536l, -3 * 65536l}};
    for (uint8_t t = 0; t < 6; t++) {
        int32_t v[4] = {edge[t][0], edge[t][1], edge[t][2], edge[t][3]};
        fx_angle_t a1, a2;
        seen_from(v, &edge[t][4], &a1, &a2);
        if (t == 3)
            a2 += 0x80000000u;
        tri_kernels((uint8_t)(200u + t), v, a1, a2, NULL, NULL);
    }
    /* optical_tri_quality on solutions of every scale (on a random stream of its own): the
     * offsets scaled as the core leaves them, ranges of 2^0 to 2^30 (down to where the
     * common shift is 16 bits), R' in [2^29, 2^30], exponents that saturate or reach 0. */
    uint32_t rng_kept = rng;
    for (uint8_t t = 0; t < 40; t++) {
        int32_t v[4];
        for (uint8_t i = 0; i < 4; i++)
            v[i] = rnd_in(0x0FFFFFFFu);
        v[t & 3u] = (t & 4u) ? -(int32_t)0x10000000 - rnd_in(0x07FFFFFFu) - 0x08000000
                             : (int32_t)0x10000000 + rnd_in(0x07FFFFFFu) + 0x08000000;
        optical_tsol_t ts = {{0, 0}, {0, 0}, {0, 0, 0}, 0, 0};
        uint8_t k = (uint8_t)(t < 31u ? t : rnd32() % 31u); /* the largest range: 2^k */
        for (uint8_t i = 0; i < 3; i++) {
            uint32_t m = (1ul << k) + (rnd32() & ((1ul << k) - 1u));
            if (i != t % 3u)
                m >>= rnd32() % 8u;
            ts.l[i] = (t & 8u) ? -(int32_t)m : (int32_t)m;
        }
        ts.r = 0x20000000u + rnd32() % 0x20000001u;
        ts.x = (int8_t)rnd_in(60);
        cy_print("triq ");
        cy_print_dec(t);
        field("x", (uint32_t)(int32_t)ts.x);
        field("q", optical_tri_quality(v, &ts));
        cy_println();
    }
    rng = rng_kept;
    cy_bench_report(&st_core);
    cy_bench_report(&st_qual);
}

static void reflectors(void)
{
    /* Seed 004: A(0,21), B(13,21), C(13,0) ft; reflections 1.0556, 2.3628, 2.8508 s after the
     * click, next click at 4 s (ticks of 100 us); and variants: a missing reflection, a late
     * click, the field given, a goal. */
    static const optical_xy_t refl[3] = {{0, 21l << 16}, {13l << 16, 21l << 16}, {13l << 16, 0}};
    static const optical_xy_t fld[4] = {
        {0, 0}, {13l << 16, 0}, {13l << 16, 21l << 16}, {0, 21l << 16}};
    static const uint32_t t[3] = {10556u, 23628u, 28508u};
    static const uint32_t tw[3] = {0xFFFFB1E0ul + 10556u, 3628u, 8508u}; /* click - 20000 */
    optical_r3_config_t cfg = {NULL, 0, 40000u, 2000u, OPTICAL_QUALITY_LIMIT};
    optical_r3_t r;
    for (uint8_t v = 0; v < 5; v++) {
        int8_t st;
        cfg.field = v == 2 ? fld : NULL;
        cfg.n_field = v == 2 ? 4 : 0;
        if (v == 1)
            st = optical_r3_fix(refl, 0, t, 2, 40000u, &cfg, NULL, &r);
        else if (v == 3)
            st = optical_r3_fix(refl, 0, t, 3, 44000u, &cfg, NULL, &r);
        else if (v == 4) /* the timer wraps during the revolution */
            st = optical_r3_fix(refl, 0xFFFFB1E0ul, tw, 3, 20000u, &cfg, NULL, &r);
        else
            st = optical_r3_fix(refl, 0, t, 3, 40000u, &cfg, NULL, &r);
        cy_print("r3 ");
        cy_print_dec(v);
        cy_print(" st ");
        cy_print_dec(st);
        pose_fields(&r.pose);
        cy_print(" first ");
        cy_print_dec(r.first);
        cy_print(" cand ");
        cy_print_dec(r.n_cand);
        if (st == OPTICAL_R3_OK) {
            static const optical_xy_t plug = {0, 688128l}; /* (0, 10.5) */
            uint32_t d;
            fx_angle_t turn;
            optical_r3_goal(&r.pose, &plug, &d, &turn);
            field("d", d);
            field("t", turn);
        }
        cy_println();
    }
}

/*
 * O7's selection (select.c) on random sets of 0 to 15
 * angles: sorted on the 50,000-count grid, on a coarse grid (tied gaps), with high words
 * tied (gaps within 2^16), unsorted (gaps modulo a turn, some near 2^32), all equal.
 */
static void selections(void)
{
    static cy_bench_stat_t st_sel = {"optical_select", 0, 0, 0};
    fx_angle_t a[OPTICAL_MAX_SIGHTINGS];
    for (uint16_t t = 0; t < 400; t++) {
        uint8_t n = (uint8_t)(t < 16 ? t : 4u + rnd32() % 12u), kind = (uint8_t)(t % 6u);
        for (uint8_t i = 0; i < n; i++) {
            uint32_t r = rnd32();
            a[i] = kind == 0   ? fx_angle_from_counts(r % 50000u, 50000u)
                   : kind == 1 ? (r % 24u) << 27
                   : kind == 2 ? 0x12340000u + (r % 8u) * 0x8000u + (r >> 29)
                   : kind == 3 ? r
                   : kind == 4 ? 0x40000000u - (r % 4u)
                               : (r % 16u) << 28;
        }
        if (kind != 3 && kind != 4)
            for (uint8_t i = 1; i < n; i++) /* ascending */
                for (uint8_t j = i; j > 0 && a[j] < a[j - 1u]; j--) {
                    fx_angle_t x = a[j];
                    a[j] = a[j - 1u];
                    a[j - 1u] = x;
                }
        uint8_t keep[3];
        CY_BENCH(&st_sel, optical_select(a, n, keep));
        cy_print("sel ");
        cy_print_dec(t);
        cy_print(" ");
        cy_print_dec(n);
        for (uint8_t i = 0; i < 3; i++) {
            cy_print(" ");
            cy_print_dec(keep[i]);
        }
        cy_println();
    }
    cy_bench_report(&st_sel);
}

/*
 * optical_triangulate (triangulate.c, on the kernels of tri_k.c): random beacons and
 * vehicles (every O8 ordering and both sides of the circle, some 3 to 39 times farther out),
 * random angles (mostly refused), coincident sightings and beacons, a tight quality limit;
 * then vehicles straight and diagonally off the middle beacon, where |U^| reaches the ends of
 * the reciprocal's range (Q near 2^22 on an axis, larger on a diagonal).
 */
static void triangulations(void)
{
    for (uint16_t t = 0; t < 224; t++) {
        optical_xy_t b[3];
        static const uint32_t span[3] = {0x003FFFFFu, 0x000FFFFFu, 0x0000FFFFu};
        uint32_t lim = span[t % 3u];
        for (uint8_t i = 0; i < 3; i++) {
            b[i].x = rnd_in(lim);
            b[i].y = rnd_in(lim);
        }
        fx_angle_t th[3];
        int32_t px = rnd_in(lim), py = rnd_in(lim);
        if (t % 4u == 1u) { /* far away: near the circles' range limit */
            px *= (int32_t)(3u + t % 37u);
            py *= (int32_t)(3u + t % 37u);
        }
        if (t >= 200u) { /* beacons (-5, 3), (0, 8), (5, 3) m; the vehicle 1 to 7 m off */
            static const int8_t dir[8][2] = {{0, -1}, {-1, 0},  {1, 0}, {0, 1},
                                             {1, -1}, {-1, -1}, {1, 1}, {-1, 1}};
            const int8_t *d = dir[t % 8u];
            int32_t k = (int32_t)(1u + (t - 200u) / 8u * 2u) * 65536;
            b[0].x = -5l * 65536;
            b[0].y = b[2].y = 3l * 65536;
            b[1].x = 0;
            b[1].y = 8l * 65536;
            b[2].x = 5l * 65536;
            px = d[0] * k + (t & 1u);
            py = d[1] * k;
        }
        fx_angle_t head = rnd32();
        for (uint8_t i = 0; i < 3; i++)
            th[i] = t % 7u == 6u && t < 200u ? rnd32() : fx_atan2(b[i].y - py, b[i].x - px) - head;
        if (t % 11u == 3u && t < 200u)
            th[2] = th[(t >> 4) & 1u];
        if (t % 13u == 5u && t < 200u)
            b[1] = b[0];
        uint32_t qmax = t % 5u == 4u ? 20000u : OPTICAL_QUALITY_LIMIT;
        optical_tri_t r = {{0, 0, 0}, 0};
        int8_t st = optical_triangulate(b, th, qmax, &r);
        cy_print("trg ");
        cy_print_dec(t);
        cy_print(" ");
        cy_print_dec(st);
        pose_fields(&r.pose);
        field("q", r.quality);
        cy_println();
    }
}

int main(void)
{
#ifdef __MSP430__
    hal_cpu_init();
#else
    posix_reset();
    posix_board_select(posix_board_create("main"));
#endif
    cy_bench_init();
    cy_print("# optical solve vectors\n");
    tri_core_cases();
    triangulations();
    selections();
    reflectors();
    cy_test_end();
    return 0;
}
