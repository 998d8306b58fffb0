/*
 * optical/fastmath.h - the arithmetic the optical fix spends its time in: the work area, the
 * identification's primitives (ident.c) and the kernels (docs/kernels.md): optical_scan
 * (scan_k.c; msp430/optical_scan.S on the target) and optical_tri_core / optical_tri_quality
 * (tri_k.c; msp430/optical_tri.S). A kernel's C twin defines every result; its assembly
 * performs the very same integer steps (the check images compare both on every call).
 *
 * These are the internals of optical_fix() and optical_triangulate(), public only so that the
 * tests can check them one by one; the work arrays they fill are described in fix.c and
 * triangulate.c.
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

/** The parts of optical_octant()'s arithmetic that optical_scan reuses for its windows. */
typedef struct {
    uint16_t r; /**< 2^30 / u (interpolated) */
    uint16_t i; /**< floor(64 v / u), 0..63 */
} optical_angle_parts_t;

/**
 * optical_angle16's arctangent of one octant: @p u in [2^15, 2^16), @p v <= u (the larger and
 * the smaller magnitude, scaled alike), unfolded by @p flags (1 swapped, 2 dx < 0, 4 dy < 0);
 * 2^-16 turn. The ratio through the interpolated reciprocal r = 2^30 / u (optical_recip_tab,
 * optical_recip_d_tab), q = min(v r / 2^14, 0xFFFF), the arctangent from optical_atan_tab
 * interpolated at q (i = q >> 10, fraction q << 6); @p p receives r and i.
 */
uint16_t optical_octant(uint16_t u, uint16_t v, uint8_t flags, optical_angle_parts_t *p);

/** round(2^30 / (2^15 + 512 i)), i = 0..64 (optical_angle16's reciprocal). */
extern const uint16_t optical_recip_tab[65];
/** (optical_recip_tab[i] - optical_recip_tab[i + 1]) 2^7, i = 0..63: the reciprocal's
 * interpolation step, scaled for a fraction of 9 bits (all below 2^16). */
extern const uint16_t optical_recip_d_tab[64];
/** round(atan(i / 64) * 2^18 / (2 pi)) + 2, i = 0..64 (optical_angle16's arctangent, 2^-18
 * turn, with the half of its rounding to 2^-16 turn). */
extern const uint16_t optical_atan_tab[65];

/** Identification margin of every window, 2^-16 turn (fix.c explains it). */
#define OPTICAL_MARGIN 6

/** Match codes of optical_work_t.sm / .bm (otherwise: the matched beacon or sighting). */
#define OPTICAL_NONE    0xFFu /**< no match */
#define OPTICAL_MULTI   0xFEu /**< more than one match */
#define OPTICAL_DROPPED 0xFDu /**< sighting dropped by the width threshold (O4) */

/** Most candidate pairs the identification keeps. */
#define OPTICAL_MAX_CAND 40

/**
 * A triangulation's solution (optical_tri_core) and what its quality needs
 * (optical_tri_quality). lambda: the offsets' unit after the scaling (Q16 m times 2^sigma).
 */
typedef struct {
    int32_t off[2]; /**< the vehicle relative to beacon 2, Q16 m, rounded */
    int32_t w[2];   /**< the direction from the vehicle to beacon 2 (any scale) */
    int32_t l[3];   /**< the ranges to beacons 1, 2, 3 times |U^| / 2^32 (lambda units) */
    uint32_t r;     /**< R' = 2^(52 + g) / Q within 16 units, Q = |U^|^2 / 2^32: in [2^29, 2^30] */
    int8_t x;       /**< e - g - sigma: the quality's exponent */
} optical_tsol_t;

/**
 * The work area of optical_fix() and of the identification kernels (static: the MSP430's
 * stack is small; optical_fix is not reentrant). Per beacon k: psi[k] its expected angle
 * minus the heading (2^-16 turn), e[k] its window position part plus OPTICAL_MARGIN (0: gated
 * out), g[k] its window factor (optical_win), bm[k] the sighting it matched (NONE, MULTI).
 * Per sorted sighting j: th[j] its angle (2^-16 turn, ascending), lev[j] its parallax lever
 * (2^-8 m), sm[j] the beacon it matched (NONE, MULTI, DROPPED: left alone), we[j] the position
 * part of that match. cand holds the candidate
 * pairs (sighting, beacon: two bytes each) of the last optical_expect_scan, nc of them (0xFF: more
 * than OPTICAL_MAX_CAND). The rest belongs to fix.c. The per-beacon arrays share their bytes with
 * the solve's (u.sv): identification is over before the identified angles are gathered.
 */
