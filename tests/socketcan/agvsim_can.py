#!/usr/bin/env python3
"""agv-sim's board link through a real SocketCAN interface (ctest socketcan.agvsim_can).

  agvsim_can.py AGV_SIM DBC SCENARIO FAULT_SCENARIO [--iface vcan0]

Run with the interface up (tools/canvm.py run). Checks:
  1. `agv-sim --can vcan0 --candump a.log` runs the scenario to its criteria while another
     program puts foreign frames on vcan0 (cangen, id 0x555), and `candump -L vcan0` captures
     the traffic;
  2. the run is the one without --can: the same report (wall time aside), the same logs and
     the same candump file, byte for byte - the bus model decides, the socket carries;
  3. what candump captured (the foreign frames aside) is agv-sim's own --candump file, frame
     for frame, in order;
  4. cantools decodes both with the DBC to the same signals, and every frame of the run is a
     frame of the DBC (`cantools decode` in process, as vcan_interop does);
  5. canplayer replays agv-sim's candump file onto vcan0 and candump sees the same frames;
  6. a fault scenario (errors and bus-off inside the bus model) is the same with and without
     --can too.
"""
import argparse
import filecmp
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import vcan_interop  # noqa: E402  (its candump listener, log-line parser, cantools decode)

T0 = time.monotonic()
FOREIGN = 0x555
SYNC, END = ("7FF#53594E43", 0x7FF), ("7FE#454E44", 0x7FE)


def say(msg):
    print(f"agvsim_can [{time.monotonic() - T0:5.1f} s]: {msg}", flush=True)


def fail(msg):
    say(f"FAIL: {msg}")
    sys.exit(1)


