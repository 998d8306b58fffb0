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
/* The assembly addresses the work area by these offsets (msp430/optical_fast.S). */
_Static_assert(offsetof(optical_work_t, x) == 2 && offsetof(optical_work_t, head) == 10 &&
                   offsetof(optical_work_t, nb) == 20 && offsetof(optical_work_t, th) == 24 &&
                   offsetof(optical_work_t, lev) == 54 && offsetof(optical_work_t, we) == 84 &&
                   offsetof(optical_work_t, sm) == 174 && offsetof(optical_work_t, bstart) == 189 &&
                   offsetof(optical_work_t, wchk) == 220 && offsetof(optical_work_t, u) == 250 &&
                   offsetof(optical_work_t, u.id.e) == 314 &&
                   offsetof(optical_work_t, u.id.g) == 378 &&
                   offsetof(optical_work_t, u.id.bm) == 442 &&
                   offsetof(optical_work_t, u.id.cand) == 474 &&
                   offsetof(optical_work_t, u.sv.frame) == 350,
               "optical_work_t layout (optical_fast.S, optical_tri.S)");
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
    uint16_t i; /* floor(64 v / u), 0..64 */
} angle_parts_t;

/*
 * The arctangent of the octant: u in [2^15, 2^16), v <= u (the larger and the smaller
 * magnitude, scaled alike), then unfolded by the flags (1 swapped, 2 dx < 0, 4 dy < 0).
 */
