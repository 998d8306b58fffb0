#!/usr/bin/env python3
"""Real-time factor of the closed-loop harness: runs agv-sim on scenarios several times and
reports the median of simulated seconds per wall second, with every ISR of both boards
running. A benchmark, not a test: the machine's load moves the figure.

  tools/bench_sim.py [--agv build/host/bin/agv-sim] [--runs 5] [scenario.json ...]
"""
import argparse
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--agv", default=os.path.join(ROOT, "build", "host", "bin", "agv-sim"))
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--json", help="also write the figures here")
    ap.add_argument("scenarios", nargs="*")
    a = ap.parse_args()
    scenarios = a.scenarios or sorted(glob.glob(os.path.join(ROOT, "sim", "scenarios", "*.json")))
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for sc in scenarios:
            factors, isr_per_s = [], 0
            for i in range(a.runs):
                rep = os.path.join(tmp, "r.json")
                subprocess.run([a.agv, "--scenario", sc, "--report", rep, "--quiet"],
                               capture_output=True)
                with open(rep) as f:
                    r = json.load(f)
                factors.append(r["sim_time_s"] / max(r["wall_time_s"], 1e-9))
                isr_per_s = sum(r["isr"].values()) / r["sim_time_s"]
            med = statistics.median(factors)
            name = os.path.splitext(os.path.basename(sc))[0]
            results.append({"scenario": name, "sim_time_s": r["sim_time_s"],
                            "realtime_factor_median": round(med), "realtime_factor_min":
                            round(min(factors)), "isr_per_sim_second": round(isr_per_s)})
            print(f"{name:<28} {r['sim_time_s']:7.1f} s simulated, {isr_per_s:6.0f} ISRs per "
                  f"simulated second: median {med:7.0f}x real time (min {min(factors):.0f}x, "
                  f"{a.runs} runs)")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(results, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
