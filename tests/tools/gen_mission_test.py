#!/usr/bin/env python3
"""ctest tools.gen_mission (label unit): tools/gen_mission.py writes the board images' mission
from a scenario, and with --path takes the start pose and the path from a tools/dxf2path.py
result (a drawing made here with ezdxf); a pursuit scenario adds the pursuit image's
parameters, one receiver only. Expected numbers: the header's formats (Q16 metres, binary
angles of 2^32 per turn, milliseconds) applied to the JSON files' values and the seed's
defaults (docs/pursuit.md). (ctest MainImage.* compares the images' whole downloads with
agv-sim's.)"""
import json
import logging
import math
import os
import re
import subprocess
import tempfile
import unittest

import ezdxf

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GEN = os.path.join(ROOT, "tools", "gen_mission.py")
DXF2PATH = os.path.join(ROOT, "tools", "dxf2path.py")
SCENARIO = os.path.join(ROOT, "sim", "scenarios", "seed002_two_segment.json")
PURSUIT = os.path.join(ROOT, "sim", "scenarios", "seed002_straight_pursuit.json")


def q16(v):
    return round(v * 65536)


def bam(deg):
    return round(deg % 360.0 * 2**32 / 360.0) % 2**32


def header_poses(text):
    """MISSION_START and MISSION_PATH of a generated header as integers."""
    start = re.search(r"#define MISSION_START \{(-?\d+)l, (-?\d+)l, (\d+)ul\}", text)
    body = text.split("#define MISSION_PATH \\\n", 1)[1].split("\n", 1)[0]
    path = [tuple(int(g) for g in m.groups()) for m in re.finditer(
        r"\{\{(-?\d+)l, (-?\d+)l, (\d+)ul\}, (-?\d+)l, 0u\}", body)]
    n = int(re.search(r"#define MISSION_N_PATH (\d+)u", text).group(1))
    return tuple(int(g) for g in start.groups()), path, n