static uint16_t octant(uint16_t u, uint16_t v, uint8_t flags, angle_parts_t *p)
{
    /* r = 2^30 / u (interpolated), q = 2^16 v / u */
    uint16_t i = (uint16_t)((u >> 9) - 64u), f = (uint16_t)(u << 7), a;
    uint16_t d = (uint16_t)(optical_recip_tab[i] - optical_recip_tab[i + 1u]);
    p->r = (uint16_t)(optical_recip_tab[i] - (((uint32_t)d * f + 0x8000u) >> 16));
    if (v >= u) {
        a = 32768u; /* 45 degrees, 2^-18 turn */
        p->i = 64;
    } else {
        uint16_t q = sat16(((uint32_t)v * p->r) >> 14);
        i = (uint16_t)(q >> 10);
        f = (uint16_t)(q << 6);
        d = (uint16_t)(optical_atan_tab[i + 1u] - optical_atan_tab[i]);
        a = (uint16_t)(optical_atan_tab[i] + (((uint32_t)d * f + 0x8000u) >> 16));
        p->i = i;
    }
    a = (uint16_t)((a + 2u) >> 2);
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

/* -OPTICAL_COORD_LIMIT <= v < OPTICAL_COORD_LIMIT (2^29): the high word + 0x2000 below 0x4000. */
static bool coord_ok(int32_t v)
{
    return (uint32_t)v + 0x20000000u < 0x40000000u;
}

static void clear(void)
{
    for (uint8_t j = 0; j < W.n; j++)
        if (W.sm[j] != OPTICAL_DROPPED)
            W.sm[j] = OPTICAL_NONE;
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

/* ceil(2^(9 + l) k), k = 1 and 2/3, l = 0..6: the window factor's scale (expect_scan). */
static const uint16_t gscale[2][7] = {{512, 1024, 2048, 4096, 8192, 16384, 32768},
                                      {342, 683, 1366, 2731, 5462, 10923, 21846}};

uint8_t optical_expect_scan(int16_t mid, uint16_t half)
{
    uint8_t bad = 0;
    clear();
    W.nc = 0;
    for (uint8_t k = 0; k < W.nb; k++) {
        const optical_xy_t *b = &W.b[k];
        bad |= !coord_ok(b->x) || !coord_ok(b->y);
        /* The offset floored to 2^-8 m (within 128 m, else gated out). */
        int32_t dx = (int32_t)((uint32_t)b->x - (uint32_t)W.x);
        int32_t dy = (int32_t)((uint32_t)b->y - (uint32_t)W.y);
        W.u.id.e[k] = 0;
        if ((uint32_t)dx + 0x00800000u > 0x00FFFFFFu || (uint32_t)dy + 0x00800000u > 0x00FFFFFFu)
            continue;
        int16_t x8 = (int16_t)(uint16_t)((uint32_t)dx >> 8),
                y8 = (int16_t)(uint16_t)((uint32_t)dy >> 8);
        uint16_t ax = (uint16_t)(x8 < 0 ? 0u - (uint16_t)x8 : (uint16_t)x8);
        uint16_t ay = (uint16_t)(y8 < 0 ? 0u - (uint16_t)y8 : (uint16_t)y8);
        if (ax > W.gate8 || ay > W.gate8)
            continue;
        uint8_t flags = (uint8_t)((x8 < 0 ? 2u : 0u) | (y8 < 0 ? 4u : 0u));
        if (ay > ax) {
            uint16_t t = ax;
            ax = ay;
            ay = t;
            flags |= 1u;
        }
        uint16_t m8 = ax, psi = 0, g = 0xFFFFu;
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
        /* The window factor (2^16 / (2 pi) asin(l8 / r8) <= g l8 / 256): the range is at least
         * m8 sqrt(1 + t^2), asin(x) <= k (pi / 2) x, and 2^16 / (2 pi) (pi / 2) 256 = 2^22, so
         * g = 2^22 k / r8 <= h k 2^(l - 7). */
        if (m8 >= 77u && m8 > W.amax8) {
            uint16_t h = (uint16_t)(((uint32_t)p.r * optical_ct_tab[p.i < 64 ? p.i : 63]) >> 16);
            uint8_t small = m8 >= 2u * (uint32_t)W.amax8; /* x <= 1/2: k = 2/3 */
            if (l <= 6) {
                g = (uint16_t)((((uint32_t)h * gscale[small][l]) >> 16) + 1u);
            } else {
                uint32_t v = small ? ((uint32_t)h * 2u + 2u) / 3u : h;
                v <<= l - 7u;
                g = v >= 0xFFFEu ? 0xFFFEu : (uint16_t)(v + 1u);
            }
        }
        if (W.lever8) /* (standing, only e is read) */
            W.u.id.g[k] = g;
        uint16_t ek = (uint16_t)(optical_win(W.eps8, g) + OPTICAL_MARGIN);
        W.u.id.e[k] = ek;
        /* The candidate sightings: from the bucket of the window's start. */
        uint16_t wmax = ek;
        if (W.lever8) /* the widest window over the sightings: the largest lever */
            wmax = (uint16_t)(optical_win(W.amax8, g) + OPTICAL_MARGIN);
        wmax = (uint16_t)(wmax + half);
        uint16_t lo = (uint16_t)(psi + (uint16_t)mid - wmax);
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
    return bad;
}

uint8_t optical_drop(uint32_t dk, uint32_t t8)
{
    uint32_t wmin = t8 ? dk / t8 : 0xFFFFu; /* 2^-16 turn */
    uint8_t kept = 0;
    for (uint8_t j = 0; j < W.n; j++) {
        bool keep = W.we[j] >= wmin;
        W.sm[j] = keep ? OPTICAL_NONE : OPTICAL_DROPPED;
        W.wchk[j] = 0x7Fu;
        kept += keep;
    }
    return kept;
}

void optical_eval(int16_t mid, uint16_t half)
{
    clear();
    for (uint8_t c = 0; c < W.nc; c++)
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

/* floor(v / 2) */
static int32_t half32(int32_t v)
{
    return (int32_t)(((uint32_t)v >> 1) | ((uint32_t)v & 0x80000000u));
}

/* floor((v + 2^29) / 2^30) without a signed shift */
static int32_t rnd30(int64_t v)
{
    uint64_t s = (uint64_t)v + (1ull << 29);
    uint64_t m = (int64_t)s < 0 ? ~0ull : 0ull;
    return (int32_t)(int64_t)(((s ^ m) >> 30) ^ m);
}

/*
 * a b without the product of the low words (a mod 2^16)(b mod 2^16) < 2^32: after the
 * rounding to 2^-30 that leaves at most 4 units, far below the sines' own error (fx_sin:
 * 118 units of 2^-30), and saves the MSP430 a quarter of the multiplies.
 */
static int64_t prod(int32_t a, int32_t b)
{
    return (int64_t)a * b - (int64_t)((uint32_t)a & 0xFFFFu) * ((uint32_t)b & 0xFFFFu);
}

/* The two homogeneous centres of one circle from the products of one offset (a, b) with the
 * sine and cosine (s, c): n0 = (as - bc, bs + ac), n1 = (-as - bc, ac - bs). */
static void group(int32_t a, int32_t b, int32_t s, int32_t c, int32_t *n0, int32_t *n1)
{
    int64_t pa = prod(a, s), pb = prod(b, c), pc = prod(b, s), pd = prod(a, c);
    n0[0] = rnd30(pa - pb);
    n0[1] = rnd30(pc + pd);
    n1[0] = rnd30(-pa - pb);
    n1[1] = rnd30(pd - pc);
}

/*
 * One pairwise intersection relative to the common beacon: cross(nY, nX) rot90(W) / |W|^2,
 * W = sX nY - sY nX (triangulate.c). False when the circles (nearly) coincide.
 */
static bool pair(const int32_t *nX, int32_t sX, const int32_t *nY, int32_t sY, int32_t p[2])
{
    int32_t wx = rnd30(prod(nY[0], sX) - prod(nX[0], sY)); /* |W| < 2^30.1 */
    int32_t wy = rnd30(prod(nY[1], sX) - prod(nX[1], sY));
    int32_t x = rnd30(prod(nY[0], nX[1]) - prod(nY[1], nX[0])); /* |x| < 2^28 */
    uint32_t m = umag(wx) | umag(wy);
    if (m == 0)
        return false;
    uint8_t e = 2; /* W~ = W 2^(e - 2), its larger component in [2^28, 2^29) */
    for (; m < (1ul << 28); m <<= 1) {
        wx *= 2;
        wy *= 2;
        e++;
    }
    for (; m >= (1ul << 29); m >>= 1) { /* at most twice */
        wx = half32(wx);
        wy = half32(wy);
        e--;
    }
    uint32_t d = (uint32_t)rnd30(prod(wx, wx) + prod(wy, wy)); /* [2^26, 2^29) */
    /* t = round(x 2^28 / d) < 2^30.1 */
    uint32_t t = (uint32_t)((((uint64_t)umag(x) << 28) + (d >> 1)) / d);
    int32_t ts = x < 0 ? -(int32_t)t : (int32_t)t;
    /* exact products here: the shift by e below would magnify the low words' part */
    int32_t px = rnd30(-(int64_t)ts * wy), py = rnd30((int64_t)ts * wx);
    for (; e > 0; e--) { /* P = t rot90(W~) 2^e / 2^30 */
        /* beyond 2^30 lambda (eight times the beacons' span) the circles all but coincide */
        if ((umag(px) | umag(py)) >= (1ul << 29))
            return false;
        px *= 2;
        py *= 2;
    }
    p[0] = px;
    p[1] = py;
    return true;
}

bool optical_tri_core(const int32_t v[4], const int32_t sc[6], int32_t out[2])
{
    /* Doubled homogeneous centres, at the common beacon of each pair (triangulate.c):
     * A at B2 s1 b1 - c1 rot90(b1), at B1 -s1 b1 - c1 rot90(b1); B at B2 s2 b3 + c2 rot90(b3),
     * at B3 -s2 b3 + c2 rot90(b3); C at B1 s3 q + c3 rot90(q), at B3 -s3 q + c3 rot90(q). */
    int32_t n[12];
    group(v[0], v[1], sc[0], -sc[1], &n[0], &n[4]);
    group(v[2], v[3], sc[2], sc[3], &n[2], &n[8]);
    group(v[2] - v[0], v[3] - v[1], sc[4], sc[5], &n[6], &n[10]);
    int32_t p[2];
    int64_t sx = 0, sy = 0;
    if (!pair(&n[0], sc[0], &n[2], sc[2], p)) /* AB at B2 */
        return false;
    sx += p[0];
    sy += p[1];
    if (!pair(&n[4], sc[0], &n[6], sc[4], p)) /* AC at B1 */
        return false;
    sx += (int64_t)p[0] + v[0];
    sy += (int64_t)p[1] + v[1];
    if (!pair(&n[8], sc[2], &n[10], sc[4], p)) /* BC at B3 */
        return false;
    sx += (int64_t)p[0] + v[2];
    sy += (int64_t)p[1] + v[3];
    /* the mean: floor(sum / 2) (2^30 / 3) / 2^30 * 2 (|sum| < 2^32) */
    out[0] = 2 * rnd30(prod((int32_t)((sx - (sx < 0)) / 2), 357913941));
    out[1] = 2 * rnd30(prod((int32_t)((sy - (sy < 0)) / 2), 357913941));
    return true;
}

#endif

#ifndef OPTICAL_ASM

uint32_t optical_shl32(uint32_t v, uint8_t n)
{
    return v << n;
}

int32_t optical_asr32(int32_t v, uint8_t n)
{
    return v < 0 ? (int32_t) ~(~(uint32_t)v >> n) : (int32_t)((uint32_t)v >> n);
}

/* floor(s / 2^16) */
static int16_t q14(int32_t s)
{
    return (int16_t)(uint16_t)((uint32_t)s >> 16);
}

/* Every component shifted right (floor) by the s that brings them all below 2^14: s. */
static uint8_t to15(int32_t *v)
{
    uint32_t m = 0;
    for (uint8_t i = 0; i < 6; i++)
        m |= umag(v[i]);
    uint8_t s = 0;
    for (; m >= 0x4000u; m >>= 1)
        s++;
    for (uint8_t i = 0; i < 6; i++)
        for (uint8_t k = 0; k < s; k++)
            v[i] = half32(v[i]);
    return s;
}

void optical_quality_parts(const int32_t v[4], const int32_t c[2], const int32_t sc[6],
                           optical_qparts_t *out)
{
    int32_t ch[6] = {v[0], v[1], v[2], v[3], v[2] - v[0], v[3] - v[1]};
    int32_t rg[6] = {v[0] - c[0], v[1] - c[1], c[0], c[1], v[2] - c[0], v[3] - c[1]};
    out->sc = to15(ch);
    to15(rg);
    uint32_t sq[6];
    for (uint8_t i = 0; i < 6; i++) {
        const int32_t *u = i < 3 ? &ch[2 * i] : &rg[2 * i - 6];
        sq[i] = (uint32_t)(u[0] * u[0] + u[1] * u[1]); /* < 2^29 */
    }
    /* chords c12, c23, c31 against the ranges r3, r1, r2 */
    uint32_t num2 = (sq[0] >> 14) * (sq[5] >> 14) + (sq[1] >> 14) * (sq[3] >> 14) +
                    (sq[2] >> 14) * (sq[4] >> 14);
    out->num = fx_sqrt32(num2);
    int32_t r1 = fx_sqrt32(sq[3]), r2 = fx_sqrt32(sq[4]), r3 = fx_sqrt32(sq[5]);
    /* a31 = 360 - alpha3: sin a31 = -s3; the sines Q14 (their high words) */
    int32_t den = r3 * q14(sc[0]) + r1 * q14(sc[2]) - r2 * q14(sc[4]);
    out->den = umag(den);
}

#endif
