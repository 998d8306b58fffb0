/*
 * fix.c - one revolution's fix (SPEC O2-O7, O11, O6): the pipeline of optical/optical.h.
 *
 * Identification works on 16-bit angles (2^-16 turn, 0.0055 degrees) and bounds: the window
 * of beacon k for sighting i is
 *     heading interval  +-  asin((eps + |c_i|) / r_k)  + margin
 * with eps the position uncertainty of the approximate pose, c_i the sighting's parallax
 * lever (vehicle moving) and r_k the beacon's range from the approximate position (its
 * reciprocal bounded from above cheaply, g_bound: at most 1.16 times too wide). A sighting of
 * beacon j then always lies in j's window, so a match that is unique both ways (one beacon
 * for the sighting, one sighting for the beacon) is safe. Every safe match shrinks the heading
 * interval (the true heading offset lies within its position part of its own offset), which
 * narrows all windows for the next pass. Only when fewer than three remain: a guess (the
 * offset most candidate pairs agree on), then the seed's widening by a computed step a
 * bounded number of times, checked with the seed's overlapping-window rule; a fix from
 * either is used only when five sightings identified again from it confirm it.
 *
 * Cost on the MSP430: per beacon one 16-bit arctangent (optical_angle16, assembly) and a few
 * compares; per candidate pair a few 16-bit operations; the precise fixed-point work is left
 * to the selected triplet. docs/optical.md lists the measured cycles (above SPEC's 20,000).
 */
#include <stdbool.h>
#include <stddef.h>

#include "optical/fastmath.h"
#include "optical/optical.h"
#include "scratch.h"

#define NONE    0xFFu /* no match */
#define MULTI   0xFEu /* more than one match */
#define DROPPED 0xFDu /* sighting dropped by the width threshold (O4) */

/* Identification margin, 2^-16 turn: optical_angle16 (2), the sighting angle rounded to 16
 * bits (0.5), the centre of a pulse from two edges quantised to counts (0.7), spare. */
#define MARGIN 6

/* O6: other identified sightings whose residual is checked at most (a misidentified triplet
 * moves the fix so far that any of them shows it). */
#define CHECK_MAX 4

/* Heading-interval refinement passes at most. */
#define MAX_PASSES 6

#define MAX_CAND OPTICAL_MAX_CAND

optical_scratch_t optical_scratch;
#define CAND (optical_scratch.cand)

/* The identified sorted sightings: positions pos[] (ring order); their reference-frame angles
 * ang[] live in the scratch memory once identification is over. */
typedef struct {
    uint8_t m;
    uint8_t pos[OPTICAL_MAX_SIGHTINGS];
    fx_angle_t *ang;
} idset_t;

/* Work area of optical_fix (static: the MSP430's stack is small; not reentrant). */
static struct {
    uint16_t psi[OPTICAL_MAX_BEACONS];   /* expected angle, 2^-16 turn, vehicle frame */
    uint16_t g[OPTICAL_MAX_BEACONS];     /* bound of 2^16/(2 pi) asin(1 m / r); 0 gated out */
    uint16_t e[OPTICAL_MAX_BEACONS];     /* window part of the position uncertainty + margin */
    uint8_t bm[OPTICAL_MAX_BEACONS];     /* per beacon: sorted sighting matched, NONE, MULTI */
    uint16_t th[OPTICAL_MAX_SIGHTINGS];  /* sighting angles in the reference frame, sorted */
    uint8_t ord[OPTICAL_MAX_SIGHTINGS];  /* input index of th[j] */
    uint8_t sm[OPTICAL_MAX_SIGHTINGS];   /* per sorted sighting: beacon, NONE, MULTI, DROPPED */
    uint16_t we[OPTICAL_MAX_SIGHTINGS];  /* position part of the window of its match */
    uint8_t wchk[OPTICAL_MAX_SIGHTINGS]; /* O5 verdict cache: beacon | 0x80 misfit, 0x7F none */
    int32_t c[OPTICAL_MAX_SIGHTINGS];    /* parallax lever c = cross(u, o), Q16 m */
    uint16_t lev[OPTICAL_MAX_SIGHTINGS]; /* |c| in 2^-8 m */
    uint16_t wd[OPTICAL_MAX_SIGHTINGS];  /* apparent width, 2^-16 turn */
    uint8_t bstart[16];                  /* first sorted sighting of each 1/16 turn */
    uint8_t ncand;
    idset_t id;        /* the identified */
    optical_xy_t b[3]; /* the triplet being solved */
    optical_tri_t tri; /* a candidate triplet's solution (solve) */
} W;

