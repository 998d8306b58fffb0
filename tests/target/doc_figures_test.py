#!/usr/bin/env python3
"""Unit test of tools/doc_figures.py on hand-written measurements (a cycle report, image
figures, a link map, an agv-sim that prints a fixed report) and documents."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

TOOL = os.path.join(os.path.dirname(__file__), "..", "..", "tools", "doc_figures.py")

REPORT = {"clock_hz": 16000000, "entries": [
    {"name": "fix", "cycles_max": 28920, "cycles_mean": 28918},
    {"name": "isr", "cycles_max": 142, "cycles_mean": 129},
    {"name": "kernel/prog/k/asm", "cycles_max": 2561, "cycles_mean": 2094, "samples": 350},
    {"name": "kernel/prog/k/c", "cycles_max": 33539, "cycles_mean": 22634, "samples": 350}]}

DOC = """# Title

Before.

<!-- cycles msp430: fix isr kernel/prog/k -->
| stale |
<!-- cycles end -->

<!-- cycles msp430-c: fix -->
| left alone |
<!-- cycles end -->

After.
"""

# The block as the tool must write it: thousands separated, microseconds at 16 MHz, the
# kernel's two sides in one row.
EXPECTED = """<!-- cycles msp430: fix isr kernel/prog/k -->
| entry | max | mean | max µs |
| --- | ---: | ---: | ---: |
| `fix` | 28,920 | 28,918 | 1,807.5 |
| `isr` | 142 | 129 | 8.9 |

