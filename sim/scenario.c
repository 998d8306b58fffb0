/*
 * scenario.c - scenario files: JSON (jansson), validated key by key (see scenario.h).
 */
#include "sim/scenario.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "jsonval.h"

#define DEG   (M_PI / 180.0)
#define FIELD 10000.0 /* |coordinate| limit, m */

/* An object member that must be an object (or may be absent when !required). */
static json_t *object_at(json_t *o, const char *key, const char *path, int required, char *err,
                         size_t errlen, int *fail)
{
    json_t *v = json_object_get(o, key);
    if (!v) {
        if (required) {
            ac_fail(err, errlen, "missing \"%s%s\"", path, key);
            *fail = 1;
        }
        return NULL;
    }
    if (!json_is_object(v)) {
        ac_fail(err, errlen, "%s%s: expected an object", path, key);
        *fail = 1;
        return NULL;
    }
    return v;
}

/* A number member, reported with its full path ("sensors.gyro.step_deg"). */
static int num(json_t *o, const char *path, const char *key, double lo, double hi, int required,
               double dflt, double *out, char *err, size_t errlen)
{
    char full[128];
    snprintf(full, sizeof full, "%s%s", path, key);
    json_t *v = json_object_get(o, key);
    if (!v) {
        if (required)
            return ac_fail(err, errlen, "missing \"%s\"", full);
        *out = dflt;
        return 0;
    }
    return ac_number_value(v, full, lo, hi, out, err, errlen);
}

/* Warn about members a reader does not know (a typo would otherwise be silently ignored). */
static void warn_unknown(json_t *o, const char *path, const char *const *known)
{
    const char *k;
    json_t *v;
    json_object_foreach(o, k, v)
    {
        int found = 0;
        for (const char *const *q = known; *q; q++)
            found |= strcmp(*q, k) == 0;
        if (!found)
            fprintf(stderr, "agv-sim: warning: unknown key \"%s%s\" ignored\n", path, k);
    }
}

static int parse_array(json_t *root, const char *key, size_t min_n, size_t max_n, int required,
                       json_t **out, char *err, size_t errlen)
{
    json_t *a = json_object_get(root, key);
    *out = NULL;
    if (!a) {
        if (required)
            return ac_fail(err, errlen, "missing \"%s\"", key);
        return 0;
    }
    if (!json_is_array(a))
        return ac_fail(err, errlen, "%s: expected an array", key);
    size_t n = json_array_size(a);
    if (n < min_n || n > max_n)
        return ac_fail(err, errlen, "%s: %zu entries, expected %zu to %zu", key, n, min_n, max_n);
    for (size_t i = 0; i < n; i++)
        if (!json_is_object(json_array_get(a, i)))
            return ac_fail(err, errlen, "%s[%zu]: expected an object", key, i);
    *out = a;
    return 0;
}

