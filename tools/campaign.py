#!/usr/bin/env python3
"""The fault campaign: hostile worlds made from one world file, run through agv-sim in
parallel, and what they did to the optical fixes and to how the runs ended (docs/campaign.md).

For every seed and every kind of disturbance (--kinds) the campaign makes a world from the
given scenario: the same building, route and vehicle, disturbed as the kind says, drawn from
a generator seeded with the kind and the seed (the same seed gives the same world), and runs
it with that seed. Kinds:

  undisturbed     the world as it is (the reference for the acceptance)
  glint_beside    2-4 mirror-like glints 5-40 cm beside map beacons
  glint_inline    2-4 glints on the line of sight through a beacon from a point of the
                  route, 0.3-6 m in front of or behind it
  screen          2-4 short walls (0.6-2 m) 0.3-1.5 m in front of beacons, across the line
                  of sight from a point of the route: the beacon is hidden from part of it
  pillars         3-8 pillars (0.2-0.6 m) near the route (at least 1 m from it)
  gonio_noise     goniometer edge noise 0.01-0.04 degrees
  gyro_drift      gyro drift 0.01-0.05 degrees per second, either sign
  worn_wheel      odometer scale 0.985-0.999 (the wheel travels less than the nav board
                  believes)
  index_loss      each index pulse lost with probability 0.05-0.25
  encoder_glitch  odometer pulses lost and spurious ones, each with probability 1e-4-1e-3
  link_loss       on the CAN bus model: 1-3 windows of 0.02-0.1 s in which every board-link
                  frame is lost, one of 0.1-0.5 s in which 1-8 frames are corrupted
                  (error frames and retransmission)
  fix_dropout     1-3 windows of 1-6 s in which the photodetector sees nothing
  all             every disturbance above at once, drawn the same way

Each run's report (outcome, stop_reason) and fixes.csv (every accepted fix's error against
the truth; `beacons`: the map beacons the revolution really saw) give, per kind and overall:
runs, fixes accepted of the fixes possible (revolutions that saw at least three map beacons
and reached the optical pipeline whole: not cut by a lost index pulse, a lost capture or a
latch lost on the link), wrong fixes (accepted more than --wrong-m off), the error's 95th percentile and
maximum over the accepted fixes, and the outcomes with their stop reasons. Printed as a
table on stdout; --json writes everything (the runs too), --plot a PNG.

--assert checks the issue's targets and exits 1 when one is missed: no wrong fix; every run
ends at the goal or stopped with its reason (a run still travelling when its time runs out,
stop_reason duration, does not); the acceptance of fixes possible at least --min-ratio of the
undisturbed world's.

Exit status: 0 done (and the checks met), 1 a check missed, 2 bad input or a run that could
not be made (agv-sim's own bad-input exit).

  tools/campaign.py sim/scenarios/factory_loop.json --seeds 1-40 --jobs 2 \\
      --json build/campaign.json --plot build/campaign.png
"""
import argparse
import csv
import json
import math
import multiprocessing
import os
import random
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KINDS = ["undisturbed", "glint_beside", "glint_inline", "screen", "pillars", "gonio_noise",
         "gyro_drift", "worn_wheel", "index_loss", "encoder_glitch", "link_loss",
         "fix_dropout", "all"]
# fixes.csv status of a revolution that did not reach the pipeline whole (optical_status_t
# OPTICAL_E_REV: lost index pulse or captures, latches lost on the link).
OPTICAL_E_REV = 2
# The schema's room for them (docs/schema/scenario.schema.json).
MAX_SPURIOUS, MAX_OCCLUDERS, MAX_PILLARS, MAX_WINDOWS = 16, 32, 32, 8


# ------------------------------------------------------------------ the route


def route_points(sc, step=0.25):
    """The route as points every @p step m along the polyline start -> path points (the
    double arcs between them stay within a few decimetres of it)."""
    poses = [sc["start"]] + sc["path"]
    pts = []
    for a, b in zip(poses, poses[1:]):
        n = max(1, int(math.hypot(b["x"] - a["x"], b["y"] - a["y"]) / step))
        pts += [(a["x"] + (b["x"] - a["x"]) * i / n, a["y"] + (b["y"] - a["y"]) * i / n)
                for i in range(n)]
    pts.append((poses[-1]["x"], poses[-1]["y"]))
    return pts


