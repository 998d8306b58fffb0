/*
 * ident.c - the identification's primitives (SPEC O2-O5, optical/fastmath.h): the work area,
 * the cheap bearing optical_angle16 and the octant arithmetic it shares with the scan, the
 * window test of one (sighting, beacon) pair, the re-evaluation of the candidate pairs, O4's
 * width threshold and marks, O5's width check. The scan over the map itself, optical_scan,
 * is a kernel (scan_k.c, msp430/optical_scan.S: docs/kernels.md). The tables are generated at
 * build time (tools/gen_optical_tables.py; formulas in fastmath.h).
 */
#include <stdbool.h>
#include <stddef.h>

#include "optical/fastmath.h"

optical_work_t optical_work;
#define W (optical_work)

static uint32_t umag(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

static uint16_t sat16(uint32_t v)
{
    return v > 0xFFFFu ? 0xFFFFu : (uint16_t)v;
}

/* (v = u needs no case of its own: q saturates, and the interpolation gives 45 degrees for
 * every u, checked exhaustively.) */
uint16_t optical_octant(uint16_t u, uint16_t v, uint8_t flags, optical_angle_parts_t *p)
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
    optical_angle_parts_t p;
    return optical_octant((uint16_t)ax, (uint16_t)ay, flags, &p);
}

uint16_t optical_win(uint16_t l, uint16_t g)
{
    if (g == 0xFFFFu)
        return 0x7FFFu;
    uint32_t v = ((uint32_t)l * g + 255u) >> 8;
    return v > 0x7FFFu ? 0x7FFFu : (uint16_t)v;
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

bool optical_pair(uint8_t j, uint8_t k, int16_t mid, uint16_t half)
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
    return optical_scan(mid, half);
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
        optical_pair(W.u.id.cand[2u * c], W.u.id.cand[2u * c + 1u], mid, half);
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
