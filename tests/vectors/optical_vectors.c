/*
 * optical_vectors.c - firmware/optical on both worlds: recorded revolutions
 * (optical_vectors_data.h, from gen_optical_vectors.py) through the capture handlers, the
 * revolution conversion and the fix; the three-reflector mode on seed 004's example and
 * variants. One line per result (hex), compared line by line between the host build and the
 * MSP430 image: bit-identical fixes.
 *
 * On the target also the cycle report (build/msp430/cycles.json): optical_fix on the
 * benchmark revolution (15 sightings, 32-beacon map; standing and driving), its parts, and the
 * two capture interrupts through the real vectors and HAL shims (isr_index_pulse,
 * isr_sighting). The floors (ISR <= 150 cycles, fix <= 20,000) are checked here.
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cy_test.h"
#include "fx/fx.h"
#include "optical/capture.h"
#include "optical/fastmath.h"
#include "optical/glue.h"
#include "optical/optical.h"
#include "optical/reflectors3.h"
#include "optical_vectors_data.h"

/* The cycles optical_fix may take on the benchmark revolution: SPEC's floor (15 sightings,
 * a 32-beacon map). */
#define OPTICAL_FIX_CYCLE_BOUND 20000ul

#ifdef __MSP430__
#include "f2618.h"
#include "hal/capture.h"
#include "hal/cpu.h"
#include "hal/irq.h"
#else
#include "hal_posix/harness.h"
#endif

static optical_capture_t cap;
static optical_sighting_t sight[OPTICAL_MAX_SIGHTINGS];
static optical_fix_t fix;

/* The latched poses of the recorded revolutions, or the map of the kernel checks (2 KB of
 * RAM: never both at once). */
static union {
    optical_pose_t lat[OPTICAL_MAX_SIGHTINGS];
    optical_xy_t kmap[OPTICAL_MAX_BEACONS];
} U;
#define lat  (U.lat)
#define kmap (U.kmap)
#define KW   (optical_work)

static void field(const char *label, uint32_t v)
{
    cy_print(" ");
    cy_print(label);
    cy_print_hex32(v);
}

/* A pose's fields, as field() prints them. */
static void pose_fields(const optical_pose_t *p)
{
    field("x", (uint32_t)p->x);
    field("y", (uint32_t)p->y);
    field("h", p->heading);
}

static void config(uint8_t variant, optical_config_t *cfg)
{
    optical_config_default(cfg);
    if (variant == 1) {           /* approximate pose within 5 degrees and 0.3 m */
        cfg->window = 63230463ul; /* 5.3 degrees */
        cfg->window_pos = 21627;  /* 0.33 m */
    }
}

/* Feed case @p i's recorded edges to the capture handlers and hand out the revolution. */
static const optical_rev_t *capture_case(uint8_t i)
{
    const vec_case_t *c = &vec_cases[i];
    optical_capture_init(&cap);
    optical_capture_start(&cap);
    for (uint8_t e = 0; e < c->n_events; e++) {
        const vec_event_t *ev = &vec_events[c->first_event + e];
        if (ev->channel == 0)
            optical_capture_on_index(&cap, ev->count, 1);
        else
            optical_capture_on_edge(&cap, ev->count, ev->rising);
    }
    return optical_capture_take(&cap);
}

/* Compiled maps: the cases' (run_case) and the kernels' (kcompile), one at a time. */
static optical_xy8_t kmap8[OPTICAL_MAX_BEACONS];

/* The fix of case @p i; the sightings in sight[], their count returned (-1: bad revolution). */
static int8_t run_case(uint8_t i, optical_config_t *cfg, optical_map_t *map, optical_pose_t *ap,
                       const optical_pose_t **latched)
{
    const vec_case_t *c = &vec_cases[i];
    const optical_rev_t *rev = capture_case(i);
    int8_t n = rev ? optical_rev_sightings(rev, 50000u, sight) : -1;
    if (rev)
        optical_capture_release(&cap);
    config(c->cfg, cfg);
    if (!optical_map_compile(map, &vec_beacons[vec_maps[c->map].first], vec_maps[c->map].n, kmap8))
        cy_check(false, "case map compiles");
    ap->x = c->approx.x;
    ap->y = c->approx.y;
    ap->heading = c->approx.h;
    *latched = NULL;
    if (c->moving && n > 0) {
        /* The latched poses belong to the sightings in time order, i.e. capture order; the
         * conversion sorts by angle, which is the same order within one revolution here. */
        for (int8_t k = 0; k < n; k++) {
            lat[k].x = vec_latched[c->first_latched + k].x;
            lat[k].y = vec_latched[c->first_latched + k].y;
            lat[k].heading = vec_latched[c->first_latched + k].h;
        }
        *latched = lat;
    }
    return n;
}

