#!/usr/bin/env python3
"""Static worst-case cycle count of MSP430 interrupt handlers from the linked image
(docs/cycles.md), with the instruction timings of TI's user's guide SLAU144, beside what
mspdebug 0.22's simulator charges for the same path.

  cycle_bound.py ELF --root HANDLER [--indirect SITE=F1,F2] [--loop SITE=N] [--json OUT]
  cycle_bound.py ELF --scenario FILE.json [--cycles-json build/msp430/cycles.json]

The handler's code and everything it calls is followed instruction by instruction (the
disassembly and the ELF's bytes: the addressing modes decide the cost), as tools/stack_bound.py
follows it for the stack: jumps, jump tables, calls (their callee's worst case added at the
call), tail calls. The worst case is the longest path from the handler's entry to its RETI,
plus the 6 cycles of accepting the interrupt: SLAU144's table of interrupt cycles, its Format I
and Format II tables by addressing mode (constant-generator operands count as registers), 2
cycles per jump (tests/target/datasheet/slau144_cycles.csv). The same path is also priced
with mspdebug 0.22's rules (drivers/sim.c: it charges constant-generator operands as the
memory modes their encoding borrows).

Indirect calls may reach every address-taken function unless --indirect narrows a site:
SITE is FUNC (all its indirect sites), FUNC@hexaddr, or FUNC#k (its k-th indirect site in
address order, from 1); an empty list means the call is not made on the path measured (the
path through it is dropped: e.g. the callback of a line whose flag is clear). Loops need a
bound: --loop FUNC=N or FUNC@hexaddr=N (the loop whose first instruction is at that address)
is the number of times the loop's first instruction runs per entry into the loop; the cost is
(N - 1) longest iterations plus the longest way out. A counted loop (a register set to #N
right before it, decremented once per iteration and tested against zero by the jump back,
no call inside) gets N without being told; any other loop without a bound is an error
naming it. Each use of --indirect and --loop should cite the source that guarantees it.

--scenario FILE: {"entries": [{"name": "isr_delta_l", "root": "hal_isr_port1",
"cases": [{"indirect": {"SITE": ["F"]}, "why": "..."}], "loops": {"SITE": N}}]} - every case
is one path set; an entry's bound is the worst case over its cases. With --cycles-json the
bounds go into the cycle report's entries of those names (static_cycles_max: SLAU144;
static_cycles_max_sim: mspdebug's rules; static_image), beside the simulator's cycles_max.
"""
import argparse
import csv
import fcntl
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import stack_bound as sb  # noqa: E402

TABLE = os.path.join(HERE, "..", "tests", "target", "datasheet", "slau144_cycles.csv")
R0, R2, R3 = 0, 2, 3


class Timings:
    """SLAU144's cycle tables (slau144_cycles.csv)."""

    def __init__(self, path=TABLE):
        with open(path) as f:
            rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
        self.fmt1 = {(r["src"], r["dst"]): int(r["cycles"]) for r in rows if r["format"] == "I"}
        self.fmt2 = {(r["operation"], r["src"]): int(r["cycles"]) for r in rows
                     if r["format"] == "II"}
        self.jump = next(int(r["cycles"]) for r in rows if r["format"] == "III")
        self.reti = next(int(r["cycles"]) for r in rows if r["operation"] == "RETI")
        self.accept = next(int(r["cycles"]) for r in rows if r["operation"] == "accepted")


def src_class(as_, rs):
    """SLAU144's source operand class of As/Rs: Rn, @Rn, @Rn+, #N or mem."""
    if rs == R3 or (rs == R2 and as_ >= 2):
        return "Rn"  # constant generator
    if as_ == 0:
        return "Rn"
    if as_ == 1:
        return "mem"  # x(Rn), EDE (R0), &EDE (R2)
    if as_ == 2:
        return "@Rn"
    return "#N" if rs == R0 else "@Rn+"


