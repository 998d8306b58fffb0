#!/usr/bin/env python3
"""The board link's figures, measured with agv-sim on the CAN bus model (README "Board link").

For each bit rate (125, 250, 500 kbit/s) it runs:
  - the 1987 run in full travel at 1 m/s (sim/scenarios/table_6_1_1987_full.json): the bus
    load, and the worst latency of a FIX and of a POSE (from the sender queueing the first
    frame to the end of the last one on the bus);
  - the same with a bus-off of each board (sim/scenarios/can_busoff.json's faults): the longest
    time from a board's bus-off to its recovery;
  - seed 002's straight path at 1 m/s (sim/scenarios/seed002_straight.json) where, from an
    instant T on, every frame of the nav board is lost (the main board stops the drive:
    link_silent), or every frame of the main board (the nav board asks for the stop:
    nav_link_silent): the time from T to the stop and to the vehicle's standstill, the worst
    over T = SILENT_FROM, + 50 ms, ... (ten instants: a revolution of the goniometer, ten
    phases of the heartbeat). The vehicle stands when it has braked to 0 (0.5 m/s^2) or when
    the double arc it was given ends, whichever comes first.
and prints the table (Markdown). With --readme FILE it rewrites the table between the markers
<!-- link-figures --> and <!-- end link-figures --> there; with --check it exits 1 when that
table is not what the runs give (ctest docs.link_figures).

  tools/link_figures.py --agv-sim build/host/bin/agv-sim
  tools/link_figures.py --agv-sim build/host/bin/agv-sim --readme README.md [--check]
"""
import argparse
import copy
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENARIOS = os.path.join(ROOT, "sim", "scenarios")
RATES = (125000, 250000, 500000)
SILENT_FROM = 1.5  # s: the straight path is cruised at 1 m/s from 0.4 s to 4.5 s
SILENT_STEPS = 10
BEGIN, END = "<!-- link-figures -->", "<!-- end link-figures -->"


def load(name):
    with open(os.path.join(SCENARIOS, name)) as f:
        return json.load(f)


def run(agv, scenario, tmp, tag):
    path = os.path.join(tmp, tag + ".json")
    with open(path, "w") as f:
        json.dump(scenario, f)
    rep = os.path.join(tmp, tag + "_report.json")
    r = subprocess.run([agv, "--scenario", path, "--report", rep, "--quiet"],
                       capture_output=True, text=True, timeout=900)
    if r.returncode not in (0, 1):
        sys.exit(f"link_figures: {tag}: agv-sim exited {r.returncode}: {r.stderr.strip()}")
    with open(rep) as f:
        return json.load(f)


def with_link(sc, rate, faults=None, name=None):
    sc = copy.deepcopy(sc)
    sc["link"] = {"bitrate_bps": rate, "faults": faults or []}
    sc["success"] = {"reach_goal": False, "final_error_m": 100}
    if name:
        sc["name"] = name
    return sc


def figures(agv):
    full, busoff, straight = (load(n) for n in ("table_6_1_1987_full.json", "can_busoff.json",
                                                "seed002_straight.json"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for rate in RATES:
            k = rate // 1000
            r = run(agv, with_link(full, rate), tmp, f"full_{k}")
            if r["outcome"] != "goal":
                sys.exit(f"link_figures: the full travel at {k} kbit/s did not reach its goal")
            b = run(agv, with_link(full, rate, busoff["link"]["faults"]), tmp, f"busoff_{k}")
            if b["link"]["recoveries"] < 2:
                sys.exit(f"link_figures: {k} kbit/s: {b['link']['recoveries']} recoveries, not 2")
            silent = {}
            for who, reason in (("nav", "link_silent"), ("main", "nav_link_silent")):
                worst = (0.0, 0.0)
                for i in range(SILENT_STEPS):
                    t = SILENT_FROM + 0.05 * i
                    s = run(agv, with_link(straight, rate, [{"kind": "drop", "at_s": t,
                                                             "duration_s": 100, "node": who,
                                                             "count": 0}]), tmp,
                            f"{who}_{k}_{i}")
                    if s.get("stop_reason") != reason or "standstill_at_s" not in s:
                        sys.exit(f"link_figures: {k} kbit/s, {who} silent at {t:.2f} s: "
                                 f"stopped for {s.get('stop_reason')}, not {reason}")
                    worst = (max(worst[0], s["stop_at_s"] - t),
                             max(worst[1], s["standstill_at_s"] - t))
                silent[who] = worst
            lat = r["link"]["latency_ms"]
            # Alone on the bus: FIX is two 8-byte frames, POSE an 8-byte and a 6-byte frame
            # (55 + 10 s bits each, worst-case stuffing).
            rows.append((k, r["link"]["bus_load"], r["link"]["frames"] / r["sim_time_s"],
                         lat["FIX"], (135 + 135) * 1e3 / rate, lat["POSE"],
                         (135 + 115) * 1e3 / rate, b["link"]["recovery_ms_max"], 1408e3 / rate,
                         silent["nav"], silent["main"]))
    return rows


def table(rows):
    out = ["| bit rate | bus load, full travel at 1 m/s | frames/s | FIX latency, worst (alone) "
           "| POSE latency, worst (alone) | bus-off to recovery, worst (minimum) | nav board "
           "silent: to the stop / to standstill, worst | main board silent: the same |",
           "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for k, load, fps, fix, fix1, pose, pose1, rec, rec_min, nav, main in rows:
        out.append(f"| {k} kbit/s | {100 * load:.2f} % | {fps:.0f} | {fix:.3f} ms "
                   f"({fix1:.2f} ms) | {pose:.3f} ms ({pose1:.2f} ms) | {rec:.2f} ms "
                   f"({rec_min:.2f} ms) | {nav[0]:.3f} s / {nav[1]:.2f} s | "
                   f"{main[0]:.3f} s / {main[1]:.2f} s |")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--agv-sim", required=True, help="the agv-sim to run")
    ap.add_argument("--readme", help="rewrite the table between the markers in this file")
    ap.add_argument("--check", action="store_true",
                    help="with --readme: exit 1 when its table is stale, change nothing")
    a = ap.parse_args()
    text = table(figures(a.agv_sim))
    if not a.readme:
        sys.stdout.write(text)
        return 0
    with open(a.readme) as f:
        doc = f.read()
    if BEGIN not in doc or END not in doc:
        sys.exit(f"link_figures: {a.readme}: no {BEGIN} ... {END} block")
    head, rest = doc.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    new = head + BEGIN + "\n" + text + END + tail
    if a.check:
        if new != doc:
            print(f"link_figures: {a.readme}: the table is stale; the runs give:\n{text}")
            return 1
        print(f"link_figures: {a.readme}: the table is what the runs give")
        return 0
    with open(a.readme, "w") as f:
        f.write(new)
    print(f"link_figures: {a.readme}: table rewritten")
    return 0


if __name__ == "__main__":
    sys.exit(main())
