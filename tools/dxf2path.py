#!/usr/bin/env python3
"""dxf2path - seed 002's path generation: the polylines of a DXF drawing become an
arc-blended path and the poses along it that a scenario's "start" and "path" take.

  tools/dxf2path.py IN.dxf -o PATH.json [--scale-x K] [--scale-y K] [--radius-multiplier R]
                    [--step M] [--min-radius M] [--speed MPS] [--plot FILE.png]

The drawing (read with ezdxf): LWPOLYLINE and old-style POLYLINE/VERTEX entities of the model
space, open or closed, with bulges (arcs). Several polylines form one path when, in drawing
order, each starts where the one before it ends. Other entities are ignored (with a warning).
A drawing unit times --scale-x / --scale-y is a metre.

Every corner (two segments whose directions differ) is blended with a circular arc of radius
  rho = K (kx + ky) / 2 (1 - cos theta1)          (seed 002, Eq. 4.2)
where theta1 is the angle between the two segments at the vertex (180 degrees: straight on,
Eq. 4.1) and K the radius multiplier, but never less than --min-radius + 1 % (room for the
firmware's fixed-point rounding). The arc is tangent to both segments, d = rho tan((180 -
theta1) / 2) from the vertex (Eq. 4.3); it may take at most half of each segment. The first
and the last vertex are not blended (a closed path starts and ends at its first vertex, as in
the seed). Bulge arcs must be as wide as the blend arcs' minimum.

Output (JSON): {"start":{"x","y","heading_deg"},"path":[{"x","y","heading_deg","speed_mps"},..]}
in metres and degrees counter-clockwise from +x in [0, 360): the start pose and poses at equal
distances along the blended path, the last one its end; the heading turns at most 90
degrees between two poses (the firmware's limit). Exit 0 on success, 2 with a message
naming the entity, vertex or value when the drawing or an option cannot give a drivable path.
docs/dxf2path.md has the details.
"""
import argparse
import bisect
import json
import math
import sys

DOUBLE_BACK_DEG = 179.0  # a corner turning more than this doubles back on the path
MAX_TURN_DEG = 90.0  # the firmware drives at most this heading change between two poses
MAX_POSES = 1024  # a scenario's path holds at most this many poses (SIM_MAX_PATH)
RADIUS_ROOM = 1.01  # arcs are at least this times --min-radius: room for the firmware's rounding
SMOOTH_RAD = 1e-9  # directions closer than this are one (no corner)
REL_TOL = 1e-6  # endpoints closer than this times the drawing's size coincide


class PathError(Exception):
    """A drawing or an option that cannot give a drivable path: exit 2 with the message."""


def fmt(v):
    return f"{v:.6g}"


def xy(p):
    return f"({fmt(p[0])}, {fmt(p[1])})"


