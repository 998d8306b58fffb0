/*
 * op_fix.c - agvcalc op "fix": the whole optical pipeline of one revolution (identify,
 * select, triangulate, bearing, acceptance) with the firmware's own code (SPEC O2-O11).
 *
 * {"op":"fix","map":[[x,y] | [x,y,d] | {"x","y","diameter_m"?,"kind"?},...],
 *  "approx":{"x","y","heading_deg"},
 *  "sightings":[{"angle_deg":..,"width_deg":..,"pose":{...}?},...],
 *  "uncertainty":{"pos_m"?,"heading_deg"?,"travel_m"?,"turn_deg"?}?,"config":{...}?}
 * -> {"ok":true,"x","y","heading_deg","used":[i,j,k],"identified":[k|-1,...],"quality",
 *     "widened","err_m","gate_m","resid_deg","agree","dropped","status"}
 * A map entry without a diameter takes config beacon_diameter_m (and beacon_flat). A
 * sighting's optional "pose" is the dead-reckoning pose latched at that sighting (give it for
 * all sightings or none); the fix is then the pose at the instant of "approx". "uncertainty":
 * what approx is worth, its bounds after the last accepted fix (pos_m, heading_deg; default
 * the configuration's largest, jump_max_m and turn_max_deg) grown over travel_m and turn_deg
 * (optical_unc_grow). Config names and defaults: docs/optical.md. On failure "identified",
 * "status" (its name) and, when a fix was solved, its quality figures are still given.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "agvcalc.h"
#include "fx/fx_host.h"
#include "optical/optical.h"

#define PER_COUNT (2.0 * M_PI / 50000.0 * 1000.0 / 65536.0)
#define LIM       8191.0

typedef struct {
    const char *key;
    double lo, hi;
    int kind; /* 0 metres, 1 degrees, 2 count, 3 bool, 4 fraction, 5 m per count */
    size_t off;
} cfg_key_t;

#define OFF(f) offsetof(optical_config_t, f)
static const cfg_key_t keys[] = {
    {"window_deg", 0.0, 90.0, 1, OFF(window)},
    {"window_pos_m", 0.0, 100.0, 0, OFF(window_pos)},
    {"widen_max_deg", 0.0, 90.0, 1, OFF(widen_max)},
    {"widen_steps", 0, 10, 2, OFF(widen_steps)},
    {"reject_overlap", 0, 1, 3, OFF(reject_overlap)},
    {"range_m", 0.1, 8000.0, 0, OFF(range)},
    {"range_max_m", 0.1, 8000.0, 0, OFF(range_max)},
    {"range_steps", 0, 10, 2, OFF(range_steps)},
    {"dist_tol_m", 0.0, 1000.0, 0, OFF(dist_tol)},
    {"dist_rel", 0.0, 10.0, 4, OFF(dist_rel)},
    {"jump_max_m", 0.0, 8000.0, 0, OFF(jump_max)},
    {"turn_max_deg", 0.0, 180.0, 1, OFF(turn_max)},
    {"bearing_err_deg", 0.0, 10.0, 1, OFF(bearing_err)},
    {"bearing_err_moving_deg", 0.0, 10.0, 1, OFF(bearing_err_moving)},
    {"err_max_m", 0.0, 100.0, 0, OFF(err_max)},
    {"unc_pos_min_m", 0.0, 100.0, 0, OFF(unc_pos_min)},
    {"unc_head_min_deg", 0.0, 90.0, 1, OFF(unc_head_min)},
    {"unc_per_m", 0.0, 0.99, 4, OFF(unc_per_m)},
    {"unc_head_per_m_deg", 0.0, 1.0, 1, OFF(unc_head_per_m)},
    {"unc_turn", 0.0, 0.99, 4, OFF(unc_turn)},
    {"quality_max", 1e-6, OPTICAL_QUALITY_LIMIT *PER_COUNT, 5, OFF(quality_max)},
    {"motion_passes", 1, 4, 2, OFF(motion_passes)},
};

/* The map entries' default reflector (config beacon_diameter_m, beacon_flat). */
typedef struct {
    double d;
    bool flat;
} refl_default_t;

