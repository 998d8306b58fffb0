#!/usr/bin/env python3
"""ctest tools.dxf2path (label unit): tools/dxf2path.py end to end on drawings made here with
ezdxf. Expected paths come from exact geometry written in this file: seed 002's Eq. 4.1-4.3 as
its listing computes them (law of cosines, radius, tangent length) for straight corners, arcs
from the bulge definition, and invariants (tangency, equal spacing, heading continuity). With
--agvcalc, the firmware's double-arc solver must solve every pair of consecutive poses of the
shipped drawings, and the chain of its double arcs must stay on the blended path; with
--agv-sim, a drawn path is driven in the closed-loop simulator.

  tests/tools/dxf2path_test.py [--agvcalc build/host/bin/agvcalc] [--agv-sim build/host/bin/agv-sim]
"""
import argparse
import contextlib
import importlib.util
import io
import json
import logging
import math
import os
import subprocess
import sys
import tempfile
import unittest

import ezdxf

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TOOL = os.path.join(ROOT, "tools", "dxf2path.py")
AGVCALC = None
AGV_SIM = None
_spec = importlib.util.spec_from_file_location("dxf2path", TOOL)
dxf2path = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(dxf2path)
ROOM = 1.01  # the tool's documented margin over --min-radius (docs/dxf2path.md)
DOC_DEVIATION_M = 0.05e-3  # docs/dxf2path.md: the double arcs stay within 0.05 mm (defaults)
DOC_DEVIATION_LONG_M = 15e-3  # ... and within 15 mm at --step 0.75


# ---------------------------------------------------------------------------------------------
# Reference geometry (independent of the tool).


def seed_corner(p0, v, p1, k_mult, k_mean, rmin):
    """Seed 002's corner at v between p0->v and v->p1, as its listing computes it:
    theta1 by the law of cosines (Eq. 4.1), rho (Eq. 4.2, never below rmin * ROOM), d (Eq. 4.3);
    the arc centre from the side of the turn (the listing's UP/DOWN)."""
    d1 = math.dist(p0, v)
    d2 = math.dist(v, p1)
    c = (p1[0] - p0[0], p1[1] - p0[1])
    cmag2 = c[0]**2 + c[1]**2
    theta1 = math.acos(max(-1.0, min(1.0, (cmag2 - d1 * d1 - d2 * d2) / (-2.0 * d1 * d2))))
    rho = max(abs(k_mult * k_mean * (1.0 - math.cos(theta1))), rmin * ROOM)
    d = abs(rho * math.tan((math.pi - theta1) / 2.0))
    u1 = ((v[0] - p0[0]) / d1, (v[1] - p0[1]) / d1)
    u2 = ((p1[0] - v[0]) / d2, (p1[1] - v[1]) / d2)
    sigma = 1.0 if u1[0] * u2[1] - u1[1] * u2[0] > 0 else -1.0
    t1 = (v[0] - d * u1[0], v[1] - d * u1[1])
    t2 = (v[0] + d * u2[0], v[1] + d * u2[1])
    centre = (t1[0] - sigma * rho * u1[1], t1[1] + sigma * rho * u1[0])
    return {"theta1": theta1, "rho": rho, "d": d, "t1": t1, "t2": t2, "centre": centre,
            "sweep": sigma * (math.pi - theta1)}


class Ref:
    """A path of ("line", p0, p1) and ("arc", centre, r, a0, sweep) pieces."""

    def __init__(self, pieces):
        self.pieces = pieces
        self.lengths = [math.dist(p[1], p[2]) if p[0] == "line" else p[2] * abs(p[4])
                        for p in pieces]
        self.length = sum(self.lengths)

    def at(self, s):
        for p, n in zip(self.pieces, self.lengths):
            if s <= n + 1e-12 or p is self.pieces[-1]:
                s = min(s, n)
                if p[0] == "line":
                    _, a, b = p
                    u = ((b[0] - a[0]) / n, (b[1] - a[1]) / n)
                    return (a[0] + s * u[0], a[1] + s * u[1]), math.atan2(u[1], u[0])
                _, c, r, a0, sw = p
                k = 1.0 if sw > 0 else -1.0
                a = a0 + k * s / r
                return (c[0] + r * math.cos(a), c[1] + r * math.sin(a)), a + k * math.pi / 2
            s -= n
        raise AssertionError("unreachable")

    def distance(self, q):
        best = math.inf
        for p in self.pieces:
            if p[0] == "line":
                _, a, b = p
                ab = (b[0] - a[0], b[1] - a[1])
                t = ((q[0] - a[0]) * ab[0] + (q[1] - a[1]) * ab[1]) / (ab[0]**2 + ab[1]**2)
                t = min(1.0, max(0.0, t))
                best = min(best, math.dist(q, (a[0] + t * ab[0], a[1] + t * ab[1])))
            else:
                _, c, r, a0, sw = p
                ang = math.atan2(q[1] - c[1], q[0] - c[0])
                off = ((ang - a0) * (1 if sw > 0 else -1)) % (2 * math.pi)
                if off <= abs(sw):
                    best = min(best, abs(math.dist(q, c) - r))
                else:
                    for e in (a0, a0 + sw):
                        best = min(best, math.dist(q, (c[0] + r * math.cos(e),
                                                       c[1] + r * math.sin(e))))
        return best


