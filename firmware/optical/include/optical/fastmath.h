/*
 * optical/fastmath.h - the kernels the optical fix spends its time in. On the MSP430 they are
 * assembly (firmware/optical/msp430/); fastmath.c holds the portable C that defines every
 * result, and the assembly performs the very same integer steps (tests/vectors/
 * optical_vectors.c prints them on both worlds: bit-identical).
 *
 * These are the internals of optical_fix() and optical_triangulate(), public only so that the
 * vector program can check them one by one; the work arrays they fill are described in
 * fix.c and triangulate.c.
 */
#ifndef OPTICAL_FASTMATH_H
#define OPTICAL_FASTMATH_H

#include <stdbool.h>
#include <stdint.h>

#include "fx/fx.h"
#include "optical/optical.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Direction of the vector (dx, dy) in 2^-16 turn (65536 = 360 degrees, CCW from +x), cheap:
 * the identification's expected angles and residuals. Any int32 components (any common
 * scale); max error 0.97 units (0.0053 degrees, measured against atan2); (0, 0) gives 0.
 * Octant folding, both components to [2^15, 2^16) by one shift, the ratio through an
 * interpolated reciprocal table and the 16 x 16 multiplier, the arctangent from an
 * interpolated table in 2^-18 turn.
 */
uint16_t optical_angle16(int32_t dx, int32_t dy);

/** round(2^30 / (2^15 + 512 i)), i = 0..64 (optical_angle16's reciprocal). */
extern const uint16_t optical_recip_tab[65];
/** round(atan(i / 64) * 2^18 / (2 pi)), i = 0..64 (optical_angle16's arctangent). */
extern const uint16_t optical_atan_tab[65];

/** Identification margin of every window, 2^-16 turn (fix.c explains it). */
#define OPTICAL_MARGIN 6

/** Match codes of optical_ident_t.sm / .bm (otherwise: the matched beacon or sighting). */
#define OPTICAL_NONE    0xFFu /**< no match */
#define OPTICAL_MULTI   0xFEu /**< more than one match */
#define OPTICAL_DROPPED 0xFDu /**< sighting dropped by the width threshold (O4) */

/** Most candidate pairs the identification keeps. */
#define OPTICAL_MAX_CAND 40

/**
 * The identification's arrays and parameters (fix.c owns the memory). Per beacon k: psi[k]
 * its expected angle minus the heading (2^-16 turn), e[k] its window position part plus
 * OPTICAL_MARGIN (0: gated out), g[k] its window factor (optical_win), bm[k] the sighting it
 * matched (NONE, MULTI). Per sorted sighting j: th[j] its angle (2^-16 turn, ascending), lev[j]
 * its parallax lever (2^-8 m; the array only when lever8 > 0), sm[j] the beacon it matched
 * (NONE, MULTI, DROPPED: left alone), we[j] the position part of that match. cand holds
 * the candidate pairs (sighting, beacon: two bytes each) of the last optical_expect_scan.
 */
typedef struct {
    const optical_xy_t *b;    /**< the map, nb beacons */
    uint16_t *psi, *e, *g;    /**< per beacon */
    uint8_t *bm;              /**< per beacon */
    const uint16_t *th, *lev; /**< per sighting */
    uint8_t *sm;              /**< per sighting */
    uint16_t *we;             /**< per sighting */
    const uint8_t *bstart;    /**< first sighting at or after each 1/16 turn (0: none) */
    uint8_t *cand;            /**< 2 OPTICAL_MAX_CAND bytes */
    fx_q16_t x, y;            /**< the position seen from, within OPTICAL_COORD_LIMIT */
    uint32_t gate;            /**< beacons with |dx| or |dy| (Q16) beyond it are gated out */
    uint16_t head;            /**< heading, 2^-16 turn */
    uint16_t eps8;            /**< position uncertainty, 2^-8 m */
    uint16_t lever8;          /**< largest parallax lever, 2^-8 m (0 standing) */
    uint16_t amax8;           /**< min(eps8 + lever8, 0xFFFF) */
    uint8_t nb, n;            /**< beacons (1..32), sightings (0..15) */
    uint8_t nc;               /**< out: candidate pairs stored, 0xFF more than the room */
} optical_ident_t;