typedef struct {
    const optical_xy_t *b; /**< the map, nb beacons */
    fx_q16_t x, y;         /**< the position seen from, within OPTICAL_COORD_LIMIT */
    uint16_t head;         /**< heading, 2^-16 turn */
    uint16_t eps8;         /**< position uncertainty, 2^-8 m */
    uint16_t lever8;       /**< largest parallax lever, 2^-8 m (0 standing) */
    uint16_t amax8;        /**< min(eps8 + lever8, 0xFFFF) */
    uint16_t gate8;        /**< beacons with |dx| or |dy| (2^-8 m) beyond: gated */
    uint8_t nb, n;         /**< beacons (1..32), sightings (0..15) */
    uint8_t nc;            /**< candidate pairs stored */
    uint8_t m;             /**< fix.c: the identified */
    uint16_t th[OPTICAL_MAX_SIGHTINGS];
    uint16_t lev[OPTICAL_MAX_SIGHTINGS];
    uint16_t we[OPTICAL_MAX_SIGHTINGS];
    int32_t c[OPTICAL_MAX_SIGHTINGS]; /**< fix.c: parallax lever, Q16 m */
    uint8_t sm[OPTICAL_MAX_SIGHTINGS];
    uint8_t bstart[16];                  /**< first sighting at or after each 1/16 turn (0: none) */
    uint8_t ord[OPTICAL_MAX_SIGHTINGS];  /**< fix.c: input index of th[j] */
    uint8_t wchk[OPTICAL_MAX_SIGHTINGS]; /**< fix.c: O5 verdict cache */
    uint8_t pos[OPTICAL_MAX_SIGHTINGS];  /**< fix.c: the identified, sorted positions */
    union {
        struct {
            uint16_t psi[OPTICAL_MAX_BEACONS];
            uint16_t e[OPTICAL_MAX_BEACONS];
            uint16_t g[OPTICAL_MAX_BEACONS];
            uint8_t bm[OPTICAL_MAX_BEACONS];
            uint8_t cand[2 * OPTICAL_MAX_CAND];
        } id;
        struct {
            fx_angle_t ang[OPTICAL_MAX_SIGHTINGS]; /**< the identified, reference frame */
            optical_xy_t b[3];                     /**< the triplet being solved */
            optical_tri_t tri;                     /**< a candidate triplet's solution */
            int32_t v[4];      /**< optical_triangulate: the offsets (optical_tri_core) */
            int32_t sc[4];     /**< its sines and cosines */
            optical_tsol_t ts; /**< its solution */
        } sv;
    } u;
    const optical_xy8_t *b8; /**< the compiled map (optical_map_t.b8), nb beacons */
    fx_q16_t ox, oy;         /**< its origin */
} optical_work_t;

/** The work area (ident.c). */
extern optical_work_t optical_work;

/**
 * Expected angle and window of every map beacon from (x, y, head) (O2), and the candidate
 * pairs within the windows centred on heading offset @p mid (2^-16 turn) of half-width @p half
 * (optical_pair's test; the pairs in scan order, sightings from the bucket of each window's
 * start). Per beacon, with (x8, y8) = b8[k] - p8 its offset in 2^-8 m, p8 = floor(((x, y) -
 * (ox, oy)) / 2^8) the position in the compiled map (a magnitude beyond gate8: e = 0, gated
 * out): psi = the angle of (x8, y8) - head, with optical_octant() (r its 2^30 / u, u = m8 2^l
 * in [2^15, 2^16), m8 the
 * larger magnitude, i = floor(64 t), t = smaller / larger). The window, when m8 >= 77 and
 * m8 > amax8 (else g = 0xFFFF, e = 0x7FFF + margin): h = floor(r optical_ct_tab[i] / 2^16)
 * (asin's factor k = 2/3 in the table), when m8 < 2 amax8 (k = 1) h + floor(h / 2) + 2;
 * e = min(floor(h eps8 2^l / 2^16) + 1, 0x7FFF) + margin (eps8 2^l < 2^16 there); g =
 * floor(h / 2^(8 - l)) + 1 (l <= 8), min(2 h + 1, 0xFFFE) (l = 9). So e - margin >= 2^16 /
 * (2 pi) asin(eps8 / r8) and optical_win(l8, g) >= 2^16 / (2 pi) asin(l8 / r8) for l8 <=
 * amax8, r8 = |(x8, y8)| (docs/optical.md "O2-O5" derives it; tests/unit/optical_test.cpp
 * checks it). Both floorings leave each coordinate of the offset within one unit of 2^-8 m
 * of the exact one (the vector within sqrt 2 units): the caller adds 2 to eps8. Clears bm and
 * nc and marks every pair as optical_pair(), sm as they are: every sm[j] NONE or DROPPED
 * (as optical_drop() leaves them; else optical_expect_scan()). Returns 1 when the position
 * lies beyond the compiled map's reach (p8 outside [-2^15, 2^15): nothing scanned), else 0.
 * The kernel of the identification (scan_k.c; msp430/optical_scan.S).
 */
uint8_t optical_scan(int16_t mid, uint16_t half);

/** optical_scan() after clearing the marks sm[j] (except DROPPED) to NONE: for marks in any
 * state. */
uint8_t optical_expect_scan(int16_t mid, uint16_t half);

