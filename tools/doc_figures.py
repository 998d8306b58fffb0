#!/usr/bin/env python3
"""Generate, or check, the figures quoted in the docs from what the build and the tests measured.

  doc_figures.py [--root DIR] [--tree TREE]... [--build DIR] [--cycles FILE] [--host-bin DIR]
                 [--write] [doc.md ...]

A table in a Markdown file (default: README.md and docs/*.md of --root) is generated when it
sits between two markers, `<!-- KIND TREE: ARGS -->` and `<!-- KIND end -->`:

  cycles msp430: optical_fix isr_index_pulse kernel/optical_vectors/optical_scan
      entries of the cycle report (BUILD/cycles.json, written by the target tests): max, mean
      and max µs; "kernel/P/K" stands for both sides of kernel K measured in the check image
      of vector program P (docs/kernels.md): one row with the assembly's and the C twin's.
  images msp430: main_board nav_board
      the board images: flash and static RAM (BUILD/images/NAME.json, tools/image_size.py, with
      the budget), the static worst-case stack (BUILD/images/NAME.stack.json,
      tools/stack_bound.py) and the measured high-water mark (the cycle report's "stack").
  flash msp430: main_board
      the flash each library takes in the image, from its link map (BUILD/bin/NAME.map).
  closedloop host: table_6_1_1987_full factory_loop      (or *: every sim/scenarios/*.json)
      agv-sim (HOST_BIN/agv-sim) run on sim/scenarios/NAME.json: fixes accepted, fix error,
      cross-track error, goal, against the scenario's criteria.

TREE names the build the figures come from: msp430 (the default MSP430 tree), msp430-c (the
kernels' C twins, docs/kernels.md), host (agv-sim). Only the blocks of the --tree given
(default: msp430 and host) are looked at.

Without --write: exit 1 when a block differs from what the measurements give (the command to
regenerate it is printed), or names something they lack. With --write: rewrite the blocks in
place. Run it after the target tests (make test runs it last, as ctest docs.figures).
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from linkmap import flash_by_library  # noqa: E402

BEGIN_RE = re.compile(r"^<!-- (?P<kind>cycles|images|flash|closedloop) (?P<tree>[\w-]+): "
                      r"(?P<names>[^>]*?) -->\s*$")
END = "<!-- {} end -->"


class Missing(Exception):
    """A figure the measurements do not have (the message says which and where)."""


def fmt(n):
    return f"{n:,}"


def load_json(path, what):
    try:
        with open(path) as f:
            return json.load(f)
    except OSError as e:
        raise Missing(f"{path}: {e.strerror} ({what})")
    except ValueError as e:
        raise Missing(f"{path}: not JSON: {e}")


class Sources:
    """The measurements, read when a block asks for them."""

    def __init__(self, root, build, cycles, host_bin):
        self.root, self.build, self.cycles_path, self.host_bin = root, build, cycles, host_bin
        self._cycles = None
        self._runs = {}

    def cycles(self):
        if self._cycles is None:
            self._cycles = load_json(self.cycles_path, "run the target tests first")
        return self._cycles

    def entries(self):
        return {e["name"]: e for e in self.cycles().get("entries", [])}

    def default_criterion(self, key):
        """The schema's default of success.KEY (docs/schema/scenario.schema.json)."""
        path = os.path.join(self.root, "docs", "schema", "scenario.schema.json")
        schema = load_json(path, "the scenario's schema")
        try:
            return schema["properties"]["success"]["properties"][key]["default"]
        except KeyError:
            raise Missing(f"{path}: no default of success.{key}")

    def run(self, name):
        """The report of agv-sim on sim/scenarios/NAME.json, and the scenario."""
        if name not in self._runs:
            scenario = os.path.join(self.root, "sim", "scenarios", f"{name}.json")
            agv = os.path.join(self.host_bin, "agv-sim")
            if not os.path.isfile(scenario):
                raise Missing(f"{scenario}: no such scenario")
            if not os.path.isfile(agv):
                raise Missing(f"{agv}: not built (make host)")
            with tempfile.TemporaryDirectory() as tmp:
                report = os.path.join(tmp, "r.json")
                r = subprocess.run([agv, "--scenario", scenario, "--quiet", "--report", report],
                                   capture_output=True, text=True, timeout=900)
                if r.returncode == 2 or not os.path.exists(report):
                    raise Missing(f"agv-sim refused {scenario}: {r.stderr.strip()}")
                self._runs[name] = (load_json(report, "agv-sim's report"),
                                    load_json(scenario, "the scenario"))
        return self._runs[name]


