#!/usr/bin/env python3
"""Plot an agv-sim run into one PNG: the map (walls, glints, beacons: used in fixes or not,
screened by a wall or not; the nominal path, the truth, the nav board's estimate, accepted and
rejected fixes), the same map with every deviation from the nominal path magnified, and three
panels on one time axis: cross-track error, estimate minus truth, fix errors. Legends sit
beside the maps, never over them.

Input is either the CSV directory of `agv-sim --log-dir DIR` or an LCM log written by
`lcm-logger` while `agv-sim --lcm URL` ran (decoded with the generated Python types in
build/host/python; the world and the nominal path are not on LCM, so that plot has the
tracks and the time panels only).

  tools/plot_run.py --log-dir out/run1 -o out/run1.png
  tools/plot_run.py --lcm-log out/run1.lcmlog -o out/run1.png
  tools/plot_run.py --log-dir out/run1 -o out/run1.png --magnify 50 --points marks.json

--points: a JSON list of points to mark on both maps, {"label", "x", "y"} (metres) and
optionally matplotlib's "marker", "color", "mfc", "ms", a "text" beside it and "magnify":
false to leave it out of the magnified map (tools/demo.py
marks Table 6-1's prescribed points, the 1987 run's actual ones and ours so).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plotting  # noqa: E402


def read_points(path):
    try:
        with open(path) as f:
            points = json.load(f)
    except OSError as e:
        raise plotting.InputError(f"{path}: {e.strerror}")
    except ValueError as e:
        raise plotting.InputError(f"{path}: not JSON: {e}")
    if not isinstance(points, list):
        raise plotting.InputError(f"{path}: a list of points expected, not {type(points).__name__}")
    for i, p in enumerate(points):
        for key in ("label", "x", "y"):
            if not isinstance(p, dict) or key not in p:
                raise plotting.InputError(f"{path}: point {i}: no key {key!r}")
        for key in ("x", "y"):
            if not isinstance(p[key], (int, float)):
                raise plotting.InputError(f"{path}: point {i}: {key}: {p[key]!r} is not a number")
    return points


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--log-dir", help="CSV directory written by agv-sim --log-dir")
    src.add_argument("--lcm-log", help="LCM log file written by lcm-logger")
    ap.add_argument("-o", "--output", required=True, help="PNG to write")
    ap.add_argument("--types", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                    "..", "build", "host", "python"),
                    help="directory of the generated Python LCM types "
                         "(default: build/host/python)")
    ap.add_argument("--title", default="", help="the figure's title (default: the input's name)")
    ap.add_argument("--magnify", type=float,
                    help="magnification of the deviations in the second map (default: chosen "
                         "so that the largest is a tenth of the map)")
    ap.add_argument("--points", help="JSON list of points to mark: {label, x, y, ...}")
    args = ap.parse_args()
    if args.magnify is not None and not args.magnify >= 1:
        ap.error(f"--magnify: {args.magnify:g} is below 1")
    try:
        run = (plotting.read_log_dir(args.log_dir) if args.log_dir
               else plotting.read_lcm_log(args.lcm_log, args.types))
        points = read_points(args.points) if args.points else None
    except plotting.InputError as e:
        print(f"plot_run: {e}", file=sys.stderr)
        return 2
    title = args.title or os.path.basename(os.path.normpath(args.log_dir or args.lcm_log))
    fig = plotting.run_figure(run, title=title, magnify=args.magnify, points=points)
    plotting.save(fig, args.output)
    print(f"plot_run: wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