static int read_config(json_t *req, optical_config_t *cfg, refl_default_t *rd, char *err,
                       size_t errlen)
{
    optical_config_default(cfg);
    rd->d = 0.08;
    rd->flat = false;
    json_t *c = json_object_get(req, "config");
    if (!c)
        return 0;
    if (!json_is_object(c))
        return ac_fail(err, errlen, "config: expected an object");
    const char *k;
    json_t *v;
    if (ac_number(c, "beacon_diameter_m", 0.005, 2.0, false, 0.08, &rd->d, err, errlen) ||
        ac_bool(c, "beacon_flat", false, &rd->flat, err, errlen))
        return -1;
    json_object_foreach(c, k, v)
    {
        if (!strcmp(k, "beacon_diameter_m") || !strcmp(k, "beacon_flat"))
            continue;
        size_t i = 0;
        while (i < sizeof keys / sizeof keys[0] && strcmp(keys[i].key, k) != 0)
            i++;
        if (i == sizeof keys / sizeof keys[0])
            return ac_fail(err, errlen,
                           "config: unknown key \"%.40s\" (docs/optical.md lists them)", k);
        const cfg_key_t *d = &keys[i];
        char what[64];
        snprintf(what, sizeof what, "config.%s", k);
        char *field = (char *)cfg + d->off;
        if (d->kind == 3) {
            bool b;
            if (ac_bool(c, k, false, &b, err, errlen))
                return -1;
            *(uint8_t *)field = b;
            continue;
        }
        double x;
        if (ac_number_value(v, what, d->lo, d->hi, &x, err, errlen))
            return -1;
        switch (d->kind) {
        case 0:
        case 4:
            *(fx_q16_t *)field = fx_q16_from_double(x);
            break;
        case 1:
            *(fx_angle_t *)field = fx_angle_from_deg(x);
            break;
        case 2:
            if (x != floor(x))
                return ac_fail(err, errlen, "%s: %g is not a whole number", what, x);
            *(uint8_t *)field = (uint8_t)x;
            break;
        default:
            *(uint32_t *)field = (uint32_t)floor(x / PER_COUNT);
            break;
        }
    }
    return 0;
}

static int read_pose(json_t *obj, const char *key, optical_pose_t *p, char *err, size_t errlen)
{
    ac_pose_t a;
    if (ac_pose(obj, key, LIM, true, &a, err, errlen))
        return -1;
    p->x = fx_q16_from_double(a.x);
    p->y = fx_q16_from_double(a.y);
    p->heading = fx_angle_from_deg(a.heading_deg);
    return 0;
}

static const char *why(int8_t st)
{
    switch (st) {
    case OPTICAL_E_FEW:
        return "fewer than 3 beacons identified";
    case OPTICAL_E_DEGENERATE:
        return "degenerate triplet: two beacons coincide or two sightings share an angle";
    case OPTICAL_E_SINGULAR:
        return "too close to singular: the vehicle lies near the circle through the three "
               "beacons (quality beyond quality_max)";
    case OPTICAL_E_JUMP:
        return "the fix lies farther from the approximate position than its uncertainty and "
               "the fix's own predicted error allow (gate_m): likely misidentification";
    case OPTICAL_E_TURN:
        return "the bearing differs from the approximate heading by more than its uncertainty "
               "and the fix's own predicted error allow: likely misidentification";
    case OPTICAL_E_DISAGREE:
        return "other identified sightings disagree with the fix beyond their residual "
               "tolerance, too many to drop as outliers: likely misidentification";
    case OPTICAL_E_INCONSISTENT:
        return "the sightings contradict the approximate pose within its uncertainty, or no "
               "position sees the selected beacons under their angles";
    case OPTICAL_E_UNCONFIRMED:
        return "identified only beyond the stated uncertainty (a guess or widened windows) "
               "and fewer than five sightings confirm the fix";
    case OPTICAL_E_POOR:
        return "no triplet's predicted error (quality times the bearing error bound) is within "
               "err_max_m";
    default:
        return "the approximate position lies more than 128 m from the map's centre";
    }
}

