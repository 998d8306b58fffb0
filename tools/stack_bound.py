#!/usr/bin/env python3
"""Static worst-case stack bound of an MSP430 image (docs/stack.md).

  stack_bound.py ELF [--objdump llvm-objdump-16] [--limit BYTES] [--ram-budget BYTES]
                 [--ram-end ADDR] [--indirect SITE=F,...] [--no-mpy-in-isr] [--no-mpy-in-nmi]
                 [--json OUT]

Disassembles the linked ELF and, per function, follows its control flow from the entry with
the stack depth it has pushed (push/pop, sub/add #N,r1, pushm/popm, decd/incd r1): its frame
is the deepest point, every `ret`/`reti` must find the depth back at 0 and every join the same
depth from all its predecessors, or the function is reported as not analysable. Calls add the
2-byte return address on top of the depth at the call site; tail calls (`br #f`, `jmp` to
another function, falling into the next function) run at the caller's depth. Indirect calls
and jumps may reach any function whose address is taken (an immediate operand naming a
function start, or a word of initialised data naming one), narrowed only where --indirect
says so. A cycle in the call graph is an error naming it.

Roots: the reset vector (the start-up code, main below it) and every other interrupt vector;
an interrupt costs 4 bytes (PC and SR) on top of its handler. No maskable handler may set
GIE again (checked: every instruction that can set GIE in a handler's reach is listed; the
restores of a state saved inside the handler keep it off); the NMI can come on top of a
maskable handler, and the NMI handler may set NMIIE again only as its last instruction before
RETI (checked), where a second request lands on the first one's 4 bytes. Worst case = reset +
the deepest maskable handler + the NMI handler (+ 4 bytes when it re-arms itself).

Multiplier rules: --no-mpy-in-isr fails when a maskable handler reaches code that names a
hardware multiplier register (0x130-0x13F): its main line then may use the multiplier with
interrupts enabled. --no-mpy-in-nmi fails when the NMI handler reaches such code or a
compiler multiply helper (__mspabi_mpy*): DINT does not hold the NMI off, so an NMI that
multiplies corrupts any multiply it lands in (in the main line, in a handler, in a helper's
DINT section). Each finding names the call path from the handler.

Prints the table (root, bound, deepest chain as function(frame) names), the worst case and
the RAM left free (RAM end, __stack_top unless --ram-end, minus __noinit_end) and exits 1 when
the worst case exceeds the free RAM or --limit, when static RAM plus the worst case exceeds
--ram-budget, or when a function cannot be analysed.
"""
import argparse
import json
import re
import struct
import subprocess
import sys

# ---------------------------------------------------------------------------------------------
# ELF (32-bit little endian, what ld.lld writes for msp430): sections, symbols, contents.

SHT_SYMTAB = 2
SHT_PROGBITS = 1
SHF_ALLOC = 0x2
SHF_EXECINSTR = 0x4
STT_FUNC = 2
STT_NOTYPE = 0
STB_GLOBAL = 1


