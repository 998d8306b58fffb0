#!/usr/bin/env python3
"""How fast dead reckoning drifts away from the truth after an optical fix, and the blind
distance that drift allows (docs/drive.md, "Dead reckoning through fix gaps").

Runs agv-sim on a scenario (default: the factory loop) once per seed and dropout window: the
photodetector is blinded for --window seconds starting at each of --starts, so that the
vehicle drives on dead reckoning for many metres at different places of the route (straights
and turns), with the blind distance lifted out of the way. From each run's logs
(truth.csv, estimate.csv: every 50 ms; fixes.csv) it takes the drift since the last accepted
fix: the error vector of dead reckoning (estimate minus truth) minus the one it had when the
nav board installed that fix, against the distance travelled since (the fix's own error
cancels; its heading error and everything dead reckoning adds do not), over the blind windows
only (between fixes a late installation would count a fix's correction as drift). It prints the worst
drift in each metre of distance, and the longest whole number of metres whose worst drift
stays within --budget: the blind distance the measurement supports.

  tools/blind_drift.py [--agv build/host/bin/agv-sim] [--scenario FILE] [--seeds 1-12]
                       [--starts 3,13,23,33,43,53] [--window 14] [--budget 0.02]
                       [--jobs N] [--json FILE] [--check-default] [--doc FILE | --check-doc FILE]

--check-default exits 1 unless the scenario schema's default blind_distance_m is within the
supported distance. --doc writes the table (with the command that measured it) between the
markers <!-- blind-drift-table --> and <!-- end blind-drift-table --> of a document;
--check-doc exits 1 when that table differs from the measurement (the runs are deterministic).
The test sim.blind_drift runs --check-default --check-doc docs/drive.md with the parameters
written in the document's table.
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCHEMA = os.path.join(ROOT, "docs", "schema", "scenario.schema.json")
INSTALL_S = 0.005  # the nav board installs a fix within a few ms of its computation
BLOCK = re.compile(r"(<!-- blind-drift-table -->\n)(.*?)(<!-- end blind-drift-table -->)", re.S)


def seeds_arg(text):
    """'1-6' or '1,4,9' -> [1, ...]."""
    out = []
    for part in text.split(","):
        lo, _, hi = part.partition("-")
        out += list(range(int(lo), int(hi or lo) + 1))
    if not out or min(out) < 0:
        raise argparse.ArgumentTypeError(f"bad seed list {text!r}")
    return out


def floats_arg(text):
    try:
        return [float(x) for x in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"bad list of numbers {text!r}") from None


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def one_run(job):
    """(seed, start) -> [(distance since the fix, drift)] of every 50 ms sample."""
    agv, scenario, seed, start, window, tmp = job
    with open(scenario) as f:
        sc = json.load(f)
    sc["blind_distance_m"] = 1000.0
    sc["sensors"]["goniometer"]["dropouts"] = [{"t_s": start, "duration_s": window}]
    sc["duration_s"] = max(sc["duration_s"], start + window + 60)
    d = os.path.join(tmp, f"run_{seed}_{start:g}")
    os.makedirs(d)
    path = os.path.join(d, "scenario.json")
    with open(path, "w") as f:
        json.dump(sc, f)
    r = subprocess.run([agv, "--scenario", path, "--seed", str(seed), "--log-dir", d, "--quiet",
                        "--report", os.path.join(d, "report.json")], capture_output=True,
                       text=True)
    if r.returncode not in (0, 1):
        raise RuntimeError(f"seed {seed} window at {start:g} s: agv-sim exited {r.returncode}: "
                           f"{r.stderr.strip()}")
    truth, est = read(os.path.join(d, "truth.csv")), read(os.path.join(d, "estimate.csv"))
    fixes = [float(x["t_s"]) for x in read(os.path.join(d, "fixes.csv")) if x["accepted"] == "1"]
    out, k, e0, s0, s, prev = [], 0, None, 0.0, 0.0, None
    for t, e in zip(truth, est):
        x, y = float(t["x_m"]), float(t["y_m"])
        if prev:
            s += math.hypot(x - prev[0], y - prev[1])
        prev = (x, y)
        err = (float(e["x_m"]) - x, float(e["y_m"]) - y)
        tt = float(t["t_s"])
        installed = False
        while k < len(fixes) and fixes[k] + INSTALL_S <= tt:
            k += 1
            installed = True
        if installed:
            e0, s0 = err, s
        if k < len(fixes) and fixes[k] <= tt:
            continue  # a fix computed just before this sample may be installed in it or not
        if e0 is not None and start <= tt <= start + window:  # blind: no fix can come
            out.append((s - s0, math.hypot(err[0] - e0[0], err[1] - e0[1])))
    return out


def measure(a):
    """Worst drift per metre bin over every run: {bin: drift}."""
    worst = {}
    with tempfile.TemporaryDirectory() as tmp:
        jobs = [(a.agv, a.scenario, seed, start, a.window, tmp) for seed in a.seeds
                for start in a.starts]
        with ProcessPoolExecutor(a.jobs) as ex:
            for i, samples in enumerate(ex.map(one_run, jobs), 1):
                print(f"blind_drift: {i}/{len(jobs)} runs", file=sys.stderr)
                for dist, drift in samples:
                    b = int(dist)
                    worst[b] = max(worst.get(b, 0.0), drift)
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--agv", default=os.path.join(ROOT, "build", "host", "bin", "agv-sim"),
                    help="the agv-sim binary (default: build/host/bin/agv-sim)")
    ap.add_argument("--scenario", default=os.path.join(ROOT, "sim", "scenarios",
                                                       "factory_loop.json"),
                    help="the world and route (default: sim/scenarios/factory_loop.json)")
    ap.add_argument("--seeds", type=seeds_arg, default=seeds_arg("1-12"),
                    help="seeds, e.g. 1-4 or 1,3,5 (default 1-12)")
    ap.add_argument("--starts", type=floats_arg, default=floats_arg("3,13,23,33,43,53"),
                    help="start times of the dropout window, s (default 3,13,23,33,43,53)")
    ap.add_argument("--window", type=float, default=14.0,
                    help="length of the dropout window, s (default 14)")
    ap.add_argument("--budget", type=float, default=0.02,
                    help="largest drift allowed at the blind distance, m (default 0.02)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="runs in parallel (default: the number of processors)")
    ap.add_argument("--json", metavar="FILE", help="also write the figures as JSON")
    ap.add_argument("--check-default", action="store_true",
                    help="exit 1 unless the schema's default blind_distance_m is supported")
    docs = ap.add_mutually_exclusive_group()
    docs.add_argument("--doc", metavar="FILE",
                      help="write the table between the blind-drift-table markers of FILE")
    docs.add_argument("--check-doc", metavar="FILE",
                      help="exit 1 when the table in FILE differs from the measurement")
    a = ap.parse_args()
    if a.window <= 0 or a.budget <= 0 or a.jobs < 1:
        ap.error("--window, --budget and --jobs must be positive")
    if not os.access(a.agv, os.X_OK):
        ap.error(f"--agv {a.agv}: not an executable (build the host preset first)")
    try:
        worst = measure(a)
    except RuntimeError as e:
        print(f"blind_drift: {e}", file=sys.stderr)
        return 2
    if not worst:
        print("blind_drift: no fix was ever accepted: nothing to measure", file=sys.stderr)
        return 2
    # Supported: the longest whole distance d with every drift below d within the budget
    # (the last metre bin is not full: it does not count).
    supported, running = 0, 0.0
    lines = ["| distance since the fix (m) | worst drift (mm) | worst so far, per metre (mm/m) |",
             "| --- | ---: | ---: |"]
    for b in range(max(worst) + 1):
        running = max(running, worst.get(b, 0.0))
        lines.append(f"| {b}-{b + 1} | {worst.get(b, 0.0) * 1000:.1f} | "
                     f"{running / (b + 1) * 1000:.2f} |")
        if running <= a.budget and supported == b and b < max(worst):
            supported = b + 1
    with open(SCHEMA) as f:
        default = json.load(f)["properties"]["blind_distance_m"]["default"]
    scen = os.path.relpath(os.path.abspath(a.scenario), ROOT)
    seeds = f"{a.seeds[0]}-{a.seeds[-1]}" if a.seeds == list(range(a.seeds[0], a.seeds[-1] + 1)) \
        else ",".join(map(str, a.seeds))
    text = (f"`tools/blind_drift.py --scenario {scen} --seeds {seeds} --starts "
            f"{','.join(f'{s:g}' for s in a.starts)} --window {a.window:g} --budget "
            f"{a.budget:g}`: {len(a.seeds) * len(a.starts)} runs.\n\n" + "\n".join(lines) +
            f"\n\nBlind distance supported by a drift budget of {a.budget * 1000:g} mm: "
            f"{supported} m; the default blind_distance_m: {default:g} m.\n")
    print(text, end="")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"budget_m": a.budget, "supported_m": supported, "default_m": default,
                       "worst_drift_m": {str(b): worst[b] for b in sorted(worst)},
                       "seeds": a.seeds, "starts_s": a.starts, "window_s": a.window}, f,
                      indent=1)
    rc = 0
    if a.check_default and default > supported:
        print(f"blind_drift: the default blind distance {default:g} m is longer than the "
              f"{supported} m the measured drift supports", file=sys.stderr)
        rc = 1
    doc = a.doc or a.check_doc
    if doc:
        with open(doc) as f:
            old = f.read()
        new, n = BLOCK.subn(lambda m: m.group(1) + text + m.group(3), old)
        if n != 1:
            print(f"blind_drift: {doc}: no blind-drift-table markers", file=sys.stderr)
            return 2
        if a.doc and new != old:
            with open(doc, "w") as f:
                f.write(new)
        elif a.check_doc and new != old:
            print(f"blind_drift: {doc}: the drift table differs from the measurement (run "
                  f"tools/blind_drift.py with its parameters and --doc {doc})", file=sys.stderr)
            rc = 1
    return rc


if __name__ == "__main__":
    sys.exit(main())