/* One map entry: [x, y], [x, y, d] or {"x", "y", "diameter_m"?, "kind"?}. */
static int read_beacon(json_t *e, size_t i, const refl_default_t *rd, optical_xy_t *b,
                       optical_refl_t *r, char *err, size_t errlen)
{
    double v[3] = {0, 0, rd->d};
    bool flat = rd->flat;
    char what[48];
    if (json_is_array(e) && (json_array_size(e) == 2 || json_array_size(e) == 3)) {
        for (size_t k = 0; k < json_array_size(e); k++) {
            snprintf(what, sizeof what, "map[%zu][%zu]", i, k);
            if (ac_number_value(json_array_get(e, k), what, k < 2 ? -LIM : 0.005, k < 2 ? LIM : 2.0,
                                &v[k], err, errlen))
                return -1;
        }
    } else if (json_is_object(e)) {
        const char *k;
        json_t *x;
        json_object_foreach(e, k, x)
        {
            if (strcmp(k, "x") && strcmp(k, "y") && strcmp(k, "diameter_m") && strcmp(k, "kind"))
                return ac_fail(err, errlen, "map[%zu]: unknown key \"%.40s\"", i, k);
        }
        char inner[200];
        if (ac_number(e, "x", -LIM, LIM, true, 0, &v[0], inner, sizeof inner) ||
            ac_number(e, "y", -LIM, LIM, true, 0, &v[1], inner, sizeof inner) ||
            ac_number(e, "diameter_m", 0.005, 2.0, false, rd->d, &v[2], inner, sizeof inner))
            return ac_fail(err, errlen, "map[%zu].%s", i, inner);
        json_t *kind = json_object_get(e, "kind");
        if (kind) {
            if (json_is_string(kind) && !strcmp(json_string_value(kind), "flat"))
                flat = true;
            else if (json_is_string(kind) && !strcmp(json_string_value(kind), "cylinder"))
                flat = false;
            else
                return ac_fail(err, errlen, "map[%zu].kind: expected \"cylinder\" or \"flat\"", i);
        }
    } else {
        return ac_fail(err, errlen,
                       "map[%zu]: expected [x, y], [x, y, diameter_m] or "
                       "{\"x\",\"y\",\"diameter_m\",\"kind\"}",
                       i);
    }
    b->x = fx_q16_from_double(v[0]);
    b->y = fx_q16_from_double(v[1]);
    r->d = fx_q16_from_double(v[2]);
    r->flat = flat;
    return 0;
}

/* "uncertainty": the bounds after the last fix (default the configuration's largest), grown
 * over travel_m and turn_deg. */
static int read_unc(json_t *req, const optical_config_t *cfg, optical_unc_t *u, bool *given,
                    char *err, size_t errlen)
{
    json_t *o = json_object_get(req, "uncertainty");
    *given = o != NULL;
    if (!o)
        return 0;
    if (!json_is_object(o))
        return ac_fail(err, errlen, "uncertainty: expected an object");
    const char *k;
    json_t *x;
    json_object_foreach(o, k, x)
    {
        if (strcmp(k, "pos_m") && strcmp(k, "heading_deg") && strcmp(k, "travel_m") &&
            strcmp(k, "turn_deg"))
            return ac_fail(err, errlen, "uncertainty: unknown key \"%.40s\"", k);
    }
    double pos, head, travel, turn;
    char inner[200];
    if (ac_number(o, "pos_m", 0, 1000, false, fx_q16_to_double(cfg->jump_max), &pos, inner,
                  sizeof inner) ||
        ac_number(o, "heading_deg", 0, 179, false, fx_angle_to_deg(cfg->turn_max), &head, inner,
                  sizeof inner) ||
        ac_number(o, "travel_m", 0, 1000, false, 0, &travel, inner, sizeof inner) ||
        ac_number(o, "turn_deg", 0, 179, false, 0, &turn, inner, sizeof inner))
        return ac_fail(err, errlen, "uncertainty.%s", inner);
    u->pos = fx_q16_from_double(pos);
    u->heading = fx_angle_from_deg(head);
    optical_unc_grow(cfg, u, fx_q16_from_double(travel), fx_angle_from_deg(turn));
    return 0;
}

