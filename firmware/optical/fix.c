/*
 * fix.c - one revolution's fix (SPEC O2-O7, O11, O6): the pipeline of optical/optical.h.
 *
 * Identification works on 16-bit angles (2^-16 turn, 0.0055 degrees) and bounds: the window
 * of beacon k for sighting i is
 *     heading interval  +-  asin((eps + |c_i|) / r_k)  + margin
 * with eps the position uncertainty of the approximate pose, c_i the sighting's parallax
 * lever (vehicle moving) and r_k the beacon's range from the approximate position (bounded
 * from below cheaply, and asin(x) from above by k (pi / 2) x, k = 2/3 where x <= 1/2, else 1:
 * optical_expect_scan). A
 * sighting of beacon j then always lies in j's window, so a match that is unique both ways
 * (one beacon for the sighting, one sighting for the beacon) is safe. Every safe match shrinks
 * the heading interval (the true heading offset lies within its position part of its own
 * offset), which narrows all windows for the next pass. Only when fewer than three remain: a
 * guess (the offset most candidate pairs agree on), then the seed's widening by a computed
 * step a bounded number of times, checked with the seed's overlapping-window rule; a fix from
 * either is used only when five sightings identified again from it confirm it.
 *
 * The margin (OPTICAL_MARGIN, 6 units of 2^-16 turn) covers optical_angle16 (1), the sighting
 * angle rounded to 16 bits (0.5), the centre of a pulse from two edges quantised to counts
 * (0.7), and spare.
 *
 * Cost: the per-beacon work (expected angle, range bound, window) and the window scans are
 * the kernels optical_scan / optical_expect_scan and optical_eval (fastmath.h); the
 * precise fixed-point work is left to the selected triplet (triangulate.c). docs/optical.md
 * lists the measured cycles.
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "optical/fastmath.h"
#include "optical/optical.h"

#define NONE    OPTICAL_NONE
#define MULTI   OPTICAL_MULTI
#define DROPPED OPTICAL_DROPPED

/* O6: other identified sightings whose residual is checked at most (a misidentified triplet
 * moves the fix so far that any of them shows it). */
#define CHECK_MAX 4

/* Heading-interval refinement passes at most. */
#define MAX_PASSES 6

/* The work area (fastmath.h: the kernels share it). */
#define W (optical_work)

static const optical_config_t defaults = OPTICAL_CONFIG_DEFAULT(5243 /* 0.08 m */);

void optical_config_default(optical_config_t *cfg)
{
    *cfg = defaults;
}

/* ------------------------------------------------------------------ small helpers */

static inline __attribute__((always_inline)) uint32_t umag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static inline __attribute__((always_inline)) uint16_t a16(fx_angle_t a)
{
    return (uint16_t)((a + 0x8000ul) >> 16);
}

static inline __attribute__((always_inline)) uint16_t abs16(uint16_t d)
{
    return (int16_t)d < 0 ? (uint16_t)(0u - d) : d;
}

static uint16_t sat16(uint32_t v)
{
    return v > 0xFFFFu ? 0xFFFFu : (uint16_t)v;
}

static uint16_t sat15(uint32_t v)
{
    return v > 0x7FFFu ? 0x7FFFu : (uint16_t)v;
}

/* Metres Q16 to 2^-8 m, rounded up, saturating. */
static uint16_t m8(uint32_t q16)
{
    return sat16((q16 >> 8) + ((q16 & 255u) != 0));
}

/* A widening's step: ceil((hi - lo) / steps), 0 when there is none. */
static uint32_t step_of(uint32_t lo, uint32_t hi, uint8_t steps)
{
    return steps && hi > lo ? (hi - lo + steps - 1u) / steps : 0u;
}

static bool coords_ok(fx_q16_t x, fx_q16_t y)
{
    /* |v| < limit  <=>  v + limit - 1 < 2 limit - 1, unsigned */
    const uint32_t l = (uint32_t)OPTICAL_COORD_LIMIT;
    return (uint32_t)x + (l - 1u) < 2u * l - 1u && (uint32_t)y + (l - 1u) < 2u * l - 1u;
}

/* ------------------------------------------------------------------ map */

