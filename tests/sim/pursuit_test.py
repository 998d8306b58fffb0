#!/usr/bin/env python3
"""ctest (label sim): pursuit mode's records and seed 002's future work, from agv-sim's own
outputs (docs/pursuit.md).

- pursuit_troubles (two receivers, dropouts, garbage, corrupted bytes, zeros, wild positions,
  an outage): every kind of refusal happens; the vehicle stands during the outage and goes on
  after it; the goal is reached. The position record (positions.csv) holds every framed
  packet, the error record (path_error.csv) one row per update the pursuit used and the average
  at its end, equal to the report's; each error is recomputed here from the position and the
  goal points (the perpendicular distance to the segment's line).
- pursuit_regulation (max_speed_mps set 35 % high): with regulation the speed measured from
  the truth comes to the one asked for; without it the vehicle runs 26 % slow.
- the same scenario and seed give the same logs (run_scenario.py --twice checks the report).

  pursuit_test.py AGV_SIM SCENARIO_DIR
"""
import copy
import csv
import json
import math
import os
import subprocess
import sys
import tempfile


def run(agv, scenario, tmp, tag):
    rep, logs = os.path.join(tmp, f"{tag}.json"), os.path.join(tmp, tag)
    r = subprocess.run([agv, "--scenario", scenario, "--report", rep, "--log-dir", logs, "--quiet"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, (scenario, r.returncode, r.stderr)
    with open(rep) as f:
        return json.load(f), logs


def rows(logs, name):
    with open(os.path.join(logs, name), newline="") as f:
        return list(csv.DictReader(f))


def goal_points(sc):
    return [(sc["start"]["x"], sc["start"]["y"])] + [(p["x"], p["y"]) for p in sc["path"]]


def troubles(agv, scen_dir, tmp):
    path = os.path.join(scen_dir, "pursuit_troubles.json")
    with open(path) as f:
        sc = json.load(f)
    rep, logs = run(agv, path, tmp, "troubles")
    p = rep["pursuit"]
    r1, r2 = p["receivers"]
    assert rep["path"]["reached_goal"], rep["path"]
    for k in ("zero", "jump", "too_close", "pair"):
        assert r1[k] > 0, (k, r1)
    assert r1["resyncs"] > 0 and r2["resyncs"] > 0, (r1, r2)
    assert p["stops"] >= 1 and p["resumes"] >= 1, p
    assert p["source"]["outage"] > 0 and p["source"]["wilds"] > 0, p["source"]

    # the vehicle stands during the outage (once stop_after_s has passed since the last
    # position, which was lag_s old) and moves again after it
    out = sc["position_source"]["outages"][0]
    stop_after = sc["pursuit"]["stop_after_s"]
    truth = rows(logs, "truth.csv")
    still = [float(r["t_s"]) for r in truth
             if out["from_s"] + stop_after + 0.6 <= float(r["t_s"]) <= out["to_s"]]
    assert still and all(abs(float(r["speed_mps"])) < 1e-9 for r in truth
                         if float(r["t_s"]) in still), "the vehicle stands in the outage"
    assert any(abs(float(r["speed_mps"])) > 0.5 for r in truth
               if float(r["t_s"]) > out["to_s"] + sc["position_source"]["lag_s"]), \
        "and goes on when positions come back"

    # the seed's records
    pos = rows(logs, "positions.csv")
    assert len(pos) == r1["framed"] + r2["framed"], (len(pos), r1, r2)
    reasons = {}
    for r in pos:
        reasons[(r["receiver"], r["reason"])] = reasons.get((r["receiver"], r["reason"]), 0) + 1
    assert reasons.get(("1", "pair"), 0) == r1["pair"], reasons
    assert reasons.get(("1", "jump"), 0) == r1["jump"], reasons
    err = rows(logs, "path_error.csv")
    assert err[-1]["t_s"] == "average", err[-1]
    body = err[:-1]
    assert len(body) == p["updates"], (len(body), p["updates"])
    mean = sum(float(r["error_m"]) for r in body) / len(body)
    assert abs(float(err[-1]["error_m"]) - mean) < 2e-6, (err[-1], mean)
    assert abs(p["path_error_m"]["mean"] - mean) < 2e-6, (p["path_error_m"], mean)
    # each error from its position (receiver 1's, accepted, at the same instant) and segment
    g = goal_points(sc)
    used = {r["t_s"]: r for r in pos if r["receiver"] == "1" and r["accepted"] == "1"}
    checked = 0
    for r in body:
        q = used.get(r["t_s"])
        if q is None:
            continue
        (ax, ay), (bx, by) = g[int(r["segment"]) - 1], g[int(r["segment"])]
        x, y = float(q["x_m"]), float(q["y_m"])
        d = abs((x - ax) * (by - ay) - (y - ay) * (bx - ax)) / math.hypot(bx - ax, by - ay)
        assert abs(d - float(r["error_m"])) < 1e-4, (r, q, d)
        checked += 1
    assert checked > 0.8 * len(body), (checked, len(body))
    print(f"pursuit_troubles: refusals {r1}, stops {p['stops']}, resumes {p['resumes']}, "
          f"{checked} errors recomputed, average {mean:.4f} m")


def regulation(agv, scen_dir, tmp):
    path = os.path.join(scen_dir, "pursuit_regulation.json")
    with open(path) as f:
        sc = json.load(f)
    rep, logs = run(agv, path, tmp, "reg")
    assert rep["path"]["reached_goal"] and rep["pursuit"]["regulations"] > 3, rep["pursuit"]
    truth = rows(logs, "truth.csv")
    late = [float(r["speed_mps"]) for r in truth if 8.0 <= float(r["t_s"]) <= 11.0]
    assert late and all(abs(v - 1.0) < 0.02 for v in late), late
    off = copy.deepcopy(sc)
    off["pursuit"]["regulate_speed"] = False
    off_path = os.path.join(tmp, "reg_off.json")
    with open(off_path, "w") as f:
        json.dump(off, f)
    rep2, logs2 = run(agv, off_path, tmp, "reg_off")
    # 1.0 x 127 / 3.0 = 42.3 counts of 1.755 cm/s
    v = [float(r["speed_mps"]) for r in rows(logs2, "truth.csv") if 2.0 <= float(r["t_s"]) <= 8.0]
    want = round(1.0 * 127 / 3.0) * 1150 / 65536
    assert v and all(abs(x - want) < 1e-3 for x in v), (v[:5], want)
    print(f"pursuit_regulation: {late[-1]:.4f} m/s with regulation ({rep['pursuit']['regulations']} "
          f"steps), {v[-1]:.4f} m/s without")


def main():
    agv, scen_dir = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        troubles(agv, scen_dir, tmp)
        regulation(agv, scen_dir, tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