static void fixes(void)
{
    for (uint8_t i = 0; i < VEC_N_CASES; i++) {
        optical_config_t cfg;
        optical_map_t map;
        optical_pose_t ap;
        const optical_pose_t *latched;
        int8_t n = run_case(i, &cfg, &map, &ap, &latched);
        cy_print("fix ");
        cy_print_dec(i);
        cy_print(" n ");
        cy_print_dec(n);
        for (int8_t k = 0; k < n; k++) {
            field("a", sight[k].angle);
            field("w", sight[k].width);
        }
        if (n < 0) {
            cy_println();
            continue;
        }
        int8_t st = optical_fix(&map, &cfg, &ap, sight, (uint8_t)n, latched, &fix);
        cy_print(" st ");
        cy_print_dec(st);
        pose_fields(&fix.pose);
        field("q", fix.quality);
        cy_print(" used");
        for (uint8_t k = 0; k < 3; k++) {
            cy_print(" ");
            cy_print_dec(st == OPTICAL_OK ? fix.used[k] : -1);
        }
        cy_print(" id");
        for (int8_t k = 0; k < n; k++) {
            cy_print(" ");
            cy_print_dec(fix.ident[k]);
        }
        cy_println();
        /* Accepted fixes of the recorded revolutions lie within 5 cm of the truth. */
        if (st == OPTICAL_OK) {
            int32_t dx = fix.pose.x - vec_cases[i].truth.x, dy = fix.pose.y - vec_cases[i].truth.y;
            cy_check(fx_hypot(dx, dy) < 3277u, "accepted fix within 5 cm of the truth");
        }
    }
}

static uint32_t rng = 0x2545F491u;

static uint32_t rnd32(void)
{
    return cy_rand32(&rng);
}

/* A random int32 of random magnitude and sign. */
static int32_t rnd_mag(void)
{
    uint32_t v = rnd32() >> (rnd32() & 31u);
    return (rnd32() & 1u) ? (int32_t)(0u - v) : (int32_t)v;
}

/* The two helpers of fastmath.h (assembly on the target): edge cases, then random. */
static void helpers(void)
{
    static const int32_t edge[] = {0,
                                   1,
                                   -1,
                                   2,
                                   32767,
                                   32768,
                                   -32768,
                                   65535,
                                   65536,
                                   0x7FFFFFFFl,
                                   -0x7FFFFFFFl - 1,
                                   0x40000000l,
                                   -0x40000000l};
    const uint8_t ne = sizeof edge / sizeof edge[0];
    for (uint16_t t = 0; t < 400u + ne * ne; t++) {
        int32_t x, y;
        if (t < ne * ne) {
            x = edge[t / ne];
            y = edge[t % ne];
        } else {
            x = rnd_mag();
            y = rnd_mag();
        }
        cy_print("a16 ");
        cy_print_hex32((uint32_t)x);
        cy_print(" ");
        cy_print_hex32((uint32_t)y);
        cy_print(" ");
        cy_print_hex16(optical_angle16(x, y));
        cy_println();
    }
}

/* A random int32 in [-lim, lim]. */
static int32_t rnd_in(uint32_t lim)
{
    return (int32_t)(rnd32() % (2u * lim + 1u)) - (int32_t)lim;
}

static void print_marks(void)
{
    cy_print(" sm");
    for (uint8_t j = 0; j < KW.n; j++) {
        cy_print(" ");
        cy_print_dec(KW.sm[j]);
        if (KW.sm[j] < OPTICAL_DROPPED) {
            cy_print(":");
            cy_print_hex16(KW.we[j]);
        }
    }
    cy_print(" bm");
    for (uint8_t k = 0; k < KW.nb; k++) {
        cy_print(" ");
        cy_print_dec(KW.u.id.bm[k]);
    }
}

/* One scan's results (optical_expect_scan, optical_first_scan), printed. */
static void print_scan(const char *what, uint8_t t, uint8_t st)
{
    cy_print(what);
    cy_print_dec(t);
    cy_print(" st ");
    cy_print_dec(st);
    for (uint8_t k = 0; k < KW.nb && !st; k++) {
        cy_print(" ");
        if (KW.u.id.e[k] == 0) {
            cy_print("-");
            continue;
        }
        cy_print_hex16(KW.u.id.psi[k]);
        cy_print(":");
        cy_print_hex16(KW.u.id.e[k]);
        if (KW.lever8) { /* (standing: g is not stored) */
            cy_print(":");
            cy_print_hex16(KW.u.id.g[k]);
        }
    }
    print_marks();
    cy_print(" nc ");
    cy_print_dec(KW.nc);
    for (uint8_t c = 0; c < KW.nc && KW.nc != 0xFFu; c++) {
        cy_print(" ");
        cy_print_dec(KW.u.id.cand[2 * c]);
        cy_print("/");
        cy_print_dec(KW.u.id.cand[2 * c + 1]);
    }
    cy_println();
}

/* A hash of one scan's results (the marks, the windows, the pairs). */
static uint32_t scan_hash(void)
{
    uint32_t h = KW.nc;
    for (uint8_t j = 0; j < KW.n; j++)
        h = h * 31u + KW.sm[j] + (KW.sm[j] < OPTICAL_DROPPED ? (uint32_t)KW.we[j] << 8 : 0u);
    for (uint8_t k = 0; k < KW.nb; k++)
        h = h * 31u + KW.u.id.bm[k] + ((uint32_t)KW.u.id.e[k] << 8) +
            (KW.u.id.e[k] ? (uint32_t)KW.u.id.psi[k] << 12 : 0u);
    for (uint8_t c = 0; KW.nc != 0xFFu && c < 2u * KW.nc; c++)
        h = h * 31u + KW.u.id.cand[c];
    return h;
}

/* The compiled form of kmap for the scan (KW.b8, KW.ox, KW.oy): the origin @p o (a multiple of
 * 2^8), every beacon first brought within its reach. */
