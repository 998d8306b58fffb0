/*
 * op_triangulate.c - agvcalc op "triangulate": three beacons and their sighting angles to a
 * position, bearing and quality with the firmware's fixed-point triangulation (SPEC O8-O10).
 *
 * {"op":"triangulate","beacons":[[x,y],[x,y],[x,y]],"angles_deg":[a1,a2,a3],
 *  "quality_max":q?} -> {"ok":true,"x":..,"y":..,"heading_deg":..,"quality":..}
 * quality: predicted RMS position error (m) for one count (360/50,000 degrees) of bearing
 * error on each sighting; ok:false when it exceeds quality_max (default 0.25) or the geometry
 * is degenerate.
 */
#include <math.h>

#include "agvcalc.h"
#include "fx/fx_host.h"
#include "optical/optical.h"

/* Q16 m per mrad -> m per count of a 50,000-count goniometer. */
#define PER_COUNT (2.0 * M_PI / 50000.0 * 1000.0 / 65536.0)

/* --help: the fields and their units. */
const char agvcalc_fields_triangulate[] =
    "    beacons       [[x, y], [x, y], [x, y]]: three beacon positions, m (within +-8191)\n"
    "    angles_deg    [a1, a2, a3]: their sighting angles, degrees CCW from the heading\n"
    "    quality_max?  largest accepted quality, m per count (default and maximum 0.2513)\n"
    "    -> x, y: position, m; heading_deg: [0, 360); quality: predicted RMS position error,\n"
    "       m per count (one count = 360/50000 degrees of bearing error on each sighting)\n";

int agvcalc_op_triangulate(json_t *req, json_t *resp, char *err, size_t errlen);

int agvcalc_op_triangulate(json_t *req, json_t *resp, char *err, size_t errlen)
{
    double pts[3][2];
    size_t n;
    if (ac_points(req, "beacons", 3, 3, 8191.0, pts, &n, err, errlen))
        return -1;
    json_t *arr = json_object_get(req, "angles_deg");
    if (!arr)
        return ac_fail(err, errlen, "missing \"angles_deg\"");
    if (!json_is_array(arr) || json_array_size(arr) != 3)
        return ac_fail(err, errlen, "angles_deg: expected an array of 3 angles");
    fx_angle_t th[3];
    for (size_t i = 0; i < 3; i++) {
        char what[32];
        double a;
        snprintf(what, sizeof what, "angles_deg[%zu]", i);
        if (ac_number_value(json_array_get(arr, i), what, -1e6, 1e6, &a, err, errlen))
            return -1;
        th[i] = fx_angle_from_deg(a);
    }
    double qmax;
    if (ac_number(req, "quality_max", 1e-6, OPTICAL_QUALITY_LIMIT * PER_COUNT, false,
                  OPTICAL_QUALITY_LIMIT * PER_COUNT, &qmax, err, errlen))
        return -1;
    optical_xy_t b[3];
    for (size_t i = 0; i < 3; i++) {
        b[i].x = fx_q16_from_double(pts[i][0]);
        b[i].y = fx_q16_from_double(pts[i][1]);
    }
    optical_tri_t tri;
    int8_t st = optical_triangulate(b, th, (uint32_t)floor(qmax / PER_COUNT), &tri);
    switch (st) {
    case OPTICAL_OK:
        break;
    case OPTICAL_E_DEGENERATE:
        return ac_fail(err, errlen,
                       "degenerate geometry: two beacons coincide or two sightings share an "
                       "angle");
    case OPTICAL_E_SINGULAR:
        if (tri.quality == UINT32_MAX)
            return ac_fail(err, errlen,
                           "too close to singular: the vehicle lies on the circle through the "
                           "three beacons");
        ac_set(resp, "quality", tri.quality * PER_COUNT, 6);
        return ac_fail(err, errlen,
                       "too close to singular: the vehicle lies near the circle through the "
                       "three beacons (quality %.4g m per count exceeds quality_max %.4g)",
                       tri.quality * PER_COUNT, qmax);
    case OPTICAL_E_INCONSISTENT:
        return ac_fail(err, errlen,
                       "no position sees the three beacons under these angles (inconsistent "
                       "angles, or too close to the circle through the beacons)");
    default:
        return ac_fail(err, errlen, "beacons: more than 2048 m apart");
    }
    ac_set_pose(resp, fx_q16_to_double(tri.pose.x), fx_q16_to_double(tri.pose.y),
                fx_angle_to_deg(tri.pose.heading));
    ac_set(resp, "quality", tri.quality * PER_COUNT, 6);
    return 0;
}