void optical_config_default(optical_config_t *cfg)
{
    cfg->beacon_diameter = 5243; /* 0.08 m */
    cfg->beacon_flat = 0;
    cfg->window = 59652324ul;     /* 5 degrees */
    cfg->window_pos = 19661;      /* 0.3 m */
    cfg->widen_max = 119304647ul; /* 10 degrees */
    cfg->widen_steps = 2;
    cfg->reject_overlap = 0;
    cfg->range = 30l * FX_Q16_ONE;
    cfg->range_max = 60l * FX_Q16_ONE;
    cfg->range_steps = 2;
    cfg->dist_tol = 32768;      /* 0.5 m */
    cfg->dist_rel = 19661;      /* 0.3 */
    cfg->jump_max = 32768;      /* 0.5 m */
    cfg->turn_max = 83513454ul; /* 7 degrees */
    cfg->resid_max = 2386093ul; /* 0.2 degrees */
    cfg->quality_max = 16384;   /* 0.25 m per mrad: 3.1 cm per count */
    cfg->motion_passes = 3;
}

/* ------------------------------------------------------------------ small helpers */

static uint32_t umag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static uint16_t a16(fx_angle_t a)
{
    return (uint16_t)((a + 0x8000ul) >> 16);
}

static uint16_t abs16(uint16_t d)
{
    return (int16_t)d < 0 ? (uint16_t)(0u - d) : d;
}

/* ceil(k * 32 / j), j = 16..31, for k = 10923 and 16384 (see g_bound) */
static const uint16_t gk_tab[2][16] = {{21846, 20561, 19419, 18397, 17477, 16645, 15888, 15198,
                                        14564, 13982, 13444, 12946, 12484, 12053, 11652, 11276},
                                       {32768, 30841, 29128, 27595, 26215, 24967, 23832, 22796,
                                        21846, 20972, 20165, 19419, 18725, 18079, 17477, 16913}};

/*
 * g_k: an upper bound of 2^16 / (2 pi) * asin(a / r) / a for every lever a (metres) up to
 * amax8, r the true range of a beacon at (dx, dy) from the approximate
 * position, so that win_part(a, g) bounds the angle a position error a can cause. The range
 * is bounded from below by max(|dx|, |dy|, (|dx| + |dy|) / sqrt 2) (at most 8.2 % short),
 * in 2^-8 m, capped at 256 m; its reciprocal from above by a 16-step table per octave (at
 * most 6.3 % high); asin(x) <= 1.0472 x (k = 10923) for x <= 1/2 and <= (pi / 2) x
 * (k = 16384) for x <= 1. 0xFFFF (no bound) when the beacon may lie within amax8 (2^-8 m)
 * or 0.3 m of the vehicle. Arguments: |dx|, |dy| (Q16).
 */
static uint16_t g_bound(uint32_t ax, uint32_t ay, uint16_t amax8)
{
    /* magnitudes in 2^-8 m, capped at 256 m (a smaller range only makes g larger) */
    uint16_t x8 = ax >= (1ul << 24) ? 0xFFFFu : (uint16_t)(ax >> 8);
    uint16_t y8 = ay >= (1ul << 24) ? 0xFFFFu : (uint16_t)(ay >> 8);
    uint16_t r8 = x8 > y8 ? x8 : y8;
    uint32_t s = (uint32_t)x8 + y8;
    uint16_t d8 = (uint16_t)((((uint32_t)(uint16_t)(s >> 1)) * 181u) >> 7); /* <= 0.70703 s */
    if (d8 > r8)
        r8 = d8;
    if (r8 <= amax8 || r8 < 77u)
        return 0xFFFFu;
    const uint16_t *tab = gk_tab[r8 >= 2u * (uint32_t)amax8 ? 0 : 1];
    uint8_t sh = 0;
    while (r8 >= 32u) { /* r8 in [j 2^sh, (j + 1) 2^sh), j = 16..31, sh >= 2 */
        r8 >>= 1;
        sh++;
    }
    /* g = k 2^16 / r <= k 2^8 / (j 2^sh) <= gk_tab[j] 2^3 / 2^sh, rounded up */
    uint16_t base = tab[r8 - 16u];
    if (sh < 3)
        return base >= 0x8000u ? 0xFFFEu : (uint16_t)(base << 1);
    uint8_t n = (uint8_t)(sh - 3u);
    uint16_t lost = 0;
    for (uint8_t i = 0; i < n; i++) {
        lost |= base & 1u;
        base >>= 1;
    }
    return (uint16_t)(base + lost);
}

/* (a * g) / 256 rounded up (a in 2^-8 m): a window part in 2^-16 turn, capped at 0x7FFF. */
static uint16_t win_part(uint16_t a, uint16_t g)
{
    if (g == 0xFFFFu)
        return 0x7FFFu;
    uint32_t v = ((uint32_t)a * g + 255u) >> 8;
    return v > 0x7FFFu ? 0x7FFFu : (uint16_t)v;
}

/* Metres Q16 to 2^-8 m, rounded up, saturating. */
static uint16_t m8(uint32_t q16)
{
    uint32_t v = (q16 + 255u) >> 8;
    return v > 0xFFFFu ? 0xFFFFu : (uint16_t)v;
}

