#!/usr/bin/env python3
"""Generate the board images' built-in mission (a C header) from an agv-sim scenario.

The MSP430 images carry one mission in flash so that they run standalone: the beacon map
with each beacon's reflector (diameter, cylinder or flat), the path with its speeds, the start
pose, the vehicle and the sensors; for a scenario in mode `pursuit` also seed 002's pursuit
parameters and the position receiver's (MISSION_PURSUIT_LAW, MISSION_POSRX_CONFIG,
MISSION_POSRX_BAUD, MISSION_PURSUIT_HEADING: the pursuit image, main_board_pursuit.elf). It
comes from a scenario file (the beacon image: the 1987 Table 6-1 run; the pursuit image: seed
002's straight path) so that the simulator and the images agree. With --path, the start pose
and the path come from a tools/dxf2path.py result instead (a drawn path; the scenario gives
the rest).

  tools/gen_mission.py sim/scenarios/table_6_1_1987_full.json -o build/.../mission_builtin.h
  tools/gen_mission.py SCENARIO.json --path PATH.json -o build/.../mission_builtin.h

Exit 2 when two beacons coincide (their posts would overlap), naming both. A pursuit scenario
with two receivers is refused: the board has one receiver line (USCI_A1).
"""
import argparse
import json
import math
import os
import sys

SCHEMA = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs",
                      "schema", "scenario.schema.json")


def q16(v):
    return int(round(v * 65536))


def angle(deg):
    return int(round((deg % 360.0) / 360.0 * 2**32)) % 2**32


def reflector(x, i, src):
    """(diameter_m, flat) of beacons[i], checked as the scenario's schema says."""
    d, kind = x.get("diameter_m"), x.get("kind", "cylinder")
    if not isinstance(d, (int, float)) or not 0.005 <= d <= 2.0:
        sys.exit(f"gen_mission: {src}: beacons[{i}].diameter_m: {d!r} is not in 0.005..2")
    if kind not in ("cylinder", "flat"):
        sys.exit(f"gen_mission: {src}: beacons[{i}].kind: {kind!r} is neither \"cylinder\" "
                 "nor \"flat\"")
    return d, 1 if kind == "flat" else 0


def read_path(filename):
    """start and path of a tools/dxf2path.py result, checked: (start, path)."""
    try:
        with open(filename) as f:
            d = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"gen_mission: --path {filename}: {e}")

    def pose(x, where, speed):
        keys = ("x", "y", "heading_deg") + (("speed_mps",) if speed else ())
        if not isinstance(x, dict):
            sys.exit(f"gen_mission: --path {filename}: {where} is not an object")
        for k in keys:
            if not isinstance(x.get(k), (int, float)) or not math.isfinite(x[k]):
                sys.exit(f"gen_mission: --path {filename}: {where}.{k} missing or not a number")
        return x

    if not isinstance(d, dict) or not isinstance(d.get("path"), list) or not d["path"]:
        sys.exit(f"gen_mission: --path {filename}: expected {{\"start\":{{..}},\"path\":[..]}} "
                 "as tools/dxf2path.py writes it")
    return (pose(d.get("start"), "start", False),
            [pose(x, f"path[{i}]", True) for i, x in enumerate(d["path"])])


def schema():
    with open(SCHEMA) as f:
        return json.load(f)


def blind_distance(sc):
    """The scenario's blind_distance_m, or the schema's default (the one the simulator takes)."""
    if "blind_distance_m" in sc:
        return sc["blind_distance_m"]
    return schema()["properties"]["blind_distance_m"]["default"]


def with_defaults(sc, key):
    """The scenario's object @p key with the schema's defaults for what it leaves out."""
    props = schema()["properties"][key]["properties"]
    out = {k: p["default"] for k, p in props.items() if "default" in p}
    out.update(sc.get(key, {}))
    return out


def lround(v):
    """C's lround: the nearest integer, halves away from zero (as agv-sim rounds)."""
    return int(math.copysign(math.floor(abs(v) + 0.5), v))


