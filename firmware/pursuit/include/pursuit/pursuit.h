/*
 * pursuit.h - seed 002's goal-point pursuit (SPEC P2, its chapter 5 and Navigate_Path) with
 * its future work (SPEC P5), as pure logic: the main board feeds it the positions its serial
 * receiver accepted (firmware/posrx) and the passing of time, and applies what it answers
 * (steering and speed on the drive board's DACs). docs/pursuit.md.
 *
 * The path is a list of points P0 (the start) .. Pn-1, each segment from the previous goal
 * point to the current one. At every accepted position update:
 *  1. the heading is the direction from the previous accepted position to this one (the
 *     seed's single receiver), or the one the caller gives (two receivers, the nav board);
 *  2. xdist, the position projected on the current segment measured from its start, and the
 *     perpendicular distance to the segment's line (the seed's path error, its ERR file);
 *  3. on the last segment, xdist >= the segment's length ends the path (stop, wheel centred);
 *  4. while xdist >= threshold x length and the goal is not the last point, the next point
 *     becomes the goal (xdist measured anew on the new segment);
 *  5. the heading error dphi = direction to the goal - heading (wrapped to +-180 degrees);
 *     when |dphi| >= 1 degree (the seed's integer degrees) and no correction is being held,
 *     the wheel turns to K x dphi (limited to the vehicle's steering range) for the
 *     activation time, then returns straight ahead.
 * Updates that arrive while a correction is held are recorded and may switch the goal; the
 * next correction waits for the first update after the hold (the seed's program slept through
 * the hold and then read the positions that had queued up).
 *
 * Future work of the seed (its chapter 7), each optional:
 *  - error recovery: with no plausible position (accepted or too close) for slow_after_ms
 *    the speed falls linearly, to a stop at stop_after_ms; it resumes when updates return;
 *  - speed regulation: the drive board's speed per DAC count is learnt from the distance
 *    between accepted positions over their time (while the command stayed the same), and the
 *    command set so that the measured speed is the one asked for;
 *  - two receivers: the heading from the vector between them (pursuit_pair()), and their
 *    distance as a check: a pair further from the mounted separation than the tolerance is
 *    refused.
 * Units: metres Q16, binary angles (fx.h), milliseconds; no floating point, no heap.
 */
#ifndef PURSUIT_PURSUIT_H
#define PURSUIT_PURSUIT_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive_path.h"
#include "fx/fx.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Speed counts of the drive board's DAC at max_speed (seed 002: 128 + 127 = 255). */
#define PURSUIT_SPEED_COUNTS 127
/** The seed's "on course": a heading error under one degree (binary angle). */
#define PURSUIT_ON_COURSE    11930465ul

/** The parameters (seed 002's menu, chapter 5, and its future work). */
typedef struct {
    fx_q16_t speed;         /**< travel speed asked for, m/s Q16, 0 < speed <= max_speed */
    fx_q16_t max_speed;     /**< speed at DAC count 127 (seed's "Maximum AGV Speed"), m/s Q16 */
    fx_q16_t k;             /**< smoothing constant K, Q16, 0 < K <= 8 */
    uint16_t activation_ms; /**< steering activation time, 1..65535 ms */
    fx_q16_t threshold;     /**< threshold fraction of a segment, Q16, (0, 1] */
    fx_angle_t max_steer;   /**< the wheel's limit, binary angle, (0, quarter turn) */
    uint16_t slow_after_ms; /**< error recovery: slow down after this long without an update;
                                 0 = off */
    uint16_t stop_after_ms; /**< ... and stand still after this long (> slow_after_ms) */
    bool regulate;          /**< speed regulation from measured travel */
    fx_q16_t pair_sep;      /**< two receivers: their separation, m Q16 (0 = one receiver) */
    fx_angle_t pair_angle;  /**< direction receiver 2 -> receiver 1 in the vehicle frame */
    fx_q16_t pair_tol;      /**< refuse a pair whose distance is off by more, m Q16 */
} pursuit_config_t;

/** Actions (bits of pursuit_out_t.actions), to be applied in this order. */
#define PURSUIT_ACT_STEER 0x01u /**< set the wheel to out.steer (0: straight ahead)  */
#define PURSUIT_ACT_SPEED 0x02u /**< set the drive speed to out.speed counts         */
#define PURSUIT_ACT_DONE  0x04u /**< the path is finished (the vehicle stops)         */

/** What the caller applies. */
typedef struct {
    uint8_t actions;
    fx_angle_t steer; /**< PURSUIT_ACT_STEER: steering angle, signed, left positive */
    int8_t speed;     /**< PURSUIT_ACT_SPEED: DAC speed counts 0..127 (0: stop) */
} pursuit_out_t;

/** One accepted update, as the seed recorded it (its position and error files). */
typedef struct {
    fx_q16_t x, y;      /**< the position used, m Q16 */
    fx_angle_t heading; /**< the heading used */
    fx_q16_t err;       /**< perpendicular distance to the current segment's line, m Q16 */
    fx_q16_t xdist;     /**< along the segment from its start (before a goal switch), m Q16 */
    uint16_t segment;   /**< index of the goal point the error was measured towards (1..n-1) */
    uint16_t goal;      /**< index of the goal point after the update */
    fx_angle_t dphi;    /**< heading error towards the goal, signed */
} pursuit_record_t;

