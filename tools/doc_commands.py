#!/usr/bin/env python3
"""Run the commands written in README.md and docs/*.md, as written, and say where one fails.

  tools/doc_commands.py [--root DIR] [--check-marks] [--list] [--only FILE:LINE] [FILE.md ...]

Every fenced block says what it holds in its info string (```sh, ```console, ```text, ```c,
```cmake, ```json, ...). Blocks of commands (`sh`: lines a reader pastes into a shell;
`console`: a session, `$ command` lines followed by what the reader types at the program's
prompt, `(gdb) break main`, or by the output to expect) carry a mark on the line before the
fence:

    <!-- run -->                      run it, as written
    <!-- run: OPTION; OPTION -->      run it with options:
        timeout N                       seconds for the block (default 300)
        exit N                          the block shows a failure: its first failing line
                                        must exit with N (and none may fail otherwise)
        with 'OLD' as 'NEW'             run a variant: OLD (which must be in the block) replaced
                                        by NEW, e.g. a bounded run or the simulator for a probe
    <!-- norun: REASON -->            not run here, and why (a display, a probe, root on the host)

How a block runs: from the repository root (DIR), stdin empty, MAKEFLAGS cleared, in its own
process group. `sh` blocks are one bash script (`set -e -o pipefail`): the first failing line
fails the block. `console` blocks run each `$` line with its `(prompt)` lines on its stdin;
other lines after a `$` line are its expected stdout, line for line (`...` matches any lines),
and a debugger's complaint (unknown command, no symbol, ...) fails it. `ctest` in a block only
lists the tests it selects (`ctest ... -N`), and fails when that selects none: the docs test
runs inside ctest, after every other test. A block fails when it leaves a process behind, or
changes a file git tracks.

Exit 1 when a block fails or a mark is missing or wrong, naming the file, the line and the
command; --check-marks checks the marks without running anything.
"""
import argparse
import glob
import hashlib
import os
import re
import shlex
import signal
import subprocess
import sys
import tempfile
import time

COMMAND_KINDS = ("sh", "console")
FENCE_RE = re.compile(r"^(?P<indent> {0,3})(?P<fence>`{3,}|~{3,})\s*(?P<info>.*?)\s*$")
MARK_RE = re.compile(r"^<!--\s*(?P<kind>run|norun)\b\s*(?::\s*(?P<opts>.*?))?\s*-->\s*$")
COMMENT_RE = re.compile(r"^<!--.*-->\s*$")
PROMPT_RE = re.compile(r"^\((?P<prog>[\w-]+)\) ?(?P<input>.*)$")
WITH_RE = re.compile(r"^with\s+'(?P<old>[^']*)'\s+as\s+'(?P<new>[^']*)'$")
# The first word of a line that is a command, in a block not marked as commands.
LOOKS_LIKE_COMMAND = re.compile(
    r"^(\$ |make |tools/|build/|ctest |cmake --|python3 |sudo |git |echo |mkdir |gdb |mspdebug )")
# What a debugger prints when a line of the session did not work.
COMPLAINT_RE = re.compile(r"(unknown command|illegal character|No symbol|Undefined command|"
                          r"not defined in|Cannot access memory|syntax error|No such file)", re.I)
DEFAULT_TIMEOUT = 300
PRELUDE = r"""
set -eE -o pipefail
trap 'echo "doc_commands: line $LINENO failed (exit $?)" >&2' ERR
ctest() {
    local out
    out=$(command ctest "$@" -N) || { echo "$out"; return 1; }
    echo "$out"
    if ! grep -Eq 'Total Tests: [1-9]' <<<"$out"; then
        echo "doc_commands: ctest $* selects no test" >&2
        return 1
    fi
}
"""


class Block:
    def __init__(self, path, line, info, body, mark, mark_line):
        self.path, self.line, self.info, self.body = path, line, info, body
        self.kind = info.split()[0] if info else ""
        self.mark, self.mark_line = mark, mark_line
        self.errors = []
        self.timeout = DEFAULT_TIMEOUT
        self.subs = []
        self.reason = None
        self.exit = 0

    def where(self, offset=0):
        return f"{self.path}:{self.line + offset}"


