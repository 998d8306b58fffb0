#!/usr/bin/env python3
"""An NMI raised inside a hardware multiply must not change the multiply's result.

  nmi_multiply_test.py IMAGE.elf     (the nav board image: its NMI is the coordinate request)

The 16 x 16 multiplier (MPY/OP2/RESLO at 0x130) holds one operation's state; the multiply
helpers (__mspabi_mpyi_hw, __mspabi_mpyl_hw) disable interrupts around it, which holds off
every interrupt but the NMI. In mspdebug's simulator, with the chip's NMI entry emulated
(tools/msp430sim.py): run the image to its main loop, then raise the nav board's pulse inputs
until a handler calls a multiply helper with operands other than 0 and 1; at the helper's
entry read its operands, compute the product in Python, and
  1. (control) let that call run: the helper must return the product;
  2. on the next call, stop right before its first write of OP2 (the multiplier's first
     operand is loaded, the multiply not started), pull the RST/NMI pin low (the coordinate
     request), and let it run: the NMI's handler runs before the OP2 write, then the helper
     must still return the product.
Fails (exit 1) when the result is wrong: the NMI's handler used the multiplier in between.
"""
import argparse
import os
import re
import subprocess
import sys
import types

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import msp430sim  # noqa: E402

HELPERS = {"__mspabi_mpyi_hw": 16, "__mspabi_mpyl_hw": 32}
OP2 = 0x0138
REG_RE = re.compile(r"\(\s*(PC|SP|SR|R\d+):\s*([0-9a-fA-F]+)\)")
# The nav board's pulse inputs on port 1 (docs/hardware.md): odometer, gyro up/down, beacon.
STIMULI = [("p1", 7), ("p1", 4), ("p1", 5), ("p1", 6)]


def registers(lines):
    regs = {}
    for line in lines:
        for name, value in REG_RE.findall(line):
            regs[name] = int(value, 16)
    return regs


def op2_writes(objdump, elf, start, end):
    """Addresses of the instructions in [start, end) that write OP2 (`mov rN, &312`)."""
    out = subprocess.run([objdump, "-d", "--no-show-raw-insn", f"--start-address={start}",
                          f"--stop-address={end}", elf], capture_output=True, text=True,
                         check=True).stdout
    found = []
    for line in out.splitlines():
        m = re.match(r"^\s*([0-9a-f]+):\s+mov\s+r\d+, &(\d+)\s*$", line)
        if m and int(m.group(2)) == OP2:
            found.append(int(m.group(1), 16))
    return found


class Session:
    def __init__(self, elf, log):
        self.elf = elf
        self.syms = msp430sim.symbols(elf)
        self.sim = msp430sim.Mspdebug(log)
        for c in msp430sim.devices():
            self.sim.cmd(c)
        self.sim.cmd(f"prog {elf}", timeout=60)
        self.sim.cmd("reset")
        args = types.SimpleNamespace(dco_cal="typical", sim_nmi=False, uart=False, vcc=None)
        self.chip = msp430sim.Chip(self.sim, args, self.syms, msp430sim.vector_words(elf))
        self.chip.reset_state()

    def run_to(self, targets, slice_s=2.0):
        """Run until PC is one of @targets (the NMI entry is handled on the way); None when
        the image did not get there within one slice."""
        while True:
            lines, broken = self.sim.run(slice_s)
            _, _, pc = msp430sim.split_run_output(lines, broken)
            if pc in targets:
                return pc, registers(lines)
            if pc == self.chip.nmi_pc:
                self.chip.on_nmi()
                continue
            if pc == self.syms["cy_halt"]:
                raise msp430sim.SimError("the image stopped (cy_halt)")
            if broken:
                return None, None
            raise msp430sim.SimError(f"unexpected stop at 0x{pc or 0:04x}")

    def word(self, addr):
        for line in self.sim.cmd(f"md 0x{addr:04x} 2"):
            m = msp430sim.MD_RE.match(line)
            if m:
                b = [int(x, 16) for x in m.group(2).split()]
                return b[0] | b[1] << 8
        raise msp430sim.SimError(f"md 0x{addr:04x} returned nothing")

    def next_multiply(self, entries):
        """Stimulate the pulse inputs until a helper is entered: (name, operands, product)."""
        for b in entries:
            self.sim.cmd(f"setbreak 0x{b:04x}")
        try:
            for dev, pin in STIMULI * 2:
                for level in (1, 0):
                    self.sim.cmd(f"simio config {dev} set {pin} {level}")
                    pc, regs = self.run_to(set(entries), slice_s=0.3)
                    if pc is not None:
                        return pc, regs
        finally:
            self.sim.cmd("delbreak")
            if self.chip.nmi_pc is not None:
                self.sim.cmd(f"setbreak 0x{self.chip.nmi_pc:04x}")
        raise msp430sim.SimError("no handler reached a multiply helper")


