/*
 * fastmath.c - optical/fastmath.h in portable C: the definition of every kernel's result. On
 * the MSP430 the kernels come from msp430/optical_fast.S and msp430/optical_tri.S
 * (OPTICAL_ASM), which perform the very same integer steps; both use the tables that
 * tools/gen_optical_tables.py generates at build time (formulas in fastmath.h).
 */
#include "optical/fastmath.h"

#include <stddef.h>

optical_work_t optical_work;
#define W (optical_work)

#ifdef __MSP430__
/* msp430/layout.h: the numbers the assembly (msp430/optical_*.S) works with. */
#include "msp430/layout.h"
_Static_assert(
    offsetof(optical_work_t, b) == OW_B && offsetof(optical_work_t, x) == OW_X &&
        offsetof(optical_work_t, y) == OW_Y && offsetof(optical_work_t, head) == OW_HEAD &&
        offsetof(optical_work_t, eps8) == OW_EPS8 &&
        offsetof(optical_work_t, lever8) == OW_LEVER8 &&
        offsetof(optical_work_t, amax8) == OW_AMAX8 &&
        offsetof(optical_work_t, gate8) == OW_GATE8 && offsetof(optical_work_t, nb) == OW_NB &&
        offsetof(optical_work_t, n) == OW_N && offsetof(optical_work_t, nc) == OW_NC &&
        offsetof(optical_work_t, m) == OW_M && offsetof(optical_work_t, th) == OW_TH &&
        offsetof(optical_work_t, lev) == OW_LEV && offsetof(optical_work_t, we) == OW_WE &&
        offsetof(optical_work_t, sm) == OW_SM && offsetof(optical_work_t, bstart) == OW_BSTART &&
        offsetof(optical_work_t, ord) == OW_ORD && offsetof(optical_work_t, wchk) == OW_WCHK &&
        offsetof(optical_work_t, pos) == OW_POS && offsetof(optical_work_t, b8) == OW_B8 &&
        offsetof(optical_work_t, ox) == OW_OX && offsetof(optical_work_t, oy) == OW_OY,
    "layout.h: optical_work_t");
_Static_assert(offsetof(optical_work_t, u.id.psi) == OW_PSI &&
                   offsetof(optical_work_t, u.id.e) == OW_E &&
                   offsetof(optical_work_t, u.id.g) == OW_G &&
                   offsetof(optical_work_t, u.id.bm) == OW_BM &&
                   offsetof(optical_work_t, u.id.cand) == OW_CAND &&
                   offsetof(optical_work_t, u.sv.ang) == OW_ANG &&
                   offsetof(optical_work_t, u.sv.frame) == OW_FRAME &&
                   sizeof optical_work.u.sv.frame >= OW_FRAME_SIZE &&
                   offsetof(optical_work_t, u.sv.v) == OW_SV_V &&
                   offsetof(optical_work_t, u.sv.sc) == OW_SV_SC &&
                   offsetof(optical_work_t, u.sv.ts) == OW_SV_TS,
               "layout.h: optical_work_t.u");
_Static_assert(offsetof(optical_tsol_t, off) == TSOL_OFF && offsetof(optical_tsol_t, w) == TSOL_W &&
                   offsetof(optical_tsol_t, l) == TSOL_L && offsetof(optical_tsol_t, r) == TSOL_R &&
                   offsetof(optical_tsol_t, x) == TSOL_X,
               "layout.h: optical_tsol_t");
_Static_assert(offsetof(optical_xy_t, x) == XY_X && offsetof(optical_xy_t, y) == XY_Y &&
                   sizeof(optical_xy_t) == XY_SIZE && offsetof(optical_pose_t, x) == POSE_X &&
                   offsetof(optical_pose_t, y) == POSE_Y &&
                   offsetof(optical_pose_t, heading) == POSE_HEADING &&
                   sizeof(optical_pose_t) == POSE_SIZE &&
                   offsetof(optical_sighting_t, angle) == SIGHT_ANGLE &&
                   offsetof(optical_sighting_t, width) == SIGHT_WIDTH &&
                   sizeof(optical_sighting_t) == SIGHT_SIZE &&
                   offsetof(optical_map_t, b) == MAP_B && offsetof(optical_map_t, n) == MAP_N,
               "layout.h: optical_xy_t, optical_pose_t, optical_sighting_t, optical_map_t");
