/*
 * op_deadreckon.c - agvcalc op "deadreckon": the nav board's dl handler replayed with the
 * firmware's own fixed-point code (firmware/groundnav, docs/groundnav.md).
 *
 *   {"op":"deadreckon","start":{"x":..,"y":..,"heading_deg":..},"wheelbase_m":..,"dl_m":..,
 *    "gyro_step_deg":..,"runs":[[n_pulses,gyro_count],...]}
 *   -> {"ok":true,"x":..,"y":..,"heading_deg":..}
 *
 * Replay (CONTRACT.md): for each run, the gyro's reading first steps from the previous run's
 * gyro_count (0 before the first run) to this run's, one edge per step, all before the run's
 * first pulse; then |n_pulses| odometer pulses arrive (backwards when n_pulses < 0). The gyro
 * reads the nearest whole step, so the start heading is the centre of step 0's cell: a vehicle
 * turning steadily by one step every p pulses from the start crosses the first threshold after
 * p/2 pulses: [[p/2, 0], [p, 1], [p, 2], ...].
 * The answer is the pose the nav board publishes after the last run (its heading is estimated
 * inside the gyro's cell, docs/groundnav.md).
 *
 * Work per line is bounded: at most DR_MAX_PULSES pulses and DR_MAX_STEPS gyro steps in all.
 * The answer must be one the nav board can hand out: its pose is Q15.16 metres (saturating at
 * +-32768 m) read from pulses Q4 (wrapping at +-2^27 pulses, i.e. +-dl_m * 2^27); a start or a
 * result beyond either is refused, never saturated or wrapped.
 */

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "agvcalc.h"
#include "fx/fx_host.h"
#include "groundnav/gnav.h"

/* Work per line: 2^24 pulses (4.26 km of 0.01 in pulses) and 2^22 gyro steps (2,913 turns of
 * 0.25 degrees): well under a second of host time together (docs/agvcalc.md). */
#define DR_MAX_PULSES (1l << 24)
#define DR_MAX_STEPS  (1l << 22)

/* The nav board's pose range: the largest Q15.16 reading, and pulses Q4 (2^27 - 1 pulses with
 * a pulse to spare for the rounding). */
#define DR_METRE_RANGE (2147483647.0 / 65536.0)
#define DR_PULSE_RANGE 134217727.0
#define DR_PULSE_WRAP  268435456.0 /* 2^28 pulses: the period of the Q4 reading */

/* --help: the fields and their units. */
const char agvcalc_fields_deadreckon[] =
    "    start         {x, y, heading_deg}: rear-axle pose, m (within +-30000 and within\n"
    "                  +-dl_m * 2^27) and degrees\n"
    "    wheelbase_m   rear axle to the steered, driven front wheel, m (0, 32]\n"
    "    dl_m          front-wheel travel per odometer pulse, m [3.06e-5, 1.95e-3]\n"
    "    gyro_step_deg heading per gyro step, degrees (0, 10]\n"
    "    runs          [[n_pulses, gyro_count], ...]: per run, the gyro steps to gyro_count\n"
    "                  (steps from the start heading), then n_pulses pulses (< 0: backwards);\n"
    "                  whole numbers, at most 16777216 pulses and 4194304 steps in all\n"
    "    -> x, y: m; heading_deg: [0, 360), the published heading inside the gyro's cell;\n"
    "       ok:false when the pose leaves the nav board's range (+-32768 m, +-dl_m * 2^27)\n";

/* A whole number at runs[i][k] within [-lim, lim]. */
static int whole(json_t *v, const char *what, int64_t lim, int64_t *out, char *err, size_t errlen)
{
    double d;
    if (ac_number_value(v, what, -INFINITY, INFINITY, &d, err, errlen))
        return -1;
    if (d != floor(d))
        return ac_fail(err, errlen, "%s: %.15g is not a whole number", what, d);
    if (fabs(d) > (double)lim)
        return ac_fail(err, errlen, "%s: %.15g is beyond the %lld allowed per line", what, d,
                       (long long)lim);
    *out = (int64_t)d;
    return 0;
}

/* Every run read and checked against the work bounds before any is driven. */
static int read_runs(json_t *runs, int64_t *pulses, char *err, size_t errlen)
{
    int64_t total = 0, steps = 0, reading = 0;
    for (size_t i = 0; i < json_array_size(runs); i++) {
        json_t *r = json_array_get(runs, i);
        if (!json_is_array(r) || json_array_size(r) != 2)
            return ac_fail(err, errlen, "runs[%zu]: expected [n_pulses, gyro_count]", i);
        char what[48];
        int64_t n, g;
        snprintf(what, sizeof what, "runs[%zu][0] (n_pulses)", i);
        if (whole(json_array_get(r, 0), what, DR_MAX_PULSES, &n, err, errlen))
            return -1;
        total += n < 0 ? -n : n;
        if (total > DR_MAX_PULSES)
            return ac_fail(err, errlen,
                           "%s: %lld brings the pulses of this line to %lld, more than the "
                           "%ld allowed",
                           what, (long long)n, (long long)total, DR_MAX_PULSES);
        snprintf(what, sizeof what, "runs[%zu][1] (gyro_count)", i);
        if (whole(json_array_get(r, 1), what, DR_MAX_STEPS, &g, err, errlen))
            return -1;
        steps += g > reading ? g - reading : reading - g;
        reading = g;
        if (steps > DR_MAX_STEPS)
            return ac_fail(err, errlen,
                           "%s: %lld brings the gyro steps of this line to %lld, more than the "
                           "%ld allowed",
                           what, (long long)g, (long long)steps, DR_MAX_STEPS);
    }
    *pulses = total;
    return 0;
}

