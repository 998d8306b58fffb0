#!/usr/bin/env python3
"""Speed of the closed-loop harness: simulated seconds per wall second (the real-time factor)
of agv-sim on every shipped scenario and on routes of 100 m and 1 km made from the factory
loop (its points driven again and again), with every ISR of both boards running. Also the
simulated seconds per CPU second of the run (less moved by the machine's load than the wall
clock) and the nominal path pieces examined per cross-track sample (the work that used to
grow with the path's length); both from agv-sim --stats. Each figure is the median of --runs runs,
or of more when they add up to less than --min-time seconds of the run loop (a scenario of a few
simulated seconds runs for a few milliseconds, which the machine's load moves most); progress
goes to stderr.
A benchmark, not a test: the machine's load moves the wall-clock figures. Build the `host`
preset (optimised) first.

  tools/bench_sim.py [--agv build/host/bin/agv-sim] [--runs 5] [--min-time 0.5] [--json FILE]
                     [--routes 100,1000] [scenario.json ...]
"""
import argparse
import glob
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FLOOR = 2000  # x real time (issue 13)


def route_length(sc):
    """Length of the polyline start -> points (the double arcs are a little longer)."""
    pts = [sc["start"]] + sc["path"]
    return sum(math.hypot(b["x"] - a["x"], b["y"] - a["y"]) for a, b in zip(pts, pts[1:]))


def make_route(loop, metres):
    """The factory loop's points repeated until the route is at least @p metres long."""
    sc = json.loads(json.dumps(loop))
    path = []
    while route_length({"start": loop["start"], "path": path}) < metres:
        path.append(loop["path"][len(path) % len(loop["path"])])
    sc["path"] = path
    length = route_length(sc)
    sc["name"] = f"factory_loop_{metres / 1000:g}km" if metres >= 1000 else \
        f"factory_loop_{metres:g}m"
    sc["duration_s"] = math.ceil(2 * length / loop["vehicle"]["speed_mps"] + 30)
    return sc, length


def run_once(agv, scenario, tmp):
    rep = os.path.join(tmp, "r.json")
    r = subprocess.run([agv, "--scenario", scenario, "--report", rep, "--quiet", "--stats"],
                       capture_output=True, text=True)
    if r.returncode not in (0, 1):
        sys.exit(f"bench_sim: {scenario}: agv-sim exited {r.returncode}: {r.stderr.strip()}")
    with open(rep) as f:
        report = json.load(f)
    stats = json.loads(r.stderr.split("agv-sim: stats ", 1)[1].splitlines()[0])
    return report, stats, stats["cpu_time_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--agv", default=os.path.join(ROOT, "build", "host", "bin", "agv-sim"),
                    help="the agv-sim to measure (default: the host preset's)")
    ap.add_argument("--runs", type=int, default=5, help="runs per scenario at least (median)")
    ap.add_argument("--min-time", type=float, default=0.5, metavar="S",
                    help="more runs (up to 100) until the run loops took S seconds in all")
    ap.add_argument("--routes", default="100,1000",
                    help="lengths (m) of the routes made from the factory loop; '' for none")
    ap.add_argument("--json", help="also write the figures here")
    ap.add_argument("scenarios", nargs="*", help="default: sim/scenarios/*.json")
    a = ap.parse_args()
    if not os.access(a.agv, os.X_OK):
        sys.exit(f"bench_sim: {a.agv}: no agv-sim there (build the host preset: make host)")
    scenarios = a.scenarios or sorted(glob.glob(os.path.join(ROOT, "sim", "scenarios", "*.json")))
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        todo = [(sc, None) for sc in scenarios]
        if a.routes:
            with open(os.path.join(ROOT, "sim", "scenarios", "factory_loop.json")) as f:
                loop = json.load(f)
            for metres in (float(m) for m in a.routes.split(",")):
                sc, length = make_route(loop, metres)
                path = os.path.join(tmp, sc["name"] + ".json")
                with open(path, "w") as f:
                    json.dump(sc, f)
                todo.append((path, length))
        for k, (sc, length) in enumerate(todo):
            name = os.path.splitext(os.path.basename(sc))[0]
            wall, cpu_f = [], []
            spent, i = 0.0, 0
            while i < a.runs or (spent < a.min_time and i < 100):
                i += 1
                print(f"bench_sim: [{k + 1}/{len(todo)}] {name}: run {i}", file=sys.stderr,
                      flush=True)
                r, st, cpu = run_once(a.agv, sc, tmp)
                spent += r["wall_time_s"]
                wall.append(r["sim_time_s"] / max(r["wall_time_s"], 1e-9))
                cpu_f.append(r["sim_time_s"] / max(cpu, 1e-9))
            isr_per_s = sum(r["isr"].values()) / r["sim_time_s"]
            per_sample = st["pieces_examined"] / max(st["samples"], 1)
            row = {"scenario": name, "route_m": round(length) if length else None, "runs": i,
                   "sim_time_s": r["sim_time_s"], "realtime_factor_median": round(
                       statistics.median(wall)), "realtime_factor_min": round(min(wall)),
                   "cpu_factor_median": round(statistics.median(cpu_f)),
                   "isr_per_sim_second": round(isr_per_s), "pieces": st["pieces"],
                   "pieces_per_sample": round(per_sample, 3),
                   "events_per_sim_second": round(st["events"] / r["sim_time_s"])}
            results.append(row)
            route = f"{length:6.0f} m route" if length else "shipped     "
            print(f"{name:<28} {route} {r['sim_time_s']:7.1f} s simulated: median "
                  f"{row['realtime_factor_median']:6d}x real time (min "
                  f"{row['realtime_factor_min']}x), {row['cpu_factor_median']:6d}x per CPU "
                  f"second; {row['pieces']:3d} pieces, {per_sample:5.2f} examined per sample; "
                  f"{isr_per_s:5.0f} ISRs per simulated second"
                  f"{'' if row['realtime_factor_median'] >= FLOOR else '  (below 2,000x)'}",
                  flush=True)
    print(f"at least {a.runs} runs each (more for the short ones, --min-time {a.min_time:g} s); "
          f"floor {FLOOR:,}x real time (issue 13)")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