def ref_polyline(pts, bulges=None, k_mult=0.3, k_mean=1.0, rmin=0.5, closed=False):
    """The expected blended path of a polyline in metres: straight corners blended by
    seed_corner(); bulge arcs from the bulge definition (they must meet their neighbours
    tangentially here: no corners next to arcs in these references)."""
    pts = list(pts) + ([pts[0]] if closed else [])
    bulges = list(bulges or [0.0] * len(pts)) + [0.0]
    segs = []
    for i in range(len(pts) - 1):
        a, b, bl = pts[i], pts[i + 1], bulges[i]
        if bl:
            th = 4.0 * math.atan(bl)
            chord = math.dist(a, b)
            r = chord / (2.0 * abs(math.sin(th / 2.0)))
            mid = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
            nrm = (-(b[1] - a[1]) / chord, (b[0] - a[0]) / chord)
            h = chord / 2.0 / math.tan(th / 2.0)
            c = (mid[0] + h * nrm[0], mid[1] + h * nrm[1])
            segs.append(["arc", c, r, math.atan2(a[1] - c[1], a[0] - c[0]), th])
        else:
            segs.append(["line", a, b])
    pieces = []
    for i, s in enumerate(segs):
        pieces.append(s)
        if i + 1 < len(segs):
            nxt = segs[i + 1]
            if s[0] == "line" and nxt[0] == "line":
                c = seed_corner(s[1], s[2], nxt[2], k_mult, k_mean, rmin)
                s[2] = c["t1"]
                nxt[1] = c["t2"]
                a0 = math.atan2(c["t1"][1] - c["centre"][1], c["t1"][0] - c["centre"][0])
                pieces.append(["arc", c["centre"], c["rho"], a0, c["sweep"]])
    return Ref([tuple(p) for p in pieces])


# ---------------------------------------------------------------------------------------------
# Drawing and running.


class Drawing:
    def __init__(self, tmp, name, version="R2010"):
        self.path = os.path.join(tmp, name)
        self.doc = ezdxf.new(version)
        self.msp = self.doc.modelspace()

    def lw(self, pts, bulges=None, closed=False, **attribs):
        b = bulges or [0.0] * len(pts)
        return self.msp.add_lwpolyline([(x, y, bb) for (x, y), bb in zip(pts, b)], format="xyb",
                                       close=closed, dxfattribs=attribs)

    def poly(self, pts, bulges=None, closed=False):
        b = bulges or [0.0] * len(pts)
        return self.msp.add_polyline2d([(x, y, 0.0, 0.0, bb) for (x, y), bb in zip(pts, b)],
                                       format="xyseb", close=closed)

    def save(self):
        self.doc.saveas(self.path)
        return self.path


def run(dxf, *args, out):
    """The tool's exit code, stderr and output (None unless it succeeded). Its main() runs in
    this process (importing ezdxf once per tool run would take most of the test's time);
    test_command_line runs the executable itself."""
    if os.path.exists(out):
        os.remove(out)
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            rc = dxf2path.main([dxf, "-o", out] + [str(a) for a in args])
        except SystemExit as e:  # argparse
            rc = e.code
    data = None
    if rc == 0:
        with open(out) as f:
            data = json.load(f)
    return rc, err.getvalue(), data


def poses(data):
    return [data["start"]] + data["path"]


def angle_diff_deg(a, b):
    return abs((a - b + 180.0) % 360.0 - 180.0)