/* The position @p v (m) read after the replay, unwrapped with the start @p v0 and the
 * farthest the vehicle can have gone (@p reach, m), checked against the range. */
static int check_range(const char *name, double v, double v0, double reach, double dl, double range,
                       char *err, size_t errlen)
{
    if (v - v0 > reach)
        v -= DR_PULSE_WRAP * dl; /* went past -2^27 pulses */
    else if (v0 - v > reach)
        v += DR_PULSE_WRAP * dl;
    if (fabs(v) >= DR_METRE_RANGE)
        return ac_fail(err, errlen,
                       "the result leaves the nav board's range: %s reaches %s32768 m "
                       "(Q15.16 metres)",
                       name, v < 0 ? "-" : "+");
    if (fabs(v) > range)
        return ac_fail(err, errlen,
                       "the result leaves the nav board's range: %s = %.3f m is beyond "
                       "+-%.3f m (dl_m * 2^27: the pulse count it keeps)",
                       name, v, range);
    return 0;
}

int agvcalc_op_deadreckon(json_t *req, json_t *resp, char *err, size_t errlen);

int agvcalc_op_deadreckon(json_t *req, json_t *resp, char *err, size_t errlen)
{
    ac_pose_t start;
    double wheelbase, dl, step;
    if (ac_pose(req, "start", 30000.0, true, &start, err, errlen) ||
        ac_number(req, "wheelbase_m", 1e-6, 32.0, true, 0, &wheelbase, err, errlen) ||
        ac_number(req, "dl_m", 3.06e-5, 1.95e-3, true, 0, &dl, err, errlen) ||
        ac_number(req, "gyro_step_deg", 1e-6, 10.0, true, 0, &step, err, errlen))
        return -1;
    json_t *runs = json_object_get(req, "runs");
    if (!runs)
        return ac_fail(err, errlen, "missing \"runs\"");
    if (!json_is_array(runs))
        return ac_fail(err, errlen, "runs: expected an array of [n_pulses, gyro_count]");
    int64_t total;
    if (read_runs(runs, &total, err, errlen))
        return -1;

    gnav_config_t cfg = {
        .wheelbase = fx_q16_from_double(wheelbase),
        .dl_q40 = (uint32_t)llround(dl * 1099511627776.0),
        .gyro_step_q48 = (uint64_t)llround(step / 360.0 * 281474976710656.0),
        .stop_distance = 0,
    };
    double dl_fw = cfg.dl_q40 / 1099511627776.0; /* the pulse the firmware counts with */
    double range = fmin(DR_METRE_RANGE, DR_PULSE_RANGE * dl_fw);
    if (fabs(start.x) > range || fabs(start.y) > range)
        return ac_fail(err, errlen,
                       "start.%s: %g m is beyond the nav board's range for dl_m %g: +-%.3f m "
                       "(dl_m * 2^27: the pulse count it keeps)",
                       fabs(start.x) > range ? "x" : "y", fabs(start.x) > range ? start.x : start.y,
                       dl, range);
    gnav_pose_t p0 = {fx_q16_from_double(start.x), fx_q16_from_double(start.y),
                      fx_angle_from_deg(start.heading_deg)};
    gnav_t g;
    int rc = gnav_init(&g, &cfg, &p0);
    if (rc == GNAV_ERR_STEERING)
        return ac_fail(err, errlen,
                       "wheelbase_m * gyro_step_deg / dl_m = %.2f pulses per step at 90 degrees "
                       "of steering; the nav board handles up to %u",
                       wheelbase * step * M_PI / 180.0 / dl, GNAV_TABLE_N - 1u);
    if (rc != GNAV_OK)
        return ac_fail(err, errlen, "configuration refused: %s", gnav_strerror(rc));

    int64_t reading = 0;
    for (size_t i = 0; i < json_array_size(runs); i++) {
        json_t *r = json_array_get(runs, i);
        int64_t n = (int64_t)json_number_value(json_array_get(r, 0));
        int64_t target = (int64_t)json_number_value(json_array_get(r, 1));
        gnav_set_reverse(&g, n < 0);
        for (; reading < target; reading++)
            gnav_on_gyro_up(&g);
        for (; reading > target; reading--)
            gnav_on_gyro_down(&g);
        for (int64_t k = n < 0 ? -n : n; k > 0; k--)
            gnav_on_delta_l(&g);
    }
    gnav_pose_t p;
    gnav_pose(&g, &p);
    /* the farthest the rear axle can be from the start: a pulse's front-wheel travel each */
    double reach = (double)total * dl_fw * (1.0 + 1e-6) + 1e-3;
    double x = fx_q16_to_double(p.x), y = fx_q16_to_double(p.y);
    if (check_range("x", x, fx_q16_to_double(p0.x), reach, dl_fw, range, err, errlen) ||
        check_range("y", y, fx_q16_to_double(p0.y), reach, dl_fw, range, err, errlen))
        return -1;
    ac_set_pose(resp, x, y, fx_angle_to_deg(p.heading));
    return 0;
}