static void kcompile(int32_t ox, int32_t oy)
{
    KW.b8 = kmap8;
    KW.ox = ox;
    KW.oy = oy;
    for (uint8_t k = 0; k < KW.nb; k++) {
        int32_t *v[2] = {&kmap[k].x, &kmap[k].y}, o[2] = {ox, oy};
        int16_t *v8[2] = {&kmap8[k].x, &kmap8[k].y};
        for (uint8_t c = 0; c < 2; c++) {
            int32_t d = *v[c] - o[c];
            d = d < -0x00800000l ? -0x00800000l : d > 0x007FFFFFl ? 0x007FFFFFl : d;
            *v[c] = o[c] + d;
            *v8[c] = (int16_t)(uint16_t)((uint32_t)d >> 8);
        }
    }
}

/* A random scene for the identification kernels: a map (some beacons near the vehicle, some
 * beyond the gate; compiled with an origin up to 128 m from the position, so that offsets up
 * to 2^16 units of 2^-8 m occur, and now and then beyond its reach), sightings near some
 * beacons' directions and elsewhere, moving or not. */
static void scene(uint8_t t)
{
    KW.b = kmap;
    uint32_t span = (t & 3) == 0 ? 0x01000000u : (t & 3) == 1 ? 0x00400000u : 0x00100000u;
    KW.x = rnd_in(span);
    KW.y = rnd_in(span);
    KW.nb = (uint8_t)(1u + rnd32() % OPTICAL_MAX_BEACONS);
    for (uint8_t k = 0; k < KW.nb; k++) {
        uint32_t r = (rnd32() & 7u) == 0 ? 0x8000u : span; /* some close */
        kmap[k].x = KW.x + rnd_in(r);
        kmap[k].y = KW.y + rnd_in(r);
    }
    uint32_t reach = (t % 8u == 5u) ? 0x00A00000u : 0x007FFF00u;
    int32_t ox = KW.x + rnd_in(reach); /* (one after the other: the same draws everywhere) */
    int32_t oy = KW.y + rnd_in(reach);
    kcompile((int32_t)((uint32_t)ox & ~(uint32_t)0xFFu),
             (int32_t)((uint32_t)oy & ~(uint32_t)0xFFu));
    KW.gate8 = (uint16_t)((rnd32() & 3u) ? 0x7FFFu : rnd32() % 0x8000u);
    KW.head = (uint16_t)rnd32();
    KW.eps8 = (uint16_t)(rnd32() % 200u);
    KW.lever8 = (t & 1) ? (uint16_t)(rnd32() % 300u) : 0u;
    uint32_t am = (uint32_t)KW.eps8 + KW.lever8;
    KW.amax8 = am > 0xFFFFu ? 0xFFFFu : (uint16_t)am;
    KW.n = (uint8_t)(rnd32() % (OPTICAL_MAX_SIGHTINGS + 1u));
    for (uint8_t j = 0; j < KW.n; j++) {
        uint16_t v = (uint16_t)rnd32();
        if (rnd32() & 1u) { /* near a beacon */
            const optical_xy_t *b = &kmap[rnd32() % KW.nb];
            v = (uint16_t)(optical_angle16(b->x - KW.x, b->y - KW.y) - KW.head + rnd_in(400));
        }
        uint8_t i = j; /* ascending */
        while (i > 0 && KW.th[i - 1] > v) {
            KW.th[i] = KW.th[i - 1];
            i--;
        }
        KW.th[i] = v;
    }
    for (uint8_t j = 0; j < KW.n; j++) {
        KW.sm[j] = (rnd32() & 7u) ? OPTICAL_NONE : OPTICAL_DROPPED;
        KW.lev[j] = KW.lever8 ? (uint16_t)(rnd32() % (KW.lever8 + 1u)) : 0u;
    }
    uint8_t j = 0;
    for (uint8_t b = 0; b < 16; b++) {
        while (j < KW.n && (KW.th[j] >> 12) < b)
            j++;
        KW.bstart[b] = j < KW.n ? j : 0;
    }
}

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

