/*
 * drive_cmd.h - from a solution to the drive board's bytes (SPEC D4, D5, D7).
 *
 * The drive board steers the front wheel and counts its travel: per arc it takes a steering
 * byte and a front-wheel length byte (seed 000, DRIVE and OUTPUT_TO_PORTS):
 *  - steering alpha = atan(L / r) = atan(L * curvature), left positive (CONTRACT.md); the
 *    byte is 128 - round(alpha * 256 / pi): 128 straight ahead, 1 count = 0.703 degrees,
 *    left below 128 (the seed computes 128 + 81.49 atan(30 / R) with its left radii negative),
 *    usable range 1..255 (|alpha| < 89.6 degrees);
 *  - front-wheel length l = s sqrt(1 + (L / r)^2) (the front wheel runs on the circle of
 *    radius sqrt(r^2 + L^2) while the rear axle covers s on radius r), in drive-board counts:
 *    the seed's 4.4 counts per inch (1 count = 5.77 mm), 8 bits: at most 255 counts = 1.47 m
 *    of front-wheel travel per arc, which is why the seed's double arcs are "of the order of
 *    1.0 m" and why path preparation spaces the points accordingly;
 *  - speed in counts of a configurable unit (seed 002: 1.755 cm/s per count), a signed byte:
 *    negative for reverse travel (the seed's listing does not show how backward travel reached
 *    the drive board; docs/drive.md).
 * D7: the drive board raises its delta-S pulse when an arc is almost done; an arc shorter
 * than min_pulse_counts cannot raise a clean one. A short second arc is still driven but only
 * one pulse is expected (the seed's fix); a short first arc is dropped (sent as 0 counts,
 * which the board skips without a pulse) and its few millimetres are left to the next
 * correction.
 */
#ifndef DRIVE_DRIVE_CMD_H
#define DRIVE_DRIVE_CMD_H

#include <stdbool.h>
#include <stdint.h>

#include "drive/drive.h"
#include "fx/fx.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The vehicle and its drive board. */
typedef struct {
    fx_q16_t wheelbase;       /**< L, rear axle to front wheel, metres Q16, 0.05..4 m */
    fx_q16_t min_radius;      /**< smallest turn radius, metres Q16 (drive.h's range) */
    fx_q16_t counts_per_m;    /**< drive-board length counts per metre of front wheel, Q16 */
    fx_q16_t speed_lsb;       /**< metres per second per speed count, Q16 (> 0) */
    uint8_t min_pulse_counts; /**< shortest arc that raises a clean delta-S pulse, counts */
    uint8_t dac_center;       /**< seed 002's steering DAC value for straight ahead */
} drive_board_t;

/** The seed's drive board (4.4 counts per inch, speed unit 1.755 cm/s (seed 002), clean
 * pulses from 3 counts (17 mm), DAC centre 132 (seed 002)) on a vehicle of wheelbase @p l and
 * minimum radius @p r (metres, Q16): a constant initializer of drive_board_t. */
#define DRIVE_BOARD_SEED_WITH(l, r)                                                                \
    {                                                                                              \
        (l), (r), 11352693l /* 173.2283 /m */, 1150l /* 0.01755 m/s */, 3u, 132u                   \
    }

/** The seed's vehicle: L = 30 in, minimum radius 10 in, on the seed's drive board. */
#define DRIVE_BOARD_SEED DRIVE_BOARD_SEED_WITH(49938l /* 0.762 m */, 16646l /* 0.254 m */)

/** Steering byte of a straight segment. */
#define DRIVE_STEER_STRAIGHT 128u

/** One double arc for the drive board. */
typedef struct {
    uint8_t steer[2];    /**< steering bytes, 128 - round(alpha * 256 / pi)             */
    uint8_t arc[2];      /**< front-wheel lengths, counts (0: arc skipped, no pulse)     */
    int8_t speed;        /**< speed counts, negative = reverse, 0 = stop                 */
    uint8_t pulses;      /**< delta-S pulses the sequencer waits for: 0, 1 or 2         */
    fx_angle_t alpha[2]; /**< the steering angles (signed binary angles, left positive)  */
} drive_cmd_t;

/**
 * Steering angle alpha = atan(L * curvature) of a segment (binary angle, signed, left
 * positive; 0 for a straight). @p curvature Q4.28 /m, @p wheelbase metres Q16.
 * Error as fx_atan_ratio (1.3e-6 rad).
 */
fx_angle_t drive_steer_angle(int32_t curvature, fx_q16_t wheelbase);

/**
 * 8255 steering byte of @p alpha: 128 - round(alpha / (pi / 256)). DRIVE_ERR_RANGE (and
 * *out untouched) when |alpha| >= 89.6 degrees (the byte would leave 1..255).
 */
drive_status_t drive_steer_byte(fx_angle_t alpha, uint8_t *out);

/**
 * Seed 002's steering DAC value of @p alpha: center - round(alpha / (pi/2) * (255 - center)),
 * clamped to 0..255 (alpha left positive gives values below the centre, as in the seed).
 */
uint8_t drive_dac_angle_byte(fx_angle_t alpha, uint8_t center);

/** Seed 002's speed DAC value of @p speed counts: 128 + speed (128 = stop). */
uint8_t drive_dac_speed_byte(int8_t speed);

/**
 * Speed counts of @p speed_mps (metres per second Q16, >= 0) for the board: round(v / lsb),
 * negated when @p reverse. DRIVE_ERR_RANGE when it exceeds 127 counts.
 */
drive_status_t drive_speed_counts(fx_q16_t speed_mps, bool reverse, const drive_board_t *board,
                                  int8_t *out);

/**
 * The command for solution @p sol at @p speed_mps (D4, D5, D7). DRIVE_ERR_RANGE when a
 * steering angle, a front-wheel length (over 255 counts) or the speed does not fit its
 * byte; DRIVE_ERR_PARAM for a NULL pointer or a wheelbase outside 0.05..4 m.
 */
drive_status_t drive_cmd_build(const drive_solution_t *sol, const drive_board_t *board,
                               fx_q16_t speed_mps, bool reverse, drive_cmd_t *cmd);

#ifdef __cplusplus
}
#endif

#endif