/* Octagonal norm max + min / 2 (Q16): true range <= it <= 1.118 true range. */
static uint32_t oct_norm(int32_t dx, int32_t dy)
{
    uint32_t ax = umag(dx), ay = umag(dy);
    return ax > ay ? ax + (ay >> 1) : ay + (ax >> 1);
}

/* ------------------------------------------------------------------ revolution */

int8_t optical_rev_sightings(const optical_rev_t *rev, uint16_t counts_per_turn,
                             optical_sighting_t *out)
{
    uint8_t order[OPTICAL_MAX_SIGHTINGS];
    return optical_rev_order(rev, counts_per_turn, out, order);
}

int8_t optical_rev_order(const optical_rev_t *rev, uint16_t counts_per_turn,
                         optical_sighting_t *out, uint8_t *order)
{
    if (rev->cov || rev->period != counts_per_turn || counts_per_turn == 0)
        return -1;
    uint8_t n = rev->n;
    if (n > OPTICAL_MAX_SIGHTINGS)
        return -1;
    fx_angle_t half = fx_angle_from_counts(1, counts_per_turn); /* one count */
    for (uint8_t i = 0; i < n; i++) {
        /* A start beyond the turn is a pulse that began before the index pulse (negative). */
        uint16_t st = rev->s[i].start;
        uint32_t start =
            st >= counts_per_turn ? (uint32_t)counts_per_turn - (uint16_t)(0u - st) : (uint32_t)st;
        fx_angle_t w = rev->s[i].width >= counts_per_turn
                           ? 0xFFFFFFFFul
                           : fx_angle_from_counts(rev->s[i].width, counts_per_turn);
        /* An edge at angle a reads floor(a) counts: the centre is half a count later. */
        fx_angle_t a = fx_angle_from_counts(start, counts_per_turn) + (w >> 1) + (half >> 1);
        uint32_t w16 = (w >> 16) + ((w >> 15) & 1u);
        /* Insertion by angle: the sightings arrive in order except one straddling the index. */
        uint8_t j = i;
        while (j > 0 && out[j - 1].angle > a) {
            out[j] = out[j - 1];
            order[j] = order[j - 1];
            j--;
        }
        order[j] = i;
        out[j].angle = a;
        out[j].width = w16 > 0xFFFFu ? 0xFFFFu : (uint16_t)w16;
    }
    return (int8_t)n;
}

/* ------------------------------------------------------------------ identification */

typedef struct {
    const optical_map_t *map;
    const optical_config_t *cfg;
    const optical_pose_t *ap;
    const optical_sighting_t *s;
    uint8_t n;       /* sightings */
    uint16_t eps8;   /* position uncertainty, 2^-8 m */
    uint16_t lever8; /* largest parallax lever, 2^-8 m */
    uint32_t dk;     /* D * 2^8 * 2^16 / (2 pi), D in m: width check constant (O5) */
} ctx_t;

/* Position part of beacon k's window for sorted sighting j, with the margin. */
static uint16_t pos_part(const ctx_t *x, uint8_t k, uint8_t j)
{
    if (W.lev[j] == 0)
        return W.e[k];
    uint32_t a = (uint32_t)x->eps8 + W.lev[j];
    return (uint16_t)(win_part(a > 0xFFFFu ? 0xFFFFu : (uint16_t)a, W.g[k]) + MARGIN);
}

static void clear_matches(const ctx_t *x)
{
    for (uint8_t j = 0; j < x->n; j++)
        if (W.sm[j] != DROPPED)
            W.sm[j] = NONE;
    for (uint8_t k = 0; k < x->map->n; k++)
        W.bm[k] = NONE;
}

static void mark(uint8_t j, uint8_t k, uint16_t e)
{
    W.sm[j] = W.sm[j] == NONE ? k : MULTI;
    W.bm[k] = W.bm[k] == NONE ? j : MULTI;
    W.we[j] = e;
}

/*
 * Scan for the (sighting, beacon) pairs within the windows centred on heading offset @p mid,
 * half-width @p half. With @p store the pairs go to the candidate list (false when more than
 * MAX_CAND: the list is then unusable); otherwise they are marked in W.sm / W.bm at once.
 */
