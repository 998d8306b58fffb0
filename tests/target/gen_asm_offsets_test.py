#!/usr/bin/env python3
"""Unit test of tools/gen_asm_offsets.py on hand-written compiler output (no toolchain)."""
import os
import subprocess
import sys
import tempfile
import unittest

TOOLS = os.path.join(os.path.dirname(__file__), "..", "..", "tools")
sys.path.insert(0, TOOLS)
import gen_asm_offsets as g  # noqa: E402

# What clang-16 -S writes for CY_OFFSET lines (the immediate with '#'), among other text.
ASM = """
	.text
	.globl	m_offsets
m_offsets:
	;APP
	.ascii	"->M_X #0"
	;NO_APP
	;APP
	.ascii	"->M_SIZE #888"
	;NO_APP
	.ascii	"->M_NEG #-5"
	.ascii	"->M_BIG #2147483648"
	.ascii	"->M_X #0"
	ret
"""


class Parse(unittest.TestCase):
    def test_markers_in_order(self):
        self.assertEqual(g.parse(ASM), [("M_X", 0), ("M_SIZE", 888), ("M_NEG", -5),
                                        ("M_BIG", 2147483648)])

    def test_conflicting_definition_names_the_symbol(self):
        with self.assertRaisesRegex(ValueError, "M_X defined twice"):
            g.parse(ASM + '\t.ascii\t"->M_X #2"\n')

    def test_unreadable_marker(self):
        with self.assertRaisesRegex(ValueError, "unreadable offset marker `M_Y #abc`"):
            g.parse('\t.ascii\t"->M_Y #abc"\n')

    def test_no_marker_at_all(self):
        with self.assertRaisesRegex(ValueError, "no CY_OFFSET markers"):
            g.parse("\tret\n")

    def test_header_from_the_command_line(self):
        with tempfile.TemporaryDirectory() as d:
            src, out = os.path.join(d, "m.s"), os.path.join(d, "m_offsets.h")
            with open(src, "w") as f:
                f.write(ASM)
            r = subprocess.run([sys.executable, os.path.join(TOOLS, "gen_asm_offsets.py"),
                                "--input", src, "--output", out, "--source", "m/m_offsets.c"],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out) as f:
                text = f.read()
            self.assertIn("#ifndef M_OFFSETS_H_GENERATED", text)
            self.assertIn("#define M_SIZE 888\n", text)
            self.assertIn("#define M_NEG  -5\n", text)
            self.assertIn("from m/m_offsets.c", text)


if __name__ == "__main__":
    unittest.main(verbosity=2)
