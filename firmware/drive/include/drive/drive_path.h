/*
 * drive_path.h - path preparation (SPEC D9, B4; seed 000 ch. 5.1 step 1).
 *
 * Before a run the vehicle gets the path vectors with their speeds, the initial vector (its
 * start pose), the nominal radius it uses at the corners and the direction of travel. The
 * path is then refitted: between consecutive primary points the nominal leg is the solver's
 * double arc with the nominal radius as minimum (drive_leg_solve()), and secondary points are
 * laid on it, equally spaced and at most `spacing` apart (the seed's double-arc length, "of
 * the order of 1.0 m"). The vehicle issues its ready signal only if the path is acceptable:
 * every leg solvable with the nominal radius, every piece between secondary points solvable
 * with the vehicle's minimum radius and representable in the drive board's bytes, every
 * speed in range.
 *
 * Turns over 90 degrees (B4): the double-arc cases take a heading change of at most 90
 * degrees between two poses. A leg that turns more (up to the half turn, e.g. a U-turn at an
 * aisle end) is split into two double arcs through one inserted pose, the middle of the
 * widest corner (straight, arc, straight) that joins the two poses (leg.c gives the
 * geometry): at most one inserted pose per leg, none stored (it is recomputed with the leg).
 * Refused (DRIVE_ERR_TURN): a turn whose corner would need a radius below the nominal one,
 * i.e. a target that does not lie inside the turn, or one too close to it (a U-turn needs a
 * lateral offset of at least two nominal radii).
 *
 * Secondary points are not stored: drive_path_target() computes one from its leg's nominal
 * double arcs when the travel sequencer needs it, caching the leg's solution. When a leg is
 * split, the inserted pose is one of its secondary points.
 */
#ifndef DRIVE_DRIVE_PATH_H
#define DRIVE_DRIVE_PATH_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "drive/drive_cmd.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A primary path point: the prescribed pose and the speed toward it. */
typedef struct {
    drive_pose_t pose; /**< rear-axle point and heading (the vehicle's nose) */
    fx_q16_t speed;    /**< metres per second Q16, > 0 */
    uint8_t nsub;      /**< set by drive_path_prepare(): secondary points on the leg to here */
} drive_path_point_t;

/** How the path is driven. */
typedef struct {
    fx_q16_t nominal_radius; /**< corner radius of the nominal legs, >= the vehicle's minimum */
    fx_q16_t spacing;        /**< longest distance between secondary points, 0.05..8 m */
    bool reverse;            /**< the whole path tail first */
} drive_path_config_t;

/** Most double arcs of a nominal leg: one, or two through an inserted pose. */
#define DRIVE_LEG_PARTS 2

/** A nominal leg between two prescribed poses (drive_leg_solve()). */
typedef struct {
    uint8_t parts;                         /**< 1, or 2 when a turn over 90 degrees is split */
    drive_pose_t via;                      /**< parts == 2: the inserted pose, end of sol[0] */
    drive_solution_t sol[DRIVE_LEG_PARTS]; /**< the double arcs, driven in order            */
} drive_leg_t;

/** A prepared path (the points stay in the caller's storage). */
typedef struct {
    drive_path_point_t *pts;
    uint8_t n;
    drive_pose_t start;
    drive_path_config_t cfg;
    const drive_board_t *board;
    bool ready;             /**< the path is acceptable */
    uint8_t bad_leg;        /**< when not ready: the leg (0 = start to pts[0]) that failed */
    uint8_t bad_sub;        /**< ... and its piece (0: the leg itself) */
    drive_status_t bad_why; /**< ... and why */
    int16_t cache_leg;      /**< leg whose nominal solution is cached, -1 none */
    drive_leg_t cache;      /**< that leg */
} drive_path_t;

/** A position on a prepared path: secondary point `sub` (1..nsub) of leg `leg`. */
typedef struct {
    uint8_t leg;
    uint8_t sub;
} drive_path_cursor_t;

/**
 * The nominal leg from @p from to @p to with @p radius (metres Q16, drive.h's range of
 * minimum radii) as the smallest radius, driven tail first when @p reverse: for a heading
 * change of at most 90 degrees the solver's double arc (parts = 1); for more, up to the half
 * turn, two double arcs through an inserted pose (parts = 2; a half turn exactly turns toward
 * the side the target lies on). DRIVE_OK, or DRIVE_ERR_TURN when no corner of @p radius
 * fits, or the solver's status for a part (DRIVE_ERR_TOO_FAR also when the poses are over
 * 128 m apart on an axis in a split leg). Following the parts' segments from @p from lands
 * on @p to within twice the solver's error (tests/unit/drive_test.cpp). No state.
 */
drive_status_t drive_leg_solve(const drive_pose_t *from, const drive_pose_t *to, fx_q16_t radius,
                               bool reverse, drive_leg_t *leg);

/**
 * Prepare @p pts[0..n-1] (1 <= n <= 254) from @p start for driving with @p board: fills every
 * point's nsub and returns DRIVE_OK with path->ready set, or the reason (DRIVE_ERR_PARAM for
 * a bad configuration or speed, drive_leg_solve()'s or the command builder's status for the
 * leg in path->bad_leg, DRIVE_ERR_PATH when a leg needs more than 255 secondary points) with
 * path->ready false. Runs one or two solves per leg and one per secondary point.
 */
drive_status_t drive_path_prepare(drive_path_t *path, const drive_pose_t *start,
                                  drive_path_point_t *pts, uint8_t n,
                                  const drive_path_config_t *cfg, const drive_board_t *board);

/** The first target of a ready path: {0, 1}. */
drive_path_cursor_t drive_path_first(const drive_path_t *path);

/** True when @p cur is the path's last point. */
bool drive_path_is_last(const drive_path_t *path, drive_path_cursor_t cur);

/** The next cursor after @p cur (unchanged at the last point). */
drive_path_cursor_t drive_path_next(const drive_path_t *path, drive_path_cursor_t cur);

/**
 * The secondary point at @p cur: its pose on the leg's nominal double arcs (the primary point
 * itself for sub == nsub, the inserted pose at the end of a split leg's first part) and the
 * leg's speed. DRIVE_ERR_PARAM when @p cur is off the path.
 */
drive_status_t drive_path_target(drive_path_t *path, drive_path_cursor_t cur, drive_pose_t *pose,
                                 fx_q16_t *speed);

/** The nominal leg @p leg (start or pts[leg-1] to pts[leg]), cached in @p path. */
drive_status_t drive_path_leg(drive_path_t *path, uint8_t leg, const drive_leg_t **out);

#ifdef __cplusplus
}
#endif

#endif