def parse(path, rel):
    """The fenced blocks of a Markdown file (a fence inside a list may be indented)."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    blocks, i = [], 0
    while i < len(lines):
        m = FENCE_RE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, start = m.group("fence"), i
        j = i + 1
        while j < len(lines) and not lines[j].strip().startswith(fence):
            j += 1
        indent = len(m.group("indent"))
        body = [ln[indent:] if ln[:indent].strip() == "" else ln for ln in lines[i + 1:j]]
        mark, mark_line, k = None, None, start - 1
        while k >= 0 and COMMENT_RE.match(lines[k].strip()):
            mm = MARK_RE.match(lines[k].strip())
            if mm:
                mark, mark_line = mm, k + 1
                break
            k -= 1
        blocks.append(Block(rel, start + 1, m.group("info"), body, mark, mark_line))
        i = j + 1
    return blocks


def check_marks(b):
    """Fill b.errors, b.timeout, b.subs, b.reason from the block and its mark."""
    if not b.kind:
        b.errors.append(f"{b.where()}: a fence without an info string: say what it holds "
                        f"(```sh, ```console, ```text, ```c, ...)")
        return
    if b.kind not in COMMAND_KINDS:
        if b.mark:
            b.errors.append(f"{b.where()}: a run mark on a ```{b.kind} block (commands are "
                            f"```sh or ```console)")
        first = next((ln for ln in b.body if ln.strip()), "")
        if LOOKS_LIKE_COMMAND.match(first):
            b.errors.append(f"{b.where()}: ```{b.kind} block that starts like a command "
                            f"({first.strip()[:40]!r}): make it ```sh or ```console with a mark")
        return
    if not b.mark:
        b.errors.append(f"{b.where()}: ```{b.kind} block without a mark on the line before: "
                        f"<!-- run -->, <!-- run: ... --> or <!-- norun: REASON -->")
        return
    opts = b.mark.group("opts") or ""
    if b.mark.group("kind") == "norun":
        b.reason = opts.strip()
        if not b.reason:
            b.errors.append(f"{b.path}:{b.mark_line}: <!-- norun --> without a reason")
        return
    text = "\n".join(b.body)
    for opt in (o.strip() for o in opts.split(";") if o.strip()):
        m = WITH_RE.match(opt)
        if opt.startswith("timeout") and opt[7:].strip().isdigit():
            b.timeout = int(opt[7:].strip())
        elif opt.startswith("exit") and opt[4:].strip().isdigit() and int(opt[4:]) > 0:
            b.exit = int(opt[4:].strip())
        elif m:
            if m.group("old") not in text:
                b.errors.append(f"{b.path}:{b.mark_line}: with '{m.group('old')}': not in the "
                                f"block")
            b.subs.append((m.group("old"), m.group("new")))
        else:
            b.errors.append(f"{b.path}:{b.mark_line}: unknown run option {opt!r} (timeout N, "
                            f"exit N, with 'OLD' as 'NEW')")


def variant(b, text):
    for old, new in b.subs:
        text = text.replace(old, new)
    return text


# ------------------------------------------------------------------ running

def block_env():
    env = dict(os.environ)
    for k in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "MAKEOVERRIDES"):
        env.pop(k, None)
    env["CY_DOC_COMMANDS"] = "1"
    return env


def session_processes(sid):
    """Live processes of session @p sid: [(pid, command line)]."""
    found = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open(f"/proc/{d}/stat") as f:
                stat = f.read().rsplit(")", 1)[1].split()
            with open(f"/proc/{d}/cmdline", "rb") as f:
                cmd = f.read().replace(b"\0", b" ").decode(errors="replace").strip()
        except OSError:
            continue
        if stat[0] != "Z" and int(stat[3]) == sid:
            found.append((int(d), cmd))
    return found


def run_in_session(argv, root, stdin_text, timeout):
    """Run @p argv in a new session; returns (exit status or None on timeout, output,
    [processes left behind, killed])."""
    with tempfile.TemporaryFile() as out:
        p = subprocess.Popen(argv, cwd=root, env=block_env(), stdout=out,
                             stderr=subprocess.STDOUT, stdin=subprocess.PIPE,
                             start_new_session=True)
        try:
            p.communicate(input=(stdin_text or "").encode(), timeout=timeout)
            rc = p.returncode
        except subprocess.TimeoutExpired:
            rc = None
        left = [] if rc is None else session_processes(p.pid)
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        for pid, _ in session_processes(p.pid):
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        p.wait()
        out.seek(0)
        return rc, out.read().decode(errors="replace"), left


def tail(text, n=25):
    lines = text.rstrip("\n").split("\n")
    return "\n".join(("    " + ln) for ln in lines[-n:])


def run_sh(b, root):
    script = variant(b, "\n".join(b.body))
    with tempfile.NamedTemporaryFile("w", suffix=".sh", delete=False) as f:
        f.write(PRELUDE)
        prelude = f.name
    try:
        argv = ["bash", "-c", f"source {shlex.quote(prelude)}\n{script}"]
        rc, out, left = run_in_session(argv, root, "", b.timeout)
    finally:
        os.unlink(prelude)
    problems = []
    if rc is None:
        problems.append(f"{b.where()}: timed out after {b.timeout} s")
    elif rc != b.exit:
        m = re.findall(r"doc_commands: line (\d+) failed", out)
        # bash counts the source line as 1: the block's lines start at 2
        k = int(m[-1]) - 1 if m else 0
        cmd = script.split("\n")[k - 1] if 0 < k <= len(b.body) else script
        expected = f" (the mark says exit {b.exit})" if b.exit else ""
        problems.append(f"{b.where(k)}: exit {rc}{expected}: {cmd.strip()}")
    for pid, cmd in left:
        problems.append(f"{b.where()}: left a process behind (killed): {pid} {cmd}")
    return problems, out


def transcript(b):
    """[(doc line offset, command, stdin lines, expected output lines or None)]."""
    steps = []
    for k, ln in enumerate(b.body, 1):
        if ln.startswith("$ "):
            steps.append([k, ln[2:], [], []])
        elif not steps:
            continue
        else:
            m = PROMPT_RE.match(ln)
            if m:
                steps[-1][2].append(m.group("input"))
            elif ln.strip():
                steps[-1][3].append(ln.rstrip())
    return steps


def matches(expected, got):
    """Expected lines against output lines; "..." matches any run of lines."""
    if not expected:
        return not got
    if expected[0] == "...":
        return any(matches(expected[1:], got[i:]) for i in range(len(got) + 1))
    return bool(got) and got[0].rstrip() == expected[0] and matches(expected[1:], got[1:])


def run_console(b, root):
    problems, outs = [], []
    for k, cmd, inputs, expected in transcript(b):
        cmd = variant(b, cmd)
        stdin = "\n".join(variant(b, i) for i in inputs) + "\n" if inputs else ""
        rc, out, left = run_in_session(["bash", "-c", cmd], root, stdin, b.timeout)
        outs.append(f"$ {cmd}\n{out}")
        if rc is None:
            problems.append(f"{b.where(k)}: timed out after {b.timeout} s: {cmd}")
            continue
        if rc != 0:
            problems.append(f"{b.where(k)}: exit {rc}: {cmd}")
        for ln in out.split("\n"):
            if inputs and COMPLAINT_RE.search(ln):
                problems.append(f"{b.where(k)}: {cmd.split()[0]} complained: {ln.strip()}")
        if expected and not matches(expected, [ln for ln in out.split("\n") if ln.strip()]):
            problems.append(f"{b.where(k)}: the output of `{cmd}` differs from the block's:\n"
                            + tail("\n".join(expected), 10) + "\n  got:\n" + tail(out, 10))
        for pid, c in left:
            problems.append(f"{b.where(k)}: left a process behind (killed): {pid} {c}")
    return problems, "\n".join(outs)


def tracked_state(root):
    """{path: digest} of the files git tracks that differ from HEAD (None without git)."""
    try:
        r = subprocess.run(["git", "status", "--porcelain=v1", "-z", "--untracked-files=no"],
                           cwd=root, capture_output=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return None
    if r.returncode != 0:
        return None
    state = {}
    for entry in r.stdout.decode(errors="replace").split("\0"):
        if len(entry) > 3:
            path = entry[3:]
            try:
                with open(os.path.join(root, path), "rb") as f:
                    state[path] = hashlib.sha1(f.read()).hexdigest()
            except OSError:
                state[path] = "gone"
    return state


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("files", nargs="*",
                    help="Markdown files (default: README.md and docs/*.md of --root)")
    ap.add_argument("--root", default=os.path.dirname(here),
                    help="the repository: where the blocks run (default: this tool's)")
    ap.add_argument("--check-marks", action="store_true",
                    help="only check that every block is marked, run nothing")
    ap.add_argument("--list", action="store_true", help="list the blocks and their marks")
    ap.add_argument("--only", action="append", default=[], metavar="FILE:LINE",
                    help="run only the block whose fence is at FILE:LINE (repeatable)")
    a = ap.parse_args(argv)
    root = os.path.abspath(a.root)
    files = a.files or ([os.path.join(root, "README.md")]
                        + sorted(glob.glob(os.path.join(root, "docs", "*.md"))))
    blocks = []
    for path in files:
        if not os.path.isfile(path):
            print(f"doc_commands: {path}: no such file", file=sys.stderr)
            return 2
        rel = os.path.relpath(os.path.abspath(path), root)
        blocks += parse(path, rel)
    errors = []
    for b in blocks:
        check_marks(b)
        errors += b.errors
    commands = [b for b in blocks if b.kind in COMMAND_KINDS and not b.errors]
    if a.only:
        commands = [b for b in commands if b.where() in a.only]
        missing = set(a.only) - {b.where() for b in commands}
        if missing:
            print(f"doc_commands: no command block at {', '.join(sorted(missing))}",
                  file=sys.stderr)
            return 2
    if a.list:
        for b in commands:
            what = f"norun: {b.reason}" if b.reason is not None else (
                "run" + "".join(f"; with {o!r} as {n!r}" for o, n in b.subs))
            print(f"{b.where()}  {b.kind:<7} {what}")
    if a.check_marks or a.list:
        for e in errors:
            print(f"doc_commands: {e}", file=sys.stderr)
        print(f"doc_commands: {len(blocks)} blocks, {len(commands)} of commands, "
              f"{len(errors)} mark problem(s)")
        return 1 if errors else 0

    before = tracked_state(root)
    ran = skipped = 0
    failed = []
    for b in commands:
        if b.reason is not None:
            skipped += 1
            continue
        t0 = time.monotonic()
        problems, out = (run_sh if b.kind == "sh" else run_console)(b, root)
        ran += 1
        after = tracked_state(root)
        if before is not None and after is not None and after != before:
            changed = sorted(p for p in set(before) | set(after) if before.get(p) != after.get(p))
            problems.append(f"{b.where()}: changed files git tracks: {', '.join(changed)}")
            before = after
        status = "FAIL" if problems else "ok  "
        print(f"{status} {b.where()} ({b.kind}, {time.monotonic() - t0:.1f} s)", flush=True)
        if problems:
            failed.append(b)
            for p in problems:
                print(f"  {p}")
            print(tail(out))
    for e in errors:
        print(f"doc_commands: {e}", file=sys.stderr)
    print(f"doc_commands: {ran} blocks run, {skipped} not run (marked norun), {len(failed)} "
          f"failed; {len(errors)} mark problem(s)")
    return 1 if failed or errors else 0


if __name__ == "__main__":
    sys.exit(main())