def run(agv, scenario, out, tag, can=None):
    rep, logs, dump = (os.path.join(out, f"{tag}_{n}") for n in ("report.json", "logs", "dump.log"))
    argv = [agv, "--scenario", scenario, "--report", rep, "--log-dir", logs, "--candump", dump,
            "--quiet"] + (["--can", can] if can else [])
    r = subprocess.run(argv, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        fail(f"{' '.join(argv)}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
    with open(rep) as f:
        report = json.load(f)
    report.pop("wall_time_s")
    return report, logs, dump


def same_run(a, b, what):
    (ra, la, da), (rb, lb, db) = a, b
    if ra != rb:
        fail(f"{what}: the reports differ with and without --can")
    cmp = filecmp.dircmp(la, lb)
    if cmp.left_only or cmp.right_only or any(
            not filecmp.cmp(os.path.join(la, n), os.path.join(lb, n), shallow=False)
            for n in cmp.common_files):
        fail(f"{what}: the logs differ with and without --can")
    if not filecmp.cmp(da, db, shallow=False):
        fail(f"{what}: the candump files differ with and without --can")


def dump_frames(path):
    with open(path) as f:
        return [vcan_interop.log_frame(line.rstrip("\n")) for line in f if line.strip()]


def between(lines):
    """Frames of candump -L lines after the last SYNC before END, foreign ones left out."""
    frames = [vcan_interop.log_frame(x) for x in lines]
    ids = [f[0] for f in frames]
    if SYNC[1] not in ids or END[1] not in ids:
        fail("candump: SYNC or END missing")
    start = len(ids) - 1 - ids[::-1].index(SYNC[1])
    return [f for f in frames[start + 1:ids.index(END[1], start)] if f[0] not in
            (FOREIGN, SYNC[1])]


def listen(iface, wait):
    """A candump -L listener that has seen a SYNC frame."""
    d = vcan_interop.Listener(["candump", "-L", iface])
    deadline = time.monotonic() + wait
    while True:
        subprocess.run(["cansend", iface, SYNC[0]], check=True)
        time.sleep(0.1)
        d.poll()
        if any(vcan_interop.log_frame(x)[0] == SYNC[1] for x in d.lines):
            return d
        if time.monotonic() > deadline:
            fail(f"candump saw no SYNC frame on {iface} in {wait:g} s")


def finish(d, iface, wait):
    subprocess.run(["cansend", iface, END[0]], check=True)
    deadline = time.monotonic() + wait
    while not any(vcan_interop.log_frame(x)[0] == END[1] for x in d.lines):
        if time.monotonic() > deadline:
            fail(f"candump saw no END frame on {iface}")
        time.sleep(0.1)
        d.poll()
    d.stop()
    return between(d.lines)


def decoded(db, frames):
    out = []
    for ident, ext, remote, data in frames:
        if ext or remote:
            fail(f"frame {ident:X}: extended or remote on the board link")
        try:
            out.append((db.get_message_by_frame_id(ident).name,
                        db.decode_message(ident, data, decode_choices=False)))
        except KeyError:
            fail(f"frame {ident:03X} is not in the DBC")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("agv_sim")
    ap.add_argument("dbc")
    ap.add_argument("scenario")
    ap.add_argument("fault_scenario")
    ap.add_argument("--iface", default="vcan0")
    ap.add_argument("--wait", type=float, default=120)
    a = ap.parse_args()
    import cantools
    db = cantools.database.load_file(a.dbc)
    out = tempfile.mkdtemp(prefix="agvsim_can_", dir=os.getcwd())

    # 1. Through vcan0, with foreign traffic, candump watching.
    d = listen(a.iface, a.wait)
    gen = subprocess.Popen(["cangen", a.iface, "-I", f"{FOREIGN:X}", "-L", "2", "-D", "i",
                            "-g", "5"])
    try:
        with_can = run(a.agv_sim, a.scenario, out, "can", a.iface)
    finally:
        gen.terminate()
        gen.wait()
    captured = finish(d, a.iface, a.wait)
    say(f"--can {a.iface}: {with_can[0]['link']['frames']} frames, outcome "
        f"{with_can[0]['outcome']}; candump captured {len(captured)} of them")

    # 2. The same run without the socket.
    same_run(with_can, run(a.agv_sim, a.scenario, out, "model"), a.scenario)
    say("the run with --can is the run without it: report, logs and candump file")

    # 3. candump's capture is agv-sim's candump file.
    own = dump_frames(with_can[2])
    if len(own) != with_can[0]["link"]["frames"]:
        fail(f"the candump file has {len(own)} frames, the report {with_can[0]['link']['frames']}")
    if captured != own:
        n = next((i for i, (x, y) in enumerate(zip(captured, own)) if x != y),
                 min(len(captured), len(own)))
        fail(f"candump and agv-sim's file differ at frame {n}: "
             f"{captured[n:n + 1]} vs {own[n:n + 1]} ({len(captured)} vs {len(own)} frames)")
    say(f"candump -L {a.iface} saw agv-sim's {len(own)} frames in order")

    # 4. cantools: the same signals; `cantools decode` reads the file.
    if decoded(db, captured) != decoded(db, own):
        fail("cantools decodes candump's capture and agv-sim's file differently")
    with open(with_can[2]) as f:
        text = f.read()
    lines = vcan_interop.cantools_decode(["--single-line", a.dbc], text)
    names = {m.name for m in db.messages}
    bad = [x for x in lines if x.split(" :: ", 1)[-1].split("(")[0] not in names]
    if len(lines) != len(own) or bad:
        fail(f"cantools decode: {len(lines)} lines for {len(own)} frames, not decoded: {bad[:3]}")
    say(f"cantools decode {os.path.basename(a.dbc)}: every one of the {len(lines)} frames")

    # 5. canplayer replays the file.
    d = listen(a.iface, a.wait)
    subprocess.run(["canplayer", "-I", with_can[2], "-t", f"{a.iface}={a.iface}"], check=True,
                   timeout=300)
    replayed = finish(d, a.iface, a.wait)
    if replayed != own:
        fail(f"canplayer replayed {len(replayed)} frames, not the file's {len(own)}")
    say(f"canplayer replayed the {len(own)} frames; candump saw them all")

    # 6. Faults stay inside the model.
    fault = run(a.agv_sim, a.fault_scenario, out, "fault_can", a.iface)
    same_run(fault, run(a.agv_sim, a.fault_scenario, out, "fault_model"), a.fault_scenario)
    say(f"{os.path.basename(a.fault_scenario)}: {fault[0]['link']['errors']} error frames, "
        f"{fault[0]['link']['bus_off']} bus-off, the same with --can")
    say("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
