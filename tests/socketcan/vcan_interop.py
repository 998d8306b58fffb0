#!/usr/bin/env python3
"""can-utils, raw SocketCAN, python-can and cantools agree on a real vcan interface.

Run with the interface up, e.g. `tools/canvm.py run -- tests/socketcan/vcan_interop.py`.
Frames sent with `cansend` must reach `candump -L` (log format), `candump` (default format), a
raw CAN_RAW socket and python-can byte for byte; a frame sent from the raw socket must reach
candump; a tiny DBC written here decodes a frame with the cantools library and with
`cantools decode` fed candump's output, to physical values worked out by hand. Every expected
value below is typed from the frame definitions, not taken from the tools under test.
"""
import argparse
import contextlib
import io
import os
import re
import select
import socket
import struct
import subprocess
import sys
import tempfile
import time

CAN_EFF_FLAG, CAN_RTR_FLAG = 0x80000000, 0x40000000
SYNC = ("7FF#53594E43", 0x7FF)  # sent until every listener has seen it
END = ("7FE#454E44", 0x7FE)      # sent once after the frames under test
# cansend argument -> (identifier, extended, remote, data bytes)
FRAMES = [
    ("123#DEADBEEF", (0x123, False, False, bytes([0xDE, 0xAD, 0xBE, 0xEF]))),
    ("1ABCDEF0#0011223344556677",
     (0x1ABCDEF0, True, False, bytes([0x00, 0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77]))),
    ("000#", (0x000, False, False, b"")),
    ("321#R", (0x321, False, True, b"")),
    ("100#01.02.03", (0x100, False, False, bytes([1, 2, 3]))),
    # NAV_STATE of the DBC below: speed -1.5 m/s = -1500 = 0xFA24 (LE: 24 FA), heading
    # 90.00 deg = 9000 = 0x2328 (LE: 28 23), mode 5 (FOLLOW) in the low nibble of byte 4.
    ("2A0#24FA282305000000",
     (0x2A0, False, False, bytes([0x24, 0xFA, 0x28, 0x23, 0x05, 0, 0, 0]))),
]
DBC = """VERSION ""

NS_ :

BS_:

BU_: NAV MAIN

BO_ 672 NAV_STATE: 8 NAV
 SG_ speed_mps : 0|16@1- (0.001,0) [-32.768|32.767] "m/s" MAIN
 SG_ heading_deg : 16|16@1+ (0.01,0) [0|655.35] "deg" MAIN
 SG_ mode : 32|4@1+ (1,0) [0|15] "" MAIN

VAL_ 672 mode 0 "IDLE" 5 "FOLLOW" ;
"""
NAV_STATE_DECODED = {"speed_mps": -1.5, "heading_deg": 90.0, "mode": "FOLLOW"}
# Encoded by cantools and sent from the raw socket: speed 2.0 m/s = 2000 = 0x07D0, heading
# 180.5 deg = 18050 = 0x4682, mode IDLE = 0.
NAV_STATE_ENCODE = ({"speed_mps": 2.0, "heading_deg": 180.5, "mode": "IDLE"},
                    "2A0#D007824600000000",
                    (0x2A0, False, False, bytes([0xD0, 0x07, 0x82, 0x46, 0, 0, 0, 0])))
RAW_SENT = (0x0A5, bytes([0xCA, 0xFE]), "0A5#CAFE")  # raw socket -> candump


T0 = time.monotonic()


def say(msg):
    print(f"vcan_interop [{time.monotonic() - T0:5.1f} s]: {msg}", flush=True)


def fail(msg):
    say(f"FAIL: {msg}")
    sys.exit(1)


def log_frame(line):
    """(id, extended, remote, data) of a `candump -L` line '(ts) iface ID#DATA'."""
    m = re.fullmatch(r"\(\d+\.\d{6}\) (\S+) ([0-9A-F]{3}|[0-9A-F]{8})#(R|(?:[0-9A-F]{2})*)",
                     line)
    if not m:
        fail(f"not a candump log line: {line!r}")
    ident, data = m.group(2), m.group(3)
    return (int(ident, 16), len(ident) == 8, data == "R",
            b"" if data == "R" else bytes.fromhex(data))


