#!/usr/bin/env python3
"""ctest (label sim): agv-sim's command-line habits, on the built binary.

-h and --help print the usage on stdout and exit 0, and every file the usage names exists in
the repository (nothing outside it is named); --version prints the CMake project's version;
--log-dir creates its missing parents; a --log-dir that cannot be created is bad input
(exit 2) naming the path.

  cli_test.py AGV_SIM VERSION REPO_ROOT SCENARIO
"""
import os
import re
import subprocess
import sys
import tempfile


def main():
    agv, version, root, scenario = sys.argv[1:5]
    failures = []

    def check(ok, what):
        print(f"{'ok ' if ok else 'BAD'} {what}")
        if not ok:
            failures.append(what)

    for h in ("-h", "--help"):
        r = subprocess.run([agv, h], capture_output=True, text=True)
        check(r.returncode == 0 and r.stdout.startswith("usage: agv-sim"), f"{h}: usage, exit 0")
        named = set(re.findall(r"\b(?:docs|sim)/[\w./-]*\w", r.stdout))
        missing = [p for p in named if not os.path.exists(os.path.join(root, p))]
        check(named and not missing, f"{h}: names files of the repository {sorted(named)}, "
              f"missing {missing}")
        check("../" not in r.stdout and "CONTRACT" not in r.stdout,
              f"{h}: points nowhere outside the repository")
    r = subprocess.run([agv, "--version"], capture_output=True, text=True)
    check(r.returncode == 0 and r.stdout == f"agv-sim {version}\n",
          f"--version: {r.stdout.strip()!r} (project version {version})")
    with tempfile.TemporaryDirectory() as tmp:
        deep = os.path.join(tmp, "a", "b", "c")
        r = subprocess.run([agv, "--scenario", scenario, "--quiet", "--log-dir", deep, "--report",
                            os.path.join(tmp, "r.json")], capture_output=True, text=True)
        check(r.returncode == 0 and os.path.isfile(os.path.join(deep, "truth.csv")),
              f"--log-dir creates its parents (exit {r.returncode} {r.stderr.strip()})")
        blocker = os.path.join(tmp, "file")
        open(blocker, "w").close()
        r = subprocess.run([agv, "--scenario", scenario, "--quiet", "--log-dir",
                            os.path.join(blocker, "logs")], capture_output=True, text=True)
        check(r.returncode == 2 and blocker in r.stderr,
              f"--log-dir under a file: exit {r.returncode}: {r.stderr.strip()}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