class Dxf2PathTest(unittest.TestCase):

    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = self._tmp.name

    def tearDown(self):
        self._tmp.cleanup()

    def drawing(self, name="d.dxf", version="R2010"):
        return Drawing(self.tmp, name, version)

    def ok(self, dxf, *args):
        rc, err, data = run(dxf, *args, out=os.path.join(self.tmp, "out.json"))
        self.assertEqual(rc, 0, err)
        return data

    def fails(self, dxf, *args, says=()):
        rc, err, data = run(dxf, *args, out=os.path.join(self.tmp, "out.json"))
        self.assertEqual(rc, 2, f"expected exit 2, got {rc}: {err}")
        self.assertIn("dxf2path: error:", err)
        for s in says:
            self.assertIn(s, err)
        self.assertNotIn("Traceback", err)
        return err

    def assert_follows(self, data, ref, step, speed=0.5, tol=2e-6):
        """Poses on the reference at equal distances L/n, n = ceil(L/step), headings its
        tangents, each with the speed; the first is the start."""
        n = math.ceil(ref.length / step - 1e-9)
        ps = poses(data)
        self.assertEqual(len(ps), n + 1)
        for k, p in enumerate(ps):
            (x, y), h = ref.at(ref.length * k / n)
            self.assertLess(math.dist((p["x"], p["y"]), (x, y)), tol, (k, p, x, y))
            self.assertLess(angle_diff_deg(p["heading_deg"], math.degrees(h)), 1e-4, (k, p))
            self.assertTrue(0.0 <= p["heading_deg"] < 360.0, p)
            if k:
                self.assertEqual(p["speed_mps"], speed)
                self.assertEqual(set(p), {"x", "y", "heading_deg", "speed_mps"})
        self.assertEqual(set(data["start"]), {"x", "y", "heading_deg"})
        self.assertEqual(set(data), {"start", "path"})

    # --- the reconstruction of Eq. 4.1-4.3 -------------------------------------------------

    def test_reconstruction_matches_the_listing_arc(self):
        """The seed's Calc_Path draws the arc in the vector frame from (endpt, 0) with centre
        (endpt, dir rho), angle from pi/2 down to -pi/2 + theta1: it must end on the second
        vector, d from the vertex, heading along it; d = rho tan((pi - theta1)/2) makes it so.
        And the seed's Path #3 with its menu's K = 0.3 (1 m per drawing unit): hand-worked,
        theta1 = acos(-0.8), rho = 0.3 * 1.8 = 0.54 m, d = 0.3 * 0.6 = 0.18 m."""
        for th1_deg in (10, 45, 90, 106.26, 143.13, 170):
            th1 = math.radians(th1_deg)
            rho = 0.7 * (1 - math.cos(th1))
            d = rho * math.tan((math.pi - th1) / 2)
            endpt = 3.0 - d  # first vector 3 m long
            a_end = -math.pi / 2 + th1
            x = endpt + rho * math.cos(a_end)
            y = rho - rho * math.sin(a_end)  # dir = UP
            v2 = (math.cos(math.pi - th1), math.sin(math.pi - th1))
            self.assertAlmostEqual(x, 3.0 + d * v2[0], places=12)
            self.assertAlmostEqual(y, d * v2[1], places=12)
        c = seed_corner((4.0, 2.0), (2.5, 4.0), (2.5, 7.0), 0.3, 1.0, 0.125)
        self.assertAlmostEqual(math.cos(c["theta1"]), -0.8, places=12)
        self.assertAlmostEqual(c["rho"], 0.54, places=12)
        self.assertAlmostEqual(c["d"], 0.18, places=12)

    # --- paths ----------------------------------------------------------------------------

    def test_right_angle_min_radius(self):
        d = self.drawing()
        d.lw([(0, 0), (4, 0), (4, 3)])
        data = self.ok(d.save())
        ref = ref_polyline([(0, 0), (4, 0), (4, 3)])
        # Eq. 4.2 gives 0.3 m at a right angle, below the minimum: 0.5 m + 1 %.
        self.assertAlmostEqual(ref.pieces[1][2], 0.505)
        self.assertAlmostEqual(ref.length, 7 - 2 * 0.505 + 0.505 * math.pi / 2)
        self.assert_follows(data, ref, 0.5)
        self.assertEqual((data["start"]["x"], data["start"]["y"], data["start"]["heading_deg"]),
                         (0.0, 0.0, 0.0))
        last = data["path"][-1]
        self.assertEqual((last["x"], last["y"], last["heading_deg"]), (4.0, 3.0, 90.0))

    def test_eq_4_2_radius_with_scales(self):
        """A 60-degree right turn (theta1 = 120 degrees), K = 0.5, kx = ky = 2: rho = 0.5 * 2 *
        (1 - cos 120) = 1.5 m, tangent length 1.5 tan 30 degrees."""
        pts = [(0, 0), (3, 0), (3 + 3 * math.cos(math.radians(-60)), 3 * math.sin(
            math.radians(-60)))]
        d = self.drawing()
        d.lw(pts)
        data = self.ok(d.save(), "--scale-x", 2, "--scale-y", 2, "--radius-multiplier", 0.5,
                       "--step", 0.3, "--speed", 1.25)
        m = [(2 * x, 2 * y) for x, y in pts]
        ref = ref_polyline(m, k_mult=0.5, k_mean=2.0)
        self.assertAlmostEqual(ref.pieces[1][2], 1.5)
        self.assertAlmostEqual(math.dist(ref.pieces[0][2], m[1]), 1.5 * math.tan(math.pi / 6))
        self.assert_follows(data, ref, 0.3, speed=1.25)

    def test_unequal_scales(self):
        pts = [(0, 0), (2, 0), (2, 8), (6, 12)]
        d = self.drawing()
        d.lw(pts)
        data = self.ok(d.save(), "--scale-x", 2, "--scale-y", 0.5, "--radius-multiplier", 1.2,
                       "--min-radius", 0.3)
        ref = ref_polyline([(2 * x, 0.5 * y) for x, y in pts], k_mult=1.2, k_mean=1.25, rmin=0.3)
        self.assert_follows(data, ref, 0.5)

    def test_polyline_vertex_as_in_appendix_a(self):
        """Seed 002's Path #2 in centimetres as an R12 POLYLINE/VERTEX, scaled to metres with the
        radius multiplier in centimetres: the same path as the LWPOLYLINE in metres."""
        cm = [(400, 200), (250, 400), (400, 600), (300, 700)]
        d = self.drawing("cm.dxf", "R12")
        d.poly(cm)
        a = self.ok(d.save(), "--scale-x", 0.01, "--scale-y", 0.01, "--radius-multiplier", 30,
                    "--min-radius", 0.3)
        m = [(x / 100, y / 100) for x, y in cm]
        ref = ref_polyline(m, k_mult=0.3, rmin=0.3)
        self.assertEqual([round(p[2], 9) for p in ref.pieces if p[0] == "arc"],
                         [round(0.3 * (1 + 0.28), 9), round(0.3 * (1 + 0.1 * math.sqrt(2)), 9)])
        self.assert_follows(a, ref, 0.5)
        d2 = self.drawing("m.dxf")
        d2.lw(m)
        b = self.ok(d2.save(), "--radius-multiplier", 0.3, "--min-radius", 0.3)
        for p, q in zip(poses(a), poses(b)):
            self.assertLess(math.dist((p["x"], p["y"]), (q["x"], q["y"])), 2e-6)

    def test_bulges_become_arcs(self):
        """A U-turn drawn with bulges (tangent to its straights: no corner), both senses, in both
        entity kinds; a bulge of 0.2 (45.2 degrees) too."""
        for kind in ("lw", "poly"):
            for sense in (1.0, -1.0):
                pts = [(0, 0), (3, 0), (3, 2 * sense), (0, 2 * sense)]
                b = [0, sense, 0, 0]
                d = self.drawing(f"{kind}{sense}.dxf", "R12" if kind == "poly" else "R2010")
                getattr(d, kind)(pts, b)
                data = self.ok(d.save(), "--step", 0.4)
                ref = ref_polyline(pts, b)
                self.assertEqual(ref.pieces[1][2], 1.0)
                self.assertAlmostEqual(ref.length, 3 + math.pi + 3)
                self.assert_follows(data, ref, 0.4)
        pts = [(0, 0), (2, 0)]
        b = [0.2, 0]
        d = self.drawing("b.dxf")
        d.lw(pts, b)
        data = self.ok(d.save(), "--step", 0.25)
        ref = ref_polyline(pts, b)
        self.assertAlmostEqual(data["start"]["heading_deg"], math.degrees(4 * math.atan(0.2)) / 2
                               * -1 % 360, places=4)
        self.assert_follows(data, ref, 0.25)

    def test_corner_next_to_a_bulge(self):
        """A straight at 45 degrees meets a counter-clockwise quarter circle (radius 2, centre
        (4, 2)) that starts heading 0: a 45-degree right corner. The blend must be one circle of
        the Eq. 4.2 radius tangent to the straight and (externally) to the arc."""
        pts = [(0, -4), (4, 0), (6, 2), (6, 6)]
        b = [0, math.tan(math.pi / 8), 0, 0]
        d = self.drawing()
        d.lw(pts, b)
        k = 0.3
        data = self.ok(d.save(), "--step", 0.05, "--radius-multiplier", k)
        rho = max(k * (1 + math.cos(math.radians(45))), 0.505)
        ps = poses(data)
        line = Ref([("line", (0, -4), (4, 0))])
        arc = Ref([("arc", (4, 2), 2.0, -math.pi / 2, math.pi / 2)])
        tail = Ref([("line", (6, 2), (6, 6))])
        blend = [p for p in ps if min(line.distance((p["x"], p["y"])), arc.distance(
            (p["x"], p["y"])), tail.distance((p["x"], p["y"]))) > 1e-5]
        self.assertGreaterEqual(len(blend), 5)
        centres = []
        for p in blend:
            h = math.radians(p["heading_deg"])  # a right turn: the centre on the right
            centres.append((p["x"] + rho * math.sin(h), p["y"] - rho * math.cos(h)))
        c = centres[0]
        for q in centres:
            self.assertLess(math.dist(q, c), 1e-5)
        # Tangent to the straight (distance rho from its line) and to the arc's circle.
        self.assertAlmostEqual(abs(c[0] - c[1] - 4) / math.sqrt(2), rho, places=5)
        self.assertAlmostEqual(math.dist(c, (4, 2)), 2.0 + rho, places=5)
        self.assertLess(min(line.distance((p["x"], p["y"])) for p in ps), 1e-9 + 1e-6)
        self.assert_smooth(ps, max_curvature=1 / rho)

    def assert_smooth(self, ps, max_curvature):
        """Heading continuity: consecutive poses turn at most spacing x the largest curvature,
        and the spacing is equal (chords at most the arc length between)."""
        chords = [math.dist((a["x"], a["y"]), (b["x"], b["y"])) for a, b in zip(ps, ps[1:])]
        spacing = max(chords)
        for a, b, ch in zip(ps, ps[1:], chords):
            turn = math.radians(angle_diff_deg(a["heading_deg"], b["heading_deg"]))
            self.assertLessEqual(turn, spacing * max_curvature + 1e-5)
            # a chord of an arc of length s turning `turn`: s sinc(turn / 2)
            expect = spacing * (math.sin(turn / 2) / (turn / 2) if turn > 1e-9 else 1.0)
            self.assertLess(abs(ch - expect), 2e-3 * spacing + 5e-6, (a, b))

    def test_closed_path(self):
        """A closed rectangle starts and ends at its first vertex, which is not blended."""
        pts = [(0, 0), (6, 0), (6, 4), (0, 4)]
        for kind in ("lw", "poly"):
            d = self.drawing(kind + ".dxf", "R12" if kind == "poly" else "R2010")
            getattr(d, kind)(pts, closed=True)
            data = self.ok(d.save())
            ref = ref_polyline(pts, closed=True)
            self.assertEqual(sum(1 for p in ref.pieces if p[0] == "arc"), 3)
            self.assert_follows(data, ref, 0.5)
            last = data["path"][-1]
            self.assertEqual((last["x"], last["y"], last["heading_deg"]), (0.0, 0.0, 270.0))
        # The same drawn open with the first vertex repeated at the end: the same path.
        d = self.drawing("open.dxf")
        d.lw(pts + [pts[0]])
        self.assertEqual(self.ok(d.save()), data)

    def test_polylines_chained_in_drawing_order(self):
        d = self.drawing()
        d.lw([(0, 0), (4, 0)])
        d.lw([(4, 0), (4, 3), (8, 3)])
        d.msp.add_text("aisle 3")  # ignored, with a warning
        rc, err, data = run(d.save(), out=os.path.join(self.tmp, "out.json"))
        self.assertEqual(rc, 0, err)
        self.assertIn("1 TEXT ignored", err)
        self.assert_follows(data, ref_polyline([(0, 0), (4, 0), (4, 3), (8, 3)]), 0.5)

    def test_repeated_vertices_and_mirrored_plane(self):
        d = self.drawing()
        d.lw([(0, 0), (4, 0), (4, 0), (4, 3)])
        self.assert_follows(self.ok(d.save()), ref_polyline([(0, 0), (4, 0), (4, 3)]), 0.5)
        # An LWPOLYLINE drawn seen from -z (extrusion (0, 0, -1)): OCS x is -WCS x.
        d = self.drawing("mirror.dxf")
        d.lw([(0, 0), (4, 0), (4, 3)], extrusion=(0, 0, -1))
        self.assert_follows(self.ok(d.save()), ref_polyline([(0, 0), (-4, 0), (-4, 3)]), 0.5)
        d = self.drawing("mirror_b.dxf")
        d.lw([(0, 0), (3, 0), (3, 2), (0, 2)], [0, 1, 0, 0], extrusion=(0, 0, -1))
        self.assert_follows(self.ok(d.save()), ref_polyline(
            [(0, 0), (-3, 0), (-3, 2), (0, 2)], [0, -1, 0, 0]), 0.5)

    def test_step_and_spacing(self):
        """The fewest equal intervals not longer than the step: 10 m at 0.3 m is 34 of
        0.294 m; at exactly 2.5 m it is 4 intervals."""
        d = self.drawing()
        d.lw([(0, 0), (10, 0)])
        f = d.save()
        for step, n in ((0.3, 34), (2.5, 4), (0.05, 200), (50, 1)):
            data = self.ok(f, "--step", step)
            self.assertEqual(len(data["path"]), n)
            for k, p in enumerate(data["path"], 1):
                self.assertAlmostEqual(p["x"], 10 * k / n, places=6)

    # --- errors ---------------------------------------------------------------------------

    def test_empty_and_unreadable(self):
        d = self.drawing()
        self.fails(d.save(), says=["empty drawing", "found: nothing"])
        d = self.drawing("lines.dxf")
        d.msp.add_line((0, 0), (1, 0))
        d.msp.add_line((1, 0), (1, 1))
        self.fails(d.save(), says=["empty drawing", "2 LINE"])
        bad = os.path.join(self.tmp, "bad.dxf")
        with open(bad, "w") as f:
            f.write("this is not\na drawing\n")
        self.fails(bad, says=["bad.dxf", "cannot read"])
        self.fails(os.path.join(self.tmp, "missing.dxf"), says=["missing.dxf"])
        d = self.drawing("dot.dxf")
        d.lw([(1, 1), (1, 1)])
        self.fails(d.save(), says=["no length"])
        d = self.drawing("mesh.dxf", "R12")
        d.msp.add_polymesh((2, 2))
        self.fails(d.save(), says=["mesh"])

    def test_polylines_without_order(self):
        d = self.drawing()
        a = d.lw([(0, 0), (4, 0)])
        b = d.lw([(5, 0), (5, 3)])
        err = self.fails(d.save(), says=[f"LWPOLYLINE #{a.dxf.handle}",
                                         f"LWPOLYLINE #{b.dxf.handle}", "(5, 0)", "(4, 0)",
                                         "drawing order"])
        self.assertNotIn("other way", err)
        d = self.drawing("rev.dxf")
        d.lw([(0, 0), (4, 0)])
        d.lw([(4, 3), (4, 0)])
        self.fails(d.save(), says=["other way round"])
        d = self.drawing("closed.dxf")
        c = d.lw([(0, 0), (4, 0), (4, 4)], closed=True)
        d.lw([(0, 0), (-3, 0)])
        self.fails(d.save(), says=[f"#{c.dxf.handle} is closed"])

    def test_doubles_back(self):
        d = self.drawing()
        e = d.lw([(0, 0), (3, 0), (1, 0)])
        self.fails(d.save(), says=[f"vertex 1 of LWPOLYLINE #{e.dxf.handle}", "doubles back",
                                   "180.00 degrees"])
        d = self.drawing("r12.dxf", "R12")
        p = d.poly([(0, 0), (3, 0), (3, 2), (3.0 + 1e-4, 0.5)])
        v = p.vertices[2].dxf.handle
        self.fails(d.save(), says=[f"VERTEX #{v}", "doubles back"])

    def test_corner_cannot_be_blended(self):
        """A right angle after a 0.8 m segment: the 0.505 m arc needs 0.505 m of it, more than
        half."""
        d = self.drawing()
        e = d.lw([(0, 0), (0.8, 0), (0.8, 3)])
        self.fails(d.save(), says=[f"vertex 1 of LWPOLYLINE #{e.dxf.handle}", "cannot be blended",
                                   "0.505 m", "0.8 m segment before it", "more than half"])
        self.ok(d.path, "--min-radius", 0.39)  # 0.3939 m fits
        # Next to an arc: a left corner of 90 degrees into a counter-clockwise quarter circle
        # of radius 1.2 m around (-1.2, 0). A left blend of radius rho has its centre on the
        # line y = rho and at 1.2 - rho from (-1.2, 0): none for rho = 1 m (K = 1); rho =
        # 0.303 m fits (inside the quarter circle, tangent to it from within).
        d = self.drawing("arc.dxf")
        e = d.lw([(-3, 0), (0, 0), (-1.2, 1.2)], [0, math.tan(math.pi / 8), 0])
        self.fails(d.save(), "--radius-multiplier", 1.0,
                   says=[f"vertex 1 of LWPOLYLINE #{e.dxf.handle}", "cannot be blended",
                         "no arc of radius 1 m", "too short or too tight"])
        data = self.ok(d.path, "--radius-multiplier", 0, "--min-radius", 0.3, "--step", 0.05)
        rho = 0.303
        line = Ref([("line", (-3, 0), (0, 0))])
        arc = Ref([("arc", (-1.2, 0), 1.2, 0.0, math.pi / 2)])
        blend = [p for p in poses(data) if min(line.distance((p["x"], p["y"])), arc.distance(
            (p["x"], p["y"]))) > 1e-5]
        self.assertGreaterEqual(len(blend), 3)
        for p in blend:  # a left turn: the centre on the left
            h = math.radians(p["heading_deg"])
            c = (p["x"] - rho * math.sin(h), p["y"] + rho * math.cos(h))
            self.assertAlmostEqual(c[1], rho, places=5)
            self.assertAlmostEqual(math.dist(c, (-1.2, 0)), 1.2 - rho, places=5)

    def test_bulge_errors(self):
        d = self.drawing()
        e = d.lw([(0, 0), (1, 0), (1, 0.6)], [0, 1, 0])
        self.fails(d.save(), says=[f"vertex 1 of LWPOLYLINE #{e.dxf.handle}", "radius 0.3 m",
                                   "--min-radius 0.5 m"])
        self.ok(d.path, "--min-radius", 0.125, "--step", 0.4)
        self.fails(d.path, "--min-radius", 0.125, "--scale-x", 2, "--scale-y", 1,
                   says=["ellipse", "--scale-x 2", "--scale-y 1"])

    def test_step_too_long_for_an_arc(self):
        d = self.drawing()
        d.lw([(0, 0), (3, 0), (3, 2), (0, 2)], [0, 1, 0, 0])  # U-turn of radius 1 m
        err = self.fails(d.save(), "--step", 2, says=["--step 2 m", "90 degrees", "radius 1 m",
                                                       "use --step 1.5708"])
        self.assertIn("vertex 1 of LWPOLYLINE", err)
        self.ok(d.path, "--step", 1.5)
        d = self.drawing("long.dxf")
        d.lw([(0, 0), (60, 0)])
        self.fails(d.save(), "--step", 0.05, says=["1200 poses", "1024"])

    def test_bad_options(self):
        d = self.drawing()
        d.lw([(0, 0), (4, 0)])
        f = d.save()
        for args, says in ((["--step", "0"], "--step 0: out of range [0.05, 50]"),
                           (["--step", "fast"], "--step 'fast': not a number"),
                           (["--scale-x", "0"], "--scale-x 0: out of range (0, 1e+06]"),
                           (["--scale-y", "-1"], "--scale-y -1"),
                           (["--speed", "9"], "--speed 9: out of range [0.01, 5]"),
                           (["--min-radius", "0.1"], "--min-radius 0.1"),
                           (["--radius-multiplier", "nan"], "--radius-multiplier nan"),
                           (["--frobnicate"], "unrecognized arguments")):
            rc, err, _ = run(f, *args, out=os.path.join(self.tmp, "out.json"))
            self.assertEqual(rc, 2, (args, err))
            self.assertIn(says, err)

    def test_command_line(self):
        """The executable itself: a run, an error, a missing option, --help."""
        d = self.drawing()
        d.lw([(0, 0), (4, 0), (4, 3)])
        f = d.save()
        out = os.path.join(self.tmp, "p.json")
        r = subprocess.run([TOOL, f, "-o", out], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("1 corner(s) blended (radii 0.505 m)", r.stdout)
        with open(out) as fh:
            self.assertEqual(json.load(fh), self.ok(f))
        r = subprocess.run([TOOL, f, "-o", out, "--min-radius", "2"], capture_output=True,
                           text=True)
        self.assertEqual(r.returncode, 2)
        self.assertIn("cannot be blended", r.stderr)
        r = subprocess.run([TOOL, f], capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertIn("-o", r.stderr)

    # --- help and plot -------------------------------------------------------------------

    def test_help(self):
        r = subprocess.run([TOOL, "--help"], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        for s in ("--scale-x", "--scale-y", "--radius-multiplier", "--step", "--min-radius",
                  "--speed", "--plot", "metres per drawing unit", "[0.05, 50] m",
                  "[0.125, 100] m", "[0.01, 5] m/s", "Eq. 4.2", "degrees counter-clockwise"):
            self.assertIn(s, r.stdout)

    def test_plot(self):
        d = self.drawing()
        d.lw([(0, 0), (3, 0), (3, 2), (0, 2), (0, 4)], [0, 1, 0, 0, 0])
        png = os.path.join(self.tmp, "p.png")
        self.ok(d.save(), "--plot", png)
        with open(png, "rb") as f:
            head = f.read(24)
        self.assertEqual(head[:8], b"\x89PNG\r\n\x1a\n")
        width, height = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
        self.assertGreater(width, 600)
        self.assertGreater(height, 400)

    # --- the firmware's solver on the shipped drawings ------------------------------------

    @unittest.skipUnless(AGVCALC or "--agvcalc" in sys.argv, "needs --agvcalc")
    def test_firmware_solves_every_leg(self):
        """agvcalc doublearc between every two consecutive poses of the drawings in sim/paths
        (default options and others): solved with --min-radius, the segments end on the next
        pose, and the chain of double arcs stays on the blended path."""
        gen = subprocess.run([sys.executable, os.path.join(ROOT, "sim", "paths",
                                                            "make_paths.py"), self.tmp],
                             capture_output=True, text=True)
        self.assertEqual(gen.returncode, 0, gen.stderr)
        shapes = {
            "seed002_straight": ([(2.5, 2), (2.5, 7)], None),
            "seed002_two_segment": ([(4, 2), (2.5, 4), (2.5, 7)], None),
            "seed002_three_segment": ([(4, 2), (2.5, 4), (4, 6), (3, 7)], None),
            "aisle_loop": ([(0, 0), (12, 0), (12, 3), (3, 3), (3, 6), (12, 6), (12, 9), (0, 9)],
                           [0, 1, 0, 0, 0, 1, 0, 0]),
        }
        worst_dev, worst_long = {}, {}
        total = 0
        for name, (pts, b) in shapes.items():
            for opts in ((), ("--step", 0.25), ("--step", 0.1, "--min-radius", 0.3),
                         ("--min-radius", 0.3, "--radius-multiplier", 0.6),
                         ("--min-radius", 0.8, "--step", 0.3), ("--step", 0.75)):
                f = os.path.join(self.tmp, name + ".dxf")
                data = self.ok(f, *opts)
                rmin = float(opts[opts.index("--min-radius") + 1]) if "--min-radius" in opts \
                    else 0.5
                k = float(opts[opts.index("--radius-multiplier") + 1]) \
                    if "--radius-multiplier" in opts else 0.3
                ref = ref_polyline(pts, b, k_mult=k, rmin=rmin, closed=name == "aisle_loop")
                step = float(opts[opts.index("--step") + 1]) if "--step" in opts else 0.5
                self.assert_follows(data, ref, step)
                dev = self.drive(poses(data), rmin, ref)
                total += len(data["path"])
                if not opts:
                    worst_dev[name] = dev
                if opts == ("--step", 0.75):
                    worst_long[name] = dev
        print(f"\nagvcalc doublearc: {total} legs solved; worst distance from the blended path "
              "at the default options: " + ", ".join(f"{n} {v * 1e3:.3f} mm"
                                                      for n, v in worst_dev.items()))
        print("at --step 0.75: " + ", ".join(f"{n} {v * 1e3:.3f} mm"
                                              for n, v in worst_long.items()))
        self.assertLessEqual(max(worst_dev.values()), DOC_DEVIATION_M)
        self.assertLessEqual(max(worst_long.values()), DOC_DEVIATION_LONG_M)

    @unittest.skipUnless(AGVCALC or "--agvcalc" in sys.argv, "needs --agvcalc")
    def test_why_the_one_percent_room(self):
        """Poses (rounded to the tool's 1e-6) on a circle of exactly the minimum radius, 0.05
        to 0.5 m apart, both senses, 100 places around it: the solver refuses most legs; on a
        circle 1 % wider, none."""
        counts = {}
        for r in (0.5, 0.505):
            reqs = []
            for s in (0.05, 0.1, 0.25, 0.5):
                for i in range(100):
                    a0 = 2 * math.pi * i / 100
                    for sense in (1, -1):
                        ends = [{"x": round(r * math.cos(a), 6), "y": round(r * math.sin(a), 6),
                                 "heading_deg": round(math.degrees(a + sense * math.pi / 2)
                                                      % 360, 6)}
                                for a in (a0, a0 + sense * s / r)]
                        reqs.append({"op": "doublearc", "from": ends[0], "to": ends[1],
                                     "min_radius_m": 0.5, "wheelbase_m": 0.75})
            out = subprocess.run([AGVCALC], input="".join(json.dumps(q) + "\n" for q in reqs),
                                 capture_output=True, text=True, check=True).stdout
            counts[r] = (sum(not json.loads(line)["ok"] for line in out.splitlines()), len(reqs))
        print(f"\nlegs on a circle of the minimum radius: {counts[0.5][0]} of {counts[0.5][1]} "
              f"refused; 1 % wider: {counts[0.505][0]} of {counts[0.505][1]}")
        self.assertGreater(counts[0.5][0], counts[0.5][1] // 2)
        self.assertEqual(counts[0.505][0], 0)

    @unittest.skipUnless(AGV_SIM or "--agv-sim" in sys.argv, "needs --agv-sim")
    def test_scenario_runs_in_agv_sim(self):
        """DXF -> path -> agv-sim: seed 002's three-segment drawing, pasted into its scenario
        (start and path), is driven to the goal within the scenario's criteria."""
        with open(os.path.join(ROOT, "sim", "scenarios", "seed002_three_segment.json")) as f:
            sc = json.load(f)
        data = self.ok(os.path.join(ROOT, "sim", "paths", "seed002_three_segment.dxf"),
                       "--speed", sc["vehicle"]["speed_mps"],
                       "--min-radius", sc["vehicle"]["min_radius_m"])
        sc.update(data)
        scenario = os.path.join(self.tmp, "dxf.json")
        with open(scenario, "w") as f:
            json.dump(sc, f)
        report = os.path.join(self.tmp, "r.json")
        r = subprocess.run([AGV_SIM, "--scenario", scenario, "--report", report, "--quiet"],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(report) as f:
            rep = json.load(f)
        self.assertTrue(rep["path"]["reached_goal"], rep)
        print(f"\nagv-sim on the drawn path: cross-track mean "
              f"{rep['path']['cross_track_m']['mean'] * 1e3:.1f} mm, max "
              f"{rep['path']['cross_track_m']['max'] * 1e3:.1f} mm, final error "
              f"{rep['path']['final_error_m'] * 1e3:.1f} mm")

    def drive(self, ps, rmin, ref):
        reqs = [{"op": "doublearc", "from": {k: a[k] for k in ("x", "y", "heading_deg")},
                 "to": {k: b[k] for k in ("x", "y", "heading_deg")}, "min_radius_m": rmin,
                 "wheelbase_m": 0.75} for a, b in zip(ps, ps[1:])]
        r = subprocess.run([AGVCALC], input="".join(json.dumps(q) + "\n" for q in reqs),
                           capture_output=True, text=True, check=True)
        answers = [json.loads(line) for line in r.stdout.splitlines()]
        self.assertEqual(len(answers), len(reqs))
        worst = 0.0
        for q, a in zip(reqs, answers):
            self.assertTrue(a["ok"], (q, a))
            x, y = q["from"]["x"], q["from"]["y"]
            th = math.radians(q["from"]["heading_deg"])
            for seg in a["segments"]:
                r_, length = seg["radius_m"], seg["length_m"]
                if r_ is not None:
                    self.assertGreaterEqual(abs(r_), rmin * (1 - 1e-6))
                for j in range(1, 21):
                    s = length * j / 20
                    if r_ is None:
                        p = (x + s * math.cos(th), y + s * math.sin(th))
                    else:
                        p = (x + r_ * (math.sin(th + s / r_) - math.sin(th)),
                             y - r_ * (math.cos(th + s / r_) - math.cos(th)))
                    worst = max(worst, ref.distance(p))
                x, y = p
                th += 0.0 if r_ is None else length / r_
            self.assertLess(math.dist((x, y), (q["to"]["x"], q["to"]["y"])), 1e-3)
            self.assertLess(angle_diff_deg(math.degrees(th), q["to"]["heading_deg"]), 0.05)
        return worst


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--agvcalc")
    ap.add_argument("--agv-sim")
    a, rest = ap.parse_known_args()
    AGVCALC, AGV_SIM = a.agvcalc, a.agv_sim
    logging.getLogger("ezdxf").setLevel(logging.ERROR)  # R12 has no $INSUNITS: not news
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