bool optical_map_compile(optical_map_t *map, const optical_xy_t *b, uint8_t n, optical_xy8_t *b8)
{
    if (map == NULL || b == NULL || b8 == NULL || n < 3 || n > OPTICAL_MAX_BEACONS)
        return false;
    int32_t lo[2] = {INT32_MAX, INT32_MAX}, hi[2] = {INT32_MIN, INT32_MIN};
    for (uint8_t k = 0; k < n; k++) {
        if (!coords_ok(b[k].x, b[k].y))
            return false;
        int32_t v[2] = {b[k].x, b[k].y};
        for (uint8_t c = 0; c < 2; c++) {
            lo[c] = v[c] < lo[c] ? v[c] : lo[c];
            hi[c] = v[c] > hi[c] ? v[c] : hi[c];
        }
    }
    /* the centre of the bounding box, floored to whole metres */
    int32_t o[2];
    for (uint8_t c = 0; c < 2; c++) {
        int32_t mid = lo[c] + (int32_t)(((uint32_t)hi[c] - (uint32_t)lo[c]) >> 1);
        o[c] = (int32_t)((uint32_t)mid & ~(uint32_t)(FX_Q16_ONE - 1));
        if (hi[c] - o[c] >= OPTICAL_MAP_REACH || o[c] - lo[c] > OPTICAL_MAP_REACH)
            return false;
    }
    for (uint8_t k = 0; k < n; k++) { /* floor((b - o) / 2^8), in [-2^15, 2^15) */
        b8[k].x = (int16_t)(uint16_t)((uint32_t)(b[k].x - o[0]) >> 8);
        b8[k].y = (int16_t)(uint16_t)((uint32_t)(b[k].y - o[1]) >> 8);
    }
    map->b = b;
    map->n = n;
    map->b8 = b8;
    map->ox = o[0];
    map->oy = o[1];
    return true;
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
    uint8_t n = rev->n;
    if (rev->cov || rev->period != counts_per_turn || counts_per_turn == 0 ||
        n > OPTICAL_MAX_SIGHTINGS)
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
        out[j].width = sat16(w16);
    }
    return (int8_t)n;
}

/* ------------------------------------------------------------------ the work area */

/*
 * The argument check and the work area and O5 arguments from the inputs: false (nothing
 * written) when @p map is NULL, map->n lies outside [3, OPTICAL_MAX_BEACONS] or approx's x or
 * y outside (-OPTICAL_COORD_LIMIT, OPTICAL_COORD_LIMIT); else true and: b, nb from @p map;
 * x, y and head = a16(heading) from @p approx; amax8 = eps8 = min(m8 + 2, 0xFFFF) with m8 =
 * min(ceil(window_pos / 2^8), 0xFFFF) (2^-8 m), lever8 = 0 (as standing); @p wd: dk = (D
 * 10430 mod 2^32) >> 8, x, y as approx, eps8 = m8, tol8 = min(dist_tol >> 8, 0xFFFF), rel16 =
 * min(dist_rel, 0xFFFF), flat.
 */
static bool setup(const optical_map_t *map, const optical_config_t *cfg,
                  const optical_pose_t *approx, optical_width_t *wd)
{
    if (map == NULL || map->n < 3 || map->n > OPTICAL_MAX_BEACONS ||
        !coords_ok(approx->x, approx->y))
        return false;
    W.b = map->b;
    W.nb = map->n;
    W.b8 = map->b8;
    W.ox = map->ox;
    W.oy = map->oy;
    W.x = wd->x = approx->x;
    W.y = wd->y = approx->y;
    W.head = a16(approx->heading);
    /* the expected angles come from offsets floored to 2^-8 m: that adds up to sqrt 2 units
     * to the position uncertainty */
    uint16_t e8 = m8((uint32_t)cfg->window_pos);
    W.amax8 = W.eps8 = sat16((uint32_t)e8 + 2u);
    W.lever8 = 0;
    /* D (m) * 2^8 * 2^16 / (2 pi) = D (Q16) * 10430.378 / 2^8 */
    wd->dk = ((uint32_t)cfg->beacon_diameter * 10430u) >> 8;
    wd->eps8 = e8;
    wd->tol8 = sat16((uint32_t)cfg->dist_tol >> 8);
    wd->rel16 = sat16((uint32_t)cfg->dist_rel);
    wd->flat = cfg->beacon_flat;
    return true;
}

/* The result before any check: nothing identified, no widening (pose, quality and status
 * are written once the outcome is known). */
