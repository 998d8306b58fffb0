#!/usr/bin/env python3
"""Run an MSP430 test image in mspdebug's simulator and judge it.

The image talks to this runner through the simulator's console device (address 0x00FF):

  @sim <device> <args...>   queue `simio config <device> <args...>` (raise a pin, latch a
                            capture...); the image then calls cy_target_sync(), where a
                            breakpoint stops it, the runner applies the queue and resumes.
  @sim-on-read ADDR <device> <args...>, @sim-on-write ADDR ...
                            armed at the next cy_target_sync(): `simio config <device>
                            <args...>` right after the next instruction that reads (writes)
                            ADDR, once.
  @cycles <name> <max> <mean> <n>
                            a cycle measurement for the cycle report (--cycles-json).
  @stack-use <name> <bytes> the deepest stack one measured call needed (CY_STACK).
  # ...                     a comment, shown with --verbose.
  CY-TEST-END PASS | CY-TEST-END FAIL <n>
                            the sentinel: the verdict of the image itself.
  FAULT 0x....              printed by hal_fault() before the CPU stops.
  KERNEL-MISMATCH <kernel> ...
                            a kernel check image (docs/kernels.md) found the assembly and
                            the C twin of a kernel disagreeing, and stopped: the run fails
                            (or, with --expect-kernel-mismatch, passes on exactly that).
  anything else             a data line, compared with the host's output (--compare-cmd)
                            and/or handed to a checker (--check).

Stack: before the run, the RAM between the end of .bss/.noinit and the top of the stack is
filled with 0xA5; after it, the lowest byte that changed gives the stack's high-water mark
(interrupt frames included), recorded in the cycle report's "stack" list, unless the image
measured its own calls with CY_STACK (which refills the area).

The image stops in cy_halt (a breakpoint). The run fails loudly when the sentinel is
missing, the image reports FAIL, the simulated cycle count passes --max-cycles (a hang),
the wall-clock --timeout passes, or mspdebug itself misbehaves.

Simulated devices (tools/mspdebug-f2618.cfg): the MSP430F2618's Timer_A3 at 0x160 (vectors
0xFFF2/0xFFF0), Timer_B7 at 0x180 (0xFFFA/0xFFF8), ports P1 (0x20, 0xFFE4) and P2 (0x28,
0xFFE6) with interrupts, ports P3-P6, the 16 x 16 hardware multiplier, the watchdog, the
console and the tracer; stand-ins that make SVSCTL, the clock registers and USCI_A0's and
USCI_B0's status and buffers readable.

Where the simulator differs from the chip the runner emulates the chip (class Chip below,
docs/hardware.md): the reset state of the transmit flags, the DCO calibration data, NMI
entry (NMIIE cleared, NMIIFG kept), and on request USCI_A0's transmitter (--uart), the
supply voltage supervisor (--vcc), an MCP2515 CAN controller on USCI_B0 (--mcp2515) and an
event between two instructions (@sim-on-read, @sim-on-write).
"""
import argparse
import fcntl
import importlib.util
import json
import os
import re
import select
import shlex
import signal
import subprocess
import sys
import time

CONFIG = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mspdebug-f2618.cfg")


def devices():
    """The simulator set-up commands (tools/mspdebug-f2618.cfg, shared with interactive use)."""
    with open(CONFIG) as f:
        return [l.strip() for l in f if l.strip() and not l.startswith("#")]


SENTINEL = "CY-TEST-END"
MISMATCH = "KERNEL-MISMATCH"
PC_RE = re.compile(r"\(\s*PC:\s*([0-9a-fA-F]+)\)")
DUMP_RE = re.compile(r"\s*\(\s*PC:")
ERROR_RE = re.compile(r"(can't|invalid|unknown|failed|expected|error|no such)", re.I)


class SimError(Exception):
    pass


