#!/usr/bin/env python3
"""The board images' interrupt vectors and the simulator's interrupt numbers against the
MSP430F2618 data sheet (tests/target/datasheet/slas541_vectors.csv, typed from TI's SLAS541).

  datasheet_vectors_test.py --mspdebug-cfg tools/mspdebug-f2618.cfg main_board.elf \
      main_board_pursuit.elf nav_board.elf [--require IMAGE:HANDLER,...]...

Independent of the project's own tables (hal/include/hal/pinmap.h, the linker scripts): the
expected word of each vector comes from the data sheet's address of the interrupt source that
the board wiring (docs, below) gives a handler. Checks, per image:
  - the vector table is 32 words at 0xFFC0 (the data sheet's range 0FFC0h-0FFFFh);
  - each source the boards use points at its handler, the reset word at cy_reset, every other
    word at cy_isr_unexpected;
  - with --require IMAGE:HANDLER,... (IMAGE: the ELF's file name), those handlers are in that
    image, at their sources' words (a board's wiring: the pursuit image's position receiver);
and for tools/mspdebug-f2618.cfg: mspdebug's simulator takes interrupt I from 0xFFE0 + 2I, so
every `irq` a device is configured with must name the data sheet's address of its source.
"""
import argparse
import csv
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import stack_bound  # noqa: E402  (its ELF reader)

TABLE = os.path.join(HERE, "datasheet", "slas541_vectors.csv")

# The wiring of both boards (README "The MCU", docs/hardware.md): the data sheet's interrupt
# source -> the HAL shim that serves it. A board that does not use a source leaves it to
# cy_isr_unexpected; a board may leave out a handler only where noted.
WIRING = {
    "Timer_A3 TACCR0": "hal_isr_timera0",          # goniometer index pulse (CCI0A, P1.1)
    "Timer_A3 TACCR1-2 TAIFG": "hal_isr_timera1",  # photodetector (CCI1A, P1.2)
    "Timer_B7 TBCCR0": "hal_isr_timerb0",          # the millisecond clock
    "I/O port P1": "hal_isr_port1",                # nav-board pulse inputs P1.4-P1.7
    "I/O port P2": "hal_isr_port2",                # delta-S (P2.0), the MCP2515's /INT (P2.2)
    "NMI": "hal_isr_nmi",                          # coordinate request (RST/NMI pin)
    "USCI_A1/B1 receive": "hal_isr_uart0_rx",      # seed 002's position receiver (UCA1RXD, P3.7)
}

# mspdebug device -> {its config key: the data sheet source it raises}
SIM_DEVICES = {
    "ta": {"irq0": "Timer_A3 TACCR0", "irq1": "Timer_A3 TACCR1-2 TAIFG"},
    "tb": {"irq0": "Timer_B7 TBCCR0", "irq1": "Timer_B7 TBCCR1-6 TBIFG"},
    "p1": {"irq": "I/O port P1"},
    "p2": {"irq": "I/O port P2"},
}


def load_table(path=TABLE):
    with open(path) as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    return {r["source"]: int(r["address"], 16) for r in rows}


def check_image(elf_path, table, required=()):
    """The list of problems of one image's vector table (@p required: handlers it must have)."""
    elf = stack_bound.Elf(elf_path)
    problems = []
    sec = next((s for s in elf.sections if s["name"] == ".vectors"), None)
    if sec is None:
        return [f"{elf_path}: no .vectors section"]
    if sec["addr"] != 0xFFC0 or sec["size"] != 64:
        problems.append(f"{elf_path}: .vectors at 0x{sec['addr']:04x}, {sec['size']} bytes; the "
                        "data sheet's table is 32 words at 0xFFC0")
    words = dict(elf.words(lambda s: s["name"] == ".vectors"))
    names = {}
    for s in elf.symbols:
        if s["name"] and s["shndx"] and s["value"] not in names and not s["name"].startswith("__"):
            names.setdefault(s["value"], s["name"])

    def at(addr):
        return names.get(words.get(addr), f"0x{words.get(addr, 0):04x}")

    expected = {table["Reset"]: "cy_reset"}
    for source, handler in WIRING.items():
        expected[table[source]] = handler
    reached = {at(a) for a in range(0xFFC0, 0x10000, 2)}
    for addr in range(0xFFC0, 0x10000, 2):
        want = expected.get(addr, "cy_isr_unexpected")
        got = at(addr)
        if got == want:
            continue
        if want in WIRING.values() and got == "cy_isr_unexpected" and want not in reached:
            continue  # this board does not link that handler at all
        problems.append(f"{os.path.basename(elf_path)}: vector 0x{addr:04x} -> {got}, the data "
                        f"sheet puts {want}'s source there")
    for handler in WIRING.values():
        if handler in names.values() and handler not in reached:
            problems.append(f"{os.path.basename(elf_path)}: {handler} is linked but no vector "
                            "points at it")
    for handler in required:
        if handler not in WIRING.values():
            problems.append(f"--require {handler}: no source of the wiring has that handler")
        elif handler not in reached:
            problems.append(f"{os.path.basename(elf_path)}: no vector points at {handler}, "
                            "which this board needs")
    return problems


def check_sim_config(cfg_path, table):
    problems = []
    seen = set()
    with open(cfg_path) as f:
        for line in f:
            w = line.split()
            if len(w) == 5 and w[:2] == ["simio", "config"] and w[2] in SIM_DEVICES \
                    and w[3] in SIM_DEVICES[w[2]]:
                source = SIM_DEVICES[w[2]][w[3]]
                addr = 0xFFE0 + 2 * int(w[4], 0)
                seen.add((w[2], w[3]))
                if addr != table[source]:
                    problems.append(f"{cfg_path}: {w[2]} {w[3]} {w[4]} raises the word at "
                                    f"0x{addr:04x}; the data sheet puts {source} at "
                                    f"0x{table[source]:04x}")
    for dev, keys in SIM_DEVICES.items():
        for k in keys:
            if (dev, k) not in seen:
                problems.append(f"{cfg_path}: no `simio config {dev} {k}`")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("images", nargs="+", help="linked board images (ELF)")
    ap.add_argument("--mspdebug-cfg", required=True, help="tools/mspdebug-f2618.cfg")
    ap.add_argument("--require", action="append", default=[], metavar="IMAGE:HANDLER,...",
                    help="handlers image IMAGE (file name) must have at their vectors")
    a = ap.parse_args()
    table = load_table()
    required = {}
    for r in a.require:
        img, _, handlers = r.partition(":")
        if not handlers:
            ap.error(f"--require {r}: expected IMAGE:HANDLER,...")
        required.setdefault(img, []).extend(handlers.split(","))
    names = {os.path.basename(i) for i in a.images}
    problems = check_sim_config(a.mspdebug_cfg, table)
    problems += [f"--require {img}: no such image given" for img in required if img not in names]
    for img in a.images:
        problems += check_image(img, table, required.get(os.path.basename(img), ()))
    for p in problems:
        print(f"FAIL {p}")
    print(f"{len(a.images)} image(s), {len(table)} data sheet vectors: "
          f"{'OK' if not problems else f'{len(problems)} problem(s)'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