_Static_assert(offsetof(optical_config_t, beacon_diameter) == CFG_DIAMETER &&
                   offsetof(optical_config_t, beacon_flat) == CFG_FLAT &&
                   offsetof(optical_config_t, window_pos) == CFG_WIN_POS &&
                   offsetof(optical_config_t, dist_tol) == CFG_DIST_TOL &&
                   offsetof(optical_config_t, dist_rel) == CFG_DIST_REL &&
                   offsetof(optical_config_t, jump_max) == CFG_JUMP_MAX &&
                   offsetof(optical_config_t, turn_max) == CFG_TURN_MAX,
               "layout.h: optical_config_t");
_Static_assert(offsetof(optical_width_t, dk) == WD_DK && offsetof(optical_width_t, x) == WD_X &&
                   offsetof(optical_width_t, y) == WD_Y &&
                   offsetof(optical_width_t, eps8) == WD_EPS8 &&
                   offsetof(optical_width_t, tol8) == WD_TOL8 &&
                   offsetof(optical_width_t, rel16) == WD_REL16 &&
                   offsetof(optical_width_t, flat) == WD_FLAT,
               "layout.h: optical_width_t");
_Static_assert(offsetof(optical_tri_t, pose) == TRI_POSE &&
                   offsetof(optical_tri_t, quality) == TRI_QUALITY &&
                   offsetof(optical_fix_t, pose) == FIX_POSE &&
                   offsetof(optical_fix_t, quality) == FIX_QUALITY &&
                   offsetof(optical_fix_t, ident) == FIX_IDENT &&
                   offsetof(optical_fix_t, n_ident) == FIX_N_IDENT &&
                   offsetof(optical_fix_t, widened) == FIX_WIDENED &&
                   OPTICAL_MAX_SIGHTINGS == MAX_SIGHTINGS && OPTICAL_MAX_BEACONS == MAX_BEACONS,
               "layout.h: optical_tri_t, optical_fix_t, limits");
_Static_assert(OPTICAL_E_DEGENERATE == E_DEGENERATE && OPTICAL_E_SINGULAR == E_SINGULAR &&
                   OPTICAL_E_JUMP == E_JUMP && OPTICAL_E_TURN == E_TURN &&
                   OPTICAL_E_DISAGREE == E_DISAGREE,
               "layout.h: status codes");
_Static_assert((MATCH_NONE & 0xFF) == OPTICAL_NONE && MATCH_MULTI == OPTICAL_MULTI &&
                   MATCH_DROPPED == OPTICAL_DROPPED && MARGIN == OPTICAL_MARGIN &&
                   MAX_CAND == OPTICAL_MAX_CAND,
               "layout.h: match codes, margin, candidates");
#endif

uint16_t optical_win(uint16_t l, uint16_t g)
{
    if (g == 0xFFFFu)
        return 0x7FFFu;
    uint32_t v = ((uint32_t)l * g + 255u) >> 8;
    return v > 0x7FFFu ? 0x7FFFu : (uint16_t)v;
}

#ifndef OPTICAL_ASM

static uint32_t umag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static uint16_t sat16(uint32_t v)
{
    return v > 0xFFFFu ? 0xFFFFu : (uint16_t)v;
}

/* The parts of the arctangent that optical_expect_scan reuses. */
typedef struct {
    uint16_t r; /* 2^30 / u (interpolated) */
    uint16_t i; /* floor(64 v / u), 0..63 */
} angle_parts_t;

