#!/usr/bin/env python3
"""Draw docs/groundnav_straight.svg: position error along a straight that follows a tight
turn, the seed's continuation (previous interval's curvature kept) against the firmware's
(kept for at most the previous interval's length, then straight).

  GNAV_FIGURE_CSV=/tmp/gnav.csv build/host/bin/groundnav_test \\
      --gtest_filter='*StraightContinuation*'
  tools/plot_groundnav.py /tmp/gnav.csv docs/groundnav_straight.svg
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", help="the figure's CSV (GNAV_FIGURE_CSV of groundnav_test)")
    ap.add_argument("svg", help="the figure to write")
    a = ap.parse_args()
    try:
        with open(a.csv, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"plot_groundnav: {a.csv}: {e.strerror}")
    need = ("travel_m", "fw_err_mm", "seed_err_mm")
    missing = [k for k in need if rows and k not in rows[0]]
    if not rows or missing:
        sys.exit(f"plot_groundnav: {a.csv}: no rows, or no column {', '.join(missing)} "
                 f"(columns: {', '.join(rows[0]) if rows else 'none'})")
    t = [float(r["travel_m"]) for r in rows]
    fw = [max(float(r["fw_err_mm"]), 1e-3) for r in rows]
    seed = [max(float(r["seed_err_mm"]), 1e-3) for r in rows]
    fig, ax = plt.subplots(figsize=(7.5, 3.6))
    ax.semilogy(t, seed, label="seed: previous curvature kept (eq. 3.5, 3.6)", color="#c0392b")
    ax.semilogy(t, fw, label="firmware: kept for one interval, then straight", color="#1f618d")
    turn = 0.5 * 3.14159265 / 2 * (1 + (0.762 / 0.5) ** 2) ** 0.5
    ax.axvline(turn, color="grey", lw=0.8, ls="--")
    ax.text(turn * 0.5, 4e-2, "90° turn, R 0.5 m", ha="center", fontsize=8, color="grey")
    ax.text(turn + 1.5, 4e-2, "straight, 3 m", ha="center", fontsize=8, color="grey")
    ax.set_xlabel("front-wheel travel (m)")
    ax.set_ylabel("position error (mm)")
    ax.set_title("Dead reckoning against exact tricycle kinematics (L 0.762 m, dl 0.01 in, 0.25°)",
                 fontsize=9)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(a.svg)
    print(f"plot_groundnav: wrote {a.svg}")


if __name__ == "__main__":
    main()