static int parse_root(json_t *root, sim_scenario_t *sc, char *err, size_t errlen)
{
    static const char *const known_root[] = {
        "name", "mode",    "beacons", "spurious",   "occluders", "vehicle",     "start",
        "path", "sensors", "seed",    "duration_s", "success",   "start_error", NULL};
    static const char *const known_xy[] = {"x", "y", "diameter_m", "width_deg", NULL};
    static const char *const known_pose[] = {"x", "y", "heading_deg", "speed_mps", NULL};
    static const char *const known_vehicle[] = {"wheelbase_m", "min_radius_m", "speed_mps",
                                                "steer_rate_deg_per_s", NULL};
    static const char *const known_sensors[] = {"goniometer", "odometer", "gyro", NULL};
    static const char *const known_gonio[] = {"rev_per_s", "counts", "noise_deg", "range_m", NULL};
    static const char *const known_odo[] = {"dl_m", "scale", NULL};
    static const char *const known_gyro[] = {"step_deg", "drift_deg_per_s", NULL};
    static const char *const known_success[] = {"cross_track_mean_m",
                                                "cross_track_max_m",
                                                "final_error_m",
                                                "fix_error_max_m",
                                                "fix_accept_ratio",
                                                "reach_goal",
                                                NULL};
    int fail = 0;
    memset(sc, 0, sizeof *sc);
    if (!json_is_object(root))
        return ac_fail(err, errlen, "a scenario must be a JSON object");
    warn_unknown(root, "", known_root);

    json_t *name = json_object_get(root, "name");
    if (!json_is_string(name))
        return ac_fail(err, errlen, name ? "name: expected a string" : "missing \"name\"");
    snprintf(sc->name, sizeof sc->name, "%s", json_string_value(name));
    json_t *mode = json_object_get(root, "mode");
    const char *m = json_string_value(mode);
    if (!m)
        return ac_fail(err, errlen,
                       mode ? "mode: expected \"full\" or \"simplified\"" : "missing \"mode\"");
    if (strcmp(m, "full") == 0)
        sc->full_travel = 1;
    else if (strcmp(m, "simplified") == 0)
        sc->full_travel = 0;
    else
        return ac_fail(err, errlen, "mode: \"%s\" is neither \"full\" nor \"simplified\"", m);

    json_t *arr;
    if (parse_array(root, "beacons", 3, SIM_MAX_BEACONS, 1, &arr, err, errlen))
        return -1;
    for (size_t i = 0; i < json_array_size(arr); i++) {
        json_t *b = json_array_get(arr, i);
        char path[48];
        snprintf(path, sizeof path, "beacons[%zu].", i);
        warn_unknown(b, path, known_xy);
        sim_beacon_t *bc = &sc->world.beacon[i];
        if (num(b, path, "x", -FIELD, FIELD, 1, 0, &bc->x, err, errlen) ||
            num(b, path, "y", -FIELD, FIELD, 1, 0, &bc->y, err, errlen) ||
            num(b, path, "diameter_m", 0.005, 2.0, 1, 0, &bc->diameter, err, errlen))
            return -1;
    }
    sc->world.n_beacons = json_array_size(arr);

    if (parse_array(root, "spurious", 0, SIM_MAX_SPURIOUS, 0, &arr, err, errlen))
        return -1;
    for (size_t i = 0; arr && i < json_array_size(arr); i++) {
        json_t *b = json_array_get(arr, i);
        char path[48];
        snprintf(path, sizeof path, "spurious[%zu].", i);
        warn_unknown(b, path, known_xy);
        sim_spurious_t *s = &sc->world.spurious[i];
        double wdeg;
        if (num(b, path, "x", -FIELD, FIELD, 1, 0, &s->x, err, errlen) ||
            num(b, path, "y", -FIELD, FIELD, 1, 0, &s->y, err, errlen) ||
            num(b, path, "width_deg", 0.001, 1.0, 0, 0.02, &wdeg, err, errlen))
            return -1;
        s->width = wdeg * DEG;
        sc->world.n_spurious = i + 1;
    }

    if (parse_array(root, "occluders", 0, SIM_MAX_OCCLUDERS, 0, &arr, err, errlen))
        return -1;
    for (size_t i = 0; arr && i < json_array_size(arr); i++) {
        json_t *b = json_array_get(arr, i);
        char path[48];
        snprintf(path, sizeof path, "occluders[%zu].", i);
        sim_occluder_t *o = &sc->world.occluder[i];
        if (num(b, path, "x1", -FIELD, FIELD, 1, 0, &o->x1, err, errlen) ||
            num(b, path, "y1", -FIELD, FIELD, 1, 0, &o->y1, err, errlen) ||
            num(b, path, "x2", -FIELD, FIELD, 1, 0, &o->x2, err, errlen) ||
            num(b, path, "y2", -FIELD, FIELD, 1, 0, &o->y2, err, errlen))
            return -1;
        sc->world.n_occluders = i + 1;
    }

    json_t *veh = object_at(root, "vehicle", "", 1, err, errlen, &fail);
    if (fail)
        return -1;
    warn_unknown(veh, "vehicle.", known_vehicle);
    double steer_rate_deg;
    if (num(veh, "vehicle.", "wheelbase_m", 0.1, 5.0, 1, 0, &sc->wheelbase, err, errlen) ||
        num(veh, "vehicle.", "min_radius_m", 0.05, 100.0, 1, 0, &sc->min_radius, err, errlen) ||
        num(veh, "vehicle.", "speed_mps", 0.01, 5.0, 1, 0, &sc->speed, err, errlen) ||
        num(veh, "vehicle.", "steer_rate_deg_per_s", 0.0, 10000.0, 0, 0.0, &steer_rate_deg, err,
            errlen))
        return -1;
    sc->steer_rate = steer_rate_deg * DEG;

    json_t *start = object_at(root, "start", "", 1, err, errlen, &fail);
    if (fail)
        return -1;
    warn_unknown(start, "start.", known_pose);
    double hd;
    if (num(start, "start.", "x", -FIELD, FIELD, 1, 0, &sc->start_x, err, errlen) ||
        num(start, "start.", "y", -FIELD, FIELD, 1, 0, &sc->start_y, err, errlen) ||
        num(start, "start.", "heading_deg", -720, 720, 1, 0, &hd, err, errlen))
        return -1;
    sc->start_heading = hd * DEG;
    json_t *serr = object_at(root, "start_error", "", 0, err, errlen, &fail);
    if (fail)
        return -1;
    if (serr) {
        warn_unknown(serr, "start_error.", known_pose);
        if (num(serr, "start_error.", "x", -1.0, 1.0, 0, 0, &sc->start_err_x, err, errlen) ||
            num(serr, "start_error.", "y", -1.0, 1.0, 0, 0, &sc->start_err_y, err, errlen) ||
            num(serr, "start_error.", "heading_deg", -10.0, 10.0, 0, 0, &hd, err, errlen))
            return -1;
        sc->start_err_heading = hd * DEG;
    }

    if (parse_array(root, "path", 1, SIM_MAX_PATH, 1, &arr, err, errlen))
        return -1;
    for (size_t i = 0; i < json_array_size(arr); i++) {
        json_t *p = json_array_get(arr, i);
        char path[48];
        snprintf(path, sizeof path, "path[%zu].", i);
        warn_unknown(p, path, known_pose);
        sim_waypoint_t *w = &sc->path[i];
        if (num(p, path, "x", -FIELD, FIELD, 1, 0, &w->x, err, errlen) ||
            num(p, path, "y", -FIELD, FIELD, 1, 0, &w->y, err, errlen) ||
            num(p, path, "heading_deg", -720, 720, 1, 0, &hd, err, errlen) ||
            num(p, path, "speed_mps", 0.01, 5.0, 0, sc->speed, &w->speed, err, errlen))
            return -1;
        w->heading = hd * DEG;
    }
    sc->n_path = json_array_size(arr);

    json_t *sensors = object_at(root, "sensors", "", 1, err, errlen, &fail);
    if (fail)
        return -1;
    warn_unknown(sensors, "sensors.", known_sensors);
    json_t *g = object_at(sensors, "goniometer", "sensors.", 1, err, errlen, &fail);
    json_t *o = fail ? NULL : object_at(sensors, "odometer", "sensors.", 1, err, errlen, &fail);
    json_t *gy = fail ? NULL : object_at(sensors, "gyro", "sensors.", 1, err, errlen, &fail);
    if (fail)
        return -1;
    warn_unknown(g, "sensors.goniometer.", known_gonio);
    warn_unknown(o, "sensors.odometer.", known_odo);
    warn_unknown(gy, "sensors.gyro.", known_gyro);
    double counts, noise_deg, step_deg, drift_deg;
    if (num(g, "sensors.goniometer.", "rev_per_s", 0.1, 50.0, 1, 0, &sc->rev_per_s, err, errlen) ||
        num(g, "sensors.goniometer.", "counts", 360, 65535, 1, 0, &counts, err, errlen) ||
        num(g, "sensors.goniometer.", "noise_deg", 0.0, 5.0, 1, 0, &noise_deg, err, errlen) ||
        num(g, "sensors.goniometer.", "range_m", 1.0, 1000.0, 0, 60.0, &sc->gonio_range, err,
            errlen) ||
        num(o, "sensors.odometer.", "dl_m", 1e-5, 0.1, 1, 0, &sc->dl, err, errlen) ||
        num(o, "sensors.odometer.", "scale", 0.9, 1.1, 0, 1.0, &sc->odo_scale, err, errlen) ||
        num(gy, "sensors.gyro.", "step_deg", 0.001, 10.0, 1, 0, &step_deg, err, errlen) ||
        num(gy, "sensors.gyro.", "drift_deg_per_s", -1.0, 1.0, 1, 0, &drift_deg, err, errlen))
        return -1;
    if (counts != floor(counts))
        return ac_fail(err, errlen, "sensors.goniometer.counts: %g is not an integer", counts);
    sc->counts = (uint32_t)counts;
    sc->gonio_noise = noise_deg * DEG;
    sc->gyro_step = step_deg * DEG;
    sc->gyro_drift = drift_deg * DEG;

    double seed;
    if (num(root, "", "seed", 0, 9007199254740991.0, 1, 0, &seed, err, errlen) ||
        num(root, "", "duration_s", 0.1, 36000.0, 1, 0, &sc->duration, err, errlen))
        return -1;
    if (seed != floor(seed))
        return ac_fail(err, errlen, "seed: %g is not an integer", seed);
    sc->seed = (uint64_t)seed;

    sim_success_t *s = &sc->success;
    json_t *succ = object_at(root, "success", "", 0, err, errlen, &fail);
    if (fail)
        return -1;
    json_t *none = json_object();
    json_t *so = succ ? succ : none;
    warn_unknown(so, "success.", known_success);
    int rc =
        num(so, "success.", "cross_track_mean_m", 0, 100, 0, 0.010, &s->max_cross_track_mean, err,
            errlen) ||
        num(so, "success.", "cross_track_max_m", 0, 100, 0, 0.100, &s->max_cross_track_max, err,
            errlen) ||
        num(so, "success.", "final_error_m", 0, 100, 0, 0.050, &s->max_final_error, err, errlen) ||
        num(so, "success.", "fix_error_max_m", 0, 100, 0, 0.050, &s->max_fix_error, err, errlen) ||
        num(so, "success.", "fix_accept_ratio", 0, 1, 0, 0.5, &s->min_fix_ratio, err, errlen);
    bool goal = true;
    if (!rc)
        rc = ac_bool(so, "reach_goal", true, &goal, err, errlen);
    json_decref(none);
    if (rc)
        return -1;
    s->require_goal = goal;
    return 0;
}

int sim_scenario_parse(const char *text, sim_scenario_t *sc, char *err, size_t errlen)
{
    json_error_t jerr;
    json_t *root = json_loads(text, JSON_REJECT_DUPLICATES, &jerr);
    if (!root)
        return ac_fail(err, errlen, "line %d, column %d: %s", jerr.line, jerr.column, jerr.text);
    int rc = parse_root(root, sc, err, errlen);
    json_decref(root);
    return rc;
}

int sim_scenario_load(const char *path, sim_scenario_t *sc, char *err, size_t errlen)
{
    json_error_t jerr;
    json_t *root = json_load_file(path, JSON_REJECT_DUPLICATES, &jerr);
    if (!root && jerr.line < 0)
        return ac_fail(err, errlen, "%s", jerr.text); /* cannot open or read the file */
    if (!root)
        return ac_fail(err, errlen, "%s: line %d, column %d: %s", path, jerr.line, jerr.column,
                       jerr.text);
    char inner[512];
    int rc = parse_root(root, sc, inner, sizeof inner);
    json_decref(root);
    if (rc)
        return ac_fail(err, errlen, "%s: %s", path, inner);
    return 0;
}
