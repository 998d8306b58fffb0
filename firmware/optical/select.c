/*
 * select.c - beacon selection (SPEC O7), the seed's section 2.2.1 with its intent restored.
 *
 * With the N identified sightings in ring order, Dif[i] is the CCW gap from sighting i to the
 * next one, Dif[N] the gap from the last across 0/360 degrees to the first. While N > 3: take
 * the smallest gap k (between k and k+1); drop the one of the two whose other neighbouring gap
 * is smaller (k when Dif[k-1] < Dif[k+1], else k+1), and merge the two gaps beside it. The
 * seed's three cases (1 < k < N, k = 1, k = N) are this one rule with the indices taken around
 * the ring. Restored from the seed: its third case merges into the wrong gap (it sets
 * Dif[N-1] = Dif[N] + Dif[1] when dropping beacon 1; the gap that grows is Dif[N]); its text
 * leaves Dif[k-1] = Dif[k+1] to neither branch (the listing's ELSE drops k+1, as here); the
 * listing's first pass reads AG(N+1) beyond the array. Ties between gaps: the first smallest.
 * Three or fewer: 0, 1, 2. The gaps are differences modulo a turn (angles in any order).
 */
#include "optical/optical.h"

void optical_select(const fx_angle_t *angle, uint8_t n, uint8_t keep[3])
{
    if (n <= 3) {
        keep[0] = 0;
        keep[1] = 1;
        keep[2] = 2;
        return;
    }
    /* The gaps as high and low halves: 16-bit compares with branches on the MSP430. */
    uint8_t id[OPTICAL_MAX_SIGHTINGS];
    uint16_t dh[OPTICAL_MAX_SIGHTINGS], dl[OPTICAL_MAX_SIGHTINGS];
    for (uint8_t i = 0; i < n; i++) {
        id[i] = i;
        fx_angle_t d = angle[i + 1u < n ? i + 1u : 0u] - angle[i]; /* the last one wraps */
        dh[i] = (uint16_t)(d >> 16);
        dl[i] = (uint16_t)d;
    }
    while (n > 3) {
        uint8_t k = 0;
        uint16_t bh = dh[0], bl = dl[0];
        for (uint8_t i = 1; i < n; i++) {
            if (dh[i] > bh || (dh[i] == bh && dl[i] >= bl))
                continue;
            bh = dh[i];
            bl = dl[i];
            k = i;
        }
        uint8_t prev = k ? (uint8_t)(k - 1u) : (uint8_t)(n - 1u);
        uint8_t nxt = k + 1u < n ? (uint8_t)(k + 1u) : 0u;
        uint8_t drop, into; /* position of the sighting removed, of the gap that grows */
        if (dh[prev] < dh[nxt] || (dh[prev] == dh[nxt] && dl[prev] < dl[nxt])) {
            drop = k; /* its gaps prev and k merge into prev */
            into = prev;
        } else {
            drop = nxt; /* its gaps k and nxt merge into k */
            into = k;
            bh = dh[nxt];
            bl = dl[nxt];
        }
        fx_angle_t sum = (((fx_angle_t)dh[into] << 16) | dl[into]) + (((fx_angle_t)bh << 16) | bl);
        dh[into] = (uint16_t)(sum >> 16);
        dl[into] = (uint16_t)sum;
        /* The gap that starts at the dropped sighting went into the merged one: both go. */
        for (uint8_t i = drop; i + 1u < n; i++) {
            id[i] = id[i + 1u];
            dh[i] = dh[i + 1u];
            dl[i] = dl[i + 1u];
        }
        n--;
    }
    keep[0] = id[0];
    keep[1] = id[1];
    keep[2] = id[2];
}
