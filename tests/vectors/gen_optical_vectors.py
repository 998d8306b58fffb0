#!/usr/bin/env python3
"""Write tests/vectors/optical_vectors_data.h: recorded goniometer revolutions for the optical
vector program (tests/vectors/optical_vectors.c).

Each revolution is what the capture handlers see on the main board: the index pulse, the
rising and falling edges of the photodetector (timer counts of the 50,000-count angle clock,
16-bit, wrapping) and the next index pulse; plus the map, the approximate (dead-reckoning)
pose at the reference instant (the second index pulse) and, for revolutions taken while
driving, the dead-reckoning pose the nav board latched at each sighting. The geometry is exact
double precision (beacon posts 0.08 m wide, apparent width 2 asin(D / 2d)); pulses that
overlap merge as on the photodetector; narrow glints and occlusions are mixed in.

Deterministic (fixed seeds): run it again and the file does not change. Usage:
    tools: python3 tests/vectors/gen_optical_vectors.py > tests/vectors/optical_vectors_data.h
"""
import math
import random

TAU = 2 * math.pi
CPT = 50000
REV_S = 0.5          # 2 revolutions per second
D = 0.08


def q16(v):
    return int(round(v * 65536))


def ang(rad):
    return int(round((rad % TAU) / TAU * 2**32)) % 2**32


def pose_at(motion, t):
    """True pose at time t (s) after the first index pulse."""
    kind, p0, phi0, v, radius = motion
    if kind == "still" or v == 0:
        return p0[0], p0[1], phi0
    if kind == "line":
        return p0[0] + v * t * math.cos(phi0), p0[1] + v * t * math.sin(phi0), phi0
    w = v / radius  # arc, left turn
    phi = phi0 + w * t
    return (p0[0] + radius * (math.sin(phi) - math.sin(phi0)),
            p0[1] - radius * (math.cos(phi) - math.cos(phi0)), phi)


def edge_time(motion, b, side, t_guess):
    """Time at which the mirror (2 rev/s, 0 at the index pulse) points at one edge of post b."""
    t = t_guess
    for _ in range(30):
        x, y, phi = pose_at(motion, t)
        d = math.hypot(b[0] - x, b[1] - y)
        hw = math.asin(min(1.0, D / (2 * d)))
        a = (math.atan2(b[1] - y, b[0] - x) - phi + side * hw) % TAU
        tn = a / TAU * REV_S
        # stay on the branch near the guess
        while tn - t > REV_S / 2:
            tn -= REV_S
        while t - tn > REV_S / 2:
            tn += REV_S
        if abs(tn - t) < 1e-12:
            break
        t = tn
    return t


def revolution(rng, bmap, motion, visible, glints):
    """Pulses of one revolution: list of (t_rise, t_fall, beacons)."""
    pulses = []
    for k in visible:
        x, y, phi = pose_at(motion, 0.0)
        a = (math.atan2(bmap[k][1] - y, bmap[k][0] - x) - phi) % TAU
        t0 = edge_time(motion, bmap[k], -1, a / TAU * REV_S)
        t1 = edge_time(motion, bmap[k], +1, t0)
        if t0 < 0 or t1 >= REV_S:
            continue  # straddles an index pulse: lost with the partial turn
        pulses.append([t0, t1, [k]])
    for g in glints:
        w = (1 + rng.randrange(3)) / CPT * REV_S
        pulses.append([g, g + w, []])
    pulses.sort()
    merged = []
    for p in pulses:
        if merged and p[0] <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], p[1])
            merged[-1][2] += p[2]
        else:
            merged.append(p)
    return merged


def counts(t):
    return int(math.floor(t / REV_S * CPT))


def perimeter_map(rng, n, w, h):
    """n posts on the walls of a w x h room, none overlapping another (centres at least D
    apart: a map refuses overlapping posts)."""
    out = []
    while len(out) < n:
        side = rng.randrange(4)
        u = rng.random()
        p = [(u * w, 0), (w, u * h), (u * w, h), (0, u * h)][side]
        if all(math.hypot(p[0] - q[0], p[1] - q[1]) >= D for q in out):
            out.append(p)
    return [(q16(x) / 65536, q16(y) / 65536) for x, y in out]


def make_case(rng, bmap, motion, visible, glints, approx, dr_err):
    pulses = revolution(rng, bmap, motion, visible, glints)
    base = rng.randrange(65536)
    events = [(base, 1, 0)]  # (count, rising, channel 0 index / 1 beacon)
    latched = []
    ex, ey, eth = dr_err
    for t0, t1, _ in pulses:
        events.append(((base + counts(t0)) % 65536, 1, 1))
        events.append(((base + counts(t1)) % 65536, 0, 1))
        x, y, phi = pose_at(motion, (t0 + t1) / 2)
        # dead reckoning = truth moved by a fixed rigid error (the correction to find)
        c, s = math.cos(eth), math.sin(eth)
        latched.append((c * x - s * y + ex, s * x + c * y + ey, phi + eth))
    events.append(((base + CPT) % 65536, 1, 0))
    return {"events": events, "latched": latched, "approx": approx,
            "truth": pose_at(motion, REV_S), "n": len(pulses)}