static bool scan(const ctx_t *x, int16_t mid, uint16_t half, bool store)
{
    uint8_t nc = 0;
    if (!store)
        clear_matches(x);
    for (uint8_t k = 0; k < x->map->n; k++) {
        if (W.g[k] == 0)
            continue;
        /* Widest window of k over all sightings (largest lever), to bound the scan. */
        uint32_t wmax = (uint32_t)half + W.e[k];
        if (x->lever8) {
            uint32_t a = (uint32_t)x->eps8 + x->lever8;
            wmax = (uint32_t)half + MARGIN + win_part(a > 0xFFFFu ? 0xFFFFu : (uint16_t)a, W.g[k]);
        }
        uint16_t centre = (uint16_t)(W.psi[k] + (uint16_t)mid);
        bool all = wmax >= 0x7000u; /* that wide: test every sighting */
        uint16_t lo = (uint16_t)(centre - (uint16_t)wmax);
        uint16_t span = (uint16_t)(2u * wmax);
        uint8_t j = all ? 0u : W.bstart[lo >> 12];
        for (uint8_t c = 0; c < x->n; c++, j = (uint8_t)(j + 1u < x->n ? j + 1u : 0u)) {
            if (!all) {
                uint16_t rel = (uint16_t)(W.th[j] - lo);
                if (rel >= 0xF000u)
                    continue; /* in lo's 1/16 turn, before lo */
                if (rel > span)
                    break;
            }
            if (W.sm[j] == DROPPED)
                continue;
            uint16_t off = (uint16_t)(W.th[j] - W.psi[k]);
            uint16_t e = pos_part(x, k, j);
            if ((uint32_t)abs16((uint16_t)(off - (uint16_t)mid)) > (uint32_t)half + e)
                continue;
            if (!store) {
                mark(j, k, e);
                continue;
            }
            if (nc == MAX_CAND)
                return false;
            CAND.j[nc] = j;
            CAND.k[nc] = k;
            CAND.off[nc] = (int16_t)off;
            CAND.e[nc] = e;
            nc++;
        }
    }
    W.ncand = nc;
    return true;
}

/* The stored candidates within the windows (mid, half), marked in W.sm / W.bm. */
static void evaluate(const ctx_t *x, int16_t mid, uint16_t half)
{
    clear_matches(x);
    for (uint8_t c = 0; c < W.ncand; c++) {
        uint16_t e = CAND.e[c];
        if ((uint32_t)abs16((uint16_t)((uint16_t)CAND.off[c] - (uint16_t)mid)) <=
            (uint32_t)half + e)
            mark(CAND.j[c], CAND.k[c], e);
    }
}

/* The seed's overlapping-window rule: k's window meets the window of another beacon. */
static bool overlaps(const ctx_t *x, uint8_t k, uint16_t half)
{
    uint32_t wk = (uint32_t)half + MARGIN + win_part(x->eps8, W.g[k]);
    for (uint8_t j = 0; j < x->map->n; j++) {
        if (j == k || W.g[j] == 0)
            continue;
        uint16_t d = abs16((uint16_t)(W.psi[j] - W.psi[k]));
        if ((uint32_t)d < wk + half + MARGIN + win_part(x->eps8, W.g[j]))
            return true;
    }
    return false;
}

/*
 * O5: is apparent width w16 (2^-16 turn) compatible with beacon k at its map distance?
 * The range from the approximate position lies in [r~ / 1.118 - eps, r~ + eps] (r~ the
 * octagonal norm); widened by tol = dist_tol + dist_rel * range on both sides. The width
 * distance dw = D / (2 sin(w/2)) (flat: D / (2 tan(w/2)) <= D / w, an upper bound) must
 * fall in it. With w in radians, 0.98 w <= 2 sin(w/2) <= w for w <= 0.5 rad:
 *     lo * 0.98 w <= D  and (posts only)  hi * w >= D.
 * In 2^-8 m and 2^-16 turn: lo8 * w16 compares with dk = D 2^8 2^16 / (2 pi).
 */
static bool width_ok(const ctx_t *x, uint8_t k, uint16_t w16)
{
    const optical_config_t *cfg = x->cfg;
    uint32_t r = oct_norm(x->map->b[k].x - x->ap->x, x->map->b[k].y - x->ap->y);
    uint32_t rhi = (r >> 8) + x->eps8;        /* 2^-8 m */
    uint32_t rlo = ((r >> 8) * 58623u) >> 16; /* / 1.118 */
    rlo = rlo > x->eps8 ? rlo - x->eps8 : 0u;
    if (rhi > 0x1FFFFu)
        rhi = 0x1FFFFu; /* 512 m */
    uint32_t tol =
        ((uint32_t)cfg->dist_tol >> 8) + (((rhi >> 2) * ((uint32_t)cfg->dist_rel >> 8)) >> 6);
    uint32_t lo = rlo > tol ? rlo - tol : 0u;
    uint32_t hi = rhi + tol;
    if (w16 > 5215u) /* 0.5 rad: a post closer than 2 D, wide for any use here */
        return lo * 5215u <= x->dk + (x->dk >> 4);
    /* lo * 0.98 w > D: the post would look wider even at the far end of the interval */
    if (lo && (lo * w16 / 50u) * 49u > x->dk)
        return false;
    return cfg->beacon_flat || hi * w16 >= x->dk;
}

/* Keep in W.sm only the matches unique both ways (and, when asked, clear of overlapping
 * windows) whose width fits the map distance (O5); count them. */