/**
 * Expected angle and window of every map beacon from (x, y, head) (O2), and the candidate
 * pairs within the windows centred on heading offset @p mid (2^-16 turn) of half-width @p half
 * (optical_eval's test). Per beacon, with dx, dy its offset (Q16) and ax, ay their
 * magnitudes: |dx| or |dy| beyond the gate: e = 0; otherwise psi = optical_angle16(dx, dy) -
 * head, g = the window factor of a beacon at range >= max(ax, ay) sqrt(1 + t^2) (t = min /
 * max, from optical_angle16's reciprocal and a table of 1 / sqrt(1 + t^2) rounded up):
 * 0xFFFF when the larger of ax, ay (2^-8 m) is below 77 or within amax8, otherwise
 * 2 H k / 2^s + 1 (saturated), with u = max(ax, ay) 2^-s in [2^15, 2^16), H = (R C) / 2^16
 * (R = 2^30 / u interpolated, C = 2^15 / sqrt(1 + (i / 64)^2) rounded up, i = floor(64 t)),
 * k = 2/3 (rounded up) when the larger is at least 2 amax8, else 1; e = optical_win(eps8, g) +
 * margin. Clears bm and sm (except DROPPED) and marks every pair as optical_eval.
 * Returns 1 (stopping there) at the first beacon beyond OPTICAL_COORD_LIMIT, else 0.
 */
uint8_t optical_expect_scan(optical_ident_t *a, int16_t mid, uint16_t half);

/**
 * The stored candidate pairs within the windows (mid, half): pair (j, k) when
 * |th[j] - psi[k] - mid| <= half + w, w = e[k] standing (lever8 = 0 or lev[j] = 0), else
 * optical_win(min(eps8 + lev[j], 0xFFFF), g[k]) + margin; marked: sm[j], bm[k] get the partner
 * (or MULTI when they had one), we[j] = w. Clears bm and sm (except DROPPED) first. half + w
 * must stay below 2^16.
 */
void optical_eval(optical_ident_t *a, int16_t mid, uint16_t half);

/** Window part min(ceil(l g / 256), 0x7FFF) of lever l (2^-8 m); 0x7FFF when g = 0xFFFF. */
uint16_t optical_win(uint16_t l, uint16_t g);

/** ceil(2^15 / sqrt(1 + (i / 64)^2)), i = 0..63 (optical_expect_scan's range bound). */
extern const uint16_t optical_ct_tab[64];

/**
 * One pairwise intersection of the triangulation and their average (triangulate.c):
 * @p v = (b1x, b1y, b3x, b3y) the beacon offsets from beacon 2 in lambda units (largest
 * component in [2^27, 2^28)), @p sc = (s1, c1, s2, c2, s3, c3) the sines and cosines of the
 * inscribed angles (Q1.30). Writes the mean of the three intersections relative to beacon 2,
 * lambda units; false when a pair of circles (nearly) coincides.
 */
bool optical_tri_core(const int32_t v[4], const int32_t sc[6], int32_t out[2]);

/** The parts of a triangulation's quality (optical_quality_parts). */
typedef struct {
    uint32_t den; /**< |r3 s1 + r1 s2 - r2 s3|, ranges 2^-sr lambda, sines Q14 */
    uint16_t num; /**< sqrt(c12^2 r3^2 + c23^2 r1^2 + c31^2 r2^2) / 2^(14 + sc + sr) */
    uint8_t sc;   /**< the chords' scale */
} optical_qparts_t;

/**
 * Quality of a triangulation in parts (triangulate.c divides them): @p v as
 * optical_tri_core, @p c the vehicle relative to beacon 2 (lambda units), @p s = (s1, s2, s3)
 * Q1.30. The chords (b1, b3, b3 - b1) and the ranges (b1 - c, c, b3 - c) are each cut to
 * 15-bit components by a common shift (sc for the chords, sr for the ranges), their squares
 * to 15 bits; the quality is num 2^(28 + sc) / den lambda per radian.
 */
void optical_quality_parts(const int32_t v[4], const int32_t c[2], const int32_t s[3],
                           optical_qparts_t *out);

/** Arguments of optical_width_ok(). */
typedef struct {
    uint32_t dk;    /**< D 2^8 2^16 / (2 pi), D the post diameter in m */
    fx_q16_t x, y;  /**< the position the beacon is seen from */
    uint16_t eps8;  /**< position uncertainty, 2^-8 m */
    uint16_t tol8;  /**< absolute distance tolerance, 2^-8 m */
    uint16_t rel16; /**< relative distance tolerance, 2^-16 */
    uint8_t flat;   /**< 1: flat strips (only the upper distance bound is checked) */
} optical_width_t;

/**
 * O5: is an apparent width of @p w16 (2^-16 turn) compatible with beacon @p b seen from (x,
 * y) +- eps8? The range lies within [o / 1.118 - eps8, o + eps8], o the octagonal norm of the
 * offset (2^-8 m, components capped at 256 m), widened by tol8 + rel16 times its upper end.
 * Posts look 2 asin(D / 2r) wide, and 0.969 w <= 2 sin(w/2) <= w below 0.5 rad.
 */
bool optical_width_ok(const optical_width_t *a, const optical_xy_t *b, uint16_t w16);

#ifdef __cplusplus
}
#endif

#endif