def pursuit_lines(sc, v, src):
    """Mode pursuit: the main board's pursuit download as agv-sim builds it (sim/mission.c) for
    one receiver, as C initialisers; [] for the other modes."""
    if sc["mode"] != "pursuit":
        return []
    pu, ps = with_defaults(sc, "pursuit"), with_defaults(sc, "position_source")
    if len(ps.get("receivers", [])) > 1:
        sys.exit(f"gen_mission: {src}: position_source.receivers: two receivers; the board "
                 "image has one receiver line (USCI_A1, hal/uart.h instance 0)")
    heading = {"positions": "MAIN_HEADING_POSITIONS", "nav": "MAIN_HEADING_NAV"}.get(pu["heading"])
    if heading is None:
        sys.exit(f"gen_mission: {src}: pursuit.heading: {pu['heading']!r} needs two receivers")
    steer = lround(math.atan(v["wheelbase_m"] / v["min_radius_m"]) / (2 * math.pi) * 2**32)
    law = [f".speed = {q16(pu['speed_mps'])}l", f".max_speed = {q16(pu['max_speed_mps'])}l",
           f".k = {q16(pu['smoothing_constant'])}l",
           f".activation_ms = {min(lround(pu['activation_s'] * 1000), 65535)}u",
           f".threshold = {q16(pu['threshold_pct'] / 100)}l", f".max_steer = {steer}ul",
           f".slow_after_ms = {lround(pu['slow_after_s'] * 1000)}u",
           f".stop_after_ms = {lround(pu['stop_after_s'] * 1000)}u",
           f".regulate = {'true' if pu['regulate_speed'] else 'false'}",
           f".pair_tol = {q16(pu['pair_tolerance_m'])}l"]
    return ["#define MISSION_PURSUIT_LAW \\", "    { " + ", ".join(law) + " }",
            "#define MISSION_POSRX_CONFIG \\",
            f"    {{ .min_update_mm = {lround(pu['min_update_m'] * 1000)}u, "
            f".max_speed_mm_s = {lround(pu['max_speed_mps'] * 1000)}u }}",
            f"#define MISSION_POSRX_BAUD {ps['baud']}ul",
            f"#define MISSION_PURSUIT_HEADING {heading}"]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario", help="agv-sim scenario (JSON): map, vehicle, sensors, path")
    ap.add_argument("-o", "--output", required=True, help="the C header to write")
    ap.add_argument("--path", metavar="PATH.json",
                    help="take start and path from this tools/dxf2path.py result")
    a = ap.parse_args()
    try:
        with open(a.scenario) as f:
            sc = json.load(f)
    except OSError as e:
        sys.exit(f"gen_mission: {a.scenario}: {e.strerror}")
    except ValueError as e:
        sys.exit(f"gen_mission: {a.scenario}: not JSON: {e}")
    try:
        return write(a, sc)
    except (KeyError, IndexError, TypeError) as e:
        # the scenario follows docs/schema/scenario.schema.json when agv-sim takes it
        sys.exit(f"gen_mission: {a.scenario}: a key missing or of the wrong type: {e!r} "
                 f"(check it with build/host/bin/agv-sim --scenario {a.scenario})")


