#!/usr/bin/env python3
"""agvcalc op "doublearc" end to end (CONTRACT.md): random requests of the issue's domain
through the real binary; each answer's segments are followed in double precision from
"from" and must land on "to" (1 mm, 0.05 degrees) with every radius >= min_radius_m; bad
requests get ok:false with a reason naming the value, and the next line is still answered."""
import json
import math
import random
import subprocess
import sys


def follow(x, y, th, segs, reverse):
    for s in segs:
        r, length = s["radius_m"], s["length_m"]
        mu = th + (math.pi if reverse else 0.0)
        if r is None:
            x += length * math.cos(mu)
            y += length * math.sin(mu)
            continue
        k = (-1.0 if reverse else 1.0) / r  # curvature along the travel
        mu2 = mu + length * k
        x += (math.sin(mu2) - math.sin(mu)) / k
        y += -(math.cos(mu2) - math.cos(mu)) / k
        th += length * k
    return x, y, th


def main():
    agvcalc = sys.argv[1]
    rng = random.Random(1)
    reqs, good = [], []
    for i in range(3000):
        rmin = rng.uniform(0.25, 1.0)
        dist = rng.uniform(0.3, 5.0)
        bearing = math.radians(rng.uniform(-89.9, 89.9))
        dth = rng.uniform(-89.9, 89.9)
        rev = rng.random() < 0.3
        x, y, h = rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(0, 360)
        t = math.radians(h) + (math.pi if rev else 0.0) + bearing
        req = {"op": "doublearc", "from": {"x": x, "y": y, "heading_deg": h},
               "to": {"x": x + dist * math.cos(t), "y": y + dist * math.sin(t),
                      "heading_deg": h + dth},
               "min_radius_m": rmin, "wheelbase_m": 0.762, "reverse": rev}
        reqs.append(req)
        good.append(True)
        if i % 100 == 0:  # a bad line after it
            reqs.append({"op": "doublearc", "from": {"x": 0, "y": 0, "heading_deg": 0},
                         "to": {"x": 1, "y": 0}, "min_radius_m": 0.5, "wheelbase_m": 0.7})
            good.append(False)
    lines = "\n".join(json.dumps(r) for r in reqs) + "\n" + "not json\n"
    out = subprocess.run([agvcalc], input=lines, capture_output=True, text=True, check=True)
    answers = [json.loads(l) for l in out.stdout.splitlines()]
    assert len(answers) == len(reqs) + 1, (len(answers), len(reqs))
    ok = refused = 0
    worst_p = worst_h = 0.0
    for req, is_good, ans in zip(reqs, good, answers):
        if not is_good:
            assert not ans["ok"] and "to.heading_deg" in ans["error"], ans
            continue
        if not ans["ok"]:
            assert ans["error"], ans
            refused += 1
            continue
        ok += 1
        f, t = req["from"], req["to"]
        x, y, th = follow(f["x"], f["y"], math.radians(f["heading_deg"]), ans["segments"],
                          req["reverse"])
        dp = math.hypot(x - t["x"], y - t["y"])
        dh = abs((math.degrees(th) - t["heading_deg"] + 180.0) % 360.0 - 180.0)
        worst_p, worst_h = max(worst_p, dp), max(worst_h, dh)
        assert dp < 1e-3 and dh < 0.05, (req, ans, dp, dh)
        assert ans["case"] in ("1", "2", "3", "4", "5", "straight"), ans
        assert len(ans["segments"]) == 2 and len(ans["steering_deg"]) == 2, ans
        for s, a in zip(ans["segments"], ans["steering_deg"]):
            if s["radius_m"] is None:
                assert s["turn"] == "straight" and a == 0.0, ans
            else:
                assert abs(s["radius_m"]) >= req["min_radius_m"] * (1 - 1e-6), ans
                assert (s["turn"] == "left") == (s["radius_m"] > 0), ans
                ref = math.degrees(math.atan(req["wheelbase_m"] / s["radius_m"]))
                assert abs(a - ref) < 1e-3, (ans, ref)
    assert not answers[-1]["ok"] and "malformed JSON" in answers[-1]["error"]
    print(f"doublearc: {ok} answered (worst {worst_p * 1e3:.3f} mm, {worst_h:.4f} deg), "
          f"{refused} refused with a reason, {good.count(False)} "
          f"bad lines rejected")
    assert ok > 1500


if __name__ == "__main__":
    main()