static void fix_init(optical_fix_t *out)
{
    for (uint8_t i = 0; i < OPTICAL_MAX_SIGHTINGS; i++)
        out->ident[i] = -1;
    out->n_ident = 0;
    out->widened = 0;
}

/* The bucket index of the sorted th[0..n): bstart[b] = the first j with th[j] >> 12 >= b, 0
 * when there is none (b = 0..15). */
static void buckets(void)
{
    uint8_t b = 0;
    for (uint8_t j = 0; j < W.n; j++) /* the buckets up to th[j]'s start at j */
        for (uint8_t bj = (uint8_t)(W.th[j] >> 12); b <= bj; b++)
            W.bstart[b] = j;
    for (; b < 16; b++)
        W.bstart[b] = 0;
}

/* The standing preparation (no latched poses): the sightings @p s by rounded 16-bit angle
 * into th[], ascending (insertion: equal angles keep their input order), ord[j] the input
 * index of th[j]; the bucket index; O4's marks for @p wmin. Returns the sightings kept. */
static uint8_t sort_standing(const optical_sighting_t *s, uint16_t wmin)
{
    for (uint8_t i = 0; i < W.n; i++) {
        uint16_t t = a16(s[i].angle);
        uint8_t j = i;
        while (j > 0 && W.th[j - 1] > t) {
            W.th[j] = W.th[j - 1];
            W.ord[j] = W.ord[j - 1];
            j--;
        }
        W.th[j] = t;
        W.ord[j] = i;
    }
    buckets();
    return optical_drop(s, wmin);
}

/*
 * The both-ways uniqueness: every sorted sighting j whose match k = sm[j] is a beacon is kept
 * when bm[k] = j and its width fits (O5, asked once per (j, k): wchk[j] caches k, bit 7 set
 * for a misfit); otherwise sm[j] becomes NONE. With @p lohi non-NULL, every kept match
 * narrows the heading-offset interval [lohi[0], lohi[1]] (2^-16 turn) to its offset +- its
 * position part. Returns the kept.
 */
static int8_t unique(const optical_width_t *wd, const optical_sighting_t *s, int16_t *lohi)
{
    int8_t found = 0;
    for (uint8_t j = 0; j < W.n; j++) {
        uint8_t k = W.sm[j];
        if (k >= DROPPED)
            continue;
        if (W.u.id.bm[k] == j) {
            uint8_t c = W.wchk[j];
            if ((c & 0x7Fu) != k) {
                c = k;
                if (!optical_width_ok(wd, &W.b[k], s[W.ord[j]].width))
                    c |= 0x80u;
                W.wchk[j] = c;
            }
            if (!(c & 0x80u)) {
                found++;
                if (lohi) { /* lo = max(lo, off - e), hi = min(hi, off + e), in 16 bits */
                    uint16_t off = (uint16_t)(W.th[j] - W.u.id.psi[k]), e = W.we[j];
                    if ((int16_t)off > lohi[0] && (uint16_t)(off - (uint16_t)lohi[0]) > e)
                        lohi[0] = (int16_t)(off - e);
                    if ((int16_t)off < lohi[1] && (uint16_t)((uint16_t)lohi[1] - off) > e)
                        lohi[1] = (int16_t)(off + e);
                }
                continue;
            }
        }
        W.sm[j] = NONE;
    }
    return found;
}

/* O6's plausibility of the fix @p p against the approximate pose @p ap: OPTICAL_E_JUMP beyond
 * cfg->jump_max (|dx| + |dy| <= jump_max bounds the distance without the root), else
 * OPTICAL_E_TURN beyond cfg->turn_max, else OPTICAL_OK. */
static int8_t jump_check(const optical_pose_t *p, const optical_pose_t *ap,
                         const optical_config_t *cfg)
{
    int32_t dx = p->x - ap->x, dy = p->y - ap->y;
    uint32_t jx = umag(dx), jy = umag(dy), jm = (uint32_t)cfg->jump_max;
    if ((jx > jm || jy > jm - jx) && fx_hypot(dx, dy) > jm)
        return OPTICAL_E_JUMP;
    if (umag((int32_t)(p->heading - ap->heading)) > cfg->turn_max)
        return OPTICAL_E_TURN;
    return OPTICAL_OK;
}

/* O6's residuals: of the identified other than the triplet @p t3, the first CHECK_MAX, each
 * beacon's bearing from the fix @p p against its sighting (reference frame, u.sv.ang);
 * OPTICAL_E_DISAGREE at the first beyond @p tol (2^-16 turn), else OPTICAL_OK. */
