/*
 * optical/optical.h - optical navigation on the main board (SPEC O2-O11): from one mirror
 * revolution of beacon sightings to a position and bearing that can be trusted.
 *
 * Pipeline of optical_fix() (docs/optical.md has the derivations):
 *   motion      each sighting is moved into the vehicle frame of one reference instant, using
 *               the dead-reckoning poses the nav board latched at the sightings (O11);
 *   identify    expected angle of every map beacon from the approximate pose (O2); angle
 *               windows that bound the pose uncertainty, tightened by the matches found and
 *               widened a bounded number of times when fewer than three remain (O3); double
 *               matches and (when widened) overlapping windows rejected; sightings too narrow
 *               for a beacon within range dropped (O4); width distance against map distance
 *               (O5);
 *   select      the seed's adjacent-gap elimination down to three beacons (O7), ordered with
 *               their angles alpha1..3 (O8);
 *   triangulate circles through pairs of beacons and the vehicle: the two through the middle
 *               beacon B2 intersected in closed form, with the geometric error bound as
 *               quality (O9), and the bearing from the direction to B2 (O10);
 *   check       refusal near the beacons' circle, implausible jumps and turns from the
 *               approximate pose, and the other identified sightings that disagree with the
 *               fix (O6).
 *
 * Formats: fx/fx.h (binary angles, Q15.16 metres). Sighting angles are counter-clockwise from
 * the vehicle heading (the index pulse marks straight ahead). Nothing here allocates; the fix
 * works in a static area (optical_fix is not reentrant: main loop only).
 */
#ifndef OPTICAL_OPTICAL_H
#define OPTICAL_OPTICAL_H

#include <stdbool.h>
#include <stdint.h>

#include "fx/fx.h"
#include "optical/capture.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most beacons a map may hold. */
#define OPTICAL_MAX_BEACONS 32

/** Map coordinates and poses must lie within +-OPTICAL_COORD_LIMIT metres (Q15.16). */
#define OPTICAL_COORD_LIMIT (8192l * FX_Q16_ONE)

/**
 * Quality limit of optical_triangulate() where its result is still within 1 mm of the exact
 * solution of the same inputs (Q16 m per mrad: 2 m per mrad, 0.25 m per count). Beyond it the
 * geometry, not the arithmetic, has made the fix meaningless: one count of bearing error
 * moves it by more than 25 cm (docs/optical.md, "The refused region").
 */
#define OPTICAL_QUALITY_LIMIT (2ul * 65536ul)

/** A point in the world frame (x east, y north), Q15.16 metres. */
typedef struct {
    fx_q16_t x, y;
} optical_xy_t;

/** A pose: position of the goniometer (rear-axle centre) and heading, CCW from +x. */
typedef struct {
    fx_q16_t x, y;
    fx_angle_t heading;
} optical_pose_t;

/** One sighting: centre of the pulse and its apparent width. */
typedef struct {
    fx_angle_t angle; /**< CCW from the vehicle heading at the sighting instant */
    uint16_t width;   /**< apparent angular width, 2^-16 turn (0.0055 degrees) */
} optical_sighting_t;

/** A beacon of a compiled map: its offset from the map's origin floored to 2^-8 m. */
typedef struct {
    int16_t x, y;
} optical_xy8_t;

/** The compiled map's reach: beacons and poses within +-OPTICAL_MAP_REACH of its origin. */
#define OPTICAL_MAP_REACH (128l * FX_Q16_ONE)

/** Largest reflector diameter (strip width) a map may hold, Q15.16 m (2 m). */
#define OPTICAL_REFL_MAX (2l * FX_Q16_ONE)

/**
 * A beacon's reflector: a post (cylinder) of diameter d, which looks 2 asin(d / 2r) wide from
 * range r, or a flat strip of width d, which looks at most 2 atan(d / 2r) wide (facing the
 * vehicle; less when turned away).
 */
typedef struct {
    fx_q16_t d;   /**< diameter or strip width, Q15.16 m, (0, OPTICAL_REFL_MAX] */
    uint8_t flat; /**< 0 a post (cylinder), 1 a flat strip */
} optical_refl_t;

/** A compiled reflector's flag (optical_map_t.dk): a flat strip. */
#define OPTICAL_DK_FLAT 0x80000000ul