def cycles_table(names, src):
    entries = src.entries()
    hz = src.cycles().get("clock_hz", 16000000)
    plain = [n for n in names if not n.startswith("kernel/")]
    kernels = [n for n in names if n.startswith("kernel/")]
    lines = []
    if plain:
        lines += ["| entry | max | mean | max µs |", "| --- | ---: | ---: | ---: |"]
        for n in plain:
            if n not in entries:
                raise Missing(f"the cycle report has no entry {n}")
            e = entries[n]
            us = e["cycles_max"] * 1e6 / hz
            lines.append(f"| `{n}` | {fmt(e['cycles_max'])} | {fmt(e['cycles_mean'])} | "
                         f"{us:,.1f} |")
    if kernels:
        if lines:
            lines.append("")
        lines += ["| kernel | program | calls | asm max | asm mean | C twin max | C twin mean |",
                  "| --- | --- | ---: | ---: | ---: | ---: | ---: |"]
        for n in kernels:
            _, program, kernel = n.split("/")
            a, c = entries.get(n + "/asm"), entries.get(n + "/c")
            if a is None or c is None:
                raise Missing(f"the cycle report has no entry {n + '/asm' if a is None else n + '/c'}")
            lines.append(f"| `{kernel}` | {program} | {fmt(a['samples'])} | "
                         f"{fmt(a['cycles_max'])} | {fmt(a['cycles_mean'])} | "
                         f"{fmt(c['cycles_max'])} | {fmt(c['cycles_mean'])} |")
    return lines