/*
 * The arctangent of the octant: u in [2^15, 2^16), v <= u (the larger and the smaller
 * magnitude, scaled alike), then unfolded by the flags (1 swapped, 2 dx < 0, 4 dy < 0).
 * (v = u needs no case of its own: q saturates, and the interpolation gives 45 degrees for
 * every u, checked exhaustively.)
 */
static uint16_t octant(uint16_t u, uint16_t v, uint8_t flags, angle_parts_t *p)
{
    /* r = 2^30 / u (interpolated: the step (RT[i] - RT[i + 1]) 2^7 times u mod 2^9, i.e. the
     * step times the fraction u << 7 mod 2^16), q = 2^16 v / u */
    uint16_t i = (uint16_t)((u >> 9) - 64u), f, d, a;
    p->r = (uint16_t)(optical_recip_tab[i] -
                      (((uint32_t)optical_recip_d_tab[i] * (u & 0x1FFu)) >> 16));
    uint16_t q = sat16(((uint32_t)v * p->r) >> 14);
    i = (uint16_t)(q >> 10);
    f = (uint16_t)(q << 6);
    d = (uint16_t)(optical_atan_tab[i + 1u] - optical_atan_tab[i]);
    /* 2^-18 turn (the step's product truncated), plus the 2 of the table: rounded to
     * 2^-16 turn */
    a = (uint16_t)((optical_atan_tab[i] + (((uint32_t)d * f) >> 16)) >> 2);
    p->i = i;
    if (flags & 1u)
        a = (uint16_t)(16384u - a);
    if (flags & 2u)
        a = (uint16_t)(32768u - a);
    if (flags & 4u)
        a = (uint16_t)(0u - a);
    return a;
}

uint16_t optical_angle16(int32_t dx, int32_t dy)
{
    uint32_t ax = umag(dx), ay = umag(dy);
    uint8_t flags = (uint8_t)((dx < 0 ? 2u : 0u) | (dy < 0 ? 4u : 0u));
    if (ay > ax) {
        uint32_t t = ax;
        ax = ay;
        ay = t;
        flags |= 1u;
    }
    if (ax == 0)
        return 0;
    while (ax > 0xFFFFu) { /* both to [2^15, 2^16) by the shift that brings ax there */
        ax >>= 1;
        ay >>= 1;
    }
    while (ax < 0x8000u) {
        ax <<= 1;
        ay <<= 1;
    }
    angle_parts_t p;
    return octant((uint16_t)ax, (uint16_t)ay, flags, &p);
}

static void clear_sm(void)
{
    for (uint8_t j = 0; j < W.n; j++)
        if (W.sm[j] != OPTICAL_DROPPED)
            W.sm[j] = OPTICAL_NONE;
}

static void clear(void)
{
    clear_sm();
    for (uint8_t k = 0; k < W.nb; k++)
        W.u.id.bm[k] = OPTICAL_NONE;
}

/* The window position part of pair (j, k). */
static uint16_t pair_w(uint8_t j, uint8_t k)
{
    if (W.lever8 == 0 || W.lev[j] == 0)
        return W.u.id.e[k];
    return (uint16_t)(optical_win(sat16((uint32_t)W.eps8 + W.lev[j]), W.u.id.g[k]) +
                      OPTICAL_MARGIN);
}

/* Pair (j, k) within the windows (mid, half): marked; true when it is. */
static bool test(uint8_t j, uint8_t k, int16_t mid, uint16_t half)
{
    uint16_t w = pair_w(j, k);
    uint16_t off = (uint16_t)(W.th[j] - W.u.id.psi[k] - (uint16_t)mid);
    if ((int16_t)off < 0)
        off = (uint16_t)(0u - off);
    if (off > (uint16_t)(half + w))
        return false;
    W.sm[j] = W.sm[j] == OPTICAL_NONE ? k : OPTICAL_MULTI;
    W.u.id.bm[k] = W.u.id.bm[k] == OPTICAL_NONE ? j : OPTICAL_MULTI;
    W.we[j] = w;
    return true;
}

