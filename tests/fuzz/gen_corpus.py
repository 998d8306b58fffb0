#!/usr/bin/env python3
"""Writes the fuzz harnesses' seed corpora (tests/fuzz/corpus/<harness>/): small, meaningful
inputs - valid frames and messages of every kind, valid request lines of every agvcalc op, the
shipped scenarios - and the edge cases around them. The message coding is implemented here from
its description in firmware/link/include/link/linkmsg.h, not taken from the C.

The output is deterministic; the seeds are committed, beside the findings kept as regression
seeds (regress_*, left alone). Run it again after a format changes:
    tests/fuzz/gen_corpus.py            (writes tests/fuzz/corpus/)
    tests/fuzz/gen_corpus.py --check    (exit 1 when the committed seeds differ)"""
import argparse
import json
import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))

# ----------------------------------------------------------------------- link frames


def crc8(data):
    """CRC-8, polynomial x^8 + x^2 + x + 1, initial value 0, no reflection."""
    crc = 0
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = ((crc << 1) ^ 0x07) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc


def q16(m):
    return struct.pack("<i", round(m * 65536))


def angle(deg):
    return struct.pack("<I", round(deg / 360.0 * 2**32) % 2**32)


def pose(x, y, h):
    return q16(x) + q16(y), angle(h)


def pair(a_id, xy, rest):
    """An A/B pair: A = x, y; B = heading and the rest, then the tag (CRC-8 of A's data)."""
    return [(a_id, xy), (a_id + 1, rest + bytes([crc8(xy)]))]


ID_STOP, ID_POSE_A, ID_FIX_A, ID_FIX_ACK = 0x010, 0x020, 0x030, 0x032
ID_LATCH_REQ, ID_LATCH_A, ID_DIR = 0x040, 0x041, 0x050
ID_MAIN_HEARTBEAT, ID_NAV_HEARTBEAT = 0x701, 0x702


def messages():
    """Every message as its frames (id, data)."""
    xy, h = pose(12.5, -3.25, 30.0)
    return {
        "stop": [(ID_STOP, b"\x01")],
        "pose": pair(ID_POSE_A, xy, h + b"\x07"),
        "fix": pair(ID_FIX_A, xy, h + struct.pack("<H", 513) + b"\x01"),
        "fix_ack": [(ID_FIX_ACK, struct.pack("<bH", -7, 513))],
        "latch_req": [(ID_LATCH_REQ, struct.pack("<HB", 510, 4))],
        "latch": pair(ID_LATCH_A, xy, h + struct.pack("<Hb", 511, 0)),
        "dir": [(ID_DIR, b"\x01")],
        "main_heartbeat": [(ID_MAIN_HEARTBEAT, bytes([41, 0x01, 0, 0]))],
        "nav_heartbeat": [(ID_NAV_HEARTBEAT, bytes([255, 0x03, 136, 2]))],
    }


# ----------------------------------------------------------------------- link messages
# linkmsg_fuzz.c records: [selector, id byte, length byte, data...]; a selector below 0xC0
# picks ids[selector % n] of the message table's ids in ascending order (linkmsg_sender()):
ID_FIX_QUALITY = 0x033
TABLE_IDS = sorted([ID_STOP, ID_POSE_A, ID_POSE_A + 1, ID_FIX_A, ID_FIX_A + 1, ID_FIX_ACK,
                    ID_FIX_QUALITY, ID_LATCH_REQ, ID_LATCH_A, ID_LATCH_A + 1, ID_DIR,
                    ID_MAIN_HEARTBEAT, ID_NAV_HEARTBEAT])
SEL = {fid: k for k, fid in enumerate(TABLE_IDS)}


def record(fid, data, raw=False):
    if raw:
        return bytes([0xC0 | (fid >> 8), fid & 0xFF, len(data)]) + data
    return bytes([SEL[fid], 0, len(data)]) + data


def linkmsg_seeds():
    s = {}
    msgs = messages()
    for name, frames in msgs.items():
        s["msg_" + name] = b"".join(record(i, d) for i, d in frames)
    s["all"] = b"".join(record(i, d) for frames in msgs.values() for i, d in frames)
    (a_id, a), (b_id, b) = msgs["pose"]
    s["b_without_a"] = record(b_id, b)
    s["bad_tag"] = record(a_id, a) + record(b_id, b[:-1] + bytes([b[-1] ^ 1]))
    s["a_short"] = record(a_id, a[:7]) + record(b_id, b)
    s["a_twice"] = record(a_id, bytes(8)) + record(a_id, a) + record(b_id, b)
    s["foreign_between"] = record(a_id, a) + record(0x7FF, b"\x01\x02", raw=True) + record(b_id, b)
    s["stop_bad_len"] = record(ID_STOP, b"")
    s["heartbeat_bad_len"] = record(ID_NAV_HEARTBEAT, b"\x01\x02\x03")
    return s


# ----------------------------------------------------------------------- agvcalc lines