/**
 * The beacon map, compiled: optical_map_compile() fills it, or a generator writes the same
 * (tools/gen_mission.py). b8[k] = floor((b[k] - origin) / 2^8) per coordinate, 2^-8 m: the
 * expected angles of O2 come from these 16-bit offsets, computed once for the map instead of
 * once a fix per beacon. Every beacon has its own reflector, compiled to
 * dk[k] = floor(d 10430 / 2^8) (d in Q16 m: d 2^8 2^16 / (2 pi), the unit in which O4 and O5
 * compare widths times ranges), plus OPTICAL_DK_FLAT for a flat strip; dkmin is the narrowest
 * (O4 drops sightings narrower than it looks at the range threshold).
 */
typedef struct {
    const optical_xy_t *b;   /**< beacon positions (the centres of the posts) */
    uint8_t n;               /**< 3..OPTICAL_MAX_BEACONS */
    const optical_xy8_t *b8; /**< the compiled positions, n of them */
    fx_q16_t ox, oy;         /**< the origin of b8 (a multiple of 2^8, Q15.16 m) */
    const uint32_t *dk;      /**< the compiled reflectors, n of them */
    uint32_t dkmin;          /**< the smallest dk[k] without its flag */
} optical_map_t;

/** Result codes (optical_fix_t.status, optical_triangulate). */
typedef enum {
    OPTICAL_OK = 0,
    OPTICAL_E_ARG,          /**< bad arguments (map size, coordinates beyond the limit) */
    OPTICAL_E_REV,          /**< implausible revolution (period, lost captures) */
    OPTICAL_E_FEW,          /**< fewer than three beacons identified */
    OPTICAL_E_DEGENERATE,   /**< two beacons or two sightings coincide */
    OPTICAL_E_SINGULAR,     /**< too close to the beacons' circle: quality beyond the limit */
    OPTICAL_E_JUMP,         /**< the fix is implausibly far from the approximate position */
    OPTICAL_E_TURN,         /**< the bearing is implausibly far from the approximate one */
    OPTICAL_E_DISAGREE,     /**< other identified sightings disagree: likely misidentified */
    OPTICAL_E_INCONSISTENT, /**< no position sees the beacons under the angles (a solution
                                 on the wrong arc of a circle: inconsistent input, or a
                                 quantised one near the beacons' circle); in optical_fix also
                                 matches that contradict the stated pose uncertainty */
    OPTICAL_E_UNCONFIRMED,  /**< identified only beyond the bounds (a guess or widened
                                 windows) and fewer than five sightings confirm the fix */
    OPTICAL_E_POOR          /**< no triplet's predicted error (quality times the bearing
                                 error bound) is within err_max */
} optical_status_t;

/** Number of status codes (optical_status_name()). */
#define OPTICAL_STATUS_COUNT 12

/**
 * Identification and checking parameters. optical_config_default() fills the defaults
 * (docs/optical.md lists them with their agvcalc names and where each default comes from).
 * Angles are binary angles, lengths Q15.16 metres, fractions Q16. The reflectors are the
 * map's (optical_map_t.refl).
 */
typedef struct {
    fx_angle_t window;      /**< largest heading uncertainty the windows cover (O3 +-dpsi) */
    fx_q16_t window_pos;    /**< largest position uncertainty the windows cover (m) */
    fx_angle_t widen_max;   /**< heading window after the last widening */
    uint8_t widen_steps;    /**< widenings allowed; step = (widen_max - window) / steps */
    uint8_t reject_overlap; /**< 0: only when widened, 1: always (the seed's rule) */
    fx_q16_t range;         /**< T: sightings narrower than a post at T are dropped (O4) */
    fx_q16_t range_max;     /**< T after the last widening of T */
    uint8_t range_steps;    /**< widenings of T; step = (range_max - range) / steps */
    fx_q16_t dist_tol;      /**< O5: |D_map - d_width| > dist_tol + dist_rel * D_map rejects */
    fx_q16_t dist_rel;      /**< relative part of that tolerance, Q16 fraction */
    fx_q16_t jump_max;      /**< O6: largest dead-reckoning position uncertainty (m): the
                                 gate's cap, and the uncertainty when none is known */
    fx_angle_t turn_max;    /**< O6: the same for the heading */
    fx_angle_t bearing_err; /**< bound of one sighting's bearing error, standing */
    fx_angle_t bearing_err_moving; /**< the same while moving (the latched headings' steps) */
    fx_q16_t err_max;              /**< largest predicted position error accepted (m) */
    fx_q16_t unc_pos_min;      /**< dead reckoning: position uncertainty after a fix, at least */
    fx_angle_t unc_head_min;   /**< dead reckoning: heading uncertainty added to a fix's own */
    fx_q16_t unc_per_m;        /**< dead reckoning: position uncertainty per metre travelled,
                                    below 1 */
    fx_angle_t unc_head_per_m; /**< dead reckoning: heading uncertainty per metre travelled, at
                                    most 1 degree */
    fx_q16_t unc_turn;         /**< dead reckoning: heading uncertainty per unit turned, below
                                    1 */
    uint32_t quality_max;      /**< O9: largest accepted quality (Q16 m of RMS error per mrad) */
    uint8_t motion_passes;     /**< O11: triangulations with refined parallax (1..4) */
} optical_config_t;

