#!/usr/bin/env python3
"""ctest (label sim): agv-sim refuses bad input with exit status 2 and a message that names the
problem, and never crashes."""
import json
import os
import subprocess
import sys
import tempfile


def main():
    agv, good = sys.argv[1], sys.argv[2]
    with open(good) as f:
        base = json.load(f)
    cases = []

    def variant(name, mutate, expect):
        sc = json.loads(json.dumps(base))
        mutate(sc)
        cases.append((name, json.dumps(sc), expect))

    variant("negative dl", lambda s: s["sensors"]["odometer"].__setitem__("dl_m", -1),
            "sensors.odometer.dl_m")
    variant("mode", lambda s: s.__setitem__("mode", "fast"), "mode")
    variant("beacon y", lambda s: s["beacons"][1].__setitem__("y", "north"), "beacons[1].y")
    variant("no path", lambda s: s.pop("path"), "path")
    variant("unreachable point",
            lambda s: s["path"].insert(0, {"x": s["start"]["x"] - 3, "y": s["start"]["y"],
                                           "heading_deg": 0, "speed_mps": 1}),
            "path[0]")
    variant("too many points", lambda s: s.__setitem__("path", s["path"] * 6), "path")
    # The board link: what its schema cannot say (sim/canbus.c).
    variant("bit time not whole ns", lambda s: s.__setitem__("link", {"bitrate_bps": 300000}),
            "link.bitrate_bps: 300000")
    variant("silence within a heartbeat",
            lambda s: s.__setitem__("link", {"heartbeat_ms": 100, "silence_ms": 100}),
            "link.silence_ms: 100 ms")
    variant("busoff of any node",
            lambda s: s.__setitem__("link", {"faults": [{"kind": "busoff", "at_s": 1}]}),
            "link.faults[0].node")
    variant("no such frame",
            lambda s: s.__setitem__("link", {"faults": [{"kind": "drop", "at_s": 1,
                                                         "frame": "FIX_C"}]}),
            "link.faults[0].frame: \"FIX_C\" is not a frame of firmware/link/cyclopion.dbc")
    variant("frame of a babble",
            lambda s: s.__setitem__("link", {"faults": [{"kind": "babble", "at_s": 1,
                                                         "frame": "FIX_A"}]}),
            "link.faults[0].frame")
    variant("two babblers",
            lambda s: s.__setitem__("link", {"faults": [{"kind": "babble", "at_s": 1},
                                                        {"kind": "babble", "at_s": 2}]}),
            "link.faults[1]")
    variant("babble of no duration",
            lambda s: s.__setitem__("link", {"faults": [{"kind": "babble", "at_s": 1,
                                                         "duration_s": 0}]}),
            "link.faults[0].duration_s")
    cases.append(("not json", "{ this is not json", "line 1"))
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        for name, text, expect in cases:
            p = os.path.join(tmp, "s.json")
            with open(p, "w") as f:
                f.write(text)
            r = subprocess.run([agv, "--scenario", p, "--quiet"], capture_output=True, text=True)
            ok = r.returncode == 2 and expect in r.stderr
            print(f"{'ok ' if ok else 'BAD'} {name}: exit {r.returncode}: {r.stderr.strip()[:160]}")
            failures += not ok
        for args, expect in ((["--scenario", "/nonexistent.json"], "/nonexistent.json"),
                             (["--scenario", good, "--candump", "/nonexistent/dir/x.log"],
                              "--candump: cannot write /nonexistent/dir/x.log"),
                             (["--scenario", good, "--can", "no_such_can9"], "--can no_such_can9"),
                             (["--seed", "x", "--scenario", good], "--seed"),
                             ([], "--scenario is required"),
                             (["--scenario", good, "extra"], "unexpected argument")):
            r = subprocess.run([agv] + args + ["--quiet"], capture_output=True, text=True)
            ok = r.returncode == 2 and expect in r.stderr
            print(f"{'ok ' if ok else 'BAD'} {args}: exit {r.returncode}: {r.stderr.strip()[:120]}")
            failures += not ok
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
