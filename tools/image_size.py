#!/usr/bin/env python3
"""Size table of MSP430 images, checked against the flash and RAM budget.

Reads the section headers with llvm-readelf, sums what lands in flash (.text, .rodata, the
load image of .data, .vectors) and in RAM (.data, .bss, .noinit), prints one table row per
image and fails (exit 1) when an image is over a limit. With --json the figures are also
written for the cycle report (build/msp430/cycles.json "images").
"""
import argparse
import json
import os
import subprocess
import sys

FLASH_SECTIONS = (".text", ".rodata", ".data", ".vectors")
RAM_SECTIONS = (".data", ".bss", ".noinit")


def sections(readelf, elf):
    out = subprocess.run([readelf, "-S", "-W", elf], check=True, capture_output=True,
                         text=True).stdout
    sizes = {}
    for line in out.splitlines():
        line = line.strip()
        if not line.startswith("["):
            continue
        fields = line.split("]", 1)[1].split()
        if len(fields) < 6 or not fields[0].startswith("."):
            continue
        name, size = fields[0], int(fields[4], 16)
        sizes[name] = sizes.get(name, 0) + size
    return sizes


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("elf", nargs="+")
    ap.add_argument("--readelf", default="llvm-readelf-16")
    ap.add_argument("--flash-limit", type=int, required=True, help="bytes")
    ap.add_argument("--ram-limit", type=int, required=True, help="bytes")
    ap.add_argument("--kind", default="board")
    ap.add_argument("--json", help="write the figures of the (single) image here")
    args = ap.parse_args()

    bad = 0
    print(f"{'image':<24}{'text':>8}{'rodata':>8}{'data':>7}{'bss':>7}"
          f"{'flash':>8}{'/limit':>8}{'ram':>7}{'/limit':>7}")
    for elf in args.elf:
        s = sections(args.readelf, elf)
        flash = sum(s.get(n, 0) for n in FLASH_SECTIONS)
        ram = sum(s.get(n, 0) for n in RAM_SECTIONS)
        name = os.path.splitext(os.path.basename(elf))[0]
        print(f"{name:<24}{s.get('.text', 0):>8}{s.get('.rodata', 0):>8}{s.get('.data', 0):>7}"
              f"{s.get('.bss', 0) + s.get('.noinit', 0):>7}{flash:>8}{args.flash_limit:>8}"
              f"{ram:>7}{args.ram_limit:>7}")
        if flash > args.flash_limit:
            print(f"image_size: {name} needs {flash} bytes of flash, the limit is "
                  f"{args.flash_limit}", file=sys.stderr)
            bad = 1
        if ram > args.ram_limit:
            print(f"image_size: {name} needs {ram} bytes of RAM, the limit is "
                  f"{args.ram_limit}", file=sys.stderr)
            bad = 1
        if args.json:
            os.makedirs(os.path.dirname(os.path.abspath(args.json)), exist_ok=True)
            with open(args.json, "w") as f:
                json.dump({"name": name, "kind": args.kind, "text": s.get(".text", 0)
                           + s.get(".rodata", 0), "data": s.get(".data", 0),
                           "bss": s.get(".bss", 0) + s.get(".noinit", 0), "flash": flash,
                           "ram": ram, "flash_limit": args.flash_limit,
                           "ram_limit": args.ram_limit}, f)
    return bad


if __name__ == "__main__":
    sys.exit(main())
