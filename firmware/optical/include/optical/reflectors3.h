/*
 * optical/reflectors3.h - the three-reflector timing mode (SPEC O12, seed 004).
 *
 * One laser turns counter-clockwise at a roughly constant speed; a switch "clicks" when it
 * points straight ahead. A timer stamps the click, the reflections from three reflectors and
 * the next click. The sighting angles are the times since the click scaled by the measured
 * revolution time. A revolution is used only with exactly three reflections between the two
 * clicks and a revolution time within the tolerance of the expected one.
 *
 * Which reflector gave which reflection is not known. The seed reads it from the sector
 * pattern (long / medium / short time between reflections) of its one field; here every
 * assignment is tried: the three-circle fix of an assignment must reproduce all three angles
 * (a wrong one lands on the other arc of some circle) and lie inside the field. When more than
 * one assignment survives, an approximate position picks the nearest; without one the
 * revolution is reported as ambiguous with its candidates, never guessed. The heading comes
 * from the first reflection after the click, as in the seed.
 */
#ifndef OPTICAL_REFLECTORS3_H
#define OPTICAL_REFLECTORS3_H

#include <stdbool.h>
#include <stdint.h>

#include "optical/optical.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most vertices of the field polygon. */
#define OPTICAL_R3_MAX_FIELD 16
/** Most candidate positions (one per assignment). */
#define OPTICAL_R3_MAX_CAND  6

/** Result codes (optical_r3_fix also returns OPTICAL_E_SINGULAR: the only fits lie too close
 * to the reflectors' circle). */
typedef enum {
    OPTICAL_R3_OK = 0,
    OPTICAL_R3_E_ARG = 1,       /**< bad arguments (coordinates, field polygon) */
    OPTICAL_R3_E_COUNT = 20,    /**< not exactly three reflections between the clicks */
    OPTICAL_R3_E_PERIOD = 21,   /**< revolution time implausible */
    OPTICAL_R3_E_ORDER = 22,    /**< event times not increasing within the revolution */
    OPTICAL_R3_E_NONE = 23,     /**< no assignment gives a position inside the field */
    OPTICAL_R3_E_AMBIGUOUS = 24 /**< several do and no approximate position was given */
} optical_r3_status_t;

/** Parameters. */
typedef struct {
    const optical_xy_t *field; /**< polygon bounding the vehicle (NULL: no bound) */
    uint8_t n_field;           /**< its vertices, 3..OPTICAL_R3_MAX_FIELD */
    uint32_t period;           /**< expected revolution time, timer ticks */
    uint32_t period_tol;       /**< accepted |measured - expected|, ticks */
    uint32_t quality_max;      /**< refuse fixes whose quality exceeds it (optical_tri_t) */
} optical_r3_config_t;

/** Result. */
typedef struct {
    optical_pose_t pose; /**< position and heading (from the first reflection) */
    uint32_t quality;    /**< as optical_tri_t.quality */
    uint8_t first;       /**< reflector (0..2) that gave the first reflection */
    uint8_t n_cand;      /**< assignments that fit (all of them on OPTICAL_R3_E_AMBIGUOUS) */
    optical_xy_t cand[OPTICAL_R3_MAX_CAND];  /**< their positions */
    uint8_t cand_first[OPTICAL_R3_MAX_CAND]; /**< and the reflector seen first in each */
    uint8_t status;                          /**< optical_r3_status_t */
} optical_r3_t;

/**
 * Fix from one revolution.
 * @param refl   the three reflectors (Q15.16 m, within OPTICAL_COORD_LIMIT)
 * @param click  timer ticks at the click that starts the revolution
 * @param t      ticks of the reflections, @p n of them (the revolution is used only if n == 3)
 * @param click_next ticks at the next click
 * @param cfg    field, expected period and tolerance
 * @param approx approximate position to resolve ambiguous assignments, or NULL
 * Tick differences are taken modulo 2^32 (the timer may wrap once per revolution).
 * Returns out->status.
 */
int8_t optical_r3_fix(const optical_xy_t refl[3], uint32_t click, const uint32_t *t, uint8_t n,
                      uint32_t click_next, const optical_r3_config_t *cfg,
                      const optical_xy_t *approx, optical_r3_t *out);

/**
 * Distance (Q15.16 m) and turn (signed binary angle, CCW positive, in [-half, half) turn) from
 * @p pose to face @p goal; the turn is 0 when the goal coincides with the position.
 */
void optical_r3_goal(const optical_pose_t *pose, const optical_xy_t *goal, uint32_t *dist,
                     fx_angle_t *turn);

/** True when @p p lies inside the polygon @p v of @p n vertices (even-odd rule). */
bool optical_r3_inside(const optical_xy_t *v, uint8_t n, const optical_xy_t *p);

#ifdef __cplusplus
}
#endif

#endif
