#!/usr/bin/env python3
"""Interleaved A/B timing of two `rigid` binaries: the method behind BENCHMARKS.md's "what was
tried" tables.

    cp target/release/rigid /tmp/rigid-A      # before the change
    cargo build --release -p rigid-cli        # after it
    python3 bench/ab.py /tmp/rigid-A target/release/rigid --only crba --rounds 9

Each round runs `rigid bench MODEL --only ALGOS --json` with A then B (the order alternating
round by round), both pinned to one core (`taskset -c CORE`), and records B/A per model and
algorithm. Prints the median ratio and [min, max] over rounds: B is faster where the median
and, to be sure, the max are below 1. The models are `bench/models.tsv`'s, from the
example-robot-data that `pip install example-robot-data` put in the Python prefix.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def models():
    import site
    roots = [os.path.join(p, "cmeel.prefix", "share", "example-robot-data", "robots")
             for p in site.getsitepackages()]
    root = next((r for r in roots if os.path.isdir(r)), None)
    out = []
    with open(os.path.join(HERE, "models.tsv")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            name, src, floating = line.rstrip("\n").split("\t")
            if src.startswith("builtin:"):
                arg = src.split(":", 1)[1]
            elif root is None:
                sys.exit("example-robot-data not found: pip install example-robot-data")
            else:
                arg = os.path.join(root, src)
            out.append((name, [arg] + (["--floating"] if floating == "1" else [])))
    return out


def run(exe, model_args, only, core, states):
    cmd = ["taskset", "-c", str(core), exe, "bench", *model_args, "--only", only, "--json",
           "--states", str(states)]
    return json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout)[
        "ns_per_call"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--only", default="crba")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--core", type=int, default=0)
    ap.add_argument("--states", type=int, default=1000)
    ap.add_argument("--models", default="", help="comma separated names (default: all)")
    args = ap.parse_args()
    wanted = set(filter(None, args.models.split(",")))
    ratios, times = {}, {}
    for r in range(args.rounds):
        for name, margs in models():
            if wanted and name not in wanted:
                continue
            order = [("a", args.a), ("b", args.b)] if r % 2 == 0 else [("b", args.b), ("a", args.a)]
            got = {side: run(exe, margs, args.only, args.core, args.states) for side, exe in order}
            for algo, ta in got["a"].items():
                ratios.setdefault((name, algo), []).append(got["b"][algo] / ta)
                times.setdefault((name, algo), []).append((ta, got["b"][algo]))
    print("| model | algorithm | A ns (median) | B ns (median) | B/A median | [min, max] |")
    print("|---|---|---:|---:|---:|---|")
    for (name, algo), rs in ratios.items():
        ta = statistics.median(t[0] for t in times[(name, algo)])
        tb = statistics.median(t[1] for t in times[(name, algo)])
        print("| %s | %s | %.0f | %.0f | %.3f | [%.3f, %.3f] |"
              % (name, algo, ta, tb, statistics.median(rs), min(rs), max(rs)))


if __name__ == "__main__":
    main()
