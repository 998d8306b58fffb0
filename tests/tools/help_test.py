#!/usr/bin/env python3
"""ctest tools.help (label unit): every tool under tools/ keeps the command-line habits.

A tool is a file under tools/ that starts with a shebang. Each tool must be executable, a
Python tool's shebang `#!/usr/bin/env python3`, and `TOOL --help` (run as written, from an
empty directory, stdin empty) must exit 0 within 60 s and print a `usage:` line on stdout.
A Python file without a shebang is a library the tools import: it must not be executable and
has no `__main__` entry.

  help_test.py [--root REPO]
"""
import argparse
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SKIP_DIRS = {"__pycache__"}


def tools(root):
    for d, dirs, files in os.walk(os.path.join(root, "tools")):
        dirs[:] = sorted(x for x in dirs if x not in SKIP_DIRS)
        for f in sorted(files):
            yield os.path.join(d, f)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", default=os.path.normpath(os.path.join(HERE, "..", "..")))
    a = ap.parse_args()
    failures, n = [], 0
    with tempfile.TemporaryDirectory() as cwd:
        for path in tools(a.root):
            rel = os.path.relpath(path, a.root)
            with open(path, "rb") as f:
                head = f.read(4096)
            shebang = head.startswith(b"#!")
            executable = os.access(path, os.X_OK)
            if not shebang:
                if rel.endswith(".py"):
                    if executable:
                        failures.append(f"{rel}: executable without a shebang")
                    with open(path, encoding="utf-8") as f:
                        if "__main__" in f.read():
                            failures.append(f"{rel}: a __main__ entry without a shebang: a "
                                            f"tool needs `#!/usr/bin/env python3` and chmod +x")
                continue
            n += 1
            first = head.split(b"\n", 1)[0].decode(errors="replace")
            if rel.endswith(".py") and first != "#!/usr/bin/env python3":
                failures.append(f"{rel}: shebang {first!r}, not #!/usr/bin/env python3")
            if not executable:
                failures.append(f"{rel}: not executable (chmod +x)")
                continue
            try:
                r = subprocess.run([path, "--help"], cwd=cwd, stdin=subprocess.DEVNULL,
                                   capture_output=True, text=True, timeout=60)
            except subprocess.TimeoutExpired:
                failures.append(f"{rel} --help: still running after 60 s")
                continue
            usage = [ln for ln in r.stdout.splitlines() if ln.lower().startswith("usage:")]
            if r.returncode != 0 or not usage:
                failures.append(f"{rel} --help: exit {r.returncode}, "
                                f"{'a' if usage else 'no'} usage line on stdout; stderr: "
                                f"{r.stderr.strip()[-300:]}")
            else:
                print(f"ok  {rel}: {usage[0][:90]}")
            if os.listdir(cwd):
                failures.append(f"{rel} --help: wrote {os.listdir(cwd)} in its directory")
                for f in os.listdir(cwd):
                    os.remove(os.path.join(cwd, f))
    for f in failures:
        print(f"FAIL {f}")
    print(f"{n} tools; {len(failures)} problem(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
