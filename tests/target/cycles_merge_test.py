#!/usr/bin/env python3
"""Unit test of tools/msp430sim.py's cycle-report merge (no toolchain needed): entries are
merged by name across images, and a run of one image replaces every entry that image wrote
before (an entry it no longer prints does not linger in a reused build directory); the
stack figure of an image is the deepest of its runs."""
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tools"))
import msp430sim  # noqa: E402


def entry(name, cycles):
    return {"name": name, "cycles_max": cycles, "cycles_mean": cycles, "samples": 1}


class MergeCycles(unittest.TestCase):
    def test_a_rerun_replaces_its_image_entries_only(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cycles.json")
            msp430sim.merge_cycles(path, [entry("fix", 900), entry("old_part", 50)], None,
                                   source="optical_vectors_target")
            msp430sim.merge_cycles(path, [entry("isr_a", 120)], None, source="irq_test")
            msp430sim.merge_cycles(path, [entry("fix", 800)], None,
                                   source="optical_vectors_target")
            with open(path) as f:
                rep = json.load(f)
            got = {e["name"]: (e["cycles_max"], e["image"]) for e in rep["entries"]}
            self.assertEqual(got, {"fix": (800, "optical_vectors_target"),
                                   "isr_a": (120, "irq_test")})
            self.assertEqual(rep["clock_hz"], 16000000)

    def test_the_stack_of_an_image_is_the_deepest_of_its_runs(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cycles.json")
            for used in (194, 174):  # two tests of one board image, either order
                msp430sim.merge_cycles(path, [], None, stack={"image": "nav_board",
                                                              "used": used, "room": 6000})
            msp430sim.merge_cycles(path, [], None, stack={"image": "main_board", "used": 400,
                                                          "room": 6000})
            with open(path) as f:
                rep = json.load(f)
            self.assertEqual({e["image"]: e["used"] for e in rep["stack"]},
                             {"main_board": 400, "nav_board": 194})

    def test_entries_of_an_older_report_without_image_stay_until_renamed(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cycles.json")
            with open(path, "w") as f:
                json.dump({"clock_hz": 16000000, "entries": [entry("legacy", 7)],
                           "images": []}, f)
            msp430sim.merge_cycles(path, [entry("new", 9)], None, source="img")
            with open(path) as f:
                names = [e["name"] for e in json.load(f)["entries"]]
            self.assertEqual(names, ["legacy", "new"])

    def test_static_bounds_stay_when_the_image_reruns(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cycles.json")
            msp430sim.merge_cycles(path, [entry("isr_x", 100)], None, source="img")
            with open(path) as f:
                rep = json.load(f)
            rep["entries"][0]["static_cycles_max"] = 120
            with open(path, "w") as f:
                json.dump(rep, f)
            msp430sim.merge_cycles(path, [entry("isr_x", 90)], None, source="img")
            with open(path) as f:
                e = json.load(f)["entries"][0]
            self.assertEqual((e["cycles_max"], e["static_cycles_max"]), (90, 120))
            # an entry the image stops printing keeps only its static bound
            msp430sim.merge_cycles(path, [entry("isr_y", 5)], None, source="img")
            with open(path) as f:
                got = {e["name"]: e for e in json.load(f)["entries"]}
            self.assertEqual(got["isr_x"], {"name": "isr_x", "static_cycles_max": 120})


if __name__ == "__main__":
    unittest.main()
