/*
 * fix.c - one revolution's fix (SPEC O2-O7, O11, O6): the pipeline of optical/optical.h.
 *
 * Identification works on 16-bit angles (2^-16 turn, 0.0055 degrees): the expected angle of
 * a beacon comes from the fast arctangent, and every window is a bound of what the pose
 * uncertainty allows, so a sighting of beacon j always lies in j's window and an identification
 * is safe when it is unique both ways (one beacon for the sighting, one sighting for the
 * beacon). The bound for beacon k is
 *     offset interval (heading)  +-  asin((eps + |c_i|) / r_k)  + margin
 * with eps the position uncertainty, c_i the sighting's parallax lever (moving vehicle) and
 * r_k the range from the approximate position. 1 / r_k is bounded from above cheaply by the
 * octagonal norm and its leading bit (at most 1.5 times the true value), so the windows are
 * never too narrow. Every safe match shrinks the heading interval (it must contain the match's
 * offset +- its position part), which narrows all windows for the next pass. Only when fewer
 * than three remain are the windows widened beyond the bounds (the seed's computed step, a
 * bounded number of times); then the seed's overlapping-window rule applies too.
 */
#include <stdbool.h>
#include <stddef.h>

#include "optical/optical.h"

#define NONE  0xFFu /* no match */
#define MULTI 0xFEu /* more than one match */

/* Identification margin, 2^-16 turn: fast arctangent (1), rounding to 16 bits (1), the
 * centre of a pulse quantised to half a count (0.7). */
#define MARGIN 4

/* Refinement passes of the heading interval, and the shrink that makes one worth it. */
#define MAX_PASSES 6

/* 2^16 / (2 pi) * asin(x) <= 10923 x for x <= 1/2; times 1.118 for the octagonal norm. */
#define GK_NUM 12212ul

/* Work area of optical_fix (not reentrant). */
static struct {
    uint16_t psi[OPTICAL_MAX_BEACONS];  /* expected angle, 2^-16 turn, relative to approx */
    uint16_t g[OPTICAL_MAX_BEACONS];    /* bound of 2^16/(2 pi) asin(1 m / r), 0: gated out */
    uint8_t bm[OPTICAL_MAX_BEACONS];    /* per beacon: sighting matched, NONE or MULTI */
    uint16_t th[OPTICAL_MAX_SIGHTINGS]; /* sighting angles in the reference frame, sorted */
    uint8_t ord[OPTICAL_MAX_SIGHTINGS]; /* input index of th[j] */
    uint8_t sm[OPTICAL_MAX_SIGHTINGS];  /* per sorted sighting: beacon matched, NONE, MULTI */
    uint8_t keep[OPTICAL_MAX_SIGHTINGS];
    uint16_t lever[OPTICAL_MAX_SIGHTINGS]; /* |c_i| in 2^-8 m (moving), 0 standing */
    int32_t c[OPTICAL_MAX_SIGHTINGS];      /* c_i = cross(u_i, o_i), Q16 m (moving) */
    fx_angle_t d[OPTICAL_MAX_SIGHTINGS];   /* precise angles in the reference frame */
    uint8_t bstart[17];                    /* first sorted sighting of each 1/16 turn */
} W;

void optical_config_default(optical_config_t *cfg)
{
    cfg->beacon_diameter = 5243; /* 0.08 m */
    cfg->beacon_flat = 0;
    cfg->window = 59652324ul;    /* 5 degrees */
    cfg->window_pos = 19661;     /* 0.3 m */
    cfg->widen_max = 119304647ul; /* 10 degrees */
    cfg->widen_steps = 2;
    cfg->reject_overlap = 0;
    cfg->range = 30l * FX_Q16_ONE;
    cfg->range_max = 60l * FX_Q16_ONE;
    cfg->range_steps = 2;
    cfg->dist_tol = 32768; /* 0.5 m */
    cfg->dist_rel = 19661; /* 0.3 */
    cfg->jump_max = 32768; /* 0.5 m */
    cfg->turn_max = 83513454ul; /* 7 degrees */
    cfg->resid_max = 2386093ul; /* 0.2 degrees */
    cfg->quality_max = 16384; /* 0.25 m per mrad: 3.1 cm per count */
    cfg->motion_passes = 3;
}

