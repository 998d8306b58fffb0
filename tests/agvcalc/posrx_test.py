#!/usr/bin/env python3
"""agvcalc op "posrx" end to end (CONTRACT.md): byte streams through the real binary.

- A drive at seed 002's conditions, packets encoded here (struct, big-endian) with garbage,
  torn packets, zero packets, wild positions and repeats between them: the positions, their
  reasons and the resync count against a model written here from the seed (its ser_int
  framing: the last 14 bytes since the previous packet start with 0x00 and end with 0xFF)
  and CONTRACT's rules (all-zero refused; a jump is farther from the last accepted position
  than max_speed_mps times the time since it; nearer than min_update_m is too close).
- Random byte streams and malformed requests: every line answered (one JSON object with
  "ok", ok:false with a readable error when the request is bad), the process never crashes.

  tests/agvcalc/posrx_test.py build/host/bin/agvcalc
"""
import json
import math
import random
import struct
import subprocess
import sys


def packet(x_mm, y_mm, z_mm):
    return b"\x00" + struct.pack(">iii", x_mm, y_mm, z_mm) + b"\xff"


def model(chunks, min_update_m=0.05, max_speed_mps=2.0):
    """The seed's framing and CONTRACT's rules: [(t_s, x, y, z, reason)], resyncs."""
    ring, since, out, resyncs, ref = [], 0, [], 0, None
    for t_s, data in chunks:
        t_ms = round(t_s * 1000)
        for b in data:
            ring = (ring + [b])[-14:]
            since += 1
            if since >= 14 and ring[-1] == 0xFF and ring[0] == 0x00:
                resyncs += since > 14
                since = 0
                x, y, z = struct.unpack(">iii", bytes(ring[1:13]))
                if x == y == z == 0:
                    why = "zero"
                elif ref is None:
                    why = "ok"
                else:
                    d = round(math.hypot(x - ref[0], y - ref[1]))
                    if d > max_speed_mps * 1000 * (t_ms - ref[2]) / 1000:
                        why = "jump"
                    elif d < round(min_update_m * 1000):
                        why = "too_close"
                    else:
                        why = "ok"
                if why == "ok":
                    ref = (x, y, t_ms)
                out.append((t_ms / 1000, x / 1000, y / 1000, z / 1000, why))
    return out, resyncs


def drive(rng):
    """Seed 002's Path #1 at 1 m/s, 10 updates a second with a half-second lag, and its
    troubles: garbage, torn packets, zeros, wild positions, a stop (repeats)."""
    chunks, t, y = [], 0.5, 2000
    for k in range(120):
        data = b""
        kind = rng.random()
        if kind < 0.1:
            data += bytes(rng.randrange(256) for _ in range(rng.randrange(1, 30)))
        elif kind < 0.15:
            data += packet(2500, y, 1200)[: rng.randrange(1, 13)]
        if 0.2 < kind < 0.25:
            data += packet(0, 0, 0)
        elif 0.25 < kind < 0.3:
            data += packet(2500 + rng.choice([-1, 1]) * rng.randrange(600, 3000), y, 1200)
        elif 40 <= k < 50:
            data += packet(2500, y, 1200)  # standing: repeats, too close
        else:
            y += 100
            data += packet(2500 + rng.randrange(-3, 4), y, 1200)
        chunks.append((round(t, 3), data))
        t += 0.1
    return chunks


def request(chunks, **cfg):
    req = {"op": "posrx", "chunks": [[t, d.hex(" ")] for t, d in chunks]}
    if cfg:
        req["config"] = cfg
    return req