/** Counters. */
typedef struct {
    uint32_t updates;      /**< accepted positions used */
    uint64_t err_sum;      /**< sum of the records' err, m Q16 (the ERR file's average: /updates) */
    fx_q16_t err_max;      /**< largest err, m Q16 */
    uint16_t corrections;  /**< steering corrections applied */
    uint16_t goals;        /**< goal switches */
    uint16_t slowdowns;    /**< error recovery: times the speed began to fall */
    uint16_t stops;        /**< ... times the vehicle was stopped for want of updates */
    uint16_t resumes;      /**< ... times it went on at full speed again */
    uint16_t regulations;  /**< speed regulation steps */
    uint16_t pair_rejects; /**< receiver pairs refused by their distance */
} pursuit_stats_t;

/** The pursuit. */
typedef struct {
    pursuit_config_t cfg;
    fx_q16_t x0, y0;                /* the start: point 0 */
    const drive_path_point_t *path; /* points 1..n-1 */
    uint16_t n;                     /* points in all, >= 2 */
    uint16_t goal;                  /* current goal point, 1..n-1 */
    fx_q16_t lx, ly, len;           /* current segment: its start and length */
    fx_q30_t ux, uy;                /* ... its direction */
    fx_q16_t px, py;                /* the previous accepted position */
    fx_angle_t heading;             /* the last heading */
    bool started, done, holding;
    uint32_t hold_end;     /* ms */
    uint32_t last_update;  /* ms: the last plausible position */
    fx_q16_t factor;       /* error recovery: speed fraction now, Q16 */
    fx_q16_t cal;          /* regulation: true speed / nominal, Q16 */
    int8_t counts;         /* the speed command on the drive board */
    uint32_t counts_since; /* ms: when it last changed */
    uint32_t last_pos_ms;  /* ms: the previous accepted position */
    pursuit_stats_t st;
} pursuit_t;

/**
 * Check @p cfg; false when a value is outside the ranges of pursuit_config_t (the caller
 * refuses the mission then).
 */
bool pursuit_config_ok(const pursuit_config_t *cfg);

/**
 * Set @p p up for the path from (x0, y0) (metres Q16, point 0) through the @p n_path points
 * of @p path (their pose.x, pose.y; kept by reference), with @p cfg (copied). Returns false
 * (and leaves @p p unusable) for a bad configuration, no path point, or a segment shorter
 * than 2^-8 m.
 */
bool pursuit_init(pursuit_t *p, const pursuit_config_t *cfg, fx_q16_t x0, fx_q16_t y0,
                  const drive_path_point_t *path, uint16_t n_path);

/**
 * Start at @p now_ms with the vehicle at point 0 heading @p heading: the first speed command
 * (out: PURSUIT_ACT_SPEED, PURSUIT_ACT_STEER straight ahead).
 */
void pursuit_start(pursuit_t *p, fx_angle_t heading, uint32_t now_ms, pursuit_out_t *out);

/**
 * An accepted position (x, y) (metres Q16) that arrived at @p t_ms. @p heading: the heading
 * to use (two receivers, the nav board), or NULL for the direction from the previous accepted
 * position. Fills @p rec (the update's record) and @p out.
 */
void pursuit_position(pursuit_t *p, fx_q16_t x, fx_q16_t y, const fx_angle_t *heading,
                      uint32_t t_ms, pursuit_record_t *rec, pursuit_out_t *out);

/** A plausible position (accepted or too close to the last) arrived at @p t_ms. */
void pursuit_alive(pursuit_t *p, uint32_t t_ms);

/** Time passes (call at least every few milliseconds): ends a held correction, slows down
 * or stops for want of updates, resumes when they are back. Fills @p out. */
void pursuit_tick(pursuit_t *p, uint32_t now_ms, pursuit_out_t *out);

/**
 * When pursuit_tick() next has something to do if no position comes first (ms; the slowing
 * down acts every millisecond): true with that millisecond in @p at_ms (at or before
 * @p now_ms: at once), false when nothing falls due (not started, done, or stopped for want
 * of updates: only a position changes that). Calls of pursuit_tick() after @p now_ms and
 * before @p at_ms do nothing. For a main loop that sleeps until its deadlines.
 */
bool pursuit_next_tick(const pursuit_t *p, uint32_t now_ms, uint32_t *at_ms);

/**
 * Two receivers: the heading from receiver 2's position (x2, y2) to receiver 1's (x1, y1)
 * into @p heading, and true, when their distance is within cfg.pair_tol of cfg.pair_sep;
 * false (a refused pair, counted) otherwise.
 */
bool pursuit_pair(pursuit_t *p, fx_q16_t x1, fx_q16_t y1, fx_q16_t x2, fx_q16_t y2,
                  fx_angle_t *heading);

/** True once the last point is reached. */
bool pursuit_done(const pursuit_t *p);

#ifdef __cplusplus
}
#endif

#endif