/* ------------------------------------------------------------------ revolution */

int8_t optical_rev_sightings(const optical_rev_t *rev, uint16_t counts_per_turn,
                             optical_sighting_t *out)
{
    if (rev->cov || rev->period != counts_per_turn || counts_per_turn == 0)
        return -1;
    uint8_t n = rev->n;
    if (n > OPTICAL_MAX_SIGHTINGS)
        return -1;
    for (uint8_t i = 0; i < n; i++) {
        uint16_t st = rev->s[i].start;
        uint32_t start = (int16_t)st < 0 ? (uint32_t)counts_per_turn - (uint16_t)(0u - st)
                                         : (uint32_t)st;
        fx_angle_t w = fx_angle_from_counts(rev->s[i].width, counts_per_turn);
        if (rev->s[i].width >= counts_per_turn)
            w = 0xFFFFFFFFul;
        fx_angle_t a = fx_angle_from_counts(start, counts_per_turn) + (w >> 1);
        uint32_t w16 = (w >> 16) + ((w >> 15) & 1u);
        /* Insertion by angle: the sightings arrive in order except one straddling the index. */
        uint8_t j = i;
        while (j > 0 && out[j - 1].angle > a) {
            out[j] = out[j - 1];
            j--;
        }
        out[j].angle = a;
        out[j].width = w16 > 0xFFFFu ? 0xFFFFu : (uint16_t)w16;
    }
    return (int8_t)n;
}

/* ------------------------------------------------------------------ helpers */

static uint32_t umag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static uint16_t a16(fx_angle_t a)
{
    return (uint16_t)((a + 0x8000ul) >> 16);
}

/*
 * Upper bound of 12212 / r for the octagonal norm r = max + min / 2 of (|dx|, |dy|) in Q16
 * metres, i.e. of 2^16 / (2 pi) * asin(1 m / true range) when the range is at least 2 m;
 * 0xFFFF below 2 m (then the beacon's direction bound is taken as unlimited).
 */
static uint16_t g_bound(uint32_t r)
{
    if (r < 2ul * FX_Q16_ONE)
        return 0xFFFFu;
    /* r in [2^p, 2^(p+1)), p >= 17: 12212 / r <= 12212 * 2^16 / 2^p; when r >= 1.5 * 2^p,
     * <= that * 2 / 3. */
    uint8_t p = 17;
    uint32_t t = r >> 18;
    while (t) {
        t >>= 1;
        p++;
    }
    uint32_t g = (GK_NUM << 16) >> p; /* p <= 31 */
    if (r >= (3ul << (p - 1)))
        g = (g * 2u + 2u) / 3u;
    return (uint16_t)(g + 1u);
}

/* (a * g) / 256 rounded up, a in 2^-8 m, capped at 0x7FFF. */
static uint16_t win_part(uint16_t a, uint16_t g)
{
    if (g == 0xFFFFu)
        return 0x7FFFu;
    uint32_t v = ((uint32_t)a * g + 255u) >> 8;
    return v > 0x7FFFu ? 0x7FFFu : (uint16_t)v;
}

/* Metres Q16 to 2^-8 m, saturating at 255.99 m. */
static uint16_t m8(uint32_t q16)
{
    uint32_t v = (q16 + 255u) >> 8;
    return v > 0xFFFFu ? 0xFFFFu : (uint16_t)v;
}

/*
 * Width threshold of distance T: a post of diameter D at T looks 2 asin(D / 2T) wide (flat:
 * 2 atan(D / 2T)); in 2^-16 turn, rounded down.
 */
static uint16_t width_at(fx_q16_t diameter, fx_q16_t t, uint8_t flat)
{
    int32_t ratio;
    if (t <= 0 || !fx_div_shift(diameter, 2 * t, 30, &ratio) || ratio >= FX_Q30_ONE)
        return 0;
    fx_angle_t half = flat ? fx_atan_ratio(ratio, FX_Q30_ONE) : fx_asin(ratio);
    return (uint16_t)(half >> 15);
}

