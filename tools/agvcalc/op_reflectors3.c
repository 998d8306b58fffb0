/*
 * op_reflectors3.c - agvcalc op "reflectors3": the three-reflector timing mode (SPEC O12,
 * seed 004) with the firmware's own code.
 *
 * {"op":"reflectors3","reflectors":[[x,y],[x,y],[x,y]],"field":[[x,y],...]?,
 *  "events_s":[t_click,t_r1,t_r2,t_r3,t_click_next],"expected_period_s":..,
 *  "period_tol":0.05?,"approx":{"x","y"}?,"goal":{"x","y"}?}
 * -> {"ok":true,"x","y","heading_deg","first","quality"[,"goal_distance_m","goal_turn_deg"]}
 * Times are converted to microsecond ticks after the click (the firmware's timer). When more
 * than one assignment of reflectors fits inside the field and no "approx" is given, the
 * answer is ok:false with "candidates":[[x,y],...].
 */
#include <math.h>

#include "agvcalc.h"
#include "fx/fx_host.h"
#include "optical/reflectors3.h"

#define PER_COUNT (2.0 * M_PI / 50000.0 * 1000.0 / 65536.0)
#define LIM       8191.0
#define TICK      1e-6

static int read_xy(json_t *req, const char *key, optical_xy_t *p, bool *given, char *err,
                   size_t errlen)
{
    *given = json_object_get(req, key) != NULL;
    if (!*given)
        return 0;
    ac_pose_t a;
    if (ac_pose(req, key, LIM, false, &a, err, errlen))
        return -1;
    p->x = fx_q16_from_double(a.x);
    p->y = fx_q16_from_double(a.y);
    return 0;
}

/* --help: the fields and their units. */
const char agvcalc_fields_reflectors3[] =
    "    reflectors    [[x, y], [x, y], [x, y]]: the three reflectors, m (within +-8191)\n"
    "    field?        [[x, y], ...]: polygon bounding where the vehicle can be, m\n"
    "    events_s      [t_click, t_r1, t_r2, t_r3, t_click_next]: seconds (within 4000 s\n"
    "                  after t_click)\n"
    "    expected_period_s  revolution time, s [0.001, 4000]\n"
    "    period_tol?   accepted relative deviation of the revolution time (default 0.05)\n"
    "    approx?       {x, y}: picks the nearest of several candidates, m\n"
    "    goal?         {x, y}: adds goal_distance_m and goal_turn_deg, m and degrees\n"
    "    -> x, y: m; heading_deg: [0, 360); first: index of the reflector seen first;\n"
    "       quality: m per count; ok:false with candidates: [[x, y], ...] when ambiguous\n";

int agvcalc_op_reflectors3(json_t *req, json_t *resp, char *err, size_t errlen);