uint8_t optical_expect_scan(int16_t mid, uint16_t half)
{
    clear_sm();
    return optical_first_scan(mid, half);
}

/* floor(v / 2^8) within [-2^15, 2^15) into *v8, else false */
static bool to8(int32_t v, int16_t *v8)
{
    if ((uint32_t)v + 0x00800000u > 0x00FFFFFFu)
        return false;
    *v8 = (int16_t)(uint16_t)((uint32_t)v >> 8);
    return true;
}

uint8_t optical_first_scan(int16_t mid, uint16_t half)
{
    int16_t px, py; /* the position in the compiled map */
    if (!to8((int32_t)((uint32_t)W.x - (uint32_t)W.ox), &px) ||
        !to8((int32_t)((uint32_t)W.y - (uint32_t)W.oy), &py))
        return 1;
    for (uint8_t k = 0; k < W.nb; k++)
        W.u.id.bm[k] = OPTICAL_NONE;
    W.nc = 0;
    for (uint8_t k = 0; k < W.nb; k++) {
        /* The offset in 2^-8 m: a difference of two values in [-2^15, 2^15), its magnitude
         * below 2^16 and its sign that of the exact difference. */
        int32_t x8 = (int32_t)W.b8[k].x - px, y8 = (int32_t)W.b8[k].y - py;
        uint16_t ax = (uint16_t)(x8 < 0 ? -x8 : x8);
        uint16_t ay = (uint16_t)(y8 < 0 ? -y8 : y8);
        W.u.id.e[k] = 0;
        if (ax > W.gate8 || ay > W.gate8)
            continue;
        uint8_t flags = (uint8_t)((x8 < 0 ? 2u : 0u) | (y8 < 0 ? 4u : 0u));
        if (ay > ax) {
            uint16_t t = ax;
            ax = ay;
            ay = t;
            flags |= 1u;
        }
        uint16_t m8 = ax, psi = 0, g = 0xFFFFu, ek = 0x7FFFu + OPTICAL_MARGIN;
        angle_parts_t p = {0, 0};
        uint8_t l = 0;
        if (ax) {
            for (; ax < 0x8000u; l++) { /* to [2^15, 2^16) */
                ax = (uint16_t)(ax << 1);
                ay = (uint16_t)(ay << 1);
            }
            psi = octant(ax, ay, flags, &p);
        }
        psi = (uint16_t)(psi - W.head);
        W.u.id.psi[k] = psi;
        /* The window (docs/optical.md "O2-O5"): 2^16 / (2 pi) asin(x) <= 2^14 k x for x =
         * eps8 / r8, k = 2/3 up to x = 1/2 (m8 >= 2 amax8), k = 1 up to 1; with r8 >= m8
         * sqrt(1 + t^2) = u 2^-l sqrt(1 + t^2) and h about 2^30 k / (u sqrt(1 + t^2)), that is
         * at most h eps8 2^l / 2^16, and a lever l8's window at most l8 g / 256. */
        if (m8 >= 77u && m8 > W.amax8) {
            uint32_t h = ((uint32_t)p.r * optical_ct_tab[p.i]) >> 16;
            if (m8 < 2u * (uint32_t)W.amax8) /* x up to 1: k = 1 */
                h += (h >> 1) + 2u;
            /* (eps8 <= amax8 < m8: eps8 2^l < 2^16) */
            uint32_t v = ((h * (uint16_t)(W.eps8 << l)) >> 16) + 1u;
            ek = (uint16_t)((v > 0x7FFFu ? 0x7FFFu : v) + OPTICAL_MARGIN);
            if (l <= 8)
                g = (uint16_t)((h >> (8u - l)) + 1u);
            else /* (l = 9: m8 < 128) */
                g = 2u * h + 1u >= 0xFFFEu ? 0xFFFEu : (uint16_t)(2u * h + 1u);
        }
        if (W.lever8) /* (standing, only e is read) */
            W.u.id.g[k] = g;
        W.u.id.e[k] = ek;
        /* The candidate sightings: from the bucket of the window's start. */
        uint32_t wmax = ek;
        if (W.lever8) /* the widest window over the sightings: the largest lever */
            wmax = optical_win(W.amax8, g) + (uint32_t)OPTICAL_MARGIN;
        wmax += half;
        uint16_t lo = (uint16_t)(psi + (uint16_t)mid - (uint16_t)wmax);
        uint16_t span = (uint16_t)(2u * wmax);
        bool all = wmax >= 0x7000u; /* that wide: test every sighting */
        uint8_t j = all ? 0u : W.bstart[lo >> 12];
        for (uint8_t c = 0; c < W.n; c++, j = (uint8_t)(j + 1u < W.n ? j + 1u : 0u)) {
            if (!all) {
                uint16_t rel = (uint16_t)(W.th[j] - lo);
                if (rel >= 0xF000u)
                    continue; /* in lo's 1/16 turn, before lo */
                if (rel > span)
                    break;
            }
            if (W.sm[j] == OPTICAL_DROPPED || !test(j, k, mid, half) || W.nc == 0xFFu)
                continue;
            if (W.nc == OPTICAL_MAX_CAND) {
                W.nc = 0xFFu;
                continue;
            }
            W.u.id.cand[2u * W.nc] = j;
            W.u.id.cand[2u * W.nc + 1u] = k;
            W.nc++;
        }
    }
    return 0;
}