def images_table(names, src):
    measured = {s["image"]: s for s in src.cycles().get("stack", [])}
    lines = ["| image | flash | budget | static RAM | stack, static worst case | "
             "stack, measured | static RAM + worst stack | budget |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for n in names:
        img = load_json(os.path.join(src.build, "images", f"{n}.json"), "build the image")
        st = load_json(os.path.join(src.build, "images", f"{n}.stack.json"),
                       "run the target tests first (target.stack_bound.*)")
        if n not in measured:
            raise Missing(f"the cycle report has no stack high-water mark of {n}")
        for key, d, what in (("flash_limit", img, "images"), ("worst", st, "stack")):
            if d.get(key) is None:
                raise Missing(f"{n}'s {what} figures have no {key} (the analysis failed: "
                              "see target.stack_bound.*); rebuild")
        lines.append(f"| `{n}.elf` | {fmt(img['flash'])} B | {fmt(img['flash_limit'])} | "
                     f"{fmt(img['ram'])} B | {fmt(st['worst'])} B | "
                     f"{fmt(measured[n]['used'])} B | {fmt(img['ram'] + st['worst'])} B | "
                     f"{fmt(st['ram_budget'])} |")
    return lines


def flash_table(names, src):
    lines = []
    for n in names:
        path = os.path.join(src.build, "bin", f"{n}.map")
        try:
            with open(path) as f:
                libs = flash_by_library(f.read())
        except OSError as e:
            raise Missing(f"{path}: {e.strerror} (build the image)")
        total = sum(libs.values())
        if lines:
            lines.append("")
        lines += [f"| in `{n}.elf` | flash | share |", "| --- | ---: | ---: |"]
        for lib, b in sorted(libs.items(), key=lambda kv: (-kv[1], kv[0])):
            lines.append(f"| `{lib}` | {fmt(b)} B | {100 * b / total:.1f} % |")
        lines.append(f"| all | {fmt(total)} B | |")
    return lines


def closedloop_table(names, src):
    if names == ["*"]:
        names = sorted(os.path.splitext(os.path.basename(p))[0] for p in
                       glob.glob(os.path.join(src.root, "sim", "scenarios", "*.json")))
    lines = ["| scenario | fixes accepted | fix error RMS / max | cross-track mean / max | "
             "goal, final error | criterion: cross-track mean |",
             "| --- | ---: | --- | --- | --- | ---: |"]
    for n in names:
        rep, sc = src.run(n)
        try:
            fx, path = rep["fixes"], rep["path"]
            err, ct = fx["error_m"], path["cross_track_m"]
            goal = "reached" if path["reached_goal"] else "not reached"
            row = (f"| `{n}` | {fx['accepted']} of {fx['attempted']} | "
                   f"{err['rms'] * 1e3:.1f} / {err['max'] * 1e3:.1f} mm | "
                   f"{ct['mean'] * 1e3:.1f} / {ct['max'] * 1e3:.1f} mm | "
                   f"{goal}, {path['final_error_m'] * 1e3:.1f} mm | ")
        except KeyError as e:
            raise Missing(f"agv-sim's report of {n} has no key {e.args[0]}")
        crit = sc.get("success", {}).get("cross_track_mean_m")
        if crit is None:
            crit = src.default_criterion("cross_track_mean_m")
            lines.append(row + f"{crit * 1e3:g} mm (default) |")
        else:
            lines.append(row + f"{crit * 1e3:g} mm |")
    return lines


TABLES = {"cycles": cycles_table, "images": images_table, "flash": flash_table,
          "closedloop": closedloop_table}


def process(path, trees, src, write):
    """Problems of one document (and its new text when write)."""
    with open(path, encoding="utf-8") as f:
        old = f.read().split("\n")
    out, errors, i = [], [], 0
    while i < len(old):
        line = old[i]
        out.append(line)
        m = BEGIN_RE.match(line)
        i += 1
        if not m:
            continue
        end_mark = END.format(m.group("kind"))
        try:
            end = old.index(end_mark, i)
        except ValueError:
            errors.append(f"{path}:{i}: `{line.strip()}` without `{end_mark}`")
            out += old[i:]
            break
        if m.group("tree") not in trees:
            out += old[i:end + 1]
            i = end + 1
            continue
        try:
            new = TABLES[m.group("kind")](m.group("names").split(), src)
        except Missing as e:
            errors.append(f"{path}:{i}: {e}")
            new = old[i:end]
        if new != old[i:end] and not write:
            errors.append(f"{path}:{i}: the {m.group('kind')} table differs from the "
                          f"measurements")
        out += new
        out.append(end_mark)
        i = end + 1
    if write:
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(out))
    return errors


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("docs", nargs="*",
                    help="Markdown files (default: README.md and docs/*.md of --root)")
    ap.add_argument("--root", default=os.path.dirname(HERE),
                    help="the repository (default: this tool's)")
    ap.add_argument("--tree", action="append",
                    help="look at the blocks of this tree (repeatable; default: msp430, host)")
    ap.add_argument("--build", help="the MSP430 build tree (default: ROOT/build/TREE)")
    ap.add_argument("--cycles", help="the cycle report (default: BUILD/cycles.json)")
    ap.add_argument("--host-bin", help="where agv-sim is (default: ROOT/build/host/bin)")
    ap.add_argument("--write", action="store_true", help="rewrite the blocks from the measurements")
    args = ap.parse_args(argv)
    trees = args.tree or ["msp430", "host"]
    mcu = next((t for t in trees if t != "host"), "msp430")
    build = args.build or os.path.join(args.root, "build", mcu)
    src = Sources(args.root, build, args.cycles or os.path.join(build, "cycles.json"),
                  args.host_bin or os.path.join(args.root, "build", "host", "bin"))
    docs = args.docs or ([os.path.join(args.root, "README.md")]
                         + sorted(glob.glob(os.path.join(args.root, "docs", "*.md"))))
    errors = []
    for d in docs:
        try:
            errors += process(d, trees, src, args.write)
        except OSError as e:
            errors.append(f"{d}: {e.strerror}")
    for e in errors:
        print(f"doc_figures: {e}", file=sys.stderr)
    if errors and not args.write:
        cmd = ["tools/doc_figures.py", *sum((["--tree", t] for t in trees), [])]
        if args.cycles:
            cmd += ["--cycles", args.cycles]
        print(f"doc_figures: regenerate with: {' '.join(cmd)} --write {' '.join(args.docs)}",
              file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
