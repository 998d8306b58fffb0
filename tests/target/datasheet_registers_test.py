#!/usr/bin/env python3
"""Every register address and bit value the MSP430 HAL uses, against tables typed from TI's
documents (tests/target/datasheet/: SLAS541's register table, SLAU144's register
descriptions and SVS levels), not the project's own header.

  datasheet_registers_test.py [--hal hal/msp430]

Checks:
  - each `#define NAME CY_REG8(addr)` / `CY_REG16(addr)` of f2618.h names a register of
    slas541_registers.csv with that address and width;
  - each bit or field constant (`#define NAME 0x..u`) has SLAU144's value
    (slau144_bits.csv); VLD_<volts> settings select the SVS level of that voltage
    (slau144_svs_levels.csv);
  - the assembly sources' `.set NAME, addr` register names (mspabi_mul.S) likewise;
  - no other source of the HAL spells a register address itself (CY_REG8/CY_REG16 with a
    number outside f2618.h, or an absolute `&0x...` operand in assembly), except the
    simulator's console byte at 0x00FF, which is no register of the chip.
"""
import argparse
import csv
import glob
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
DATASHEET = os.path.join(HERE, "datasheet")
SIM_CONSOLE = 0x00FF  # tools/mspdebug-f2618.cfg: `simio add console`, not a chip register

REG_RE = re.compile(r"^#define\s+(\w+)\s+CY_REG(8|16)\((0x[0-9A-Fa-f]+)\)")
BIT_RE = re.compile(r"^#define\s+(\w+)\s+(0x[0-9A-Fa-f]+)u?\b")
SET_RE = re.compile(r"^\s*\.set\s+(\w+)\s*,\s*(0x[0-9A-Fa-f]+)")
VLD_RE = re.compile(r"^VLD_(\d+)V(\d+)$")


def table(name):
    with open(os.path.join(DATASHEET, name)) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def parse_header(path):
    regs, bits = {}, {}
    with open(path) as f:
        for line in f:
            m = REG_RE.match(line)
            if m:
                regs[m.group(1)] = (int(m.group(3), 16), int(m.group(2)))
                continue
            m = BIT_RE.match(line)
            if m:
                bits[m.group(1)] = int(m.group(2), 16)
    return regs, bits


def check(hal):
    problems = []
    registers = {r["name"]: (int(r["address"], 16), int(r["width"])) for r in
                 table("slas541_registers.csv")}
    by_addr = {a: n for n, (a, _) in registers.items()}
    bit_values = {r["name"]: int(r["value"], 16) for r in table("slau144_bits.csv")}
    levels = {float(r["volts"]): int(r["vld"]) for r in table("slau144_svs_levels.csv")}

    regs, bits = parse_header(os.path.join(hal, "f2618.h"))
    if not regs or not bits:
        problems.append(f"{hal}/f2618.h: no register or bit definitions found")
    for name, (addr, width) in sorted(regs.items()):
        if name not in registers:
            problems.append(f"f2618.h: {name} ({addr:#06x}) is not in SLAS541's register table")
        elif registers[name] != (addr, width):
            a, w = registers[name]
            problems.append(f"f2618.h: {name} = {addr:#06x} ({width}-bit), SLAS541: {a:#06x} "
                            f"({w}-bit)")
    for name, value in sorted(bits.items()):
        m = VLD_RE.match(name)
        if m:
            volts = float(f"{m.group(1)}.{m.group(2)}")
            if volts not in levels:
                problems.append(f"f2618.h: {name}: SLAU144 has no SVS level of {volts} V")
            elif value != levels[volts] << 4:
                problems.append(f"f2618.h: {name} = {value:#04x}, SLAU144: VLDx = "
                                f"{levels[volts]} ({levels[volts] << 4:#04x}) for {volts} V")
        elif name not in bit_values:
            problems.append(f"f2618.h: {name} ({value:#x}) is not in SLAU144's bit table")
        elif bit_values[name] != value:
            problems.append(f"f2618.h: {name} = {value:#x}, SLAU144: {bit_values[name]:#x}")

    for path in sorted(glob.glob(os.path.join(hal, "*.S"))):
        with open(path) as f:
            for n, line in enumerate(f, 1):
                where = f"{os.path.basename(path)}:{n}"
                m = SET_RE.match(line)
                if m:
                    name, addr = m.group(1), int(m.group(2), 16)
                    if name not in registers:
                        problems.append(f"{where}: .set {name} is not a register of SLAS541")
                    elif registers[name][0] != addr:
                        problems.append(f"{where}: {name} = {addr:#06x}, SLAS541: "
                                        f"{registers[name][0]:#06x}")
                for lit in re.findall(r"&(0x[0-9A-Fa-f]+|\d+)\b", line.split(";")[0]):
                    problems.append(f"{where}: absolute address {lit} spelled out: use the "
                                    "name from f2618.h")
    for path in sorted(glob.glob(os.path.join(hal, "*.c")) + glob.glob(os.path.join(hal, "*.h"))):
        if os.path.basename(path) == "f2618.h":
            continue
        with open(path) as f:
            for n, line in enumerate(f, 1):
                for lit in re.findall(r"CY_REG(?:8|16)\((0x[0-9A-Fa-f]+|\d+)\)", line):
                    a = int(lit, 0)
                    if a == SIM_CONSOLE:
                        continue
                    name = by_addr.get(a, "no register of SLAS541's table")
                    problems.append(f"{os.path.basename(path)}:{n}: register {a:#06x} ({name}) "
                                    "defined outside f2618.h")
    return problems, len(regs), len(bits)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--hal", default=os.path.join(ROOT, "hal", "msp430"),
                    help="the MSP430 HAL directory (default: hal/msp430)")
    a = ap.parse_args()
    problems, nregs, nbits = check(a.hal)
    for p in problems:
        print(f"FAIL {p}")
    print(f"f2618.h: {nregs} registers, {nbits} bit values against SLAS541/SLAU144: "
          f"{'OK' if not problems else f'{len(problems)} problem(s)'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