def sightings(x, y, h, beacons, d=0.08):
    out = []
    for bx, by in beacons:
        r = math.hypot(bx - x, by - y)
        a = (math.degrees(math.atan2(by - y, bx - x)) - h) % 360.0
        out.append({"angle_deg": round(a, 6), "width_deg": round(math.degrees(2 * math.asin(d / (2 * r))), 6)})
    return out


def agvcalc_seeds():
    beacons = [[0.0, 0.0], [20.0, 0.0], [20.0, 15.0], [0.0, 15.0], [10.0, 18.0]]
    x, y, h = 6.0, 5.0, 30.0
    sg = sightings(x, y, h, beacons)
    tri = {"op": "triangulate", "beacons": beacons[:3], "angles_deg": [s["angle_deg"] for s in sg[:3]]}
    fix = {"op": "fix", "map": beacons, "approx": {"x": x + 0.1, "y": y - 0.1, "heading_deg": h + 1},
           "sightings": sg}
    fix_cfg = dict(fix, config={"beacon_diameter_m": 0.08, "window_deg": 5, "widen_steps": 2,
                                "beacon_flat": False, "quality_max": 0.03})
    r3 = {"op": "reflectors3", "reflectors": [[0, 21], [13, 21], [13, 0]],
          "events_s": [0, 1.0556, 2.3628, 2.8508, 4], "expected_period_s": 4}
    r3_field = dict(r3, field=[[0, 0], [13, 0], [13, 21], [0, 21]], approx={"x": 6, "y": 10},
                    goal={"x": 10, "y": 10})
    da = {"op": "doublearc", "from": {"x": 0, "y": 0, "heading_deg": 0},
          "to": {"x": 0.8, "y": 1.8, "heading_deg": 90}, "min_radius_m": 0.5, "wheelbase_m": 0.762}
    da_rev = dict(da, reverse=True, to={"x": -0.8, "y": 1.8, "heading_deg": -90})
    cfg = {"wheelbase_m": 0.762, "dl_m": 0.000254, "gyro_step_deg": 0.25}
    dr = dict({"op": "deadreckon", "start": {"x": 1, "y": 2, "heading_deg": 90}}, **cfg,
              runs=[[14, 0], [28, 1], [28, 2], [28, 3], [14, 4]])
    dr_back = dict(dr, runs=[[-100, 0], [0, -4], [-50, -4], [3, 2]])
    dr_edge = dict(dr, start={"x": 29999, "y": -29999, "heading_deg": 0}, dl_m=0.00195,
                   runs=[[400000, 0]])

    def line(o):
        return json.dumps(o, separators=(",", ":")).encode()

    s = {
        "triangulate": line(tri),
        "fix": line(fix),
        "fix_config": line(fix_cfg),
        "reflectors3": line(r3),
        "reflectors3_field_goal": line(r3_field),
        "doublearc": line(da),
        "doublearc_reverse": line(da_rev),
        "deadreckon": line(dr),
        "deadreckon_backwards": line(dr_back),
        "deadreckon_range_edge": line(dr_edge),
        "posrx": line({"op": "posrx", "chunks": [[0.1, position_packet(2500, 2000, 1200).hex(" ")],
                                                [0.2, "12 ff " + position_packet(2500, 2100, 1200).hex(" ")],
                                                [0.3, position_packet(10000, 2200, 1200).hex()]],
                       "config": {"min_update_m": 0.05, "max_speed_mps": 2.0}}),
        "posrx_reference": line({"op": "posrx", "reference": {"x": 2.5, "y": 2.0, "t_s": 0},
                                 "chunks": [[0.5, position_packet(0, 0, 0).hex()]]}),
        "version": b'{"op":"version"}',
        "several_lines": b"\n".join([line(tri), b"", b"not json", line(da)]) + b"\r\n",
        "unknown_op": b'{"op":"nope","x":1}',
        "not_object": b'[1,2,3]',
        "bad_number": line(dict(dr, dl_m="fast")),
        "duplicate_key": b'{"op":"version","op":"fix"}',
    }
    return s


# ----------------------------------------------------------------------- position packets


def position_packet(x_mm, y_mm, z_mm):
    """Seed 002's packet (docs/posrx.md): 0x00, x, y, z as signed 32-bit big-endian mm, 0xFF."""
    return b"\x00" + struct.pack(">iii", x_mm, y_mm, z_mm) + b"\xff"