def default_frame(line):
    """(id, extended, remote, data) of a default `candump` line 'iface ID [n] bytes'."""
    m = re.fullmatch(r"\s*(\S+)\s+([0-9A-F]{3}|[0-9A-F]{8})\s+\[(\d)\]\s*(remote request|"
                     r"(?:[0-9A-F]{2}(?: |$))*)\s*", line)
    if not m:
        fail(f"not a candump line: {line!r}")
    remote = m.group(4) == "remote request"
    data = b"" if remote else bytes.fromhex(m.group(4))
    if not remote and len(data) != int(m.group(3)):
        fail(f"candump line with a length that does not match its bytes: {line!r}")
    return int(m.group(2), 16), len(m.group(2)) == 8, remote, data


def raw_frame(buf):
    """(id, extended, remote, data) of a struct can_frame read from a CAN_RAW socket."""
    can_id, dlc, data = struct.unpack("=IB3x8s", buf)
    return (can_id & (0x1FFFFFFF if can_id & CAN_EFF_FLAG else 0x7FF),
            bool(can_id & CAN_EFF_FLAG), bool(can_id & CAN_RTR_FLAG),
            b"" if can_id & CAN_RTR_FLAG else data[:dlc])


class Listener:
    """A candump process whose lines are collected without blocking."""

    def __init__(self, argv):
        self.p = subprocess.Popen(argv, stdout=subprocess.PIPE, text=True)
        self.lines, self.buf = [], ""

    def poll(self):
        while select.select([self.p.stdout], [], [], 0)[0]:
            chunk = os.read(self.p.stdout.fileno(), 65536).decode()
            if not chunk:
                break
            self.buf += chunk
            *done, self.buf = self.buf.split("\n")
            self.lines += done

    def stop(self):
        self.p.terminate()
        self.p.wait()


def cansend(iface, frame):
    subprocess.run(["cansend", iface, frame], check=True)


def frames_between(items, ident_of, what):
    """The items after the last SYNC and before END (both must be there)."""
    ids = [ident_of(x) for x in items]
    if SYNC[1] not in ids or END[1] not in ids:
        fail(f"{what}: SYNC or END missing from {items!r}")
    start = len(ids) - 1 - ids[::-1].index(SYNC[1])
    return items[start + 1:ids.index(END[1], start)]