/**
 * Bound of one sighting's bearing error standing, for a goniometer whose edges have a noise
 * of @p noise RMS (binary angle): 0.01 degrees (the pulse centre's quantisation to counts of
 * a 50,000-count goniometer, 0.0036 degrees, with room) plus 3 noise (the centre of two
 * edges has noise / sqrt 2 RMS: 4.2 sigma). docs/optical.md "O6".
 */
#define OPTICAL_BEARING_ERR(noise) (119305ul + 3ul * (noise))

/**
 * The same while moving with a heading gyro of step @p step (binary angle): each sighting is
 * turned into the reference frame by the change of the latched heading, which the nav board
 * knows to its steps (docs/optical.md "O6": in agv-sim 99.9 % of moving fixes err by less
 * than their quality times 3.5 mrad, 0.2 degrees, with steps of 0.25 degrees): the standing
 * bound plus three quarters of a step.
 */
#define OPTICAL_BEARING_ERR_MOVING(noise, step) (OPTICAL_BEARING_ERR(noise) + (step) / 4u * 3u)

/**
 * The configuration (optical_config_default()'s values) for a goniometer of edge noise
 * @p noise RMS and a gyro of step @p step (binary angles), as a constant initializer of
 * optical_config_t (a configuration kept in flash). docs/optical.md derives each value.
 */
#define OPTICAL_CONFIG(noise, step)                                                                \
    {                                                                                              \
        59652324ul /* window 5 degrees */, 19661 /* window_pos 0.3 m */,                           \
            119304647 /* widen_max 10 degrees */, 2 /* widen_steps */, 0 /* reject_overlap */,     \
            30l << 16 /* range 30 m */, 60l << 16 /* range_max 60 m */, 2 /* range_steps */,       \
            32768 /* dist_tol 0.5 m */, 19661 /* dist_rel 0.3 */, 32768 /* jump_max 0.5 m */,      \
            83513454ul /* turn_max 7 degrees */, OPTICAL_BEARING_ERR(noise),                       \
            OPTICAL_BEARING_ERR_MOVING(noise, step), 3277 /* err_max 0.05 m */,                    \
            655 /* unc_pos_min 0.01 m */, (step) / 2u /* unc_head_min: half a step */,             \
            131 /* unc_per_m 0.002 */, 596523ul /* unc_head_per_m 0.05 degrees */,                 \
            328 /* unc_turn 0.005 */, 16384 /* quality_max 0.25 m per mrad: 3.1 cm per count */,   \
            3 /* motion_passes */                                                                  \
    }

/** The defaults: OPTICAL_CONFIG for an edge noise of 0.005 degrees and gyro steps of 0.25
 * degrees (the shipped scenarios' sensors). */
#define OPTICAL_CONFIG_DEFAULT OPTICAL_CONFIG(59652ul, 2982616ul)

/**
 * What the approximate pose of a fix is worth: bounds of its position and heading error (the
 * dead reckoning's uncertainty since the last accepted fix, optical_unc_grow()).
 */
typedef struct {
    fx_q16_t pos;       /**< position error bound, Q15.16 m (>= 0) */
    fx_angle_t heading; /**< heading error bound (binary angle, below a half turn) */
} optical_unc_t;

/** The result of one triangulation (optical_triangulate). */
typedef struct {
    optical_pose_t pose; /**< position and bearing of the vehicle */
    /**
     * Predicted RMS position error for independent bearing errors of 1 mrad RMS on each of
     * the three sightings, Q15.16 metres (the Cramer-Rao bound of the geometry, linearised);
     * saturates at UINT32_MAX. Multiply by 0.12566 for one count of a 50,000-count goniometer.
     */
    uint32_t quality;
} optical_tri_t;

