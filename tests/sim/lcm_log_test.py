#!/usr/bin/env python3
"""ctest (label sim): telemetry on loopback. lcm-logger records while agv-sim publishes on a UDP
multicast LCM URL (ttl=0: loopback only); every message of the log must decode with the Python
types that lcm-gen generated at build time, and every channel must be there.

  lcm_log_test.py AGV_SIM SCENARIO PYTHON_TYPES_DIR
"""
import os
import subprocess
import sys
import tempfile
import time

URL = "udpm://239.255.76.67:7719?ttl=0"
CHANNELS = {"CYCLOPION_TRUTH": "truth_t", "CYCLOPION_POSE": "pose_t", "CYCLOPION_FIX": "fix_t",
            "CYCLOPION_SIGHTINGS": "sightings_t", "CYCLOPION_DRIVE": "drive_command_t"}


def multicast_works(lcm):
    lc = lcm.LCM(URL)
    got = []
    lc.subscribe("CYCLOPION_PROBE", lambda ch, data: got.append(data))
    lcm.LCM(URL).publish("CYCLOPION_PROBE", b"probe")
    lc.handle_timeout(500)
    return bool(got)


def main():
    agv, scenario, types = sys.argv[1], sys.argv[2], sys.argv[3]
    sys.path.insert(0, types)
    import lcm
    import cyclopion

    if not multicast_works(lcm) and os.geteuid() == 0:
        # A machine without a multicast route: send multicast through the loopback interface.
        subprocess.run(["ip", "link", "set", "lo", "multicast", "on"], check=False)
        subprocess.run(["ip", "route", "add", "224.0.0.0/4", "dev", "lo"], check=False)
    if not multicast_works(lcm):
        print("FAIL: LCM multicast does not reach this process on loopback "
              "(see https://lcm-proj.github.io/lcm/content/multicast-setup.html)")
        return 1

    with tempfile.TemporaryDirectory() as tmp:
        log = os.path.join(tmp, "run.lcmlog")
        logger = subprocess.Popen(["lcm-logger", "-f", "-l", URL, log],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        time.sleep(0.5)  # let the logger subscribe
        r = subprocess.run([agv, "--scenario", scenario, "--lcm", URL, "--quiet",
                            "--report", os.path.join(tmp, "r.json")], capture_output=True,
                           text=True)
        time.sleep(0.5)
        logger.terminate()
        logger.wait(timeout=10)
        if r.returncode != 0:
            print(f"FAIL: agv-sim exited {r.returncode}: {r.stderr}")
            return 1
        counts = {}
        for ev in lcm.EventLog(log, "r"):
            if ev.channel not in CHANNELS:
                continue
            cls = getattr(cyclopion, CHANNELS[ev.channel])
            msg = cls.decode(ev.data)  # raises on a bad fingerprint or short data
            if ev.channel == "CYCLOPION_TRUTH" and not (-1e4 < msg.x < 1e4):
                print(f"FAIL: implausible truth message {msg.x}")
                return 1
            counts[ev.channel] = counts.get(ev.channel, 0) + 1
        print("decoded:", ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
        absent = [c for c in CHANNELS if not counts.get(c)]
        if absent:
            print(f"FAIL: no messages on {absent}")
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
