#!/usr/bin/env python3
"""Unit test of tools/msp430sim.py's cycle-report merge (no toolchain needed): entries are
merged by name across images, and a run of one image replaces every entry that image wrote
before (an entry it no longer prints does not linger in a reused build directory)."""
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


if __name__ == "__main__":
    unittest.main()
