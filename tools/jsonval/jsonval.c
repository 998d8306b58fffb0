/*
 * jsonval.c - validating readers of JSON input (see jsonval.h).
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "jsonval.h"

int ac_fail(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return -1;
}

/* A short rendering of any JSON value for error messages. */
static void show(json_t *v, char *buf, size_t n)
{
    char *s = json_dumps(v, JSON_ENCODE_ANY | JSON_COMPACT);
    if (!s) {
        snprintf(buf, n, "?");
        return;
    }
    if (strlen(s) > 40)
        snprintf(buf, n, "%.37s...", s);
    else
        snprintf(buf, n, "%s", s);
    free(s);
}

int ac_number_value(json_t *v, const char *what, double lo, double hi, double *out, char *err,
                    size_t errlen)
{
    char shown[48];
    if (!json_is_number(v)) {
        show(v, shown, sizeof shown);
        return ac_fail(err, errlen, "%s: expected a number, got %s", what, shown);
    }
    double d = json_number_value(v);
    if (!isfinite(d))
        return ac_fail(err, errlen, "%s: not a finite number", what);
    if (d < lo || d > hi)
        return ac_fail(err, errlen, "%s: %g is out of range [%g, %g]", what, d, lo, hi);
    *out = d;
    return 0;
}

int ac_number(json_t *obj, const char *key, double lo, double hi, bool required, double dflt,
              double *out, char *err, size_t errlen)
{
    json_t *v = json_object_get(obj, key);
    if (!v) {
        if (required)
            return ac_fail(err, errlen, "missing \"%s\"", key);
        *out = dflt;
        return 0;
    }
    return ac_number_value(v, key, lo, hi, out, err, errlen);
}

int ac_bool(json_t *obj, const char *key, bool dflt, bool *out, char *err, size_t errlen)
{
    json_t *v = json_object_get(obj, key);
    if (!v) {
        *out = dflt;
        return 0;
    }
    if (!json_is_boolean(v)) {
        char shown[48];
        show(v, shown, sizeof shown);
        return ac_fail(err, errlen, "%s: expected true or false, got %s", key, shown);
    }
    *out = json_is_true(v);
    return 0;
}

int ac_points(json_t *obj, const char *key, size_t min_n, size_t max_n, double lim,
              double (*out)[2], size_t *n, char *err, size_t errlen)
{
    json_t *arr = json_object_get(obj, key);
    if (!arr)
        return ac_fail(err, errlen, "missing \"%s\"", key);
    if (!json_is_array(arr))
        return ac_fail(err, errlen, "%s: expected an array of [x, y] points", key);
    size_t count = json_array_size(arr);
    if (count < min_n || count > max_n) {
        if (min_n == max_n)
            return ac_fail(err, errlen, "%s: expected exactly %zu points, got %zu", key, min_n,
                           count);
        return ac_fail(err, errlen, "%s: expected %zu to %zu points, got %zu", key, min_n, max_n,
                       count);
    }
    for (size_t i = 0; i < count; i++) {
        json_t *p = json_array_get(arr, i);
        if (!json_is_array(p) || json_array_size(p) != 2)
            return ac_fail(err, errlen, "%s[%zu]: expected [x, y]", key, i);
        for (size_t k = 0; k < 2; k++) {
            char what[64];
            snprintf(what, sizeof what, "%s[%zu][%zu]", key, i, k);
            if (ac_number_value(json_array_get(p, k), what, -lim, lim, &out[i][k], err, errlen))
                return -1;
        }
    }
    *n = count;
    return 0;
}

int ac_pose(json_t *obj, const char *key, double lim, bool need_heading, ac_pose_t *out, char *err,
            size_t errlen)
{
    json_t *p = json_object_get(obj, key);
    if (!p)
        return ac_fail(err, errlen, "missing \"%s\"", key);
    if (!json_is_object(p))
        return ac_fail(err, errlen, "%s: expected an object {\"x\",\"y\",\"heading_deg\"}", key);
    char what[64];
    snprintf(what, sizeof what, "%s.x", key);
    json_t *v = json_object_get(p, "x");
    if (!v)
        return ac_fail(err, errlen, "missing \"%s\"", what);
    if (ac_number_value(v, what, -lim, lim, &out->x, err, errlen))
        return -1;
    snprintf(what, sizeof what, "%s.y", key);
    v = json_object_get(p, "y");
    if (!v)
        return ac_fail(err, errlen, "missing \"%s\"", what);
    if (ac_number_value(v, what, -lim, lim, &out->y, err, errlen))
        return -1;
    snprintf(what, sizeof what, "%s.heading_deg", key);
    v = json_object_get(p, "heading_deg");
    out->heading_deg = 0.0;
    if (!v) {
        if (need_heading)
            return ac_fail(err, errlen, "missing \"%s\"", what);
        return 0;
    }
    return ac_number_value(v, what, -1e6, 1e6, &out->heading_deg, err, errlen);
}

void ac_set(json_t *resp, const char *key, double v, int decimals)
{
    double scale = pow(10.0, decimals);
    double r = round(v * scale) / scale;
    if (r == 0.0)
        r = 0.0; /* no "-0" */
    json_object_set_new(resp, key, json_real(r));
}

void ac_set_pose(json_t *resp, double x, double y, double heading_deg)
{
    ac_set(resp, "x", x, 6);
    ac_set(resp, "y", y, 6);
    ac_set(resp, "heading_deg", round(heading_deg * 1e6) >= 360e6 ? 0.0 : heading_deg, 6);
}
