#!/usr/bin/env python3
"""Record the odometer/gyro pulse stream of the groundnav vector program (issue 5).

Run by firmware/groundnav/CMakeLists.txt at build time:

  tools/gen_gnav_stream.py --out build/.../gnav_stream.h

The stream comes from exact tricycle kinematics: the rear-axle centre follows arcs of
constant curvature k (a constant steering angle atan(L k)); the steered front wheel, L ahead,
travels sqrt(1 + L^2 k^2) times as far as the rear axle, and every dl of front-wheel travel is
one odometer pulse. The gyro emits an edge each time the heading crosses a threshold; the
thresholds lie half a step either side of the start heading (the start is a cell centre).
Events are ordered by front-wheel travel; an edge and a pulse at the same travel: edge first.

The path (wheelbase 0.762 m, dl 0.01 in, 0.25 degree steps) visits every branch of the dl
handler: straights (short and 2.6 m long intervals), gentle and tight arcs, an S-curve
(reversals of the heading), steering past 80 degrees (too few pulses per step), reverse
travel, and a heading that jitters across one threshold; beacon sightings throughout, so
that latches fall into every kind of interval the heading estimate distinguishes.

Encoding (uint16 words): kind << 13 | count. kind 0: count pulses (1..8191); 1: gyro up;
2: gyro down; 3: beacon sighted; 4: reverse on; 5: reverse off; 6: print the pose.
"""
import argparse
import math

L = 0.762
DL = 0.000254
STEP = math.radians(0.25)

# (front-wheel travel in metres or None, rear curvature 1/m, backwards, heading change in
#  degrees or None): an arc runs until its heading change (if given) or its front travel.
PATH = [
    ("line", 0.40),
    ("arc", 1 / 3.0, 30.0),      # gentle left
    ("line", 0.30),
    ("arc", -1 / 1.5, 45.0),     # right
    ("arc", 1 / 1.5, 45.0),      # S: left again
    ("line", 2.60),              # long interval: the large-count branches
    ("arc", 1 / 0.8, 60.0),      # tight left
    ("arc", 1 / 0.12, 20.0),     # steering ~81 degrees: too few pulses per step
    ("line", 0.20),
    ("rev", True),
    ("arc", -1 / 2.0, 25.0),     # backwards, steering right
    ("line", 0.30),
    ("rev", False),
    ("wiggle", 3.0, 8),          # heading jitters across a threshold
    ("arc", 1 / 5.0, 15.0),
    ("line", 0.50),
]


def simulate():
    events = []  # (kind, count)
    travel = 0.0      # front-wheel travel, metres
    next_pulse = DL * 0.37
    heading = 0.0     # relative to the start, radians
    cell = 0
    back = False
    beacon_every = 0.047  # about 21 sightings per metre: latches in every kind of interval
    next_beacon = 0.02

    def emit_pulses(k):
        while k > 0:
            c = min(k, 8191)
            if events and events[-1][0] == 0 and events[-1][1] + c <= 8191:
                events[-1] = (0, events[-1][1] + c)
            else:
                events.append((0, c))
            k -= c

    def run(front, curv):
        """Travel `front` metres of front wheel at rear curvature curv."""
        nonlocal travel, next_pulse, heading, cell, next_beacon
        ratio = 1.0 / math.sqrt(1.0 + (L * curv) ** 2)  # rear per front
        sgn = -1.0 if back else 1.0
        end = travel + front
        while True:
            # next threshold crossing of the heading
            rate = sgn * curv * ratio  # heading per front metre
            t_edge = math.inf
            if rate > 0:
                t_edge = travel + ((cell + 0.5) * STEP - heading) / rate
            elif rate < 0:
                t_edge = travel + ((cell - 0.5) * STEP - heading) / rate
            t = min(t_edge, end, next_beacon)
            pulses = 0
            while next_pulse < t or (next_pulse == t and t != t_edge):
                pulses += 1
                next_pulse += DL
            emit_pulses(pulses)
            heading += rate * (t - travel)
            travel = t
            if t == t_edge:
                if rate > 0:
                    cell += 1
                    events.append((1, 0))
                else:
                    cell -= 1
                    events.append((2, 0))
            elif t == next_beacon:
                events.append((3, 0))
                next_beacon += beacon_every
            else:
                return

    for seg in PATH:
        if seg[0] == "line":
            run(seg[1], 0.0)
        elif seg[0] == "arc":
            curv, deg = seg[1], seg[2]
            ratio = math.sqrt(1.0 + (L * curv) ** 2)
            run(math.radians(deg) / abs(curv) * ratio, curv)
        elif seg[0] == "rev":
            back = seg[1]
            events.append((4 if back else 5, 0))
        elif seg[0] == "wiggle":
            # across the threshold above and back, seg[2] times, on arcs of radius seg[1]
            radius, times = seg[1], seg[2]
            ratio = math.sqrt(1.0 + (L / radius) ** 2)
            up = (cell + 0.5) * STEP - heading + math.radians(0.05)
            run(up * radius * ratio, 1 / radius)
            for i in range(times):
                swing = math.radians(0.1)
                run(swing * radius * ratio, (-1 if i % 2 == 0 else 1) / radius)
        events.append((6, 0))
    return events


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    ev = simulate()
    words = [(k << 13) | c for k, c in ev]
    pulses = sum(c for k, c in ev if k == 0)
    with open(a.out, "w") as f:
        f.write("/* generated by tools/gen_gnav_stream.py: do not edit */\n")
        f.write(f"/* {pulses} odometer pulses, {sum(1 for k, _ in ev if k in (1, 2))} gyro edges */\n")
        f.write("#include <stdint.h>\n\n")
        f.write(f"#define GNAV_STREAM_N {len(words)}u\n")
        f.write(f"static const uint16_t gnav_stream[GNAV_STREAM_N] = {{\n")
        for i in range(0, len(words), 12):
            f.write("    " + ", ".join(f"0x{w:04x}u" for w in words[i:i + 12]) + ",\n")
        f.write("};\n")


if __name__ == "__main__":
    main()