def main():
    rng = random.Random(20240611)
    maps = []
    cases = []
    # 1. standing revolutions in a 20 m room, approximate pose off by up to 0.3 m, 5 degrees
    for i in range(16):
        bmap = perimeter_map(rng, 6 + rng.randrange(7), 20.0, 20.0)
        maps.append(bmap)
        p = (1 + rng.random() * 18, 1 + rng.random() * 18)
        phi = rng.random() * TAU
        vis = list(range(len(bmap)))
        rng.shuffle(vis)
        vis = vis[:len(vis) - rng.randrange(3)]
        glints = [rng.random() * REV_S * 0.98 for _ in range(rng.randrange(4))]
        e, eb = rng.random() * 0.3, rng.random() * TAU
        approx = (p[0] + e * math.cos(eb), p[1] + e * math.sin(eb),
                  phi + math.radians(rng.uniform(-5, 5)))
        c = make_case(rng, bmap, ("still", p, phi, 0, 0), vis, glints, approx, (0, 0, 0))
        c.update(map=len(maps) - 1, cfg=1, moving=0)
        cases.append(c)
    # 2. driving at 1 m/s on straights and 1 m arcs, dead reckoning off by a rigid error
    for i in range(8):
        bmap = perimeter_map(rng, 10, 20.0, 20.0)
        maps.append(bmap)
        p = (6 + rng.random() * 8, 6 + rng.random() * 8)
        phi = rng.random() * TAU
        motion = ("line" if i % 2 == 0 else "arc", p, phi, 1.0, 1.0)
        dr = (rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), math.radians(rng.uniform(-1, 1)))
        c = make_case(rng, bmap, motion, list(range(10)), [], None, dr)
        tx, ty, tphi = c["truth"]
        cs, sn = math.cos(dr[2]), math.sin(dr[2])
        c["approx"] = (cs * tx - sn * ty + dr[0], sn * tx + cs * ty + dr[1], tphi + dr[2])
        c.update(map=len(maps) - 1, cfg=0, moving=1)
        cases.append(c)
    # 3. the cycle benchmark: 32 beacons around a 30 m hall, 15 of them seen (standing and
    #    driving): every beacon is within the range gate.
    bench = perimeter_map(random.Random(7), 32, 30.0, 30.0)
    maps.append(bench)
    for moving in (0, 1):
        p, phi = (14.0, 16.0), 0.7
        r2 = random.Random(11)
        vis = sorted(r2.sample(range(32), 15))
        if moving:
            motion = ("arc", p, phi, 1.0, 1.0)
            dr = (0.05, -0.03, math.radians(0.5))
        else:
            motion = ("still", p, phi, 0, 0)
            dr = (0, 0, 0)
        c = make_case(r2, bench, motion, vis, [], None, dr)
        tx, ty, tphi = c["truth"]
        cs, sn = math.cos(dr[2]), math.sin(dr[2])
        if moving:  # the dead-reckoning pose at the reference instant
            c["approx"] = (cs * tx - sn * ty + dr[0], sn * tx + cs * ty + dr[1], tphi + dr[2])
        else:  # a standing vehicle: an approximate pose off by 0.14 m and 2 degrees
            c["approx"] = (tx + 0.1, ty - 0.1, tphi + math.radians(2))
        c.update(map=len(maps) - 1, cfg=0, moving=moving)
        cases.append(c)

    out = []
    w = out.append
    w("/* generated by tests/vectors/gen_optical_vectors.py: do not edit */")
    w("#include <stdint.h>")
    w("")
    w('#include "optical/optical.h"')
    w("")
    w("typedef optical_xy_t vec_xy_t;")
    w("typedef struct { int32_t x, y; uint32_t h; } vec_pose_t;")
    w("typedef struct { uint16_t count; uint8_t rising, channel; } vec_event_t;")
    w("typedef struct {")
    w("    uint8_t map, cfg, moving, n_events;")
    w("    uint16_t first_event, first_latched;")
    w("    vec_pose_t approx, truth;")
    w("} vec_case_t;")
    w("")
    offs = []
    w("static const vec_xy_t vec_beacons[] = {")
    o = 0
    for m in maps:
        offs.append((o, len(m)))
        w("    " + ", ".join("{%d, %d}" % (q16(x), q16(y)) for x, y in m) + ",")
        o += len(m)
    w("};")
    w("static const struct { uint16_t first; uint8_t n; } vec_maps[] = {")
    w("    " + ", ".join("{%d, %d}" % t for t in offs) + ",")
    w("};")
    ev, lat = [], []
    w("static const vec_case_t vec_cases[] = {")
    for c in cases:
        a = c["approx"]
        t = c["truth"]
        w("    {%d, %d, %d, %d, %d, %d, {%d, %d, %du}, {%d, %d, %du}}," % (
            c["map"], c["cfg"], c["moving"], len(c["events"]), len(ev),
            len(lat) if c["moving"] else 0xFFFF, q16(a[0]), q16(a[1]), ang(a[2]),
            q16(t[0]), q16(t[1]), ang(t[2])))
        ev += c["events"]
        if c["moving"]:
            lat += c["latched"]
    w("};")
    w("static const vec_event_t vec_events[] = {")
    for i in range(0, len(ev), 6):
        w("    " + " ".join("{%d, %d, %d}," % e for e in ev[i:i + 6]))
    w("};")
    w("static const vec_pose_t vec_latched[] = {")
    for i in range(0, len(lat), 3):
        w("    " + " ".join("{%d, %d, %du}," % (q16(x), q16(y), ang(h)) for x, y, h in lat[i:i + 3]))
    w("};")
    w("#define VEC_N_CASES %d" % len(cases))
    w("#define VEC_BENCH_STILL %d" % (len(cases) - 2))
    w("#define VEC_BENCH_MOVING %d" % (len(cases) - 1))
    print("\n".join(out))


if __name__ == "__main__":
    main()