def expected(width, regs):
    if width == 16:
        return (regs["R12"] * regs["R13"]) & 0xFFFF, f"{regs['R12']} x {regs['R13']}"
    a = regs["R12"] | regs["R13"] << 16
    b = regs["R14"] | regs["R15"] << 16
    return (a * b) & 0xFFFFFFFF, f"{a} x {b}"


def result(width, regs):
    return regs["R12"] if width == 16 else regs["R12"] | regs["R13"] << 16


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("image")
    ap.add_argument("--objdump", default="llvm-objdump-16")
    ap.add_argument("--loop", default="nav_board_poll", help="the main loop's symbol")
    ap.add_argument("--log", help="write the mspdebug conversation here")
    a = ap.parse_args()
    log = open(a.log, "w") if a.log else None
    s = None
    try:
        s = Session(a.image, log)
        names = {s.syms[n]: n for n in HELPERS if n in s.syms}
        if not names:
            print(f"FAIL {a.image}: no hardware multiply helper linked")
            return 1
        loop = s.syms[a.loop]
        s.sim.cmd(f"setbreak 0x{loop:04x}")
        pc, _ = s.run_to({loop}, slice_s=30)
        s.sim.cmd(f"delbreak")
        s.sim.cmd(f"setbreak 0x{s.chip.nmi_pc:04x}")
        if pc != loop:
            print(f"FAIL {a.image}: never reached {a.loop}")
            return 1
        failures = []
        for with_nmi in (False, True):
            for _ in range(40):  # a multiply whose operands are neither 0 nor 1
                pc, regs = s.next_multiply(sorted(names))
                name, width = names[pc], HELPERS[names[pc]]
                want, what = expected(width, regs)
                if not re.search(r"\b[01]\b", what):
                    break
            else:
                failures.append("no multiply with operands other than 0 and 1 reached")
                break
            ret = s.word(regs["SP"])
            ends = sorted(v for v in s.syms.values() if v > pc)
            if with_nmi:
                writes = op2_writes(a.objdump, a.image, pc, ends[0])
                if not writes:
                    failures.append(f"{name}: no write of OP2 found")
                    break
                s.sim.cmd(f"setbreak 0x{writes[0]:04x}")
                at, _ = s.run_to({writes[0]})
                s.sim.cmd("delbreak")
                s.sim.cmd(f"setbreak 0x{s.chip.nmi_pc:04x}")
                s.sim.cmd("simio config wdt nmi 0")
            s.sim.cmd(f"setbreak 0x{ret:04x}")
            at, out = s.run_to({ret})
            s.sim.cmd("delbreak")
            s.sim.cmd(f"setbreak 0x{s.chip.nmi_pc:04x}")
            if with_nmi:
                s.sim.cmd("simio config wdt nmi 1")
            got = result(width, out)
            tag = "NMI before the OP2 write" if with_nmi else "no NMI (control)"
            verdict = "ok" if got == want else "WRONG"
            print(f"{name} {what} = {want}: returned {got} with {tag}: {verdict}")
            if got != want:
                failures.append(f"{name} {what} returned {got}, not {want}, with {tag}")
        for f in failures:
            print(f"FAIL {f}")
        print(f"{os.path.basename(a.image)}: {'OK' if not failures else 'the NMI corrupts a multiply'}")
        return 1 if failures else 0
    except msp430sim.SimError as e:
        print(f"FAIL {a.image}: {e}")
        return 1
    finally:
        if s is not None:
            s.sim.close()
        if log:
            log.close()


if __name__ == "__main__":
    sys.exit(main())
