#!/usr/bin/env python3
"""Print the MSP430 cycle report (build/msp430/cycles.json, written by the target tests)."""
import json
import sys


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "build/msp430/cycles.json"
    try:
        with open(path) as f:
            rep = json.load(f)
    except OSError as e:
        print(f"cycles_report: {e}", file=sys.stderr)
        return 1
    hz = rep.get("clock_hz", 16000000)
    print(f"MSP430 cycle report ({path}, {hz / 1e6:.0f} MHz)")
    print(f"  {'entry':<22}{'max':>9}{'mean':>9}{'max us':>9}{'stack B':>9}")
    for e in rep.get("entries", []):
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
    return 0


if __name__ == "__main__":
    sys.exit(main())
