#!/usr/bin/env python3
"""Fail when a tracked C or C++ source does not follow the checked-in .clang-format.
Fix with: tools/check_format.py --fix ."""
import argparse
import subprocess
import sys

EXTS = (".c", ".h", ".cpp", ".hpp")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("root")
    ap.add_argument("--clang-format", default="clang-format-16")
    ap.add_argument("--fix", action="store_true", help="rewrite the files in place")
    args = ap.parse_args()
    files = subprocess.run(["git", "-C", args.root, "ls-files", "--cached", "--others",
                            "--exclude-standard"], check=True, capture_output=True,
                           text=True).stdout.split()
    files = [f"{args.root}/{f}" for f in files if f.endswith(EXTS)]
    if not files:
        print("check_format: no sources found")
        return 1
    if args.fix:
        subprocess.run([args.clang_format, "-i"] + files, check=True)
        return 0
    r = subprocess.run([args.clang_format, "--dry-run", "--Werror"] + files,
                       capture_output=True, text=True)
    if r.returncode:
        print(r.stderr[:4000])
        print("check_format: run tools/check_format.py --fix . to reformat")
        return 1
    print(f"check_format: {len(files)} files follow .clang-format")
    return 0


if __name__ == "__main__":
    sys.exit(main())