static int8_t resid_check(const optical_pose_t *p, const uint8_t t3[3], uint16_t tol)
{
    uint16_t h16 = a16(p->heading);
    uint8_t left = CHECK_MAX;
    for (uint8_t i = 0; i < W.m && left; i++) {
        if (i == t3[0] || i == t3[1] || i == t3[2])
            continue;
        left--;
        const optical_xy_t *bk = &W.b[W.sm[W.pos[i]]];
        uint16_t res =
            (uint16_t)(optical_angle16(bk->x - p->x, bk->y - p->y) - h16 - a16(W.u.sv.ang[i]));
        if (abs16(res) > tol)
            return OPTICAL_E_DISAGREE;
    }
    return OPTICAL_OK;
}

/* ------------------------------------------------------------------ identification */

typedef struct {
    const optical_map_t *map;
    const optical_config_t *cfg;
    const optical_pose_t *ap;
    const optical_sighting_t *s;
    const optical_pose_t *latched;
    int8_t *ident;      /* the result's */
    optical_width_t wd; /* O5 */
} ctx_t;

/* Position part of beacon k's window for sorted sighting j, with the margin (as
 * optical_eval). */
static uint16_t pos_part(uint8_t k, uint8_t j)
{
    if (!W.lever8 || !W.lev[j])
        return W.u.id.e[k];
    return (uint16_t)(optical_win(sat16((uint32_t)W.eps8 + W.lev[j]), W.u.id.g[k]) +
                      OPTICAL_MARGIN);
}

/* The seed's overlapping-window rule: k's window meets the window of another beacon. */
__attribute__((noinline)) static bool overlaps(uint8_t k, uint16_t half)
{
    uint32_t wk = 2u * (uint32_t)half + W.u.id.e[k];
    for (uint8_t j = 0; j < W.nb; j++) {
        if (j == k || W.u.id.e[j] == 0)
            continue;
        if (abs16((uint16_t)(W.u.id.psi[j] - W.u.id.psi[k])) < wk + W.u.id.e[j])
            return true;
    }
    return false;
}

/*
 * The seed's overlapping-window rule before the both-ways uniqueness (unique()): a
 * unique match whose window meets another beacon's is dropped (W.sm = NONE), neither
 * width-checked nor counted.
 */
__attribute__((noinline)) static void drop_overlapping(uint16_t half)
{
    for (uint8_t j = 0; j < W.n; j++) {
        uint8_t k = W.sm[j];
        if (k < DROPPED && W.u.id.bm[k] == j && overlaps(k, half))
            W.sm[j] = NONE;
    }
}

enum { IDENT_SAFE = 0, IDENT_GUESS = 1, IDENT_WIDENED = 2 };

/*
 * A guess when the bounds leave fewer than three: the heading offset that the candidate pairs
 * (of the first pass, @p nc of them) of the most sightings agree on (each pair's offset +- its
 * position part, doubled), then the unique matches there. Only a fix that the other sightings
 * confirm may use it.
 */
static int8_t guess(ctx_t *x, uint8_t nc)
{
    const uint8_t *cd = W.u.id.cand;
    int16_t best_h = 0;
    uint16_t best_e = 0;
    uint8_t best_n = 0;
    for (uint8_t c = 0; c < nc; c++) {
        int16_t off_c = (int16_t)(W.th[cd[2 * c]] - W.u.id.psi[cd[2 * c + 1]]);
        uint16_t e_c = pos_part(cd[2 * c + 1], cd[2 * c]);
        uint16_t seen = 0; /* sightings that agree, as a bit set */
        uint8_t cnt = 0;
        for (uint8_t d = 0; d < nc; d++) {
            uint16_t bit = (uint16_t)(1u << cd[2 * d]);
            int16_t off_d = (int16_t)(W.th[cd[2 * d]] - W.u.id.psi[cd[2 * d + 1]]);
            if (!(seen & bit) && (uint32_t)abs16((uint16_t)(off_d - off_c)) <=
                                     (uint32_t)pos_part(cd[2 * d + 1], cd[2 * d]) + e_c) {
                seen |= bit;
                cnt++;
            }
        }
        if (cnt > best_n) {
            best_n = cnt;
            best_h = off_c;
            best_e = e_c;
        }
    }
    if (best_n < 3)
        return 0;
    optical_eval(best_h, best_e);
    return unique(&x->wd, x->s, NULL);
}

