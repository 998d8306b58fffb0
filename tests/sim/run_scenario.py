#!/usr/bin/env python3
"""ctest (label sim): run one scenario through agv-sim and check it.

  run_scenario.py AGV_SIM SCENARIO            the scenario file must follow its JSON Schema, the
                                              run must meet the scenario's criteria (exit 0),
                                              and its report must follow the report's schema
                                              (docs/schema/*.schema.json)
  run_scenario.py AGV_SIM SCENARIO --twice    and a second run gives byte-identical report
                                              (wall time aside) and logs
"""
import filecmp
import json
import os
import subprocess
import sys
import tempfile

import jsonschema

SCHEMAS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "schema")


def violations(doc, name):
    with open(os.path.join(SCHEMAS, name)) as f:
        schema = json.load(f)
    v = jsonschema.Draft202012Validator(schema)
    return [f"{'.'.join(str(p) for p in e.absolute_path) or '(root)'}: {e.message}"
            for e in v.iter_errors(doc)]


def run(agv, scenario, tmp, tag):
    rep = os.path.join(tmp, f"report_{tag}.json")
    logs = os.path.join(tmp, f"logs_{tag}")
    r = subprocess.run([agv, "--scenario", scenario, "--report", rep, "--log-dir", logs,
                        "--quiet"], capture_output=True, text=True)
    return r, rep, logs


def main():
    agv, scenario = sys.argv[1], sys.argv[2]
    twice = "--twice" in sys.argv[3:]
    with open(scenario) as f:
        bad = violations(json.load(f), "scenario.schema.json")
    if bad:
        print(f"FAIL {scenario}: not a valid scenario: {bad}")
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        r, rep, logs = run(agv, scenario, tmp, "a")
        sys.stdout.write(r.stderr)
        if r.returncode != 0:
            print(f"FAIL {scenario}: agv-sim exited {r.returncode}")
            return 1
        with open(rep) as f:
            report = json.load(f)
        bad = violations(report, "report.schema.json")
        if bad:
            print(f"FAIL {scenario}: the report does not follow its schema: {bad}")
            return 1
        p, fx = report["path"], report["fixes"]
        print(f"{report['scenario']}: cross-track mean {p['cross_track_m']['mean'] * 1000:.2f} mm"
              f" max {p['cross_track_m']['max'] * 1000:.1f} mm, final {p['final_error_m'] * 1000:.1f}"
              f" mm, fixes {fx['accepted']}/{fx['attempted']} rms {fx['error_m']['rms'] * 1000:.2f}"
              f" mm max {fx['error_m']['max'] * 1000:.1f} mm, "
              f"{report['sim_time_s'] / max(report['wall_time_s'], 1e-9):.0f}x real time")
        if twice:
            r2, rep2, logs2 = run(agv, scenario, tmp, "b")
            if r2.returncode != 0:
                print(f"FAIL {scenario}: the second run exited {r2.returncode}")
                return 1
            with open(rep2) as f:
                report2 = json.load(f)
            report.pop("wall_time_s")
            report2.pop("wall_time_s")
            if json.dumps(report, sort_keys=True) != json.dumps(report2, sort_keys=True):
                print(f"FAIL {scenario}: the reports of two runs differ")
                return 1
            with open(rep) as a, open(rep2) as b:
                la = [l for l in a if "wall_time_s" not in l]
                lb = [l for l in b if "wall_time_s" not in l]
            if la != lb:
                print(f"FAIL {scenario}: the report files differ beyond wall_time_s")
                return 1
            cmp = filecmp.dircmp(logs, logs2)
            if cmp.left_only or cmp.right_only or cmp.diff_files or cmp.funny_files:
                print(f"FAIL {scenario}: logs differ: {cmp.diff_files or cmp.left_only}")
                return 1
            for fn in cmp.same_files:  # dircmp compares shallowly: check the bytes
                if not filecmp.cmp(os.path.join(logs, fn), os.path.join(logs2, fn),
                                   shallow=False):
                    print(f"FAIL {scenario}: {fn} differs between runs")
                    return 1
            print(f"{report['scenario']}: two runs byte-identical ({len(cmp.same_files)} logs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
