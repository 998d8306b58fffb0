#!/usr/bin/env python3
"""Unit test of tools/doc_figures.py on a hand-written cycle report and document."""
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
        self.assertIn("differs from the cycle report", r.stderr)
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
        self.assertIn("no entry nosuch", r.stderr)
        self.assertIn("without `<!-- cycles end -->`", r.stderr)

    def test_other_tree(self):
        self.assertEqual(self.run_tool("--tree", "msp430-c", "--write").returncode, 0)
        self.assertIn("| `fix` | 28,920 |", self.text().split("msp430-c")[1])
        self.assertIn("| stale |", self.text())

    def test_no_report(self):
        os.remove(self.report)
        r = self.run_tool()
        self.assertEqual(r.returncode, 1)
        self.assertIn("run the target tests first", r.stderr)


if __name__ == "__main__":
    unittest.main()