def posrx_seeds():
    """The posrx harness's input (tests/fuzz/posrx_fuzz.c): the minimum update distance and the
    top speed (16-bit little-endian mm, mm/s), then (byte, control) records: control bit 0 a
    receive error, bits 1-7 the milliseconds before the byte."""
    cfg = struct.pack("<HH", 50, 2000)

    def records(stream, first_ms=100, error_at=None):
        out = bytearray()
        for i, b in enumerate(stream):
            ctrl = (min(first_ms, 127) << 1) if i == 0 else 0
            out += bytes([b, ctrl | (1 if i == error_at else 0)])
        return bytes(out)

    a, b = position_packet(2500, 2000, 1200), position_packet(2500, 2100, 1200)
    return {
        "packet": cfg + records(a),
        "two_packets": cfg + records(a) + records(b),
        "garbage_then_packet": cfg + records(b"\x12\xff\x00\x34" + a),
        "torn_then_packet": cfg + records(a[:9] + b),
        "zeros": cfg + records(position_packet(0, 0, 0)),
        "jump": cfg + records(a) + records(position_packet(90000, 2000, 1200), first_ms=10),
        "too_close": cfg + records(a) + records(position_packet(2510, 2000, 1200)),
        "error_byte": cfg + records(a, error_at=5) + records(b),
        "beyond_range": cfg + records(position_packet(2**31 - 1, -(2**31), 0)),
        "max_speed_zero": struct.pack("<HH", 50, 0) + records(a),
    }


# ----------------------------------------------------------------------- scenarios


def scenario_seeds():
    """The shipped scenarios (compact), a minimal one, every optional key, and edge cases."""
    s = {}
    sdir = os.path.join(HERE, "..", "..", "sim", "scenarios")
    for f in sorted(os.listdir(sdir)):
        if f.endswith(".json"):
            with open(os.path.join(sdir, f)) as fh:
                s[f[:-5]] = json.dumps(json.load(fh), separators=(",", ":")).encode()
    minimal = {"name": "m", "mode": "full",
               "beacons": [{"x": 0, "y": 0, "diameter_m": 0.08}, {"x": 5, "y": 0, "diameter_m": 0.08},
                           {"x": 0, "y": 5, "diameter_m": 0.08}],
               "vehicle": {"wheelbase_m": 0.75, "min_radius_m": 0.5, "speed_mps": 1.0},
               "start": {"x": 1, "y": 1, "heading_deg": 0},
               "path": [{"x": 3, "y": 1, "heading_deg": 0}],
               "sensors": {"goniometer": {"rev_per_s": 2, "counts": 50000, "noise_deg": 0},
                           "odometer": {"dl_m": 0.000254}, "gyro": {"step_deg": 0.25, "drift_deg_per_s": 0}},
               "seed": 1, "duration_s": 10}
    full = dict(minimal, mode="simplified",
                spurious=[{"x": 2, "y": 2, "width_deg": 0.1}],
                occluders=[{"x1": -1, "y1": 3, "x2": 1, "y2": 3}],
                start_error={"x": 0.01, "y": -0.01, "heading_deg": 0.5},
                success={"cross_track_mean_m": 0.02, "cross_track_max_m": 0.05, "final_error_m": 0.1,
                         "fix_error_max_m": 0.05, "fix_accept_ratio": 0.9, "reach_goal": True})
    full["sensors"] = {"goniometer": {"rev_per_s": 2, "counts": 50000, "noise_deg": 0.01, "range_m": 30},
                       "odometer": {"dl_m": 0.000254, "scale": 1.001},
                       "gyro": {"step_deg": 0.25, "drift_deg_per_s": 0.001}}

    def text(o):
        return json.dumps(o, separators=(",", ":")).encode()

    s["minimal"] = text(minimal)
    s["every_key"] = text(full)
    s["unknown_keys"] = text(dict(minimal, colour="red", vehicle=dict(minimal["vehicle"], wings=2)))
    s["bad_mode"] = text(dict(minimal, mode="teleport"))
    s["too_many_beacons"] = text(dict(minimal, beacons=[{"x": i, "y": 0, "diameter_m": 0.08} for i in range(65)]))
    s["long_name"] = text(dict(minimal, name="n" * 100))
    s["fractional_seed"] = text(dict(minimal, seed=1.5))
    s["no_path"] = text(dict(minimal, path=[]))
    s["not_object"] = b"[]"
    return s


def write(check):
    corpora = {"linkmsg": linkmsg_seeds(), "agvcalc": agvcalc_seeds(), "scenario": scenario_seeds(),
               "posrx": posrx_seeds()}
    differ = []
    for harness, seeds in corpora.items():
        d = os.path.join(HERE, "corpus", harness)
        os.makedirs(d, exist_ok=True)
        present = set(os.listdir(d))
        for name, data in seeds.items():
            p = os.path.join(d, name)
            if check:
                if not os.path.exists(p) or open(p, "rb").read() != data:
                    differ.append(p)
            else:
                with open(p, "wb") as f:
                    f.write(data)
        for extra in sorted(present - set(seeds)):
            if extra.startswith("regress_"):
                continue  # a finding kept as a regression seed (docs/fuzzing.md)
            if check:
                differ.append(os.path.join(d, extra) + " (not generated)")
            else:
                os.remove(os.path.join(d, extra))
    if differ:
        print("gen_corpus: seeds differ from the generator:\n  " + "\n  ".join(differ))
        return 1
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="compare instead of writing")
    return write(ap.parse_args().check)


if __name__ == "__main__":
    sys.exit(main())