int agvcalc_op_reflectors3(json_t *req, json_t *resp, char *err, size_t errlen)
{
    double pts[OPTICAL_R3_MAX_FIELD][2];
    size_t n;
    if (ac_points(req, "reflectors", 3, 3, LIM, pts, &n, err, errlen))
        return -1;
    optical_xy_t refl[3];
    for (size_t i = 0; i < 3; i++) {
        refl[i].x = fx_q16_from_double(pts[i][0]);
        refl[i].y = fx_q16_from_double(pts[i][1]);
    }
    optical_xy_t field[OPTICAL_R3_MAX_FIELD];
    size_t nf = 0;
    if (json_object_get(req, "field")) {
        if (ac_points(req, "field", 3, OPTICAL_R3_MAX_FIELD, LIM, pts, &nf, err, errlen))
            return -1;
        for (size_t i = 0; i < nf; i++) {
            field[i].x = fx_q16_from_double(pts[i][0]);
            field[i].y = fx_q16_from_double(pts[i][1]);
        }
    }
    json_t *ev = json_object_get(req, "events_s");
    if (!ev)
        return ac_fail(err, errlen, "missing \"events_s\"");
    if (!json_is_array(ev) || json_array_size(ev) < 2)
        return ac_fail(err, errlen,
                       "events_s: expected [t_click, t_r1, t_r2, t_r3, t_click_next] (seconds)");
    size_t ne = json_array_size(ev);
    double t[16];
    if (ne > 16)
        return ac_fail(err, errlen,
                       "events_s: %zu reflections between the clicks; exactly 3 are needed, the "
                       "revolution is discarded",
                       ne - 2);
    for (size_t i = 0; i < ne; i++) {
        char what[32];
        snprintf(what, sizeof what, "events_s[%zu]", i);
        if (ac_number_value(json_array_get(ev, i), what, -1e9, 1e9, &t[i], err, errlen))
            return -1;
    }
    double per;
    if (ac_number(req, "expected_period_s", 1e-3, 4000.0, true, 0.0, &per, err, errlen))
        return -1;
    double tol;
    if (ac_number(req, "period_tol", 0.0, 0.5, false, 0.05, &tol, err, errlen))
        return -1;
    for (size_t i = 1; i < ne; i++) {
        double rel = t[i] - t[0];
        if (rel < 0.0 || rel > 4000.0)
            return ac_fail(err, errlen,
                           "events_s[%zu]: %g s is not within 4000 s after the click at %g s", i,
                           t[i], t[0]);
    }
    uint32_t ticks[16];
    for (size_t i = 0; i < ne; i++)
        ticks[i] = (uint32_t)llround((t[i] - t[0]) / TICK);
    optical_xy_t approx;
    bool has_approx, has_goal;
    optical_xy_t goal;
    if (read_xy(req, "approx", &approx, &has_approx, err, errlen) ||
        read_xy(req, "goal", &goal, &has_goal, err, errlen))
        return -1;
    optical_r3_config_t cfg = {nf ? field : NULL, (uint8_t)nf, (uint32_t)llround(per / TICK),
                               (uint32_t)llround(per * tol / TICK),
                               (uint32_t)floor(OPTICAL_QUALITY_LIMIT)};
    optical_r3_t r;
    int8_t st = optical_r3_fix(refl, ticks[0], &ticks[1], (uint8_t)(ne - 2), ticks[ne - 1], &cfg,
                               has_approx ? &approx : NULL, &r);
    switch (st) {
    case OPTICAL_R3_OK:
        break;
    case OPTICAL_R3_E_COUNT:
        return ac_fail(err, errlen,
                       "events_s: %zu reflections between the clicks; exactly 3 are needed, the "
                       "revolution is discarded",
                       ne - 2);
    case OPTICAL_R3_E_PERIOD:
        return ac_fail(err, errlen,
                       "revolution time %g s is not within %g%% of expected_period_s %g: the "
                       "revolution is discarded",
                       t[ne - 1] - t[0], tol * 100.0, per);
    case OPTICAL_R3_E_ORDER:
        return ac_fail(err, errlen,
                       "events_s: the reflections must follow the click in increasing order "
                       "before the next click");
    case OPTICAL_R3_E_AMBIGUOUS: {
        json_t *c = json_array();
        for (uint8_t i = 0; i < r.n_cand; i++) {
            json_t *p = json_array();
            json_array_append_new(p, json_real(round(fx_q16_to_double(r.cand[i].x) * 1e6) / 1e6));
            json_array_append_new(p, json_real(round(fx_q16_to_double(r.cand[i].y) * 1e6) / 1e6));
            json_array_append_new(c, p);
        }
        json_object_set_new(resp, "candidates", c);
        return ac_fail(err, errlen,
                       "ambiguous: %u assignments of reflectors to reflections fit inside the "
                       "field; give \"approx\" to choose",
                       r.n_cand);
    }
    case OPTICAL_E_SINGULAR:
        return ac_fail(err, errlen,
                       "too close to singular: the vehicle lies near the circle through the "
                       "three reflectors");
    case OPTICAL_R3_E_NONE:
        return ac_fail(err, errlen,
                       "no assignment of reflectors to reflections gives a position "
                       "inside the field");
    default:
        return ac_fail(err, errlen, "coordinates beyond +-8192 m");
    }
    ac_set_pose(resp, fx_q16_to_double(r.pose.x), fx_q16_to_double(r.pose.y),
                fx_angle_to_deg(r.pose.heading));
    json_object_set_new(resp, "first", json_integer(r.first));
    ac_set(resp, "quality", r.quality * PER_COUNT, 6);
    if (has_goal) {
        uint32_t d;
        fx_angle_t turn;
        optical_r3_goal(&r.pose, &goal, &d, &turn);
        ac_set(resp, "goal_distance_m", d / 65536.0, 6);
        ac_set(resp, "goal_turn_deg", fx_angle_to_deg_signed(turn), 6);
    }
    return 0;
}
