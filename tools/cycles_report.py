#!/usr/bin/env python3
"""Print the MSP430 cycle report (build/msp430/cycles.json, written by the target tests).

  cycles_report.py [CYCLES_JSON]

The entries the vector programs and target tests measured (max, mean, max in microseconds at
the report's clock, the stack of one call where measured), the board images' sizes, the stack
high-water marks, and the kernels measured by the check images (docs/kernels.md): per kernel
and vector program, the cycles of the assembly and of its C twin on the same calls.
"""
import argparse
import json
import sys

KERNEL_PREFIX = "kernel/"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("path", nargs="?", default="build/msp430/cycles.json",
                    help="the cycle report (default: build/msp430/cycles.json)")
    args = ap.parse_args(argv)
    path = args.path
    try:
        with open(path) as f:
            rep = json.load(f)
    except OSError as e:
        print(f"cycles_report: {e}", file=sys.stderr)
        return 1
    hz = rep.get("clock_hz", 16000000)
    entries = rep.get("entries", [])
    print(f"MSP430 cycle report ({path}, {hz / 1e6:.0f} MHz)")
    print(f"  {'entry':<22}{'max':>9}{'mean':>9}{'max us':>9}{'stack B':>9}")
    for e in entries:
        if e["name"].startswith(KERNEL_PREFIX):
            continue
        st = str(e["stack_bytes"]) if "stack_bytes" in e else "-"
        print(f"  {e['name']:<22}{e['cycles_max']:>9}{e['cycles_mean']:>9}"
              f"{e['cycles_max'] * 1e6 / hz:>9.1f}{st:>9}")
    print(f"  {'image':<22}{'text':>9}{'data':>9}{'bss':>9}")
    for i in rep.get("images", []):
        print(f"  {i['name']:<22}{i['text']:>9}{i['data']:>9}{i['bss']:>9}")
    if rep.get("stack"):
        print(f"  {'stack (high water)':<22}{'used':>9}{'room':>9}")
        for st in rep["stack"]:
            print(f"  {st['image']:<22}{st['used']:>9}{st['room']:>9}")
    kernels = {}
    for e in entries:
        if not e["name"].startswith(KERNEL_PREFIX):
            continue
        _, program, kernel, side = e["name"].split("/")
        kernels.setdefault((kernel, program), {})[side] = e
    if kernels:
        print("  kernels (check images: the assembly and its C twin on the same calls)")
        print(f"  {'kernel':<22}{'program':<22}{'asm max':>9}{'mean':>7}{'C max':>9}"
              f"{'mean':>7}{'calls':>8}")
        for (kernel, program), sides in sorted(kernels.items()):
            a, c = sides.get("asm"), sides.get("c")
            if not a or not c:
                continue
            print(f"  {kernel:<22}{program:<22}{a['cycles_max']:>9}{a['cycles_mean']:>7}"
                  f"{c['cycles_max']:>9}{c['cycles_mean']:>7}{a['samples']:>8}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
