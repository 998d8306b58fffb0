#!/usr/bin/env python3
"""ctest sim.tickless (label sim): the tickless harness gives the run the ticked one gives.

agv-sim is tickless by default: a board's main loop runs when its interrupts wake it and at
the deadlines it states (hal_clock_wake_at()), not at every 1 ms tick. That is only right if
every main loop states every deadline it waits on. This test runs every scenario given twice,
with --ticks (every board's clock interrupt every simulated millisecond, as on the MSP430) and
without, and requires the same report (wall time aside: the interrupt counts included, since
the report counts the ticks the boards' timers took) and, for the first scenario, the same
logs byte for byte. A deadline some main loop forgot shows up as a difference, named here.

  tickless_test.py AGV_SIM SCENARIO.json...
"""
import filecmp
import json
import os
import subprocess
import sys
import tempfile

VARIES = ("wall_time_s", "realtime_factor")


def run(agv, scenario, out, ticks, logs=None):
    cmd = [agv, "--scenario", scenario, "--report", out, "--quiet"]
    if ticks:
        cmd.append("--ticks")
    if logs:
        cmd += ["--log-dir", logs]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode not in (0, 1):
        sys.exit(f"FAIL {scenario}: agv-sim {' '.join(cmd[1:])} exited {r.returncode}: "
                 f"{r.stderr.strip()}")
    with open(out) as f:
        rep = json.load(f)
    for k in VARIES:
        rep.pop(k, None)
    return r.returncode, rep


def differences(a, b, path=""):
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            out += differences(a.get(k), b.get(k), f"{path}.{k}" if path else k)
        return out
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        out = []
        for i, (x, y) in enumerate(zip(a, b)):
            out += differences(x, y, f"{path}[{i}]")
        return out
    return [] if a == b else [f"{path}: ticked {a!r}, tickless {b!r}"]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    agv, scenarios = sys.argv[1], sys.argv[2:]
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for k, sc in enumerate(scenarios):
            name = os.path.splitext(os.path.basename(sc))[0]
            logs = [os.path.join(tmp, "ticked"), os.path.join(tmp, "tickless")] if k == 0 \
                else [None, None]
            ea, a = run(agv, sc, os.path.join(tmp, "a.json"), True, logs[0])
            eb, b = run(agv, sc, os.path.join(tmp, "b.json"), False, logs[1])
            diff = differences(a, b)
            if ea != eb:
                diff.insert(0, f"exit status: ticked {ea}, tickless {eb}")
            if logs[0]:
                names = sorted(os.listdir(logs[0]))
                if names != sorted(os.listdir(logs[1])):
                    diff.append(f"log files: {names} against {sorted(os.listdir(logs[1]))}")
                _, mismatch, errors = filecmp.cmpfiles(logs[0], logs[1], names, shallow=False)
                diff += [f"log {n} differs" for n in mismatch + errors]
            if not a["isr"].get("nav.clock_tick"):
                diff.append("the report counts no clock tick: the tick count is not checked")
            print(f"tickless: [{k + 1}/{len(scenarios)}] {name}: "
                  f"{'same run' if not diff else 'DIFFERENT'}", flush=True)
            for d in diff[:10]:
                print(f"  {d}")
            failed += bool(diff)
    if failed:
        print(f"FAIL: {failed} of {len(scenarios)} scenarios run differently without the ticks "
              "(a main loop does not state a deadline it waits on: hal_clock_wake_at())")
        return 1
    print(f"tickless: {len(scenarios)} scenarios, the same runs with and without the ticks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