/* The half-width of the first pass's windows (optical_fix scans them). */
static uint16_t half0(const optical_config_t *cfg)
{
    uint16_t h = a16(cfg->window);
    return h > 0x7FFAu ? 0x7FFAu : h; /* half + window part below 2^16 */
}

/*
 * Identify (O3-O5), after optical_fix's first scan (mid 0, @p h0 = half0): leaves in W.sm[j] the
 * beacon of each identified sorted sighting (NONE, MULTI or DROPPED otherwise) and returns
 * how many, or -1 when the matches contradict the stated uncertainty. *mode: IDENT_SAFE
 * (within the bounds), IDENT_GUESS or IDENT_WIDENED (the fix must be confirmed by the other
 * sightings). *widened: widenings used.
 */
static int8_t identify(ctx_t *x, uint16_t h0, uint8_t *mode, uint8_t *widened)
{
    const optical_config_t *cfg = x->cfg;
    int16_t hi = (int16_t)h0, lo = (int16_t)-hi;
    uint8_t nc = W.nc; /* the first pass's candidates (0xFF: too many to keep) */
    int8_t found;
    *mode = IDENT_SAFE;
    *widened = 0;
    /* Within the bounds: each safe match narrows the heading interval for the next pass; the
     * narrower windows hold a subset of the first pass's candidates. */
    for (uint8_t pass = 1;; pass++) {
        uint16_t d = (uint16_t)((uint16_t)hi - (uint16_t)lo); /* (hi >= lo) */
        if (pass > 1) {
            int16_t mid = (int16_t)((uint16_t)lo + (d >> 1)); /* floor((lo + hi) / 2) */
            uint16_t half = (uint16_t)((d >> 1) + (d & 1u));  /* ceil((hi - lo) / 2) */
            if (nc != 0xFFu)
                optical_eval(mid, half);
            else
                optical_expect_scan(mid, half);
        }
        int16_t lohi[2] = {lo, hi};
        /* Keep in W.sm only the matches unique both ways (and, when asked, clear of
         * overlapping windows) whose width fits the map distance (O5); narrow the interval to
         * the offsets every kept match allows. */
        if (cfg->reject_overlap)
            drop_overlapping((uint16_t)((d >> 1) + (d & 1u)));
        found = unique(&x->wd, x->s, lohi);
        int16_t nlo = lohi[0], nhi = lohi[1];
        if (nlo > nhi)
            return -1;
        uint32_t nd = (uint16_t)((uint16_t)nhi - (uint16_t)nlo);
        if (pass < MAX_PASSES && found < 3 + CHECK_MAX && (nd << 2) < (uint32_t)d + 2ul * d) {
            lo = nlo; /* tighter by a quarter or more: another pass, never fewer matches */
            hi = nhi;
            continue;
        }
        break;
    }
    if (found >= 3)
        return found;
    /* Beyond the bounds: a guess, then the seed's widening. */
    if (nc != 0xFFu) {
        found = guess(x, nc);
        if (found >= 3) {
            *mode = IDENT_GUESS;
            return found;
        }
    }
    uint32_t step = step_of(a16(cfg->window), a16(cfg->widen_max), cfg->widen_steps);
    int32_t wlo = lo, whi = hi;
    for (uint8_t w = 1; w <= cfg->widen_steps && step; w++) {
        wlo -= (int32_t)step;
        whi += (int32_t)step;
        if (whi - wlo >= 0x8000)
            break;
        int16_t mid = (int16_t)((uint32_t)(wlo + whi) >> 1); /* floor((lo + hi) / 2) */
        uint16_t half = (uint16_t)((uint32_t)(whi - wlo + 1) >> 1);
        optical_expect_scan(mid, half);
        drop_overlapping(half);
        found = unique(&x->wd, x->s, NULL);
        *widened = w;
        if (found >= 3) {
            *mode = IDENT_WIDENED;
            return found;
        }
    }
    return found;
}

/* ------------------------------------------------------------------ fix */

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

static int8_t finish(optical_fix_t *out, int8_t status)
{
    out->status = (uint8_t)status;
    return status;
}

/* A result without a solution: the pose @p ap, quality UINT32_MAX (field by field: no
 * memcpy). */