static int8_t unique_matches(const ctx_t *x, bool overlap_rule, uint16_t half)
{
    int8_t found = 0;
    for (uint8_t j = 0; j < x->n; j++) {
        uint8_t k = W.sm[j];
        if (k >= DROPPED)
            continue;
        if (W.bm[k] != j || (overlap_rule && overlaps(x, k, half))) {
            W.sm[j] = NONE;
            continue;
        }
        /* O5, once per (sighting, beacon): bit 7 of wchk marks a misfit. */
        if ((W.wchk[j] & 0x7Fu) != k)
            W.wchk[j] = (uint8_t)(k | (width_ok(x, k, W.wd[j]) ? 0u : 0x80u));
        if (W.wchk[j] & 0x80u) {
            W.sm[j] = NONE;
            continue;
        }
        found++;
    }
    return found;
}

enum { IDENT_SAFE = 0, IDENT_GUESS = 1, IDENT_WIDENED = 2 };

/*
 * A guess when the bounds leave fewer than three: the heading offset that the candidate pairs
 * of the most sightings agree on (each pair's offset +- its position part, doubled), then the
 * unique matches there. Only a fix that the other sightings confirm may use it.
 */
static int8_t guess(const ctx_t *x)
{
    int16_t best_h = 0;
    uint16_t best_e = 0;
    uint8_t best_n = 0;
    for (uint8_t c = 0; c < W.ncand; c++) {
        int16_t h = CAND.off[c];
        uint16_t seen = 0; /* sightings that agree, as a bit set */
        uint8_t cnt = 0;
        for (uint8_t d = 0; d < W.ncand; d++) {
            uint16_t bit = (uint16_t)(1u << CAND.j[d]);
            if (seen & bit)
                continue;
            if ((uint32_t)abs16((uint16_t)(CAND.off[d] - h)) <= (uint32_t)CAND.e[d] + CAND.e[c]) {
                seen |= bit;
                cnt++;
            }
        }
        if (cnt > best_n) {
            best_n = cnt;
            best_h = h;
            best_e = CAND.e[c];
        }
    }
    if (best_n < 3)
        return 0;
    evaluate(x, best_h, best_e);
    return unique_matches(x, false, best_e);
}

/*
 * Identify (O3-O5): leaves in W.sm[j] the beacon of each identified sorted sighting (NONE,
 * MULTI or DROPPED otherwise) and returns how many, or -1 when the matches contradict the
 * stated uncertainty. *mode: IDENT_SAFE (within the bounds), IDENT_GUESS or IDENT_WIDENED
 * (the fix must be confirmed by the other sightings). *widened: widenings used.
 */
static int8_t identify(const ctx_t *x, uint8_t *mode, uint8_t *widened)
{
    const optical_config_t *cfg = x->cfg;
    int32_t lo = -(int32_t)a16(cfg->window), hi = (int32_t)a16(cfg->window);
    uint8_t passes = 0;
    bool stored = false;
    int8_t found;
    *mode = IDENT_SAFE;
    *widened = 0;
    /* Within the bounds: each safe match narrows the heading interval for the next pass. */
    for (;;) {
        int16_t mid = (int16_t)((lo + hi) / 2);
        uint16_t half = (uint16_t)((hi - lo + 1) / 2);
        if (stored) {
            evaluate(x, mid, half); /* a narrower window: a subset of the stored pairs */
        } else if (scan(x, mid, half, true)) {
            stored = true;
            evaluate(x, mid, half);
        } else {
            scan(x, mid, half, false); /* too many pairs to keep: this pass scans */
        }
        passes++;
        found = unique_matches(x, cfg->reject_overlap, half);
        int32_t nlo = lo, nhi = hi;
        for (uint8_t j = 0; j < x->n; j++) {
            uint8_t k = W.sm[j];
            if (k >= DROPPED)
                continue;
            int16_t off = (int16_t)(W.th[j] - W.psi[k]);
            int32_t e = W.we[j];
            if (off - e > nlo)
                nlo = off - e;
            if (off + e < nhi)
                nhi = off + e;
        }
        if (nlo > nhi)
            return -1;
        if (passes < MAX_PASSES && 4 * (nhi - nlo) < 3 * (hi - lo)) {
            lo = nlo; /* tighter by a quarter or more: another pass, never fewer matches */
            hi = nhi;
            continue;
        }
        break;
    }
    if (found >= 3)
        return found;
    /* Beyond the bounds: a guess, then the seed's widening. */
    if (stored) {
        found = guess(x);
        if (found >= 3) {
            *mode = IDENT_GUESS;
            return found;
        }
    }
    uint32_t step = 0;
    if (cfg->widen_steps && cfg->widen_max > cfg->window)
        step = (a16(cfg->widen_max) - a16(cfg->window) + cfg->widen_steps - 1u) / cfg->widen_steps;
    for (uint8_t w = 1; w <= cfg->widen_steps && step; w++) {
        lo -= (int32_t)step;
        hi += (int32_t)step;
        if (hi - lo >= 0x8000)
            break;
        int16_t mid = (int16_t)((lo + hi) / 2);
        uint16_t half = (uint16_t)((hi - lo + 1) / 2);
        scan(x, mid, half, false);
        found = unique_matches(x, true, half);
        *widened = w;
        if (found >= 3) {
            *mode = IDENT_WIDENED;
            return found;
        }
    }
    return found;
}