/*
 * O5: is the apparent width @p w16 compatible with a beacon at map distance between rlo and
 * rhi (Q16)? Width distance dw = D / (2 sin(w/2)) (flat: D / (2 tan(w/2)), an upper bound).
 * Accept when [rlo - tol, rhi + tol] meets dw (flat: when rlo - tol <= dw), tol = dist_tol +
 * dist_rel * rhi. Multiplied out: (rlo - tol) 2 sin(w/2) <= D <= (rhi + tol) 2 sin(w/2).
 */
static bool width_matches(const optical_config_t *cfg, uint16_t w16, uint32_t rlo, uint32_t rhi)
{
    int32_t tol = cfg->dist_tol + fx_mul_q16((int32_t)rhi, cfg->dist_rel);
    fx_angle_t half = (fx_angle_t)w16 << 15;
    fx_q30_t s2 = fx_sin(half); /* sin(w/2) */
    if (cfg->beacon_flat) {
        fx_q30_t c2 = fx_cos(half);
        int32_t lo = (int32_t)rlo - tol;
        if (lo <= 0)
            return true;
        /* lo <= D cos / (2 sin)  <=>  2 lo sin <= D cos */
        return fx_mul_q30(2 * lo, s2) <= fx_mul_q30(cfg->beacon_diameter, c2);
    }
    int32_t lo = (int32_t)rlo - tol, hi = (int32_t)rhi + tol;
    if (lo > 0 && fx_mul_q30(2 * lo, s2) > cfg->beacon_diameter)
        return false; /* wider than a post anywhere in the interval: closer than lo - tol */
    return fx_mul_q30(2 * hi, s2) >= cfg->beacon_diameter;
}

/* Range bounds [lo, hi] (Q16) of beacon k from the approximate position +- eps. */
static void range_bounds(const optical_map_t *map, const optical_pose_t *ap, uint8_t k,
                         fx_q16_t eps, uint32_t *lo, uint32_t *hi)
{
    uint32_t r = fx_hypot(map->b[k].x - ap->x, map->b[k].y - ap->y);
    *lo = r > (uint32_t)eps ? r - (uint32_t)eps : 0u;
    *hi = r + (uint32_t)eps;
}

/* ------------------------------------------------------------------ identification */

typedef struct {
    const optical_map_t *map;
    const optical_config_t *cfg;
    const optical_pose_t *ap;
    const optical_sighting_t *s;
    uint8_t n;      /* sightings */
    uint8_t moving;     /* latched poses given */
    uint16_t eps8;      /* position uncertainty, 2^-8 m */
    uint16_t lever_max; /* largest W.lever[] */
} ctx_t;

/* Window half-width of beacon k for sorted sighting j beyond the heading half-width. */
static uint16_t pos_part(const ctx_t *x, uint8_t k, uint8_t j)
{
    uint32_t a = (uint32_t)x->eps8 + W.lever[j];
    return win_part(a > 0xFFFFu ? 0xFFFFu : (uint16_t)a, W.g[k]);
}

/*
 * One matching pass with the heading-offset interval centred on @p mid, half-width @p half
 * (2^-16 turn). Fills W.sm / W.bm with the matches.
 */
static void match_pass(const ctx_t *x, int16_t mid, uint16_t half)
{
    uint8_t nb = x->map->n;
    for (uint8_t j = 0; j < x->n; j++)
        W.sm[j] = NONE;
    for (uint8_t k = 0; k < nb; k++) {
        W.bm[k] = NONE;
        if (W.g[k] == 0)
            continue;
        /* Widest window of k over all sightings (largest lever), to bound the scan. */
        uint32_t a = (uint32_t)x->eps8 + x->lever_max;
        uint32_t wmax = (uint32_t)half + MARGIN + win_part(a > 0xFFFFu ? 0xFFFFu : (uint16_t)a,
                                                           W.g[k]);
        uint16_t centre = (uint16_t)(W.psi[k] + (uint16_t)mid);
        bool all = wmax >= 0x7000u; /* wide: test every sighting */
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
            if (!W.keep[j])
                continue;
            uint16_t diff = (uint16_t)(W.th[j] - centre);
            uint16_t ad = (int16_t)diff < 0 ? (uint16_t)(0u - diff) : diff;
            uint32_t wj = (uint32_t)half + MARGIN + pos_part(x, k, j);
            if (ad > wj)
                continue;
            W.sm[j] = W.sm[j] == NONE ? k : MULTI;
            W.bm[k] = W.bm[k] == NONE ? j : MULTI;
        }
    }
}