class Decoder:
    """Instruction words from the image's bytes and their cost under both models."""

    def __init__(self, elf, timings):
        self.elf = elf
        self.t = timings
        self.spans = [(s["addr"], s["addr"] + s["size"], s["offset"]) for s in elf.sections
                      if s["type"] == sb.SHT_PROGBITS and s["flags"] & sb.SHF_EXECINSTR]

    def word(self, addr):
        for lo, hi, off in self.spans:
            if lo <= addr < hi - 1:
                d = self.elf.data
                return d[off + addr - lo] | d[off + addr - lo + 1] << 8
        raise ValueError(f"{addr:04x}: not in a code section")

    def cost(self, addr):
        """(SLAU144 cycles, mspdebug 0.22 cycles) of the instruction at addr."""
        w = self.word(addr)
        if w & 0xE000 == 0x2000:
            return self.t.jump, 2
        if w & 0xF000 >= 0x4000:
            rs, ad, as_, rd = (w >> 8) & 15, (w >> 7) & 1, (w >> 4) & 3, w & 15
            dst = "mem" if ad else ("PC" if rd == R0 else "Rm")
            guide = self.t.fmt1[(src_class(as_, rs), dst)]
            # mspdebug 0.22, step_double(): by the encoded modes, constants included
            if not ad and rd == R0:
                sim = 2 if as_ in (0, 2) else 3
            else:
                sim = 2 if as_ in (2, 3) else 3 if as_ == 1 else 1
                sim += 3 if ad else 0
            return guide, sim
        if w & 0xFC00 == 0x1000:
            op, as_, reg = (w >> 7) & 7, (w >> 4) & 3, w & 15
            if op == 6:
                return self.t.reti, 5
            src = src_class(as_, reg)
            name = {4: "PUSH", 5: "CALL"}.get(op, "RRA/RRC/SWPB/SXT")
            guide = self.t.fmt2[(name, src)]
            # mspdebug 0.22, step_single()
            if op == 4:
                sim = 3 if as_ == 0 else 4 if as_ == 2 or (as_ == 3 and reg == R0) else 5
            elif op == 5:
                sim = 4 if as_ in (0, 2) else 5
            else:
                sim = 4 if as_ == 1 else 1 if as_ == 0 else 3
            return guide, sim
        raise ValueError(f"{addr:04x}: word {w:04x} is no MSP430 instruction this tool knows")


class Unbounded(Exception):
    pass