/* ------------------------------------------------------------------ fix */

/* Precise angle of sorted sighting j in the reference frame. */
static fx_angle_t ref_angle(const ctx_t *x, const optical_pose_t *latched, uint8_t j)
{
    uint8_t i = W.ord[j];
    fx_angle_t d = x->s[i].angle;
    if (latched != NULL)
        d += latched[i].heading - x->ap->heading;
    return d;
}

/*
 * O11: the angle under which the reference position sees the beacon of sorted sighting j
 * (reference-frame angle d) at range r (Q16) from it: d + asin(c / r).
 */
static fx_angle_t corrected(fx_angle_t d, uint8_t j, uint32_t r)
{
    int32_t ratio;
    if (W.c[j] == 0 || r == 0 || r > 0x7FFFFFFFul || !fx_div_shift(W.c[j], (int32_t)r, 30, &ratio))
        return d;
    return d + fx_asin(ratio);
}

static bool coords_ok(fx_q16_t x, fx_q16_t y)
{
    /* |v| < limit  <=>  v + limit - 1 < 2 limit - 1, unsigned */
    const uint32_t l = (uint32_t)OPTICAL_COORD_LIMIT;
    return (uint32_t)x + (l - 1u) < 2u * l - 1u && (uint32_t)y + (l - 1u) < 2u * l - 1u;
}

static int8_t finish(optical_fix_t *out, int8_t status)
{
    out->status = (uint8_t)status;
    return status;
}

/* Expected angles and window factors of the beacons within the gate, seen from @p p. */
static void expect(const ctx_t *x, const optical_pose_t *p, uint32_t gate)
{
    uint16_t head = a16(p->heading);
    uint32_t amax = (uint32_t)x->eps8 + x->lever8;
    uint16_t amax8 = amax > 0xFFFFu ? 0xFFFFu : (uint16_t)amax;
    for (uint8_t k = 0; k < x->map->n; k++) {
        int32_t dx = x->map->b[k].x - p->x, dy = x->map->b[k].y - p->y;
        uint32_t ax = umag(dx), ay = umag(dy);
        if (ax > gate || ay > gate) {
            W.g[k] = 0;
            continue;
        }
        W.psi[k] = (uint16_t)(optical_angle16(dx, dy) - head);
        W.g[k] = g_bound(ax, ay, amax8);
        W.e[k] = (uint16_t)(win_part(x->eps8, W.g[k]) + MARGIN);
    }
}

static void gather(const ctx_t *x, const optical_pose_t *latched, idset_t *id)
{
    id->m = 0;
    id->ang = optical_scratch.solve.ang; /* the candidates are no longer needed */
    for (uint8_t j = 0; j < x->n; j++) {
        if (W.sm[j] >= DROPPED)
            continue;
        id->ang[id->m] = ref_angle(x, latched, j);
        id->pos[id->m++] = j;
    }
}

/* Triangulate the triplet at positions t[] of the identified set; when moving, refine the
 * parallax with the ranges of the fix (O11). */
static int8_t solve_triplet(const ctx_t *x, const idset_t *id, const uint8_t t[3], uint8_t passes,
                            optical_tri_t *tri)
{
    optical_xy_t *b = W.b;
    bool moving = false;
    for (uint8_t i = 0; i < 3; i++) {
        uint8_t j = id->pos[t[i]];
        b[i] = x->map->b[W.sm[j]];
        moving |= W.c[j] != 0;
    }
    optical_pose_t p = *x->ap;
    if (!moving)
        passes = 1;
    int8_t st = OPTICAL_OK;
    for (uint8_t pass = 0; pass < passes; pass++) {
        fx_angle_t th[3];
        for (uint8_t i = 0; i < 3; i++) {
            uint8_t j = id->pos[t[i]];
            th[i] = id->ang[t[i]];
            if (W.c[j])
                th[i] = corrected(th[i], j, fx_hypot(b[i].x - p.x, b[i].y - p.y));
        }
        st = optical_triangulate(b, th, x->cfg->quality_max, tri);
        if (st != OPTICAL_OK)
            return st;
        uint32_t moved = oct_norm(tri->pose.x - p.x, tri->pose.y - p.y);
        p = tri->pose;
        if (moved < 16) /* 0.25 mm */
            break;
    }
    return st;
}

