#!/usr/bin/env python3
"""The pins of a board image from reset to its main loop, in mspdebug's simulator, against
the pin table of docs/hardware.md and SLAS541's pin-function tables
(tests/target/datasheet/slas541_pins.csv).

  pins_test.py --board main|pursuit|nav [--hardware docs/hardware.md] IMAGE.elf

(main: the main board's beacon image, main_board.elf; pursuit: its pursuit image,
main_board_pursuit.elf.)

Runs the image twice, with every output latch (PxOUT) preset to 0x00 and to 0xFF before the
start-up (the chip leaves PxOUT undefined at power-up), with the simulator's ports P1-P6 as
gpio devices and a tracer recording every register write. Checks:
  - after every single write to a port register, each pin is in a state the table allows
    it: its reset state (an input), its start-up state or its state on this board; an output
    at the table's level only. A pin driven before its latch was written shows up as the
    preset's level in one of the two runs; a receive line made an output, or a peripheral
    pin made a plain output before its function was selected, as a state the table does
    not list;
  - the state when the start-up is done (the board's init function is entered) is the
    table's start-up column; the state in the main loop, or at the first drive-port bus
    cycle (hal_drive_port_write) when one comes first, is the board's column (in the main
    loop the bus lines then show the last cycle's levels: only their function and direction
    are compared there).
The write-by-write check ends at the first bus cycle, of the drive port or of the SPI bus to
the MCP2515 (hal_spi_transfer): /WR and /CS pulses from then on are bus cycles. The state of a pin is what SLAS541's table
names for its PxSEL/PxDIR bits (e.g. P1.1 with SEL = 1, DIR = 0: Timer_A3.CCI0A).
"""
import argparse
import csv
import os
import re
import sys
import types

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import msp430sim  # noqa: E402

DATASHEET = os.path.join(HERE, "datasheet")
BOARDS = {"main": ("main_board_init", "main_board_poll"),
          "pursuit": ("main_board_init", "main_board_poll"),
          "nav": ("nav_board_init", "nav_board_poll")}
TRACE_DEPTH = 65536
ROW_RE = re.compile(r"^\|\s*(P\d\.\d)\s*\|(.*)\|\s*$")


def csv_rows(name):
    with open(os.path.join(DATASHEET, name)) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def port_registers():
    """{address: (port, register)} of PxOUT/PxDIR/PxSEL from SLAS541's register table."""
    out = {}
    for r in csv_rows("slas541_registers.csv"):
        m = re.match(r"^P(\d)(OUT|DIR|SEL)$", r["name"])
        if m:
            out[int(r["address"], 16)] = (int(m.group(1)), m.group(2))
    return out


def pin_functions():
    """{pin: [(function, sel, dir, io)]} from SLAS541's pin-function tables."""
    out = {}
    for r in csv_rows("slas541_pins.csv"):
        out.setdefault(r["pin"], []).append((r["function"], r["sel"], r["dir"], r["io"]))
    return out


def state_of(functions, pin, sel, dirb, out):
    """The SLAS541 name of a pin's state: 'GPIO in', 'GPIO out 0|1' or a function name."""
    if not sel:
        return f"GPIO out {out}" if dirb else "GPIO in"
    for fn, s, d, _io in functions.get(pin, []):
        if s == "1" and d in ("X", str(dirb)):
            return fn
    return f"unknown function (SEL 1, DIR {dirb})"


def load_plan(path):
    """{pin: {'startup': state, 'main': state, 'pursuit': state, 'nav': state}} from the pin
    table of docs/hardware.md (columns: pin, start-up, main board's beacon image, its pursuit
    image, nav board, signal)."""
    plan = {}
    with open(path) as f:
        for line in f:
            m = ROW_RE.match(line.rstrip())
            if m:
                cells = [c.strip().strip("`") for c in m.group(2).split("|")]
                plan[m.group(1)] = {"startup": cells[0], "main": cells[1], "pursuit": cells[2],
                                    "nav": cells[3]}
    return plan


def check_plan(plan, functions):
    """Every state the table names exists for its pin in SLAS541."""
    problems = []
    for pin in (f"P{p}.{b}" for p in range(1, 7) for b in range(8)):
        if pin not in plan:
            problems.append(f"docs/hardware.md: no row for {pin}")
            continue
        for col, st in plan[pin].items():
            if re.fullmatch(r"GPIO (in|out [01])", st):
                continue
            if st not in [f[0] for f in functions.get(pin, [])]:
                problems.append(f"docs/hardware.md: {pin} {col}: `{st}` is no function of "
                                f"{pin} in SLAS541")
    return problems


def port_dump(sim):
    """{port: {'OUT','DIR','SEL': value}} read back through the simulator's gpio devices."""
    regs = port_registers()
    out = {}
    for addr, (port, reg) in regs.items():
        line = sim.cmd(f"md 0x{addr:04x} 1")
        m = [msp430sim.MD_RE.match(l) for l in line]
        v = next(int(x.group(2).split()[0], 16) for x in m if x)
        out.setdefault(port, {})[reg] = v
    return out


def states(dump, functions):
    return {f"P{p}.{b}": state_of(functions, f"P{p}.{b}", dump[p]["SEL"] >> b & 1,
                                  dump[p]["DIR"] >> b & 1, dump[p]["OUT"] >> b & 1)
            for p in dump for b in range(8)}