def wrap_pi(a):
    """An angle in radians wrapped to (-pi, pi]."""
    a = math.fmod(a, 2.0 * math.pi)
    if a <= -math.pi:
        a += 2.0 * math.pi
    elif a > math.pi:
        a -= 2.0 * math.pi
    return a


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def dist(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


# ---------------------------------------------------------------------------------------------
# Path pieces: straight lines and circular arcs, parametrised by the length s along them.


class Line:
    """A straight piece from p0 to p1 (metres)."""
    kind = "line"

    def __init__(self, p0, p1, origin):
        self.p0, self.p1, self.origin = p0, p1, origin
        self.length = dist(p0, p1)
        self.u = ((p1[0] - p0[0]) / self.length, (p1[1] - p0[1]) / self.length)
        self.curvature = 0.0

    def point(self, s):
        return (self.p0[0] + s * self.u[0], self.p0[1] + s * self.u[1])

    def heading(self, s):
        return math.atan2(self.u[1], self.u[0])

    def param(self, q):
        return dot(sub(q, self.p0), self.u)

    def part(self, s0, s1):
        return Line(self.point(s0), self.point(s1), self.origin)

    def offset(self, t):
        """The line t to the left (negative: right): ("line", point, direction)."""
        return ("line", (self.p0[0] - t * self.u[1], self.p0[1] + t * self.u[0]), self.u)

    def foot(self, c):
        return self.point(self.param(c))


class Arc:
    """A circular piece: centre c, radius r, from the angle a0 (radians, of the radius to the
    first point) sweeping `sweep` radians (positive: counter-clockwise, a left turn)."""
    kind = "arc"

    def __init__(self, c, r, a0, sweep, origin):
        self.c, self.r, self.a0, self.sweep, self.origin = c, r, a0, sweep, origin
        self.k = 1.0 if sweep > 0 else -1.0
        self.length = r * abs(sweep)
        self.curvature = self.k / r

    def point(self, s):
        a = self.a0 + self.k * s / self.r
        return (self.c[0] + self.r * math.cos(a), self.c[1] + self.r * math.sin(a))

    def heading(self, s):
        return self.a0 + self.k * s / self.r + self.k * math.pi / 2.0

    def param(self, q):
        a = math.atan2(q[1] - self.c[1], q[0] - self.c[0])
        d = (self.k * (a - self.a0)) % (2.0 * math.pi)
        if d > abs(self.sweep) + (2.0 * math.pi - abs(self.sweep)) / 2.0:
            d -= 2.0 * math.pi  # nearer the start than the end
        return d * self.r

    def part(self, s0, s1):
        return Arc(self.c, self.r, self.a0 + self.k * s0 / self.r, self.k * (s1 - s0) / self.r,
                   self.origin)

    def offset(self, t):
        """The circle t to the left: ("circle", centre, signed radius); negative when the
        offset passes the centre."""
        return ("circle", self.c, self.r - self.k * t)


def arc_from_bulge(p0, p1, bulge, origin):
    """The arc from p0 to p1 of a polyline bulge (tan of a quarter of the included angle,
    positive counter-clockwise)."""
    theta = 4.0 * math.atan(bulge)
    chord = dist(p0, p1)
    m = ((p0[0] + p1[0]) / 2.0, (p0[1] + p1[1]) / 2.0)
    n = (-(p1[1] - p0[1]) / chord, (p1[0] - p0[0]) / chord)  # left normal of the chord
    h = chord / 2.0 / math.tan(theta / 2.0)
    c = (m[0] + h * n[0], m[1] + h * n[1])
    r = chord / 2.0 / abs(math.sin(theta / 2.0))
    return Arc(c, r, math.atan2(p0[1] - c[1], p0[0] - c[0]), theta, origin)


# ---------------------------------------------------------------------------------------------
# Reading the drawing.


class Poly:
    """One polyline in drawing units: vertices, bulges (one per vertex: the arc to the next),
    closed flag, and names for messages."""

    def __init__(self, name, pts, bulges, vnames, closed):
        self.name, self.pts, self.bulges, self.vnames, self.closed = (name, pts, bulges, vnames,
                                                                      closed)


def entity_name(e):
    return f"{e.dxftype()} #{e.dxf.handle}"


def plane_sign(e, name):
    """+1 for an entity in the XY plane seen from +z, -1 from -z (x mirrored, bulges
    reversed); anything else is refused."""
    ez = e.dxf.extrusion[2] if e.dxf.hasattr("extrusion") else 1.0
    ex, ey = (e.dxf.extrusion[0], e.dxf.extrusion[1]) if e.dxf.hasattr("extrusion") else (0, 0)
    if abs(ex) > 1e-9 or abs(ey) > 1e-9 or abs(abs(ez) - 1.0) > 1e-9:
        raise PathError(f"{name}: extrusion {tuple(e.dxf.extrusion)}: the polyline is not in "
                        "the XY plane")
    return 1.0 if ez > 0 else -1.0


def read_polylines(filename):
    try:
        import ezdxf
    except ImportError:
        raise PathError("the Python package ezdxf is missing: run tools/install-deps.sh")
    try:
        doc = ezdxf.readfile(filename)
    except (OSError, ezdxf.DXFError, UnicodeError, ValueError) as e:
        raise PathError(f"{filename}: cannot read the DXF file: {e}")
    polys, ignored = [], {}
    for e in doc.modelspace():
        t = e.dxftype()
        name = entity_name(e)
        if t == "LWPOLYLINE":
            sign = plane_sign(e, name)
            pts, bulges = [], []
            for x, y, b in e.get_points("xyb"):
                pts.append((sign * float(x), float(y)))
                bulges.append(sign * float(b))
            vnames = [f"vertex {i} of {name}" for i in range(len(pts))]
            polys.append(Poly(name, pts, bulges, vnames, bool(e.closed)))
        elif t == "POLYLINE":
            mode = e.get_mode()
            if mode not in ("AcDb2dPolyline", "AcDb3dPolyline"):
                raise PathError(f"{name}: a {mode[4:]} (mesh) is not a path")
            if e.dxf.flags & 6:
                raise PathError(f"{name}: a curve-fit or spline-fit POLYLINE is not supported: "
                                "draw the path as a plain polyline (bulges make true arcs)")
            sign = plane_sign(e, name) if mode == "AcDb2dPolyline" else 1.0
            pts, bulges, vnames = [], [], []
            for v in e.vertices:
                loc = v.dxf.location
                pts.append((sign * float(loc[0]), float(loc[1])))
                bulges.append(sign * float(v.dxf.bulge) if mode == "AcDb2dPolyline" else 0.0)
                vnames.append(f"VERTEX #{v.dxf.handle} (vertex {len(pts) - 1} of {name})")
            polys.append(Poly(name, pts, bulges, vnames, bool(e.is_closed)))
        else:
            ignored[t] = ignored.get(t, 0) + 1
    return polys, ignored


def order_polylines(polys, ignored, filename):
    """The one chain the drawing's polylines form in drawing order, as (point, bulge, name)
    per vertex; the closed flag; the tolerance (drawing units)."""
    if not polys:
        found = ", ".join(f"{n} {t}" for t, n in sorted(ignored.items())) or "nothing"
        raise PathError(f"{filename}: empty drawing: no LWPOLYLINE or POLYLINE in the model "
                        f"space (found: {found})")
    for poly in polys:
        if not poly.pts:
            raise PathError(f"{poly.name}: a polyline without vertices")
    allpts = [p for poly in polys for p in poly.pts]
    size = max(max(abs(p[0]), abs(p[1])) for p in allpts)
    size = max(size, max(p[0] for p in allpts) - min(p[0] for p in allpts),
               max(p[1] for p in allpts) - min(p[1] for p in allpts))
    tol = REL_TOL * max(1.0, size)
    closed = [p for p in polys if p.closed]
    if closed and len(polys) > 1:
        raise PathError(f"{closed[0].name} is closed and the drawing has {len(polys)} "
                        "polylines: a closed polyline is a whole path of its own")
    chain = []
    for i, poly in enumerate(polys):
        if i > 0:
            prev = polys[i - 1]
            end, start = chain[-1][0], poly.pts[0]
            if dist(end, start) > tol:
                hint = ""
                if dist(end, poly.pts[-1]) <= tol:
                    hint = " (it ends there: it was drawn the other way round)"
                raise PathError(
                    f"{poly.name} (polyline {i + 1} in drawing order) starts at {xy(start)}, "
                    f"{fmt(dist(end, start))} drawing units from where {prev.name} ends "
                    f"{xy(end)}{hint}: several polylines make one path only when, in drawing "
                    "order, each starts where the one before it ends")
            # The joint: the previous polyline's last vertex carries this one's first bulge.
            chain[-1] = (chain[-1][0], poly.bulges[0],
                         f"the joint of {prev.name} and {poly.name}")
            rest = range(1, len(poly.pts))
        else:
            rest = range(len(poly.pts))
        for j in rest:
            chain.append((poly.pts[j], poly.bulges[j], poly.vnames[j]))
    is_closed = bool(closed)
    if is_closed:
        chain.append((chain[0][0], 0.0, chain[0][2]))
    return chain, is_closed, tol


def build_elements(chain, kx, ky, min_radius, tol):
    """Scaled lines and bulge arcs (metres) between consecutive distinct vertices; each
    remembers the names of its two vertices."""
    if kx != ky and any(abs(b) > 0 for _, b, _ in chain[:-1]):
        i = next(i for i, (_, b, _) in enumerate(chain[:-1]) if abs(b) > 0)
        raise PathError(f"{chain[i][2]}: bulge {fmt(chain[i][1])}: an arc scaled by "
                        f"--scale-x {fmt(kx)} and --scale-y {fmt(ky)} is an ellipse; use equal "
                        "scales for a drawing with arcs")
    elems = []
    for i in range(len(chain) - 1):
        (p, b, na), (q, _, nb) = chain[i], chain[i + 1]
        if dist(p, q) <= tol:
            continue  # a repeated vertex
        p0, p1 = (p[0] * kx, p[1] * ky), (q[0] * kx, q[1] * ky)
        origin = {"from": na, "to": nb}
        if abs(b) > 1e-12:
            arc = arc_from_bulge(p0, p1, b, origin)
            if arc.r < RADIUS_ROOM * min_radius:
                raise PathError(f"{na}: bulge {fmt(b)}: the arc to the next vertex has radius "
                                f"{fmt(arc.r)} m, below the {fmt(RADIUS_ROOM * min_radius)} m "
                                f"the path needs (--min-radius {fmt(min_radius)} m + 1 %)")
            elems.append(arc)
        else:
            elems.append(Line(p0, p1, origin))
    if not elems:
        raise PathError(f"{chain[0][2]}: the path has no length (all its vertices coincide)")
    return elems


# ---------------------------------------------------------------------------------------------
# Blending the corners.


def intersections(oa, ob):
    """The points where two offset curves (lines or circles) meet."""
    if oa[0] == "circle" and ob[0] == "line":
        oa, ob = ob, oa
    if oa[0] == "line" and ob[0] == "line":
        (_, a, u), (_, b, v) = oa, ob
        den = cross(u, v)
        if abs(den) < 1e-15:
            return []
        t = cross(sub(b, a), v) / den
        return [(a[0] + t * u[0], a[1] + t * u[1])]
    if oa[0] == "line":
        (_, a, u), (_, c, r) = oa, ob
        t0 = dot(sub(c, a), u)
        f = (a[0] + t0 * u[0], a[1] + t0 * u[1])
        h2 = r * r - dist(f, c)**2
        if h2 < 0:
            return []
        h = math.sqrt(h2)
        return [(f[0] + h * u[0], f[1] + h * u[1]), (f[0] - h * u[0], f[1] - h * u[1])]
    (_, c1, r1), (_, c2, r2) = oa, ob
    r1, r2 = abs(r1), abs(r2)
    d = dist(c1, c2)
    if d < 1e-15 or d > r1 + r2 or d < abs(r1 - r2):
        return []
    a = (d * d + r1 * r1 - r2 * r2) / (2.0 * d)
    h = math.sqrt(max(0.0, r1 * r1 - a * a))
    e = ((c2[0] - c1[0]) / d, (c2[1] - c1[1]) / d)
    m = (c1[0] + a * e[0], c1[1] + a * e[1])
    return [(m[0] - h * e[1], m[1] + h * e[0]), (m[0] + h * e[1], m[1] - h * e[0])]


def foot(elem, c, rho):
    """Where the fillet circle (centre c, radius rho) touches the element."""
    if elem.kind == "line":
        return elem.foot(c)
    d = dist(c, elem.c)
    if d < 1e-12:
        return None
    e = ((c[0] - elem.c[0]) / d, (c[1] - elem.c[1]) / d)
    cands = [(elem.c[0] + elem.r * e[0], elem.c[1] + elem.r * e[1]),
             (elem.c[0] - elem.r * e[0], elem.c[1] - elem.r * e[1])]
    return min(cands, key=lambda t: abs(dist(t, c) - rho))


def fillet(a, b, vertex, sigma, rho):
    """The arc of radius rho turning sigma (+1 left, -1 right) tangent to the end of element a
    and the start of element b, which meet at vertex: (arc, length taken from a's end, length
    taken from b's start), or None when there is no such arc."""
    cands = intersections(a.offset(sigma * rho), b.offset(sigma * rho))
    best = None
    for c in sorted(cands, key=lambda c: dist(c, vertex)):
        ta, tb = foot(a, c, rho), foot(b, c, rho)
        if ta is None or tb is None:
            continue
        sa, sb = a.param(ta), b.param(tb)
        if sa > a.length + 1e-9 or sb < -1e-9:
            continue  # it touches the other side of the vertex
        a0 = math.atan2(ta[1] - c[1], ta[0] - c[0])
        a1 = math.atan2(tb[1] - c[1], tb[0] - c[0])
        sweep = (sigma * (a1 - a0)) % (2.0 * math.pi)
        turn = wrap_pi(b.heading(sb) - a.heading(sa))
        if abs(wrap_pi(sigma * sweep - turn)) > 1e-7 or sweep >= math.pi:
            continue  # not tangent in the direction of travel
        best = (Arc(c, rho, a0, sigma * sweep, None), a.length - sa, sb)
        break
    return best


def blend(elems, k_mult, k_mean, min_radius):
    """The pieces of the blended path: the elements, shortened where a corner's arc takes
    over, and the corners' arcs; and the corners: name, turn (degrees, left positive),
    radius (m)."""
    cut_start = [0.0] * len(elems)
    cut_end = [0.0] * len(elems)
    arcs = [None] * len(elems)  # arcs[i]: the blend between elems[i] and elems[i + 1]
    corners = []
    for i in range(len(elems) - 1):
        a, b = elems[i], elems[i + 1]
        name, vertex = a.origin["to"], a.point(a.length)
        delta = wrap_pi(b.heading(0.0) - a.heading(a.length))
        if abs(delta) < SMOOTH_RAD:
            continue
        deg = math.degrees(abs(delta))
        if deg > DOUBLE_BACK_DEG:
            raise PathError(f"{name}: the path doubles back (it turns {deg:.2f} degrees): the "
                            "vehicle would have to reverse; draw a loop instead")
        theta1 = math.pi - abs(delta)  # Eq. 4.1: the angle between the segments
        rho_eq = abs(k_mult * k_mean * (1.0 - math.cos(theta1)))  # Eq. 4.2
        rho = max(rho_eq, RADIUS_ROOM * min_radius)
        why = (f"radius {fmt(rho)} m (Eq. 4.2 gives {fmt(rho_eq)} m, --min-radius "
               f"{fmt(min_radius)} m + 1 %)")
        f = fillet(a, b, vertex, 1.0 if delta > 0 else -1.0, rho)
        if f is None:
            raise PathError(f"{name}: the corner of {deg:.2f} degrees cannot be blended: no arc "
                            f"of {why} is tangent to both of its segments (an arc segment there "
                            "is too short or too tight for it); lower --radius-multiplier or "
                            "--min-radius, or redraw the corner")
        arc, ta, tb = f
        for t, e, which in ((ta, a, "before"), (tb, b, "after")):
            if t > e.length / 2.0 + 1e-9:
                raise PathError(
                    f"{name}: the corner of {deg:.2f} degrees cannot be blended: its arc of "
                    f"{why} needs {fmt(t)} m of the {fmt(e.length)} m segment {which} it, more "
                    "than half; lower --radius-multiplier or --min-radius, or lengthen the "
                    "segment")
        cut_end[i], cut_start[i + 1] = ta, tb
        arcs[i] = arc
        corners.append({"name": name, "deg": math.degrees(delta), "rho": rho})
    pieces = []
    for i, e in enumerate(elems):
        s0, s1 = cut_start[i], e.length - cut_end[i]
        if s1 - s0 > 1e-12:
            part = e.part(s0, s1)
            part.role = "bulge" if e.kind == "arc" else "line"
            part.name = (f"the bulge arc from {e.origin['from']}" if e.kind == "arc" else
                         f"the segment from {e.origin['from']}")
            pieces.append(part)
        if arcs[i] is not None:
            arcs[i].role = "blend"
            arcs[i].name = f"the blend arc at {e.origin['to']}"
            pieces.append(arcs[i])
    return pieces, corners


# ---------------------------------------------------------------------------------------------
# Poses.


def sample(pieces, step):
    """Poses at equal distances (the fewest intervals not longer than step) from the start to
    the end of the path; checks the heading change between consecutive poses."""
    starts = [0.0]
    for p in pieces:
        starts.append(starts[-1] + p.length)
    total = starts[-1]
    n = max(1, math.ceil(total / step - 1e-9))
    if n > MAX_POSES:
        raise PathError(f"--step {fmt(step)} m: the {fmt(total)} m path needs {n} poses, more "
                        f"than the {MAX_POSES} a scenario's path holds; use a longer --step")
    spacing = total / n

    def at(s):
        i = min(max(bisect.bisect_right(starts, s) - 1, 0), len(pieces) - 1)
        p = pieces[i]
        u = min(max(s - starts[i], 0.0), p.length)
        return p.point(u), p.heading(u)

    def turn(s0, s1):
        """Heading change from s0 to s1 and the piece that turns most within."""
        total_turn, worst = 0.0, None
        for i, p in enumerate(pieces):
            o = min(s1, starts[i + 1]) - max(s0, starts[i])
            if o > 0 and p.curvature:
                total_turn += o * p.curvature
                if worst is None or abs(p.curvature) > abs(worst.curvature):
                    worst = p
        return total_turn, worst

    poses = []
    for k in range(n + 1):
        s = total if k == n else k * spacing
        (x, y), h = at(s)
        poses.append((x, y, h))
        if k > 0:
            dpsi, worst = turn((k - 1) * spacing, s)
            if abs(math.degrees(dpsi)) > MAX_TURN_DEG + 1e-9:
                limit = math.radians(MAX_TURN_DEG) / abs(worst.curvature)
                raise PathError(
                    f"--step {fmt(step)} m: the poses {fmt(spacing)} m apart at "
                    f"{xy(poses[k - 1])} and {xy(poses[k])} turn "
                    f"{abs(math.degrees(dpsi)):.1f} degrees on {worst.name} (radius "
                    f"{fmt(1.0 / abs(worst.curvature))} m); the firmware drives at most "
                    f"{MAX_TURN_DEG:g} degrees between two poses: use --step {fmt(limit)} or "
                    "less")
    return poses, total, spacing


def heading_deg(h):
    d = round(math.degrees(h) % 360.0, 6)
    return 0.0 if d >= 360.0 else d + 0.0


def to_json(poses, speed):
    x, y, h = poses[0]
    return {
        "start": {"x": round(x, 6) + 0.0, "y": round(y, 6) + 0.0, "heading_deg": heading_deg(h)},
        "path": [{"x": round(px, 6) + 0.0, "y": round(py, 6) + 0.0, "heading_deg": heading_deg(ph),
                  "speed_mps": speed} for px, py, ph in poses[1:]],
    }


# ---------------------------------------------------------------------------------------------
# The preview.


def plot(filename, drawn, pieces, poses, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 7))
    for i, e in enumerate(drawn):
        n = 2 if e.kind == "line" else max(2, int(e.length / 0.01) + 1)
        pts = [e.point(e.length * j / (n - 1)) for j in range(n)]
        ax.plot([q[0] for q in pts], [q[1] for q in pts], "--", color="0.55", lw=1,
                label="polyline as drawn (scaled)" if i == 0 else None)
    ax.plot([e.p0[0] if e.kind == "line" else e.point(0)[0] for e in drawn],
            [e.p0[1] if e.kind == "line" else e.point(0)[1] for e in drawn], "s", color="0.4",
            ms=4, label="vertices")
    colours = {"line": "tab:blue", "blend": "tab:orange", "bulge": "tab:green"}
    labels = {"line": "straight", "blend": "blend arc (Eq. 4.2)", "bulge": "bulge arc"}
    seen = set()
    for p in pieces:
        n = max(2, int(p.length / 0.01) + 1)
        pts = [p.point(p.length * j / (n - 1)) for j in range(n)]
        lab = labels[p.role] if p.role not in seen else None
        seen.add(p.role)
        ax.plot([q[0] for q in pts], [q[1] for q in pts], color=colours[p.role], lw=2.2,
                label=lab)
    span = max(max(p[0] for p in poses) - min(p[0] for p in poses),
               max(p[1] for p in poses) - min(p[1] for p in poses), 1e-3)
    arrow = span * 0.03
    ax.quiver([p[0] for p in poses[1:]], [p[1] for p in poses[1:]],
              [math.cos(p[2]) * arrow for p in poses[1:]],
              [math.sin(p[2]) * arrow for p in poses[1:]], angles="xy", scale_units="xy",
              scale=1, color="k", width=0.003, label=f"poses ({len(poses) - 1})")
    ax.plot([poses[0][0]], [poses[0][1]], "o", color="tab:red", ms=8, label="start")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title, fontsize=10)
    ax.grid(True, lw=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, fontsize=9)
    fig.savefig(filename, dpi=110, bbox_inches="tight")
    plt.close(fig)