/*
 * O7-O10: select three of the identified (the seed's rule) and triangulate. When that
 * triplet lies too close to its beacons' circle (refused as singular or inconsistent), the
 * triplets with one of its beacons replaced by another identified one are tried, and the
 * best taken.
 */
static int8_t solve(const ctx_t *x, const idset_t *id, uint8_t passes, uint8_t t[3],
                    optical_tri_t *tri)
{
    optical_select(id->ang, id->m, t);
    int8_t st = solve_triplet(x, id, t, passes, tri);
    if ((st != OPTICAL_E_SINGULAR && st != OPTICAL_E_INCONSISTENT) || id->m <= 3)
        return st;
    uint32_t best = UINT32_MAX;
    uint8_t bt[3] = {t[0], t[1], t[2]};
    optical_tri_t *cand = &W.tri;
    for (uint8_t r = 0; r < 3; r++) {
        for (uint8_t q = 0; q < id->m; q++) {
            if (q == t[0] || q == t[1] || q == t[2])
                continue;
            uint8_t u[3] = {t[0], t[1], t[2]};
            u[r] = q;
            if (solve_triplet(x, id, u, passes, cand) == OPTICAL_OK && cand->quality < best) {
                best = cand->quality;
                bt[0] = u[0];
                bt[1] = u[1];
                bt[2] = u[2];
                *tri = *cand;
            }
        }
    }
    if (best == UINT32_MAX)
        return st;
    t[0] = bt[0];
    t[1] = bt[1];
    t[2] = bt[2];
    return OPTICAL_OK;
}