class Analysis:
    """Worst-case cycles per function (both models) with calls, loops, narrowed sites."""

    def __init__(self, image, decoder, sites, loops):
        self.image, self.dec = image, decoder
        self.sites, self.loops = sites, loops  # {SITE: [targets]}, {SITE: N}
        self.memo, self.stack = {}, []
        self.used_sites, self.used_loops = set(), set()
        self.derived = []  # the loop bounds derived from the code: FUNC@addr=N

    def site_targets(self, f, addr, ordinal, default):
        for key in (f"{f.name}@{addr:04x}", f"{f.name}#{ordinal}", f.name):
            if key in self.sites:
                self.used_sites.add(key)
                return self.sites[key]
        return default

    def bound(self, f, header):
        for key in (f"{f.name}@{header:04x}", f.name):
            if key in self.loops:
                self.used_loops.add(key)
                return self.loops[key]
        return None

    def derive(self, h, latches, body, succ):
        """The bound of a counted loop: a register set to #N just before the loop, counted
        down by one once per iteration and tested against zero by the jump back (what the
        compiler makes of `for (i = 0; i < N; i++)` without other uses of i); None else."""
        img = self.image
        if len(latches) != 1 or not all(isinstance(x, int) for x in body):
            return None
        u = next(iter(latches))
        if img.insns[u].mnem not in ("jne", "jnz") or sb.jump_target(img.insns[u]) != h:
            return None
        prev = img.addrs[img._index(u) - 1]
        p = img.insns[prev]
        if p.mnem in ("tst", "tst.b"):
            reg = p.ops[0]
        else:
            reg = sb.dest(p)
        if reg is None or not re.fullmatch(r"r\d+", reg):
            return None

        def decrement(i):
            return (i.mnem in ("add", "add.b") and i.ops[0] == "#-1") or \
                (i.mnem in ("sub", "sub.b") and i.ops[0] == "#1") or i.mnem in ("dec", "dec.b")
        writes = [a for a in body if sb.dest(img.insns[a]) == reg]
        if len(writes) != 1 or not decrement(img.insns[writes[0]]):
            return None
        if any(img.insns[a].mnem in ("call", "calla") for a in body):
            return None
        preds = [x for x, ys in succ.items() if h in ys and x not in body]
        before = img.addrs[img._index(h) - 1]
        if preds != [before]:
            return None
        a = before
        for _ in range(8):
            i = img.insns[a]
            if i.mnem in ("mov", "mov.b") and i.ops[1:] == [reg] and sb.imm(i.ops[0]):
                return sb.imm(i.ops[0])
            if sb.dest(i) == reg or i.mnem in sb.COND_JUMPS or i.mnem in ("jmp", "call", "br",
                                                                         "ret", "reti"):
                return None
            a = img.addrs[img._index(a) - 1]
        return None

    def of(self, name):
        """(SLAU144 cycles, mspdebug cycles, path of function names) of the worst path from
        the entry of @name to its return (the call instruction not included)."""
        if name in self.memo:
            return self.memo[name]
        if name in self.stack:
            raise Unbounded("recursion: " + " -> ".join(self.stack + [name]))
        self.stack.append(name)
        try:
            self.memo[name] = self._function(self.image.funcs[name])
        finally:
            self.stack.pop()
        return self.memo[name]

    def _graph(self, f):
        """Nodes (instruction addresses) reachable from f's entry: {addr: (w_guide, w_sim,
        callees)}, successors, terminal nodes; None weight: a path not taken."""
        img = self.image
        calls = {}
        for e in f.edges:
            calls.setdefault(e[3], []).append(e)
        icall_sites = sorted(a for a, es in calls.items() if any(x[1] is None for x in es))
        nodes, succ, term = {}, {}, set()
        work, seen = [f.start], {f.start}
        while work:
            a = work.pop()
            insn = img.insns[a]
            g, s = self.dec.cost(a)
            nxt = img._next(a)
            out, callees, dropped = [], [], False
            m = insn.mnem
            edges = calls.get(a, [])
            for kind, target, _, _ in edges:
                if target is not None:
                    callees.append(target)
                    continue
                k = icall_sites.index(a) + 1
                ts = self.site_targets(f, a, k, img.targets(f, (kind, None, 0, a)))
                if not ts:
                    dropped = True
                callees += ts if len(ts) == 1 else [tuple(ts)]
            if dropped:
                nodes[a] = (None, None, [])
                succ[a] = []
                continue
            if m in ("ret", "reti", "reta"):
                term.add(a)
            elif m == "jmp" or m in sb.COND_JUMPS:
                t = sb.jump_target(insn)
                if any(e[0] == "tail" for e in edges):
                    term.add(a)
                else:
                    out.append(t)
                if m != "jmp" and nxt is not None:
                    out.append(nxt)
            elif m in ("call", "calla"):
                if all(isinstance(c, tuple) or c in self._returning for c in callees) \
                        and nxt is not None:
                    out.append(nxt)
                else:
                    term.add(a)
            elif m in ("br", "bra") or sb.dest(insn) == sb.PC:
                t = sb.imm(insn.ops[0]) if m in ("br", "bra") else None
                table = img.jump_table(f, insn) if m in ("br", "bra") and t is None else None
                if t is not None and t in img.insns and t not in img.by_addr:
                    out.append(t)
                elif table:
                    out += table
                else:
                    term.add(a)  # a tail call (its target among the callees)
            elif nxt is not None:
                if nxt in img.by_addr and nxt != f.start:
                    term.add(a)  # falls into the next function: a tail call
                    callees.append(img.by_addr[nxt])
                else:
                    out.append(nxt)
            nodes[a] = (g, s, callees)
            succ[a] = out
            for t in out:
                if t not in seen:
                    seen.add(t)
                    work.append(t)
        return nodes, succ, term

    def _function(self, f):
        nodes, succ, term = self._graph(f)
        weight = {}
        path_of = {}
        for a, (g, s, callees) in nodes.items():
            if g is None:
                weight[a] = None
                continue
            best = (0, 0, [])
            for c in callees:
                options = c if isinstance(c, tuple) else (c,)
                for t in options:
                    cg, cs, cp = self.of(t)
                    if cg > best[0]:
                        best = (cg, cs, [t] + cp)
            # several direct callees at one instruction cannot happen; a tuple is one
            # indirect call to one of several targets
            weight[a] = (g + best[0], s + best[1])
            path_of[a] = best[2]
        return self._longest(f, weight, succ, term, path_of)

    def _longest(self, f, weight, succ, term, path_of):
        """Longest entry-to-exit path over the graph, loops collapsed innermost first."""
        w = {a: v for a, v in weight.items()}
        s = {a: list(v) for a, v in succ.items()}
        t = set(term)
        paths = {a: list(path_of.get(a, [])) for a in w}
        entry = f.start
        while True:
            back = self._back_edges(entry, s)
            if not back:
                break
            headers = {}
            for u, h in back:
                headers.setdefault(h, set()).add(u)
            bodies = {h: self._body(h, us, s) for h, us in headers.items()}
            h = min(bodies, key=lambda x: len(bodies[x]))
            body, latches = bodies[h], headers[h]
            n = self.bound(f, h)
            if n is None:
                n = self.derive(h, latches, body, s)
                if n is not None:
                    self.derived.append(f"{f.name}@{h:04x}={n}")
            if n is None:
                raise Unbounded(f"loop at {f.name}@{h:04x} (back edge from "
                                f"{', '.join(f'{u:04x}' for u in sorted(latches))}) needs "
                                f"--loop {f.name}@{h:04x}=N")
            dist = self._dag_longest_from(h, body, s, w, h)
            it = [dist[u] for u in latches if u in dist and dist[u] is not None]
            ex = [dist[x] for x in body if x in dist and dist[x] is not None and
                  (x in t or any(y not in body for y in s[x]))]
            if not ex:
                raise Unbounded(f"loop at {f.name}@{h:04x} has no way out")
            it_g = max((d[0] for d in it), default=0)
            it_s = max((d[1] for d in it), default=0)
            last_g = max(d[0] for d in ex)
            last_s = max(d[1] for d in ex)
            node = ("loop", h)
            w[node] = ((n - 1) * it_g + last_g, (n - 1) * it_s + last_s)
            paths[node] = sorted({p for x in body for p in paths.get(x, [])})
            outs = sorted({y for x in body for y in s[x] if y not in body}, key=str)
            s[node] = outs
            if any(x in t for x in body):
                t.add(node)
            for x in list(s):
                if x not in body:
                    s[x] = [node if y == h else y for y in s[x]]
            for x in body:
                del s[x]
                w.pop(x, None)
                t.discard(x)
            if entry in body:
                entry = node
        memo = {}

        def best(v, depth=0):
            if v in memo:
                return memo[v]
            if w.get(v) is None:
                memo[v] = None
                return None
            cands = []
            if v in t or not s[v]:
                if v in t:
                    cands.append((0, 0, []))
            for y in s[v]:
                b = best(y)
                if b is not None:
                    cands.append(b)
            if not cands:
                memo[v] = None
                return None
            g = max(cands, key=lambda c: c[0])
            sm = max(c[1] for c in cands)
            memo[v] = (w[v][0] + g[0], w[v][1] + sm, paths.get(v, []) + g[2])
            return memo[v]

        sys.setrecursionlimit(100000)
        r = best(entry)
        if r is None:
            raise Unbounded(f"{f.name}: no path from the entry to a return")
        seen, path = set(), []
        for p in r[2]:
            if p not in seen:
                seen.add(p)
                path.append(p)
        return r[0], r[1], path

    @staticmethod
    def _back_edges(entry, s):
        back, state = [], {}
        stack = [(entry, iter(s.get(entry, [])))]
        state[entry] = 1
        while stack:
            v, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                state[v] = 2
                stack.pop()
                continue
            if nxt not in s:
                continue
            if state.get(nxt) == 1:
                back.append((v, nxt))
            elif nxt not in state:
                state[nxt] = 1
                stack.append((nxt, iter(s.get(nxt, []))))
        return back

    @staticmethod
    def _body(h, latches, s):
        pred = {}
        for x, ys in s.items():
            for y in ys:
                pred.setdefault(y, []).append(x)
        body, work = {h}, [u for u in latches]
        while work:
            x = work.pop()
            if x in body:
                continue
            body.add(x)
            work += pred.get(x, [])
        return body

    @staticmethod
    def _dag_longest_from(h, body, s, w, header):
        """Longest distances (both models) from h to every node of the body, the back
        edges to the header left out (inner loops are collapsed already: a DAG)."""
        order, seen = [], set()

        def visit(v):
            seen.add(v)
            for y in s[v]:
                if y in body and y != header and y not in seen:
                    visit(y)
            order.append(v)
        visit(h)
        dist = {h: w[h]}
        for v in reversed(order):
            if v not in dist or dist[v] is None or w[v] is None:
                continue
            for y in s[v]:
                if y in body and y != header and w.get(y) is not None:
                    c = (dist[v][0] + w[y][0], dist[v][1] + w[y][1])
                    if y not in dist or dist[y] is None or c[0] > dist[y][0]:
                        dist[y] = (c[0], max(c[1], dist.get(y, (0, 0))[1] if dist.get(y) else 0))
        return dist


