"""Plot helpers shared by the tools that draw runs (tools/plot_run.py, tools/demo.py, the
campaign's and the records' plots): reading an agv-sim --log-dir or an LCM log into one run
structure, the world (beacons, glints, walls) on a map, a track magnified about the nominal
path, time panels on one time axis, legends outside the axes. A library, not a tool.

    import plotting
    run = plotting.read_log_dir("out/run1")
    fig, axes = plotting.run_figure(run, title="...", magnify=None)
    plotting.save(fig, "out/run1.png")

Errors name the file, the column and the value (plotting.InputError).
"""
import csv
import math
import os


class InputError(Exception):
    """A log the plot cannot use; the message names the file, the column, the row, the value."""


# Colours (colour-blind safe: Okabe-Ito) and styles used by every plot of the project.
C_PATH = "0.72"
C_TRUTH = "#0072B2"
C_EST = "#E69F00"
C_FIX = "#009E73"
C_REJECT = "#D55E00"
C_GLINT = "#CC79A7"
C_WALL = "#3b2a1a"
C_SCREENED = "#999999"


def _matplotlib():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


# ------------------------------------------------------------------ reading

def read_csv(path, columns, required=True):
    """Rows of a CSV log as dicts of floats for @p columns (others kept as text). A missing
    optional file gives []."""
    if not os.path.exists(path):
        if required:
            raise InputError(f"{path}: missing (is the directory an agv-sim --log-dir?)")
        return []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        absent = [c for c in columns if c not in (reader.fieldnames or [])]
        if absent:
            raise InputError(f"{path}: no column {', '.join(absent)} (columns: "
                             f"{', '.join(reader.fieldnames or [])})")
        rows = []
        for n, row in enumerate(reader, start=2):
            out = dict(row)
            for c in columns:
                try:
                    out[c] = float(row[c])
                except (TypeError, ValueError):
                    raise InputError(f"{path}:{n}: column {c}: {row[c]!r} is not a number")
            rows.append(out)
    return rows


def read_log_dir(d):
    """The run of an agv-sim --log-dir: truth, estimate, fixes, nominal path, beacons, glints,
    walls (the last two absent from logs of older builds)."""
    truth = read_csv(os.path.join(d, "truth.csv"), ["t_s", "x_m", "y_m", "cross_track_m"])
    if not truth:
        raise InputError(f"{d}/truth.csv: no rows")
    est = read_csv(os.path.join(d, "estimate.csv"), ["t_s", "x_m", "y_m"])
    fixes = read_csv(os.path.join(d, "fixes.csv"), ["t_s", "ref_t_s", "accepted", "x_m",
                                                     "y_m", "error_m", "status"])
    for f in fixes:
        used = f.get("used") or ""
        f["used"] = [int(i) for i in used.split(";") if i.strip().lstrip("-").isdigit()
                     and int(i) >= 0]
    return {
        "truth": truth, "estimate": est, "fixes": fixes,
        "path": read_csv(os.path.join(d, "path.csv"), ["x_m", "y_m"]),
        "beacons": read_csv(os.path.join(d, "beacons.csv"), ["x_m", "y_m"]),
        "glints": read_csv(os.path.join(d, "glints.csv"), ["x_m", "y_m"], required=False),
        "walls": read_csv(os.path.join(d, "walls.csv"), ["x1_m", "y1_m", "x2_m", "y2_m"],
                          required=False),
        "source": d,
    }