__attribute__((noinline)) static int8_t fail(optical_fix_t *out, const optical_pose_t *ap,
                                             int8_t status)
{
    out->pose.x = ap->x;
    out->pose.y = ap->y;
    out->pose.heading = ap->heading;
    out->quality = UINT32_MAX;
    return finish(out, status);
}

/* The gathered angles into the reference frame: each turned by its latched heading's change
 * to the reference instant. */
__attribute__((noinline)) static void rotate(const ctx_t *x)
{
    const optical_pose_t *lat = x->latched;
    for (uint8_t i = 0; i < W.m; i++)
        W.u.sv.ang[i] += lat[W.ord[W.pos[i]]].heading - x->ap->heading;
}

/* The identified (sm[j] a beacon), in sorted order, into pos[0..m), their beacons into the
 * result's ident (input order) and their reference-frame angles into u.sv.ang[0..m)
 * (standing: the sightings' own). */
static void gather(const ctx_t *x)
{
    uint8_t m = 0;
    for (uint8_t j = 0; j < W.n; j++) {
        if (W.sm[j] >= DROPPED)
            continue;
        x->ident[W.ord[j]] = (int8_t)W.sm[j];
        W.u.sv.ang[m] = x->s[W.ord[j]].angle;
        W.pos[m++] = j;
    }
    W.m = m;
    if (x->latched != NULL)
        rotate(x);
}

/* solve_triplet() with a parallax lever among the three: the angles refined with the
 * ranges of the fix (O11), @p passes at most. */
__attribute__((noinline)) static int8_t solve_moving(const ctx_t *x, const uint8_t t[3],
                                                     uint8_t passes, optical_tri_t *tri)
{
    optical_xy_t *b = W.u.sv.b;
    fx_angle_t th[3];
    for (uint8_t i = 0; i < 3; i++)
        b[i] = x->map->b[W.sm[W.pos[t[i]]]];
    optical_pose_t p = *x->ap;
    int8_t st = OPTICAL_OK;
    for (uint8_t pass = 0; pass < passes; pass++) {
        for (uint8_t i = 0; i < 3; i++) {
            uint8_t j = W.pos[t[i]];
            th[i] = W.u.sv.ang[t[i]];
            if (W.c[j])
                th[i] = corrected(th[i], j, fx_hypot(b[i].x - p.x, b[i].y - p.y));
        }
        st = optical_triangulate(b, th, x->cfg->quality_max, tri);
        if (st != OPTICAL_OK)
            return st;
        if (pass + 1u >= passes) /* (the last: no need to know how far it moved) */
            break;
        uint32_t moved = fx_hypot(tri->pose.x - p.x, tri->pose.y - p.y);
        p = tri->pose;
        if (moved < 16) /* 0.25 mm */
            break;
    }
    return st;
}

/* Triangulate the triplet at positions t[] of the identified set; when moving, refine the
 * parallax with the ranges of the fix (O11). Standing (no lever among the three): one pass
 * with the angles as gathered (the kernel straight away: no frame to set up). */
static int8_t solve_triplet(const ctx_t *x, const uint8_t t[3], uint8_t passes, optical_tri_t *tri)
{
    if (x->latched != NULL) /* (standing: W.c unset) */
        for (uint8_t i = 0; i < 3; i++)
            if (W.c[W.pos[t[i]]] != 0)
                return solve_moving(x, t, passes, tri);
    return optical_tri_take(x->map->b, t, x->cfg->quality_max, tri);
}

/*
 * O7-O10: select three of the identified (the seed's rule) and triangulate. When that
 * triplet lies too close to its beacons' circle (refused as singular or inconsistent), the
 * triplets with one of its beacons replaced by another identified one are tried, and the
 * best taken.
 */
static int8_t solve(const ctx_t *x, uint8_t passes, uint8_t t[3], optical_tri_t *tri)
{
    optical_select(W.u.sv.ang, W.m, t);
    int8_t st = solve_triplet(x, t, passes, tri);
    if ((st != OPTICAL_E_SINGULAR && st != OPTICAL_E_INCONSISTENT) || W.m <= 3)
        return st;
    uint32_t best = UINT32_MAX;
    uint8_t br = 0, bq = 0; /* the best: t with t[br] = bq */
    for (uint8_t r = 0; r < 3; r++) {
        for (uint8_t q = 0; q < W.m; q++) {
            uint8_t u[3] = {t[0], t[1], t[2]};
            if (q == u[0] || q == u[1] || q == u[2])
                continue;
            u[r] = q;
            if (solve_triplet(x, u, passes, &W.u.sv.tri) == OPTICAL_OK &&
                W.u.sv.tri.quality < best) {
                best = W.u.sv.tri.quality;
                br = r;
                bq = q;
            }
        }
    }
    if (best == UINT32_MAX)
        return st;
    /* the best once more into *tri (the same inputs: the same solution, OPTICAL_OK) */
    t[br] = bq;
    return solve_triplet(x, t, passes, tri);
}

