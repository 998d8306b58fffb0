#!/usr/bin/env python3
"""Test of tools/cycle_bound.py.

  cycle_bound_test.py [--objdump llvm-objdump-16] irq_test.elf

1. Decoding: hand-assembled instruction words (the examples of SLAU144's cycle tables, one
   per addressing-mode row, and the constant-generator forms) priced by both models: SLAU144's
   figures (the constant generator counting as a register) and mspdebug 0.22's (drivers/sim.c
   charges the encodings' memory modes).
2. The simulator as the reference of its own rules: in irq_test.elf, the millisecond tick's
   handler (one path, no branch) is timed in mspdebug from its first instruction to the one
   after its RETI; the tool's mspdebug-priced worst case of the same handler must equal it,
   and SLAU144's figure must not exceed it.
"""
import argparse
import os
import sys
import types
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import cycle_bound as cb  # noqa: E402
import msp430sim  # noqa: E402
import stack_bound as sb  # noqa: E402

ARGS = None

# (word(s), text, SLAU144 cycles, mspdebug 0.22 cycles)
CASES = [
    (0x4508, "mov r5, r8", 1, 1),
    (0x4900, "br r9 (mov r9, pc)", 2, 2),
    (0x5586, "add r5, 4(r6)", 4, 4),
    (0xF425, "and @r4, r5", 2, 2),
    (0x4920, "br @r9 (mov @r9, pc)", 2, 2),
    (0x4930, "br @r9+ (mov @r9+, pc)", 3, 3),
    (0x4039, "mov #20, r9", 2, 2),
    (0x4030, "br #N (mov #N, pc)", 3, 3),
    (0x40B6, "mov #N, 0(r6)", 5, 5),
    (0x4517, "mov 2(r5), r7", 3, 3),
    (0x4218, "mov &EDE, r8", 3, 3),
    (0x4799, "add 4(r7), 6(r9) (mov form)", 6, 6),
    (0x430C, "mov #0, r12 (constant generator, R3)", 1, 1),
    (0x431C, "mov #1, r12 (constant generator, R3 indexed)", 1, 3),
    (0x432C, "mov #2, r12 (constant generator, R3 indirect)", 1, 2),
    (0x433C, "mov #-1, r12 (constant generator, R3 autoincrement)", 1, 2),
    (0x422C, "mov #4, r12 (constant generator, R2 indirect)", 1, 2),
    (0x423C, "mov #8, r12 (constant generator, R2 autoincrement)", 1, 2),
    (0xD232, "eint (bis #8, r2)", 1, 2),
    (0x53A6, "incd 4(r6)... add #2, 4(r6) (constant)", 4, 5),
    (0x1105, "rra r5", 1, 1),
    (0x1125, "rra @r5", 3, 3),
    (0x1115, "rra 2(r5)", 4, 4),
    (0x120A, "push r10", 3, 3),
    (0x1230, "push #N", 4, 4),
    (0x1219, "push 2(r9)", 5, 5),
    (0x1213, "push #1 (constant generator)", 3, 5),
    (0x128D, "call r13", 4, 4),
    (0x12AD, "call @r13", 4, 4),
    (0x12B0, "call #N", 5, 5),
    (0x1292, "call &EDE", 5, 5),
    (0x1300, "reti", 5, 5),
    (0x3C00, "jmp", 2, 2),
    (0x2400, "jeq", 2, 2),
]


class FakeElf:
    """One code section holding @words at 0x1000."""

    def __init__(self, words):
        self.data = b"".join(w.to_bytes(2, "little") for w in words)
        self.sections = [{"name": ".text", "type": sb.SHT_PROGBITS,
                          "flags": sb.SHF_ALLOC | sb.SHF_EXECINSTR, "addr": 0x1000,
                          "offset": 0, "size": len(self.data)}]


class Decoding(unittest.TestCase):
    def test_each_row(self):
        dec = cb.Decoder(FakeElf([c[0] for c in CASES]), cb.Timings())
        for i, (word, text, guide, sim) in enumerate(CASES):
            with self.subTest(text):
                self.assertEqual(dec.cost(0x1000 + 2 * i), (guide, sim), text)

    def test_interrupt_acceptance(self):
        self.assertEqual(cb.Timings().accept, 6)


class AgainstTheSimulator(unittest.TestCase):
    def test_tick_handler(self):
        elf_path = ARGS.image
        elf, image, _ = sb.load_image(elf_path, ARGS.objdump, {})
        image.analyse()
        dec = cb.Decoder(elf, cb.Timings())
        a = cb.Analysis(image, dec, {}, {})
        a._returning = cb.returning(image)
        guide, sim_static, _ = a.of("hal_isr_timerb0")
        f = image.funcs["hal_isr_timerb0"]
        reti = [x for x in image.insns if f.start <= x < f.end and image.insns[x].mnem == "reti"]
        syms = msp430sim.symbols(elf_path)
        s = msp430sim.Mspdebug(None)
        try:
            for c in msp430sim.devices():
                s.cmd(c)
            s.cmd(f"prog {elf_path}", timeout=60)
            s.cmd("reset")
            args = types.SimpleNamespace(dco_cal="typical", sim_nmi=False, uart=False, vcc=None)
            chip = msp430sim.Chip(s, args, syms, msp430sim.vector_words(elf_path))
            chip.reset_state()
            s.cmd(f"setbreak 0x{f.start:04x}")
            measured = None
            for _ in range(400):
                lines, broken = s.run(20)
                _, _, pc = msp430sim.split_run_output(lines, broken)
                if pc == chip.nmi_pc:
                    chip.on_nmi()
                    continue
                if pc == syms.get("cy_target_sync"):
                    continue
                if pc != f.start:
                    break
                c0 = s.cycles()
                s.cmd(f"setbreak 0x{reti[0]:04x}")
                lines, broken = s.run(20)
                _, _, pc = msp430sim.split_run_output(lines, broken)
                self.assertEqual(pc, reti[0])
                s.cmd("step")
                measured = s.cycles() - c0
                break
        finally:
            s.close()
        self.assertIsNotNone(measured, "the tick's handler never ran")
        self.assertEqual(sim_static, measured)
        self.assertLessEqual(guide, measured)


def main():
    global ARGS
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("image", help="irq_test.elf (its tick handler runs)")
    ap.add_argument("--objdump", default="llvm-objdump-16")
    ARGS, rest = ap.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


if __name__ == "__main__":
    main()