# ---------------------------------------------------------------------------------------------


def number(name, lo, hi, lo_open=False):
    def parse(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} {text!r}: not a number")
        if not math.isfinite(v) or v < lo or v > hi or (lo_open and v == lo):
            rng = f"{'(' if lo_open else '['}{fmt(lo)}, {fmt(hi)}]"
            raise argparse.ArgumentTypeError(f"{name} {text}: out of range {rng}")
        return v
    return parse


def parse_args(argv):
    ap = argparse.ArgumentParser(
        prog="dxf2path.py", description=__doc__.split("\n\n", 2)[2],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="Example: tools/dxf2path.py sim/paths/seed002_three_segment.dxf -o path.json "
        "--plot path.png   (docs/dxf2path.md)")
    ap.add_argument("dxf", metavar="IN.dxf", help="the drawing (DXF R12 or later)")
    ap.add_argument("-o", "--output", metavar="PATH.json", required=True,
                    help="the poses as {\"start\":{..},\"path\":[..]} (metres, degrees)")
    ap.add_argument("--scale-x", metavar="K", type=number("--scale-x", 0, 1e6, True),
                    default=1.0, help="(0, 1e6] metres per drawing unit along x "
                    "(the seed's kx; default 1)")
    ap.add_argument("--scale-y", metavar="K", type=number("--scale-y", 0, 1e6, True),
                    default=1.0, help="(0, 1e6] metres per drawing unit along y "
                    "(the seed's ky; default 1); must equal --scale-x when the drawing has "
                    "arcs (bulges)")
    ap.add_argument("--radius-multiplier", metavar="R", type=number("--radius-multiplier", 0,
                                                                     1e6),
                    default=0.3, help="[0, 1e6] drawing units: the seed's radius of curvature "
                    "multiplier K; a corner's arc has radius R (kx+ky)/2 (1 - cos theta1), "
                    "R (kx+ky)/2 for a right angle (default 0.3, the seed's menus; 0: every "
                    "corner at --min-radius)")
    ap.add_argument("--step", metavar="M", type=number("--step", 0.05, 50.0), default=0.5,
                    help="[0.05, 50] m: the longest distance between consecutive poses "
                    "(default 0.5; the path is cut into the fewest equal parts not longer; "
                    "docs/dxf2path.md says why 0.5)")
    ap.add_argument("--min-radius", metavar="M", type=number("--min-radius", 0.125, 100.0),
                    default=0.5, help="[0.125, 100] m: the vehicle's minimum turn radius; "
                    "every arc of the path is at least 1 %% wider (default 0.5, the vehicle of "
                    "the seed-002 scenarios)")
    ap.add_argument("--speed", metavar="MPS", type=number("--speed", 0.01, 5.0), default=0.5,
                    help="[0.01, 5] m/s: speed_mps of every pose (default 0.5, the seed's "
                    "PathGen)")
    ap.add_argument("--plot", metavar="FILE.png",
                    help="also draw the polyline, the blended path and the poses into a PNG")
    return ap.parse_args(argv)


