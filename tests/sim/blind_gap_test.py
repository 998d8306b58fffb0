#!/usr/bin/env python3
"""ctest sim.blind_gap (label sim): dead reckoning through fix gaps in the closed loop.

  blind_gap_test.py AGV_SIM CROSSED.json STOPPED.json

CROSSED (a corridor without visible beacons, shorter than the blind distance): the vehicle
drives more than 4.5 m without an accepted fix (four failed fixes used to end the run after
about 2 m) and reaches its goal. STOPPED (a longer corridor): the vehicle stops with
stop_reason blind_distance, the stop command coming when the travel since the last accepted
fix reaches the blind distance. In both, every double arc's speed follows the law of
docs/drive.md: the path speed times clamp(5/4 - blind / B, 1/4, 1), blind measured here on the
true path from the last accepted fix's instant (a reference independent of the firmware's own
count), and full speed returns after the gap. The blind distance B is the scenario's, or the
schema's default.
"""
import bisect
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SPEED_TOL = 0.04  # m/s: one speed count (0.0176) and the law's slope over the 0.5 m between
#                   the fix's instant, the pose it is counted from and the truth's 50 ms samples


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run(agv, scenario, tmp):
    logs = os.path.join(tmp, os.path.basename(scenario))
    rep = logs + ".report.json"
    r = subprocess.run([agv, "--scenario", scenario, "--log-dir", logs, "--report", rep,
                        "--quiet"], capture_output=True, text=True)
    if r.returncode != 0:
        raise AssertionError(f"{scenario}: agv-sim exited {r.returncode}: {r.stderr.strip()}")
    with open(rep) as f:
        report = json.load(f)
    truth = read(os.path.join(logs, "truth.csv"))
    t = [float(x["t_s"]) for x in truth]
    s = [0.0]
    for a, b in zip(truth, truth[1:]):
        s.append(s[-1] + math.hypot(float(b["x_m"]) - float(a["x_m"]),
                                    float(b["y_m"]) - float(a["y_m"])))

    def s_at(tt):  # distance travelled at time tt, interpolated
        i = max(1, min(bisect.bisect(t, tt), len(t) - 1))
        f = (tt - t[i - 1]) / (t[i] - t[i - 1])
        return s[i - 1] + max(0.0, min(1.0, f)) * (s[i] - s[i - 1])

    fixes = [(float(x["t_s"]), s_at(float(x["ref_t_s"])))
             for x in read(os.path.join(logs, "fixes.csv")) if x["accepted"] == "1"]
    cmds = read(os.path.join(logs, "commands.csv"))
    return report, fixes, cmds, s_at


def blind_limit(scenario):
    with open(scenario) as f:
        sc = json.load(f)
    if "blind_distance_m" in sc:
        return sc, sc["blind_distance_m"]
    with open(os.path.join(ROOT, "docs", "schema", "scenario.schema.json")) as f:
        return sc, json.load(f)["properties"]["blind_distance_m"]["default"]


def check_law(name, sc, limit, fixes, cmds, s_at):
    """Every load's speed against the law; returns (slowest, loads checked)."""
    path_speed = sc["path"][0].get("speed_mps", sc["vehicle"]["speed_mps"])
    times = [f[0] for f in fixes]
    slowest, n = path_speed, 0
    for c in cmds:
        if c["kind"] != "load":
            continue
        tc = float(c["t_s"])
        k = bisect.bisect(times, tc)
        blind = s_at(tc) - fixes[k - 1][1] if k else s_at(tc)
        want = path_speed * min(1.0, max(0.25, 1.25 - blind / limit))
        got = float(c["speed_mps"])
        if abs(got - want) > SPEED_TOL:
            raise AssertionError(f"{name}: the load at {tc:.3f} s, {blind:.2f} m after the last "
                                 f"fix, drives at {got:.4f} m/s; the law gives {want:.4f}")
        slowest = min(slowest, got)
        n += 1
    return slowest, n


def main():
    agv, crossed, stopped = sys.argv[1:4]
    with tempfile.TemporaryDirectory() as tmp:
        sc, limit = blind_limit(crossed)
        report, fixes, cmds, s_at = run(agv, crossed, tmp)
        gap = max(b[1] - a[1] for a, b in zip(fixes, fixes[1:]))
        slowest, n = check_law("crossed", sc, limit, fixes, cmds, s_at)
        print(f"{sc['name']}: {gap:.2f} m without a fix (blind distance {limit:g} m), slowest "
              f"{slowest:.3f} m/s, {n} loads on the law, outcome {report['outcome']}")
        assert report["outcome"] == "goal" and "stop_reason" not in report, report
        assert gap > 4.5, f"crossed: the longest stretch without a fix is only {gap:.2f} m"
        assert slowest < 0.95 * sc["path"][0].get("speed_mps", sc["vehicle"]["speed_mps"])
        last = [c for c in cmds if c["kind"] == "load"][-3]
        assert float(last["speed_mps"]) > 0.98, f"full speed after the gap: {last}"

        sc, limit = blind_limit(stopped)
        report, fixes, cmds, s_at = run(agv, stopped, tmp)
        halt = [float(c["t_s"]) for c in cmds if c["kind"] == "speed" and
                float(c["speed_mps"]) == 0.0]
        assert halt, "stopped: no stop command"
        blind = s_at(halt[0]) - fixes[-1][1]
        slowest, n = check_law("stopped", sc, limit, fixes, cmds, s_at)
        print(f"{sc['name']}: stop commanded {blind:.2f} m after the last fix (blind distance "
              f"{limit:g} m), slowest {slowest:.3f} m/s, {n} loads on the law, outcome "
              f"{report['outcome']} ({report.get('stop_reason')}), at rest "
              f"{s_at(1e9) - fixes[-1][1]:.2f} m after it")
        assert report["outcome"] == "stopped", report
        assert report["stop_reason"] == "blind_distance", report
        assert limit - 0.1 <= blind <= limit + 0.3, f"stopped {blind:.2f} m after the last fix"
        assert slowest < 0.3, f"not slowed to a quarter of the speed: {slowest:.3f} m/s"
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except AssertionError as e:
        print(f"FAIL {e}")
        sys.exit(1)