/* O11: the sightings into the vehicle frame of the reference instant, sorted by angle, with
 * their parallax levers, lever8 and amax8 (standing: none, and W.c / W.lev are not read;
 * lever8 = 0 and amax8 = eps8 as setup() left them), and O4's marks for the range
 * T = cfg->range (threshold()); the sightings kept, or -1 when a latched pose lies beyond the
 * coordinate limit. */
static int8_t prepare(ctx_t *x)
{
    const optical_pose_t *ap = x->ap, *lat = x->latched;
    const optical_sighting_t *si = x->s; /* (pointers: no index multiplies on the MSP430) */
    uint16_t lever8 = 0;
    uint8_t n = W.n, kept;
    uint32_t wmin = optical_wmin(x->wd.dk, (uint32_t)x->cfg->range >> 8);
    if (lat == NULL) {
        kept = sort_standing(si, (uint16_t)wmin); /* and the buckets */
        if (wmin > 0xFFFFu)
            kept = optical_drop(si, wmin); /* (none kept) */
    } else {
        for (uint8_t i = 0; i < n; i++, si++, lat++) {
            fx_angle_t d = si->angle;
            int32_t c = 0;
            uint16_t l = 0;
            if (!coords_ok(lat->x, lat->y))
                return -1;
            int32_t ex = lat->x - ap->x, ey = lat->y - ap->y;
            if (ex | ey) {
                /* c = cross(u(d), R(-heading) e) = cross(u(heading + d), e): the sighting's
                 * world direction is its angle plus the latched heading. */
                fx_q30_t sd, cd;
                fx_sincos(d + lat->heading, &sd, &cd);
                c = fx_mul_q30(ey, cd) - fx_mul_q30(ex, sd);
                if (c) {
                    l = m8(umag(c));
                    if (l > lever8)
                        lever8 = l;
                }
            }
            d += lat->heading - ap->heading;
            uint16_t t = a16(d);
            uint8_t j = i;
            while (j > 0 && W.th[j - 1] > t) {
                W.th[j] = W.th[j - 1];
                W.c[j] = W.c[j - 1];
                W.ord[j] = W.ord[j - 1];
                W.lev[j] = W.lev[j - 1];
                j--;
            }
            W.c[j] = c;
            W.lev[j] = l;
            W.th[j] = t;
            W.ord[j] = i;
        }
        buckets();
        kept = optical_drop(x->s, wmin);
        W.lever8 = lever8;
        W.amax8 = sat16((uint32_t)W.eps8 + lever8);
    }
    return (int8_t)kept;
}

/* O4: drop sightings too narrow for a beacon within T; widen T when fewer than 3 stay
 * (@p kept of them at T = cfg->range: prepare() marked them). A post at T looks
 * 2 asin(D / 2T) >= D / T wide: the threshold D / T keeps those. Returns T. */
static fx_q16_t threshold(const ctx_t *x, uint8_t kept)
{
    const optical_config_t *cfg = x->cfg;
    fx_q16_t t = cfg->range;
    for (uint8_t step = 0;; step++) {
        if (kept >= 3 || step >= cfg->range_steps)
            return t;
        /* (the division only when a widening is needed) */
        uint32_t tstep = step_of((uint32_t)cfg->range, (uint32_t)cfg->range_max, cfg->range_steps);
        if (tstep == 0)
            return t;
        t += (fx_q16_t)tstep;
        kept = optical_drop(x->s, optical_wmin(x->wd.dk, (uint32_t)t >> 8));
    }
}

/* O6: implausible jumps and turns, then the other identified sightings must agree (when
 * moving, their angles in W.u.sv.ang corrected for the parallax first: the fix's last use). */