int8_t optical_fix(const optical_map_t *map, const optical_config_t *cfg,
                   const optical_pose_t *approx, const optical_sighting_t *s, uint8_t n,
                   const optical_pose_t *latched, optical_fix_t *out)
{
    for (uint8_t i = 0; i < OPTICAL_MAX_SIGHTINGS; i++)
        out->ident[i] = -1;
    out->n_ident = 0;
    out->widened = 0;
    out->quality = UINT32_MAX;
    out->pose = *approx;
    if (map == NULL || map->n < 3 || map->n > OPTICAL_MAX_BEACONS || n > OPTICAL_MAX_SIGHTINGS ||
        !coords_ok(approx->x, approx->y))
        return finish(out, OPTICAL_E_ARG);
    for (uint8_t k = 0; k < map->n; k++)
        if (!coords_ok(map->b[k].x, map->b[k].y))
            return finish(out, OPTICAL_E_ARG);
    if (n < 3)
        return finish(out, OPTICAL_E_FEW);

    ctx_t x = {map, cfg, approx, s, n, m8((uint32_t)cfg->window_pos), 0, 0};
    /* D (m) * 2^8 * 2^16 / (2 pi) = D (Q16) * 10430.378 / 2^8 */
    x.dk = ((uint32_t)cfg->beacon_diameter * 10430u) >> 8;

    /* O11: sightings into the vehicle frame of the reference instant, sorted by angle. */
    fx_q30_t sa = 0, ca = FX_Q30_ONE;
    if (latched != NULL)
        fx_sincos(approx->heading, &sa, &ca);
    for (uint8_t i = 0; i < n; i++) {
        fx_angle_t d = s[i].angle;
        int32_t c = 0;
        if (latched != NULL) {
            if (!coords_ok(latched[i].x, latched[i].y))
                return finish(out, OPTICAL_E_ARG);
            d += latched[i].heading - approx->heading;
            int32_t ex = latched[i].x - approx->x, ey = latched[i].y - approx->y;
            if (ex | ey) {
                /* o = R(-heading) e, then c = cross(u(d), o) = oy cos d - ox sin d. */
                int32_t ox = fx_mul_q30(ex, ca) + fx_mul_q30(ey, sa);
                int32_t oy = fx_mul_q30(ey, ca) - fx_mul_q30(ex, sa);
                fx_q30_t sd, cd;
                fx_sincos(d, &sd, &cd);
                c = fx_mul_q30(oy, cd) - fx_mul_q30(ox, sd);
            }
        }
        uint16_t t = a16(d);
        uint8_t j = i;
        while (j > 0 && W.th[j - 1] > t) {
            W.th[j] = W.th[j - 1];
            W.c[j] = W.c[j - 1];
            W.ord[j] = W.ord[j - 1];
            j--;
        }
        W.th[j] = t;
        W.c[j] = c;
        W.ord[j] = i;
    }
    for (uint8_t j = 0; j < n; j++) {
        uint16_t l = W.c[j] ? m8(umag(W.c[j])) : 0u;
        W.lev[j] = l;
        W.wd[j] = s[W.ord[j]].width;
        if (l > x.lever8)
            x.lever8 = l;
    }
    /* Bucket index: first sorted sighting at or after each 1/16 turn (0 when none: wraps). */
    {
        uint8_t j = 0;
        for (uint8_t b = 0; b < 16; b++) {
            while (j < n && (W.th[j] >> 12) < b)
                j++;
            W.bstart[b] = j < n ? j : 0;
        }
    }

    /* O4: drop sightings too narrow for a beacon within T; widen T when fewer than 3 stay.
     * A post at T looks 2 asin(D / 2T) >= D / T wide: the threshold D / T keeps those. */
    fx_q16_t t = cfg->range;
    int32_t tstep = cfg->range_steps && cfg->range_max > cfg->range
                        ? (cfg->range_max - cfg->range + cfg->range_steps - 1) / cfg->range_steps
                        : 0;
    for (uint8_t step = 0;; step++) {
        uint32_t t8 = (uint32_t)t >> 8;
        uint32_t wmin = t8 ? x.dk / t8 : 0xFFFFu; /* 2^-16 turn */
        uint8_t kept = 0;
        for (uint8_t j = 0; j < n; j++) {
            bool keep = W.wd[j] >= wmin;
            W.sm[j] = keep ? NONE : DROPPED;
            W.wchk[j] = 0x7Fu;
            kept += keep;
        }
        if (kept >= 3 || step >= cfg->range_steps || tstep == 0)
            break;
        t += tstep;
    }
    /* O2: expected angles of the beacons within T (+ the position uncertainty). */
    uint32_t gate = (uint32_t)t + (uint32_t)cfg->window_pos;
    expect(&x, approx, gate);

    /* O3-O5 */
    uint8_t mode, widened;
    int8_t found = identify(&x, &mode, &widened);
    out->widened = widened;
    if (found < 0)
        return finish(out, OPTICAL_E_INCONSISTENT);
    idset_t *id = &W.id;
    gather(&x, latched, id);
    if (id->m < 3) {
        out->n_ident = id->m;
        return finish(out, OPTICAL_E_FEW);
    }

    /* O7-O11 */
    uint8_t passes = cfg->motion_passes ? cfg->motion_passes : 1u;
    uint8_t t3[3];
    optical_tri_t tri;
    int8_t st = solve(&x, id, passes, t3, &tri);
    if (st == OPTICAL_OK && mode != IDENT_SAFE) {
        /* Beyond the bounds the identification is a hypothesis: identify again from the fix
         * (5 cm, the residual tolerance) and use it only when at least five sightings agree. */
        x.eps8 = 13;
        expect(&x, &tri.pose, gate);
        scan(&x, 0, a16(cfg->resid_max), false);
        if (unique_matches(&x, false, a16(cfg->resid_max)) < 5) {
            for (uint8_t j = 0; j < n; j++)
                if (W.sm[j] < DROPPED)
                    W.sm[j] = NONE;
            gather(&x, latched, id);
            out->n_ident = id->m;
            return finish(out, OPTICAL_E_UNCONFIRMED);
        }
        gather(&x, latched, id);
        st = solve(&x, id, passes, t3, &tri);
    }
    for (uint8_t i = 0; i < id->m; i++)
        out->ident[W.ord[id->pos[i]]] = (int8_t)W.sm[id->pos[i]];
    out->n_ident = id->m;
    if (st == OPTICAL_OK || st == OPTICAL_E_SINGULAR) {
        out->pose = tri.pose;
        out->quality = tri.quality;
        for (uint8_t i = 0; i < 3; i++)
            out->used[i] = W.sm[id->pos[t3[i]]];
    }
    if (st != OPTICAL_OK)
        return finish(out, st);
    optical_pose_t p = tri.pose;

    /* O6: implausible jumps and turns, then the other identified sightings must agree. */
    int32_t jx = p.x - approx->x, jy = p.y - approx->y;
    if (oct_norm(jx, jy) > (uint32_t)cfg->jump_max && fx_hypot(jx, jy) > (uint32_t)cfg->jump_max)
        return finish(out, OPTICAL_E_JUMP);
    fx_angle_t dh = p.heading - approx->heading;
    if ((int32_t)dh > (int32_t)cfg->turn_max || (int32_t)dh < -(int32_t)cfg->turn_max)
        return finish(out, OPTICAL_E_TURN);
    uint16_t rmax = a16(cfg->resid_max), h16 = a16(p.heading);
    uint8_t checked = 0;
    for (uint8_t i = 0; i < id->m && checked < CHECK_MAX; i++) {
        if (i == t3[0] || i == t3[1] || i == t3[2])
            continue;
        checked++;
        uint8_t j = id->pos[i];
        const optical_xy_t *bk = &map->b[W.sm[j]];
        int32_t dx = bk->x - p.x, dy = bk->y - p.y;
        fx_angle_t th = id->ang[i];
        if (W.c[j])
            th = corrected(th, j, fx_hypot(dx, dy));
        uint16_t res = (uint16_t)(optical_angle16(dx, dy) - h16 - a16(th));
        if (abs16(res) > rmax + 3u)
            return finish(out, OPTICAL_E_DISAGREE);
    }
    return finish(out, OPTICAL_OK);
}
