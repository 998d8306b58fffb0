/*
 * scan_k.c - the C twin of the kernel optical_scan (optical/fastmath.h; the assembly:
 * msp430/optical_scan.S): the expected angle and window of every map beacon and the candidate
 * pairs within the windows. The definition of every result: the build takes this file or the
 * assembly whole, and the check images run both on every call (docs/kernels.md).
 */
#include <stdbool.h>

#include "optical/fastmath.h"

#define W (optical_work)

/* floor(v / 2^8) within [-2^15, 2^15) into *v8, else false */
static bool to8(int32_t v, int16_t *v8)
{
    if ((uint32_t)v + 0x00800000u > 0x00FFFFFFu)
        return false;
    *v8 = (int16_t)(uint16_t)((uint32_t)v >> 8);
    return true;
}

uint8_t optical_scan(int16_t mid, uint16_t half)
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
        optical_angle_parts_t p = {0, 0};
        uint8_t l = 0;
        if (ax) {
            for (; ax < 0x8000u; l++) { /* to [2^15, 2^16) */
                ax = (uint16_t)(ax << 1);
                ay = (uint16_t)(ay << 1);
            }
            psi = optical_octant(ax, ay, flags, &p);
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
            if (W.sm[j] == OPTICAL_DROPPED || !optical_pair(j, k, mid, half) || W.nc == 0xFFu)
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