def travel_time(sc):
    """Seconds the route takes at its speeds (the polyline's length)."""
    poses = [sc["start"]] + sc["path"]
    t = 0.0
    for a, b in zip(poses, poses[1:]):
        t += math.hypot(b["x"] - a["x"], b["y"] - a["y"]) / b.get("speed_mps",
                                                                   sc["vehicle"]["speed_mps"])
    return t


def seg_dist(p, a, b):
    """Distance from point p to segment a-b."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    l2 = dx * dx + dy * dy
    u = 0.0 if l2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2))
    return math.hypot(a[0] + u * dx - p[0], a[1] + u * dy - p[1])


def near_route(route, p, d):
    return any(math.hypot(q[0] - p[0], q[1] - p[1]) < d for q in route)


def sight(rng, route, beacons, max_range=25.0):
    """A route point and a beacon within max_range of it."""
    for _ in range(200):
        p = rng.choice(route)
        b = rng.choice(beacons)
        d = math.hypot(b["x"] - p[0], b["y"] - p[1])
        if 1.0 < d < max_range:
            return p, b, d
    raise ValueError("no beacon within 25 m of the route")


# ------------------------------------------------------------------ the generators
# Each takes the scenario (a copy, changed in place), its route and a random.Random.


def g_glint_beside(sc, route, rng):
    sp = sc.setdefault("spurious", [])
    for _ in range(rng.randint(2, 4)):
        if len(sp) >= MAX_SPURIOUS:
            break
        b = rng.choice(sc["beacons"])
        r, phi = rng.uniform(0.05, 0.4), rng.uniform(0, 2 * math.pi)
        sp.append({"x": round(b["x"] + r * math.cos(phi), 4),
                   "y": round(b["y"] + r * math.sin(phi), 4),
                   "width_deg": round(rng.uniform(0.01, 0.1), 4)})


def g_glint_inline(sc, route, rng):
    sp = sc.setdefault("spurious", [])
    for _ in range(rng.randint(2, 4)):
        if len(sp) >= MAX_SPURIOUS:
            break
        p, b, d = sight(rng, route, sc["beacons"])
        k = rng.choice([-1, 1]) * rng.uniform(0.3, 6.0)
        k = max(k, -(d - 0.5))  # in front of the beacon, never at the vehicle
        ux, uy = (b["x"] - p[0]) / d, (b["y"] - p[1]) / d
        sp.append({"x": round(b["x"] + k * ux, 4), "y": round(b["y"] + k * uy, 4),
                   "width_deg": round(rng.uniform(0.01, 0.1), 4)})


def g_screen(sc, route, rng):
    occ = sc.setdefault("occluders", [])
    want = rng.randint(2, 4)
    for _ in range(200):
        if want == 0 or len(occ) >= MAX_OCCLUDERS:
            break
        p, b, d = sight(rng, route, sc["beacons"])
        ux, uy = (b["x"] - p[0]) / d, (b["y"] - p[1]) / d
        back, half = rng.uniform(0.3, min(1.5, d - 0.8)), rng.uniform(0.3, 1.0)
        cx, cy = b["x"] - back * ux, b["y"] - back * uy
        a, e = (cx - half * uy, cy + half * ux), (cx + half * uy, cy - half * ux)
        if any(seg_dist(q, a, e) < 0.6 for q in route):
            continue  # it would stand in the vehicle's way
        occ.append({"x1": round(a[0], 4), "y1": round(a[1], 4), "x2": round(e[0], 4),
                    "y2": round(e[1], 4)})
        want -= 1


def g_pillars(sc, route, rng):
    pil = sc.setdefault("pillars", [])
    xs, ys = [q[0] for q in route], [q[1] for q in route]
    want = rng.randint(3, 8)
    for _ in range(500):
        if want == 0 or len(pil) >= MAX_PILLARS:
            break
        dia = rng.uniform(0.2, 0.6)
        p = (rng.uniform(min(xs) - 3, max(xs) + 3), rng.uniform(min(ys) - 3, max(ys) + 3))
        if near_route(route, p, 1.0 + dia / 2) or any(
                math.hypot(b["x"] - p[0], b["y"] - p[1]) < dia / 2 + b["diameter_m"] / 2 + 0.3
                for b in sc["beacons"]):
            continue
        pil.append({"x": round(p[0], 4), "y": round(p[1], 4), "diameter_m": round(dia, 3)})
        want -= 1


def g_gonio_noise(sc, route, rng):
    sc["sensors"]["goniometer"]["noise_deg"] = round(rng.uniform(0.01, 0.04), 5)


def g_gyro_drift(sc, route, rng):
    sc["sensors"]["gyro"]["drift_deg_per_s"] = round(rng.choice([-1, 1]) *
                                                     rng.uniform(0.01, 0.05), 5)


def g_worn_wheel(sc, route, rng):
    sc["sensors"]["odometer"]["scale"] = round(rng.uniform(0.985, 0.999), 5)


def g_index_loss(sc, route, rng):
    sc["sensors"]["goniometer"]["index_loss"] = round(rng.uniform(0.05, 0.25), 4)


def g_encoder_glitch(sc, route, rng):
    sc["sensors"]["odometer"]["missed"] = round(10 ** rng.uniform(-4, -3), 6)
    sc["sensors"]["odometer"]["extra"] = round(10 ** rng.uniform(-4, -3), 6)


def windows(rng, n, lo, hi, t_end):
    out = []
    for _ in range(n):
        d = rng.uniform(lo, hi)
        out.append({"t_s": round(rng.uniform(2.0, max(2.5, t_end - d)), 3),
                    "duration_s": round(d, 3)})
    return sorted(out, key=lambda w: w["t_s"])


def g_link_loss(sc, route, rng):
    # On the CAN bus model: 1-3 windows in which every frame is lost (with the heartbeat
    # period before them, shorter than the boards' silence time: a loss the link must ride
    # out, not a silence) and one in which 1-8 frames are corrupted (error frames, each
    # retransmitted; corrupting every frame for long drives a node bus-off: a silence).
    faults = [{"kind": "drop", "at_s": w["t_s"], "duration_s": w["duration_s"], "count": 0}
              for w in windows(rng, rng.randint(1, 3), 0.02, 0.1, travel_time(sc))]
    faults += [{"kind": "corrupt", "at_s": w["t_s"], "duration_s": w["duration_s"],
                "count": rng.randint(1, 8)}
               for w in windows(rng, 1, 0.1, 0.5, travel_time(sc))]
    sc.setdefault("link", {"bus": "can"})["faults"] = sorted(faults, key=lambda f: f["at_s"])


def g_fix_dropout(sc, route, rng):
    sc["sensors"]["goniometer"]["dropouts"] = windows(rng, rng.randint(1, 3), 1.0, 6.0,
                                                      travel_time(sc))


GENERATORS = {"glint_beside": g_glint_beside, "glint_inline": g_glint_inline,
              "screen": g_screen, "pillars": g_pillars, "gonio_noise": g_gonio_noise,
              "gyro_drift": g_gyro_drift, "worn_wheel": g_worn_wheel,
              "index_loss": g_index_loss, "encoder_glitch": g_encoder_glitch,
              "link_loss": g_link_loss, "fix_dropout": g_fix_dropout}


def make_world(base, kind, seed):
    """The world of @p kind and @p seed made from scenario @p base (not changed)."""
    sc = json.loads(json.dumps(base))
    rng = random.Random(f"{kind}:{seed}")
    route = route_points(sc)
    for name, gen in GENERATORS.items():
        if kind in (name, "all"):
            gen(sc, route, rng)
    sc["name"] = f"{base['name'][:40]}_{kind}"[:63]
    sc["seed"] = seed
    # Slower travel through gaps and outages takes longer: room for it.
    sc["duration_s"] = max(base["duration_s"], math.ceil(2 * travel_time(sc) + 30))
    return sc


# ------------------------------------------------------------------ one run


def run_one(job):
    """Make and run one world; returns its record (or one with "error")."""
    agv, base, kind, seed, workdir = job
    sc = make_world(base, kind, seed)
    d = os.path.join(workdir, f"{kind}_{seed}")
    os.makedirs(d, exist_ok=True)
    path = os.path.join(d, "scenario.json")
    with open(path, "w") as f:
        json.dump(sc, f, indent=1)
    rep = os.path.join(d, "report.json")
    r = subprocess.run([agv, "--scenario", path, "--report", rep, "--log-dir", d, "--quiet"],
                       capture_output=True, text=True)
    rec = {"kind": kind, "seed": seed, "exit": r.returncode}
    if r.returncode not in (0, 1):
        rec["error"] = r.stderr.strip() or f"agv-sim exited {r.returncode}"
        return rec
    with open(rep) as f:
        report = json.load(f)
    errors, possible = [], 0
    with open(os.path.join(d, "fixes.csv")) as f:
        for row in csv.DictReader(f):
            possible += int(row["beacons"]) >= 3 and int(row["status"]) != OPTICAL_E_REV
            if row["accepted"] == "1" and float(row["error_m"]) >= 0:
                errors.append(float(row["error_m"]))
    rec.update(outcome=report["outcome"], stop_reason=report.get("stop_reason"),
               attempted=report["fixes"]["attempted"], accepted=report["fixes"]["accepted"],
               possible=possible, errors_m=errors, sim_time_s=report["sim_time_s"],
               cross_track_max_m=report["path"]["cross_track_m"]["max"])
    return rec


# ------------------------------------------------------------------ figures


def percentile(v, p):
    """Nearest rank, as agv-sim's report; 0 for no values."""
    if not v:
        return 0.0
    v = sorted(v)
    return v[max(1, math.ceil(p * len(v))) - 1]