/* Seed's overlap rule: k's window meets the window of another beacon in range. */
static bool overlaps(const ctx_t *x, uint8_t k, uint16_t half)
{
    uint32_t wk = (uint32_t)half + MARGIN + win_part(x->eps8, W.g[k]);
    for (uint8_t j = 0; j < x->map->n; j++) {
        if (j == k || W.g[j] == 0)
            continue;
        uint16_t d = (uint16_t)(W.psi[j] - W.psi[k]);
        uint16_t ad = (int16_t)d < 0 ? (uint16_t)(0u - d) : d;
        if ((uint32_t)ad < wk + half + MARGIN + win_part(x->eps8, W.g[j]))
            return true;
    }
    return false;
}

/*
 * Identify: sets W.sm[j] to the beacon of each safely identified sorted sighting (NONE
 * otherwise); returns the number identified, or -1 when the matches contradict the stated
 * uncertainty. *widened gets the widenings used.
 */
static int8_t identify(const ctx_t *x, uint8_t *widened)
{
    const optical_config_t *cfg = x->cfg;
    int32_t lo = -(int32_t)a16(cfg->window), hi = (int32_t)a16(cfg->window);
    uint32_t step = 0;
    if (cfg->widen_steps && cfg->widen_max > cfg->window)
        step = (a16(cfg->widen_max) - a16(cfg->window) + cfg->widen_steps - 1u) / cfg->widen_steps;
    uint8_t wid = 0, passes = 0;
    int8_t found = 0;
    for (;;) {
        int16_t mid = (int16_t)((lo + hi) / 2);
        uint16_t half = (uint16_t)((hi - lo + 1) / 2);
        match_pass(x, mid, half);
        passes++;
        found = 0;
        int32_t nlo = lo, nhi = hi;
        for (uint8_t j = 0; j < x->n; j++) {
            uint8_t k = W.sm[j];
            if (k >= MULTI)
                continue;
            if (W.bm[k] != j || ((wid || cfg->reject_overlap) && overlaps(x, k, half))) {
                W.sm[j] = NONE;
                continue;
            }
            uint32_t rlo, rhi;
            range_bounds(x->map, x->ap, k, cfg->window_pos, &rlo, &rhi);
            if (!width_matches(cfg, x->s[W.ord[j]].width, rlo, rhi)) {
                W.sm[j] = NONE;
                continue;
            }
            found++;
            if (!wid) {
                int16_t off = (int16_t)(W.th[j] - W.psi[k]);
                int32_t e = (int32_t)pos_part(x, k, j) + MARGIN;
                if (off - e > nlo)
                    nlo = off - e;
                if (off + e < nhi)
                    nhi = off + e;
            }
        }
        if (!wid) {
            if (nlo > nhi)
                return -1;
            /* Tighter by at least a quarter: another pass finds more (or the same) safely. */
            if (passes < MAX_PASSES && 4 * (nhi - nlo) < 3 * (hi - lo)) {
                lo = nlo;
                hi = nhi;
                continue;
            }
        }
        if (found >= 3 || wid >= cfg->widen_steps || step == 0)
            break;
        wid++;
        lo -= (int32_t)step;
        hi += (int32_t)step;
        if (hi - lo >= 0x8000)
            break;
    }
    *widened = wid;
    return found;
}

/* ------------------------------------------------------------------ fix */

/* Parallax-corrected angle of sorted sighting j towards a beacon at range r (Q16). */
static fx_angle_t corrected(uint8_t j, uint32_t r)
{
    if (W.c[j] == 0)
        return W.d[j];
    int32_t ratio;
    if (r == 0 || r > 0x7FFFFFFFul || !fx_div_shift(W.c[j], (int32_t)r, 30, &ratio))
        return W.d[j];
    return W.d[j] + fx_asin(ratio);
}

