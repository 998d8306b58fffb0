#!/usr/bin/env python3
"""agvcalc's request lines (CONTRACT.md: one response per line, in order; malformed input gets
ok:false with an "error", never a crash, and the next line is still answered), with the inputs
the fuzzer found (tests/fuzz/corpus/agvcalc/regress_*) and the edges of the line format; and
--help, which lists every op (as the "version" op names them) with the fields CONTRACT.md gives
it and their units.
Usage: lines_test.py AGVCALC"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REGRESS = os.path.join(HERE, "..", "fuzz", "corpus", "agvcalc")

# The request fields of each op as CONTRACT.md states them.
CONTRACT_FIELDS = {
    "triangulate": ["beacons", "angles_deg"],
    "fix": ["map", "approx", "sightings", "angle_deg", "width_deg", "config", "beacon_diameter_m"],
    "reflectors3": ["reflectors", "field", "events_s", "expected_period_s", "approx"],
    "doublearc": ["from", "to", "min_radius_m", "wheelbase_m", "reverse"],
    "deadreckon": ["start", "wheelbase_m", "dl_m", "gyro_step_deg", "runs", "n_pulses",
                   "gyro_count"],
}

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL: " + what)


def answers(agvcalc, data):
    out = subprocess.run([agvcalc], input=data, capture_output=True, check=True)
    return [json.loads(l) for l in out.stdout.decode("utf-8").splitlines()]


def test_lines(agvcalc):
    version = b'{"op":"version"}\n'
    cases = [
        ("empty line", b"\n", "empty request line"),
        ("CR LF", b'{"op":"version"}\r\n', None),
        ("not an object", b"[1]\n", "must be a JSON object"),
        ("no op", b'{"x":1}\n', 'missing "op"'),
        ("NUL inside", b'{"op":"version"}\x00junk\n', "malformed JSON"),
        ("invalid UTF-8", b'{"op":"\xff"}\n', "malformed JSON"),
        ("duplicate key", b'{"op":"version","op":"fix"}\n', "malformed JSON"),
        # found by the fuzzer: the unknown op is quoted cut to 40 bytes, which split a
        # two-byte character; the error was dropped (ok:false without "error")
        ("unknown op cut inside a character", ('{"op":"a' + "\u00e9" * 30 + '"}\n').encode(),
         "unknown op"),
        ("unknown config key cut inside a character",
         ('{"op":"fix","map":[[0,0],[1,0],[0,1]],"approx":{"x":0,"y":0,"heading_deg":0},'
          '"sightings":[],"config":{"b' + "\u00e9" * 30 + '":1}}\n').encode(), "unknown key"),
        ("longer than 1 MiB", b'{"op":"version","pad":"' + b"x" * (1 << 20) + b'"}\n', "1 MiB"),
    ]
    data = b"".join(c[1] + version for c in cases)
    got = answers(agvcalc, data)
    check(len(got) == 2 * len(cases), f"{len(got)} answers to {2 * len(cases)} lines")
    for i, (what, _, needle) in enumerate(cases):
        a, after = got[2 * i], got[2 * i + 1]
        if needle is None:
            check(a.get("ok") is True, f"{what}: {a}")
        else:
            check(a.get("ok") is False and needle in a.get("error", ""),
                  f"{what}: expected ok:false with \"{needle}\", got {a}")
        check(after.get("ok") is True, f"{what}: the next line not answered: {after}")
    # every finding kept as a regression seed is answered line by line
    for name in sorted(os.listdir(REGRESS)):
        if not name.startswith("regress_"):
            continue
        with open(os.path.join(REGRESS, name), "rb") as f:
            body = f.read()
        lines = body.split(b"\n")
        got = answers(agvcalc, body + b"\n")
        check(len(got) == len(lines), f"{name}: {len(got)} answers to {len(lines)} lines")
        for a in got:
            check(isinstance(a.get("ok"), bool) and (a["ok"] or a.get("error")),
                  f"{name}: answer without ok or error: {a}")
        print(f"{name}: {len(got)} lines answered")


def test_help(agvcalc):
    out = subprocess.run([agvcalc, "--help"], capture_output=True, text=True, check=True).stdout
    ops = answers(agvcalc, b'{"op":"version"}\n')[0]["ops"]
    check(set(CONTRACT_FIELDS) <= set(ops), f"ops {ops} lack some of {sorted(CONTRACT_FIELDS)}")
    # each op's section: from its name at the line start to the next op's
    sections, cur = {}, None
    for line in out.splitlines():
        head = line[2:].split(" ")[0] if line.startswith("  ") and not line.startswith("   ") else None
        if head in ops:
            cur = head
            sections[cur] = ""
        elif cur:
            sections[cur] += line + "\n"
    for op in ops:
        check(op in sections, f"--help does not list op {op}")
    for op, fields in CONTRACT_FIELDS.items():
        text = sections.get(op, "")
        for f in fields:
            check(f in text, f"--help: op {op} does not list field {f}")
        check(" m" in text or "m (" in text, f"--help: op {op} gives no unit in metres")
    for op in ("triangulate", "fix", "doublearc", "deadreckon"):
        check("degrees" in sections.get(op, ""), f"--help: op {op} gives no unit in degrees")
    check("seconds" in sections.get("reflectors3", ""), "--help: reflectors3 gives no seconds")
    print(f"--help lists {len(sections)} ops with their fields")


def main():
    agvcalc = sys.argv[1]
    test_lines(agvcalc)
    test_help(agvcalc)
    if failures:
        print(f"{len(failures)} failures")
        return 1
    print("lines: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
