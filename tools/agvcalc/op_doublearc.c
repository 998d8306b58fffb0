/*
 * op_doublearc.c - agvcalc op "doublearc" (CONTRACT.md): the drive routine's double arc from
 * one pose to another, solved by the firmware's fixed-point solver (firmware/drive).
 *
 * {"op":"doublearc","from":{x,y,heading_deg},"to":{...},"min_radius_m":..,"wheelbase_m":..,
 *  "reverse":false}
 * -> {"ok":true,"case":"1".."5"|"straight","segments":[{"turn":"left|right|straight",
 *     "radius_m":r|null,"length_m":s},{...}],"steering_deg":[a1,a2]}
 * Radii are signed, left positive (the steering's turn, also when reversing); lengths are
 * rear-axle path lengths; steering angles are atan(wheelbase / radius). Following the
 * segments from "from" ends at "to" (docs/drive.md gives the precision).
 */
#include <math.h>
#include <stdio.h>

#include "agvcalc.h"
#include "drive/drive.h"
#include "drive/drive_cmd.h"
#include "fx/fx_host.h"

/* Positions must fit Q15.16 with room for the difference of two of them. */
#define POS_LIMIT 16000.0

static drive_pose_t to_pose(const ac_pose_t *p)
{
    drive_pose_t d = {fx_q16_from_double(p->x), fx_q16_from_double(p->y),
                      fx_angle_from_deg(p->heading_deg)};
    return d;
}

/* --help: the fields and their units. */
const char agvcalc_fields_doublearc[] =
    "    from, to      {x, y, heading_deg}: rear-axle poses, m (within +-16000) and degrees\n"
    "    min_radius_m  smallest turn radius allowed, m [0.125, 100]\n"
    "    wheelbase_m   rear axle to front wheel, m [0.01, 10]\n"
    "    reverse?      true: drive backwards (default false)\n"
    "    -> case: \"1\"..\"5\" or \"straight\"; segments: [{turn: left|right|straight,\n"
    "       radius_m: signed m (left positive) or null, length_m: rear-axle path, m}, ...];\n"
    "       steering_deg: [a1, a2], atan(wheelbase / radius), degrees, left positive\n";

int agvcalc_op_doublearc(json_t *req, json_t *resp, char *err, size_t errlen);

int agvcalc_op_doublearc(json_t *req, json_t *resp, char *err, size_t errlen)
{
    ac_pose_t from, to;
    double rmin, wheelbase;
    bool reverse;
    if (ac_pose(req, "from", POS_LIMIT, true, &from, err, errlen) ||
        ac_pose(req, "to", POS_LIMIT, true, &to, err, errlen) ||
        ac_number(req, "min_radius_m", fx_q16_to_double(DRIVE_MIN_RADIUS_MIN),
                  fx_q16_to_double(DRIVE_MIN_RADIUS_MAX), true, 0, &rmin, err, errlen) ||
        ac_number(req, "wheelbase_m", 0.01, 10.0, true, 0, &wheelbase, err, errlen) ||
        ac_bool(req, "reverse", false, &reverse, err, errlen))
        return -1;

    drive_pose_t f = to_pose(&from), t = to_pose(&to);
    fx_q16_t rq = fx_q16_from_double(rmin), lq = fx_q16_from_double(wheelbase);
    drive_solution_t sol;
    int32_t need = 0;
    drive_status_t st = drive_solve(&f, &t, rq, reverse, &sol, &need);
    if (st == DRIVE_ERR_RADIUS) {
        if (need == INT32_MAX)
            return ac_fail(err, errlen,
                           "%s: the double arc needs a radius below 0.125 m (min_radius_m %g)",
                           drive_status_text(st), rmin);
        return ac_fail(err, errlen, "%s: the double arc needs %.4f m (min_radius_m %g)",
                       drive_status_text(st), (double)DRIVE_CURV_ONE / need, rmin);
    }
    double dx = to.x - from.x, dy = to.y - from.y, dist = sqrt(dx * dx + dy * dy);
    double dh = fmod(fmod(to.heading_deg - from.heading_deg, 360.0) + 540.0, 360.0) - 180.0;
    switch (st) {
    case DRIVE_OK:
        break;
    case DRIVE_ERR_HEADING:
        return ac_fail(err, errlen, "%s: %.3f degrees", drive_status_text(st), dh);
    case DRIVE_ERR_TOO_CLOSE:
    case DRIVE_ERR_TOO_FAR:
        return ac_fail(err, errlen, "%s: %.6f m", drive_status_text(st), dist);
    case DRIVE_ERR_BEHIND: {
        double a = (from.heading_deg + (reverse ? 180.0 : 0.0)) * (M_PI / 180.0);
        return ac_fail(err, errlen, "%s: %.6f m along it (%s)", drive_status_text(st),
                       dx * cos(a) + dy * sin(a), reverse ? "reversing" : "forward");
    }
    default:
        return ac_fail(err, errlen, "%s", drive_status_text(st));
    }

    static const char *const names[] = {"straight", "1", "2", "3", "4", "5"};
    json_object_set_new(resp, "case", json_string(names[sol.kase]));
    json_t *segs = json_array(), *steer = json_array();
    for (int i = 0; i < 2; i++) {
        const drive_segment_t *g = &sol.seg[i];
        json_t *o = json_object();
        json_object_set_new(o, "turn",
                            json_string(g->curvature > 0   ? "left"
                                        : g->curvature < 0 ? "right"
                                                           : "straight"));
        if (g->curvature == 0)
            json_object_set_new(o, "radius_m", json_null());
        else
            ac_set(o, "radius_m", (double)DRIVE_CURV_ONE / g->curvature, 6);
        ac_set(o, "length_m", fx_q16_to_double(g->length), 6);
        json_array_append_new(segs, o);
        json_t *a = json_object();
        ac_set(a, "v", fx_angle_to_deg_signed(drive_steer_angle(g->curvature, lq)), 6);
        json_array_append(steer, json_object_get(a, "v"));
        json_decref(a);
    }
    json_object_set_new(resp, "segments", segs);
    json_object_set_new(resp, "steering_deg", steer);
    return 0;
}