static int8_t check(const ctx_t *x, const optical_pose_t *p, const uint8_t t3[3])
{
    int8_t st = jump_check(p, x->ap, x->cfg);
    if (st != OPTICAL_OK)
        return st;
    if (x->latched != NULL) {
        uint8_t left = CHECK_MAX;
        for (uint8_t i = 0; i < W.m && left; i++) {
            if (i == t3[0] || i == t3[1] || i == t3[2])
                continue;
            left--;
            uint8_t j = W.pos[i];
            if (W.c[j]) {
                const optical_xy_t *bk = &W.b[W.sm[j]];
                W.u.sv.ang[i] = corrected(W.u.sv.ang[i], j, fx_hypot(bk->x - p->x, bk->y - p->y));
            }
        }
    }
    return resid_check(p, t3, (uint16_t)(a16(x->cfg->resid_max) + 3u));
}

int8_t optical_fix(const optical_map_t *map, const optical_config_t *cfg,
                   const optical_pose_t *approx, const optical_sighting_t *s, uint8_t n,
                   const optical_pose_t *latched, optical_fix_t *out)
{
    fix_init(out);
    ctx_t x;
    if (n > OPTICAL_MAX_SIGHTINGS || !setup(map, cfg, approx, &x.wd))
        return fail(out, approx, OPTICAL_E_ARG);
    x.map = map;
    x.cfg = cfg;
    x.ap = approx;
    x.s = s;
    x.latched = latched;
    x.ident = out->ident;
    W.n = n;

    int8_t kept = prepare(&x);
    if (kept < 0)
        return fail(out, approx, OPTICAL_E_ARG);
    /* O4, then O2: expected angles of the beacons within T (+ the position uncertainty),
     * and the first identification pass (O3). */
    W.gate8 = sat15(((uint32_t)threshold(&x, (uint8_t)kept) + (uint32_t)cfg->window_pos) >> 8);
    uint16_t h0 = half0(cfg);
    if (optical_scan(0, h0)) /* (O4 left every mark NONE or DROPPED) */
        return fail(out, approx, OPTICAL_E_ARG);
    if (n < 3)
        return fail(out, approx, OPTICAL_E_FEW);

    /* O3-O5 */
    uint8_t mode, widened;
    int8_t found = identify(&x, h0, &mode, &widened);
    out->widened = widened;
    if (found < 0)
        return fail(out, approx, OPTICAL_E_INCONSISTENT);
    if (found < 3) { /* (found: the identified, as gather would count them) */
        out->n_ident = (uint8_t)found;
        return fail(out, approx, OPTICAL_E_FEW);
    }
    gather(&x);

    /* O7-O11 */
    uint8_t passes = cfg->motion_passes ? cfg->motion_passes : 1u;
    uint8_t t3[3];
    optical_tri_t tri;
    int8_t st = solve(&x, passes, t3, &tri);
    if (st == OPTICAL_OK && mode != IDENT_SAFE) {
        /* Beyond the bounds the identification is a hypothesis: identify again from the fix
         * (5 cm, the residual tolerance) and use it only when at least five sightings agree. */
        uint16_t rmax = a16(cfg->resid_max);
        x.wd.eps8 = 13;
        W.eps8 = 15;
        W.amax8 = sat16(15ul + W.lever8);
        W.x = x.wd.x = tri.pose.x;
        W.y = x.wd.y = tri.pose.y;
        W.head = a16(tri.pose.heading);
        for (uint8_t j = 0; j < n; j++)
            W.wchk[j] = 0x7Fu;
        optical_expect_scan(0, rmax);
        fix_init(out); /* (none identified: gather wrote ident) */
        out->widened = widened;
        if (unique(&x.wd, x.s, NULL) < 5)
            return fail(out, approx, OPTICAL_E_UNCONFIRMED);
        gather(&x);
        st = solve(&x, passes, t3, &tri);
    }
    out->n_ident = W.m;
    if (st != OPTICAL_OK && st != OPTICAL_E_SINGULAR)
        return fail(out, approx, st);
    out->pose.x = tri.pose.x; /* (field by field, unrolled: no memcpy, no counter) */
    out->pose.y = tri.pose.y;
    out->pose.heading = tri.pose.heading;
    out->quality = tri.quality;
    out->used[0] = W.sm[W.pos[t3[0]]];
    out->used[1] = W.sm[W.pos[t3[1]]];
    out->used[2] = W.sm[W.pos[t3[2]]];
    if (st == OPTICAL_OK)
        st = check(&x, &tri.pose, t3);
    return finish(out, st);
}