def run(agvcalc, lines):
    text = "\n".join(l if isinstance(l, str) else json.dumps(l) for l in lines) + "\n"
    out = subprocess.run([agvcalc], input=text, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    answers = [json.loads(l) for l in out.stdout.splitlines()]
    assert len(answers) == len(lines), (len(answers), len(lines))
    for a in answers:
        assert "ok" in a and (a["ok"] or (isinstance(a.get("error"), str) and a["error"])), a
    return answers


def check_against_model(agvcalc):
    rng = random.Random(1993)
    reqs, want = [], []
    for trial in range(40):
        chunks = drive(rng)
        cfg = {} if trial % 2 else {"min_update_m": 0.05, "max_speed_mps": 2.0}
        reqs.append(request(chunks, **cfg))
        want.append(model(chunks))
    answers = run(agvcalc, reqs)
    reasons = {}
    for a, (positions, resyncs) in zip(answers, want):
        assert a["ok"], a
        got = [(p["t_s"], p["x"], p["y"], p["z"], p["reason"]) for p in a["positions"]]
        assert len(got) == len(positions), (len(got), len(positions))
        for g, w in zip(got, positions):
            assert g[4] == w[4] and all(abs(u - v) < 1e-9 for u, v in zip(g[:4], w[:4])), (g, w)
        assert all(p["accepted"] == (p["reason"] == "ok") for p in a["positions"])
        assert a["resyncs"] == resyncs, (a["resyncs"], resyncs)
        for p in a["positions"]:
            reasons[p["reason"]] = reasons.get(p["reason"], 0) + 1
    assert all(reasons.get(k, 0) > 20 for k in ("ok", "zero", "jump", "too_close")), reasons
    print(f"posrx: {len(reqs)} drives, reasons {reasons}: as the model")


def check_reference_and_config(agvcalc):
    start = [[0.0, packet(2500, 2000, 1200).hex()], [0.4, packet(2500, 2020, 1200).hex()],
             [0.5, packet(9000, 9000, 1200).hex()]]
    a = run(agvcalc, [
        {"op": "posrx", "chunks": start, "reference": {"x": 2.5, "y": 2.0, "t_s": 0.0}},
        {"op": "posrx", "chunks": start, "config": {"min_update_m": 0.01}},
        {"op": "posrx", "chunks": start, "config": {"max_speed_mps": 30.0}},
    ])
    assert [p["reason"] for p in a[0]["positions"]] == ["too_close", "too_close", "jump"], a[0]
    assert [p["reason"] for p in a[1]["positions"]] == ["ok", "ok", "jump"], a[1]
    assert [p["reason"] for p in a[2]["positions"]] == ["ok", "too_close", "ok"], a[2]
    assert a[0]["trailing_bytes"] == 0 and a[0]["skipped_bytes"] == 0


def check_random_and_malformed(agvcalc):
    rng = random.Random(7)
    lines = []
    for _ in range(300):  # random bytes in random chunks
        t, chunks = 0.0, []
        for _ in range(rng.randrange(0, 20)):
            t += rng.choice([0.0, 0.001, 0.1, 1.5])
            n = rng.randrange(0, 200)
            data = bytes(rng.choice([0x00, 0xFF, rng.randrange(256)]) for _ in range(n))
            chunks.append([round(t, 3), data.hex(" ") if rng.random() < 0.5 else data.hex()])
        lines.append({"op": "posrx", "chunks": chunks})
    bad = [
        '{"op":"posrx"}',
        '{"op":"posrx","chunks":5}',
        '{"op":"posrx","chunks":[[0,"0g"]]}',
        '{"op":"posrx","chunks":[[0,"000"]]}',
        '{"op":"posrx","chunks":[[0,"0 0"]]}',
        '{"op":"posrx","chunks":[[1,"00"],[0.5,"ff"]]}',
        '{"op":"posrx","chunks":[[-1,"00"]]}',
        '{"op":"posrx","chunks":[[1e300,"00"]]}',
        '{"op":"posrx","chunks":[["0","00"]]}',
        '{"op":"posrx","chunks":[[0]]}',
        '{"op":"posrx","chunks":[[0,"00",1]]}',
        '{"op":"posrx","chunks":[[0,12]]}',
        '{"op":"posrx","chunks":[{"t":0}]}',
        '{"op":"posrx","chunks":[],"config":{"max_speed_mps":0}}',
        '{"op":"posrx","chunks":[],"config":{"min_update_m":-1}}',
        '{"op":"posrx","chunks":[],"config":[]}',
        '{"op":"posrx","chunks":[],"config":{"max_speed_mps":"fast"}}',
        '{"op":"posrx","chunks":[],"reference":{"x":1}}',
        '{"op":"posrx","chunks":[],"reference":7}',
        '{"op":"posrx","chunks":[[0,"\\u00e9\\u00e9"]]}',
        '{"op":"posrx","chunks":[[0,"00"]]',
        'garbage',
        '[]',
    ]
    for i, b in enumerate(bad):
        lines.insert(3 * i + 1, b)
    answers = run(agvcalc, lines)
    for line, a in zip(lines, answers):
        if isinstance(line, str):
            assert not a["ok"], (line, a)
        else:
            assert a["ok"], (line, a)
            assert all(set(p) == {"t_s", "x", "y", "z", "accepted", "reason"}
                       for p in a["positions"])
    errors = [a["error"] for l, a in zip(lines, answers) if isinstance(l, str)]
    assert any("chunks[0][1]" in e and "hex" in e for e in errors), errors
    assert any("time order" in e for e in errors), errors
    assert any("max_speed_mps" in e for e in errors), errors
    print(f"posrx: {len(lines) - len(bad)} random streams and {len(bad)} malformed requests "
          f"answered, line for line")


def main():
    agvcalc = sys.argv[1]
    check_against_model(agvcalc)
    check_reference_and_config(agvcalc)
    check_random_and_malformed(agvcalc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