def summarise(runs, wrong_m):
    """Figures of a group of runs."""
    errors = [e for r in runs for e in r["errors_m"]]
    acc, pos = sum(r["accepted"] for r in runs), sum(r["possible"] for r in runs)
    reasons = {}
    for r in runs:
        if r["outcome"] != "goal":
            reasons[r["stop_reason"]] = reasons.get(r["stop_reason"], 0) + 1
    return {"runs": len(runs), "attempted": sum(r["attempted"] for r in runs),
            "accepted": acc, "possible": pos, "acceptance": acc / pos if pos else 0.0,
            "wrong": sum(e > wrong_m for e in errors),
            "error_p95_m": percentile(errors, 0.95), "error_max_m": max(errors, default=0.0),
            "goal": sum(r["outcome"] == "goal" for r in runs),
            "stopped": sum(r["outcome"] != "goal" for r in runs),
            "stop_reasons": dict(sorted(reasons.items()))}


def table(summary, kinds, wrong_m):
    """The campaign's table (markdown)."""
    head = ("| kind | runs | fixes accepted / possible | acceptance | wrong (> "
            f"{wrong_m * 100:g} cm) | error p95 (mm) | error max (mm) | goal | stopped "
            "(reasons) |")
    lines = [head, "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
    for k in kinds + ["overall"]:
        s = summary[k]
        why = ", ".join(f"{n} {r}" for r, n in s["stop_reasons"].items())
        name = f"**{k}**" if k == "overall" else k
        lines.append(f"| {name} | {s['runs']} | {s['accepted']} / {s['possible']} | "
                     f"{100 * s['acceptance']:.1f} % | {s['wrong']} | "
                     f"{1000 * s['error_p95_m']:.1f} | {1000 * s['error_max_m']:.1f} | "
                     f"{s['goal']} | {s['stopped']}{f' ({why})' if why else ''} |")
    return "\n".join(lines) + "\n"


def plot(summary, kinds, runs, wrong_m, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(3, 1, figsize=(11, 11), sharex=True)
    x = list(range(len(kinds)))
    ref = summary.get("undisturbed", {}).get("acceptance")
    ax[0].bar(x, [100 * summary[k]["acceptance"] for k in kinds], color="tab:blue")
    if ref:
        ax[0].axhline(95 * ref, color="tab:red", ls="--", label="95 % of undisturbed")
        ax[0].legend(loc="lower left")
    ax[0].set_ylabel("fixes accepted of possible (%)")
    ax[0].set_ylim(0, 105)
    for i, k in enumerate(kinds):
        e = [1000 * v for r in runs if r["kind"] == k for v in r["errors_m"]]
        if e:
            ax[1].boxplot([e], positions=[i], widths=0.6, whis=(5, 95), showfliers=True,
                          flierprops={"markersize": 3})
        w = summary[k]["wrong"]
        if w:
            ax[1].annotate(f"{w} wrong", (i, 1000 * summary[k]["error_max_m"]),
                           textcoords="offset points", xytext=(0, 4), ha="center",
                           fontsize=8, color="tab:red")
    ax[1].axhline(1000 * wrong_m, color="tab:red", ls="--", label=f"{wrong_m * 100:g} cm")
    ax[1].set_yscale("log")
    ax[1].set_ylabel("accepted fix error (mm)")
    ax[1].legend(loc="upper left")
    reasons = sorted({r for k in kinds for r in summary[k]["stop_reasons"]})
    bottom = [summary[k]["goal"] for k in kinds]
    ax[2].bar(x, bottom, color="tab:green", label="goal")
    for j, reason in enumerate(reasons):
        h = [summary[k]["stop_reasons"].get(reason, 0) for k in kinds]
        ax[2].bar(x, h, bottom=bottom, label=f"stopped: {reason}",
                  color=plt.cm.Oranges(0.4 + 0.5 * j / max(1, len(reasons))))
        bottom = [b + v for b, v in zip(bottom, h)]
    ax[2].set_ylabel("runs")
    ax[2].legend(loc="lower left", fontsize=8)
    ax[2].set_xticks(x)
    ax[2].set_xticklabels(kinds, rotation=30, ha="right")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


# ------------------------------------------------------------------ the campaign


def seeds_arg(text):
    out = []
    try:
        for part in text.split(","):
            lo, _, hi = part.partition("-")
            out += list(range(int(lo), int(hi or lo) + 1))
    except ValueError:
        out = []
    if not out or min(out) < 0:
        raise argparse.ArgumentTypeError(f"seeds: {text!r} is not like 1-20 or 1,4,9")
    return out


def kinds_arg(text):
    ks = KINDS if text == "all-kinds" else text.split(",")
    bad = [k for k in ks if k not in KINDS]
    if bad:
        raise argparse.ArgumentTypeError(f"unknown kind(s) {', '.join(bad)}; "
                                         f"known: {', '.join(KINDS)}")
    return ks


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("world", help="the scenario the hostile worlds are made from")
    ap.add_argument("--seeds", type=seeds_arg, default=seeds_arg("1-10"),
                    help="seeds: 1-20 or 1,4,9 (default 1-10); one world per kind and seed")
    ap.add_argument("--kinds", type=kinds_arg, default=KINDS,
                    help="comma-separated kinds of disturbance, or all-kinds (the default): "
                    + ", ".join(KINDS))
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                    help="runs in parallel (default: the number of processors)")
    ap.add_argument("--agv", default=os.path.join(ROOT, "build", "host", "bin", "agv-sim"),
                    help="the agv-sim binary (default: build/host/bin/agv-sim)")
    ap.add_argument("--wrong-m", type=float, default=0.05,
                    help="an accepted fix further than this from the truth is wrong, m "
                    "(default 0.05)")
    ap.add_argument("--min-ratio", type=float, default=0.95,
                    help="--assert: smallest acceptance as a share of the undisturbed "
                    "world's (default 0.95)")
    ap.add_argument("--json", metavar="FILE", help="write the summary and every run as JSON")
    ap.add_argument("--plot", metavar="FILE", help="write the plot (PNG)")
    ap.add_argument("--title", default=None, help="the plot's title (default: world and seeds)")
    ap.add_argument("--keep", metavar="DIR",
                    help="keep every world, report and log in DIR (default: a temporary "
                    "directory, removed)")
    ap.add_argument("--assert", dest="check", action="store_true",
                    help="exit 1 unless: no wrong fix, every run ends at the goal or stopped "
                    "with its reason, acceptance at least --min-ratio of the undisturbed "
                    "world's")
    ap.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    a = ap.parse_args()
    if a.jobs < 1 or a.wrong_m <= 0 or not 0 < a.min_ratio <= 1:
        ap.error("--jobs must be at least 1, --wrong-m positive, --min-ratio in (0, 1]")
    if not os.access(a.agv, os.X_OK):
        ap.error(f"--agv {a.agv}: not an executable (build the host preset first)")
    try:
        with open(a.world) as f:
            base = json.load(f)
        route_points(base)
        if not isinstance(base.get("beacons"), list) or not base["beacons"]:
            raise ValueError("no beacons")
    except (OSError, ValueError, KeyError, TypeError) as e:
        print(f"campaign: {a.world}: not a scenario the campaign can use: {e}", file=sys.stderr)
        return 2
    kinds = list(a.kinds)
    if a.check and "undisturbed" not in kinds:
        kinds.insert(0, "undisturbed")  # the acceptance's reference

    workdir = a.keep or tempfile.mkdtemp(prefix="campaign-")
    os.makedirs(workdir, exist_ok=True)
    jobs = [(a.agv, base, k, s, workdir) for k in kinds for s in a.seeds]
    runs = []
    try:
        with multiprocessing.Pool(a.jobs) as pool:
            for i, rec in enumerate(pool.imap_unordered(run_one, jobs), 1):
                runs.append(rec)
                if not a.quiet:
                    what = rec.get("error") or (
                        f"{rec['outcome']}{' (' + rec['stop_reason'] + ')' if rec.get('stop_reason') else ''}"
                        f", {rec['accepted']}/{rec['attempted']} fixes")
                    print(f"campaign: {i}/{len(jobs)} {rec['kind']} seed {rec['seed']}: {what}",
                          file=sys.stderr)
    finally:
        if not a.keep:
            subprocess.run(["rm", "-rf", workdir], check=False)
    failed = [r for r in runs if "error" in r]
    if failed:
        for r in failed:
            print(f"campaign: {r['kind']} seed {r['seed']}: {r['error']}", file=sys.stderr)
        return 2
    order = {k: i for i, k in enumerate(kinds)}
    runs.sort(key=lambda r: (order[r["kind"]], r["seed"]))
    summary = {k: summarise([r for r in runs if r["kind"] == k], a.wrong_m) for k in kinds}
    summary["overall"] = summarise(runs, a.wrong_m)
    print(table(summary, kinds, a.wrong_m), end="")

    checks = []
    if a.check:
        ref = summary["undisturbed"]["acceptance"]
        over = summary["overall"]
        checks = [
            ("no accepted fix more than %g m off" % a.wrong_m, over["wrong"] == 0,
             f"{over['wrong']} wrong fixes, the worst {over['error_max_m']:.3f} m off"),
            ("every run ends at the goal or stopped with its reason",
             all(r["outcome"] == "goal" or (r["stop_reason"] and r["stop_reason"] != "duration")
                 for r in runs),
             ", ".join(f"{r['kind']} seed {r['seed']}: {r['stop_reason']}" for r in runs
                       if r["outcome"] != "goal" and r["stop_reason"] in (None, "duration"))),
            (f"acceptance at least {a.min_ratio:g} of the undisturbed world's",
             over["acceptance"] >= a.min_ratio * ref,
             f"{100 * over['acceptance']:.1f} % against {100 * ref:.1f} % undisturbed"),
        ]
        for name, ok, why in checks:
            print(f"campaign: {'ok  ' if ok else 'FAIL'} {name}" + ("" if ok else f": {why}"))
    if a.json:
        slim = []  # each run's figures, without the list of its errors
        for r in runs:
            e = r["errors_m"]
            slim.append({k: v for k, v in r.items() if k != "errors_m"} |
                        {"wrong": sum(x > a.wrong_m for x in e),
                         "error_p95_m": percentile(e, 0.95), "error_max_m": max(e, default=0.0)})
        with open(a.json, "w") as f:
            json.dump({"world": os.path.relpath(os.path.abspath(a.world), ROOT),
                       "seeds": a.seeds, "kinds": kinds, "wrong_m": a.wrong_m,
                       "min_ratio": a.min_ratio, "summary": summary,
                       "checks": [{"check": n, "ok": ok, "why": "" if ok else why}
                                  for n, ok, why in checks],
                       "runs": slim}, f, indent=1)
    if a.plot:
        title = a.title or (f"{os.path.basename(a.world)}: {len(runs)} runs, seeds "
                            f"{a.seeds[0]}-{a.seeds[-1]}")
        plot(summary, kinds, runs, a.wrong_m, a.plot, title)
    return 1 if any(not ok for _, ok, _ in checks) else 0


if __name__ == "__main__":
    sys.exit(main())