class Elf:
    """The sections and symbols of an ELF32 LE file."""

    def __init__(self, path):
        with open(path, "rb") as f:
            self.data = f.read()
        d = self.data
        if d[:4] != b"\x7fELF" or d[4] != 1 or d[5] != 1:
            raise ValueError(f"{path}: not a 32-bit little-endian ELF")
        shoff, = struct.unpack_from("<I", d, 0x20)
        shentsize, shnum, shstrndx = struct.unpack_from("<HHH", d, 0x2E)
        raw = [struct.unpack_from("<IIIIIIIIII", d, shoff + i * shentsize) for i in range(shnum)]
        strtab = raw[shstrndx]
        self.sections = []
        for name, typ, flags, addr, off, size, link, _info, _align, entsize in raw:
            self.sections.append({"name": self._str(strtab[4], name), "type": typ,
                                  "flags": flags, "addr": addr, "offset": off, "size": size,
                                  "link": link, "entsize": entsize})
        self.symbols = []
        for s in self.sections:
            if s["type"] != SHT_SYMTAB:
                continue
            strs = self.sections[s["link"]]["offset"]
            for i in range(s["size"] // 16):
                name, value, size, info, _other, shndx = struct.unpack_from(
                    "<IIIBBH", d, s["offset"] + 16 * i)
                self.symbols.append({"name": self._str(strs, name), "value": value,
                                     "size": size, "type": info & 0xF, "bind": info >> 4,
                                     "shndx": shndx})

    def _str(self, off, idx):
        end = self.data.index(b"\0", off + idx)
        return self.data[off + idx:end].decode()

    def symbol(self, name):
        for s in self.symbols:
            if s["name"] == name:
                return s["value"]
        return None

    def functions(self):
        """[(name, address, is_entry)] of the code symbols: FUNC ones and global untyped ones
        are entries; local untyped ones are assembly labels (entries only when called)."""
        out = []
        for s in self.symbols:
            if not s["name"] or s["shndx"] == 0 or s["shndx"] >= len(self.sections):
                continue
            sec = self.sections[s["shndx"]]
            if not sec["flags"] & SHF_EXECINSTR:
                continue
            if s["type"] == STT_FUNC or (s["type"] == STT_NOTYPE and s["bind"] == STB_GLOBAL):
                out.append((s["name"], s["value"], True))
            elif s["type"] == STT_NOTYPE:
                out.append((s["name"], s["value"], False))
        return out

    def words(self, pred):
        """[(address, word)] of the even-aligned 16-bit words of the sections pred accepts."""
        out = []
        for s in self.sections:
            if s["type"] != SHT_PROGBITS or not s["flags"] & SHF_ALLOC or not pred(s):
                continue
            base = s["addr"]
            start = (base + 1) & ~1
            for a in range(start, base + s["size"] - 1, 2):
                w, = struct.unpack_from("<H", self.data, s["offset"] + a - base)
                out.append((a, w))
        return out


# ---------------------------------------------------------------------------------------------
# Disassembly text (llvm-objdump -d --no-show-raw-insn) to instructions.

INSN_RE = re.compile(r"^\s*([0-9a-f]+):\s+([a-z][a-z0-9.]*)(?:\s+(.*?))?\s*$")
HEADER_RE = re.compile(r"^([0-9a-f]+) <([^>]+)>:\s*$")


class Insn:
    def __init__(self, addr, mnem, ops):
        self.addr = addr
        self.mnem = mnem
        self.ops = ops

    def __repr__(self):
        return f"{self.addr:04x}: {self.mnem} {', '.join(self.ops)}"


def split_ops(text):
    return [o.strip() for o in text.split(",")] if text else []


def parse_disassembly(text):
    """{address: Insn} of every instruction line."""
    insns = {}
    for line in text.splitlines():
        if HEADER_RE.match(line):
            continue
        m = INSN_RE.match(line)
        if m:
            a = int(m.group(1), 16)
            insns[a] = Insn(a, m.group(2), split_ops(m.group(3)))
    return insns


def functions_from_headers(text):
    """{name: address} of the `addr <name>:` headers (for disassembly without an ELF)."""
    return {m.group(2): int(m.group(1), 16)
            for m in map(HEADER_RE.match, text.splitlines()) if m}


def imm(op):
    """The value of an immediate operand #N (16 bits, unsigned), else None."""
    if op.startswith("#"):
        try:
            return int(op[1:], 0) & 0xFFFF
        except ValueError:
            return None
    return None


def signed16(v):
    return v - 0x10000 if v & 0x8000 else v


COND_JUMPS = {"jeq", "jz", "jne", "jnz", "jc", "jhs", "jnc", "jlo", "jn", "jge", "jl"}
SP = "r1"
PC = "r0"
SR = "r2"
# Two-operand instructions that write their second operand.
WRITES_DST = {"mov", "add", "addc", "sub", "subc", "and", "bic", "bis", "xor", "dadd",
              "mov.b", "add.b", "addc.b", "sub.b", "subc.b", "and.b", "bic.b", "bis.b",
              "xor.b", "dadd.b", "mova", "adda", "suba"}
# One-operand instructions that write their operand.
WRITES_ONE = {"rra", "rrc", "swpb", "sxt", "inc", "incd", "dec", "decd", "inv", "clr", "adc",
              "sbc", "rla", "rlc", "rra.b", "rrc.b", "inc.b", "incd.b", "dec.b", "decd.b",
              "inv.b", "clr.b", "adc.b", "sbc.b", "rla.b", "rlc.b", "pop", "pop.b"}


def jump_target(insn):
    """Target of jmp/jCC `$+N` (relative to the instruction's own address)."""
    op = insn.ops[0]
    m = re.match(r"^\$([+-]\d+)$", op)
    if not m:
        raise ValueError(f"{insn}: unexpected jump operand")
    return (insn.addr + int(m.group(1))) & 0xFFFF


def dest(insn):
    if insn.mnem in WRITES_DST and len(insn.ops) == 2:
        return insn.ops[1]
    if insn.mnem in WRITES_ONE and len(insn.ops) == 1:
        return insn.ops[0]
    return None


def sp_delta(insn):
    """Bytes the instruction pushes (negative: pops), None for no change, 'reset' for
    `mov #N, r1` (the start-up setting the stack), 'unknown' for another write to SP."""
    m, ops = insn.mnem, insn.ops
    if m in ("push", "push.b", "push.w"):
        return 2
    if m in ("pop", "pop.b", "pop.w"):
        return -2
    if ops and ops[0] == "@r1+" and dest(insn) != SP:
        return -2  # a source read off the stack with autoincrement (add @r1+, r12): a pop
    if m in ("pushm", "pushm.w", "pushm.a", "popm", "popm.w", "popm.a"):
        n = imm(ops[0])
        per = 4 if m.endswith(".a") else 2
        return n * per if m.startswith("push") else -n * per
    if dest(insn) != SP:
        return None
    if m in ("sub", "suba") and imm(ops[0]) is not None:
        return signed16(imm(ops[0]))
    if m in ("add", "adda") and imm(ops[0]) is not None:
        return -signed16(imm(ops[0]))
    if m == "decd":
        return 2
    if m == "incd":
        return -2
    if m == "mov" and imm(ops[0]) is not None:
        return "reset"
    return "unknown"


def sets_gie(insn):
    """'set' if the instruction sets GIE outright, 'restore' if it writes SR from a value
    (pop r2, mov rN, r2: a copy saved earlier), None if it cannot set GIE."""
    if insn.mnem == "eint":
        return "set"
    if dest(insn) != SR or insn.mnem.startswith(("bic", "and")):
        return None
    v = imm(insn.ops[0]) if len(insn.ops) == 2 else None
    if v is not None:
        if insn.mnem.startswith(("bis", "mov", "xor")):
            return "set" if v & 0x8 else None
        return "set"
    if insn.mnem.startswith(("mov", "pop")):
        return "restore"
    return "set"


def reads_sr_copy(insn):
    """A copy of SR (GIE included) taken: push r2, or mov r2 to somewhere."""
    return (insn.mnem in ("push", "push.w") and insn.ops == [SR]) or (
        insn.mnem in ("mov", "mov.w") and insn.ops[:1] == [SR])


# ---------------------------------------------------------------------------------------------
# Per-function control flow with stack depth.


class Func:
    def __init__(self, name, start, end):
        self.name = name
        self.start = start
        self.end = end
        self.frame = 0
        self.edges = []  # (kind, target name or None, depth, insn address)
        self.errors = []
        self.returns = False
        self.gie = []  # (insn address, 'set'|'restore', text)
        self.stack_reset = False
        self.depth_at = {}  # instruction address -> stack depth there


class Image:
    """Everything the analysis needs: instructions, functions, address-taken set."""

    def __init__(self, insns, functions, data_words=(), indirect=None):
        self.insns = insns
        self.addrs = sorted(insns)
        # One name per address: an alias such as CY_ISR's __cy_vector_N yields to the
        # function's own name.
        starts = sorted((a, n.startswith("__cy_vector_"), n)
                        for n, a in functions.items() if a in insns)
        self.by_addr = {}
        for a, _, n in starts:
            self.by_addr.setdefault(a, n)
        self.funcs = {}
        order = sorted(self.by_addr.items())
        last = (self.addrs[-1] + 1) if self.addrs else 0
        for i, (a, n) in enumerate(order):
            end = order[i + 1][0] if i + 1 < len(order) else last
            self.funcs[n] = Func(n, a, end)
        self.data_words = list(data_words)
        self.indirect = indirect or {}
        self.taken = self._address_taken()

    def func_at(self, addr):
        for f in self.funcs.values():
            if f.start <= addr < f.end:
                return f
        return None

    def _address_taken(self):
        taken = {}
        for i in self.insns.values():
            # A pointer is made by moving or pushing the address; an immediate that is
            # compared, added or masked is a number (0x8000, the reset entry of the board
            # images, is also INT16_MIN).
            if i.mnem not in ("mov", "mov.w", "mova", "push", "push.w", "pusha") or not i.ops:
                continue
            v = imm(i.ops[0])
            if v is not None and v in self.by_addr:
                taken.setdefault(self.by_addr[v], f"#{v:#06x} at {i.addr:04x}")
        for a, w in self.data_words:
            if w in self.by_addr:
                taken.setdefault(self.by_addr[w], f"data word at {a:04x}")
        return taken

    def jump_table(self, f, insn):
        """Targets of `br X(rN)` when X names a table of code addresses inside f."""
        m = re.match(r"^(-?\d+)\((r\d+)\)$", insn.ops[0])
        if not m:
            return None
        base = int(m.group(1)) & 0xFFFF
        words = dict(self.data_words)
        out = []
        a = base
        while a in words and f.start <= words[a] < f.end and words[a] in self.insns:
            out.append(words[a])
            a += 2
        return out or None

    def walk(self, f, returning):
        """Follow f from its entry; fills frame, edges, errors, returns, gie."""
        f.frame, f.edges, f.errors, f.returns, f.gie = 0, [], [], False, []
        depth_at = {f.start: 0}
        saved_sr = {f.start: False}
        work = [f.start]

        def goto(src, target, depth, saved):
            # Another function's entry is a tail call; any other instruction continues this
            # function (assembly sources share code past a called local label).
            if target != f.start and target in self.by_addr:
                f.edges.append(("tail", self.by_addr[target], depth, src.addr))
            elif target in self.insns:
                if target in depth_at:
                    if depth_at[target] != depth:
                        f.errors.append(f"{target:04x}: reached with stack depth "
                                        f"{depth_at[target]} and {depth}")
                    if saved_sr[target] and not saved:
                        saved_sr[target] = False
                        work.append(target)
                    return
                depth_at[target] = depth
                saved_sr[target] = saved
                work.append(target)
            else:
                f.errors.append(f"{src.addr:04x}: jumps to {target:04x}, not an instruction")

        while work:
            a = work.pop()
            insn = self.insns[a]
            d = depth_at[a]
            saved = saved_sr[a] or reads_sr_copy(insn)
            delta = sp_delta(insn)
            if delta == "reset":
                d, f.stack_reset = 0, True
            elif delta == "unknown":
                f.errors.append(f"{insn}: writes the stack pointer")
                continue
            elif delta is not None:
                d += delta
                if d < 0:
                    f.errors.append(f"{insn}: pops below the entry depth")
                    continue
            f.frame = max(f.frame, d)
            nxt = self._next(a)
            m = insn.mnem
            if m in ("ret", "reti", "reta"):
                if d != 0:
                    f.errors.append(f"{insn}: returns with {d} bytes still pushed")
                f.returns = True
                continue
            if m == "jmp":
                goto(insn, jump_target(insn), d, saved)
                continue
            if m in COND_JUMPS:
                goto(insn, jump_target(insn), d, saved)
                if nxt is not None:
                    goto(insn, nxt, d, saved)
                continue
            if m in ("call", "calla"):
                t = imm(insn.ops[0])
                if t is not None:
                    if t not in self.by_addr:
                        f.errors.append(f"{insn}: calls {t:04x}, not a function start")
                        continue
                    f.edges.append(("call", self.by_addr[t], d, a))
                    if self.by_addr[t] not in returning:
                        continue
                else:
                    f.edges.append(("icall", None, d, a))
                if nxt is not None:
                    goto(insn, nxt, d, saved)
                continue
            if m in ("br", "bra") or dest(insn) == PC:
                t = imm(insn.ops[0]) if m in ("br", "bra") else None
                if t is not None:
                    goto(insn, t, d, saved)
                    continue
                table = self.jump_table(f, insn) if m in ("br", "bra") else None
                if table:
                    for t in table:
                        goto(insn, t, d, saved)
                else:
                    f.edges.append(("ijump", None, d, a))
                continue
            if nxt is not None:
                goto(insn, nxt, d, saved)

        f.depth_at = depth_at
        # A write of GIE after a copy of SR was taken on every path to it (push r2 / mov r2,
        # in this function) puts back the state of that copy: GIE off inside a handler.
        for a in sorted(depth_at):
            g = sets_gie(self.insns[a])
            if g:
                kind = "restore" if saved_sr[a] else "set"
                if g == "set" and self.insns[a].mnem != "eint":
                    kind = "set"
                f.gie.append((a, kind, repr(self.insns[a])))
        f.edges = sorted(set(f.edges), key=lambda e: (e[3], e[0]))

    def _next(self, a):
        i = self._index(a)
        return self.addrs[i + 1] if i + 1 < len(self.addrs) else None

    def _index(self, a):
        if not hasattr(self, "_idx"):
            self._idx = {x: i for i, x in enumerate(self.addrs)}
        return self._idx[a]

    def analyse(self):
        """Walk every function, with the set of functions that can return (least fixpoint:
        a function returns when a ret is reachable while calls to functions not known to
        return end the path)."""
        returning = set()
        while True:
            for f in self.funcs.values():
                self.walk(f, returning)
            now = set()
            changed = True
            while changed:
                changed = False
                for f in self.funcs.values():
                    if f.name in now:
                        continue
                    if f.returns or any(k == "ijump" or (k == "tail" and t in now)
                                        for k, t, _, _ in f.edges):
                        now.add(f.name)
                        changed = True
            if now == returning:
                return
            returning = now

    def targets(self, f, edge):
        kind, target, _, addr = edge
        if target is not None:
            return [target]
        key = f"{f.name}@{addr:04x}"
        for k in (key, f.name):
            if k in self.indirect:
                return self.indirect[k]
        # The reset entry sets the stack pointer itself: reached through a pointer it starts
        # over from the top of RAM (the reset root), not on top of the caller.
        return sorted(t for t in self.taken if not self.funcs[t].stack_reset)


class Recursion(Exception):
    pass


class Bounds:
    """Deepest stack of each function including its callees, with the chain."""

    def __init__(self, image):
        self.image = image
        self.memo = {}
        self.stack = []

    def of(self, name):
        if name in self.memo:
            return self.memo[name]
        if name in self.stack:
            cycle = self.stack[self.stack.index(name):] + [name]
            raise Recursion(" -> ".join(cycle))
        self.stack.append(name)
        try:
            f = self.image.funcs[name]
            best = (f.frame, [(name, f.frame)])
            for e in f.edges:
                kind, _, depth, _ = e
                for t in self.image.targets(f, e):
                    sub, chain = self.of(t)
                    total = depth + (2 if kind in ("call", "icall") else 0) + sub
                    if total > best[0]:
                        hop = [("*" + chain[0][0], chain[0][1])] if e[1] is None else chain[:1]
                        best = (total, [(name, f.frame)] + hop + chain[1:])
        finally:
            self.stack.pop()
        self.memo[name] = best
        return best

    def reach(self, name, seen=None):
        seen = set() if seen is None else seen
        if name in seen:
            return seen
        seen.add(name)
        f = self.image.funcs[name]
        for e in f.edges:
            for t in self.image.targets(f, e):
                self.reach(t, seen)
        return seen

    def paths(self, root):
        """{function: [root, ..., function]}: a shortest call path to each function root
        reaches (breadth first, calls and tail calls and indirect targets alike)."""
        path = {root: [root]}
        todo = [root]
        while todo:
            nxt = []
            for name in todo:
                f = self.image.funcs[name]
                for e in f.edges:
                    for t in self.image.targets(f, e):
                        if t not in path:
                            path[t] = path[name] + [t]
                            nxt.append(t)
            todo = nxt
        return path


def chain_text(chain):
    return " > ".join(f"{n}({fr})" for n, fr in chain)


# ---------------------------------------------------------------------------------------------
# Roots and the report.

# The MSP430F2618's vector table (SLAS541): 32 words at 0xFFC0, vector N at 0xFFC0 + 2N.
VECTOR_BASE = 0xFFC0
VECTOR_COUNT = 32
RESET_VECTOR = 31
NMI_VECTOR = 30
INTERRUPT_ENTRY = 4  # PC and SR pushed by the hardware
# Restores of a GIE state saved before (hal/msp430/irq.c): inside a handler that state has
# GIE off, so they cannot enable interrupts there.
GIE_RESTORERS = ("hal_irq_restore", "hal_critical_exit")


# The 16 x 16 hardware multiplier's registers (MPY .. SUMEXT).
MPY_REGS = range(0x130, 0x140)


def mpy_operands(image, fn):
    """The instructions of function fn that name a multiplier register (&addr or #addr)."""
    f = image.funcs[fn]
    out = []
    for a in sorted(image.insns):
        if f.start <= a < f.end:
            i = image.insns[a]
            for op in i.ops:
                m = re.fullmatch(r"[&#](-?\d+)", op.strip())
                if m and int(m.group(1)) & 0xFFFF in MPY_REGS:
                    out.append(f"{a:04x}: {i.mnem} {', '.join(i.ops)}")
                    break
    return out


IE1_ADDR, NMIIE = 0x0000, 0x10  # SLAU144: interrupt enable 1, NMI interrupt enable (bit 4)


def nmiie_writes(image, fn):
    """[(address, text)] of the instructions of fn that can set NMIIE (a bis or mov of an
    immediate with bit 4 to &IE1, or any other write of IE1 from a register)."""
    f = image.funcs[fn]
    out = []
    for a in sorted(f.depth_at):
        i = image.insns[a]
        d = dest(i)
        if d is None or not re.fullmatch(r"&0+|&0x0+", d.strip()):
            continue
        if i.mnem.startswith(("bic", "and")):
            continue
        v = imm(i.ops[0]) if len(i.ops) == 2 else None
        if v is not None and not v & NMIIE:
            continue
        out.append((a, repr(i)))
    return out


def nmi_rearm(image, root, reach):
    """How the NMI handler @root re-enables NMIIE (SLAU144: only as the last instruction
    before RETI, or NMIs nest without bound): (nested bytes, note, errors). Accepted: every
    write setting NMIIE in the handler's reach is in the root itself, at stack depth 0 (the
    handler's registers restored), followed by `reti`. A request that came while the handler
    ran is then taken right there, on top of this NMI's PC and SR: 4 bytes under one more NMI
    (counted; a third request during the second's handler would nest again: the coordinate
    requests come a link message apart, far more than two handler run times)."""
    errors, sites = [], []
    for fn in sorted(reach):
        for a, text in nmiie_writes(image, fn):
            sites.append(text)
            f = image.funcs[fn]
            nxt = image._next(a)
            ok = fn == root and f.depth_at.get(a) == 0 and nxt is not None and \
                image.insns[nxt].mnem == "reti"
            if not ok:
                errors.append(f"{fn}: {text}: sets NMIIE other than as the NMI handler's last "
                              "instruction before RETI (SLAU144): nested NMIs are not bounded")
    if not sites:
        return 0, "NMIIE not set again by the handler: no nesting", errors
    if errors:
        return 0, "NMIIE set before the handler's last instruction: nesting not bounded", errors
    return INTERRUPT_ENTRY, "NMIIE set as the last instruction before RETI: one more NMI on " \
        "the first one's 4 bytes", errors


MPY_HELPER_PREFIX = "__mspabi_mpy"


def nmi_multiplies(image, bounds, name):
    """The findings of --no-mpy-in-nmi for the NMI handler name: every function it reaches
    that is a compiler multiply helper or names a multiplier register, with the path."""
    out = []
    paths = bounds.paths(name)
    for fn in sorted(paths):
        via = " > ".join(paths[fn])
        if fn.startswith(MPY_HELPER_PREFIX):
            out.append(f"the NMI handler {name} reaches the multiply helper {fn}: {via}")
            continue
        for insn in mpy_operands(image, fn):
            out.append(f"the NMI handler {name} reaches the hardware multiplier: {fn} {insn}: "
                       f"{via}")
    return out


def report(image, vectors, free_ram, limit, restorers=GIE_RESTORERS, no_mpy_in_isr=False,
           static_ram=None, ram_budget=None, no_mpy_in_nmi=False):
    """The analysis of an image as a dict; vectors: {vector number: function name}.
    static_ram, ram_budget: the image's static data (bytes) and the budget it and the worst
    case must fit together.
    no_mpy_in_isr: no maskable handler may reach code that names a multiplier register (its
    main line then uses the multiplier with interrupts enabled).
    no_mpy_in_nmi: the NMI handler may reach neither such code nor a __mspabi_mpy* helper."""
    errors = []
    for f in image.funcs.values():
        errors += [f"{f.name}: {e}" for e in f.errors]
        if f.stack_reset and f.name != vectors.get(RESET_VECTOR):
            errors.append(f"{f.name}: sets the stack pointer outside the reset entry")
    bounds = Bounds(image)
    roots = []
    handlers = {}
    for v in sorted(vectors):
        handlers.setdefault(vectors[v], []).append(v)
    for name, vecs in handlers.items():
        try:
            b, chain = bounds.of(name)
        except Recursion as r:
            errors.append(f"recursion: {r}")
            continue
        reset = RESET_VECTOR in vecs
        entry = 0 if reset else INTERRUPT_ENTRY
        gie = []
        for fn in sorted(bounds.reach(name)):
            for addr, kind, text in image.funcs[fn].gie:
                if kind == "set" and fn in restorers:
                    kind = "restore"
                gie.append({"function": fn, "insn": text, "kind": kind})
        indirect = []
        for fn in sorted(bounds.reach(name)):
            f = image.funcs[fn]
            for e in f.edges:
                if e[1] is None:
                    indirect.append(f"{fn}@{e[3]:04x}")
        if no_mpy_in_isr and not reset and NMI_VECTOR not in vecs:
            for fn in sorted(bounds.reach(name)):
                for insn in mpy_operands(image, fn):
                    errors.append(f"{name} reaches the hardware multiplier: {fn} {insn}")
        if no_mpy_in_nmi and NMI_VECTOR in vecs:
            errors += nmi_multiplies(image, bounds, name)
        roots.append({"root": "reset" if reset else "isr", "function": name,
                      "vectors": vecs, "bound": b + entry, "entry": entry,
                      "chain": [{"function": n, "frame": fr} for n, fr in chain],
                      "reenables": any(g["kind"] == "set" for g in gie) and not reset,
                      "gie": gie, "indirect_sites": indirect})
    reset = [r for r in roots if r["root"] == "reset"]
    isrs = [r for r in roots if r["root"] == "isr"]
    maskable = [r for r in isrs if NMI_VECTOR not in r["vectors"]]
    nmi = [r for r in isrs if NMI_VECTOR in r["vectors"]]
    nmi_nested, nmi_note = 0, None
    for r in nmi:
        nmi_nested, nmi_note, errs = nmi_rearm(image, r["function"], bounds.reach(r["function"]))
        errors += errs
    nesting = any(r["reenables"] for r in isrs)
    worst = None
    if reset and not errors:
        worst = reset[0]["bound"]
        if nesting:
            # A handler that enables interrupts lets every other one in on top of it; each
            # at most once (a handler re-entering itself is not bounded: reported).
            worst += sum(r["bound"] for r in isrs)
        else:
            worst += max((r["bound"] for r in maskable), default=0)
            worst += max((r["bound"] for r in nmi), default=0)
            worst += nmi_nested if nmi else 0
    over = []
    if worst is not None and free_ram is not None and worst > free_ram:
        over.append(f"worst case {worst} B exceeds the free RAM {free_ram} B")
    if worst is not None and limit is not None and worst > limit:
        over.append(f"worst case {worst} B exceeds --limit {limit} B")
    if worst is not None and static_ram is not None and ram_budget is not None and \
            static_ram + worst > ram_budget:
        over.append(f"static RAM {static_ram} B + worst case {worst} B = "
                    f"{static_ram + worst} B exceeds the RAM budget {ram_budget} B")
    return {"roots": roots, "worst": worst, "free_ram": free_ram, "nesting": nesting,
            "nmi_nested": nmi_nested, "nmi_note": nmi_note,
            "static_ram": static_ram, "ram_budget": ram_budget,
            "address_taken": image.taken, "errors": sorted(set(errors)), "over": over,
            "resets": sorted(n for n in image.taken if image.funcs[n].stack_reset)}


def print_report(r, out=sys.stdout):
    print(f"{'root':<8}{'handler':<24}{'vec':<8}{'bound':>6}  deepest chain (frame bytes)",
          file=out)
    for x in sorted(r["roots"], key=lambda x: (x["root"] != "reset", -x["bound"])):
        vec = ",".join(str(v) for v in x["vectors"])
        chain = chain_text([(c["function"], c["frame"]) for c in x["chain"]])
        extra = f"{x['entry']} + " if x["entry"] else ""
        print(f"{x['root']:<8}{x['function']:<24}{vec:<8}{x['bound']:>6}  {extra}{chain}",
              file=out)
    isr_gie = {}
    for x in r["roots"]:
        if x["root"] != "isr":
            continue
        for g in x["gie"]:
            isr_gie.setdefault((g["function"], g["insn"], g["kind"]), []).append(x["function"])
    if isr_gie:
        print("GIE writes reachable from handlers:", file=out)
        for (fn, insn, kind), who in sorted(isr_gie.items()):
            what = "SETS GIE" if kind == "set" else "restores a saved state (GIE off here)"
            print(f"  {fn}: {insn}: {what}; from {', '.join(sorted(set(who)))}", file=out)
    print("handlers re-enable interrupts: " + ("YES, nesting counted" if r["nesting"]
                                               else "no"), file=out)
    print(f"address-taken functions (indirect targets): {len(r['address_taken'])}: "
          + ", ".join(sorted(r["address_taken"])), file=out)
    if r["resets"]:
        print("  not targets, they set the stack pointer themselves: "
              + ", ".join(r["resets"]), file=out)
    for e in r["errors"]:
        print(f"error: {e}", file=out)
    if r.get("nmi_note"):
        print(f"NMI: {r['nmi_note']}", file=out)
    if r["worst"] is not None:
        how = ("reset + every handler" if r["nesting"]
               else "reset + deepest maskable handler + NMI handler")
        if r.get("nmi_nested"):
            how += f" + {r['nmi_nested']} (the NMI under a second one)"
        print(f"worst case: {r['worst']} B ({how})", file=out)
    if r["free_ram"] is not None:
        print(f"free RAM: {r['free_ram']} B", file=out)
        if r["worst"] is not None:
            print(f"margin: {r['free_ram'] - r['worst']} B", file=out)
    if r.get("ram_budget") is not None and r.get("static_ram") is not None and \
            r["worst"] is not None:
        used = r["static_ram"] + r["worst"]
        print(f"RAM budget: static {r['static_ram']} B + stack {r['worst']} B = {used} B "
              f"of {r['ram_budget']} B ({r['ram_budget'] - used} B left)", file=out)
    for o in r["over"]:
        print(f"stack_bound: {o}", file=out)


def load_image(elf_path, objdump, indirect):
    elf = Elf(elf_path)
    run = subprocess.run([objdump, "-d", "--no-show-raw-insn", elf_path], capture_output=True,
                         text=True, check=True)
    insns = parse_disassembly(run.stdout)
    data = elf.words(lambda s: not s["flags"] & SHF_EXECINSTR
                     and not VECTOR_BASE <= s["addr"] < 0x10000)
    # Local labels of the assembly sources that are called are subroutine entries too.
    called = {imm(i.ops[0]) for i in insns.values() if i.mnem in ("call", "calla") and i.ops}
    syms = [(n, a) for n, a, entry in elf.functions() if entry or a in called]
    # Static functions of different files may share a name: the later ones get @address.
    funcs = {}
    for n, a in sorted(syms, key=lambda x: x[1]):
        if n in funcs and funcs[n] != a:
            n = f"{n}@{a:04x}"
        funcs.setdefault(n, a)
    image = Image(insns, funcs, data, indirect)
    vecs = {}
    allwords = dict(elf.words(lambda s: True))
    for v in range(VECTOR_COUNT):
        a = VECTOR_BASE + 2 * v
        if a not in allwords:
            raise ValueError(f"{elf_path}: no vector table word at {a:04x}")
        w = allwords[a]
        if w not in image.by_addr:
            raise ValueError(f"vector {v} ({a:04x}) points at {w:04x}, not a function")
        vecs[v] = image.by_addr[w]
    return elf, image, vecs


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("elf")
    ap.add_argument("--objdump", default="llvm-objdump-16")
    ap.add_argument("--limit", type=int, help="fail when the worst case exceeds this many bytes")
    ap.add_argument("--ram-budget", type=int,
                    help="fail when the static RAM (.data, .bss, .noinit) plus the worst case "
                         "exceeds this many bytes (the board images' budget)")
    ap.add_argument("--ram-end", type=lambda s: int(s, 0),
                    help="end of RAM (default: the image's __stack_top)")
    ap.add_argument("--indirect", action="append", default=[], metavar="SITE=F1,F2",
                    help="narrow the targets of the indirect calls of SITE (a function, or "
                         "function@hexaddr) to these functions")
    ap.add_argument("--function", action="append", default=[], metavar="NAME",
                    help="also print the bound of this function (its call included: +2)")
    ap.add_argument("--no-mpy-in-isr", action="store_true",
                    help="fail when a maskable interrupt handler reaches code that names a "
                         "hardware multiplier register (0x130-0x13F)")
    ap.add_argument("--no-mpy-in-nmi", action="store_true",
                    help="fail when the NMI handler reaches code that names a hardware "
                         "multiplier register or a compiler multiply helper (__mspabi_mpy*)")
    ap.add_argument("--json", help="write the analysis here")
    args = ap.parse_args(argv)

    indirect = {}
    for spec in args.indirect:
        site, _, names = spec.partition("=")
        indirect[site] = [n for n in names.split(",") if n]
    elf, image, vectors = load_image(args.elf, args.objdump, indirect)
    for site, names in indirect.items():
        for n in [site.split("@")[0]] + names:
            if n not in image.funcs:
                print(f"stack_bound: --indirect names {n}, not a function of the image",
                      file=sys.stderr)
                return 2
    image.analyse()
    ram_end = args.ram_end if args.ram_end is not None else elf.symbol("__stack_top")
    static_end = elf.symbol("__noinit_end")
    free = ram_end - static_end if ram_end is not None and static_end is not None else None
    ram_start = elf.symbol("__ram_start")
    static = static_end - ram_start if static_end is not None and ram_start is not None else None
    r = report(image, vectors, free, args.limit, no_mpy_in_isr=args.no_mpy_in_isr,
               static_ram=static, ram_budget=args.ram_budget, no_mpy_in_nmi=args.no_mpy_in_nmi)
    r["image"] = args.elf
    r["ram_end"] = ram_end
    r["static_end"] = static_end
    print(f"{args.elf}: RAM end {ram_end:#06x}, static data end {static_end:#06x}")
    print_report(r)
    r["functions"] = {}
    for name in args.function:
        if name not in image.funcs:
            print(f"stack_bound: no function {name} in the image", file=sys.stderr)
            return 2
        b, chain = Bounds(image).of(name)
        r["functions"][name] = {"bound": b + 2, "chain": [{"function": n, "frame": fr}
                                                         for n, fr in chain]}
        print(f"function {name}: {b + 2} B with its call: 2 + {chain_text(chain)}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(r, f, indent=1)
    if r["errors"]:
        print("stack_bound: the image could not be analysed", file=sys.stderr)
        return 1
    return 1 if r["over"] else 0


if __name__ == "__main__":
    sys.exit(main())
