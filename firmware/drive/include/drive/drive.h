/*
 * drive.h - the double-arc solver of the drive routine (SPEC D2, D3, D5; seed 000 ch. 4).
 *
 * From a pose (rear-axle point, heading) to a target pose, the vehicle drives two segments:
 * two circular arcs of equal radius and opposite turn (seed cases 1, 2, 3), an arc and a
 * straight (case 4), a straight and an arc (case 5), or two straight halves (straight case).
 * The seed's parameters T = (A x D)z, P = A . D, C = (A x B)z, S = A . B select the case; the
 * arc-and-straight cases are preferred when their radius is at least the minimum, otherwise
 * the double arc is used (the seed's fallbacks); a double arc below the minimum radius is
 * refused. docs/drive.md rebuilds every case, proves the formulas and maps them to the seed.
 *
 * Conventions (CONTRACT.md): x east, y north, headings counter-clockwise; curvature and
 * steering are signed in the vehicle frame, left positive; lengths are rear-axle path
 * lengths. Reverse travel (D5): the vehicle moves tail first; headings stay the vehicle's
 * heading (its nose, the gyro's bearing); the solver negates both direction vectors, solves,
 * and mirrors the turns, so a segment's curvature is still the steering's.
 *
 * Domain (anything else is refused with a reason, never answered with a path that misses):
 * target ahead in the direction of travel (P > 0), heading change |B - A| <= 90 degrees,
 * distance between DRIVE_MIN_DIST and DRIVE_MAX_DIST, minimum radius between
 * DRIVE_MIN_RADIUS_MIN and DRIVE_MIN_RADIUS_MAX, every radius >= the minimum radius.
 */
#ifndef DRIVE_DRIVE_H
#define DRIVE_DRIVE_H

#include <stdbool.h>
#include <stdint.h>

#include "fx/fx.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Curvature format: Q4.28, 1/m (|curvature| < 8 /m, 1 LSB = 3.7e-9 /m). */
#define DRIVE_CURV_SHIFT 28
#define DRIVE_CURV_ONE   (1l << DRIVE_CURV_SHIFT)

/** Shortest distance between the two poses: 2^-8 m (3.9 mm), Q16. */
#define DRIVE_MIN_DIST       (FX_Q16_ONE >> 8)
/** Longest distance between the two poses: 64 m, Q16. */
#define DRIVE_MAX_DIST       (64l * FX_Q16_ONE)
/** Smallest minimum radius accepted: 0.125 m (curvature below 8 /m), Q16. */
#define DRIVE_MIN_RADIUS_MIN (FX_Q16_ONE / 8)
/** Largest minimum radius accepted: 100 m, Q16. */
#define DRIVE_MIN_RADIUS_MAX (100l * FX_Q16_ONE)

/** A pose: rear-axle point (metres, Q16) and heading (the vehicle's nose, binary angle). */
typedef struct {
    fx_q16_t x;
    fx_q16_t y;
    fx_angle_t heading;
} drive_pose_t;

/** One segment: an arc (curvature != 0) or a straight (curvature == 0). */
typedef struct {
    int32_t curvature; /**< 1/radius, Q4.28 /m, vehicle frame, left positive */
    fx_q16_t length;   /**< rear-axle path length, metres Q16, >= 0 */
    fx_angle_t sweep;  /**< heading change along it, signed binary angle (read as int32_t) */
} drive_segment_t;

/** The seed's case numbers (docs/drive.md). */
typedef enum {
    DRIVE_CASE_STRAIGHT = 0, /**< two straight halves                                      */
    DRIVE_CASE_1 = 1,        /**< double arc, first toward the target side, heading same side */
    DRIVE_CASE_2 = 2,        /**< double arc, first away (heading changes more than 2 beta)   */
    DRIVE_CASE_3 = 3,        /**< double arc, target and heading change on opposite sides     */
    DRIVE_CASE_4 = 4,        /**< arc, then straight                                          */
    DRIVE_CASE_5 = 5         /**< straight, then arc                                          */
} drive_case_t;

/** A solution: the case and its two segments, driven in order. */
typedef struct {
    drive_case_t kase;
    drive_segment_t seg[2];
} drive_solution_t;

/** Result of drive_solve() (and the other drive functions). */
typedef enum {
    DRIVE_OK = 0,
    DRIVE_ERR_PARAM,     /**< minimum radius out of range, or a NULL pointer              */
    DRIVE_ERR_TOO_CLOSE, /**< poses closer than DRIVE_MIN_DIST                            */
    DRIVE_ERR_TOO_FAR,   /**< poses farther apart than DRIVE_MAX_DIST                     */
    DRIVE_ERR_BEHIND,    /**< target not ahead in the direction of travel (P <= 0)        */
    DRIVE_ERR_HEADING,   /**< heading change over 90 degrees (S < 0)                      */
    DRIVE_ERR_RADIUS,    /**< every path of the cases needs a radius below the minimum    */
    DRIVE_ERR_SWEEP,     /**< the double arc would turn a full circle or more             */
    DRIVE_ERR_RANGE,     /**< a drive-board byte cannot hold the value (drive_cmd.h)      */
    DRIVE_ERR_PATH,      /**< path preparation: see drive_path.h                         */
    DRIVE_ERR_TURN       /**< a turn over 90 degrees has no corner of the radius (drive_path.h) */
} drive_status_t;

/** Short English reason for a status ("ok" for DRIVE_OK). */
const char *drive_status_text(drive_status_t st);

/**
 * Solve the drive from @p from to @p to (SPEC D2-D3, D5).
 * @p min_radius: metres Q16 in [DRIVE_MIN_RADIUS_MIN, DRIVE_MIN_RADIUS_MAX].
 * @p reverse: the vehicle drives tail first (both poses keep the vehicle's heading).
 * On DRIVE_OK, @p out holds the case and the segments: following them from @p from ends at
 * @p to within 0.05 mm and 0.005 degrees in the domain (0.3 - 5 m; within 0.5 mm and
 * 0.01 degrees up to 64 m; tests/unit/drive_test.cpp checks both), every arc's radius is >= @p
 * min_radius (exactly: curvature * min_radius <= 1 in the fixed-point values returned).
 * Otherwise the status says why and @p out is unspecified; on DRIVE_ERR_RADIUS, @p needed (if
 * not NULL) receives the curvature the double arc would need (Q4.28; INT32_MAX when over 8 /m),
 * so that callers can report the radius. Reentrant; no state.
 * Cost on the MSP430: within 20,000 cycles (SPEC's floor), checked by the vector program;
 * measured in cycles.json as "doublearc" (and "doublearc_wide" for legs up to 64 m).
 */
drive_status_t drive_solve(const drive_pose_t *from, const drive_pose_t *to, fx_q16_t min_radius,
                           bool reverse, drive_solution_t *out, int32_t *needed);

/**
 * Advance @p pose by @p dist metres (Q16, >= 0) along a segment of curvature @p curvature
 * (Q4.28, vehicle frame), driving tail first when @p reverse; |dist * curvature| < 8 rad
 * (any arc of the solver). Error within 0.05 mm and 5e-6 rad over 5 m (tests/unit). Used to
 * sample the nominal path and to predict where a loaded arc leads.
 */
drive_pose_t drive_pose_advance(const drive_pose_t *pose, int32_t curvature, fx_q16_t dist,
                                bool reverse);

/** Radius of a curvature: metres Q16, signed; saturates at +-32767 m, 0 for a straight. */
fx_q16_t drive_radius_of(int32_t curvature);

#ifdef __cplusplus
}
#endif

#endif