def main(argv=None):
    a = parse_args(argv)
    try:
        polys, ignored = read_polylines(a.dxf)
        for t, n in sorted(ignored.items()) if polys else ():
            print(f"dxf2path: warning: {n} {t} ignored (only polylines make the path)",
                  file=sys.stderr)
        chain, closed, tol = order_polylines(polys, ignored, a.dxf)
        elems = build_elements(chain, a.scale_x, a.scale_y, a.min_radius, tol)
        pieces, corners = blend(elems, a.radius_multiplier, (a.scale_x + a.scale_y) / 2.0,
                                a.min_radius)
        poses, total, spacing = sample(pieces, a.step)
        out = to_json(poses, a.speed)
        if a.plot:
            title = (f"{a.dxf}: {len(corners)} corners blended, {total:.3f} m, "
                     f"{len(poses) - 1} poses {spacing:.3f} m apart")
            plot(a.plot, elems, pieces, poses, title)
        with open(a.output, "w") as f:
            json.dump(out, f, indent=1)
            f.write("\n")
    except PathError as e:
        print(f"dxf2path: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"dxf2path: error: {e}", file=sys.stderr)
        return 2
    radii = ", ".join(fmt(c["rho"]) for c in corners) or "none"
    print(f"dxf2path: {len(polys)} polyline(s), {'closed' if closed else 'open'}, "
          f"{len(corners)} corner(s) blended (radii {radii} m), {total:.3f} m, "
          f"{len(poses) - 1} poses {spacing:.4f} m apart -> {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
