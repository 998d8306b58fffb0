/*
 * op_deadreckon.c - agvcalc op "deadreckon": the nav board's dl handler replayed with the
 * firmware's own fixed-point code (firmware/groundnav, docs/groundnav.md).
 *
 *   {"op":"deadreckon","start":{"x":..,"y":..,"heading_deg":..},"wheelbase_m":..,"dl_m":..,
 *    "gyro_step_deg":..,"runs":[[n_pulses,gyro_count],...]}
 *   -> {"ok":true,"x":..,"y":..,"heading_deg":..}
 *
 * For each run, n_pulses odometer pulses arrive while the gyro reading goes from the previous
 * run's gyro_count (0 before the first run: the start heading) to this run's gyro_count, in
 * steps of gyro_step_deg counted from the start heading. Interleaving, as a vehicle turning
 * steadily over the run produces it: its true heading goes linearly with the pulses from the
 * previous reading to the new one, and the gyro (whose reading is the nearest step) signals
 * step j of the run's |d| (j = 1 .. |d|) when the heading has turned by j - 1/2 steps, i.e.
 * just before pulse ceil((j - 1/2) |n| / |d|). A run without pulses turns in place (its steps
 * arrive at once). n_pulses < 0 drives backwards (|n_pulses| pulses). The answer is the pose
 * the nav board publishes after the last run: its heading is estimated inside the gyro's cell
 * (docs/groundnav.md), so a run that turns in place ends on the threshold of its last step.
 */

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "agvcalc.h"
#include "fx/fx_host.h"
#include "groundnav/gnav.h"

#define MAX_TOTAL_PULSES 200000000.0 /* about 4 s of host time */
#define MAX_GYRO_COUNT   10000000.0

/* A whole number at runs[i][k]. */
static int whole(json_t *v, const char *what, double lim, int64_t *out, char *err, size_t errlen)
{
    double d;
    if (ac_number_value(v, what, -lim, lim, &d, err, errlen))
        return -1;
    if (d != floor(d))
        return ac_fail(err, errlen, "%s: %g is not a whole number", what, d);
    *out = (int64_t)d;
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
    /* validate every run before driving */
    size_t nruns = json_array_size(runs);
    double total = 0;
    for (size_t i = 0; i < nruns; i++) {
        json_t *r = json_array_get(runs, i);
        if (!json_is_array(r) || json_array_size(r) != 2)
            return ac_fail(err, errlen, "runs[%zu]: expected [n_pulses, gyro_count]", i);
        char what[48];
        int64_t n, g;
        snprintf(what, sizeof what, "runs[%zu][0] (n_pulses)", i);
        if (whole(json_array_get(r, 0), what, MAX_TOTAL_PULSES, &n, err, errlen))
            return -1;
        snprintf(what, sizeof what, "runs[%zu][1] (gyro_count)", i);
        if (whole(json_array_get(r, 1), what, MAX_GYRO_COUNT, &g, err, errlen))
            return -1;
        total += fabs((double)n);
        if (total > MAX_TOTAL_PULSES)
            return ac_fail(err, errlen, "runs: more than %.0f pulses in all (at runs[%zu])",
                           MAX_TOTAL_PULSES, i);
    }

    gnav_config_t cfg = {
        .wheelbase = fx_q16_from_double(wheelbase),
        .dl_q40 = (uint32_t)llround(dl * 1099511627776.0),
        .gyro_step_q48 = (uint64_t)llround(step / 360.0 * 281474976710656.0),
        .stop_distance = 0,
    };
    gnav_pose_t p0 = {fx_q16_from_double(start.x), fx_q16_from_double(start.y),
                      fx_angle_from_deg(start.heading_deg)};
    static gnav_t g;
    int rc = gnav_init(&g, &cfg, &p0);
    if (rc == GNAV_ERR_STEERING)
        return ac_fail(err, errlen,
                       "wheelbase_m * gyro_step_deg / dl_m = %.2f pulses per step at 90 degrees "
                       "of steering; the nav board handles up to %u",
                       wheelbase * step * M_PI / 180.0 / dl, GNAV_TABLE_N - 1u);
    if (rc != GNAV_OK)
        return ac_fail(err, errlen, "configuration refused: %s", gnav_strerror(rc));

    int64_t reading = 0;
    for (size_t i = 0; i < nruns; i++) {
        json_t *r = json_array_get(runs, i);
        int64_t n = (int64_t)json_number_value(json_array_get(r, 0));
        int64_t target = (int64_t)json_number_value(json_array_get(r, 1));
        int64_t d = target - reading, ad = d < 0 ? -d : d, an = n < 0 ? -n : n;
        void (*edge)(void *) = d > 0 ? gnav_on_gyro_up : gnav_on_gyro_down;
        gnav_set_reverse(&g, n < 0);
        int64_t j = 1;
        if (an == 0) {
            for (; j <= ad; j++)
                edge(&g);
        }
        for (int64_t k = 1; k <= an; k++) {
            /* the steps due before pulse k: ceil((2j - 1) an / 2ad) <= k */
            while (j <= ad && ((2 * j - 1) * an + 2 * ad - 1) / (2 * ad) <= k) {
                edge(&g);
                j++;
            }
            gnav_on_delta_l(&g);
        }
        reading = target;
    }
    gnav_pose_t p;
    gnav_pose(&g, &p);
    ac_set_pose(resp, fx_q16_to_double(p.x), fx_q16_to_double(p.y), fx_angle_to_deg(p.heading));
    return 0;
}