/** The result of optical_fix(), with the quality of the fix (docs/optical.md, "O6"). */
typedef struct {
    optical_pose_t pose;                 /**< the vehicle at the reference instant */
    uint32_t quality;                    /**< geometry: as optical_tri_t.quality (Q16 m/mrad) */
    fx_q16_t err;                        /**< position error bound, m: the geometry's (quality
                                              times the bearing error bound, standing or moving,
                                              plus each pulse's centre bias) or, when that
                                              exceeds err_max and the fix was accepted, the
                                              dead reckoning's bound plus the distance to it */
    fx_angle_t err_heading;              /**< predicted heading error bound (the bearing error
                                              bound) */
    fx_q16_t gate;                       /**< the dead-reckoning gate the fix was held to: the
                                              position uncertainty plus err, m (0: not reached) */
    uint16_t resid;                      /**< largest |residual| of the other agreeing beacons,
                                              2^-16 turn (0: none) */
    int8_t ident[OPTICAL_MAX_SIGHTINGS]; /**< map index per sighting (input order), -1 none */
    uint8_t used[3];                     /**< map indices of the triplet, in ring order */
    uint8_t n_ident;                     /**< sightings identified (outliers dropped included) */
    uint8_t n_agree;                     /**< beacons that agree with the fix: the triplet and
                                              the others within their residual tolerance */
    uint8_t n_dropped;                   /**< identified sightings dropped as outliers (their
                                              ident is -1) */
    uint8_t widened;                     /**< window widenings used (0: within the bounds) */
    uint8_t status;                      /**< optical_status_t */
} optical_fix_t;

/** Fill @p cfg with the defaults (docs/optical.md). */
void optical_config_default(optical_config_t *cfg);

/**
 * Convert a captured revolution into sightings for optical_fix(): centre = start + (width + 1)
 * / 2 counts (an edge at angle a reads floor(a) counts after the index pulse, which the angle
 * clock's encoder aligns with a count) on a goniometer of @p counts_per_turn counts (exact to
 * one binary-angle LSB), sorted by angle. Returns the number of sightings
 * (0..OPTICAL_MAX_SIGHTINGS) or -1 when the revolution is implausible: its period is not @p
 * counts_per_turn (lost angle-clock pulses or a lost index pulse) or the timer lost a capture
 * (COV). Widths beyond 2^-16 turn units saturate.
 */
int8_t optical_rev_sightings(const optical_rev_t *rev, uint16_t counts_per_turn,
                             optical_sighting_t *out);

/**
 * optical_rev_sightings() that also tells where each sorted sighting came from: @p order[j]
 * is the capture (time) order of sorted sighting j, so that per-sighting data kept in time
 * order (the nav board's latches) can follow the sort. Same return value.
 */
int8_t optical_rev_order(const optical_rev_t *rev, uint16_t counts_per_turn,
                         optical_sighting_t *out, uint8_t *order);

/**
 * Triangulate from three beacons and their sighting angles (O8-O10).
 * @param b     the three beacons (any order), within OPTICAL_COORD_LIMIT, at most 2048 m apart
 * @param theta their sighting angles (CCW from the vehicle heading), same order
 * @param out   pose and quality; written on OPTICAL_OK and on OPTICAL_E_SINGULAR
 * @param quality_max refuse (OPTICAL_E_SINGULAR) when the quality exceeds it
 * Returns OPTICAL_OK, OPTICAL_E_DEGENERATE (coincident beacons or sightings), OPTICAL_E_SINGULAR
 * (quality beyond the limit, or the circles coincide), OPTICAL_E_INCONSISTENT (the solution
 * does not reproduce all three angles) or OPTICAL_E_ARG.
 * Accuracy: within 1 mm of the exact solution of the same inputs wherever quality <=
 * OPTICAL_QUALITY_LIMIT in a 50 m field (measured worst 0.2 mm, tests/unit/optical_test.cpp).
 * Not reentrant (static work memory).
 */
int8_t optical_triangulate(const optical_xy_t b[3], const fx_angle_t theta[3], uint32_t quality_max,
                           optical_tri_t *out);