uint32_t optical_wmin(uint32_t dk, uint32_t t8)
{
    return t8 ? dk / t8 : 0xFFFFu; /* 2^-16 turn */
}

uint8_t optical_drop(const optical_sighting_t *s, uint32_t wmin)
{
    uint8_t kept = 0;
    for (uint8_t j = 0; j < W.n; j++) {
        bool keep = s[W.ord[j]].width >= wmin;
        W.sm[j] = keep ? OPTICAL_NONE : OPTICAL_DROPPED;
        W.wchk[j] = 0x7Fu;
        kept += keep;
    }
    return kept;
}

void optical_eval(int16_t mid, uint16_t half)
{
    clear();
    for (uint8_t c = W.nc; c-- > 0;) /* (from the last pair) */
        test(W.u.id.cand[2u * c], W.u.id.cand[2u * c + 1u], mid, half);
}

bool optical_width_ok(const optical_width_t *a, const optical_xy_t *b, uint16_t w16)
{
    uint32_t ax = umag(b->x - a->x), ay = umag(b->y - a->y);
    uint16_t x8 = ax >= (1ul << 24) ? 0xFFFFu : (uint16_t)(ax >> 8);
    uint16_t y8 = ay >= (1ul << 24) ? 0xFFFFu : (uint16_t)(ay >> 8);
    uint16_t o = sat16(x8 > y8 ? x8 + (uint32_t)(y8 >> 1) : y8 + (uint32_t)(x8 >> 1));
    uint16_t rhi = sat16((uint32_t)o + a->eps8);
    uint16_t rlo = (uint16_t)(((uint32_t)o * 58623u) >> 16); /* / 1.118 */
    rlo = rlo > a->eps8 ? (uint16_t)(rlo - a->eps8) : 0u;
    uint16_t tol = sat16(a->tol8 + (((uint32_t)rhi * a->rel16) >> 16));
    uint32_t lo = rlo > tol ? (uint16_t)(rlo - tol) : 0u, hi = sat16((uint32_t)rhi + tol);
    if (w16 > 5215u) /* 0.5 rad: a post closer than 2 D, wide for any use here */
        return lo * 5215u <= a->dk + (a->dk >> 4);
    /* 0.969 w lo > D: the post would look wider even at the far end of the interval */
    uint32_t p = lo * w16;
    if (p - (p >> 5) > a->dk)
        return false;
    return a->flat || hi * w16 >= a->dk;
}

