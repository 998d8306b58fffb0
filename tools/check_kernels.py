#!/usr/bin/env python3
"""Check a library's kernels: the assembly, the C twins and the list agree (docs/kernels.md).

  check_kernels.py --library libM.a --twins twin.obj... --asm M.S... --c M_k.c...
                   --kernels name... [--doc docs/kernels.md] [--nm llvm-nm-16]

- the objects assembled from the .S files (members of the library named after them) define,
  as global symbols, exactly the kernels listed;
- the C twins' objects (compiled with every kernel renamed NAME_c, cy_kernels() in
  cmake/cyclopion.cmake) define exactly NAME_c for each kernel and nothing else: a twin file
  holds only kernels;
- the document names every kernel, every .S file and every twin file.

Exit 1 with one line per disagreement.
"""
import argparse
import os
import re
import subprocess
import sys


def defined_globals(nm, paths):
    """{member or file: set of global defined symbols} from llvm-nm."""
    out = subprocess.run([nm, "--defined-only", "--extern-only", *paths], check=True,
                         capture_output=True, text=True).stdout
    table = {}
    current = paths[0] if len(paths) == 1 else None
    for line in out.splitlines():
        line = line.rstrip()
        if not line:
            continue
        if line.endswith(":") and len(line.split()) == 1:
            current = line[:-1]
            table.setdefault(current, set())
            continue
        parts = line.split()
        if len(parts) >= 2:
            table.setdefault(current, set()).add(parts[-1])
    return table


def member_of(asm_path, table):
    """The archive member assembled from asm_path (CMake names it file.S.obj or file.S.o)."""
    base = os.path.basename(asm_path)
    for key in table:
        name = key.rsplit("(", 1)[-1].rstrip(")") if key else ""
        if name in (base + ".obj", base + ".o"):
            return key
    return None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--nm", default="llvm-nm-16")
    ap.add_argument("--library", required=True, help="the module's static library (ASM build)")
    ap.add_argument("--twins", nargs="+", required=True, help="the C twins' object files")
    ap.add_argument("--asm", nargs="+", required=True, help="the .S files")
    ap.add_argument("--c", nargs="+", required=True, help="the C twin files")
    ap.add_argument("--kernels", nargs="+", required=True, help="the kernels' names")
    ap.add_argument("--doc", help="the document that must name every kernel and file")
    args = ap.parse_args(argv)

    errors = []
    kernels = set(args.kernels)
    lib = defined_globals(args.nm, [args.library])
    asm_syms = set()
    for a in args.asm:
        key = member_of(a, lib)
        if key is None:
            errors.append(f"{a}: no member of {args.library} assembled from it")
            continue
        asm_syms |= lib[key]
    for k in sorted(kernels - asm_syms):
        errors.append(f"{k}: listed as a kernel, not defined by the assembly")
    for k in sorted(asm_syms - kernels):
        errors.append(f"{k}: a global symbol of the assembly that is not a listed kernel")
    twin_syms = set()
    for syms in defined_globals(args.nm, args.twins).values():
        twin_syms |= syms
    want = {k + "_c" for k in kernels}
    for k in sorted(want - twin_syms):
        errors.append(f"{k}: the C twin of a listed kernel is missing")
    for k in sorted(twin_syms - want):
        errors.append(f"{k}: defined by a C twin file but not a kernel (twin files hold only "
                      f"kernels)")
    if args.doc:
        with open(args.doc) as f:
            doc = f.read()
        for name in sorted(kernels) + [os.path.basename(p) for p in args.asm + args.c]:
            if not re.search(r"(?<![\w.])" + re.escape(name) + r"(?![\w])", doc):
                errors.append(f"{args.doc} does not name {name}")
    for e in errors:
        print(f"check_kernels: {e}")
    if not errors:
        print(f"check_kernels: {len(kernels)} kernels, assembly and C twins agree"
              + (f", all named in {args.doc}" if args.doc else ""))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