| kernel | program | calls | asm max | asm mean | C twin max | C twin mean |
| --- | --- | ---: | ---: | ---: | ---: | ---: |
| `k` | prog | 350 | 2,561 | 2,094 | 33,539 | 22,634 |
<!-- cycles end -->"""


class DocFigures(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.report = os.path.join(self.dir.name, "cycles.json")
        self.doc = os.path.join(self.dir.name, "doc.md")
        with open(self.report, "w") as f:
            json.dump(REPORT, f)
        with open(self.doc, "w", encoding="utf-8") as f:
            f.write(DOC)

    def tearDown(self):
        self.dir.cleanup()

    def run_tool(self, *extra):
        return subprocess.run([sys.executable, TOOL, "--cycles", self.report, *extra, self.doc],
                              capture_output=True, text=True)

    def text(self):
        with open(self.doc, encoding="utf-8") as f:
            return f.read()

    def test_stale_table_fails_then_write_fixes_it(self):
        r = self.run_tool()
        self.assertEqual(r.returncode, 1)
        self.assertIn("the cycles table differs from the measurements", r.stderr)
        self.assertEqual(self.run_tool("--write").returncode, 0)
        text = self.text()
        self.assertIn(EXPECTED, text)
        self.assertIn("| left alone |", text)  # another tree's block
        self.assertTrue(text.startswith("# Title\n\nBefore.") and text.endswith("After.\n"))
        self.assertEqual(self.run_tool().returncode, 0)

    def test_missing_entry_and_unterminated_block(self):
        with open(self.doc, "w", encoding="utf-8") as f:
            f.write("<!-- cycles msp430: nosuch -->\n<!-- cycles end -->\n"
                    "<!-- cycles msp430: fix -->\n| x |\n")
        r = self.run_tool()
        self.assertEqual(r.returncode, 1)
        self.assertIn("the cycle report has no entry nosuch", r.stderr)
        self.assertIn("without `<!-- cycles end -->`", r.stderr)

    def test_other_tree(self):
        self.assertEqual(self.run_tool("--tree", "msp430-c", "--write").returncode, 0)
        self.assertIn("| `fix` | 28,920 |", self.text().split("msp430-c")[1])
        self.assertIn("| stale |", self.text())

    def write(self, rel, text):
        path = os.path.join(self.dir.name, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text if isinstance(text, str) else json.dumps(text))
        if rel.endswith("agv-sim"):
            os.chmod(path, 0o755)

    def test_images_flash_closedloop(self):
        d = self.dir.name
        with open(self.report, "w") as f:
            json.dump(dict(REPORT, stack=[{"image": "main_board", "used": 406, "room": 6548}]), f)
        self.write("images/main_board.json", {"name": "main_board", "flash": 40522,
                                              "ram": 1644, "flash_limit": 49152,
                                              "ram_limit": 6144})
        self.write("images/main_board.stack.json", {"worst": 594, "ram_budget": 6144})
        # lld's map: output sections, then input sections "file(member):(section)"
        self.write("bin/main_board.map", "\n".join([
            "     VMA      LMA     Size Align Out     In      Symbol",
            "    3100     3100     1000     2 .text",
            "    3100     3100      c00     2         /b/libcy_a.a(x.o):(.text.f)",
            "    3d00     3d00      300     2         /b/libcy_b.a(y.o):(.text.g)",
            "    4000     4000      100     2         /b/main.c.obj:(.text.main)",
            "    4100     4100       20     2 .rodata",
            "    4100     4100       20     2         /b/libcy_a.a(z.o):(.rodata.t)",
            "    1100     4120       10     2 .data",
            "    1100     4120       10     2         /b/libcy_b.a(y.o):(.data.d)",
            "    1110     1110       40     2 .bss",
            "    1110     1110       40     2         /b/libcy_a.a(x.o):(.bss.s)", ""]))
        report = {"fixes": {"attempted": 10, "accepted": 8, "error_m": {"rms": 0.0012,
                                                                          "max": 0.0029}},
                  "path": {"reached_goal": True, "cross_track_m": {"mean": 0.0031, "max": 0.024},
                           "final_error_m": 0.0042}}
        self.write("bin/agv-sim", "#!/bin/sh\n# agv-sim --scenario S --quiet --report R\n"
                   f"echo '{json.dumps(report)}' > \"$5\"\n")
        self.write("root/sim/scenarios/s1.json", {"name": "s1",
                                                  "success": {"cross_track_mean_m": 0.01}})
        with open(self.doc, "w", encoding="utf-8") as f:
            f.write("<!-- images msp430: main_board -->\n<!-- images end -->\n"
                    "<!-- flash msp430: main_board -->\n<!-- flash end -->\n"
                    "<!-- closedloop host: s1 -->\n<!-- closedloop end -->\n")
        args = ["--root", os.path.join(d, "root"), "--build", d, "--host-bin",
                os.path.join(d, "bin"), "--tree", "msp430", "--tree", "host"]
        self.assertEqual(self.run_tool(*args).returncode, 1)  # stale (empty) tables
        r = self.run_tool(*args, "--write")
        self.assertEqual(r.returncode, 0, r.stderr)
        text = self.text()
        self.assertIn("| `main_board.elf` | 40,522 B | 49,152 | 1,644 B | 594 B | 406 B | "
                      "2,238 B | 6,144 |", text)
        # 0xc00 + 0x20 = 3,104 B of libcy_a.a (its .bss is not flash), 0x300 + 0x10 = 784 B
        # of libcy_b.a, 0x100 = 256 B of the loose object: 4,144 B
        self.assertIn("| `libcy_a.a` | 3,104 B | 74.9 % |\n| `libcy_b.a` | 784 B | 18.9 % |\n"
                      "| `main.c.obj` | 256 B | 6.2 % |\n| all | 4,144 B | |", text)
        self.assertIn("| `s1` | 8 of 10 | 1.2 / 2.9 mm | 3.1 / 24.0 mm | reached, 4.2 mm | "
                      "10 mm |", text)
        self.assertEqual(self.run_tool(*args).returncode, 0)
        r = self.run_tool(*args[:-2])  # the host block left alone without --tree host
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_no_report(self):
        os.remove(self.report)
        r = self.run_tool()
        self.assertEqual(r.returncode, 1)
        self.assertIn("run the target tests first", r.stderr)


if __name__ == "__main__":
    unittest.main()
