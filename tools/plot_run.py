#!/usr/bin/env python3
"""Plot an agv-sim run: trajectory (truth, estimate, fixes) against the nominal path and the
beacons, fix errors and cross-track error over time, into one PNG.

Input is either the CSV directory of `agv-sim --log-dir DIR` or an LCM log written by
`lcm-logger` while `agv-sim --lcm URL` ran (decoded with the generated Python types in
build/host/python).

  tools/plot_run.py --log-dir out/run1 -o out/run1.png
  tools/plot_run.py --lcm-log out/run1.lcmlog -o out/run1.png
"""
import argparse
import csv
import math
import os
import sys


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def col(rows, key):
    return [float(r[key]) for r in rows]


def from_csv(d):
    run = {"truth": read_csv(os.path.join(d, "truth.csv")),
           "estimate": read_csv(os.path.join(d, "estimate.csv")),
           "fixes": read_csv(os.path.join(d, "fixes.csv")),
           "path": read_csv(os.path.join(d, "path.csv")),
           "beacons": read_csv(os.path.join(d, "beacons.csv"))}
    if not run["truth"]:
        raise SystemExit(f"plot_run: {d}/truth.csv missing or empty: is it an agv-sim --log-dir?")
    return {
        "truth": (col(run["truth"], "t_s"), col(run["truth"], "x_m"), col(run["truth"], "y_m"),
                  col(run["truth"], "cross_track_m")),
        "estimate": (col(run["estimate"], "x_m"), col(run["estimate"], "y_m")),
        "fixes": [(float(r["t_s"]), float(r["x_m"]), float(r["y_m"]), float(r["error_m"]),
                   r["accepted"] == "1") for r in run["fixes"]],
        "path": (col(run["path"], "x_m"), col(run["path"], "y_m")),
        "beacons": (col(run["beacons"], "x_m"), col(run["beacons"], "y_m")),
    }


def from_lcm(path, types_dir):
    sys.path.insert(0, types_dir)
    try:
        import lcm
        from cyclopion import fix_t, pose_t, truth_t
    except ImportError as e:
        raise SystemExit(f"plot_run: cannot import the LCM types from {types_dir}: {e}")
    t, x, y, ct, ex, ey, fixes = [], [], [], [], [], [], []
    for ev in lcm.EventLog(path, "r"):
        if ev.channel == "CYCLOPION_TRUTH":
            m = truth_t.decode(ev.data)
            t.append(m.utime * 1e-6)
            x.append(m.x)
            y.append(m.y)
            ct.append(m.cross_track_m)
        elif ev.channel == "CYCLOPION_POSE":
            m = pose_t.decode(ev.data)
            ex.append(m.x)
            ey.append(m.y)
        elif ev.channel == "CYCLOPION_FIX":
            m = fix_t.decode(ev.data)
            fixes.append((m.utime * 1e-6, m.x, m.y, m.error_m, m.accepted))
    if not t:
        raise SystemExit(f"plot_run: no CYCLOPION_TRUTH messages in {path}")
    return {"truth": (t, x, y, ct), "estimate": (ex, ey), "fixes": fixes, "path": ([], []),
            "beacons": ([], [])}


def plot(run, out, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(13, 7))
    ax = fig.add_subplot(1, 2, 1)
    px, py = run["path"]
    if px:
        ax.plot(px, py, "-", color="0.6", lw=3, label="nominal path")
    t, x, y, ct = run["truth"]
    ax.plot(x, y, "-", color="tab:blue", lw=1, label="truth")
    ex, ey = run["estimate"]
    if ex:
        ax.plot(ex, ey, ":", color="tab:orange", lw=1, label="nav-board estimate")
    acc = [f for f in run["fixes"] if f[4]]
    if acc:
        ax.plot([f[1] for f in acc], [f[2] for f in acc], ".", color="tab:green", ms=3,
                label="accepted fixes")
    bx, by = run["beacons"]
    if bx:
        ax.plot(bx, by, "k^", ms=6, label="beacons")
    ax.set_aspect("equal")
    ax.set_xlabel("x / m")
    ax.set_ylabel("y / m")
    ax.legend(loc="best", fontsize=8)
    ax.set_title(title)

    ax2 = fig.add_subplot(2, 2, 2)
    if acc:
        ax2.plot([f[0] for f in acc], [1000 * f[3] for f in acc], ".", color="tab:green", ms=3)
    ax2.set_ylabel("fix error / mm")
    ax2.grid(True, alpha=0.3)
    ax3 = fig.add_subplot(2, 2, 4)
    ax3.plot(t, [1000 * c if math.isfinite(c) else float("nan") for c in ct], "-",
             color="tab:blue", lw=0.8)
    ax3.set_ylabel("cross-track / mm")
    ax3.set_xlabel("t / s")
    ax3.grid(True, alpha=0.3)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--log-dir", help="CSV directory written by agv-sim --log-dir")
    src.add_argument("--lcm-log", help="LCM log file written by lcm-logger")
    ap.add_argument("-o", "--output", required=True, help="PNG to write")
    ap.add_argument("--types", default=os.path.join(os.path.dirname(__file__), "..", "build",
                                                    "host", "python"),
                    help="directory of the generated Python LCM types")
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    run = from_csv(args.log_dir) if args.log_dir else from_lcm(args.lcm_log, args.types)
    plot(run, args.output, args.title or os.path.basename(args.log_dir or args.lcm_log))
    print(f"plot_run: wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