def read_lcm_log(path, types_dir):
    """The run of an LCM log written by lcm-logger while agv-sim --lcm ran (truth, estimate,
    fixes; the world and the nominal path are not on LCM)."""
    import sys
    sys.path.insert(0, types_dir)
    try:
        import lcm
        from cyclopion import fix_t, pose_t, truth_t
    except ImportError as e:
        raise InputError(f"cannot import the LCM types from {types_dir}: {e} (make host)")
    if not os.path.isfile(path):
        raise InputError(f"{path}: no such file")
    truth, est, fixes = [], [], []
    try:
        log = lcm.EventLog(path, "r")
    except IOError as e:
        raise InputError(f"{path}: not an LCM log: {e}")
    for ev in log:
        try:
            if ev.channel == "CYCLOPION_TRUTH":
                m = truth_t.decode(ev.data)
                truth.append({"t_s": m.utime * 1e-6, "x_m": m.x, "y_m": m.y,
                              "cross_track_m": m.cross_track_m})
            elif ev.channel == "CYCLOPION_POSE":
                m = pose_t.decode(ev.data)
                est.append({"t_s": m.utime * 1e-6, "x_m": m.x, "y_m": m.y})
            elif ev.channel == "CYCLOPION_FIX":
                m = fix_t.decode(ev.data)
                fixes.append({"t_s": m.utime * 1e-6, "ref_t_s": m.ref_utime * 1e-6,
                              "accepted": float(m.accepted), "x_m": m.x, "y_m": m.y,
                              "error_m": m.error_m, "status": 0.0,
                              "used": [int(i) for i in m.used if i >= 0]})
        except ValueError as e:
            raise InputError(f"{path}: event {ev.eventnum} on {ev.channel}: {e}")
    if not truth:
        raise InputError(f"{path}: no CYCLOPION_TRUTH messages")
    return {"truth": truth, "estimate": est, "fixes": fixes, "path": [], "beacons": [],
            "glints": [], "walls": [], "source": path}


# ------------------------------------------------------------------ geometry

def _segments_cross(a, b, c, d):
    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    return (orient(a, b, c) * orient(a, b, d) < 0) and (orient(c, d, a) * orient(c, d, b) < 0)


def screened_fraction(run, beacon, step=10):
    """The share of the truth samples (every @p step-th) from which a wall hides @p beacon."""
    if not run["walls"]:
        return 0.0
    b = (beacon["x_m"], beacon["y_m"])
    walls = [((w["x1_m"], w["y1_m"]), (w["x2_m"], w["y2_m"])) for w in run["walls"]]
    samples = run["truth"][::step] or run["truth"]
    hidden = sum(1 for t in samples
                 if any(_segments_cross((t["x_m"], t["y_m"]), b, w1, w2) for w1, w2 in walls))
    return hidden / len(samples)


