#!/usr/bin/env python3
"""ctest hygiene.leftovers (label hygiene), the last test of the MSP430 tree: no test left a
process behind. make test runs the host-asan, fuzz and MSP430 trees one after the other, so
by now every test of every tree has finished; a process still alive whose working directory
is in the build trees (ctest starts each test there) or whose command line names them is a
leftover, unless it is one of this test's ancestors (ctest, make, the shell that started them).
Lists each with its pid, working directory and command line, and fails.

  leftovers_test.py --build-root ROOT/build
"""
import argparse
import os
import sys


def ancestors():
    pids, pid = set(), os.getpid()
    while pid > 1:
        pids.add(pid)
        try:
            with open(f"/proc/{pid}/stat") as f:
                pid = int(f.read().rsplit(")", 1)[1].split()[1])
        except OSError:
            break
    return pids


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build-root", required=True, help="the directory of the build trees")
    a = ap.parse_args()
    root = os.path.realpath(a.build_root) + os.sep
    mine = ancestors()
    left = []
    for d in os.listdir("/proc"):
        if not d.isdigit() or int(d) in mine:
            continue
        try:
            with open(f"/proc/{d}/stat") as f:
                state = f.read().rsplit(")", 1)[1].split()[0]
            with open(f"/proc/{d}/cmdline", "rb") as f:
                cmd = f.read().replace(b"\0", b" ").decode(errors="replace").strip()
            cwd = os.path.realpath(os.readlink(f"/proc/{d}/cwd")) + os.sep
        except OSError:
            continue  # gone, or not ours to look at
        if state == "Z" or not cmd:
            continue
        if cwd.startswith(root) or root in cmd + " ":
            left.append((int(d), cwd, cmd))
    for pid, cwd, cmd in left:
        print(f"FAIL left behind: pid {pid}, in {cwd}: {cmd}")
    print(f"{len(left)} process(es) left behind by the tests under {root}")
    return 1 if left else 0


if __name__ == "__main__":
    sys.exit(main())
