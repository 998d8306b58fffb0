#!/usr/bin/env python3
"""ctest (label sim): agv-sim's work per simulated second does not grow with the path's length.

Measured by deterministic counts, not by time (agv-sim --stats): the factory loop driven once
and eight times (a 550 m route) must examine the same number of nominal path pieces per
cross-track sample, and run the same number of harness events per simulated second; the
longer route has eight times the pieces. Before the grid index, each sample examined every
piece: 12 for the loop, 96 for the eight laps.

  flat_cost.py AGV_SIM FACTORY_LOOP_SCENARIO
"""
import json
import os
import subprocess
import sys
import tempfile


def stats(agv, scenario, tmp):
    r = subprocess.run([agv, "--scenario", scenario, "--quiet", "--stats", "--report",
                        os.path.join(tmp, "r.json")], capture_output=True, text=True, timeout=900)
    if r.returncode not in (0, 1) or "agv-sim: stats " not in r.stderr:
        sys.exit(f"FAIL: agv-sim exited {r.returncode}: {r.stderr.strip()}")
    return json.loads(r.stderr.split("agv-sim: stats ", 1)[1].splitlines()[0])


def main():
    agv, loop_file = sys.argv[1], sys.argv[2]
    with open(loop_file) as f:
        loop = json.load(f)
    with tempfile.TemporaryDirectory() as tmp:
        long = dict(loop, name="factory_loop_x8", path=loop["path"] * 8,
                    duration_s=loop["duration_s"] * 8)
        long_file = os.path.join(tmp, "x8.json")
        with open(long_file, "w") as f:
            json.dump(long, f)
        one, eight = stats(agv, loop_file, tmp), stats(agv, long_file, tmp)
    failures = []
    per = [s["pieces_examined"] / s["samples"] for s in (one, eight)]
    ev = [s["events"] / s["sim_time_s"] for s in (one, eight)]
    print(f"factory loop x1: {one['pieces']} pieces, {per[0]:.3f} examined per sample, "
          f"{ev[0]:.0f} events per simulated second")
    print(f"factory loop x8: {eight['pieces']} pieces, {per[1]:.3f} examined per sample, "
          f"{ev[1]:.0f} events per simulated second ({eight['sim_time_s']:.0f} s simulated)")
    if eight["pieces"] != 8 * one["pieces"]:
        failures.append("the eight laps should have eight times the pieces")
    if eight["sim_time_s"] < 7 * one["sim_time_s"]:
        failures.append("the eight laps did not run to their end")
    if per[1] > 1.05 * per[0]:
        failures.append(f"pieces per sample grew from {per[0]:.3f} to {per[1]:.3f}")
    if per[1] >= one["pieces"] / 2:
        failures.append("samples examine a large part of the path")
    if abs(ev[1] - ev[0]) > 0.05 * ev[0]:
        failures.append(f"events per simulated second moved from {ev[0]:.0f} to {ev[1]:.0f}")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
