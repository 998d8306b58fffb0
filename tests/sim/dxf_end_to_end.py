#!/usr/bin/env python3
"""ctest (label sim): a path drawn in CAD runs end to end, DXF -> tools/dxf2path.py ->
scenario -> agv-sim, for every drawing of sim/paths/ (seed 002's three test paths and the aisle
loop), in the double-arc travel (mode full) and in seed 002's goal-point pursuit (mode pursuit),
each scenario generated here at test time: the vehicle and sensors of the seed-002 scenarios,
eight beacons around the drawing, the path as dxf2path wrote it (poses 1 m apart at most, the
seed's segment size). Each run must follow the scenario schema, reach the goal and meet its
criteria (full: the SPEC's 10 mm mean cross-track error; pursuit: the seed's order of magnitude).

  dxf_end_to_end.py AGV_SIM [DXF...]      (default: sim/paths/*.dxf)
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

import jsonschema

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
CRITERIA = {
    "full": {"cross_track_mean_m": 0.01, "cross_track_max_m": 0.1, "final_error_m": 0.05},
    "pursuit": {"cross_track_mean_m": 0.5, "cross_track_max_m": 1.5, "final_error_m": 2.5,
                "fix_accept_ratio": 0},
}


# The blend arcs' smallest radius: 1.5 times the vehicle's (0.5 m), so that the double arcs
# that bring the vehicle back onto a corner after a fix have room to steer tighter than the
# corner itself (at the vehicle's own minimum a corrected pose on the inside of the corner has
# no double arc to the next point: fault:solve).
MIN_RADIUS_M = 0.75


def scenario(name, mode, drawn):
    with open(os.path.join(ROOT, "sim", "scenarios", "seed002_two_segment.json")) as f:
        base = json.load(f)
    pts = [drawn["start"]] + drawn["path"]
    x0, x1 = min(p["x"] for p in pts) - 1.5, max(p["x"] for p in pts) + 1.5
    y0, y1 = min(p["y"] for p in pts) - 1.5, max(p["y"] for p in pts) + 1.5
    xm, ym = (x0 + x1) / 2, (y0 + y1) / 2
    beacons = [{"x": x, "y": y, "diameter_m": 0.08} for x, y in
               [(x0, y0), (xm, y0 - 0.2), (x1, y0), (x1 + 0.2, ym), (x1, y1), (xm, y1 + 0.2),
                (x0, y1), (x0 - 0.2, ym)]]
    length = sum(((b["x"] - a["x"]) ** 2 + (b["y"] - a["y"]) ** 2) ** 0.5
                 for a, b in zip(pts, pts[1:]))
    sc = {"name": name, "mode": mode, "beacons": beacons, "vehicle": base["vehicle"],
          "start": drawn["start"], "path": drawn["path"], "sensors": base["sensors"],
          "seed": 2002, "duration_s": round(20 + 3 * length), "success": CRITERIA[mode]}
    if mode == "pursuit":
        sc["pursuit"] = {}
        sc["position_source"] = {}
    return sc


def main():
    agv = sys.argv[1]
    drawings = sys.argv[2:] or sorted(glob.glob(os.path.join(ROOT, "sim", "paths", "*.dxf")))
    with open(os.path.join(ROOT, "docs", "schema", "scenario.schema.json")) as f:
        validator = jsonschema.Draft202012Validator(json.load(f))
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        for dxf in drawings:
            stem = os.path.splitext(os.path.basename(dxf))[0]
            out = os.path.join(tmp, stem + ".json")
            r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "dxf2path.py"), dxf,
                                "-o", out, "--step", "1.0", "--speed", "1.0",
                                "--min-radius", str(MIN_RADIUS_M)],
                               capture_output=True, text=True)
            if r.returncode != 0:
                print(f"FAIL {stem}: dxf2path: {r.stderr.strip()}")
                failures += 1
                continue
            with open(out) as f:
                drawn = json.load(f)
            for mode in ("full", "pursuit"):
                sc = scenario(f"{stem}_dxf_{mode}", mode, drawn)
                bad = [e.message for e in validator.iter_errors(sc)]
                file = os.path.join(tmp, f"{stem}_{mode}.json")
                with open(file, "w") as f:
                    json.dump(sc, f, indent=1)
                rep = os.path.join(tmp, f"{stem}_{mode}_report.json")
                run = subprocess.run([agv, "--scenario", file, "--report", rep, "--quiet"],
                                     capture_output=True, text=True, timeout=900)
                if bad or run.returncode != 0:
                    print(f"FAIL {stem} ({mode}): schema {bad}, agv-sim exit {run.returncode}: "
                          f"{run.stderr.strip()}")
                    failures += 1
                    continue
                with open(rep) as f:
                    p = json.load(f)["path"]
                print(f"ok   {stem} ({mode}, {len(drawn['path'])} poses): goal reached, "
                      f"cross-track mean {p['cross_track_m']['mean'] * 1000:.1f} mm, max "
                      f"{p['cross_track_m']['max'] * 1000:.1f} mm")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
