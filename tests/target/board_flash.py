#!/usr/bin/env python3
"""Flash taken by one module library in the main board image, checked against its budget.

Links the main board's objects and libraries again, with the board's section layout but a
test memory map (the whole flash, 3.75 KB of RAM), so that the figure exists even while the
image as a whole is over the 32 KB / 2 KB budget. --gc-sections keeps only what the main
board reaches, exactly as in the board link. From the linker map it sums, per object of the
--library (libcy_drive.a, libcy_optical.a, ...), the input sections that land in flash
(.text, .rodata and the load image of .data), prints the table and fails (exit 1) when their
total exceeds --budget bytes.

  board_flash.py --lld ld.lld-16 --ld-dir hal/msp430/ld --library libcy_drive.a --budget 6656 \
      --map out.map [--elf out.elf] main_msp430.c.obj libcy_main_board.a ... libcy_drive.a ...
"""
import argparse
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from linkmap import flash_by_object  # noqa: E402

# An MSP430F2618-like map with more flash than the part has below 64 KB (the RAM moved down
# to make room): room for any image, so the link does not stop at the budget this script is
# measuring against.
LAYOUT = """MEMORY
{
    RAM (rwx)    : ORIGIN = 0x0200, LENGTH = 0x0F00
    FLASH (rx)   : ORIGIN = 0x1100, LENGTH = 0xEEC0
    VECTORS (r)  : ORIGIN = 0xFFC0, LENGTH = 0x0040
}
CY_STACK_RESERVE = 384;
INCLUDE f2618_sections.ld
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("inputs", nargs="+", help="the main board's objects and libraries")
    ap.add_argument("--lld", required=True)
    ap.add_argument("--ld-dir", required=True, help="hal/msp430/ld (f2618_sections.ld)")
    ap.add_argument("--budget", type=int, required=True, help="bytes of flash for the library")
    ap.add_argument("--library", required=True, help="whose objects are summed (libcy_drive.a)")
    ap.add_argument("--map", help="keep the linker map here")
    ap.add_argument("--elf", help="keep the linked image here (e.g. for tools/stack_bound.py)")
    args = ap.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        ld = os.path.join(tmp, "layout.ld")
        with open(ld, "w") as f:
            f.write(LAYOUT)
        map_path = args.map or os.path.join(tmp, "image.map")
        elf_path = args.elf or os.path.join(tmp, "image.elf")
        run = subprocess.run([args.lld, "-T", ld, "-L", args.ld_dir, "--gc-sections",
                              "-Map=" + map_path, "-o", elf_path]
                             + args.inputs, capture_output=True, text=True)
        if run.returncode != 0:
            sys.stderr.write(run.stderr)
            print("board_flash: the link failed", file=sys.stderr)
            return 1
        with open(map_path) as f:
            sizes = flash_by_object(f.read())

    mine = {o: n for o, n in sizes.items()
            if os.path.basename(o.split("(", 1)[0]) == args.library}
    total = sum(mine.values())
    for obj, n in sorted(mine.items(), key=lambda kv: -kv[1]):
        print(f"{n:>7}  {obj.split('(', 1)[1].rstrip(')') if '(' in obj else obj}")
    print(f"{total:>7}  {args.library} in the image (budget {args.budget}); "
          f"the whole image {sum(sizes.values())}")
    if total > args.budget:
        print(f"board_flash: {args.library} takes {total} bytes of flash, the budget is "
              f"{args.budget}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