/* The identification kernels on random scenes, and the width check. */
static void kernels(void)
{
    static cy_bench_stat_t st_exs = {"optical_expect_scan_per_beacon", 0, 0, 0};
    static cy_bench_stat_t st_eval = {"optical_eval_per_pair", 0, 0, 0};
    static cy_bench_stat_t st_core = {"optical_tri_core", 0, 0, 0};
    static cy_bench_stat_t st_qual = {"optical_tri_quality", 0, 0, 0};
    static cy_bench_stat_t st_a16 = {"optical_angle16", 0, 0, 0};
    for (uint8_t t = 0; t < 60; t++) {
        scene(t);
        int16_t mid = (int16_t)rnd_in(600);
        uint16_t half = (uint16_t)(rnd32() % ((t & 7) == 7 ? 0x7000u : 1200u));
        uint8_t st;
        uint16_t t0 = cy_bench_now();
        st = optical_expect_scan(mid, half);
        uint16_t t1 = cy_bench_now();
        if ((t & 7) != 7 && !st)
            cy_bench_add(&st_exs, (uint16_t)(t1 - t0) / KW.nb);
        print_scan("exs ", t, st);
        if (st || KW.nc == 0xFFu)
            continue;
        half = (uint16_t)(half / 2u);
        mid = (int16_t)(mid + rnd_in(100));
        t0 = cy_bench_now();
        optical_eval(mid, half);
        t1 = cy_bench_now();
        if (KW.nc)
            cy_bench_add(&st_eval, (uint16_t)(t1 - t0) / KW.nc);
        cy_print("eval ");
        cy_print_dec(t);
        print_marks();
        cy_println();
    }
    cy_bench_report(&st_exs);
    cy_bench_report(&st_eval);
    /* optical_first_scan: the marks as optical_drop leaves them (the scene's NONE and
     * DROPPED), printed; optical_expect_scan must give the same after the marks were
     * scrambled (stale matches, MULTI: it clears them, DROPPED stays). On a random stream of
     * its own: the cases after it stay as they were. */
    uint32_t rng_saved = rng;
    for (uint8_t t = 0; t < 24; t++) {
        scene(t);
        int16_t mid = (int16_t)((t & 1) ? rnd_in(600) : 0);
        uint16_t half = (uint16_t)(rnd32() % ((t & 7) == 7 ? 0x7000u : 1200u));
        uint8_t sm0[OPTICAL_MAX_SIGHTINGS];
        for (uint8_t j = 0; j < KW.n; j++)
            sm0[j] = KW.sm[j];
        uint8_t st = optical_first_scan(mid, half);
        print_scan("exf ", t, st);
        if (st)
            continue;
        uint32_t h = scan_hash();
        for (uint8_t j = 0; j < KW.n; j++) {
            KW.sm[j] = sm0[j] == OPTICAL_DROPPED ? OPTICAL_DROPPED
                       : (rnd32() & 3u)          ? (uint8_t)(rnd32() % OPTICAL_MAX_BEACONS)
                                                 : OPTICAL_MULTI;
            KW.we[j] = (uint16_t)rnd32();
        }
        for (uint8_t k = 0; k < KW.nb; k++)
            KW.u.id.bm[k] = (uint8_t)rnd32();
        cy_check(optical_expect_scan(mid, half) == 0 && scan_hash() == h,
                 "first scan: the results of optical_expect_scan");
    }
    rng = rng_saved;
    /* The coordinate limit's edges: [-2^29, 2^29) is accepted. */
    /* The compiled map's reach: the position at, just within and just beyond +-128 m of the
     * origin on either axis (beyond: 1, nothing scanned), a beacon on each side. */
    static const int32_t reach_edge[5] = {-0x00800000l, -0x007FFFFFl, 0x007FFFFFl, 0x00800000l,
                                          -0x00800001l};
    for (uint8_t t = 0; t < 10; t++) {
        KW.nb = 2;
        KW.n = 0;
        KW.x = (t & 1) ? 0x10000l : reach_edge[t >> 1];
        KW.y = (t & 1) ? reach_edge[t >> 1] : -0x10000l;
        kmap[0].x = kmap[0].y = -0x7F0000l;
        kmap[1].x = kmap[1].y = 0x7F0000l;
        kcompile(0, 0);
        cy_print("reach ");
        cy_print_dec(t);
        cy_print(" ");
        cy_print_dec(optical_expect_scan(0, 100));
        for (uint8_t k = 0; k < 2; k++)
            field("", ((uint32_t)KW.u.id.psi[k] << 16) | KW.u.id.e[k]);
        cy_println();
    }
    /* The triangulation kernels: beacon offsets from beacon 2 of every span (Q16), the
     * inscribed angles of a vehicle among them (fx_atan2) or random ones (near 0 and 180
     * degrees too: most of them inconsistent or beyond the circles' range). */
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
    for (uint8_t t = 0; t < 50; t++) {
        volatile int32_t x = rnd_in(0x00200000u), y = rnd_in(0x00200000u);
        uint16_t t0 = cy_bench_now();
        (void)optical_angle16(x, y);
        uint16_t t1 = cy_bench_now();
        cy_bench_add(&st_a16, (uint16_t)(t1 - t0));
    }
    cy_bench_report(&st_a16);
    /* O4's drop: widths around the threshold, ranges from 0 to beyond 2^16 units of 2^-8 m */
    for (uint8_t t = 0; t < 60; t++) {
        uint32_t dk = 213000u + rnd32() % 1000000u, t8 = rnd32() % 20000u;
        if (t % 10 == 1)
            t8 = 0;
        else if (t % 10 == 2)
            t8 = 0x10000u + rnd32() % 0x01000000u;
        else if (t % 10 == 3)
            t8 = dk >> 16; /* the quotient just beyond 16 bits */
        else if (t % 10 == 4)
            dk = rnd32();
        uint32_t q = t8 ? dk / t8 : 0xFFFFu;
        KW.n = (uint8_t)(rnd32() % (OPTICAL_MAX_SIGHTINGS + 1u));
        for (uint8_t j = 0; j < KW.n; j++) {
            uint32_t w = q + (rnd32() % 5u) - 2u;
            sight[j].width = (rnd32() & 3u) == 0 ? (uint16_t)rnd32()
                             : w > 0xFFFFu       ? 0xFFFFu
                                                 : (uint16_t)w;
            KW.ord[j] = (uint8_t)((7u * j + t) % KW.n); /* (no draw: the stream as before) */
        }
        uint32_t wmin = optical_wmin(dk, t8);
        cy_print("drop ");
        cy_print_dec(t);
        cy_print(" ");
        cy_print_hex32(wmin);
        cy_print(" ");
        cy_print_dec(optical_drop(sight, wmin));
        for (uint8_t j = 0; j < KW.n; j++) {
            cy_print(" ");
            cy_print_dec(KW.sm[j]);
            cy_print(":");
            cy_print_dec(KW.wchk[j]);
        }
        cy_println();
    }
    for (uint16_t t = 0; t < 300; t++) {
        optical_width_t w;
        optical_xy_t b;
        w.dk = 213000u + rnd32() % 1000000u;
        w.x = rnd_in(0x00800000u);
        w.y = rnd_in(0x00800000u);
        uint32_t r = (t & 1) ? 0x00100000u : 0x02000000u;
        b.x = w.x + rnd_in(r);
        b.y = w.y + rnd_in(r);
        w.eps8 = (uint16_t)(rnd32() % 300u);
        w.tol8 = (uint16_t)(rnd32() % 300u);
        w.rel16 = (uint16_t)rnd32();
        w.flat = (uint8_t)(rnd32() & 1u);
        uint16_t w16 = (uint16_t)(rnd32() % ((t & 3) ? 400u : 9000u));
        cy_print("wok ");
        cy_print_dec(t);
        cy_print(" ");
        cy_print_dec(optical_width_ok(&w, &b, w16));
        cy_println();
    }
}

