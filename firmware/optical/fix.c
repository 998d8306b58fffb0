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

/* Heading-interval refinement passes at most, and the identified beyond three that end them
 * early (enough to check the fix). */
#define MAX_PASSES  6
#define PASS_ENOUGH 4

/* The work area (fastmath.h: the kernels share it). */
#define W (optical_work)

static const optical_config_t defaults = OPTICAL_CONFIG_DEFAULT;

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

/* Do beacons i and j overlap: centres closer than the sum of their radii (d_i + d_j) / 2?
 * In 2^-12 m (each component and the sum floored: the squares stay within 32 bits). */
static bool coincide(const optical_xy_t *b, const optical_refl_t *r, uint8_t i, uint8_t j)
{
    uint32_t rs = ((uint32_t)r[i].d + (uint32_t)r[j].d) >> 5;
    uint32_t dx = umag(b[i].x - b[j].x) >> 4, dy = umag(b[i].y - b[j].y) >> 4;
    return dx < rs && dy < rs && dx * dx + dy * dy < rs * rs;
}

static int8_t compile_fail(uint8_t bad[2], uint8_t i, uint8_t j, int8_t st)
{
    if (bad) {
        bad[0] = i;
        bad[1] = j;
    }
    return st;
}

int8_t optical_map_compile(optical_map_t *map, const optical_xy_t *b, const optical_refl_t *refl,
                           uint8_t n, optical_xy8_t *b8, uint32_t *dk, uint8_t bad[2])
{
    if (map == NULL || b == NULL || refl == NULL || b8 == NULL || dk == NULL || n < 3 ||
        n > OPTICAL_MAX_BEACONS)
        return compile_fail(bad, 0, 0, OPTICAL_E_ARG);
    int32_t lo[2] = {INT32_MAX, INT32_MAX}, hi[2] = {INT32_MIN, INT32_MIN};
    fx_q16_t dmin = OPTICAL_REFL_MAX;
    for (uint8_t k = 0; k < n; k++) {
        if (!coords_ok(b[k].x, b[k].y) || refl[k].d <= 0 || refl[k].d > OPTICAL_REFL_MAX)
            return compile_fail(bad, k, k, OPTICAL_E_ARG);
        dmin = refl[k].d < dmin ? refl[k].d : dmin;
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
            return compile_fail(bad, 0, 0, OPTICAL_E_ARG);
    }
    for (uint8_t i = 0; i < n; i++)
        for (uint8_t j = (uint8_t)(i + 1u); j < n; j++)
            if (coincide(b, refl, i, j))
                return compile_fail(bad, i, j, OPTICAL_E_DEGENERATE);
    for (uint8_t k = 0; k < n; k++) { /* floor((b - o) / 2^8), in [-2^15, 2^15) */
        b8[k].x = (int16_t)(uint16_t)((uint32_t)(b[k].x - o[0]) >> 8);
        b8[k].y = (int16_t)(uint16_t)((uint32_t)(b[k].y - o[1]) >> 8);
        dk[k] = optical_dk(refl[k].d) | (refl[k].flat ? OPTICAL_DK_FLAT : 0u);
    }
    map->b = b;
    map->n = n;
    map->b8 = b8;
    map->ox = o[0];
    map->oy = o[1];
    map->dk = dk;
    map->dkmin = optical_dk(dmin);
    return OPTICAL_OK;
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
 * min(ceil(@p pos / 2^8), 0xFFFF) (2^-8 m: the windows' position uncertainty), lever8 = 0 (as
 * standing); @p wd: x, y as approx, eps8 = m8, tol8 = min(dist_tol >> 8, 0xFFFF), rel16 =
 * min(dist_rel, 0xFFFF).
 */
static bool setup(const optical_map_t *map, const optical_config_t *cfg,
                  const optical_pose_t *approx, fx_q16_t pos, optical_width_t *wd)
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
    uint16_t e8 = m8((uint32_t)pos);
    W.amax8 = W.eps8 = sat16((uint32_t)e8 + 2u);
    W.lever8 = 0;
    wd->eps8 = e8;
    wd->tol8 = sat16((uint32_t)cfg->dist_tol >> 8);
    wd->rel16 = sat16((uint32_t)cfg->dist_rel);
    return true;
}