/**
 * Pair (sighting @p j, beacon @p k) within the windows centred on heading offset @p mid of
 * half-width @p half (2^-16 turn): |th[j] - psi[k] - mid| <= half + w, w = e[k] standing
 * (lever8 = 0 or lev[j] = 0), else optical_win(min(eps8 + lev[j], 0xFFFF), g[k]) + margin;
 * then marked: sm[j], bm[k] get the partner (or MULTI when they had one), we[j] = w. Returns
 * whether it is. half + w must stay below 2^16.
 */
bool optical_pair(uint8_t j, uint8_t k, int16_t mid, uint16_t half);

/**
 * The stored candidate pairs within the windows (mid, half), by optical_pair() (the pairs
 * taken from the last to the first). Clears bm and sm (except DROPPED) first. nc not 0xFF.
 */
void optical_eval(int16_t mid, uint16_t half);

/**
 * O4 (fix.c's threshold): the narrowest width kept, floor(@p dk / @p t8) (0xFFFF when t8 = 0),
 * 2^-16 turn. @p dk: the post diameter as optical_width_t.dk, @p t8 the range threshold in
 * 2^-8 m.
 */
uint32_t optical_wmin(uint32_t dk, uint32_t t8);

/**
 * O4's marks: every sorted sighting j narrower than @p wmin (optical_wmin), its width
 * @p s[ord[j]].width (2^-16 turn), is dropped: sm[j] = DROPPED, the others NONE; wchk[j] = 0x7F
 * (no O5 verdict yet). Returns the sightings kept.
 */
uint8_t optical_drop(const optical_sighting_t *s, uint32_t wmin);

/** Window part min(ceil(l g / 256), 0x7FFF) of lever l (2^-8 m); 0x7FFF when g = 0xFFFF. */
uint16_t optical_win(uint16_t l, uint16_t g);

/** ceil(2^16 (2/3) / sqrt(1 + (i / 64)^2)), i = 0..63 (optical_scan's range bound with
 * asin's factor 2/3). */
extern const uint16_t optical_ct_tab[64];

/**
 * The triangulation's arithmetic (triangulate.c, docs/optical.md "O9"): @p v = (b1x, b1y,
 * b3x, b3y) the offsets of beacons 1 and 3 from beacon 2, Q16 m, scaled in place by 2^sigma
 * (largest component in [2^28, 2^29): lambda units); @p sc = (s1, c1, s2, c2) the sines and
 * cosines of alpha1 and alpha2 (Q1.30). Products are sums of x y / 2^32 of balanced 16-bit
 * halves (x = h 2^16 + l, l the low word, signed; the products l l dropped). With
 * a = R(alpha1) b1, c = R(-alpha2) b3, U = s2 a + s1 c, kappa = cross(a, c) (A = a / 4,
 * C = c / 4, V = U / 16, 16 K = kappa / 2^32 as computed), beacon 2 lies at d = kappa U / |U|^2
 * from the vehicle; U normalised to U^ = V 2^e (larger component in [2^27, 2^28)),
 * K' = 16 K 2^(e - 4). Writes @p out on OPTICAL_OK. Returns OPTICAL_OK, OPTICAL_E_ARG (a
 * component of 2^27 or more: 2048 m), OPTICAL_E_DEGENERATE (b1 = 0, b3 = 0 or b1 = b3),
 * OPTICAL_E_SINGULAR (U = 0, or beacon 2 2^31 lambda or farther, four to eight times the
 * span: the circles all but coincide) or OPTICAL_E_INCONSISTENT (a beacon lies behind its
 * sighting: the solution of the other arc of a circle, or the vehicle on beacon 2).
 */
int8_t optical_tri_core(int32_t v[4], const int32_t sc[4], optical_tsol_t *out);

/**
 * The quality of a triangulation from optical_tri_core's @p v (scaled) and @p s: the RMS
 * position error per unit independent bearing error, S = sqrt(c12^2 r3^2 + c23^2 r1^2 + c31^2
 * r2^2) / |U| (docs/optical.md), in Q16 m per mrad, rounded down, saturated at UINT32_MAX.
 * Within about 0.2 % of the exact bound (measured; the chords' 15-bit parts limit it where
 * two beacons are close) plus the output's unit. The square root: M normalised to [2^30,
 * 2^32) by factors of 4, optical_sqrt_tab interpolated (k = M / 2^27 - 8, the fraction
 * M / 2^16 mod 2^11): at most 0.05 % low.
 */
uint32_t optical_tri_quality(const int32_t v[4], const optical_tsol_t *s);

/** round(sqrt((8 + k) 2^27)) - 2^15, k = 0..24 (optical_tri_quality's root). */
extern const uint16_t optical_sqrt_tab[25];

/**
 * optical_triangulate() of the identified triplet at positions @p t[3] of fix.c's identified
 * set: the beacons map[sm[pos[t[i]]]] and the angles u.sv.ang[t[i]] of the work area (copied
 * into u.sv.b).
 */
int8_t optical_tri_take(const optical_xy_t *map, const uint8_t t[3], uint32_t quality_max,
                        optical_tri_t *out);

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
