#!/usr/bin/env python3
"""ctest tools.doc_commands (label unit): the docs test's runner (tools/doc_commands.py) finds
what it promises to find, on a hand-written document: the failing line of a script with its
file and line, a process left behind (and kills it), a session's output that differs from the
block, a debugger's complaint, a `ctest` that selects no test, a block that changes a file
git tracks, and every kind of bad mark; and it runs a variant (`with 'OLD' as 'NEW'`) and a
block that shows a failure (`exit N`)."""
import os
import subprocess
import sys
import tempfile
import time
import unittest

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                    "doc_commands.py")

DOC = """# sample

<!-- run -->
```sh
echo one
false
echo never
```

<!-- run -->
```sh
sleep 300 &
echo started
```

<!-- run -->
```console
$ printf 'hello\\nworld\\n'
hello
there
$ printf 'a\\nb\\nc\\n'
a
...
c
```

<!-- run -->
```console
$ gdb -q -nx
(gdb) print nosuchsymbol
```

<!-- run: with 'exit 3' as 'exit 0' -->
```sh
exit 3
```

<!-- run -->
```sh
ctest --test-dir . -R nosuchtest
```

<!-- run -->
```sh
echo changed >> tracked.txt
```

<!-- run: exit 4 -->
```sh
echo shows a failure
exit 4
```

<!-- run: exit 4 -->
```sh
true
```
"""

BAD_MARKS = """
```
make all
```

<!-- run: with 'nothere' as 'x' -->
```sh
echo here
```

<!-- norun -->
```sh
echo x
```

<!-- run -->
```text
x
```

<!-- run: sometimes -->
```sh
echo x
```

```text
build/host/bin/agv-sim --help
```
"""


class DocCommands(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name
        self.doc = os.path.join(self.root, "doc.md")
        with open(os.path.join(self.root, "tracked.txt"), "w") as f:
            f.write("v1\n")
        for cmd in (["git", "init", "-q"], ["git", "add", "tracked.txt"],
                    ["git", "-c", "user.email=t@t", "-c", "user.name=t", "commit", "-qm", "t"]):
            subprocess.run(cmd, cwd=self.root, check=True)

    def tearDown(self):
        self.tmp.cleanup()

    def run_tool(self, text, *extra):
        with open(self.doc, "w") as f:
            f.write(text)
        return subprocess.run([sys.executable, TOOL, "--root", self.root, *extra, self.doc],
                              capture_output=True, text=True, timeout=300)

    def test_failures_are_found_and_located(self):
        r = self.run_tool(DOC)
        out = r.stdout
        self.assertEqual(r.returncode, 1, out)
        self.assertIn("doc.md:6: exit 1: false", out)            # the failing line
        self.assertNotIn("never", out.split("doc.md:6")[1].split("FAIL")[0])
        self.assertIn("left a process behind (killed)", out)
        self.assertIn("sleep 300", out)
        self.assertIn("differs from the block's", out)
        self.assertNotIn("doc.md:22", out)                      # "..." matched b
        self.assertIn("gdb complained", out)
        self.assertIn("ok   doc.md:34", out)                     # the variant ran
        self.assertIn("selects no test", out)
        self.assertIn("changed files git tracks: tracked.txt", out)
        self.assertIn("ok   doc.md:49", out)                     # exit 4 as the mark says
        self.assertIn("doc.md:55: exit 0 (the mark says exit 4)", out)
        self.assertIn("9 blocks run, 0 not run (marked norun), 7 failed", out)
        time.sleep(0.2)
        left = subprocess.run(["pgrep", "-f", "^sleep 300$"], capture_output=True, text=True)
        mine = [p for p in left.stdout.split()
                if os.path.exists(f"/proc/{p}/cwd") and os.readlink(f"/proc/{p}/cwd") == self.root]
        self.assertEqual(mine, [], "the runner kills what a block leaves behind")

    def test_marks(self):
        r = self.run_tool(BAD_MARKS, "--check-marks")
        self.assertEqual(r.returncode, 1)
        for what in ("doc.md:2: a fence without an info string",
                     "with 'nothere': not in the block",
                     "<!-- norun --> without a reason",
                     "a run mark on a ```text block",
                     "unknown run option 'sometimes'",
                     "```text block that starts like a command"):
            self.assertIn(what, r.stderr)
        self.assertIn("6 mark problem(s)", r.stdout)

    def test_only_and_list(self):
        r = self.run_tool(DOC, "--only", "doc.md:34")
        self.assertEqual(r.returncode, 0, r.stdout)
        self.assertIn("1 blocks run", r.stdout)
        r = self.run_tool(DOC, "--list")
        self.assertIn("doc.md:34  sh      run; with 'exit 3' as 'exit 0'", r.stdout)


if __name__ == "__main__":
    unittest.main()