#endif

#ifndef OPTICAL_ASM

/* The triangulation kernels (fastmath.h; docs/optical.md "O9" derives them). */

/* floor(v / 2^n), n < 32 */
static int32_t asr(int32_t v, uint8_t n)
{
    return v < 0 ? (int32_t) ~(~(uint32_t)v >> n) : (int32_t)((uint32_t)v >> n);
}

/* x = hi(x) 2^16 + lo(x): lo the low word read as signed, |hi| <= 2^15 for |x| < 2^31 - 2^15 */
static int32_t lo16(int32_t x)
{
    return (int16_t)(uint16_t)(uint32_t)x;
}

static int32_t hi16(int32_t x)
{
    return (int16_t)(uint16_t)(((uint32_t)x + 0x8000u) >> 16);
}

/*
 * sum of x[i] y[i] / 2^32 (i < n): sum of hi hi + floor(sum of (hi lo + lo hi) / 2^16), the
 * products lo lo dropped (each below 2^30: a quarter unit). Every caller keeps both partial
 * sums below 2^31 (the MSP430 accumulates them in its multiplier).
 */
static int32_t dot(const int32_t *x, const int32_t *y, uint8_t n)
{
    int32_t hh = 0, m = 0;
    for (uint8_t i = 0; i < n; i++) {
        hh += hi16(x[i]) * hi16(y[i]);
        m += hi16(x[i]) * lo16(y[i]) + lo16(x[i]) * hi16(y[i]);
    }
    return hh + asr(m, 16);
}

/* The left shifts that bring m (nonzero) to 2^top or more. */
static uint8_t lead(uint32_t m, uint8_t top)
{
    uint8_t n = 0;
    for (; m < (1ul << top); m <<= 1)
        n++;
    return n;
}

static uint32_t tmag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static uint32_t mag2(int32_t a, int32_t b)
{
    return tmag(a) | tmag(b);
}

/*
 * R' = 2^(52 + g) / q for q in [2^22, 2^25), g = 9 - n with q 2^n in [2^31, 2^32): within 16
 * units (2^-25; measured over every 16-bit head of q 2^n and 300,000 random q: 15.4), in
 * [2^29, 2^30]. One Newton step on the multiplier from optical_recip_tab's interpolated
 * reciprocal r0 of the head qh (r0 = 2^46 / (q 2^n) within 1.1e-4, so |E| < 2^17):
 * R' = r0 2^15 (1 + E / 2^30), E = 2^30 - q 2^n r0 / 2^16, the product in 16-bit parts.
 */
static uint32_t recip_q(uint32_t q, uint8_t *g)
{
    uint8_t n = lead(q, 31);
    uint32_t qn = q << n;
    uint16_t qh = (uint16_t)(qn >> 16), ql = (uint16_t)qn;
    uint16_t i = (uint16_t)((qh >> 9) - 64u), f = (uint16_t)(qh << 7);
    uint16_t d = (uint16_t)(optical_recip_tab[i] - optical_recip_tab[i + 1u]);
    uint16_t r0 = (uint16_t)(optical_recip_tab[i] - (((uint32_t)d * f + 0x8000u) >> 16));
    uint32_t s = (uint32_t)qh * r0 + (((uint32_t)ql * r0) >> 16);
    int16_t e2 = (int16_t)(uint16_t)((0x40000000u - s) >> 2); /* E / 4: |E| < 2^17 */
    int32_t p = (int32_t)(r0 >> 1) * e2;
    *g = (uint8_t)(9u - n);
    return ((uint32_t)r0 << 15) + (uint32_t)asr(p, 12);
}

