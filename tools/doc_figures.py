#!/usr/bin/env python3
"""Generate, or check, the cycle tables quoted in the docs from the MSP430 cycle report.

  doc_figures.py --cycles build/msp430/cycles.json [--tree msp430] [--write] doc.md...

A table in a Markdown file is generated from the report when it sits between two markers:

    <!-- cycles msp430: optical_fix isr_index_pulse kernel/optical_vectors/optical_scan -->
    | entry | max | mean | max µs |
    ...
    <!-- cycles end -->

The word after "cycles" names the build tree whose report the table comes from (msp430: the
default tree; msp430-c: the tree with the kernels' C twins, docs/kernels.md); the names after
the colon are entries of that report (build/<tree>/cycles.json). A name "kernel/P/K" stands
for both sides of kernel K measured in the check image of vector program P: one row with the
assembly's and the C twin's max and mean. Only the blocks of --tree are looked at.

Without --write: exit 1 when a block differs from what the report gives (the line to run
to regenerate it is printed), or names an entry the report lacks. With --write: rewrite the
blocks in place. Run it after the target tests (ctest writes the report).
"""
import argparse
import json
import re
import sys

BEGIN_RE = re.compile(r"^<!-- cycles (?P<tree>[\w-]+): (?P<names>[^>]*?) -->\s*$")
END = "<!-- cycles end -->"


def fmt(n):
    return f"{n:,}"


def table(names, entries, hz):
    """The Markdown lines of one block, or raises KeyError naming a missing entry."""
    plain = [n for n in names if not n.startswith("kernel/")]
    kernels = [n for n in names if n.startswith("kernel/")]
    lines = []
    if plain:
        lines += ["| entry | max | mean | max µs |", "| --- | ---: | ---: | ---: |"]
        for n in plain:
            if n not in entries:
                raise KeyError(n)
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
                raise KeyError(n + "/asm" if a is None else n + "/c")
            lines.append(f"| `{kernel}` | {program} | {fmt(a['samples'])} | "
                         f"{fmt(a['cycles_max'])} | {fmt(a['cycles_mean'])} | "
                         f"{fmt(c['cycles_max'])} | {fmt(c['cycles_mean'])} |")
    return lines


def process(path, tree, entries, hz, write):
    """Errors of one document (and its new text when write)."""
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
        try:
            end = old.index(END, i)
        except ValueError:
            errors.append(f"{path}:{i}: `{line.strip()}` without `{END}`")
            out += old[i:]
            break
        if m.group("tree") != tree:
            out += old[i:end + 1]
            i = end + 1
            continue
        try:
            new = table(m.group("names").split(), entries, hz)
        except KeyError as e:
            errors.append(f"{path}:{i}: the report has no entry {e.args[0]}")
            new = old[i:end]
        if new != old[i:end] and not write:
            errors.append(f"{path}:{i}: the table differs from the cycle report")
        out += new
        out.append(END)
        i = end + 1
    if write:
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(out))
    return errors


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("docs", nargs="+", help="Markdown files")
    ap.add_argument("--cycles", default="build/msp430/cycles.json",
                    help="the cycle report (default: build/msp430/cycles.json)")
    ap.add_argument("--tree", default="msp430",
                    help="the blocks to look at: those of this build tree (default: msp430)")
    ap.add_argument("--write", action="store_true", help="rewrite the blocks from the report")
    args = ap.parse_args(argv)
    try:
        with open(args.cycles) as f:
            rep = json.load(f)
    except (OSError, ValueError) as e:
        print(f"doc_figures: {args.cycles}: {e} (run the target tests first)", file=sys.stderr)
        return 1
    entries = {e["name"]: e for e in rep.get("entries", [])}
    hz = rep.get("clock_hz", 16000000)
    errors = []
    for d in args.docs:
        errors += process(d, args.tree, entries, hz, args.write)
    for e in errors:
        print(f"doc_figures: {e}", file=sys.stderr)
    if errors and not args.write:
        print(f"doc_figures: regenerate with: tools/doc_figures.py --cycles {args.cycles} "
              f"--tree {args.tree} --write {' '.join(args.docs)}", file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
