#!/usr/bin/env python3
"""tools/canvm.py does what it promises: the command runs with vcan0 up, its stdout, stderr and
exit status come back, the caller's environment and directory are the command's, the build tree
is writable; the direct path (checked again from inside the VM, whose kernel has AF_CAN) works;
a timeout or a SIGKILL of canvm leaves no QEMU and no command behind; a failing VM is an error
(125) and a missing QEMU a skip (77), each with its reason.

Exits 77 (skipped) when canvm finds no path to SocketCAN here, after the checks that need none.
"""
import argparse
import os
import re
import secrets
import signal
import subprocess
import sys
import time

CANVM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                     "canvm.py")
failures = []


def check(ok, what, detail=""):
    print(f"canvm_test: {'ok' if ok else 'FAIL'}: {what}" + ("" if ok else f"\n{detail}"),
          flush=True)
    if not ok:
        failures.append(what)


def canvm(*argv, env=None, **kw):
    return subprocess.run([sys.executable, CANVM] + list(argv), capture_output=True, text=True,
                          env=env, **kw)


def processes_with(token):
    """Pids of processes whose command line contains token (canvm's own excepted)."""
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                if token.encode() in f.read() and int(pid) != os.getpid():
                    pids.append(int(pid))
        except OSError:
            pass
    return pids


def job_token(pid):
    """What the command line of the QEMU started by canvm process pid contains."""
    with open("/proc/sys/kernel/random/boot_id") as f:
        return f"/jobs/{f.read().strip().replace('-', '')[:8]}-{pid}-"


def gone(tokens, within_s):
    end = time.monotonic() + within_s
    while time.monotonic() < end:
        if not any(processes_with(t) for t in tokens):
            return True
        time.sleep(0.1)
    return False


def test_skip():
    env = dict(os.environ, CANVM_QEMU="/nonexistent/qemu-system-x86_64")
    r = canvm("run", "--mode", "vm", "--", "true", env=env)
    check(r.returncode == 77 and "SKIPPED" in r.stderr and "/nonexistent/qemu" in r.stderr,
          "no QEMU: exit 77 with the reason", f"exit {r.returncode}: {r.stderr}")
    r = canvm("run", "--iface", "vcan 0", "--", "true")
    check(r.returncode == 2 and "--iface 'vcan 0'" in r.stderr,
          "a bad interface name: exit 2 naming it", f"exit {r.returncode}: {r.stderr}")


def test_passthrough(workdir):
    token = secrets.token_hex(8)
    out = os.path.join(workdir, "canvm_test.out")
    if os.path.exists(out):
        os.remove(out)
    cmd = (f"printf 'out:%s\\n' \"$CANVM_TEST_TOKEN\"; echo \"err:$(pwd)\" >&2; "
           "ip -o link show vcan0 | grep -q 'vcan0:.*[<,]UP[,>]' || exit 9; "
           "echo written > canvm_test.out || exit 10; "
           f"{sys.executable} {CANVM} check > check.out 2>&1 || exit 11; "
           "grep -qx 'path: direct' check.out || exit 12; "
           f"{sys.executable} {CANVM} run -q --mode direct -- "
           "'ip -o link show vcan0 | grep -q \"[<,]UP[,>]\" && exit 5'; "
           "[ $? = 5 ] || exit 13; exit 3")
    env = dict(os.environ, CANVM_TEST_TOKEN=token)
    t0 = time.monotonic()
    r = canvm("run", "--timeout", "600", "--", cmd, env=env, cwd=workdir)
    dt = time.monotonic() - t0
    check(r.returncode == 3, "exit status passed through (3)",
          f"exit {r.returncode}; stderr:\n{r.stderr}")
    check(r.stdout == f"out:{token}\n", "stdout passed through, environment kept",
          f"stdout {r.stdout!r}")
    check(f"err:{workdir}\n" in r.stderr, "stderr passed through, directory kept",
          f"stderr {r.stderr!r}")
    check(os.path.exists(out) and open(out).read() == "written\n",
          "the command wrote into the build tree")
    print(f"canvm_test: one run with checks inside took {dt:.1f} s", flush=True)


def test_timeout(mode):
    t0 = time.monotonic()
    p = subprocess.Popen([sys.executable, CANVM, "run", "--timeout", "3", "--",
                          "sleep 100.123"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    _, err = p.communicate(timeout=120)
    dt = time.monotonic() - t0
    check(p.returncode == 124 and "timed out" in err, f"--timeout 3: exit 124 after {dt:.1f} s",
          f"exit {p.returncode}: {err}")
    check(gone([job_token(p.pid), "100.123"], 5), f"after the timeout no QEMU or command is left "
                                                  f"({mode})")


def test_sigkill(mode):
    p = subprocess.Popen([sys.executable, CANVM, "run", "-q", "--", "sleep 100.456"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    token = job_token(p.pid) if mode == "vm" else "100.456"
    end = time.monotonic() + 120
    while not processes_with(token) and time.monotonic() < end and p.poll() is None:
        time.sleep(0.1)
    started = bool(processes_with(token))
    p.send_signal(signal.SIGKILL)
    p.wait()
    check(started and gone([token, "100.456"], 5),
          f"SIGKILL of canvm takes its {'QEMU' if mode == 'vm' else 'command'} along")


def test_vm_failure():
    r = canvm("run", "--mode", "vm", "--iface", "lo", "--", "true")  # lo exists: not a vcan
    check(r.returncode == 125 and "creating lo failed" in r.stderr,
          "a VM that cannot set up: exit 125 with the reason", f"exit {r.returncode}: {r.stderr}")


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--workdir", default=os.getcwd(),
                    help="a writable directory in the build tree (default: the current one)")
    args = ap.parse_args()
    workdir = os.path.abspath(args.workdir)
    test_skip()
    r = canvm("check")
    print(r.stdout, end="", flush=True)
    m = re.search(r"^path: (direct|vm)$", r.stdout, re.M)
    if r.returncode == 77 or not m:
        print(f"canvm_test: SKIPPED: no path to SocketCAN here ({r.stdout.strip()})")
        return 1 if failures else 77
    mode = m.group(1)
    test_passthrough(workdir)
    test_timeout(mode)
    test_sigkill(mode)
    if mode == "vm":
        test_vm_failure()
    print(f"canvm_test: {len(failures)} failed" if failures else "canvm_test: PASS")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