def run_board(elf, board, preset, plan, functions, log=None):
    init_sym, loop_sym = BOARDS[board]
    syms = msp430sim.symbols(elf)
    for s in (init_sym, loop_sym, "cy_halt"):
        if s not in syms:
            raise msp430sim.SimError(f"{elf}: no symbol {s}")
    problems = []
    sim = msp430sim.Mspdebug(log)
    try:
        for c in msp430sim.devices():
            sim.cmd(c)
        sim.cmd(f"simio add tracer pins {TRACE_DEPTH}")
        sim.cmd(f"prog {elf}", timeout=60)
        sim.cmd("reset")
        args = types.SimpleNamespace(dco_cal="typical", sim_nmi=False, uart=False, vcc=None)
        msp430sim.Chip(sim, args, syms, msp430sim.vector_words(elf)).reset_state()
        regs = port_registers()
        for addr, (port, reg) in sorted(regs.items()):
            if reg == "OUT":
                sim.cmd(f"mw 0x{addr:04x} 0x{preset:02x}")
        sim.cmd("simio config pins clear")
        stops = {syms[init_sym]: "startup", syms[loop_sym]: "loop", syms["cy_halt"]: "halt"}
        if "hal_drive_port_write" in syms:
            stops[syms["hal_drive_port_write"]] = "bus"
        if "hal_spi_transfer" in syms:
            stops[syms["hal_spi_transfer"]] = "spi"
        for a in stops:
            sim.cmd(f"setbreak 0x{a:04x}")
        seen, trace = {}, None
        while "loop" not in seen:
            lines, _ = sim.run(30)
            _, _, pc = msp430sim.split_run_output(lines, False)
            what = stops.get(pc)
            if what is None or what == "halt":
                raise msp430sim.SimError(f"stopped at 0x{pc or 0:04x} ({what or 'no stop'}) "
                                         f"before {loop_sym}")
            seen.setdefault(what, states(port_dump(sim), functions))
            if what in ("bus", "spi", "loop") and trace is None:
                trace = sim.cmd("simio info pins", check=False, timeout=120)
        events = [msp430sim.TRACE_RE.match(l) for l in trace]
        events = [(m.group(2), int(m.group(4), 16), int(m.group(5) or "0", 16))
                  for m in events if m]
        if len(events) >= TRACE_DEPTH - 1:
            problems.append(f"the tracer's {TRACE_DEPTH} events overflowed: enlarge it")
        problems += replay(events, regs, preset, plan, board, functions)
        # The board's column holds before the first bus cycle (or in the main loop when none
        # comes first); in the main loop the functions and directions still hold, the bus
        # lines' levels being those of the last cycle.
        board_at = "bus" if "bus" in seen else "loop"
        checks = [("startup", "startup", "the end of the start-up", lambda x: x),
                  (board_at, board, "the main loop" if board_at == "loop" else
                   "the first drive-port bus cycle", lambda x: x),
                  ("loop", board, "the main loop (levels aside)",
                   lambda x: re.sub(r"^GPIO out [01]$", "GPIO out", x))]
        for what, col, when, norm in checks:
            for pin, st in sorted(seen[what].items()):
                want = plan[pin][col]
                if norm(st) != norm(want):
                    problems.append(f"{pin} at {when}: `{st}`, docs/hardware.md: `{want}`")
        return problems, events
    finally:
        sim.close()


def replay(events, regs, preset, plan, board, functions):
    """Every write to a port register, in order: each pin's state after it must be one the
    table allows that pin (its reset state, its start-up state, its state on this board)."""
    state = {p: {"OUT": preset, "DIR": 0, "SEL": 0} for p in range(1, 7)}
    problems = []
    for n, (rw, addr, value) in enumerate(events):
        if rw != "write" or addr not in regs:
            continue
        port, reg = regs[addr]
        state[port][reg] = value
        for b in range(8):
            pin = f"P{port}.{b}"
            st = state_of(functions, pin, state[port]["SEL"] >> b & 1,
                          state[port]["DIR"] >> b & 1, state[port]["OUT"] >> b & 1)
            allowed = {"GPIO in", plan[pin]["startup"], plan[pin][board]}
            if st not in allowed:
                problems.append(f"{pin}: `{st}` after write {n} (P{port}{reg} = 0x{value:02x}, "
                                f"latches preset 0x{preset:02x}); allowed: "
                                f"{', '.join(sorted(allowed))}")
                break
    return problems


def write_order(events, regs):
    """'P5: OUT DIR ...' per port: the registers in the order the image wrote them."""
    order = {}
    for rw, addr, _ in events:
        if rw == "write" and addr in regs:
            port, reg = regs[addr]
            order.setdefault(port, []).append(reg)
    return {p: " ".join(r) for p, r in sorted(order.items())}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("image")
    ap.add_argument("--board", required=True, choices=sorted(BOARDS))
    ap.add_argument("--hardware", default=os.path.join(ROOT, "docs", "hardware.md"))
    ap.add_argument("--log", help="write the mspdebug conversation here")
    a = ap.parse_args()
    functions = pin_functions()
    plan = load_plan(a.hardware)
    problems = check_plan(plan, functions)
    if problems:
        for p in problems:
            print(f"FAIL {p}")
        return 1
    log = open(a.log, "w") if a.log else None
    try:
        for preset in (0x00, 0xFF):
            try:
                found, events = run_board(a.image, a.board, preset, plan, functions, log)
            except msp430sim.SimError as e:
                found, events = [str(e)], []
            for p in found[:20]:
                print(f"FAIL latches 0x{preset:02x}: {p}")
            problems += found
            if not found:
                order = write_order(events, port_registers())
                print(f"latches preset 0x{preset:02x}: {len(events)} IO events, writes per "
                      "port: " + "; ".join(f"P{p} {o}" for p, o in order.items()))
    finally:
        if log:
            log.close()
    print(f"{os.path.basename(a.image)} ({a.board} board): "
          f"{'OK' if not problems else f'{len(problems)} problem(s)'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