/* The result before any check: nothing identified, no widening (pose, quality and status
 * are written once the outcome is known). */
static void fix_init(optical_fix_t *out)
{
    for (uint8_t i = 0; i < OPTICAL_MAX_SIGHTINGS; i++)
        out->ident[i] = -1;
    out->n_ident = 0;
    out->n_agree = 0;
    out->n_dropped = 0;
    out->widened = 0;
    out->gate = 0;
    out->resid = 0;
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
 * when bm[k] = j and its width fits beacon k's compiled reflector @p dk[k] (O5, asked once per (j,
 * k): wchk[j] caches k, bit 7 set for a misfit); otherwise sm[j] becomes NONE. With @p lohi
 * non-NULL, every kept match narrows the heading-offset interval [lohi[0], lohi[1]] (2^-16 turn) to
 * its offset +- its position part. Returns the kept.
 */
static int8_t unique(const optical_width_t *wd, const uint32_t *dk, const optical_sighting_t *s,
                     int16_t *lohi)
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
                if (!optical_width_ok(wd, &W.b[k], dk[k], s[W.ord[j]].width))
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

/* Error bounds are capped at 4096 m (2^28 in Q16): four of them and a dead-reckoning
 * uncertainty (at most jump_max, 8192 m) add up within int32. */
#define ERR_CAP (1l << 28)

/* The length of (dx, dy) (Q16 m) in 2^-8 m, at least the length and at most 3 units more
 * (each component's floor plus one, the root's floor plus one); 0xFFFF when a component
 * reaches 181 m (the squares' sum would pass 32 bits). */
static uint16_t len8(int32_t dx, int32_t dy)
{
    uint32_t ax = umag(dx), ay = umag(dy);
    if ((ax | ay) >= 0xB50000ul)
        return 0xFFFFu;
    uint16_t x8 = (uint16_t)(ax >> 8) + 1u, y8 = (uint16_t)(ay >> 8) + 1u;
    return (uint16_t)(fx_sqrt32((uint32_t)x8 * x8 + (uint32_t)y8 * y8) + 1u);
}

/* Milliradians of the binary angle @p a in 2^-8 mrad, rounded up (a bound stays a bound):
 * a 2 pi 1000 2^8 / 2^32 = (a / 2^8) 6283.19 / 2^16, with a / 2^8 rounded up and the floor
 * plus one; 0xFFFF from 14.6 degrees on. */
static uint16_t mrad8_of(fx_angle_t a)
{
    uint32_t a24 = (a >> 8) + 1u;
    return a24 >= 0xFFFFFFFFul / 6284u ? 0xFFFFu : sat16(((a24 * 6284u) >> 16) + 1u);
}

/* The predicted position error bound of a fix of quality @p q (Q16 m per mrad) for bearing
 * errors of @p mrad8 (2^-8 mrad): q mrad8 / 2^8 rounded up, Q16 m, at most ERR_CAP (two
 * 16 x 16 products: no 64-bit arithmetic on the fix's path). */
static fx_q16_t err_of(uint32_t q, uint16_t mrad8)
{
    uint32_t hi = (uint32_t)(uint16_t)(q >> 16) * mrad8, lo = (uint32_t)(uint16_t)q * mrad8;
    if (q >= (uint32_t)ERR_CAP || hi >= (1ul << 20))
        return ERR_CAP;
    uint32_t v = (hi << 8) + (lo >> 8) + ((lo & 0xFFu) != 0u);
    return v < (uint32_t)ERR_CAP ? (fx_q16_t)v : ERR_CAP;
}

/* The octagonal norm of (dx, dy) (Q16 m) in 2^-8 m, each component capped at 256 m: between
 * the length and 1.118 times it. */