class Mspdebug:
    """mspdebug reading commands from a pipe.

    (Its --embedded mode has a reader thread that silently drops a command arriving between
    its "\\ready" and the main thread asking for input; under load that hangs the runner, so
    the plain mode is used.) Each command is followed by an unknown command "cymark_<n>",
    whose error line marks the end of the command's output; a running `run` is stopped with
    SIGINT, mspdebug's Ctrl+C.
    """

    def __init__(self, log):
        self.log = log
        self.proc = subprocess.Popen(["mspdebug", "-q", "-n", "sim"], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        self.buf = ""
        self.marks = 0

    def close(self):
        try:
            self.proc.stdin.write(b"exit\n")
            self.proc.stdin.flush()
            self.proc.wait(timeout=5)
        except Exception:
            self.proc.kill()

    def _send(self, command):
        self.marks += 1
        mark = f"cymark_{self.marks}"
        if self.log:
            self.log.write(f">> {command}\n")
        self.proc.stdin.write(f"{command}\n{mark}\n".encode())
        self.proc.stdin.flush()
        return mark

    def _wait(self, mark, timeout):
        """Output up to the marker; None when it did not come within @timeout seconds."""
        end_text = f"unknown command: {mark}"
        end = time.monotonic() + timeout
        while True:
            i = self.buf.find(end_text)
            if i >= 0:
                j = self.buf.find("\n", i)
                if j >= 0:
                    out = self.buf[:i]
                    self.buf = self.buf[j + 1:]
                    if self.log:
                        self.log.write(out)
                    k = out.rfind(f"(mspdebug) {mark}")
                    return out[:k] if k >= 0 else out
            left = end - time.monotonic()
            if left <= 0:
                return None
            ready, _, _ = select.select([self.proc.stdout], [], [], min(left, 0.5))
            if not ready:
                continue
            data = os.read(self.proc.stdout.fileno(), 65536)
            if not data:
                raise SimError("mspdebug exited unexpectedly:\n" + self.buf[-2000:])
            self.buf += data.decode("latin-1")

    @staticmethod
    def _lines(out, command):
        lines = out.split("\n")
        # Drop the echo "(mspdebug) <command>" and a trailing empty piece.
        while lines and (lines[0].startswith("(mspdebug)") or not lines[0].strip()):
            if lines[0].startswith("(mspdebug)"):
                lines.pop(0)
                break
            lines.pop(0)
        if lines and lines[-1] == "":
            lines.pop()
        return lines

    def cmd(self, command, timeout=30, check=True):
        mark = self._send(command)
        out = self._wait(mark, timeout)
        if out is None:
            raise SimError(f"mspdebug did not answer `{command}` within {timeout} s")
        lines = self._lines(out, command)
        errors = [l for l in lines if check and ERROR_RE.search(l)]
        if errors:
            raise SimError(f"mspdebug: `{command}`: " + "; ".join(errors))
        return lines

    def run(self, slice_s):
        """One `run`: (lines, stopped by SIGINT?). Stops it with SIGINT after @slice_s."""
        mark = self._send("run")
        out = self._wait(mark, slice_s)
        broken = out is None
        while out is None:
            self.proc.send_signal(signal.SIGINT)
            out = self._wait(mark, 0.5)
        return self._lines(out, "run"), broken

    def cycles(self):
        for line in self.cmd("simio info tr", check=False):
            if line.startswith("MCLK:"):
                return int(line.split()[1])
        raise SimError("tracer did not report MCLK")


def symbols(elf):
    nm = os.environ.get("CY_NM", "llvm-nm-16")
    out = subprocess.run([nm, elf], check=True, capture_output=True, text=True).stdout
    table = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3:
            table[parts[2]] = int(parts[0], 16)
    return table


def split_run_output(lines, broken):
    """Console lines, the unfinished console text and the PC of the stop of one `run`.

    A stop at a breakpoint prints the register dump right after the console's bytes, so
    unfinished console text is what precedes "( PC:" on that line. A stop by \\break first
    prints a newline, so the last line before the dump is the unfinished text (often empty).
    """
    console, pc, partial = [], None, ""
    for line in lines:
        text = line
        if text.startswith(("Running. Press Ctrl+C", "Stepping over breakpoint")):
            continue
        m = DUMP_RE.search(text)
        if m and pc is None:
            pc = int(PC_RE.search(text).group(1), 16)
            if broken:
                partial = console.pop() if console else ""
            else:
                partial = text[:m.start()]
            continue
        if pc is None:
            console.append(text)
    return console, partial, pc


STACK_FILL = 0xA5
MD_RE = re.compile(r"^\s*([0-9a-fA-F]{4,5}):((?:\s[0-9a-fA-F]{2})+)")


def stack_used(md_lines, lo, top):
    """Bytes of stack used: from the lowest byte in [lo, top) that lost the fill to top."""
    mem = {}
    for line in md_lines:
        m = MD_RE.match(line)
        if m:
            addr = int(m.group(1), 16)
            for i, b in enumerate(m.group(2).split()):
                mem[addr + i] = int(b, 16)
    if any(a not in mem for a in range(lo, top)):
        raise SimError(f"`md` did not return the whole stack area 0x{lo:04x}-0x{top:04x}")
    low = next((a for a in range(lo, top) if mem[a] != STACK_FILL), top)
    return top - low


def merge_cycles(path, entries, images_dir, stack=None, source=None):
    """Merge entries (by name) into the cycle report, under a lock (ctest runs in parallel).

    Entries carry the image that measured them (`source`): a run replaces all of that image's
    earlier entries, so an entry the image no longer prints does not linger in a reused build
    directory. The static bounds tools/cycle_bound.py put into an entry (static_* keys) stay."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path + ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        report = {"clock_hz": 16000000, "entries": [], "images": []}
        if os.path.exists(path):
            try:
                with open(path) as f:
                    report = json.load(f)
            except (OSError, ValueError):
                pass
        # The static bounds of tools/cycle_bound.py (static_* keys) stay with their entry.
        by_name = {}
        for e in report.get("entries", []):
            if source is not None and e.get("image") == source:
                e = {k: v for k, v in e.items() if k == "name" or k.startswith("static_")}
                if len(e) == 1:
                    continue
            by_name[e["name"]] = e
        for e in entries:
            if source is not None:
                e["image"] = source
            old = by_name.get(e["name"], {})
            by_name[e["name"]] = {**{k: v for k, v in old.items() if k.startswith("static_")},
                                  **e}
        report["entries"] = [by_name[k] for k in sorted(by_name)]
        images = []
        if images_dir and os.path.isdir(images_dir):
            for fn in sorted(os.listdir(images_dir)):
                if fn.endswith(".json"):
                    with open(os.path.join(images_dir, fn)) as f:
                        img = json.load(f)
                    if img.get("kind") == "board":
                        images.append({k: img[k] for k in ("name", "text", "data", "bss")})
        report["images"] = images
        if stack is not None:
            # Several tests run one image along different paths (a board's boot, its link
            # coming up): the image's figure is the deepest of them (make test starts a
            # fresh report, so none is stale).
            stacks = {e["image"]: e for e in report.get("stack", [])}
            old = stacks.get(stack["image"])
            if old is None or old.get("used", 0) <= stack["used"]:
                stacks[stack["image"]] = stack
            report["stack"] = [stacks[k] for k in sorted(stacks)]
        report["clock_hz"] = 16000000
        tmp = path + ".tmp"
        with open(tmp, "w") as f:
            json.dump(report, f, indent=1)
            f.write("\n")
        os.replace(tmp, path)


# ---------------------------------------------------------------------------------------------
# Where mspdebug 0.22's simulator differs from the MSP430F2618, the runner emulates the chip
# (docs/hardware.md "What the simulator gets wrong").

# A typical part's DCO calibration bytes in information memory segment A (SLAS541: CALDCO_16MHZ
# at 0x10F8 .. CALBC1_1MHZ at 0x10FF; every part has its own). The simulator's information
# memory reads 0xFF (an erased part) unless the runner writes them.
DCO_CAL = {"typical": [0x95, 0x8F, 0x9E, 0x8E, 0x8B, 0x8D, 0x4B, 0x86], "erased": None}
CAL_ADDR = 0x10F8
# Special function registers (SLAU144): IE1/IFG1 (NMIIE, NMIIFG), IFG2 (UCA0TXIFG), UC1IFG.
IE1, IFG1, IFG2, UC1IFG = 0x0000, 0x0002, 0x0003, 0x0007
NMIIE = NMIIFG = 0x10
UCA0TXIFG = UCA1TXIFG = 0x02
UCA0STAT, UCA0TXBUF, UCBUSY = 0x0065, 0x0067, 0x01
SVSCTL, SVSOP, SVSON, PORON = 0x0055, 0x02, 0x04, 0x08
# USCI_B0 in SPI mode and the MCP2515's /CS on P3.0 (hal/msp430/spi_usci_b0.c, docs/can.md).
UCB0RXBUF, UCB0TXBUF, UCB0RXIFG, P3OUT, CS_BIT = 0x006E, 0x006F, 0x04, 0x0019, 0x01
# SVSCTL's VLDx levels, V (SLAU144, supply voltage supervisor, SVSCTL register).
VLD_VOLTS = {1: 1.9, 2: 2.1, 3: 2.2, 4: 2.3, 5: 2.4, 6: 2.5, 7: 2.65, 8: 2.8, 9: 2.9,
             10: 3.05, 11: 3.2, 12: 3.35, 13: 3.5, 14: 3.7}
NMI_VECTOR_WORD = 0xFFFC
SET_BP_RE = re.compile(r"Set breakpoint (\d+)")


class Mcp2515:
    """The MCP2515 CAN controller behind USCI_B0 for board images (--mcp2515): its SPI
    instructions (DS20001801 Table 12-1: RESET, READ, WRITE, READ RX BUFFER, LOAD TX BUFFER,
    RTS, READ STATUS, RX STATUS, BIT MODIFY) on a register file with the power-on values of
    Table 11-1 (CANCTRL 0x87, CANSTAT 0x80, the rest 0), REQOP taking effect at once. There is
    no CAN bus: requested frames stay pending, nothing is received, INT stays high. (The
    register-level model the driver's tests use is tests/support/mcp2515_model.c.)"""

    def __init__(self):
        self.power_on()
        self.selected = False

    def power_on(self):
        self.reg = [0] * 128
        self.reg[0x0F], self.reg[0x0E] = 0x87, 0x80

    @staticmethod
    def canonical(addr):
        addr &= 0x7F
        return 0x0E if addr & 0x0F == 0x0E else 0x0F if addr & 0x0F == 0x0F else addr

    def write(self, addr, value):
        a = self.canonical(addr)
        self.reg[a] = value
        if a == 0x0F and value >> 5 <= 4:  # CANCTRL.REQOP -> CANSTAT.OPMOD
            self.reg[0x0E] = (value & 0xE0) | (self.reg[0x0E] & 0x1F)

    def status(self):
        f, s = self.reg[0x2C], self.reg[0x2C] & 0x03
        for n in range(3):
            s |= (0x04 << 2 * n) if self.reg[0x30 + 16 * n] & 0x08 else 0
            s |= (0x08 << 2 * n) if f & (0x04 << n) else 0
        return s

    def select(self):
        self.selected, self.phase, self.instr, self.clear, self.reset = True, 0, None, 0, False

    def deselect(self):
        if self.selected and self.reset:
            self.power_on()
        elif self.selected:
            self.reg[0x2C] &= ~self.clear & 0xFF
        self.selected = False

    def exchange(self, mosi):
        """One byte while selected: @mosi in, the byte the MCP2515 shifts out returned."""
        if not self.selected:
            return 0xFF
        phase, self.phase = self.phase, self.phase + 1
        if phase == 0:
            self.instr = mosi
            if mosi == 0xC0:
                self.reset = True
            elif mosi & 0xF9 == 0x90:  # READ RX BUFFER 1001 0nm0
                nm = mosi >> 1 & 3
                self.addr, self.clear = (0x61, 0x66, 0x71, 0x76)[nm], 0x02 if nm & 2 else 0x01
            elif mosi & 0xF8 == 0x40 and mosi & 7 < 6:  # LOAD TX BUFFER 0100 0abc
                self.addr = (0x31, 0x36, 0x41, 0x46, 0x51, 0x56)[mosi & 7]
            elif mosi & 0xF8 == 0x80:  # RTS 1000 0nnn
                for n in range(3):
                    if mosi >> n & 1:
                        self.reg[0x30 + 16 * n] |= 0x08
            return 0xFF
        i = self.instr
        if i in (0x02, 0x03, 0x05) and phase == 1:
            self.addr = mosi & 0x7F
            return 0xFF
        if i == 0x03 or (i & 0xF9) == 0x90:
            a = self.canonical(self.addr)
            self.addr = (self.addr + 1) & 0x7F
            return self.reg[a]
        if i == 0x02 or (i & 0xF8 == 0x40 and i & 7 < 6):
            self.write(self.addr, mosi)
            self.addr = (self.addr + 1) & 0x7F
        elif i == 0x05 and phase == 2:
            self.mask = mosi
        elif i == 0x05 and phase == 3:
            a = self.canonical(self.addr)
            self.write(a, (self.reg[a] & ~self.mask & 0xFF) | (mosi & self.mask))
        elif i == 0xA0:
            return self.status()
        elif i == 0xB0:
            return 0x00  # RX STATUS: never a message
        return 0xFF


class Chip:
    """The emulation of one run: what the runner does when the simulator stops.

    - Reset state: UCA0TXIFG and UCA1TXIFG set (SLAU144: set after a PUC; the simulator's
      special function registers start at 0) and the DCO calibration bytes of --dco-cal.
    - NMI entry: the chip clears NMIIE and leaves NMIIFG set when it accepts the NMI;
      mspdebug's watchdog model does the reverse. A breakpoint on the NMI handler's first
      instruction puts the chip's state back.
    - @sim-on-read / @sim-on-write ADDR CMD: CMD applied right after the next instruction that
      reads / writes ADDR (a watchpoint), e.g. a capture between a read of TACCTL1 and the
      write that follows it.
    - --uart: USCI_A0's transmitter (not modelled by mspdebug): a byte written to UCA0TXBUF
      clears UCA0TXIFG and sets UCBUSY; the flag comes back after the firmware polled IFG2
      twice, UCBUSY clears after two polls of UCA0STAT (time passes while it waits). The
      bytes are the console. Stopping with UCBUSY set is a failure (the message is cut).
    - --vcc: the supply voltage supervisor (not modelled): after each write of SVSCTL, SVSOP
      reads 1 when the supply is below the selected VLDx level; PORON with the supply below
      the level would reset the part (reported as a failure).
    - --mcp2515: USCI_B0 (not modelled) with an MCP2515 behind it (class Mcp2515): P3.0 is
      its /CS; a byte written to UCB0TXBUF goes to it and its answer appears in UCB0RXBUF
      with UCB0RXIFG set (at once: the shift time is not modelled).
    """

    def __init__(self, sim, args, syms, elf_words):
        self.sim, self.args = sim, args
        self.watch = {}  # breakpoint index -> (kind, address)
        self.hooks = []  # (kind, address, command) armed at the next sync
        self.nmi_pc = elf_words.get(NMI_VECTOR_WORD)
        self.seen = None
        self.uart_bytes = []
        self.uart_polls = {"ifg2": 0, "stat": 0}
        self.uart_busy = False
        self.uart_txifg = True
        self.failures = []
        self.mcp = Mcp2515() if getattr(args, "mcp2515", False) else None
        self.cs = 1

    def setbreak(self, cmd, addr):
        for line in self.sim.cmd(f"{cmd} 0x{addr:04x}"):
            m = SET_BP_RE.search(line)
            if m:
                return int(m.group(1))
        raise SimError(f"`{cmd} 0x{addr:04x}`: mspdebug did not say which slot it used")

    def reset_state(self):
        self.sim.cmd(f"mw 0x{IFG2:04x} 0x{UCA0TXIFG:02x}")
        self.sim.cmd(f"mw 0x{UC1IFG:04x} 0x{UCA1TXIFG:02x}")
        cal = DCO_CAL[self.args.dco_cal]
        if cal is not None:
            self.sim.cmd(f"mw 0x{CAL_ADDR:04x} " + " ".join(f"0x{b:02x}" for b in cal))
        if self.nmi_pc is not None and not self.args.sim_nmi:
            self.sim.cmd(f"setbreak 0x{self.nmi_pc:04x}")
        if self.args.uart:
            for cmd, addr in (("setwatch_w", UCA0TXBUF), ("setwatch_r", IFG2),
                              ("setwatch_r", UCA0STAT)):
                self.watch[self.setbreak(cmd, addr)] = ("uart",)
        if self.args.vcc is not None:
            self.watch[self.setbreak("setwatch_w", SVSCTL)] = ("svs",)
        if self.mcp is not None:
            for addr in (UCB0TXBUF, P3OUT):
                self.watch[self.setbreak("setwatch_w", addr)] = ("mcp",)

    def byte(self, addr):
        for line in self.sim.cmd(f"md 0x{addr:04x} 1"):
            m = MD_RE.match(line)
            if m:
                return int(m.group(2).split()[0], 16)
        raise SimError(f"`md 0x{addr:04x} 1` returned nothing")

    def set_bits(self, addr, mask, on):
        v = self.byte(addr)
        self.sim.cmd(f"mw 0x{addr:04x} 0x{(v | mask) if on else (v & ~mask & 0xFF):02x}")

    def arm(self):
        """At a sync: set the watchpoints the image asked for."""
        for kind, addr, command in self.hooks:
            if addr < 0x10:
                raise SimError(f"@sim-on-{kind} 0x{addr:04x}: the tracer does not see the "
                               "special function registers (below 0x0010)")
            idx = self.setbreak("setwatch_r" if kind == "read" else "setwatch_w", addr)
            self.watch[idx] = ("hook", command, kind, addr)
        self.hooks = []

    def on_nmi(self):
        """IE1 .. IFG2 read and written back in one command each: NMIIE off, NMIIFG on."""
        for line in self.sim.cmd("md 0x0000 4"):
            m = MD_RE.match(line)
            if m:
                b = [int(x, 16) for x in m.group(2).split()]
                b[IE1] &= ~NMIIE & 0xFF
                b[IFG1] |= NMIIFG
                self.sim.cmd("mw 0x0000 " + " ".join(f"0x{x:02x}" for x in b))
                return
        raise SimError("`md 0x0000 4` returned nothing")

    def on_watch(self):
        """A stop that was no breakpoint: a watchpoint fired. mspdebug does not say which:
        the tracer's newest IO event tells (SFR reads such as IFG2's are not traced: a stop
        without a new event is the IFG2 poll)."""
        if not self.watch:
            return
        ev = self.newest_io_event()
        new = ev is not None and ev != self.seen
        self.seen = ev
        for i, w in list(self.watch.items()):
            if w[0] == "hook" and new and (ev[0], ev[1]) == (w[2], w[3]):
                self.sim.cmd("simio config " + w[1])
                self.sim.cmd(f"delbreak {i}")
                del self.watch[i]
                return
        kinds = {w[0] for w in self.watch.values()}
        if "mcp" in kinds and new and ev[:2] in (("write", UCB0TXBUF), ("write", P3OUT)):
            self.spi(ev[1], ev[2])
        elif "svs" in kinds and new and ev[:2] == ("write", SVSCTL):
            self.svs()
        elif "uart" in kinds:
            if new and ev[:2] == ("write", UCA0TXBUF):
                self.uart_bytes.append(ev[2])
                self.uart_txifg, self.uart_busy = False, True
                self.uart_polls = {"ifg2": 0, "stat": 0}
                self.set_bits(IFG2, UCA0TXIFG, False)
                self.sim.cmd("simio config ua0 set 0 1")
            elif new and ev[:2] == ("read", UCA0STAT):
                if self.uart_txifg and self.uart_busy:
                    self.uart_polls["stat"] += 1
                    if self.uart_polls["stat"] >= 2:
                        self.uart_busy = False
                        self.sim.cmd("simio config ua0 set 0 0")
            elif not new and not self.uart_txifg:
                self.uart_polls["ifg2"] += 1
                if self.uart_polls["ifg2"] >= 2:
                    self.uart_txifg = True
                    self.set_bits(IFG2, UCA0TXIFG, True)

    def spi(self, addr, value):
        if addr == P3OUT:
            cs = value & CS_BIT
            if cs and not self.cs:
                self.mcp.deselect()
            elif not cs and self.cs:
                self.mcp.select()
            self.cs = cs
            return
        self.sim.cmd(f"mw 0x{UCB0RXBUF:04x} 0x{self.mcp.exchange(value):02x}")
        self.set_bits(IFG2, UCB0RXIFG, True)

    def svs(self):
        v = self.byte(SVSCTL)
        vld = v >> 4
        below = vld in VLD_VOLTS and self.args.vcc < VLD_VOLTS[vld]
        if below and v & PORON:
            self.failures.append(f"the SVS would reset the part: VCC {self.args.vcc} V below "
                                 f"VLD {vld} ({VLD_VOLTS[vld]} V) with PORON set")
        self.sim.cmd(f"simio config clk set 1 {1 if below else 0}")
        self.sim.cmd(f"simio config clk set 2 {1 if vld else 0}")

    def newest_io_event(self):
        """(read|write, address, value, cycle) of the newest event in the tracer's history."""
        last = None
        for line in self.sim.cmd("simio info tr", check=False):
            m = TRACE_RE.match(line)
            if m:
                last = (m.group(2), int(m.group(4), 16), int(m.group(5) or "0", 16),
                        int(m.group(1)))
        return last

    def at_halt(self):
        if self.args.uart and self.uart_busy:
            self.failures.append("the CPU stopped while the UART was still sending: the "
                                 "message is cut (no flush before the halt)")


TRACE_RE = re.compile(r"^\s*(\d+): (read|write)\.([bw]) => 0x([0-9a-fA-F]+)(?: 0x([0-9a-fA-F]+))?\s*$")


def run_image(args, log):
    syms = symbols(args.elf)
    for needed in ("cy_halt",):
        if needed not in syms:
            raise SimError(f"{args.elf}: no symbol {needed}; is it an image of this project?")
    sync_pc = syms.get("cy_target_sync")
    halt_pc = syms["cy_halt"]
    until_pc = None
    if args.until:
        if args.until not in syms:
            raise SimError(f"{args.elf}: no symbol {args.until} for --until")
        until_pc = syms[args.until]

    sim = Mspdebug(log)
    try:
        for c in devices():
            sim.cmd(c)
        sim.cmd(f"prog {args.elf}", timeout=60)
        sim.cmd("reset")
        chip = Chip(sim, args, syms, vector_words(args.elf))
        chip.reset_state()
        sim.cmd(f"setbreak 0x{halt_pc:04x}")
        if sync_pc is not None:
            sim.cmd(f"setbreak 0x{sync_pc:04x}")
        if until_pc is not None:
            sim.cmd(f"setbreak 0x{until_pc:04x}")
        sim.cmd("simio config tr clear")
        stack_lo, stack_top = syms.get("__noinit_end"), syms.get("__stack_top")
        if stack_lo is not None and stack_top is not None and stack_top > stack_lo:
            sim.cmd(f"fill 0x{stack_lo:04x} {stack_top - stack_lo} 0x{STACK_FILL:02x}")

        console_text = []
        pending_line = ""
        queue = []
        started = time.monotonic()
        halted = False
        uart_done = 0

        def take(text_lines):
            nonlocal pending_line
            for t in text_lines:
                full = pending_line + t
                pending_line = ""
                console_text.append(full)
                if full.startswith("@sim "):
                    queue.append(full[5:].strip())
                elif full.startswith(("@sim-on-read ", "@sim-on-write ")):
                    kind, addr, command = full.split(None, 2)
                    chip.hooks.append((kind[8:], int(addr, 0), command))
                if args.verbose:
                    print("  | " + full)

        while not halted:
            lines, broken = sim.run(args.slice)
            text, partial, pc = split_run_output(lines, broken)
            take(text)
            pending_line += partial
            if args.uart and len(chip.uart_bytes) > uart_done:
                chunk = bytes(chip.uart_bytes[uart_done:]).decode("latin-1").replace("\r", "")
                uart_done = len(chip.uart_bytes)
                *done, rest = (pending_line + chunk).split("\n")
                pending_line = ""
                take(done)
                pending_line = rest
            # The count is read when a slice ran out (a hang shows there) or at the end, not
            # at every breakpoint: a run with thousands of stops saves as many commands.
            cycles = sim.cycles() if broken or pc in (halt_pc, until_pc) else 0
            if until_pc is not None and pc == until_pc:
                sr = next(int(m.group(1), 16) for m in
                          (re.search(r"\(\s*SR:\s*([0-9a-fA-F]+)\)", l) for l in lines) if m)
                console_text.append(f"@until {args.until} sr=0x{sr:04x}")
                halted = True
            elif pc == halt_pc:
                chip.at_halt()
                halted = True
            elif sync_pc is not None and pc == sync_pc:
                for q in queue:
                    sim.cmd("simio config " + q)
                queue = []  # `run` steps over the breakpoint it stands on
                chip.arm()
            elif chip.nmi_pc is not None and pc == chip.nmi_pc and not args.sim_nmi:
                chip.on_nmi()
            elif not broken:
                chip.on_watch()
            if cycles > args.max_cycles:
                raise SimError(f"cycle limit: {cycles} cycles > {args.max_cycles} "
                               f"(PC 0x{pc or 0:04x}); the image hangs or needs a larger "
                               f"--max-cycles")
            if time.monotonic() - started > args.timeout:
                raise SimError(f"wall-clock timeout after {args.timeout} s at {cycles} cycles "
                               f"(PC 0x{pc or 0:04x})")
        if pending_line:
            console_text.append(pending_line)
        console_text += [f"@chip {f}" for f in chip.failures]
        if stack_lo is not None and stack_top is not None and stack_top > stack_lo:
            used = stack_used(sim.cmd(f"md 0x{stack_lo:04x} {stack_top - stack_lo}"), stack_lo,
                              stack_top)
            console_text.append(f"@stack {used} {stack_top - stack_lo}")
        return console_text, sim.cycles()
    finally:
        sim.close()


def vector_words(elf_path):
    """{address: word} of the image's vector table (0xFFC0-0xFFFF)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import stack_bound
    elf = stack_bound.Elf(elf_path)
    return {a: w for a, w in elf.words(lambda s: s["name"] == ".vectors")}


def write_script(args):
    """The commands that set up an interactive simulator session like a run of this tool
    (without the stops of the NMI emulation: mspdebug's own NMI entry applies there)."""
    lines = ["# Written by tools/msp430sim.py --mspdebug-script: mspdebug -C THIS sim"]
    lines += devices()
    lines += [f"prog {os.path.abspath(args.elf)}", "reset",
              f"mw 0x{IFG2:04x} 0x{UCA0TXIFG:02x}", f"mw 0x{UC1IFG:04x} 0x{UCA1TXIFG:02x}"]
    cal = DCO_CAL[args.dco_cal]
    if cal is not None:
        lines.append(f"mw 0x{CAL_ADDR:04x} " + " ".join(f"0x{b:02x}" for b in cal))
    os.makedirs(os.path.dirname(os.path.abspath(args.mspdebug_script)), exist_ok=True)
    with open(args.mspdebug_script, "w") as f:
        f.write("\n".join(lines) + "\n")


def data_lines(lines):
    return [l for l in lines if l and not l.startswith(("@", "#", SENTINEL, MISMATCH))]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--elf", required=True, help="image to run")
    ap.add_argument("--mspdebug-script", metavar="OUT",
                    help="write the start-up commands of an interactive session instead of "
                         "running: the devices, the image loaded and reset, the chip's reset "
                         "state (`mspdebug -C OUT sim`; make debug SIM=1)")
    ap.add_argument("--max-cycles", type=int, default=200_000_000,
                    help="fail when the simulated MCLK count passes this (default 2e8)")
    ap.add_argument("--timeout", type=float, default=120, help="wall-clock limit, s")
    ap.add_argument("--slice", type=float, default=2.0,
                    help="wall-clock seconds between cycle-limit checks")
    ap.add_argument("--until", metavar="SYMBOL",
                    help="pass when execution reaches SYMBOL (a boot check; no sentinel)")
    ap.add_argument("--expect-gie", action="store_true",
                    help="with --until: interrupts must be enabled there")
    ap.add_argument("--expect-fault", help="pass only if the image stops with this fault code")
    ap.add_argument("--expect-kernel-mismatch", metavar="KERNEL",
                    help="pass only if the image stops at its first line KERNEL-MISMATCH, "
                         "naming KERNEL (the proof that a check image can fail)")
    ap.add_argument("--expect-text", action="append", default=[], metavar="LINE",
                    help="the console must show this line (repeatable)")
    ap.add_argument("--dco-cal", choices=sorted(DCO_CAL), default="typical",
                    help="information memory's DCO calibration bytes: a typical part's "
                         "(default) or erased (0xFF, what the simulator holds by itself)")
    ap.add_argument("--vcc", type=float, metavar="VOLTS",
                    help="emulate the supply voltage supervisor with this supply (default: "
                         "none, the SVS output stays low: above every level)")
    ap.add_argument("--uart", action="store_true",
                    help="emulate USCI_A0's transmitter; its bytes are the console (board "
                         "images' console_uart)")
    ap.add_argument("--mcp2515", action="store_true",
                    help="emulate USCI_B0 with an MCP2515 CAN controller behind it (no CAN "
                         "bus): board images set up their CAN link")
    ap.add_argument("--sim-nmi", action="store_true",
                    help="keep mspdebug's NMI entry (NMIIE left set, NMIIFG cleared) instead "
                         "of the chip's")
    ap.add_argument("--compare-cmd", help="host command whose stdout data lines must equal "
                                          "the image's, line by line (bit-identical results)")
    ap.add_argument("--check", help="Python file with check(lines) -> list of errors, run on "
                                    "the image's data lines")
    ap.add_argument("--min-lines", type=int, default=0,
                    help="fail when the image printed fewer data lines")
    ap.add_argument("--cycles-json", help="merge @cycles lines into this report")
    ap.add_argument("--images-dir", help="image size records for the report "
                                         "(default: images/ beside --cycles-json)")
    ap.add_argument("--log", help="write the mspdebug conversation here")
    ap.add_argument("--verbose", action="store_true", help="echo the console")
    args = ap.parse_args()

    if args.mspdebug_script:
        write_script(args)
        return 0
    log = open(args.log, "w") if args.log else None
    name = os.path.basename(args.elf)
    try:
        console, cycles = run_image(args, log)
    except SimError as e:
        print(f"FAIL {name}: {e}")
        return 1
    finally:
        if log:
            log.close()

    failures = [l[6:] for l in console if l.startswith("@chip ")]
    for want in args.expect_text:
        if want not in console:
            failures.append(f"the console never showed `{want}`")
    faults = [l for l in console if l.startswith("FAULT ")]
    mismatches = [l for l in console if l.startswith(MISMATCH)]
    if args.expect_kernel_mismatch:
        rest = [l for l in console if l and not l.startswith("@stack ")]
        if len(mismatches) != 1 or not mismatches[0].startswith(
                f"{MISMATCH} {args.expect_kernel_mismatch} "):
            failures.append(f"expected one `{MISMATCH} {args.expect_kernel_mismatch} ...`, "
                            f"the image printed {mismatches or 'none'}")
        elif rest[-1] != mismatches[0]:
            failures.append(f"the image went on after `{mismatches[0]}`: `{rest[-1]}`")
        else:
            print(f"  stopped as expected: {mismatches[0]}")
        args.compare_cmd = None  # the run stopped early on purpose
    elif mismatches:
        failures.append(f"kernel check: {mismatches[0]}")
    if args.expect_kernel_mismatch:
        pass
    elif args.until:
        stops = [l for l in console if l.startswith("@until ")]
        if not stops:
            failures.append(f"never reached {args.until}")
        elif args.expect_gie and not int(stops[0].split("sr=")[1], 16) & 0x0008:
            failures.append(f"reached {args.until} with interrupts disabled ({stops[0]})")
    elif args.expect_fault:
        want = f"FAULT {args.expect_fault.lower()}"
        if not any(l.lower() == want.lower() for l in faults):
            failures.append(f"expected `{want}`, the image printed {faults or 'no fault'}")
    else:
        if faults:
            failures.append(f"the image faulted: {faults[0]}")
        verdicts = [l for l in console if l.startswith(SENTINEL)]
        if not verdicts:
            failures.append(f"missing sentinel `{SENTINEL}`: the image stopped without a verdict")
        elif verdicts[-1] != f"{SENTINEL} PASS":
            failures.append(f"the image reports `{verdicts[-1]}`")
        for l in console:
            if l.startswith("FAIL"):
                failures.append("image: " + l)

    data = data_lines(console)
    if len(data) < args.min_lines:
        failures.append(f"only {len(data)} data lines, expected at least {args.min_lines}")

    if args.check:
        spec = importlib.util.spec_from_file_location("cy_check", args.check)
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        errors = mod.check(data)
        failures.extend(errors[:20])
        if len(errors) > 20:
            failures.append(f"... and {len(errors) - 20} more")

    if args.compare_cmd:
        host = subprocess.run(shlex.split(args.compare_cmd), capture_output=True, text=True)
        if host.returncode != 0 and not os.path.exists(shlex.split(args.compare_cmd)[0]):
            failures.append(f"host reference `{args.compare_cmd}` not found: build the host "
                            "preset first")
        else:
            ref = data_lines(host.stdout.splitlines())
            if len(ref) != len(data):
                failures.append(f"host printed {len(ref)} data lines, target {len(data)}")
            for i, (a, b) in enumerate(zip(ref, data)):
                if a != b:
                    failures.append(f"line {i + 1} differs: host `{a}` target `{b}`")
                    break

    stack = None
    # An image that measures its calls (CY_STACK) refills the area: its own high-water mark
    # is then not the runner's to judge.
    per_call = any(l.startswith("@stack-use ") for l in console)
    for l in console:
        if l.startswith("@stack ") and not per_call:
            used, room = (int(v) for v in l.split()[1:3])
            stack = {"image": os.path.splitext(name)[0], "used": used, "room": room}
            if used >= room:
                failures.append(f"the stack used all {room} bytes above .bss: it overflowed")
    if args.cycles_json:
        entries = []
        for l in console:
            if l.startswith("@cycles "):
                f = l.split()
                entries.append({"name": f[1], "cycles_max": int(f[2]),
                                "cycles_mean": int(f[3]), "samples": int(f[4])})
        for l in console:
            if l.startswith("@stack-use "):
                f = l.split()
                e = next((e for e in entries if e["name"] == f[1]), None)
                if e is None:
                    failures.append(f"`{l}` names no @cycles entry")
                else:
                    e["stack_bytes"] = int(f[2])
        if entries or stack:
            images_dir = args.images_dir or os.path.join(
                os.path.dirname(os.path.abspath(args.cycles_json)), "images")
            merge_cycles(args.cycles_json, entries, images_dir, stack,
                         os.path.splitext(name)[0])
            for e in entries:
                st = f", stack {e['stack_bytes']} B" if "stack_bytes" in e else ""
                print(f"  cycles {e['name']:<20} max {e['cycles_max']:>7}  mean "
                      f"{e['cycles_mean']:>7}  ({e['samples']} samples{st})")

    if failures:
        print(f"FAIL {name} ({cycles} cycles)")
        for f in failures:
            print("  " + f)
        return 1
    room = f", stack {stack['used']} of {stack['room']} bytes" if stack else ""
    print(f"PASS {name}: {len(data)} data lines, {cycles} simulated cycles{room}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
