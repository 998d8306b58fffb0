#!/usr/bin/env python3
"""ctest tools.campaign (label unit): tools/campaign.py's hostile worlds and figures.

Every kind's world follows the scenario schema and is the same for the same seed; each
generator puts its disturbance where docs/campaign.md says (glints beside beacons, glints in
line with a beacon seen from the route, screens across a line of sight and off the route,
pillars off the route and clear of the beacons, sensor and link values in their ranges); the
figures (nearest-rank percentile, acceptance, wrong fixes, outcomes) from hand-made runs;
the command line refuses bad input with exit 2, and --help names every option.
"""
import json
import math
import os
import subprocess
import sys
import unittest

import jsonschema

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import campaign  # noqa: E402

WORLD = os.path.join(ROOT, "sim", "scenarios", "factory_loop.json")
TOOL = os.path.join(ROOT, "tools", "campaign.py")


def load(path):
    with open(path) as f:
        return json.load(f)


class Worlds(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.base = load(WORLD)
        cls.schema = jsonschema.Draft202012Validator(
            load(os.path.join(ROOT, "docs", "schema", "scenario.schema.json")))
        cls.route = campaign.route_points(cls.base)

    def world(self, kind, seed):
        return campaign.make_world(self.base, kind, seed)

    def test_every_world_follows_the_schema_and_repeats(self):
        for kind in campaign.KINDS:
            for seed in range(1, 21):
                w = self.world(kind, seed)
                errs = [e.message for e in self.schema.iter_errors(w)]
                self.assertEqual(errs, [], f"{kind} seed {seed}")
                self.assertEqual(w, self.world(kind, seed))
                self.assertEqual(w["seed"], seed)
        self.assertEqual(self.world("undisturbed", 3)["beacons"], self.base["beacons"])
        self.assertNotEqual(self.world("glint_beside", 1), self.world("glint_beside", 2))

    def new(self, w, key):
        return w.get(key, [])[len(self.base.get(key, [])):]

    def test_glints_beside_beacons(self):
        for seed in range(1, 51):
            g = self.new(self.world("glint_beside", seed), "spurious")
            self.assertTrue(2 <= len(g) <= 4)
            for s in g:
                d = min(math.hypot(s["x"] - b["x"], s["y"] - b["y"]) for b in self.base["beacons"])
                self.assertTrue(0.05 - 1e-3 <= d <= 0.4 + 1e-3, d)
                self.assertTrue(0.01 <= s["width_deg"] <= 0.1)

    def test_glints_in_line_with_a_beacon_from_the_route(self):
        for seed in range(1, 51):
            for s in self.new(self.world("glint_inline", seed), "spurious"):
                # Some route point and beacon are collinear with it (within rounding).
                best = min(abs(math.remainder(
                    math.atan2(s["y"] - p[1], s["x"] - p[0]) -
                    math.atan2(b["y"] - p[1], b["x"] - p[0]), 2 * math.pi))
                    for p in self.route for b in self.base["beacons"]
                    if math.hypot(b["x"] - p[0], b["y"] - p[1]) > 1.0)
                self.assertLess(best, 1e-3)

    def test_screens_stand_across_a_line_of_sight_off_the_route(self):
        for seed in range(1, 51):
            occ = self.new(self.world("screen", seed), "occluders")
            self.assertTrue(2 <= len(occ) <= 4, len(occ))
            for o in occ:
                a, e = (o["x1"], o["y1"]), (o["x2"], o["y2"])
                self.assertTrue(0.6 - 1e-3 <= math.dist(a, e) <= 2.0 + 1e-3)
                self.assertGreaterEqual(min(campaign.seg_dist(q, a, e) for q in self.route),
                                        0.6 - 1e-3)
                near = min(math.hypot((a[0] + e[0]) / 2 - b["x"], (a[1] + e[1]) / 2 - b["y"])
                           for b in self.base["beacons"])
                self.assertLessEqual(near, 1.5 + 1e-3)

    def test_pillars_keep_off_the_route_and_the_beacons(self):
        for seed in range(1, 51):
            pil = self.new(self.world("pillars", seed), "pillars")
            self.assertTrue(3 <= len(pil) <= 8)
            for p in pil:
                r = p["diameter_m"] / 2
                self.assertGreaterEqual(min(math.hypot(q[0] - p["x"], q[1] - p["y"])
                                            for q in self.route), 1.0 + r - 1e-3)
                for b in self.base["beacons"]:
                    self.assertGreater(math.hypot(b["x"] - p["x"], b["y"] - p["y"]),
                                       r + b["diameter_m"] / 2)

    def test_sensor_and_link_values_in_their_ranges(self):
        for seed in range(1, 51):
            s = self.world("all", seed)["sensors"]
            self.assertTrue(0.01 <= s["goniometer"]["noise_deg"] <= 0.04)
            self.assertTrue(0.01 <= abs(s["gyro"]["drift_deg_per_s"]) <= 0.05)
            self.assertTrue(0.985 <= s["odometer"]["scale"] <= 0.999)
            self.assertTrue(0.05 <= s["goniometer"]["index_loss"] <= 0.25)
            for k in ("missed", "extra"):
                self.assertTrue(1e-4 <= s["odometer"][k] <= 1e-3 + 1e-9)
            t = campaign.travel_time(self.base)
            for w in s["goniometer"]["dropouts"]:
                self.assertTrue(1.0 <= w["duration_s"] <= 6.0 and 2.0 <= w["t_s"] <= t)
            faults = self.world("all", seed)["link"]["faults"]
            drops = [f for f in faults if f["kind"] == "drop"]
            corrupts = [f for f in faults if f["kind"] == "corrupt"]
            self.assertTrue(1 <= len(drops) <= 3 and len(corrupts) == 1)
            for f in drops:
                self.assertTrue(0.02 <= f["duration_s"] <= 0.1 and f["count"] == 0)
            self.assertTrue(0.1 <= corrupts[0]["duration_s"] <= 0.5)
            self.assertTrue(1 <= corrupts[0]["count"] <= 8)
            self.assertEqual([f["at_s"] for f in faults], sorted(f["at_s"] for f in faults))


class Figures(unittest.TestCase):

    def test_percentile_is_nearest_rank(self):
        v = [0.1 * i for i in range(1, 21)]
        self.assertEqual(campaign.percentile(v, 0.95), v[18])  # ceil(0.95 * 20) = 19th
        self.assertEqual(campaign.percentile([], 0.95), 0.0)
        self.assertEqual(campaign.percentile([3.0], 0.95), 3.0)

    def test_summary_of_hand_made_runs(self):
        runs = [
            {"outcome": "goal", "stop_reason": None, "attempted": 10, "accepted": 8,
             "possible": 9, "errors_m": [0.01, 0.02, 0.06]},
            {"outcome": "stopped", "stop_reason": "blind_distance", "attempted": 5,
             "accepted": 1, "possible": 1, "errors_m": [0.2]},
        ]
        s = campaign.summarise(runs, 0.05)
        self.assertEqual((s["runs"], s["accepted"], s["possible"], s["attempted"]), (2, 9, 10, 15))
        self.assertAlmostEqual(s["acceptance"], 0.9)
        self.assertEqual(s["wrong"], 2)
        self.assertEqual(s["error_max_m"], 0.2)
        self.assertEqual(s["error_p95_m"], 0.2)
        self.assertEqual((s["goal"], s["stopped"]), (1, 1))
        self.assertEqual(s["stop_reasons"], {"blind_distance": 1})
        t = campaign.table({"x": s, "overall": s}, ["x"], 0.05)
        self.assertIn("| x | 2 | 9 / 10 | 90.0 % | 2 | 200.0 | 200.0 | 1 | 1 (1 blind_distance) |",
                      t)


class CommandLine(unittest.TestCase):

    def run_tool(self, *args):
        return subprocess.run([sys.executable, TOOL] + list(args), capture_output=True,
                              text=True)

    def test_help_names_every_option(self):
        r = self.run_tool("--help")
        self.assertEqual(r.returncode, 0)
        for opt in ("--seeds", "--kinds", "--jobs", "--agv", "--wrong-m", "--min-ratio",
                    "--json", "--plot", "--title", "--keep", "--assert", "--quiet"):
            self.assertIn(opt, r.stdout)
        for kind in campaign.KINDS:
            self.assertIn(kind, r.stdout)

    def test_bad_input_exits_2(self):
        self.assertEqual(self.run_tool(WORLD, "--kinds", "glint,rain").returncode, 2)
        self.assertEqual(self.run_tool(WORLD, "--seeds", "x").returncode, 2)
        self.assertEqual(self.run_tool(WORLD, "--agv", "/nonexistent").returncode, 2)
        r = self.run_tool("/nonexistent.json", "--agv", sys.executable)
        self.assertEqual(r.returncode, 2)
        self.assertIn("nonexistent.json", r.stderr)


if __name__ == "__main__":
    unittest.main()
