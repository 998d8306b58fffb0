/*
 * jsonval.h - validating readers of JSON input (jansson), for agvcalc requests and agv-sim
 * scenarios: a missing key, a wrong type, a value out of range or not finite becomes an
 * error that names the key (with its path) and the value.
 */
#ifndef JSONVAL_H
#define JSONVAL_H

#include <jansson.h>
#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** printf into the op's error buffer; always returns -1 (so `return ac_fail(...)` works). */
int ac_fail(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/**
 * A finite number at @p key of @p obj within [lo, hi]. When the key is absent: required ->
 * error, otherwise *out = dflt. Returns 0 or -1 (err filled).
 */
int ac_number(json_t *obj, const char *key, double lo, double hi, bool required, double dflt,
              double *out, char *err, size_t errlen);

/** The same for a value that is not in an object (an array element); @p what names it. */
int ac_number_value(json_t *v, const char *what, double lo, double hi, double *out, char *err,
                    size_t errlen);

/** A boolean at @p key (absent -> dflt). */
int ac_bool(json_t *obj, const char *key, bool dflt, bool *out, char *err, size_t errlen);

/**
 * An array of [x, y] points at @p key, between @p min_n and @p max_n of them, each
 * coordinate within [-lim, lim] metres. Returns 0 with *n set, or -1.
 */
int ac_points(json_t *obj, const char *key, size_t min_n, size_t max_n, double lim,
              double (*out)[2], size_t *n, char *err, size_t errlen);

/** A pose object {"x","y","heading_deg"} at @p key; heading any finite degrees. */
typedef struct {
    double x, y, heading_deg;
} ac_pose_t;
int ac_pose(json_t *obj, const char *key, double lim, bool need_heading, ac_pose_t *out, char *err,
            size_t errlen);

/** Set a number, rounded to @p decimals decimals (stable text output). */
void ac_set(json_t *resp, const char *key, double v, int decimals);

/** Set "x", "y" (metres) and "heading_deg" (degrees, [0, 360)), each to 6 decimals; a heading
 * that rounds to 360 is written as 0. */
void ac_set_pose(json_t *resp, double x, double y, double heading_deg);

#ifdef __cplusplus
}
#endif

#endif