int8_t optical_tri_core(int32_t v[4], const int32_t sc[4], optical_tsol_t *out)
{
    uint32_t m = mag2(v[0], v[1]) | mag2(v[2], v[3]);
    if (m >= (1ul << 27))
        return OPTICAL_E_ARG;
    if ((v[0] | v[1]) == 0 || (v[2] | v[3]) == 0 || (v[0] == v[2] && v[1] == v[3]))
        return OPTICAL_E_DEGENERATE;
    /* lambda: the largest component to [2^28, 2^29) */
    uint8_t sigma = lead(m, 28);
    for (uint8_t i = 0; i < 4; i++)
        v[i] = (int32_t)((uint32_t)v[i] << sigma);
    int32_t s1 = sc[0], c1 = sc[1], s2 = sc[2], c2 = sc[3];
    /* A = R(alpha1) b1 / 4, C = R(-alpha2) b3 / 4 */
    int32_t r[5][2] = {{c1, -s1}, {s1, c1}, {c2, s2}, {-s2, c2}, {s2, s1}};
    int32_t ax = dot(r[0], &v[0], 2), ay = dot(r[1], &v[0], 2);
    int32_t cx = dot(r[2], &v[2], 2), cy = dot(r[3], &v[2], 2);
    /* V = (s2 a + s1 c) / 16 = U / 16; 16 K = cross(4 A, 4 C) / 2^32 = kappa / 2^32 (the
     * halves of 4 A and 4 C: the products lo lo dropped stay below a unit) */
    int32_t xs[2] = {ax, cx}, ys[2] = {ay, cy};
    int32_t u[3] = {dot(r[4], xs, 2), dot(r[4], ys, 2), 0};
    int32_t k4[2] = {ax * 4, cx * 4}, kk[2] = {cy * 4, -ay * 4};
    int32_t k = dot(k4, kk, 2);
    m = mag2(u[0], u[1]);
    if (m == 0)
        return OPTICAL_E_SINGULAR;
    /* U^ = V 2^e, its larger component in [2^27, 2^28) (V < 2^26.5: e >= 1); K' = 16 K
     * 2^(e - 4) = r2 |U^| / 2^32: 2^28 or more only when beacon 2 lies beyond 2^31 lambda
     * (refused below) */
    uint8_t e = lead(m, 27);
    u[0] = (int32_t)((uint32_t)u[0] << e);
    u[1] = (int32_t)((uint32_t)u[1] << e);
    if (e < 4) {
        k = asr(k, (uint8_t)(4u - e));
    } else {
        if (k >= (1l << (32 - e)) || k < -(1l << (32 - e)))
            return OPTICAL_E_SINGULAR;
        k = (int32_t)((uint32_t)k << (e - 4u));
    }
    u[2] = k;
    /* Each beacon ahead along its sighting: l_i = (a U + c_i kappa) 2^e / 2^38 = +-r_i |U^| /
     * 2^34 (i = 1, 3) with the sign of K' = +-r2 |U^| / 2^32: on the other arc one of them has
     * the other sign. */
    int32_t la[3] = {ax, ay, c1}, lc[3] = {cx, cy, c2};
    int32_t l1 = dot(la, u, 3), l3 = dot(lc, u, 3);
    if (k == 0 || (l1 ^ k) < 0 || (l3 ^ k) < 0 || l1 == 0 || l3 == 0)
        return OPTICAL_E_INCONSISTENT;
    /* 1 / |U^|^2: Q = |U^|^2 / 2^32 in [2^22, 2^25), R' = 2^(52 + g) / Q in [2^29, 2^30] */
    uint8_t g;
    uint32_t rq = recip_q((uint32_t)dot(u, u, 2), &g);
    /* d = K' U^ / Q = K' R' U^ / 2^(52 + g): T = K'' R' / 2^32 with K'' = K' 2^f (|K''| in
     * [2^29, 2^30)), T' = T 2^t likewise, d = T' U^ / 2^32 2^(12 - f - g - t) */
    uint8_t f = lead(tmag(k), 29);
    int32_t kn = (int32_t)((uint32_t)k << f), rs = (int32_t)rq;
    int32_t t = dot(&kn, &rs, 1);
    uint8_t tt = lead(tmag(t), 29);
    t = (int32_t)((uint32_t)t << tt);
    int8_t sh = (int8_t)(12 - f - g - tt);
    int8_t rsh = (int8_t)(sigma - sh);
    for (uint8_t i = 0; i < 2; i++) {
        int32_t d = dot(&t, &u[i], 1); /* |d| < 2^26 */
        /* beacon 2 2^31 lambda (4 to 8 times the beacons' span) or farther: the circles all
         * but coincide */
        if (sh > 0 && (d >= (1l << (31 - sh)) || d < -(1l << (31 - sh))))
            return OPTICAL_E_SINGULAR;
        /* the vehicle relative to beacon 2: -d 2^sh / 2^sigma (Q16 m), rounded half up */
        uint32_t nd = 0u - (uint32_t)d;
        out->off[i] = rsh <= 0 ? (int32_t)(nd << (uint8_t)-rsh)
                               : asr((int32_t)nd, (uint8_t)rsh) + (int32_t)((nd >> (rsh - 1)) & 1u);
        out->w[i] = k < 0 ? -u[i] : u[i];
    }
    out->l[0] = l1 * 4;
    out->l[1] = k;
    out->l[2] = l3 * 4;
    out->r = rq;
    out->x = (int8_t)(e - g - sigma);
    return OPTICAL_OK;
}