/**
 * Select three of @p n identified beacons (O7): with their sighting angles @p angle sorted
 * ascending, repeatedly drop the beacon beside the smallest adjacent gap (around the circle),
 * on the side of the smaller neighbouring gap. Writes the positions (0..n-1) of the three
 * kept into @p keep, ascending. 3 <= n <= OPTICAL_MAX_SIGHTINGS.
 */
void optical_select(const fx_angle_t *angle, uint8_t n, uint8_t keep[3]);

/**
 * Compile a map of @p n beacons @p b with their reflectors @p refl (3..OPTICAL_MAX_BEACONS,
 * within OPTICAL_COORD_LIMIT) for optical_fix(): the origin is the centre of their bounding
 * box (whole metres), @p b8 receives the n compiled positions, @p dk the n compiled
 * reflectors (optical_map_t), and *map refers to b, b8 and dk (all must outlive it; refl need
 * not). Returns OPTICAL_OK, or (*map
 * untouched) OPTICAL_E_ARG when n is out of range, a coordinate lies beyond
 * OPTICAL_COORD_LIMIT, a reflector's d is not in (0, OPTICAL_REFL_MAX] (@p bad[0] = its index)
 * or the beacons do not fit within +-OPTICAL_MAP_REACH of one origin (a site larger than
 * 256 m); OPTICAL_E_DEGENERATE when two beacons coincide: their centres closer than the sum
 * of their radii (the posts would overlap), @p bad = the pair (lower index first). @p bad may
 * be NULL. optical_fix() refuses (OPTICAL_E_ARG) an approximate pose beyond the reach too.
 */
int8_t optical_map_compile(optical_map_t *map, const optical_xy_t *b, const optical_refl_t *refl,
                           uint8_t n, optical_xy8_t *b8, uint32_t *dk, uint8_t bad[2]);

/**
 * The dead-reckoning uncertainty @p u after a stretch of @p travel metres (Q16, >= 0; counted
 * up to 256 m, in 2^-8 m rounded up) with @p turn of heading change (the sum of its
 * magnitudes, binary angle; counted up to a half turn, in 2^-16 turn): heading += unc_turn *
 * turn + unc_head_per_m * travel, then position += unc_per_m * travel + heading (rad) *
 * travel (at most 2 travel); each capped at turn_max and jump_max, every step rounded up
 * (docs/optical.md "O6").
 */
void optical_unc_grow(const optical_config_t *cfg, optical_unc_t *u, fx_q16_t travel,
                      fx_angle_t turn);

/**
 * The dead-reckoning uncertainty right after the accepted fix @p fix (the nav board takes its
 * pose): its position error bound, at least unc_pos_min; its heading error bound plus
 * unc_head_min (the nav board reads its gyro to whole steps).
 */
void optical_unc_after_fix(const optical_config_t *cfg, const optical_fix_t *fix, optical_unc_t *u);

/**
 * One revolution's fix (O2-O11) and its acceptance (O6).
 * @param map     beacon map (3..OPTICAL_MAX_BEACONS beacons), compiled (optical_map_compile)
 * @param cfg     parameters (optical_config_default)
 * @param approx  approximate pose at the reference instant: the nav board's dead-reckoning
 *                pose there. The fix is the pose at that same instant.
 * @param unc     what approx is worth (optical_unc_grow), or NULL: the configuration's largest
 *                uncertainty (jump_max, turn_max). The identification's windows cover at most
 *                window_pos and window; the fix must lie within unc plus its own predicted
 *                error of approx (OPTICAL_E_JUMP, OPTICAL_E_TURN).
 * @param s       sightings sorted by angle (optical_rev_sightings), @p n of them (<= 15)
 * @param latched dead-reckoning pose latched at each sighting (same frame as @p approx), or
 *                NULL when the vehicle stood still during the revolution
 * @param out     the fix and its quality; out->status tells whether it may be used (OPTICAL_OK)
 * Returns out->status.
 */
int8_t optical_fix(const optical_map_t *map, const optical_config_t *cfg,
                   const optical_pose_t *approx, const optical_unc_t *unc,
                   const optical_sighting_t *s, uint8_t n, const optical_pose_t *latched,
                   optical_fix_t *out);

/** A short name of status @p st ("ok", "few", "jump", ...; "?" beyond the codes): for logs
 * and telemetry (docs/optical.md lists them). */
const char *optical_status_name(int st);

#ifdef __cplusplus
}
#endif

#endif
