#!/usr/bin/env python3
"""The README's simulator commands, run as written (non-interactively).

  readme_test.py [--root REPO]

1. `make sim IMAGE=irq_test` runs the image as ctest does and passes.
2. The mspdebug block of README.md (after `<!-- readme-mspdebug-block -->`): its `$` line is
   run from the repository root with the `(mspdebug)` lines on its standard input; none may
   fail, the first `run` must stop at cy_target_sync, the second on the first instruction of
   hal_isr_port2 and the `step N` on the first instruction of the portable handler on_test.
"""
import argparse
import os
import re
import shlex
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import msp430sim  # noqa: E402

MARK = "<!-- readme-mspdebug-block -->"
PC_RE = re.compile(r"\(\s*PC:\s*([0-9a-fA-F]+)\)")
FAIL_RE = re.compile(r"(unknown command|can't|invalid|failed|error)", re.I)


def block(readme):
    with open(readme) as f:
        text = f.read()
    if MARK not in text:
        raise SystemExit(f"{readme}: no `{MARK}`")
    body = text.split(MARK, 1)[1].split("```", 2)[1]
    lines = [l for l in body.splitlines()[1:] if l.strip()]  # after the info string
    shell = [l[2:] for l in lines if l.startswith("$ ")]
    cmds = [l[len("(mspdebug) "):] for l in lines if l.startswith("(mspdebug) ")]
    if len(shell) != 1 or len(cmds) + 1 != len(lines):
        raise SystemExit(f"{readme}: the block must be one `$` line and `(mspdebug)` lines")
    return shell[0], cmds


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=os.path.normpath(os.path.join(HERE, "..", "..")))
    a = ap.parse_args()
    problems = []

    run = subprocess.run(["make", "-s", "sim", "IMAGE=irq_test"], cwd=a.root,
                         capture_output=True, text=True, timeout=300)
    if run.returncode != 0 or "PASS irq_test.elf" not in run.stdout:
        problems.append(f"`make sim IMAGE=irq_test` failed:\n{run.stdout}{run.stderr}")

    shell, cmds = block(os.path.join(a.root, "README.md"))
    m = re.search(r"IMAGE=(\S+)", shell)
    elf = os.path.join(a.root, "build", "msp430", "bin", f"{m.group(1)}.elf")
    syms = msp430sim.symbols(elf)
    proc = subprocess.run(shlex.split(shell), cwd=a.root, input="\n".join(cmds + ["exit"]) + "\n",
                          capture_output=True, text=True, timeout=120)
    out = proc.stdout + proc.stderr
    for line in out.splitlines():
        if FAIL_RE.search(line):
            problems.append(f"mspdebug: {line}")
    pcs = [int(x, 16) for x in PC_RE.findall(out)]
    # One register dump per `run`, per `step` and per `regs`, in order.
    want = []
    for c in cmds:
        if c.startswith(("run", "step", "regs")):
            want.append(c)
    if len(pcs) != len(want):
        problems.append(f"{len(pcs)} register dumps for {len(want)} run/step/regs commands")
    else:
        stops = dict(zip(range(len(want)), pcs))
        runs = [i for i, c in enumerate(want) if c == "run"]
        steps = [i for i, c in enumerate(want) if c.startswith("step")]
        checks = [(runs[0], "cy_target_sync"), (runs[1], "hal_isr_port2"),
                  (steps[0], "on_test")]
        for i, sym in checks:
            if stops[i] != syms[sym]:
                name = min(((stops[i] - v, n) for n, v in syms.items() if v <= stops[i]),
                           default=(0, "?"))
                problems.append(f"`{want[i]}` stopped at 0x{stops[i]:04x} ({name[1]}+{name[0]}), "
                                f"the README says {sym} (0x{syms[sym]:04x})")
    for p in problems:
        print(f"FAIL {p}")
    print(f"README simulator commands: {'OK' if not problems else f'{len(problems)} problem(s)'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