static uint16_t oct8(int32_t dx, int32_t dy)
{
    uint32_t ax = umag(dx), ay = umag(dy);
    uint16_t x8 = ax >= (1ul << 24) ? 0xFFFFu : (uint16_t)(ax >> 8);
    uint16_t y8 = ay >= (1ul << 24) ? 0xFFFFu : (uint16_t)(ay >> 8);
    return sat16(x8 > y8 ? x8 + (uint32_t)(y8 >> 1) : y8 + (uint32_t)(x8 >> 1));
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
    optical_unc_t u;    /* the dead-reckoning uncertainty of ap (the gate's) */
    uint16_t mrad8;     /* the bearing error bound (standing or moving), 2^-8 mrad */
    uint16_t wtol;      /* the width check's tolerance, 2^-16 turn (below 2^12) */
    uint16_t rtol;      /* the residuals' tolerance: the bearing error bound plus the
                           roundings of res and optical_angle16's error, 2^-16 turn */
    uint8_t moving;     /* a sighting's latched pose differs from ap */
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
    return unique(&x->wd, x->map->dk, x->s, NULL);
}

/* The half-width of the first pass's windows (optical_fix scans them): the heading
 * uncertainty @p u, at most cfg->window. */
static uint16_t half0(const optical_config_t *cfg, fx_angle_t u)
{
    uint16_t h = a16(u < cfg->window ? u : cfg->window);
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
        found = unique(&x->wd, x->map->dk, x->s, lohi);
        int16_t nlo = lohi[0], nhi = lohi[1];
        if (nlo > nhi)
            return -1;
        uint32_t nd = (uint16_t)((uint16_t)nhi - (uint16_t)nlo);
        if (pass < MAX_PASSES && found < 3 + PASS_ENOUGH && (nd << 2) < (uint32_t)d + 2ul * d) {
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
    uint32_t step = step_of(h0, a16(cfg->widen_max), cfg->widen_steps);
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
        found = unique(&x->wd, x->map->dk, x->s, NULL);
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
    out->err = INT32_MAX;
    out->err_heading = 0xFFFFFFFFul;
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
 * The centre bias bound of sorted sighting j (identified) in the fix @p p, 2^-8 mrad: a pulse
 * wider than its beacon looks from its range (merged with a glint or a post behind) or
 * narrower (a post partly screened; not a flat strip, which looks narrower when turned) has
 * its centre off by up to half the difference. optical_width_excess() compares them, the
 * range from where the sighting was taken (p plus its latched offset when moving) within
 * -3.1 % and +0.7 %, the beacon's width dk / r8 (2 asin(D / 2r) = D / r within 0.04 % from
 * r = 10 D); tolerated: x->wtol (two edges, each within the standing bound) plus 1/16 of the
 * width (the range's approximation and rounding). The excess / (2 r8), rounded up, is the
 * bias; 0 within (or beyond 128 m).
 */
static uint16_t bias_of(const ctx_t *x, uint8_t j, const optical_pose_t *p)
{
    uint8_t k = W.sm[j];
    uint32_t dkf = x->map->dk[k];
    optical_wx_t a;
    a.dx = W.b[k].x - p->x;
    a.dy = W.b[k].y - p->y;
    if (x->latched != NULL) {
        const optical_pose_t *l = &x->latched[W.ord[j]];
        a.dx -= l->x - x->ap->x;
        a.dy -= l->y - x->ap->y;
    }
    a.dk = dkf & ~OPTICAL_DK_FLAT;
    a.w = x->s[W.ord[j]].width;
    a.tol = (uint16_t)(x->wtol | (dkf & OPTICAL_DK_FLAT ? 0x8000u : 0u));
    uint32_t ex = optical_width_excess(&a);
    if (ex == 0)
        return 0;
    /* ex / (2 r8) units of 2^-16 turn, in 2^-8 mrad: times 2 pi 1000 2^8 / 2^16 (24.54) */
    uint32_t u = ex / a.r8 + 1u;
    return u > 5000u ? 0xFFFFu : (uint16_t)((u * 1571u >> 6) + 1u);
}

/* The predicted error bound of the triplet at positions @p t (its solution @p tri): the
 * quality times the bearing error bound, plus the quality times each sighting's centre bias
 * (bias_of: |g_i| <= quality for each column of the error's linearisation); each term at most
 * ERR_CAP. */
static fx_q16_t e_total(const ctx_t *x, const uint8_t t[3], const optical_tri_t *tri)
{
    fx_q16_t e = err_of(tri->quality, x->mrad8);
    for (uint8_t i = 0; i < 3; i++) {
        uint16_t b = bias_of(x, W.pos[t[i]], &tri->pose);
        if (b)
            e += err_of(tri->quality, b);
    }
    return e;
}

/*
 * O7-O10: select three of the identified (the seed's rule) and triangulate. When that
 * triplet lies too close to its beacons' circle (refused as singular or inconsistent), or its
 * predicted error (e_total: its geometry and its pulses' widths) exceeds err_max, the triplets
 * with one of its beacons replaced by another identified one are tried, and the one of the
 * smallest predicted error taken when it is smaller. *err: the predicted error of *tri
 * (INT32_MAX when it has none).
 */
static int8_t solve(const ctx_t *x, uint8_t passes, uint8_t t[3], optical_tri_t *tri, fx_q16_t *err)
{
    optical_select(W.u.sv.ang, W.m, t);
    int8_t st = solve_triplet(x, t, passes, tri);
    *err = st == OPTICAL_OK ? e_total(x, t, tri) : INT32_MAX;
    bool weak = st == OPTICAL_OK && *err > x->cfg->err_max;
    if ((st != OPTICAL_E_SINGULAR && st != OPTICAL_E_INCONSISTENT && !weak) || W.m <= 3)
        return st;
    fx_q16_t best = weak ? *err : INT32_MAX;
    uint8_t br = 0, bq = 0xFFu; /* the best: t with t[br] = bq */
    for (uint8_t r = 0; r < 3; r++) {
        for (uint8_t q = 0; q < W.m; q++) {
            uint8_t u[3] = {t[0], t[1], t[2]};
            if (q == u[0] || q == u[1] || q == u[2])
                continue;
            u[r] = q;
            if (solve_triplet(x, u, passes, &W.u.sv.tri) != OPTICAL_OK)
                continue;
            fx_q16_t e = e_total(x, u, &W.u.sv.tri);
            if (e < best) {
                best = e;
                br = r;
                bq = q;
            }
        }
    }
    if (bq == 0xFFu)
        return st; /* (weak: *tri and *err are still the selected triplet's) */
    /* the best once more into *tri (the same inputs: the same solution, OPTICAL_OK) */
    t[br] = bq;
    *err = best;
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
    uint32_t wmin = optical_wmin(x->map->dkmin, (uint32_t)x->cfg->range >> 8);
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
            if (ex | ey | (int32_t)(lat->heading - ap->heading))
                x->moving = 1;
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
        kept = optical_drop(x->s, optical_wmin(x->map->dkmin, (uint32_t)t >> 8));
    }
}

/*
 * O6's residuals: every identified sighting i other than the triplet @p t3 (its reference-frame
 * angle u.sv.ang[i], corrected for the parallax seen from the fix when moving) against the
 * direction of its beacon from the fix @p p: res = angle16(B - p) - heading - angle (2^-16
 * turn). It agrees when |res| <= tol16 + err / r, r the beacon's range: the sighting's own
 * error bound plus what the fix's predicted error @p err8 (2^-8 m) can turn the direction by.
 * Without division: (|res| - tol16) r_lo <= err8 2^16 / (2 pi), r_lo = o / 1.118 <= r from the
 * octagonal norm o (2^-8 m). *agree counts those that agree, *worst is their largest |res|;
 * returns the outliers as a bit set over i.
 */
static uint16_t residuals(const ctx_t *x, const optical_pose_t *p, const uint8_t t3[3],
                          uint16_t tol16, uint16_t err8, uint8_t *agree, uint16_t *worst)
{
    uint16_t h16 = a16(p->heading), outl = 0, wst = 0;
    uint32_t lat = (uint32_t)err8 * 10430u; /* err8 2^16 / (2 pi) */
    uint8_t ag = 0;
    for (uint8_t i = 0; i < W.m; i++) {
        if (i == t3[0] || i == t3[1] || i == t3[2])
            continue;
        uint8_t j = W.pos[i];
        const optical_xy_t *bk = &W.b[W.sm[j]];
        int32_t dx = bk->x - p->x, dy = bk->y - p->y;
        fx_angle_t ang = W.u.sv.ang[i];
        if (x->latched != NULL && W.c[j])
            ang = corrected(ang, j, fx_hypot(dx, dy));
        uint16_t res = abs16((uint16_t)(optical_angle16(dx, dy) - h16 - a16(ang)));
        if (res > tol16) {
            uint32_t rlo = ((uint32_t)oct8(dx, dy) * 58623u) >> 16; /* / 1.118 */
            if ((uint32_t)(res - tol16) * rlo > lat) {
                outl |= (uint16_t)(1u << i);
                continue;
            }
        }
        ag++;
        wst = res > wst ? res : wst;
    }
    *agree = ag;
    *worst = wst;
    return outl;
}

/*
 * O6, the acceptance of the fix @p p (solved from the triplet @p t3; out->err and
 * out->err_heading its predicted error bounds): within the dead-reckoning gate (x->u plus its
 * own predicted error, out->gate; compared in 2^-8 m, len8's distance up to 3 units long) of the
 * approximate pose (OPTICAL_E_JUMP, OPTICAL_E_TURN); then every other identified
 * sighting must agree (residuals()); outliers are dropped (their ident -1) when the others
 * that agree are at least three and at least three times as many, otherwise the fix is
 * refused (OPTICAL_E_DISAGREE). Writes out->gate, resid, n_agree, n_dropped.
 */
static int8_t check(const ctx_t *x, const optical_pose_t *p, const uint8_t t3[3],
                    optical_fix_t *out)
{
    out->gate = x->u.pos + out->err;
    /* (in 2^-8 m: the distance up to 3 units long, the bound rounded up; no root when
     * |dx| + |dy| is within the gate) */
    int32_t dx = p->x - x->ap->x, dy = p->y - x->ap->y;
    uint16_t g8 = m8((uint32_t)out->gate);
    if (m8(umag(dx)) + (uint32_t)m8(umag(dy)) > g8 && len8(dx, dy) > g8)
        return OPTICAL_E_JUMP;
    /* (the uncertainty at most turn_max, a half turn; the bound at most 10 degrees) */
    if (umag((int32_t)(p->heading - x->ap->heading)) > x->u.heading + out->err_heading)
        return OPTICAL_E_TURN;
    uint8_t agree;
    uint16_t outl = residuals(x, p, t3, x->rtol, m8((uint32_t)out->err), &agree, &out->resid);
    out->n_agree = (uint8_t)(3u + agree);
    if (outl == 0)
        return OPTICAL_OK;
    uint8_t k = 0;
    for (uint16_t b = outl; b; b &= (uint16_t)(b - 1u))
        k++;
    if (agree < 3 || agree < 3u * k)
        return OPTICAL_E_DISAGREE;
    for (uint8_t i = 0; i < W.m; i++)
        if (outl & (1u << i))
            x->ident[W.ord[W.pos[i]]] = -1;
    out->n_dropped = k;
    return OPTICAL_OK;
}

int8_t optical_fix(const optical_map_t *map, const optical_config_t *cfg,
                   const optical_pose_t *approx, const optical_unc_t *unc,
                   const optical_sighting_t *s, uint8_t n, const optical_pose_t *latched,
                   optical_fix_t *out)
{
    fix_init(out);
    ctx_t x;
    if (unc != NULL) {
        x.u = *unc;
    } else {
        x.u.pos = cfg->jump_max;
        x.u.heading = cfg->turn_max;
    }
    /* the windows cover the uncertainty, at most window_pos and window */
    fx_q16_t wpos = x.u.pos < cfg->window_pos ? x.u.pos : cfg->window_pos;
    if (n > OPTICAL_MAX_SIGHTINGS || x.u.pos < 0 || !setup(map, cfg, approx, wpos, &x.wd))
        return fail(out, approx, OPTICAL_E_ARG);
    x.map = map;
    x.cfg = cfg;
    x.ap = approx;
    x.s = s;
    x.latched = latched;
    x.ident = out->ident;
    x.moving = 0;
    W.n = n;

    int8_t kept = prepare(&x);
    if (kept < 0)
        return fail(out, approx, OPTICAL_E_ARG);
    fx_angle_t bearing = x.moving ? cfg->bearing_err_moving : cfg->bearing_err;
    x.mrad8 = mrad8_of(bearing);
    x.rtol = (uint16_t)(a16(bearing) + 3u);
    /* two edges, each within the standing bound (at most 2^12 - 1) */
    x.wtol = (uint16_t)(2u * (a16(cfg->bearing_err) > 2046u ? 2046u : a16(cfg->bearing_err)) + 2u);
    /* O4, then O2: expected angles of the beacons within T (+ the position uncertainty),
     * and the first identification pass (O3). */
    W.gate8 = sat15(((uint32_t)threshold(&x, (uint8_t)kept) + (uint32_t)wpos) >> 8);
    uint16_t h0 = half0(cfg, x.u.heading);
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
    fx_q16_t err;
    int8_t st = solve(&x, passes, t3, &tri, &err);
    /* the fix's heading error bound: a sighting's */
    out->err_heading = bearing;
    if (st == OPTICAL_OK && mode != IDENT_SAFE) {
        /* Beyond the bounds the identification is a hypothesis: identify again from the fix
         * (5 cm, and its heading error bound) and use it only when at least five sightings
         * agree. */
        x.wd.eps8 = 13;
        W.eps8 = 15;
        W.amax8 = sat16(15ul + W.lever8);
        W.x = x.wd.x = tri.pose.x;
        W.y = x.wd.y = tri.pose.y;
        W.head = a16(tri.pose.heading);
        for (uint8_t j = 0; j < n; j++)
            W.wchk[j] = 0x7Fu;
        optical_expect_scan(0, a16(out->err_heading));
        fix_init(out); /* (none identified: gather wrote ident) */
        out->widened = widened;
        if (unique(&x.wd, map->dk, x.s, NULL) < 5)
            return fail(out, approx, OPTICAL_E_UNCONFIRMED);
        gather(&x);
        st = solve(&x, passes, t3, &tri, &err);
    }
    out->n_ident = W.m;
    /* (singular with a solution: its pose and quality are reported, not used) */
    if (st != OPTICAL_OK && (st != OPTICAL_E_SINGULAR || tri.quality == UINT32_MAX))
        return fail(out, approx, st);
    out->pose.x = tri.pose.x; /* (field by field, unrolled: no memcpy, no counter) */
    out->pose.y = tri.pose.y;
    out->pose.heading = tri.pose.heading;
    out->quality = tri.quality;
    out->err = err;
    out->used[0] = W.sm[W.pos[t3[0]]];
    out->used[1] = W.sm[W.pos[t3[1]]];
    out->used[2] = W.sm[W.pos[t3[2]]];
    if (st == OPTICAL_OK && err > cfg->err_max)
        st = OPTICAL_E_POOR;
    if (st == OPTICAL_OK)
        st = check(&x, &tri.pose, t3, out);
    return finish(out, st);
}