def parse_specs(specs, what):
    out = {}
    for spec in specs:
        site, _, value = spec.partition("=")
        if not site:
            raise ValueError(f"--{what} {spec}: expected SITE=...")
        out[site] = value
    return out


def analyse_root(image, decoder, root, indirect, loops):
    """(guide cycles, mspdebug cycles, path, sites used, loops used) of handler @root,
    the interrupt's acceptance included."""
    a = Analysis(image, decoder, indirect, loops)
    a._returning = returning(image)
    g, s, path = a.of(root)
    acc = decoder.t.accept
    return g + acc, s + 6, [root] + path, a.used_sites, a.used_loops


def returning(image):
    """Functions that can return (stack_bound's least fixpoint)."""
    out = set()
    changed = True
    while changed:
        changed = False
        for f in image.funcs.values():
            if f.name not in out and (f.returns or any(k == "ijump" or (k == "tail" and t in out)
                                                       for k, t, _, _ in f.edges)):
                out.add(f.name)
                changed = True
    return out


def merge_static(path, image_name, results):
    """Put the static bounds into the cycle report's entries of those names (under the lock
    tools/msp430sim.py's merge uses), keeping every other field of the entries."""
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
        by_name = {e["name"]: e for e in report.get("entries", [])}
        for e in by_name.values():  # this image's earlier static figures go first
            if e.get("static_image") == image_name:
                for k in ("static_cycles_max", "static_cycles_max_sim", "static_image"):
                    e.pop(k, None)
        for name, (g, s) in results.items():
            e = by_name.setdefault(name, {"name": name})
            e.update({"static_cycles_max": g, "static_cycles_max_sim": s,
                      "static_image": image_name})
        report["entries"] = [by_name[k] for k in sorted(by_name)
                             if set(by_name[k]) != {"name"}]
        tmp = path + ".tmp"
        with open(tmp, "w") as f:
            json.dump(report, f, indent=1)
            f.write("\n")
        os.replace(tmp, path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("elf")
    ap.add_argument("--objdump", default="llvm-objdump-16")
    ap.add_argument("--root", action="append", default=[], help="a handler to count")
    ap.add_argument("--indirect", action="append", default=[], metavar="SITE=F1,F2")
    ap.add_argument("--loop", action="append", default=[], metavar="SITE=N")
    ap.add_argument("--scenario", help="JSON file of entries, their roots, cases and loops")
    ap.add_argument("--cycles-json", help="merge the scenario's bounds into this report")
    ap.add_argument("--json", help="write the results here")
    args = ap.parse_args(argv)

    elf, image, _vectors = sb.load_image(args.elf, args.objdump, {})
    image.analyse()
    dec = Decoder(elf, Timings())
    jobs = []  # (entry name, root, [(indirect, why)], loops)
    try:
        ind = {k: [t for t in v.split(",") if t] for k, v in
               parse_specs(args.indirect, "indirect").items()}
        lps = {k: int(v) for k, v in parse_specs(args.loop, "loop").items()}
    except ValueError as e:
        print(f"cycle_bound: {e}", file=sys.stderr)
        return 2
    for r in args.root:
        jobs.append((r, r, [(ind, "")], lps))
    if args.scenario:
        with open(args.scenario) as f:
            sc = json.load(f)
        for e in sc["entries"]:
            cases = [(c.get("indirect", {}), c.get("why", "")) for c in e["cases"]]
            jobs.append((e["name"], e["root"], cases, e.get("loops", {})))
    if not jobs:
        print("cycle_bound: give --root or --scenario", file=sys.stderr)
        return 2
    problems, results, out = [], {}, {}
    for name, root, cases, loops in jobs:
        if root not in image.funcs:
            problems.append(f"{name}: no function {root} in the image")
            continue
        best = None
        for indirect, why in cases:
            for site in indirect:
                fn = re.split(r"[@#]", site)[0]
                if fn not in image.funcs:
                    problems.append(f"{name}: --indirect names {fn}, not a function")
            try:
                g, s, path, used, lused = analyse_root(image, dec, root, indirect, loops)
            except Unbounded as u:
                problems.append(f"{name}: {u}")
                continue
            for site in sorted(set(indirect) - used):
                problems.append(f"{name}: --indirect {site} matches no indirect site reached")
            if best is None or g > best[0]:
                best = (g, s, path)
            elif s > best[1]:
                best = (best[0], s, best[2])
        if best is None:
            continue
        results[name] = (best[0], best[1])
        out[name] = {"root": root, "static_cycles_max": best[0], "static_cycles_max_sim": best[1],
                     "path": best[2]}
        print(f"{name:<22} {root:<18} {best[0]:>7} (SLAU144)  {best[1]:>7} (mspdebug 0.22)  "
              f"{' > '.join(best[2])}")
    for p in problems:
        print(f"error: {p}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)
    if args.cycles_json and results and not problems:
        merge_static(args.cycles_json, os.path.splitext(os.path.basename(args.elf))[0], results)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
