#!/usr/bin/env python3
"""agvcalc op "deadreckon" end to end (CONTRACT.md, docs/agvcalc.md), expected values from exact
geometry:
- straight runs along the heading (forwards, backwards) land at start + n dl (cos h, sin h);
- steady turns of the tricycle: the front wheel on a circle of radius r = p dl / step when the
  gyro steps every p pulses, the rear axle on R = sqrt(r^2 - L^2); the gyro reads the nearest
  step, so a steady turn from the start heading (the centre of its step) passes the first
  threshold after p/2 pulses: [[p//2, 0], [p, 1], ..., [p, K-1], [p - p//2, K]] ends K steps
  on, on the exact circle; left, right, and back along the same pulses to the start. Where an
  odometer pulse falls between its marks is not known (up to one pulse, 0.254 mm), nor where
  the gyro's threshold falls between two pulses: the tolerance is that pulse and a little;
  replaying a run's steps half a run late (before the fix) missed this quarter turn by 5.3 mm;
- the work bounds (pulses, gyro steps per line) and the nav board's range (+-32768 m, dl 2^27)
  are refused with ok:false naming the field and the value, just beyond; just inside, answered
  exactly; the next line is always answered.
Usage: deadreckon_test.py AGVCALC"""
import json
import math
import subprocess
import sys

L, DL, STEP = 0.762, 0.000254, 0.25
CFG = {"wheelbase_m": L, "dl_m": DL, "gyro_step_deg": STEP}
MAX_PULSES, MAX_STEPS = 2**24, 2**22

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL: " + what)


def ask(agvcalc, reqs):
    lines = "".join(json.dumps(r) + "\n" for r in reqs)
    out = subprocess.run([agvcalc], input=lines, capture_output=True, text=True, check=True)
    answers = [json.loads(l) for l in out.stdout.splitlines()]
    assert len(answers) == len(reqs), (len(answers), len(reqs))
    return answers


def dr(start, runs, **cfg):
    return dict({"op": "deadreckon", "start": start, "runs": runs}, **dict(CFG, **cfg))


