#!/usr/bin/env python3
"""The DBC and the firmware agree, both ways (ctest link.dbc_roundtrip, label unit).

  dbc_test.py CODEC firmware/link/cyclopion.dbc

CODEC is tests/link/linkmsg_codec (the firmware's linkmsg.c on the host, JSON Lines).
  1. Firmware -> cantools: every message, with random and extreme raw field values, is encoded
     by the firmware; cantools decodes each frame with the DBC; every signal is compared with
     the field it names: raw, and scaled against the units the firmware's types have (Q15.16
     metres, 32-bit binary angles in degrees: fx/fx.h), worked out here. The B frames' tag
     is checked against a CRC-8 written here from its definition (polynomial 0x07, initial 0,
     not reflected; its check value for "123456789" is 0xF4).
  2. cantools -> firmware: physical values encoded by cantools with the DBC (the tag added
     here) are decoded by the firmware to the same fields.
  3. The DBC has exactly the frames the firmware sends: ids, lengths, and for each pair the
     B frame at the A frame's id + 1.
"""
import json
import random
import subprocess
import sys

import cantools

# The firmware's units (fx/fx.h): physical value of one raw step, by signal name.
UNITS = {"x": 2.0**-16, "y": 2.0**-16, "heading": 360.0 / 2**32,
         # FIX_QUALITY (link/linkmsg.h): 2^-18 m per mrad, 2^-8 m, 2^-14 turn
         "quality": 2.0**-18, "err": 2.0**-8, "resid": 360.0 / 2**14}


def crc8(data):
    crc = 0
    for byte in data:
        for i in range(7, -1, -1):
            bit = ((crc >> 7) ^ (byte >> i)) & 1
            crc = ((crc << 1) & 0xFF) ^ (0x07 if bit else 0)
    return crc


class Codec:
    def __init__(self, path):
        self.p = subprocess.Popen([path], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                  text=True)

    def ask(self, req):
        self.p.stdin.write(json.dumps(req) + "\n")
        self.p.stdin.flush()
        return json.loads(self.p.stdout.readline())

    def close(self):
        self.p.stdin.close()
        self.p.wait(timeout=10)


def main():
    codec_path, dbc_path = sys.argv[1], sys.argv[2]
    assert crc8(b"123456789") == 0xF4, "the test's own CRC-8"
    db = cantools.database.load_file(dbc_path)
    rng = random.Random(14)
    codec = Codec(codec_path)
    failures = []
    checked = 0

    def fail(msg):
        failures.append(msg)
        print("FAIL " + msg)

    # The firmware's messages and their fields: from the codec, by encoding zeros.
    names = ["STOP", "POSE", "FIX", "FIX_ACK", "FIX_QUALITY", "LATCH_REQ", "LATCH", "DIR",
             "MAIN_HEARTBEAT", "NAV_HEARTBEAT"]
    frames_sent = {}
    for name in names:
        pair = [m for m in db.messages if m.name in (name, name + "_A", name + "_B")]
        sigs = [s for m in pair for s in m.signals if s.name != "tag"]
        if not sigs:
            fail(f"{name}: not in the DBC")
            continue
        for trial in range(300):
            raw = {}
            for s in sigs:
                lo = -(1 << (s.length - 1)) if s.is_signed else 0
                hi = (1 << (s.length - 1)) - 1 if s.is_signed else (1 << s.length) - 1
                raw[s.name] = (lo, hi, 0)[trial] if trial < 3 else rng.randint(lo, hi)
            ans = codec.ask({"op": "encode", "message": name, "fields": raw})
            if not ans.get("ok"):
                fail(f"{name}: the firmware does not encode {raw}: {ans}")
                break
            frames = [(f["id"], bytes.fromhex(f["data"])) for f in ans["frames"]]
            for fid, data in frames:
                frames_sent[fid] = len(data)
            # 1. cantools reads what the firmware wrote.
            got_raw, got_phys = {}, {}
            for fid, data in frames:
                m = db.get_message_by_frame_id(fid)
                if len(data) != m.length:
                    fail(f"{name}: frame 0x{fid:03X} has {len(data)} bytes, the DBC {m.length}")
                got_raw.update(m.decode(data, decode_choices=False, scaling=False))
                got_phys.update(m.decode(data, decode_choices=False))
            if len(frames) == 2 and got_raw.get("tag") != crc8(frames[0][1]):
                fail(f"{name}: tag {got_raw.get('tag')} is not the CRC-8 of the A frame")
            for s in sigs:
                if got_raw.get(s.name) != raw[s.name]:
                    fail(f"{name}.{s.name}: firmware wrote {raw[s.name]}, cantools reads "
                         f"{got_raw.get(s.name)}")
                want = raw[s.name] * UNITS.get(s.name, 1.0)
                if abs(got_phys[s.name] - want) > 1e-9 * max(1.0, abs(want)):
                    fail(f"{name}.{s.name}: raw {raw[s.name]} is {want} {s.unit or ''}, "
                         f"cantools says {got_phys[s.name]}")
            # 2. The firmware reads what cantools wrote (physical values, the tag added here).
            phys = {s.name: raw[s.name] * UNITS.get(s.name, 1.0) for s in sigs}
            out = []
            for m in pair:
                values = {s.name: phys[s.name] for s in m.signals if s.name != "tag"}
                if any(s.name == "tag" for s in m.signals):
                    values["tag"] = crc8(out[0][1])
                out.append((m.frame_id, m.encode(values, strict=True)))
            out.sort()
            ans = codec.ask({"op": "decode", "frames": [{"id": i, "data": d.hex()}
                                                         for i, d in out]})
            if not ans.get("ok") or ans.get("message") != name:
                fail(f"{name}: the firmware does not decode cantools' frames {out}: {ans}")
                break
            for s in sigs:
                if ans["fields"].get(s.name) != raw[s.name]:
                    fail(f"{name}.{s.name}: cantools wrote {phys[s.name]}, the firmware reads "
                         f"{ans['fields'].get(s.name)}, not {raw[s.name]}")
            checked += 1
    codec.close()
    # 3. The DBC has the frames the firmware sends, no more.
    dbc_frames = {m.frame_id: m.length for m in db.messages}
    if dbc_frames != frames_sent:
        fail(f"frames: the DBC has {sorted(dbc_frames.items())}, the firmware sends "
             f"{sorted(frames_sent.items())}")
    for m in db.messages:
        if m.name.endswith("_B") and db.get_message_by_frame_id(m.frame_id - 1).name != \
                m.name[:-2] + "_A":
            fail(f"{m.name}: not at its A frame's id + 1")
    print(f"{checked} messages both ways, {len(dbc_frames)} frames, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
