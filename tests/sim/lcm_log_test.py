#!/usr/bin/env python3
"""ctest (label sim): a live run on LCM is logged whole, and leaves no process behind.

lcm-logger (the real binary, not a wrapper that would leave its child behind) starts first, on
a UDP multicast URL of this test's own (ttl=0: loopback only; a port derived from the test's
process id, so that parallel runs do not hear each other); once it records, agv-sim runs the
scenario with --realtime=FACTOR and --stats, which reports how many messages it published on
each channel. Then:

- every message published is in the log: the log's count per channel equals agv-sim's;
- every message decodes with the Python types lcm-gen generated, and with lcm-spy's own type
  database over the Java types (tests/sim/SpyDecode.java, the CLASSPATH of `make lcm-spy`);
- pacing changed nothing but the time: the live run's report equals an unpaced run's (wall
  time excepted), and the live run took at least the simulated time over FACTOR;
- every process the test started is gone afterwards (process groups killed on every exit
  path, children tied to the test's life), checked by looking for them.

  lcm_log_test.py AGV_SIM SCENARIO PYTHON_TYPES_DIR --logger LCM_LOGGER --classpath CP
                  [--factor F]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
from cy_procs import Group  # noqa: E402

CHANNELS = {"CYCLOPION_TRUTH": "truth_t", "CYCLOPION_POSE": "pose_t", "CYCLOPION_FIX": "fix_t",
            "CYCLOPION_SIGHTINGS": "sightings_t", "CYCLOPION_DRIVE": "drive_command_t"}
PROBE = "CYCLOPION_TEST_PROBE"


def multicast_works(lcm, url):
    lc = lcm.LCM(url)
    got = []
    lc.subscribe(PROBE, lambda ch, data: got.append(data))
    lcm.LCM(url).publish(PROBE, b"probe")
    lc.handle_timeout(500)
    return bool(got)


def log_counts(lcm, path):
    """Messages per channel in an LCM log (a log being written is read up to its end)."""
    counts = {}
    try:
        for ev in lcm.EventLog(path, "r"):
            counts[ev.channel] = counts.get(ev.channel, 0) + 1
    except (IOError, ValueError):
        pass
    return counts


def wait_for(cond, timeout, step=0.1):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if cond():
            return True
        time.sleep(step)
    return cond()


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("agv_sim")
    ap.add_argument("scenario")
    ap.add_argument("types", help="directory of the generated Python LCM types")
    ap.add_argument("--logger", required=True, help="the lcm-logger binary")
    ap.add_argument("--classpath", required=True, help="lcm-spy's CLASSPATH (make lcm-spy)")
    ap.add_argument("--factor", type=float, default=4.0, help="--realtime factor (default 4)")
    a = ap.parse_args()
    sys.path.insert(0, a.types)
    import lcm
    import cyclopion

    url = f"udpm://239.255.76.67:{20000 + os.getpid() % 30000}?ttl=0"
    if not multicast_works(lcm, url) and os.geteuid() == 0:
        # A machine without a multicast route: send multicast through the loopback interface.
        subprocess.run(["ip", "link", "set", "lo", "multicast", "on"], check=False)
        subprocess.run(["ip", "route", "add", "224.0.0.0/4", "dev", "lo"], check=False)
    if not multicast_works(lcm, url):
        print("FAIL: LCM multicast does not reach this process on loopback "
              "(see https://lcm-proj.github.io/lcm/content/multicast-setup.html)")
        return 1

    failures = []

    def check(ok, what):
        print(f"{'ok ' if ok else 'BAD'} {what}")
        if not ok:
            failures.append(what)

    with tempfile.TemporaryDirectory(prefix="cy-lcm-log-") as tmp:
        log = os.path.join(tmp, "run.lcmlog")
        group = Group(tmp)
        with group:
            logger = group.spawn([a.logger, "--quiet", "--force", "--flush-interval=20",
                                  f"--lcm-url={url}", log], stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL)
            # The logger records: probes go out until one is in the log.
            pub = lcm.LCM(url)

            def probe_logged():
                pub.publish(PROBE, b"probe")
                return log_counts(lcm, log).get(PROBE, 0) > 0
            check(wait_for(probe_logged, 20, 0.2), f"{a.logger} records on {url}")
            live = group.run([a.agv_sim, "--scenario", a.scenario, "--lcm", url,
                              f"--realtime={a.factor:g}", "--stats", "--quiet", "--report",
                              os.path.join(tmp, "live.json")], timeout=600,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            m = re.search(r"^agv-sim: stats (\{.*\})$", live.stderr, re.M)
            check(live.returncode == 0 and m, f"agv-sim --realtime={a.factor:g} exit "
                  f"{live.returncode}, stats line {'found' if m else 'missing'}")
            stats = json.loads(m.group(1)) if m else {}
            published = stats.get("lcm_published", {})
            total = sum(published.values())
            # Every message published, in the log (flushed every 20 ms).
            wait_for(lambda: all(log_counts(lcm, log).get(c, 0) >= n
                                 for c, n in published.items()), 10)
            group.stop(logger)
        left = group.leftovers()
        check(not left, f"no process left behind {left}")

        logged = {c: n for c, n in log_counts(lcm, log).items() if c != PROBE}
        print(f"published {total}: {published}; failed {stats.get('lcm_failed')}")
        print(f"logged    {sum(logged.values())}: {logged}")
        check(set(published) == set(CHANNELS) and all(published.values()),
              "agv-sim published on every channel")
        check(stats.get("lcm_failed") == 0, "no publish failed")
        check(logged == published, "every message published was logged, nothing else")

        decoded = {}
        for ev in lcm.EventLog(log, "r"):
            if ev.channel in CHANNELS:
                getattr(cyclopion, CHANNELS[ev.channel]).decode(ev.data)  # raises when bad
                decoded[ev.channel] = decoded.get(ev.channel, 0) + 1
        check(decoded == published, "every message decodes with the Python types")
        with Group(tmp) as g:
            spy = g.run(["java", "-cp", a.classpath, os.path.join(HERE, "SpyDecode.java"), log,
                         "CYCLOPION_(TRUTH|POSE|FIX|SIGHTINGS|DRIVE)"],
                        timeout=300, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        spied = {ln.split()[0]: int(ln.split()[2]) for ln in spy.stdout.splitlines()
                 if len(ln.split()) == 3 and ln.split()[0] in CHANNELS}
        check(spy.returncode == 0 and spied == published,
              f"lcm-spy's type database decodes every message: {spied} {spy.stderr.strip()}")

        with Group(tmp) as g:
            fast = g.run([a.agv_sim, "--scenario", a.scenario, "--quiet", "--report",
                          os.path.join(tmp, "fast.json")], timeout=600)
        reports = []
        for name in ("live.json", "fast.json"):
            with open(os.path.join(tmp, name)) as f:
                r = json.load(f)
            r.pop("wall_time_s")
            reports.append(r)
        check(fast.returncode == 0 and reports[0] == reports[1],
              "the live run's report equals the unpaced run's (wall time excepted)")
        sim_s = reports[0]["sim_time_s"]
        with open(os.path.join(tmp, "live.json")) as f:
            wall = json.load(f)["wall_time_s"]
        check(wall >= sim_s / a.factor * 0.99,
              f"the live run took {wall:.2f} s for {sim_s:.2f} s simulated at {a.factor:g}x")
    print("FAIL" if failures else "PASS", f"{len(failures)} problem(s)" if failures else "")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