static bool coords_ok(fx_q16_t x, fx_q16_t y)
{
    return x > -OPTICAL_COORD_LIMIT && x < OPTICAL_COORD_LIMIT && y > -OPTICAL_COORD_LIMIT &&
           y < OPTICAL_COORD_LIMIT;
}

static int8_t finish(optical_fix_t *out, int8_t status)
{
    out->status = (uint8_t)status;
    return status;
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
    if (map == NULL || map->n < 3 || map->n > OPTICAL_MAX_BEACONS ||
        n > OPTICAL_MAX_SIGHTINGS || !coords_ok(approx->x, approx->y))
        return finish(out, OPTICAL_E_ARG);
    for (uint8_t k = 0; k < map->n; k++)
        if (!coords_ok(map->b[k].x, map->b[k].y))
            return finish(out, OPTICAL_E_ARG);
    if (n < 3)
        return finish(out, OPTICAL_E_FEW);

    ctx_t x = {map, cfg, approx, s, n, latched != NULL, m8((uint32_t)cfg->window_pos), 0};

    /* O11: sightings into the vehicle frame of the reference instant. */
    fx_q30_t sa = 0, ca = FX_Q30_ONE;
    if (x.moving)
        fx_sincos(approx->heading, &sa, &ca);
    uint16_t lever_max = 0;
    for (uint8_t i = 0; i < n; i++) {
        fx_angle_t d = s[i].angle;
        int32_t c = 0;
        if (x.moving) {
            if (!coords_ok(latched[i].x, latched[i].y))
                return finish(out, OPTICAL_E_ARG);
            d += latched[i].heading - approx->heading;
            int32_t ex = latched[i].x - approx->x, ey = latched[i].y - approx->y;
            /* o = R(-heading) e, then c = cross(u(d), o) = oy cos d - ox sin d. */
            int32_t ox = fx_mul_q30(ex, ca) + fx_mul_q30(ey, sa);
            int32_t oy = fx_mul_q30(ey, ca) - fx_mul_q30(ex, sa);
            fx_q30_t sd, cd;
            fx_sincos(d, &sd, &cd);
            c = fx_mul_q30(oy, cd) - fx_mul_q30(ox, sd);
        }
        /* Sorted insert by the reference-frame angle. */
        uint16_t t = a16(d);
        uint8_t j = i;
        while (j > 0 && W.th[j - 1] > t) {
            W.th[j] = W.th[j - 1];
            W.d[j] = W.d[j - 1];
            W.c[j] = W.c[j - 1];
            W.ord[j] = W.ord[j - 1];
            j--;
        }
        W.th[j] = t;
        W.d[j] = d;
        W.c[j] = c;
        W.ord[j] = i;
    }
    for (uint8_t j = 0; j < n; j++) {
        uint16_t l = m8(umag(W.c[j]));
        W.lever[j] = l;
        if (l > lever_max)
            lever_max = l;
    }
    x.lever_max = lever_max;
    /* Bucket index: first sorted sighting at or after each 1/16 turn (n when none: wraps). */
    {
        uint8_t j = 0;
        for (uint8_t b = 0; b < 16; b++) {
            while (j < n && (W.th[j] >> 12) < b)
                j++;
            W.bstart[b] = j < n ? j : 0;
        }
    }

    /* O4: drop sightings too narrow for a beacon within T; widen T when fewer than 3 stay. */
    fx_q16_t t = cfg->range;
    int32_t tstep = cfg->range_steps && cfg->range_max > cfg->range
                        ? (cfg->range_max - cfg->range + cfg->range_steps - 1) / cfg->range_steps
                        : 0;
    for (uint8_t step = 0;; step++) {
        uint16_t wmin = width_at(cfg->beacon_diameter, t, cfg->beacon_flat);
        uint8_t kept = 0;
        for (uint8_t j = 0; j < n; j++) {
            W.keep[j] = x.s[W.ord[j]].width >= wmin;
            kept += W.keep[j];
        }
        if (kept >= 3 || step >= cfg->range_steps || tstep == 0)
            break;
        t += tstep;
    }

    /* O2: expected angles of the beacons within T (+ the position uncertainty). */
    uint32_t gate = (uint32_t)t + (uint32_t)cfg->window_pos;
    for (uint8_t k = 0; k < map->n; k++) {
        int32_t dx = map->b[k].x - approx->x, dy = map->b[k].y - approx->y;
        uint32_t ax = umag(dx), ay = umag(dy);
        if (ax > gate || ay > gate) {
            W.g[k] = 0;
            continue;
        }
        W.psi[k] = a16(fx_atan2_fast(dy, dx) - approx->heading);
        uint32_t r = ax > ay ? ax + (ay >> 1) : ay + (ax >> 1);
        uint16_t g = g_bound(r);
        W.g[k] = g ? g : 1u;
    }

    /* O3-O5 */
    uint8_t widened = 0;
    int8_t found = identify(&x, &widened);
    out->widened = widened;
    if (found < 0)
        return finish(out, OPTICAL_E_INCONSISTENT);
    fx_angle_t ang[OPTICAL_MAX_SIGHTINGS];
    uint8_t pos[OPTICAL_MAX_SIGHTINGS];
    uint8_t m = 0;
    for (uint8_t j = 0; j < n; j++) {
        if (W.sm[j] >= MULTI)
            continue;
        out->ident[W.ord[j]] = (int8_t)W.sm[j];
        ang[m] = W.d[j];
        pos[m++] = j;
    }
    out->n_ident = m;
    if (m < 3)
        return finish(out, OPTICAL_E_FEW);

    /* O7, O8: three of them (ang[] is in ring order: sorted). */
    uint8_t keep[3];
    optical_select(ang, m, keep);
    uint8_t tj[3];
    optical_xy_t b[3];
    for (uint8_t i = 0; i < 3; i++) {
        tj[i] = pos[keep[i]];
        b[i] = map->b[W.sm[tj[i]]];
        out->used[i] = W.sm[tj[i]];
    }

    /* O9-O11: triangulate; when moving, refine the parallax with the ranges of the fix. */
    optical_tri_t tri;
    optical_pose_t p = *approx;
    int8_t st = OPTICAL_OK;
    uint8_t passes = x.moving ? cfg->motion_passes : 1u;
    if (passes == 0)
        passes = 1;
    for (uint8_t pass = 0; pass < passes; pass++) {
        fx_angle_t th[3];
        for (uint8_t i = 0; i < 3; i++)
            th[i] = corrected(tj[i], fx_hypot(b[i].x - p.x, b[i].y - p.y));
        st = optical_triangulate(b, th, cfg->quality_max, &tri);
        if (st != OPTICAL_OK && st != OPTICAL_E_SINGULAR)
            return finish(out, st);
        uint32_t moved = fx_hypot(tri.pose.x - p.x, tri.pose.y - p.y);
        p = tri.pose;
        if (moved < 16) /* 0.25 mm */
            break;
    }
    out->pose = tri.pose;
    out->quality = tri.quality;
    if (st != OPTICAL_OK)
        return finish(out, st);

    /* O6: implausible jumps and turns, then the other identified sightings must agree. */
    if (fx_hypot(p.x - approx->x, p.y - approx->y) > (uint32_t)cfg->jump_max)
        return finish(out, OPTICAL_E_JUMP);
    fx_angle_t dh = p.heading - approx->heading;
    if ((int32_t)dh > (int32_t)cfg->turn_max || (int32_t)dh < -(int32_t)cfg->turn_max)
        return finish(out, OPTICAL_E_TURN);
    for (uint8_t i = 0; i < m; i++) {
        uint8_t j = pos[i];
        if (j == tj[0] || j == tj[1] || j == tj[2])
            continue;
        const optical_xy_t *bk = &map->b[W.sm[j]];
        int32_t dx = bk->x - p.x, dy = bk->y - p.y;
        fx_angle_t th = corrected(j, fx_hypot(dx, dy));
        fx_angle_t res = fx_atan2_fast(dy, dx) - p.heading - th;
        if ((int32_t)res > (int32_t)cfg->resid_max || (int32_t)res < -(int32_t)cfg->resid_max)
            return finish(out, OPTICAL_E_DISAGREE);
    }
    return finish(out, OPTICAL_OK);
}
