#!/usr/bin/env python3
"""Runs cyclopion's libFuzzer harnesses (tests/fuzz, docs/fuzzing.md) from the fuzz tree.

    tools/fuzz.py --seconds 600                 every harness, 10 minutes each, one after another
    tools/fuzz.py --seconds 3600 agvcalc        one harness for an hour
    tools/fuzz.py --list                        the harnesses built (build/fuzz/fuzzers.json)

Build the tree first: `make fuzz-build` (or `cmake --preset fuzz && cmake --build --preset fuzz`).
Each harness starts from its seed corpus (tests/fuzz/corpus/NAME) plus what earlier long runs
found (build/fuzz/fuzz-work/NAME/corpus, kept between runs), with a fixed seed. A finding - a
crash, a sanitizer report, a failed property, a leak, an input slower than --timeout - ends
that harness's run, stays in build/fuzz/findings/NAME/ (its path printed, with the command that
replays it) and makes the exit status 1.

ctest runs each harness the same way for a short time (--test: a fresh working corpus every
time, so that a run depends only on the seeds, the seed and the time)."""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# What a program prints about input it refuses or ignores ("agv-sim: warning: unknown key"):
# the fuzzer's inputs make a lot of it; counted, not logged.
WARNING = re.compile(r"^[\w.-]+: warning: ")


def load_manifest(build_dir):
    path = os.path.join(build_dir, "fuzzers.json")
    if not os.path.exists(path):
        sys.exit(f"fuzz.py: {path} not found: build the fuzz tree first "
                 "(make fuzz-build, or cmake --preset fuzz && cmake --build --preset fuzz)")
    with open(path) as f:
        return json.load(f)


def stats(log):
    """libFuzzer's final statistics and coverage from its output."""
    out = {}
    for key in ("number_of_executed_units", "average_exec_per_sec", "peak_rss_mb"):
        m = re.search(r"stat::%s:\s*(\d+)" % key, log)
        if m:
            out[key] = int(m.group(1))
    cov = re.findall(r"cov: (\d+) ft: (\d+) corp: (\d+)", log)
    if cov:
        out["cov"], out["ft"], out["corpus"] = (int(v) for v in cov[-1])
    return out


def run_one(h, args, build_dir):
    name = h["name"]
    work = os.path.join(build_dir, "fuzz-work", name)
    corpus = os.path.join(work, "test-corpus" if args.test else "corpus")
    if args.test and os.path.isdir(corpus):
        shutil.rmtree(corpus)  # a test run depends only on the seeds, the seed and the time
    os.makedirs(corpus, exist_ok=True)
    findings = os.path.join(build_dir, "findings", name)
    os.makedirs(findings, exist_ok=True)
    before = set(os.listdir(findings))
    cmd = [h["binary"], corpus, h["corpus"],
           f"-seed={args.seed}", f"-max_total_time={args.seconds}", f"-timeout={args.timeout}",
           f"-rss_limit_mb={args.rss_limit_mb}", f"-max_len={h.get('max_len', 4096)}",
           f"-artifact_prefix={findings}/", "-print_final_stats=1"]
    if h.get("dict"):
        cmd.append(f"-dict={h['dict']}")
    log_path = os.path.join(work, "test-log.txt" if args.test else "log.txt")
    print(f"fuzz {name}: {args.seconds} s, seed {args.seed} (log: {log_path})", flush=True)
    t0 = time.monotonic()
    warnings = 0
    with open(log_path, "w", errors="replace") as log:
        log.write(" ".join(cmd) + "\n")
        with subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              errors="replace") as p:
            for line in p.stdout:
                if WARNING.match(line):
                    warnings += 1  # the code under test warning about its input: expected
                else:
                    log.write(line)
        rc = p.returncode
        log.write(f"({warnings} warnings of the code under test not logged)\n")
    elapsed = time.monotonic() - t0
    with open(log_path, errors="replace") as f:
        text = f.read()
    st = stats(text)
    new = sorted(set(os.listdir(findings)) - before)
    summary = (f"fuzz {name}: {st.get('number_of_executed_units', '?')} inputs in {elapsed:.0f} s, "
               f"coverage {st.get('cov', '?')} edges, {st.get('corpus', '?')} corpus inputs, "
               f"peak {st.get('peak_rss_mb', '?')} MB")
    if rc == 0 and not new:
        print(summary + ": no findings", flush=True)
        return True
    print(summary + f": FINDING (exit status {rc})", flush=True)
    lines = text.splitlines()
    start = next((i for i, l in enumerate(lines)
                  if re.search(r"==\d+==ERROR|fuzz check failed|runtime error|ALARM|"
                               r"ERROR: libFuzzer|Sanitizer", l)), max(0, len(lines) - 40))
    print("\n".join(lines[start:start + 60]))
    for f in new or ["(libFuzzer wrote no reproducer: see the log)"]:
        path = os.path.join(findings, f)
        print(f"fuzz {name}: reproducer {path}")
        print(f"fuzz {name}: replay it with: {h['binary']} {path}")
    return False


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("names", nargs="*", help="harnesses to run (default: all)")
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build", "fuzz"),
                    help="the fuzz tree (default: build/fuzz)")
    ap.add_argument("--seconds", type=int, default=600, help="per harness (default 600)")
    ap.add_argument("--seed", type=int, default=1, help="libFuzzer's -seed (default 1)")
    ap.add_argument("--timeout", type=int, default=20,
                    help="seconds one input may take before it is a finding (default 20)")
    ap.add_argument("--rss-limit-mb", type=int, default=2048, help="memory limit (default 2048)")
    ap.add_argument("--list", action="store_true", help="list the harnesses and exit")
    ap.add_argument("--test", action="store_true",
                    help="ctest mode: a fresh working corpus (the run depends only on the seeds)")
    ap.add_argument("--binary", help="run this harness binary (with --corpus; ctest does)")
    ap.add_argument("--corpus", help="its seed corpus directory")
    ap.add_argument("--dict", help="its libFuzzer dictionary")
    ap.add_argument("--max-len", type=int, default=4096, help="longest input (default 4096)")
    args = ap.parse_args()
    build_dir = os.path.abspath(args.build_dir)

    if args.binary:
        if len(args.names) != 1 or not args.corpus:
            ap.error("--binary needs --corpus and exactly one harness name")
        harnesses = [{"name": args.names[0], "binary": args.binary, "corpus": args.corpus,
                      "dict": args.dict, "max_len": args.max_len}]
    else:
        harnesses = load_manifest(build_dir)
        if args.list:
            for h in harnesses:
                print(f"{h['name']:16} {h['binary']}  seeds: {os.path.relpath(h['corpus'], ROOT)}")
            return 0
        if args.names:
            known = {h["name"] for h in harnesses}
            unknown = [n for n in args.names if n not in known]
            if unknown:
                ap.error(f"unknown harness {', '.join(unknown)}; built: {', '.join(sorted(known))}")
            harnesses = [h for h in harnesses if h["name"] in args.names]
    for h in harnesses:
        if not os.path.exists(h["binary"]):
            sys.exit(f"fuzz.py: {h['binary']} not built (cmake --build --preset fuzz)")
    failed = [h["name"] for h in harnesses if not run_one(h, args, build_dir)]
    if failed:
        print(f"fuzz: findings in {', '.join(failed)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
