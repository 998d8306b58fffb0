/*
 * optical_vectors.c - firmware/optical on both worlds, capture to fix: the identification
 * kernels on random scenes; recorded revolutions (optical_vectors_data.h, from
 * gen_optical_vectors.py) through the capture handlers, the revolution conversion and the
 * fix, as recorded and with moved poses and other configurations. One line per result (hex),
 * compared line by line between the host build and the MSP430 image: bit-identical fixes.
 * (optical_solve_vectors.c: selection, triangulation, the three-reflector mode.)
 *
 * On the target also the cycle report (build/msp430/cycles.json): optical_fix on the
 * benchmark revolution (15 sightings, 32-beacon map; standing and driving), its parts, and the
 * two capture interrupts through the real vectors and HAL shims (isr_index_pulse,
 * isr_sighting). The floors (ISR <= 150 cycles, fix <= 30,000) are checked here.
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cy_test.h"
#include "fx/fx.h"
#include "optical/capture.h"
#include "optical/fastmath.h"
#include "optical/optical.h"
#include "optical_vectors.h"
#include "optical_vectors_data.h"

/* The cycles optical_fix may take on the benchmark revolution: SPEC's floor (15 sightings,
 * a 32-beacon map). */
#define OPTICAL_FIX_CYCLE_BOUND 30000ul

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

/* A random int32 of random magnitude and sign. */
static int32_t rnd_mag(void)
{
    uint32_t v = rnd32() >> (rnd32() & 31u);
    return (rnd32() & 1u) ? (int32_t)(0u - v) : (int32_t)v;
}

/* optical_angle16 (ident.c): edge cases, then random. */
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

/* One scan's results (optical_expect_scan, optical_scan), printed. */
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

/* The identification kernels on random scenes, and the width check. */
static void kernels(void)
{
    static cy_bench_stat_t st_exs = {"optical_expect_scan_per_beacon", 0, 0, 0};
    static cy_bench_stat_t st_eval = {"optical_eval_per_pair", 0, 0, 0};
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
    /* optical_scan: the marks as optical_drop leaves them (the scene's NONE and
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
        uint8_t st = optical_scan(mid, half);
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

/*
 * optical_fix beyond the recorded revolutions' configurations, the pipeline's branches the
 * recorded cases leave alone: every case again with its approximate pose moved (up to 0.5 m
 * and 5.6 degrees: guesses, widenings, unconfirmed fixes) and a configuration of eight: the
 * defaults, the seed's overlap rule always, a range threshold that must be widened, tight
 * jump and turn limits, a tight residual limit with a sighting off, a position uncertainty that
 * saturates, a narrow heading window widened in four steps, flat strips with one motion pass and a
 * tight quality limit. Then the argument checks: no map, 2 and 33 beacons, 16 sightings, a pose at
 * and just within the coordinate limit.
 */
static void fix_print(const char *what, uint16_t t, int8_t n, int8_t st)
{
    cy_print(what);
    cy_print_dec(t);
    cy_print(" st ");
    cy_print_dec(st);
    pose_fields(&fix.pose);
    field("q", fix.quality);
    cy_print(" n ");
    cy_print_dec(fix.n_ident);
    cy_print(" w ");
    cy_print_dec(fix.widened);
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
}

static void fix_variants(void)
{
    optical_config_t cfg;
    optical_map_t map;
    optical_pose_t ap;
    const optical_pose_t *latched;
    for (uint16_t t = 0; t < 4u * VEC_N_CASES; t++) {
        int8_t n = run_case((uint8_t)(t / 4u), &cfg, &map, &ap, &latched);
        if (n < 0)
            continue;
        ap.x += rnd_in((t & 3u) ? 0x8000u : 0x2000u);
        ap.y += rnd_in((t & 3u) ? 0x8000u : 0x2000u);
        ap.heading += (uint32_t)rnd_in(0x04000000u);
        switch (t % 8u) {
        case 1:
            cfg.reject_overlap = 1;
            break;
        case 2:
            cfg.range = 2l << 16;
            cfg.range_max = 40l << 16;
            cfg.range_steps = 3;
            break;
        case 3:
            cfg.jump_max = 3277;      /* 5 cm */
            cfg.turn_max = 5965232ul; /* 0.5 degrees */
            break;
        case 4:
            cfg.resid_max = 0; /* 3 units of 2^-16 turn: 0.016 degrees */
            if (n > 0)         /* and one sighting 8 units off */
                sight[n / 2].angle += 0x00080000u;
            break;
        case 5:
            cfg.window_pos = (fx_q16_t)(0xFFFE00l + (int32_t)(rnd32() % 0x300u));
            break;
        case 6:
            cfg.window = 11930465ul;     /* 1 degree */
            cfg.widen_max = 238609294ul; /* 20 degrees */
            cfg.widen_steps = 4;
            break;
        case 7:
            cfg.beacon_flat = 1;
            cfg.motion_passes = 1;
            cfg.quality_max = 100;
            break;
        default:
            break;
        }
        fix_print("fixv ", t, n, optical_fix(&map, &cfg, &ap, sight, (uint8_t)n, latched, &fix));
    }
    for (uint8_t t = 0; t < 8; t++) {
        int8_t n = run_case(VEC_BENCH_STILL, &cfg, &map, &ap, &latched);
        const optical_map_t *mp = &map;
        uint8_t nb = map.n;
        if (t == 0)
            mp = NULL;
        else if (t == 1 || t == 2)
            map.n = t == 1 ? 2u : 33u;
        else if (t == 3)
            n = OPTICAL_MAX_SIGHTINGS + 1;
        else { /* x or y at the limit (refused) or one unit within it */
            fx_q16_t v = (fx_q16_t)(OPTICAL_COORD_LIMIT - (t & 1u));
            if (t & 2u)
                v = -v;
            if (t & 4u)
                ap.y = v;
            else
                ap.x = v;
        }
        fix_print("fixa ", t, n, optical_fix(mp, &cfg, &ap, sight, (uint8_t)n, latched, &fix));
        map.n = nb;
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
    if (cy_kernel_check_mode()) /* (both sides of every kernel run: not the fix's cycles) */
        return;
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
    cy_print("# optical_fix: SPEC floor 30000 cycles, measured ");
    cy_print_dec((int32_t)st_fix.max);
    cy_println();
    cy_check(st_fix.max <= OPTICAL_FIX_CYCLE_BOUND, "optical_fix within SPEC's 30,000 cycles");
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
    if (!cy_kernel_check_mode()) {
        cy_check(st_idx.max <= 150u, "isr_index_pulse <= 150 cycles");
        cy_check(st_sig.max <= 150u, "isr_sighting <= 150 cycles");
    }
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
    fixes();
    fix_variants();
    bench();
    isr_cost();
    cy_test_end();
    return 0;
}