def turn(p, k, sign):
    """A steady turn by k steps of one step every p pulses (sign: +1 left, -1 right)."""
    return [[p // 2, 0]] + [[p, sign * j] for j in range(1, k)] + [[p - p // 2, sign * k]]


def turn_back(p, k, sign):
    """Back over the same marks from step k to the start: the odometer's marks at whole
    pulses, the thresholds half way between two (p odd), the vehicle on the last mark."""
    return ([[-(p // 2), sign * k]] + [[-p, sign * j] for j in range(k - 1, 0, -1)] +
            [[-(p - p // 2), 0]])


def on_circle(x0, y0, h0_deg, p, k, sign):
    """Exact rear-axle pose after k steps of a steady turn, one step every p pulses."""
    beta = math.radians(STEP)
    r = p * DL / beta
    big_r = math.sqrt(r * r - L * L)
    h0 = math.radians(h0_deg)
    cx, cy = x0 - sign * big_r * math.sin(h0), y0 + sign * big_r * math.cos(h0)
    h = h0 + sign * k * beta
    return cx + sign * big_r * math.sin(h), cy - sign * big_r * math.cos(h), math.degrees(h) % 360


def near(a, exp, tol_m, tol_deg, what):
    if not a.get("ok"):
        check(False, f"{what}: refused: {a}")
        return
    ex, ey, eh = exp
    dh = (a["heading_deg"] - eh + 180) % 360 - 180
    print(f"{what}: x {a['x']:.6f} y {a['y']:.6f} h {a['heading_deg']:.6f}  exact "
          f"{ex:.6f} {ey:.6f} {eh:.6f}  error {math.hypot(a['x'] - ex, a['y'] - ey) * 1e3:.4f} mm "
          f"{dh:.5f} deg")
    check(math.hypot(a["x"] - ex, a["y"] - ey) <= tol_m, f"{what}: position off by more than {tol_m} m")
    check(abs(dh) <= tol_deg, f"{what}: heading off by more than {tol_deg} deg")


def refused(a, *needles, what):
    ok = not a.get("ok") and all(n in a.get("error", "") for n in needles)
    check(ok, f"{what}: expected ok:false naming {needles}, got {a}")


def main():
    agvcalc = sys.argv[1]
    st = {"x": 1.0, "y": 2.0, "heading_deg": 30.0}
    n = 100000
    p, k = 27, 360  # a quarter turn on r = 1.572 m (front wheel), R = 1.375 m (rear axle)
    reqs = [
        dr(st, [[n, 0]]),                                           # 0 straight
        dr(st, [[-n, 0]]),                                          # 1 backwards
        dr(st, [[n // 2, 0], [n // 2, 0]]),                         # 2 the same in two runs
        dr({"x": 1, "y": 2, "heading_deg": 90}, turn(p, k, +1)),    # 3 left quarter turn
        dr({"x": 1, "y": 2, "heading_deg": 90}, turn(p, k, -1)),    # 4 right quarter turn
        dr({"x": -3, "y": 5, "heading_deg": 200}, turn(41, 1440, +1)),  # 5 a whole circle
        dr({"x": 1, "y": 2, "heading_deg": 90}, turn(p, k, -1) + turn_back(p, k, -1)),  # 6
        dr(st, [[3937, 0], [0, 360]]),                              # 7 straight, turn in place
    ]
    a = ask(agvcalc, reqs)
    d = n * DL
    t = math.radians(30)
    near(a[0], (1 + d * math.cos(t), 2 + d * math.sin(t), 30.0), 5e-5, 1e-5, "straight 25.4 m")
    near(a[1], (1 - d * math.cos(t), 2 - d * math.sin(t), 30.0), 5e-5, 1e-5, "backwards 25.4 m")
    near(a[2], (1 + d * math.cos(t), 2 + d * math.sin(t), 30.0), 5e-5, 1e-5, "straight, two runs")
    near(a[3], on_circle(1, 2, 90, p, k, +1), 3e-4, 0.01, "left quarter turn, R 1.375 m")
    near(a[4], on_circle(1, 2, 90, p, k, -1), 3e-4, 0.01, "right quarter turn, R 1.375 m")
    near(a[5], on_circle(-3, 5, 200, 41, 1440, +1), 3e-4, 0.01, "whole circle, R 2.262 m")
    near(a[6], (1, 2, 90.0), 6e-4, 0.01, "right quarter turn and back")
    # a tricycle cannot turn in place (its front wheel would roll M = 13 pulses a step): the
    # nav board keeps the position and publishes the heading on the last step's threshold
    # (no pulse has moved it into the cell yet): 30 + 90 - 0.125 degrees
    t = 3937 * DL
    near(a[7], (1 + t * math.cos(math.radians(30)), 2 + t * math.sin(math.radians(30)), 119.875), 5e-5,
         1e-5, "turn in place")

    # the work per line
    big = {"x": 0, "y": 0, "heading_deg": 0}
    small_dl = dict(dl_m=3.1e-5, wheelbase_m=0.1)
    # the pulse count the nav board keeps: 2^27 - 1 of its dl (dl_m rounded to 2^-40 m)
    rng = "%.3f" % ((2**27 - 1) * round(3.1e-5 * 2**40) / 2**40)
    reqs = [
        dr(big, [[MAX_PULSES // 2, 0], [MAX_PULSES // 2 + 1, 0]]),
        dr(big, [[MAX_PULSES + 1, 0]]),
        dr(big, [[0, MAX_STEPS], [0, MAX_STEPS - 1]]),
        dr(big, [[0, MAX_STEPS // 2], [0, -MAX_STEPS // 2 - 1]]),
        dr(big, [[2.5, 0]]),
        dr(big, [[0, 1e300]]),
        dr(big, [[0, 2], [7, "3"]]),
        # the range: Q15.16 metres
        dr({"x": 29000, "y": 0, "heading_deg": 0}, [[2000000, 0]], dl_m=0.00195),
        dr({"x": 29000, "y": 0, "heading_deg": 0}, [[1900000, 0]], dl_m=0.00195),
        dr({"x": 0, "y": -29000, "heading_deg": 270}, [[2000000, 0]], dl_m=0.00195),
        # the range: dl * 2^27 (a small pulse)
        dr({"x": 5000, "y": 0, "heading_deg": 0}, [], **small_dl),
        dr({"x": 0, "y": -4161, "heading_deg": 0}, [], **small_dl),
        dr({"x": 4100, "y": 0, "heading_deg": 0}, [[2500000, 0]], **small_dl),
        dr({"x": 4100, "y": 0, "heading_deg": 0}, [[1900000, 0]], **small_dl),
        dr({"x": 0, "y": -4100, "heading_deg": 270}, [[2500000, 0]], **small_dl),
        dr({"x": 4100, "y": 0, "heading_deg": 0}, [[2500000, 0], [-2500000, 0]], **small_dl),
        dr(big, [[10, 0]]),
    ]
    a = ask(agvcalc, reqs)
    refused(a[0], "runs[1][0] (n_pulses)", "8388609", "16777217", "16777216 allowed",
            what="pulses per line")
    refused(a[1], "runs[0][0] (n_pulses)", "16777217", "16777216 allowed", what="pulses in one run")
    refused(a[2], "runs[1][1] (gyro_count): 4194303", "to 4194305", "4194304 allowed",
            what="steps per line")
    refused(a[3], "runs[1][1] (gyro_count)", "-2097153", "6291457", what="steps back and forth")
    refused(a[4], "runs[0][0] (n_pulses): 2.5 is not a whole number", what="fraction")
    refused(a[5], "runs[0][1] (gyro_count)", "1e+300", what="huge gyro count")
    refused(a[6], "runs[1][1] (gyro_count): expected a number", what="string")
    refused(a[7], "x reaches +32768 m", what="beyond +32768 m")
    # (a start converts to pulses with the nav board's pulses per metre in Q16: 1.5e-8 of 29 km)
    near(a[8], (29000 + 1900000 * 0.00195, 0, 0.0), 5e-4, 1e-5, "just inside +32768 m")
    refused(a[9], "y reaches -32768 m", what="beyond -32768 m")
    refused(a[10], "start.x: 5000 m", rng, what="start beyond dl 2^27")
    refused(a[11], "start.y: -4161 m", rng, what="start beyond -dl 2^27")
    refused(a[12], "x = 4177.500 m", rng, what="result beyond dl 2^27")
    near(a[13], (4100 + 1900000 * 3.1e-5, 0, 0.0), 1e-4, 1e-5, "just inside dl 2^27")
    refused(a[14], "y = -4177.500 m", rng, what="result beyond -dl 2^27")
    # out and back: the firmware's state is 64-bit; only the pose it hands out is bounded
    near(a[15], (4100, 0, 0.0), 1e-4, 1e-5, "out of range and back")
    near(a[16], (10 * DL, 0, 0.0), 1e-5, 1e-5, "the next line still answered")

    if failures:
        print(f"{len(failures)} failures")
        return 1
    print("deadreckon: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