/* fix.c's glue kernels (optical/glue.h) on random work areas: the standing preparation and
 * its buckets, the both-ways uniqueness with its O5 checks and narrowing, the gather. */
static void print_work(uint8_t n)
{
    for (uint8_t j = 0; j < n; j++) {
        cy_print(" ");
        cy_print_dec(KW.sm[j]);
        cy_print(":");
        cy_print_dec(KW.wchk[j]);
    }
}

static void glue_kernels(void)
{
    for (uint8_t t = 0; t < 40; t++) {
        KW.n = (uint8_t)(rnd32() % (OPTICAL_MAX_SIGHTINGS + 1u));
        for (uint8_t i = 0; i < KW.n; i++) {
            /* ascending with ties, some near the wrap, some out of order */
            uint32_t a = (t & 1) ? (uint32_t)i << 28 : rnd32();
            if (t % 5 == 2)
                a = 0xFFFF7000u + (rnd32() & 0x1FFFu);
            else if (t % 5 == 3)
                a = (rnd32() & 3u) << 16 | 0x7FFFu;
            else if (t % 5 == 4) /* ascending (ties too), to the end of the turn or not */
                a = (i ? sight[i - 1].angle : 0u) + (rnd32() >> (t & 8 ? 4 : 8)) * (rnd32() & 1u);
            sight[i].angle = a;
            sight[i].width = (uint16_t)rnd32();
        }
        /* O4's marks: widths around wmin (0: all kept, 0xFFFF: all but the widest dropped) */
        uint16_t wmin = t % 7 == 1   ? 0u
                        : t % 7 == 2 ? 0xFFFFu
                                     : (uint16_t)(KW.n ? sight[t % KW.n].width : 0u);
        if (t % 7 == 3)
            sight[0].width = 0xFFFFu;
        for (uint8_t i = 0; t % 7 > 3 && i < KW.n; i++)
            sight[i].width = (uint16_t)(wmin + (7u * i + t) % 5u - 2u);
        uint8_t kept = optical_sort(sight, wmin);
        cy_print("sort ");
        cy_print_dec(t);
        cy_print(" ");
        cy_print_dec(kept);
        print_work(KW.n);
        for (uint8_t b = 0; b < 16; b++) {
            cy_print(" ");
            cy_print_dec(KW.bstart[b]);
            KW.bstart[b] = 0xAA;
        }
        optical_buckets();
        for (uint8_t j = 0; j < KW.n; j++) {
            cy_print(" ");
            cy_print_dec(KW.th[j]);
            cy_print(":");
            cy_print_dec(KW.ord[j]);
        }
        cy_print(" b");
        for (uint8_t b = 0; b < 16; b++) {
            cy_print(" ");
            cy_print_dec(KW.bstart[b]);
        }
        cy_println();
    }
    for (uint8_t t = 0; t < 100; t++) {
        optical_width_t wd;
        wd.dk = 213000u + rnd32() % 1000000u;
        wd.x = rnd_in(0x00800000u);
        wd.y = rnd_in(0x00800000u);
        wd.eps8 = (uint16_t)(rnd32() % 300u);
        wd.tol8 = (uint16_t)(rnd32() % 300u);
        wd.rel16 = (uint16_t)rnd32();
        wd.flat = (uint8_t)(rnd32() & 1u);
        KW.nb = (uint8_t)(1u + rnd32() % OPTICAL_MAX_BEACONS);
        for (uint8_t k = 0; k < KW.nb; k++) {
            kmap[k].x = wd.x + rnd_in(0x01000000u);
            kmap[k].y = wd.y + rnd_in(0x01000000u);
            KW.u.id.psi[k] = (uint16_t)rnd32();
            uint8_t r = (uint8_t)(rnd32() % 8u);
            KW.u.id.bm[k] = r < 2 ? (uint8_t)(0xFEu + r) : (uint8_t)(rnd32() % 16u);
        }
        KW.b = kmap;
        KW.n = (uint8_t)(rnd32() % (OPTICAL_MAX_SIGHTINGS + 1u));
        for (uint8_t j = 0; j < KW.n; j++) {
            uint8_t r = (uint8_t)(rnd32() % 8u), k = (uint8_t)(rnd32() % KW.nb);
            KW.sm[j] = r < 3 ? (uint8_t)(0xFDu + r) : k;
            if (r >= 5) /* unique both ways */
                KW.u.id.bm[k] = j;
            r = (uint8_t)(rnd32() % 4u);
            KW.wchk[j] = r == 0   ? 0x7Fu
                         : r == 1 ? k
                         : r == 2 ? (uint8_t)(k | 0x80u)
                                  : (uint8_t)rnd32();
            KW.th[j] = (uint16_t)rnd32();
            KW.we[j] = (uint16_t)(rnd32() >> (rnd32() & 15u));
            KW.ord[j] = (uint8_t)(rnd32() % KW.n);
            sight[j].angle = rnd32();
            sight[j].width = (uint16_t)(rnd32() % ((t & 3) ? 400u : 9000u));
        }
        int16_t lohi[2] = {(int16_t)rnd32(), (int16_t)rnd32()};
        if (t & 4) { /* an interval around 0, as identify() passes */
            lohi[1] = (int16_t)(rnd32() & 0x3FFFu);
            lohi[0] = (int16_t)-lohi[1];
        }
        int8_t found = optical_unique(&wd, sight, (t % 3) ? lohi : NULL);
        cy_print("uniq ");
        cy_print_dec(t);
        cy_print(" ");
        cy_print_dec(found);
        cy_print(" ");
        cy_print_dec(lohi[0]);
        cy_print(" ");
        cy_print_dec(lohi[1]);
        print_work(KW.n);
        int8_t id[OPTICAL_MAX_SIGHTINGS];
        for (uint8_t i = 0; i < OPTICAL_MAX_SIGHTINGS; i++)
            id[i] = (int8_t)(-1 - (int8_t)(t & 1u));
        optical_gather(sight, id);
        cy_print(" g ");
        cy_print_dec(KW.m);
        for (uint8_t i = 0; i < KW.m; i++) {
            cy_print(" ");
            cy_print_dec(KW.pos[i]);
            cy_print(":");
            cy_print_hex32(KW.u.sv.ang[i]);
        }
        for (uint8_t i = 0; i < OPTICAL_MAX_SIGHTINGS; i++) {
            cy_print(" ");
            cy_print_dec(id[i]);
        }
        cy_println();
    }
    /* O6's residuals: a fix near the beacons' true bearings, tolerances around them, the
     * triplet anywhere among the identified. */
    for (uint8_t t = 0; t < 60; t++) {
        optical_pose_t p = {rnd_in(0x00800000u), rnd_in(0x00800000u), rnd32()};
        KW.nb = OPTICAL_MAX_BEACONS;
        KW.n = OPTICAL_MAX_SIGHTINGS;
        KW.m = (uint8_t)(rnd32() % (OPTICAL_MAX_SIGHTINGS + 1u));
        KW.b = kmap;
        for (uint8_t k = 0; k < KW.nb; k++) {
            kmap[k].x = p.x + rnd_in((t & 1) ? 0x00080000u : 0x02000000u);
            kmap[k].y = p.y + rnd_in((t & 1) ? 0x00080000u : 0x02000000u);
        }
        for (uint8_t i = 0; i < KW.m; i++) {
            uint8_t j = (uint8_t)(rnd32() % OPTICAL_MAX_SIGHTINGS), k = (uint8_t)(rnd32() % KW.nb);
            KW.pos[i] = j;
            KW.sm[j] = k;
            /* the bearing the fix sees, off by up to about 3 tolerances */
            uint16_t a = optical_angle16(kmap[k].x - p.x, kmap[k].y - p.y);
            KW.u.sv.ang[i] = ((uint32_t)a << 16) - p.heading + (uint32_t)rnd_in(0x01000000u);
        }
        uint8_t t3[3];
        for (uint8_t q = 0; q < 3; q++)
            t3[q] = (uint8_t)(rnd32() % (OPTICAL_MAX_SIGHTINGS + 1u));
        uint16_t tol = (uint16_t)(rnd32() % 400u);
        if (t % 7 == 3)
            tol = (uint16_t)rnd32();
        cy_print("resid ");
        cy_print_dec(t);
        cy_print(" ");
        cy_print_dec(optical_resid(&p, t3, tol));
        if (t % 3 == 0) { /* the work area's and O5's arguments: ordinary, then saturating */
            optical_config_t c;
            optical_config_default(&c);
            optical_map_t mp = {kmap, (uint8_t)(3u + t % 30u), NULL, 0, 0};
            c.beacon_diameter = (fx_q16_t)(rnd32() >> (rnd32() % 32u));
            c.beacon_flat = (uint8_t)(t & 1u);
            c.window_pos = (fx_q16_t)(rnd32() >> (t < 30 ? 12u + rnd32() % 8u : rnd32() % 8u));
            if (t % 9 == 3)
                c.window_pos = (fx_q16_t)(0xFFFE00l + rnd32() % 0x300u);
            c.dist_tol = (fx_q16_t)(rnd32() >> (rnd32() % 16u));
            c.dist_rel = (fx_q16_t)(rnd32() >> (rnd32() % 20u));
            optical_width_t w;
            cy_print(" s ");
            /* the argument check: no map, too few or many beacons, a coordinate at or just
             * within the limit (then the ordinary pose again) */
            optical_pose_t q = p;
            const optical_map_t *mq = t == 3 ? NULL : &mp;
            uint8_t nb = mp.n;
            if (t == 6 || t == 9)
                mp.n = t == 6 ? 2u : 33u;
            if (t % 3 == 0 && t >= 12) {
                int32_t lim = (int32_t)OPTICAL_COORD_LIMIT - (int32_t)(t / 3u % 3u);
                fx_q16_t v = (t & 4) ? -lim : lim;
                if (t & 8)
                    q.y = v;
                else
                    q.x = v;
            }
            cy_print_dec(optical_setup(mq, &c, &q, &w));
            mp.n = nb;
            optical_setup(&mp, &c, &p, &w);
            cy_print(" ");
            cy_print_hex32(w.dk);
            field("", (uint32_t)w.x);
            field("", (uint32_t)w.y);
            field("", ((uint32_t)w.eps8 << 16) | w.tol8);
            field("", ((uint32_t)w.rel16 << 16) | w.flat);
            field("", (uint32_t)KW.x);
            field("", (uint32_t)KW.y);
            field("", ((uint32_t)KW.head << 16) | KW.eps8);
            field("", ((uint32_t)KW.nb << 16) | (KW.b == kmap));
        }
        { /* O6's jump and turn: around the limits, and far beyond */
            optical_config_t c;
            optical_config_default(&c);
            c.jump_max = (fx_q16_t)(rnd32() >> (8u + rnd32() % 20u));
            c.turn_max = rnd32() >> (rnd32() % 16u);
            optical_pose_t ap = {p.x + rnd_in((uint32_t)c.jump_max), p.y, p.heading};
            ap.y += (t & 2) ? rnd_in((uint32_t)c.jump_max) : rnd_in(0x3FFFFFFFu);
            ap.heading += (t & 4) ? (uint32_t)rnd_in((c.turn_max >> 2) | 1u) : rnd32();
            cy_print(" j ");
            cy_print_dec(optical_jump(&p, &ap, &c));
        }
        /* the identified output through random orders (the gather of whatever sm holds) */
        int8_t id[OPTICAL_MAX_SIGHTINGS];
        for (uint8_t i = 0; i < OPTICAL_MAX_SIGHTINGS; i++) {
            id[i] = -1;
            KW.ord[i] = (uint8_t)(rnd32() % OPTICAL_MAX_SIGHTINGS);
        }
        optical_gather(sight, id);
        if (t % 10 == 0) { /* the result's initial state (over whatever was there) */
            optical_fix_t f;
            for (uint8_t i = 0; i <= offsetof(optical_fix_t, status); i++)
                ((uint8_t *)&f)[i] = (uint8_t)rnd32();
            optical_fix_init(&f);
            cy_print(" f");
            for (uint8_t i = 0; i <= offsetof(optical_fix_t, status); i++) {
                cy_print(" ");
                cy_print_dec(((const uint8_t *)&f)[i]);
            }
        }
        for (uint8_t i = 0; i < OPTICAL_MAX_SIGHTINGS; i++) {
            cy_print(" ");
            cy_print_dec(id[i]);
        }
        cy_println();
    }
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
 * O7's selection (select.c; msp430/optical_sel.S on the target) on random sets of 0 to 15
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
 * optical_triangulate (triangulate.c; msp430/optical_tri.S on the target): random beacons and
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

#ifdef __MSP430__
extern char __noinit_end[];

/* Fill the free stack below the caller with a pattern (the high-water mark is read back). */
__attribute__((noinline)) static uint16_t stack_paint(void)
{
    uint16_t sp;
    __asm__ volatile("mov r1, %0" : "=r"(sp));
    for (volatile char *p = __noinit_end; (uint16_t)p < sp - 16u; p++)
        *p = (char)0xA5;
    return sp;
}

/* Bytes of stack used below @p sp since stack_paint(). */
static uint16_t stack_used(uint16_t sp)
{
    volatile char *p = __noinit_end;
    while ((uint16_t)p < sp && *p == (char)0xA5)
        p++;
    return (uint16_t)(sp - (uint16_t)p);
}
#endif

#ifdef __MSP430__
/* Timer_B at SMCLK / 8: a 16-bit count covers 524,280 cycles (the fix needs more than
 * Timer_B's plain 65,535), to 8 cycles. */
#define ID_3 0x00C0u
static volatile uint8_t vcase;

static uint16_t slow_now(void)
{
    return TBR;
}

/* Cycles of optical_fix on case i (8-cycle resolution). */
static uint32_t time_fix(uint8_t i, optical_config_t *cfg, optical_map_t *map, optical_pose_t *ap)
{
    const optical_pose_t *latched;
    int8_t n = run_case(i, cfg, map, ap, &latched);
    uint16_t t0 = slow_now();
    optical_fix(map, cfg, ap, sight, (uint8_t)n, latched, &fix);
    uint16_t t1 = slow_now();
    return 8ul * (uint16_t)(t1 - t0);
}
#endif

static void bench(void)
{
#ifdef __MSP430__
    static cy_bench_stat_t st_fix = {"optical_fix", 0, 0, 0};
    static cy_bench_stat_t st_fix_m = {"optical_fix_moving", 0, 0, 0};
    static cy_bench_stat_t st_rev = {"optical_rev_sightings", 0, 0, 0};
    static cy_bench_stat_t st_tri = {"optical_triangulate", 0, 0, 0};
    optical_config_t cfg;
    optical_map_t map;
    optical_pose_t ap;
    const optical_pose_t *latched;
    /* The fix: 15 sightings, a 32-beacon map, every beacon within the range gate. */
    TBCTL = TASSEL_2 | ID_3 | MC_2 | TACLR;
    for (uint8_t rep = 0; rep < 3; rep++) {
        vcase = VEC_BENCH_STILL;
        cy_bench_add(&st_fix, time_fix(vcase, &cfg, &map, &ap));
        cy_check(fix.status == OPTICAL_OK, "benchmark fix accepted");
        vcase = VEC_BENCH_MOVING;
        cy_bench_add(&st_fix_m, time_fix(vcase, &cfg, &map, &ap));
        cy_check(fix.status == OPTICAL_OK, "benchmark fix while driving accepted");
    }
    cy_bench_init(); /* back to Timer_B at SMCLK for the short ones */
    for (uint8_t rep = 0; rep < 3; rep++) {
        vcase = VEC_BENCH_STILL;
        int8_t n = run_case(vcase, &cfg, &map, &ap, &latched);
        cy_check(n == 15, "benchmark revolution has 15 sightings");
        optical_fix(&map, &cfg, &ap, sight, (uint8_t)n, latched, &fix);
        const optical_rev_t *rev = capture_case(vcase);
        CY_BENCH(&st_rev, optical_rev_sightings(rev, 50000u, sight));
        optical_capture_release(&cap);
        optical_xy_t b[3] = {map.b[fix.used[0]], map.b[fix.used[1]], map.b[fix.used[2]]};
        fx_angle_t th[3];
        for (uint8_t k = 0; k < 3; k++)
            for (int8_t i = 0; i < n; i++)
                if (fix.ident[i] == fix.used[k])
                    th[k] = sight[i].angle;
        optical_tri_t tri;
        CY_BENCH(&st_tri, optical_triangulate(b, th, OPTICAL_QUALITY_LIMIT, &tri));
    }
    /* Stack: the deepest of a standing fix and a fix while driving, counted from this
     * function's frame (the board's main loop adds its own few bytes). */
    uint16_t deepest = 0;
    for (uint8_t v = 0; v < 2; v++) {
        int8_t n = run_case(v ? VEC_BENCH_MOVING : VEC_BENCH_STILL, &cfg, &map, &ap, &latched);
        uint16_t sp = stack_paint();
        optical_fix(&map, &cfg, &ap, sight, (uint8_t)n, latched, &fix);
        uint16_t used = stack_used(sp);
        if (used > deepest)
            deepest = used;
    }
    cy_print("# optical_fix stack bytes ");
    cy_print_dec(deepest);
    cy_println();
    cy_check(deepest <= 320u, "optical_fix needs at most 320 bytes of stack");
    cy_bench_report(&st_fix);
    cy_bench_report(&st_fix_m);
    cy_bench_report(&st_rev);
    cy_bench_report(&st_tri);
    cy_print("# optical_fix: SPEC floor 20000 cycles, measured ");
    cy_print_dec((int32_t)st_fix.max);
    cy_println();
    cy_check(st_fix.max <= OPTICAL_FIX_CYCLE_BOUND, "optical_fix within SPEC's 20,000 cycles");
#endif
}

#ifdef __MSP430__
/* Cycles from setting the flag to being back after RETI, minus the same sequence without it. */
static uint16_t isr_once(volatile uint16_t *ctl)
{
    cy_dint();
    *ctl |= CCIFG;
    uint16_t t0 = cy_bench_now();
    cy_eint();
    uint16_t t1 = cy_bench_now();
    return (uint16_t)(t1 - t0);
}

static uint16_t isr_base(void)
{
    cy_dint();
    uint16_t t0 = cy_bench_now();
    cy_eint();
    uint16_t t1 = cy_bench_now();
    return (uint16_t)(t1 - t0);
}
#endif

static void isr_cost(void)
{
#ifdef __MSP430__
    static cy_bench_stat_t st_idx = {"isr_index_pulse", 0, 0, 0};
    static cy_bench_stat_t st_sig = {"isr_sighting", 0, 0, 0};
    optical_capture_init(&cap);
    hal_capture_init(HAL_CAPTURE_INDEX, optical_capture_on_index, &cap);
    hal_capture_init(HAL_CAPTURE_BEACON, optical_capture_on_edge, &cap);
    optical_capture_start(&cap);
    uint16_t base = isr_base();
    isr_once(&TACCTL0); /* the first index pulse: arms */
    for (uint8_t r = 0; r < 12; r++) {
        /* A sighting: rising edge (the handler's short path), then the falling edge that
         * stores it (the long path, measured) - the simulated pin reads low: falling. */
        for (uint8_t s = 0; s < 3; s++) {
            cy_dint();
            optical_capture_on_edge(&cap, (uint16_t)(1000u * s), 1);
            cy_bench_add(&st_sig, (uint16_t)(isr_once(&TACCTL1) - base));
        }
        /* Index pulse completing a revolution; every other one finds the previous held. */
        cy_bench_add(&st_idx, (uint16_t)(isr_once(&TACCTL0) - base));
        if (r & 1) {
            if (optical_capture_take(&cap))
                optical_capture_release(&cap);
        } else {
            optical_capture_take(&cap);
        }
    }
    cy_check(cap.buf[0].n + cap.buf[1].n > 0, "the interrupts reached the handlers");
    cy_bench_report(&st_idx);
    cy_bench_report(&st_sig);
    cy_check(st_idx.max <= 150u, "isr_index_pulse <= 150 cycles");
    cy_check(st_sig.max <= 150u, "isr_sighting <= 150 cycles");
    cy_dint();
#endif
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
    cy_print("# optical vectors\n");
    helpers();
    kernels();
    glue_kernels();
    fixes();
    reflectors();
    selections();
    triangulations();
    bench();
    isr_cost();
    cy_test_end();
    return 0;
}