/* The quality of a solved fix (also of a refused one). */
static void set_quality(json_t *resp, const optical_fix_t *f)
{
    ac_set(resp, "quality", f->quality * PER_COUNT, 6);
    ac_set(resp, "err_m", fx_q16_to_double(f->err), 6);
    ac_set(resp, "gate_m", fx_q16_to_double(f->gate), 6);
    ac_set(resp, "resid_deg", f->resid * 360.0 / 65536.0, 4);
    json_object_set_new(resp, "agree", json_integer(f->n_agree));
    json_object_set_new(resp, "dropped", json_integer(f->n_dropped));
}
/* --help: the fields and their units. */
const char agvcalc_fields_fix[] =
    "    map           [[x, y] | [x, y, diameter_m] | {x, y, diameter_m?, kind?}, ...]: 3 to\n"
    "                  32 beacons, m (within +-8191); kind \"cylinder\" (a post) or \"flat\"\n"
    "    approx        {x, y, heading_deg}: the dead-reckoning pose, m and degrees\n"
    "    uncertainty?  {pos_m?, heading_deg?, travel_m?, turn_deg?}: what approx is worth\n"
    "                  (default jump_max_m, turn_max_deg), grown over travel and turn\n"
    "    sightings     [{angle_deg, width_deg, pose?}, ...]: up to 15; angle: degrees CCW\n"
    "                  from the heading; width: apparent angular width, degrees [0, 180];\n"
    "                  pose: the pose latched at the sighting (all sightings or none)\n"
    "    config?       {name: value}: thresholds (docs/optical.md: beacon_diameter_m 0.08,\n"
    "                  window_deg, window_pos_m, range_m, jump_max_m, err_max_m, ...)\n"
    "    -> x, y: m; heading_deg: [0, 360); used: [i, j, k] map indices; identified: the map\n"
    "       index per sighting (-1: none); quality: m per count; widened: widenings used;\n"
    "       err_m, gate_m: the error bound and the gate; resid_deg, agree, dropped, status\n";

int agvcalc_op_fix(json_t *req, json_t *resp, char *err, size_t errlen);