uint32_t optical_tri_quality(const int32_t v[4], const optical_tsol_t *s)
{
    /* ranges: r_i = |l_i| 2^32 / |U^|; 16 bits by a common shift */
    uint8_t sr = 0;
    uint32_t m = mag2(s->l[0], s->l[1]) | tmag(s->l[2]);
    for (; m >= 0x8000u; m >>= 1)
        sr++;
    int32_t rl[3];
    for (uint8_t i = 0; i < 3; i++)
        rl[i] = asr(s->l[i], sr);
    /* chords b1, b3, b3 - b1: lambda / 2^15 */
    int32_t ch[6] = {asr(v[0], 15), asr(v[1], 15), asr(v[2], 15), asr(v[3], 15), 0, 0};
    ch[4] = ch[2] - ch[0];
    ch[5] = ch[3] - ch[1];
    /* M = c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2: each chord times its range, / 2^16, squared */
    static const uint8_t pair[3] = {2, 0, 1};
    uint32_t mm = 0;
    for (uint8_t c = 0; c < 3; c++)
        for (uint8_t j = 0; j < 2; j++) {
            int32_t w = asr(rl[pair[c]] * ch[2 * c + j], 16);
            mm += (uint32_t)(w * w);
        }
    if (mm == 0)
        return UINT32_MAX;
    /* S = sqrt(M) 2^(sr + 31) R' 2^(e - g - 56) lambda per radian */
    int8_t x = (int8_t)(s->x + sr - 19);
    while (mm < (1ul << 30)) {
        mm <<= 2;
        x--;
    }
    /* the root (optical_sqrt_tab interpolated, within 0.05 % low); Q16 m per mrad: / 2^sigma
     * / 1000 (2^25 / 1000 = 33554.4) */
    uint16_t k = (uint16_t)((mm >> 27) - 8u), f = (uint16_t)((mm >> 16) << 5);
    uint16_t d = (uint16_t)(optical_sqrt_tab[k + 1u] - optical_sqrt_tab[k]);
    uint16_t root = (uint16_t)(0x8000u + optical_sqrt_tab[k] + (((uint32_t)d * f) >> 16));
    uint32_t p = ((uint32_t)root * 33554u) >> 16;
    p *= s->r >> 15;
    if (x > 0)
        return x >= 31 || (p >> (32 - x)) != 0 ? UINT32_MAX : p << x;
    return x <= -32 ? 0 : p >> (uint8_t)-x;
}

#endif