def write(a, sc):
    """The header of scenario @p sc (a.scenario) into a.output."""
    b, p, v, st, sen = sc["beacons"], sc["path"], sc["vehicle"], sc["start"], sc["sensors"]
    src = a.scenario
    if a.path:
        st, p = read_path(a.path)
        src = f"{a.scenario} with the path of {a.path}"
    if len(p) > 32:
        sys.exit(f"gen_mission: {a.path or a.scenario}: {len(p)} path points, the board image "
                 "holds at most 32" + (" (dxf2path: use a longer --step)" if a.path else ""))
    if len(b) > 32:
        sys.exit(f"gen_mission: {a.scenario}: {len(b)} beacons, the board image holds at most 32")
    refl = [reflector(x, i, a.scenario) for i, x in enumerate(b)]
    # Two reflectors in one place (their posts would overlap): as optical_map_compile() and
    # agv-sim refuse them, with exit 2.
    for i in range(len(b)):
        for j in range(i + 1, len(b)):
            dist = math.hypot(b[i]["x"] - b[j]["x"], b[i]["y"] - b[j]["y"])
            if dist < 0.5 * (refl[i][0] + refl[j][0]):
                print(f"gen_mission: {a.scenario}: beacons[{i}] ({b[i]['x']:g}, {b[i]['y']:g}) "
                      f"and beacons[{j}] ({b[j]['x']:g}, {b[j]['y']:g}) coincide: {dist:.4g} m "
                      f"apart, closer than their radii ({refl[i][0] / 2:g} + "
                      f"{refl[j][0] / 2:g} m)", file=sys.stderr)
                return 2
    out = [f"/* Generated by tools/gen_mission.py from {src}: do not edit. */",
           "#ifndef MISSION_BUILTIN_H", "#define MISSION_BUILTIN_H", "",
           f"#define MISSION_NAME \"{sc['name']}\"",
           f"#define MISSION_FULL_TRAVEL {1 if sc['mode'] == 'full' else 0}",
           f"#define MISSION_WHEELBASE {q16(v['wheelbase_m'])}l",
           f"#define MISSION_MIN_RADIUS {q16(v['min_radius_m'])}l",
           f"#define MISSION_COUNTS {int(sen['goniometer']['counts'])}u",
           f"#define MISSION_DL_Q40 {int(round(sen['odometer']['dl_m'] * 2**40))}ul",
           f"#define MISSION_GYRO_STEP_Q48 "
           f"{int(round(sen['gyro']['step_deg'] / 360.0 * 2**48))}ull",
           # the optical fix's bearing error bounds come from these (OPTICAL_CONFIG)
           f"#define MISSION_GONIO_NOISE {angle(sen['goniometer']['noise_deg'])}ul",
           f"#define MISSION_GYRO_STEP {angle(sen['gyro']['step_deg'])}ul",
           f"#define MISSION_BLIND_DISTANCE {q16(blind_distance(sc))}l",
           f"#define MISSION_START {{{q16(st['x'])}l, {q16(st['y'])}l, "
           f"{angle(st['heading_deg'])}ul}}",
           f"#define MISSION_N_BEACONS {len(b)}u",
           "#define MISSION_BEACONS \\"]
    out.append("    { " + ", ".join(f"{{{q16(x['x'])}l, {q16(x['y'])}l}}" for x in b) + " }")
    # Each beacon's reflector compiled as optical_map_compile() does it (optical_map_t.dk:
    # floor(d 10430 / 2^8) for d in Q16 m, plus 2^31 for a flat strip) and the narrowest.
    dk = [(q16(d) * 10430 >> 8) | (flat << 31) for d, flat in refl]
    out.append("#define MISSION_DK \\")
    out.append("    { " + ", ".join(f"{v}ul" for v in dk) + " }")
    out.append(f"#define MISSION_DKMIN {min(v & 0x7FFFFFFF for v in dk)}ul")
    # The compiled map as optical_map_compile() makes it: the origin the centre of the bounding
    # box floored to whole metres, each beacon floor((b - origin) / 2^8) within 16 bits.
    org = []
    for c in ("x", "y"):
        cs = [q16(x[c]) for x in b]
        o = (min(cs) + ((max(cs) - min(cs)) >> 1)) & ~0xFFFF
        if max(cs) - o >= 1 << 23 or o - min(cs) > 1 << 23:
            sys.exit(f"gen_mission: {a.scenario}: the beacons must fit within +-128 m of one "
                     "point")
        org.append(o)
    out.append(f"#define MISSION_ORIGIN_X {org[0]}l")
    out.append(f"#define MISSION_ORIGIN_Y {org[1]}l")
    out.append("#define MISSION_BEACONS8 \\")
    out.append("    { " + ", ".join(f"{{{(q16(x['x']) - org[0]) >> 8}, {(q16(x['y']) - org[1]) >> 8}}}"
                                    for x in b) + " }")
    out.append(f"#define MISSION_N_PATH {len(p)}u")
    out.append("#define MISSION_PATH \\")
    out.append("    { " + ", ".join(
        f"{{{{{q16(x['x'])}l, {q16(x['y'])}l, {angle(x['heading_deg'])}ul}}, "
        f"{q16(x.get('speed_mps', v['speed_mps']))}l, 0u}}" for x in p) + " }")
    out += pursuit_lines(sc, v, a.scenario)
    out += ["", "#endif", ""]
    with open(a.output, "w") as f:
        f.write("\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