int agvcalc_op_fix(json_t *req, json_t *resp, char *err, size_t errlen)
{
    optical_config_t cfg;
    refl_default_t rd;
    if (read_config(req, &cfg, &rd, err, errlen))
        return -1;
    json_t *jm = json_object_get(req, "map");
    if (!jm)
        return ac_fail(err, errlen, "missing \"map\"");
    if (!json_is_array(jm) || json_array_size(jm) < 3 || json_array_size(jm) > OPTICAL_MAX_BEACONS)
        return ac_fail(err, errlen, "map: expected an array of 3 to %d beacons",
                       OPTICAL_MAX_BEACONS);
    size_t nb = json_array_size(jm);
    optical_xy_t b[OPTICAL_MAX_BEACONS];
    optical_refl_t refl[OPTICAL_MAX_BEACONS];
    for (size_t k = 0; k < nb; k++)
        if (read_beacon(json_array_get(jm, k), k, &rd, &b[k], &refl[k], err, errlen))
            return -1;
    optical_pose_t approx;
    if (read_pose(req, "approx", &approx, err, errlen))
        return -1;
    optical_unc_t unc;
    bool with_unc;
    if (read_unc(req, &cfg, &unc, &with_unc, err, errlen))
        return -1;
    json_t *arr = json_object_get(req, "sightings");
    if (!arr)
        return ac_fail(err, errlen, "missing \"sightings\"");
    if (!json_is_array(arr) || json_array_size(arr) > OPTICAL_MAX_SIGHTINGS)
        return ac_fail(err, errlen, "sightings: expected an array of at most %d objects",
                       OPTICAL_MAX_SIGHTINGS);
    size_t n = json_array_size(arr);
    optical_sighting_t s[OPTICAL_MAX_SIGHTINGS];
    optical_pose_t lat[OPTICAL_MAX_SIGHTINGS] = {{0, 0, 0}};
    size_t with_pose = 0;
    for (size_t i = 0; i < n; i++) {
        json_t *o = json_array_get(arr, i);
        char what[48];
        snprintf(what, sizeof what, "sightings[%zu]", i);
        if (!json_is_object(o))
            return ac_fail(err, errlen, "%s: expected {\"angle_deg\",\"width_deg\"}", what);
        double a, w;
        snprintf(what, sizeof what, "sightings[%zu].angle_deg", i);
        json_t *v = json_object_get(o, "angle_deg");
        if (!v)
            return ac_fail(err, errlen, "missing \"%s\"", what);
        if (ac_number_value(v, what, -1e6, 1e6, &a, err, errlen))
            return -1;
        snprintf(what, sizeof what, "sightings[%zu].width_deg", i);
        v = json_object_get(o, "width_deg");
        if (!v)
            return ac_fail(err, errlen, "missing \"%s\"", what);
        if (ac_number_value(v, what, 0.0, 180.0, &w, err, errlen))
            return -1;
        s[i].angle = fx_angle_from_deg(a);
        double w16 = round(w / 360.0 * 65536.0);
        s[i].width = (uint16_t)(w16 > 65535.0 ? 65535.0 : w16);
        if (json_object_get(o, "pose")) {
            char inner[400];
            if (read_pose(o, "pose", &lat[i], inner, sizeof inner))
                return ac_fail(err, errlen, "sightings[%zu].%s", i, inner);
            with_pose++;
        }
    }
    if (with_pose != 0 && with_pose != n)
        return ac_fail(err, errlen, "sightings: give \"pose\" for every sighting or for none");

    /* The firmware takes the sightings sorted by angle. */
    size_t ord[OPTICAL_MAX_SIGHTINGS];
    for (size_t i = 0; i < n; i++) {
        size_t j = i;
        while (j > 0 && s[ord[j - 1]].angle > s[i].angle) {
            ord[j] = ord[j - 1];
            j--;
        }
        ord[j] = i;
    }
    optical_sighting_t ss[OPTICAL_MAX_SIGHTINGS];
    optical_pose_t sl[OPTICAL_MAX_SIGHTINGS];
    for (size_t j = 0; j < n; j++) {
        ss[j] = s[ord[j]];
        sl[j] = lat[ord[j]];
    }
    optical_xy8_t b8[OPTICAL_MAX_BEACONS];
    optical_map_t map;
    uint8_t bad[2];
    uint32_t dk[OPTICAL_MAX_BEACONS];
    int8_t mst = optical_map_compile(&map, b, refl, (uint8_t)nb, b8, dk, bad);
    if (mst == OPTICAL_E_DEGENERATE)
        return ac_fail(err, errlen,
                       "map[%u] and map[%u] coincide: closer than the sum of their radii", bad[0],
                       bad[1]);
    if (mst != OPTICAL_OK)
        return ac_fail(err, errlen,
                       "map: the beacons must fit within +-128 m of one point (a site of at "
                       "most 256 m by 256 m)");
    optical_fix_t fix;
    int8_t st = optical_fix(&map, &cfg, &approx, with_unc ? &unc : NULL, ss, (uint8_t)n,
                            with_pose ? sl : NULL, &fix);

    json_t *ident = json_array();
    int idx[OPTICAL_MAX_SIGHTINGS];
    for (size_t j = 0; j < n; j++)
        idx[ord[j]] = fix.ident[j];
    for (size_t i = 0; i < n; i++)
        json_array_append_new(ident, json_integer(idx[i]));
    json_object_set_new(resp, "status", json_string(optical_status_name(st)));
    if (st != OPTICAL_OK) {
        json_object_set_new(resp, "identified", ident);
        if (st == OPTICAL_E_FEW)
            return ac_fail(err, errlen, "fewer than 3 beacons identified (%u)", fix.n_ident);
        if (fix.quality != UINT32_MAX)
            set_quality(resp, &fix);
        return ac_fail(err, errlen, "%s", why(st));
    }
    ac_set_pose(resp, fx_q16_to_double(fix.pose.x), fx_q16_to_double(fix.pose.y),
                fx_angle_to_deg(fix.pose.heading));
    json_t *used = json_array();
    for (int i = 0; i < 3; i++)
        json_array_append_new(used, json_integer(fix.used[i]));
    json_object_set_new(resp, "used", used);
    json_object_set_new(resp, "identified", ident);
    set_quality(resp, &fix);
    json_object_set_new(resp, "widened", json_integer(fix.widened));
    return 0;
}