class PathFrame:
    """The nominal path (samples every centimetre) as a frame: the foot point of a position
    and its offset, to magnify deviations about the path."""

    def __init__(self, path, cell=0.5):
        self.px = [p["x_m"] for p in path]
        self.py = [p["y_m"] for p in path]
        self.cell = cell
        self.grid = {}
        for i, (x, y) in enumerate(zip(self.px, self.py)):
            self.grid.setdefault((int(x // cell), int(y // cell)), []).append(i)

    def foot(self, x, y):
        """Index of the nearest path sample (searching the nearby grid cells first)."""
        cx, cy = int(x // self.cell), int(y // self.cell)
        for r in (1, 3, 10):
            cand = [i for dx in range(-r, r + 1) for dy in range(-r, r + 1)
                    for i in self.grid.get((cx + dx, cy + dy), [])]
            if cand:
                break
        else:
            cand = range(len(self.px))
        return min(cand, key=lambda i: (self.px[i] - x) ** 2 + (self.py[i] - y) ** 2)

    def magnify(self, xs, ys, k):
        """Each position moved k times as far from its foot point on the path."""
        out_x, out_y = [], []
        for x, y in zip(xs, ys):
            i = self.foot(x, y)
            out_x.append(self.px[i] + k * (x - self.px[i]))
            out_y.append(self.py[i] + k * (y - self.py[i]))
        return out_x, out_y


def interp(rows, t, key):
    """@p key of time-stamped rows (sorted by t_s) at time @p t, linearly."""
    lo, hi = 0, len(rows) - 1
    if t <= rows[0]["t_s"]:
        return rows[0][key]
    if t >= rows[hi]["t_s"]:
        return rows[hi][key]
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if rows[mid]["t_s"] <= t:
            lo = mid
        else:
            hi = mid
    a, b = rows[lo], rows[hi]
    u = (t - a["t_s"]) / (b["t_s"] - a["t_s"]) if b["t_s"] > a["t_s"] else 0.0
    return a[key] + u * (b[key] - a[key])


def estimate_error(run):
    """(t, |estimate - truth| in m) at the estimate's samples."""
    tr = run["truth"]
    out = []
    for e in run["estimate"]:
        out.append((e["t_s"], math.hypot(e["x_m"] - interp(tr, e["t_s"], "x_m"),
                                         e["y_m"] - interp(tr, e["t_s"], "y_m"))))
    return out


def auto_magnify(run):
    """A magnification that makes the largest deviation from the path about a tenth of the
    map's size (a round 1, 2, 5 x 10^n), or 1 when there is no path."""
    if not run["path"]:
        return 1.0
    x0, x1, y0, y1 = _bounds(run, None)
    size = max(x1 - x0, y1 - y0)
    dev = max([abs(t["cross_track_m"]) for t in run["truth"]
               if math.isfinite(t["cross_track_m"])] + [1e-4])
    want = 0.08 * size / dev
    k = 1.0
    for base in (1, 2, 5):
        for e in range(0, 6):
            if base * 10 ** e <= want:
                k = max(k, base * 10 ** e)
    return k


# ------------------------------------------------------------------ drawing

def draw_world(ax, run, marker_scale=1.0):
    """Walls, glints and beacons; a beacon filled when an accepted fix used it, its edge grey
    when a wall screens it from the whole run, orange when from part of it. Returns the
    legend handles in drawing order."""
    from matplotlib.lines import Line2D
    handles = []
    for i, w in enumerate(run["walls"]):
        ax.plot([w["x1_m"], w["x2_m"]], [w["y1_m"], w["y2_m"]], "-", color=C_WALL, lw=4,
                solid_capstyle="butt", zorder=2)
    if run["walls"]:
        handles.append(Line2D([], [], color=C_WALL, lw=4, label="wall (blocks the beam)"))
    if run["glints"]:
        ax.plot([g["x_m"] for g in run["glints"]], [g["y_m"] for g in run["glints"]], "*",
                color=C_GLINT, ms=13 * marker_scale, mec="k", mew=0.5, zorder=5)
        handles.append(Line2D([], [], ls="", marker="*", color=C_GLINT, mec="k", mew=0.5,
                              ms=12, label="glint (spurious reflector)"))
    used = {}
    for f in run["fixes"]:
        if f["accepted"]:
            for i in f["used"]:
                used[i] = used.get(i, 0) + 1
    kinds = set()
    for i, b in enumerate(run["beacons"]):
        screened = screened_fraction(run, b)
        edge = C_SCREENED if screened >= 0.999 else "#D55E00" if screened > 0 else "k"
        face = "k" if used.get(i) else "white"
        ax.plot(b["x_m"], b["y_m"], "^", ms=9 * marker_scale, mfc=face, mec=edge, mew=1.8,
                zorder=6)
        kinds.add(("used" if used.get(i) else "unused",
                   "all" if screened >= 0.999 else "part" if screened > 0 else "none"))
    if run["beacons"]:
        if any(k[0] == "used" for k in kinds):
            handles.append(Line2D([], [], ls="", marker="^", mfc="k", mec="k", ms=9,
                                  label="beacon used in fixes"))
        if any(k[0] == "unused" for k in kinds):
            handles.append(Line2D([], [], ls="", marker="^", mfc="white", mec="k", ms=9,
                                  mew=1.5, label="beacon never used"))
        if any(k[1] == "part" for k in kinds):
            handles.append(Line2D([], [], ls="", marker="^", mfc="white", mec="#D55E00", ms=9,
                                  mew=1.8, label="beacon screened by a wall\nfor part of the run"))
        if any(k[1] == "all" for k in kinds):
            handles.append(Line2D([], [], ls="", marker="^", mfc="white", mec=C_SCREENED,
                                  ms=9, mew=1.8, label="beacon screened all run"))
    return handles


def draw_track(ax, run, frame=None, k=1.0):
    """The nominal path, the truth, the nav board's estimate, accepted and rejected fixes;
    with a PathFrame and k > 1 every position is drawn k times as far from the path. Returns
    the legend handles."""
    from matplotlib.lines import Line2D

    def xy(rows):
        xs, ys = [r["x_m"] for r in rows], [r["y_m"] for r in rows]
        return frame.magnify(xs, ys, k) if frame and k != 1 else (xs, ys)
    handles = []
    if run["path"]:
        ax.plot([p["x_m"] for p in run["path"]], [p["y_m"] for p in run["path"]], "-",
                color=C_PATH, lw=5 if k == 1 else 1.2, zorder=1, solid_capstyle="round")
        handles.append(Line2D([], [], color=C_PATH, lw=5, label="nominal path"))
    x, y = xy(run["truth"])
    ax.plot(x, y, "-", color=C_TRUTH, lw=1.3, zorder=3)
    handles.append(Line2D([], [], color=C_TRUTH, lw=1.3, label="truth (rear axle)"))
    if run["estimate"]:
        x, y = xy(run["estimate"])
        ax.plot(x, y, "--", color=C_EST, lw=1.3, zorder=4, dashes=(4, 2))
        handles.append(Line2D([], [], color=C_EST, lw=1.3, ls="--",
                              label="nav-board estimate"))
    acc = [f for f in run["fixes"] if f["accepted"]]
    rej = [f for f in run["fixes"] if not f["accepted"] and (f["x_m"] or f["y_m"])]
    if acc:
        x, y = xy(acc)
        ax.plot(x, y, "o", color=C_FIX, ms=4.5, mec="k", mew=0.4, zorder=7)
        handles.append(Line2D([], [], ls="", marker="o", color=C_FIX, mec="k", mew=0.4,
                              ms=5, label=f"accepted fix ({len(acc)})"))
    if rej:
        x, y = xy(rej)
        ax.plot(x, y, "x", color=C_REJECT, ms=6, mew=1.6, zorder=7)
    n_rej = sum(1 for f in run["fixes"] if not f["accepted"])
    if n_rej:
        handles.append(Line2D([], [], ls="", marker="x", color=C_REJECT, ms=6, mew=1.6,
                              label=f"rejected fix ({n_rej})"))
    return handles


def legend_outside(ax, handles, title=None, loc="upper left", anchor=(1.02, 1.0)):
    """A legend beside @p ax (not over the map)."""
    return ax.legend(handles=handles, loc=loc, bbox_to_anchor=anchor, borderaxespad=0.0,
                     fontsize=8.5, title=title, title_fontsize=9, frameon=False)


def time_panels(axes, run, t_end=None):
    """On axes sharing one time axis: the cross-track error of the truth, the estimate's
    distance from the truth, the fix errors (accepted; rejected fixes marked at the bottom)."""
    t_end = t_end or run["truth"][-1]["t_s"]
    ax_ct, ax_est, ax_fix = axes
    t = [r["t_s"] for r in run["truth"]]
    ax_ct.plot(t, [1e3 * r["cross_track_m"] if math.isfinite(r["cross_track_m"])
                   else float("nan") for r in run["truth"]], "-", color=C_TRUTH, lw=1)
    ax_ct.set_ylabel("cross-track\nerror / mm")
    ee = estimate_error(run)
    if ee:
        ax_est.plot([e[0] for e in ee], [1e3 * e[1] for e in ee], "-", color=C_EST, lw=1)
    ax_est.set_ylabel("estimate − truth\n/ mm")
    acc = [f for f in run["fixes"] if f["accepted"] and f["error_m"] >= 0]
    if acc:
        ax_fix.plot([f["t_s"] for f in acc], [1e3 * f["error_m"] for f in acc], "o",
                    color=C_FIX, ms=4, mec="k", mew=0.4, label="accepted fix")
    rej = [f for f in run["fixes"] if not f["accepted"]]
    if rej:
        trans = ax_fix.get_xaxis_transform()
        ax_fix.plot([f["t_s"] for f in rej], [0.04] * len(rej), "x", color=C_REJECT, ms=6,
                    mew=1.5, transform=trans, clip_on=False, label="rejected fix")
    ax_fix.set_ylabel("fix error / mm")
    if acc or rej:
        ax_fix.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.set_xlim(0, t_end)
        ax.set_ylim(bottom=0)
    axes[-1].set_xlabel("simulated time / s")


def save(fig, out):
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    fig.savefig(out, dpi=110)
    _matplotlib().close(fig)


def run_figure(run, title="", magnify=None, points=None):
    """The whole run: the map (world, path, truth, estimate, fixes), the same magnified about
    the nominal path, and three time panels on one time axis. @p points: marked points
    [{"label", "x", "y", "marker", "color", "text", "magnify"}] drawn on both maps (on the
    map only with "magnify": false) (e.g. Table 6-1's). Returns
    the figure."""
    plt = _matplotlib()
    k = auto_magnify(run) if magnify is None else magnify
    frame = PathFrame(run["path"]) if run["path"] and k != 1 else None
    x0, x1, y0, y1 = _bounds(run, points)
    # the maps' height from their aspect (two maps of 5.6 in side by side), then the panels
    map_h = min(max(5.6 * (y1 - y0) / (x1 - x0), 2.5), 7.0)
    panels_h = 3 * 1.45
    fig_h = map_h + panels_h + 2.0
    fig = plt.figure(figsize=(15, fig_h))
    gs = fig.add_gridspec(4, 3, width_ratios=[1, 1, 0.36],
                          height_ratios=[map_h, panels_h / 3, panels_h / 3, panels_h / 3],
                          hspace=0.3, wspace=0.16, left=0.06, right=0.985,
                          top=1 - 0.75 / fig_h, bottom=0.5 / fig_h)
    ax_map = fig.add_subplot(gs[0, 0] if frame else gs[0, 0:2])
    ax_mag = fig.add_subplot(gs[0, 1]) if frame else None
    ax_t = [fig.add_subplot(gs[1 + i, 0:2]) for i in range(3)]
    for a in ax_t[1:]:
        a.sharex(ax_t[0])
    for a in ax_t[:-1]:
        a.tick_params(labelbottom=False)

    world = draw_world(ax_map, run)
    track = draw_track(ax_map, run)
    marks = _draw_points(ax_map, points)
    ax_map.set_title("map")
    if ax_mag:
        draw_world(ax_mag, run, marker_scale=0.8)
        draw_track(ax_mag, run, frame, k)
        _draw_points(ax_mag, points, frame, k)
        ax_mag.set_title(f"deviations from the nominal path magnified ×{k:g}")
        ax_mag.tick_params(labelleft=False)
    for a in (ax_map, ax_mag):
        if a:
            a.set_xlim(x0, x1)
            a.set_ylim(y0, y1)
            a.set_aspect("equal", adjustable="box")
            a.set_xlabel("x / m")
            a.grid(True, alpha=0.25)
    ax_map.set_ylabel("y / m")
    legend_outside(ax_mag or ax_map, track + marks + world)
    time_panels(ax_t, run)
    fig.suptitle(title, fontsize=13)
    return fig


def _bounds(run, points, margin=0.06):
    """The map's extent: the world, the path, the truth and the points, with a margin."""
    xs, ys = [], []
    for key in ("beacons", "glints", "path", "truth"):
        xs += [r["x_m"] for r in run[key]]
        ys += [r["y_m"] for r in run[key]]
    for w in run["walls"]:
        xs += [w["x1_m"], w["x2_m"]]
        ys += [w["y1_m"], w["y2_m"]]
    xs += [p["x"] for p in points or []]
    ys += [p["y"] for p in points or []]
    dx, dy = max(xs) - min(xs), max(ys) - min(ys)
    m = margin * max(dx, dy, 1e-3)
    return min(xs) - m, max(xs) + m, min(ys) - m, max(ys) + m


def _draw_points(ax, points, frame=None, k=1.0):
    from matplotlib.lines import Line2D
    handles, seen = [], set()
    for p in points or []:
        x, y = (p["x"], p["y"])
        if frame and k != 1 and p.get("magnify") is False:
            continue
        if frame and k != 1:
            (x,), (y,) = frame.magnify([x], [y], k)
        style = dict(marker=p.get("marker", "s"), color=p.get("color", "k"), ms=p.get("ms", 7),
                     mfc=p.get("mfc", "none"), mew=1.5, ls="")
        ax.plot([x], [y], zorder=8, **style)
        if p.get("text"):
            ax.annotate(p["text"], (x, y), xytext=(6, 5), textcoords="offset points",
                        fontsize=8, color=p.get("color", "k"), zorder=9)
        if p["label"] not in seen:
            seen.add(p["label"])
            handles.append(Line2D([], [], label=p["label"], **style))
    return handles