class GenMissionTest(unittest.TestCase):

    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory()
        self.tmp = self._tmp.name
        logging.getLogger("ezdxf").setLevel(logging.ERROR)

    def tearDown(self):
        self._tmp.cleanup()

    def gen(self, *args, scenario=SCENARIO):
        out = os.path.join(self.tmp, "mission.h")
        r = subprocess.run([GEN, scenario, "-o", out] + list(args), capture_output=True,
                           text=True)
        text = None
        if r.returncode == 0:
            with open(out) as f:
                text = f.read()
        return r, text

    def dxf_path(self, pts, step):
        dxf = os.path.join(self.tmp, "p.dxf")
        doc = ezdxf.new("R12")
        doc.modelspace().add_polyline2d(pts)
        doc.saveas(dxf)
        out = os.path.join(self.tmp, "p.json")
        r = subprocess.run([DXF2PATH, dxf, "-o", out, "--step", str(step), "--speed", "0.75"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(out) as f:
            return out, json.load(f)

    def test_scenario_path(self):
        r, text = self.gen()
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(SCENARIO) as f:
            sc = json.load(f)
        start, path, n = header_poses(text)
        st = sc["start"]
        self.assertEqual(start, (q16(st["x"]), q16(st["y"]), bam(st["heading_deg"])))
        self.assertEqual(n, len(sc["path"]))
        self.assertEqual(path, [(q16(p["x"]), q16(p["y"]), bam(p["heading_deg"]),
                                 q16(p["speed_mps"])) for p in sc["path"]])

    def test_dxf2path_result(self):
        path_json, d = self.dxf_path([(4.0, 2.0), (2.5, 4.0), (2.5, 7.0)], 0.75)
        r, text = self.gen("--path", path_json)
        self.assertEqual(r.returncode, 0, r.stderr)
        start, path, n = header_poses(text)
        st = d["start"]
        self.assertEqual(start, (q16(4.0), q16(2.0), bam(st["heading_deg"])))
        self.assertEqual(n, len(d["path"]))
        self.assertEqual(path, [(q16(p["x"]), q16(p["y"]), bam(p["heading_deg"]), q16(0.75))
                                for p in d["path"]])
        self.assertEqual(path[-1][:3], (q16(2.5), q16(7.0), 2**30))  # heading 90 degrees
        self.assertIn("with the path of " + path_json, text)
        # The rest comes from the scenario, as without --path.
        _, plain = self.gen()
        keep = [line for line in plain.splitlines()
                if not line.startswith(("/*", "#define MISSION_START", "#define MISSION_N_PATH"))
                and "{{" not in line]
        for line in keep:
            self.assertIn(line, text)

    def test_refusals(self):
        path_json, d = self.dxf_path([(0.0, 0.0), (20.0, 0.0)], 0.5)
        self.assertEqual(len(d["path"]), 40)
        r, _ = self.gen("--path", path_json)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("40 path points", r.stderr)
        self.assertIn("at most 32", r.stderr)
        self.assertIn("longer --step", r.stderr)
        bad = os.path.join(self.tmp, "bad.json")
        for content, says in (("{ not json", "bad.json"),
                              (json.dumps({"start": {"x": 0, "y": 0}, "path": [
                                  {"x": 1, "y": 0, "heading_deg": 0, "speed_mps": 1}]}),
                               "start.heading_deg"),
                              (json.dumps({"start": {"x": 0, "y": 0, "heading_deg": 0},
                                           "path": [{"x": 1, "y": "n", "heading_deg": 0,
                                                     "speed_mps": 1}]}), "path[0].y"),
                              (json.dumps([1, 2]), "dxf2path")):
            with open(bad, "w") as f:
                f.write(content)
            r, _ = self.gen("--path", bad)
            self.assertNotEqual(r.returncode, 0)
            self.assertIn(says, r.stderr)
            self.assertNotIn("Traceback", r.stderr)

    def pursuit_scenario(self, pursuit, source):
        """seed002_straight_pursuit.json with these pursuit and position_source objects."""
        with open(PURSUIT) as f:
            sc = json.load(f)
        sc["pursuit"], sc["position_source"] = pursuit, source
        path = os.path.join(self.tmp, "pursuit.json")
        with open(path, "w") as f:
            json.dump(sc, f)
        return path

    def test_pursuit_parameters(self):
        fields = r"\.(\w+) = (-?\d+|true|false)[ul]*"
        # the seed's defaults where the scenario leaves them out
        r, text = self.gen(scenario=self.pursuit_scenario({"threshold_pct": 70}, {}))
        self.assertEqual(r.returncode, 0, r.stderr)
        law = re.search(r"#define MISSION_PURSUIT_LAW \\\n(.*)", text).group(1)
        got = {k: v for k, v in re.findall(fields, law)}
        steer = round(math.atan(0.75 / 0.5) / (2 * math.pi) * 2**32)  # the vehicle's
        self.assertEqual(got, {"speed": str(q16(1.0)), "max_speed": str(q16(2.229)),
                               "k": str(q16(1.0)), "activation_ms": "400",
                               "threshold": str(q16(0.7)), "max_steer": str(steer),
                               "slow_after_ms": "1000", "stop_after_ms": "3000",
                               "regulate": "false", "pair_tol": str(q16(0.05))})
        rx = re.search(r"#define MISSION_POSRX_CONFIG \\\n(.*)", text).group(1)
        self.assertEqual(dict(re.findall(fields, rx)),
                         {"min_update_mm": "50", "max_speed_mm_s": "2229"})
        self.assertIn("#define MISSION_POSRX_BAUD 9600ul", text)
        self.assertIn("#define MISSION_PURSUIT_HEADING MAIN_HEADING_POSITIONS", text)
        # every one set
        r, text = self.gen(scenario=self.pursuit_scenario(
            {"speed_mps": 0.5, "max_speed_mps": 1.5, "smoothing_constant": 1.2,
             "activation_s": 0.25, "threshold_pct": 85, "min_update_m": 0.02,
             "heading": "nav", "slow_after_s": 2.0, "stop_after_s": 4.5,
             "regulate_speed": True, "pair_tolerance_m": 0.1}, {"baud": 115200}))
        self.assertEqual(r.returncode, 0, r.stderr)
        law = re.search(r"#define MISSION_PURSUIT_LAW \\\n(.*)", text).group(1)
        got = {k: v for k, v in re.findall(fields, law)}
        self.assertEqual(got, {"speed": str(q16(0.5)), "max_speed": str(q16(1.5)),
                               "k": str(q16(1.2)), "activation_ms": "250",
                               "threshold": str(q16(0.85)), "max_steer": str(steer),
                               "slow_after_ms": "2000", "stop_after_ms": "4500",
                               "regulate": "true", "pair_tol": str(q16(0.1))})
        self.assertIn("{ .min_update_mm = 20u, .max_speed_mm_s = 1500u }", text)
        self.assertIn("#define MISSION_POSRX_BAUD 115200ul", text)
        self.assertIn("#define MISSION_PURSUIT_HEADING MAIN_HEADING_NAV", text)
        # the other modes carry none of it
        _, plain = self.gen()
        self.assertNotIn("MISSION_PURSUIT", plain)
        self.assertNotIn("MISSION_POSRX", plain)

    def test_pursuit_two_receivers_refused(self):
        two = [{"forward_m": 0.3, "left_m": 0}, {"forward_m": 0, "left_m": 0}]
        for pursuit in ({}, {"heading": "receivers"}):
            r, _ = self.gen(scenario=self.pursuit_scenario(pursuit, {"receivers": two}))
            self.assertNotEqual(r.returncode, 0)
            self.assertIn("position_source.receivers: two receivers", r.stderr)
            self.assertIn("USCI_A1", r.stderr)
            self.assertNotIn("Traceback", r.stderr)
        # and so the heading from the two receivers
        r, _ = self.gen(scenario=self.pursuit_scenario({"heading": "receivers"}, {}))
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("pursuit.heading: 'receivers' needs two receivers", r.stderr)


if __name__ == "__main__":
    unittest.main(verbosity=2)
