#!/usr/bin/env python3
"""ctest sim.acceptance_worlds (label sim): the two ways issue 16 saw wrong fixes accepted are
present in these worlds, and refused.

  acceptance_worlds.py AGV_SIM SCENARIO_DIR

- sim/scenarios/glint_beside_beacon.json: the factory loop with beacon-like glints 5-40 cm
  beside map beacons (the fault campaign's glint_beside world of seed 2), dead reckoning close
  to the truth;
- sim/scenarios/screened_turn.json: the factory loop with short walls in front of the beacons
  near the top corners (the campaign's screen world of seed 18), so that the fixes taken while
  turning there (about 40 degrees per second) lean on far beacons.

For each world, a run (with logs) must: reach the goal; accept no fix more than 5 cm off; and
have refused at least one fix attempt whose solution was more than 5 cm off (fixes.csv gives
the error of every solved attempt, accepted or not): the hostile element really produced a
wrong fix, and the acceptance rules refused it. Its twin, the same world without the glints
beside beacons (those within 0.6 m of one) or without the screens (walls within 2 m of a
beacon), produces no such attempt: the wrong candidates are the hostile element's.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

WRONG_M = 0.05


def run(agv, sc, d):
    """Run @p sc in directory @p d: (report, fixes.csv rows)."""
    os.makedirs(d)
    path = os.path.join(d, "scenario.json")
    with open(path, "w") as f:
        json.dump(sc, f)
    r = subprocess.run([agv, "--scenario", path, "--log-dir", d, "--quiet", "--report",
                        os.path.join(d, "report.json")], capture_output=True, text=True)
    if r.returncode not in (0, 1):
        sys.exit(f"acceptance_worlds: {sc['name']}: agv-sim exited {r.returncode}: {r.stderr}")
    with open(os.path.join(d, "report.json")) as f:
        rep = json.load(f)
    with open(os.path.join(d, "fixes.csv")) as f:
        rows = list(csv.DictReader(f))
    return rep, rows


def near_beacon(sc, x, y, dist):
    return any(math.hypot(b["x"] - x, b["y"] - y) < dist for b in sc["beacons"])


def without_glints(sc):
    t = json.loads(json.dumps(sc))
    t["spurious"] = [s for s in sc.get("spurious", []) if not near_beacon(sc, s["x"], s["y"], 0.6)]
    return t


def without_screens(sc):
    t = json.loads(json.dumps(sc))
    t["occluders"] = [o for o in sc.get("occluders", [])
                      if not near_beacon(sc, (o["x1"] + o["x2"]) / 2, (o["y1"] + o["y2"]) / 2, 2.0)]
    return t


# Refusals of a solved fix (docs/optical.md "O6"); the other statuses have no solution.
SOLVED = ("poor", "jump", "turn", "disagree", "singular")


def refused_wrong(rows):
    """Refused attempts with a solution more than WRONG_M off: [(t_s, error_m, reason)]."""
    return [(float(r["t_s"]), float(r["error_m"]), r["reason"]) for r in rows
            if r["accepted"] == "0" and r["reason"] in SOLVED and float(r["error_m"]) > WRONG_M]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    agv, scen = sys.argv[1], sys.argv[2]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, twin_of, removed in (("glint_beside_beacon", without_glints, "spurious"),
                                       ("screened_turn", without_screens, "occluders")):
            with open(os.path.join(scen, name + ".json")) as f:
                sc = json.load(f)
            twin = twin_of(sc)
            if len(twin[removed]) >= len(sc[removed]):
                failures.append(f"{name}: nothing hostile to remove ({removed})")
                continue
            rep, rows = run(agv, sc, os.path.join(tmp, name))
            trep, trows = run(agv, twin, os.path.join(tmp, name + "_twin"))
            acc = [float(r["error_m"]) for r in rows if r["accepted"] == "1"]
            wrong = [e for e in acc if e > WRONG_M]
            caught, twin_caught = refused_wrong(rows), refused_wrong(trows)
            print(f"{name}: {rep['outcome']}, {len(acc)} of {len(rows)} fixes accepted, worst "
                  f"{max(acc) * 1000:.1f} mm; refused with a solution more than 5 cm off: "
                  + (", ".join(f"t {t:.2f} s {e * 100:.1f} cm ({why})" for t, e, why in caught)
                     or "none")
                  + f"; its twin without the {removed} beside beacons: {len(twin_caught)}")
            if rep["outcome"] != "goal":
                failures.append(f"{name}: the run did not reach the goal ({rep.get('stop_reason')})")
            if wrong:
                failures.append(f"{name}: {len(wrong)} accepted fixes more than 5 cm off")
            if not caught:
                failures.append(f"{name}: no wrong candidate was refused: the world does not "
                                f"show the failure mode")
            if twin_caught:
                failures.append(f"{name}: the twin has wrong candidates too: {twin_caught}")
    for f in failures:
        print("FAIL " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
