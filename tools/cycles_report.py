#!/usr/bin/env python3
"""Print the MSP430 cycle report (build/msp430/cycles.json, written by the target tests).

  cycles_report.py [CYCLES_JSON]

Per entry: the simulator's measured maximum and mean (mspdebug 0.22, the floors' figures), the
maximum in microseconds at the report's clock, the stack of one call where measured, and where
tools/cycle_bound.py counted it, the static worst case from SLAU144's instruction timings and
the same path priced with the simulator's rules (docs/cycles.md). Then the board images' sizes,
the stack high-water marks, and the kernels measured by the check images (docs/kernels.md): per
kernel and vector program, the cycles of the assembly and of its C twin on the same calls.
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
    path = ap.parse_args(argv).path
    try:
        with open(path) as f:
            rep = json.load(f)
    except (OSError, ValueError) as e:
        print(f"cycles_report: {path}: {e}", file=sys.stderr)
        return 1
    hz = rep.get("clock_hz", 16000000)
    entries = rep.get("entries", [])
    print(f"MSP430 cycle report ({path}, {hz / 1e6:.0f} MHz)")
    print(f"  {'entry':<32}{'max':>8}{'mean':>8}{'max us':>8}{'stack B':>8}"
          f"{'static':>8}{'st.sim':>8}")

    def num(e, k):
        return str(e[k]) if k in e else "-"
    for e in entries:
        if e["name"].startswith(KERNEL_PREFIX):
            continue
        us = f"{e['cycles_max'] * 1e6 / hz:.1f}" if "cycles_max" in e else "-"
        print(f"  {e['name']:<32}{num(e, 'cycles_max'):>8}{num(e, 'cycles_mean'):>8}{us:>8}"
              f"{num(e, 'stack_bytes'):>8}{num(e, 'static_cycles_max'):>8}"
              f"{num(e, 'static_cycles_max_sim'):>8}")
    print(f"  {'image':<32}{'text':>8}{'data':>8}{'bss':>8}")
    for i in rep.get("images", []):
        print(f"  {i['name']:<32}{i['text']:>8}{i['data']:>8}{i['bss']:>8}")
    if rep.get("stack"):
        print(f"  {'stack (high water)':<32}{'used':>8}{'room':>8}")
        for st in rep["stack"]:
            print(f"  {st['image']:<32}{st['used']:>8}{st['room']:>8}")
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