def cantools_decode(argv, stdin):
    """The lines `cantools decode ARGV...` prints for this stdin: the command line tool's own
    decode subcommand (its argument parser and handler), called in this process. Not through
    `cantools`'s entry point, which also loads the plot subcommand and matplotlib, nor through
    a second Python: each costs seconds, and tens in the VM."""
    from cantools.subparsers import decode
    ap = argparse.ArgumentParser(prog="cantools")
    decode.add_subparser(ap.add_subparsers(dest="subcommand", required=True))
    args = ap.parse_args(["decode"] + argv)
    saved = sys.stdin
    sys.stdin = io.StringIO(stdin)
    out = io.StringIO()
    try:
        with contextlib.redirect_stdout(out):
            args.func(args)
    finally:
        sys.stdin = saved
    return out.getvalue().splitlines()


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--iface", default="vcan0", help="CAN interface, up (default vcan0)")
    ap.add_argument("--wait", type=float, default=120, help="seconds to wait for listeners")
    args = ap.parse_args()
    import can
    import cantools
    say(f"python-can {can.__version__} and cantools {cantools.__version__} imported")

    raw = socket.socket(socket.AF_CAN, socket.SOCK_RAW, socket.CAN_RAW)
    raw.bind((args.iface,))
    bus = can.Bus(interface="socketcan", channel=args.iface)
    dumps = {"log": Listener(["candump", "-L", args.iface]),
             "default": Listener(["candump", args.iface])}
    parse = {"log": log_frame, "default": default_frame}
    try:
        # Listeners are ready once each has seen a SYNC frame.
        deadline = time.monotonic() + args.wait
        while True:
            cansend(args.iface, SYNC[0])
            time.sleep(0.1)
            for d in dumps.values():
                d.poll()
            if all(any(parse[k](x)[0] == SYNC[1] for x in d.lines) for k, d in dumps.items()):
                break
            if time.monotonic() > deadline:
                fail(f"candump saw no SYNC frame on {args.iface} in {args.wait:g} s")
        for arg, _ in FRAMES:
            cansend(args.iface, arg)
        db = cantools.database.load_string(DBC, database_format="dbc")
        msg = db.get_message_by_name("NAV_STATE")
        raw.send(struct.pack("=IB3x8s", RAW_SENT[0], len(RAW_SENT[1]), RAW_SENT[1]))
        payload = msg.encode(NAV_STATE_ENCODE[0])
        raw.send(struct.pack("=IB3x8s", msg.frame_id, len(payload), payload))
        cansend(args.iface, END[0])
        while not all(any(parse[k](x)[0] == END[1] for x in d.lines) for k, d in dumps.items()):
            if time.monotonic() > deadline:
                fail(f"candump saw no END frame on {args.iface}")
            time.sleep(0.05)
            for d in dumps.values():
                d.poll()
    finally:
        for d in dumps.values():
            d.stop()

    want = [f for _, f in FRAMES]
    sent_raw = [(RAW_SENT[0], False, False, RAW_SENT[1]), NAV_STATE_ENCODE[2]]
    for kind, d in dumps.items():
        got = [parse[kind](x) for x in frames_between(d.lines, lambda x: parse[kind](x)[0],
                                                      f"candump ({kind} format)")]
        if got != want + sent_raw:
            fail(f"candump ({kind} format) saw {got}, want {want + sent_raw}")
    log_lines = frames_between(dumps["log"].lines, lambda x: log_frame(x)[0], "candump -L")
    if log_lines[-2].split(" ", 1)[1] != f"{args.iface} {RAW_SENT[2]}":
        fail(f"candump -L shows the raw socket's frame as {log_lines[-2]!r}")
    if log_lines[-1].split(" ", 1)[1] != f"{args.iface} {NAV_STATE_ENCODE[1]}":
        fail(f"cantools encoded {NAV_STATE_ENCODE[0]} as {log_lines[-1]!r}, want "
             f"{NAV_STATE_ENCODE[1]}")
    say(f"candump -L and candump agree with cansend on {len(want)} frames and see the raw "
          "socket's 2")

    # The raw socket received everything cansend sent (and not its own frames).
    got = []
    raw.settimeout(5)
    while True:
        f = raw_frame(raw.recv(16))
        got.append(f)
        if f[0] == END[1]:
            break
    got = frames_between(got, lambda f: f[0], "raw socket")
    if got != want:
        fail(f"raw CAN_RAW socket saw {got}, want {want}")
    say(f"a raw CAN_RAW socket received the same {len(want)} frames")

    got = []
    while True:
        m = bus.recv(timeout=5)
        if m is None:
            fail("python-can received nothing within 5 s")
        got.append((m.arbitration_id, m.is_extended_id, m.is_remote_frame,
                    b"" if m.is_remote_frame else bytes(m.data)))
        if m.arbitration_id == END[1]:
            break
    bus.shutdown()
    got = frames_between(got, lambda f: f[0], "python-can")
    if got != want + sent_raw:
        fail(f"python-can saw {got}, want {want + sent_raw}")
    say(f"python-can (interface socketcan) received the same {len(want)} frames and the raw "
          "socket's 2")

    nav = want[-1]
    decoded = db.decode_message(nav[0], nav[3])
    if {k: (str(v) if k == "mode" else v) for k, v in decoded.items()} != NAV_STATE_DECODED:
        fail(f"cantools decoded NAV_STATE as {decoded}, want {NAV_STATE_DECODED}")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "tiny.dbc")
        with open(path, "w") as f:
            f.write(DBC)
        lines = [x for x in dumps["default"].lines if default_frame(x)[0] == 0x2A0]
        out = cantools_decode(["--single-line", path], "\n".join(lines) + "\n")
    want_cli = ["NAV_STATE(speed_mps: -1.5 m/s, heading_deg: 90.0 deg, mode: FOLLOW)",
                "NAV_STATE(speed_mps: 2.0 m/s, heading_deg: 180.5 deg, mode: IDLE)"]
    if len(out) != 2 or [x.split(" :: ", 1)[-1] for x in out] != want_cli:
        fail(f"`candump {args.iface} | cantools decode` printed {out}, want {want_cli}")
    say("cantools decodes NAV_STATE from the frame and from `candump | cantools decode`")
    say("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
