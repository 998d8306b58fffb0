"""Process hygiene for the Python tests: every helper process in its own process group, tied
to the test's life (it gets SIGTERM when the test dies, even by SIGKILL), killed as a group on
every exit path, and a check that nothing is left behind.

    from cy_procs import Group
    with Group("lcm_log") as g:
        logger = g.spawn([LOGGER, ...])   # subprocess.Popen
        ...
    # on leaving: every process group spawned is killed and reaped
    assert not g.leftovers()

Test scripts import it with sys.path (tests/support).
"""
import ctypes
import os
import signal
import subprocess
import time

PR_SET_PDEATHSIG = 1


def _die_with_parent():
    """In the child before exec: a new session (its own process group), and SIGTERM when the
    parent dies."""
    os.setsid()
    try:
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)
    except (OSError, AttributeError):
        pass  # not Linux: the group kill below still applies


class Group:
    """The processes of one test. `marker` is a string unique to the test run that appears in
    the spawned processes' command lines (a temporary path, a port): leftovers() looks for it
    in every process of the machine."""

    def __init__(self, marker):
        self.marker = marker
        self.procs = []

    def spawn(self, cmd, **kw):
        p = subprocess.Popen(cmd, preexec_fn=_die_with_parent, **kw)
        self.procs.append(p)
        return p

    def run(self, cmd, timeout, **kw):
        """subprocess.run in its own group: killed with its children on timeout."""
        p = self.spawn(cmd, **kw)
        try:
            out, err = p.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            self.kill(p)
            out, err = p.communicate()
            raise subprocess.TimeoutExpired(cmd, timeout, out, err)
        return subprocess.CompletedProcess(cmd, p.returncode, out, err)

    def stop(self, p, sig=signal.SIGINT, grace=5.0):
        """Ask @p p's group to finish (SIGINT: lcm-logger flushes and exits), then kill it."""
        try:
            os.killpg(p.pid, sig)
        except ProcessLookupError:
            pass
        try:
            p.wait(timeout=grace)
        except subprocess.TimeoutExpired:
            pass
        self.kill(p)

    def kill(self, p):
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        try:
            p.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass

    def close(self):
        for p in self.procs:
            self.kill(p)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def leftovers(self, wait=2.0):
        """Processes still alive (not zombies) whose command line holds the marker or whose
        process group is one spawned here: [(pid, command line)]."""
        groups = {p.pid for p in self.procs}
        deadline = time.monotonic() + wait
        while True:
            found = []
            for d in os.listdir("/proc"):
                if not d.isdigit() or int(d) == os.getpid():
                    continue
                try:
                    with open(f"/proc/{d}/cmdline", "rb") as f:
                        cmd = f.read().replace(b"\0", b" ").decode(errors="replace").strip()
                    with open(f"/proc/{d}/stat") as f:
                        stat = f.read().rsplit(")", 1)[1].split()
                except OSError:
                    continue
                state, pgid = stat[0], int(stat[2])
                if state == "Z":
                    continue
                if (self.marker and self.marker in cmd) or pgid in groups:
                    found.append((int(d), cmd))
            if not found or time.monotonic() > deadline:
                return found
            time.sleep(0.1)
