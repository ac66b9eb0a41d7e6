#!/usr/bin/env python3
"""Per-call cost of rigid's Python module against Pinocchio's, in one process (BENCHMARKS.md).

    python3 bench/python_overhead.py                 # UR5, 15 rounds
    python3 bench/python_overhead.py --rounds 31 --robot talos

Needs `pip install ./crates/rigid-py` and scripts/requirements-test.txt (pin, example-robot-data).

1. Single calls: for each verb (rnea, crba, aba, nle, gravity), rounds of `--calls` calls of
   `pinocchio.X` then `rigid.X` (the order alternates round by round), on the same robot loaded
   by both with `layout="pinocchio"` (the same q, v, a arrays passed to both, contiguous float64),
   cycling through 100 random states. A side's time per call is the median over rounds; the
   ratio is the median over rounds of rigid / Pinocchio within the round.
2. Batch: `rigid.rnea_batch` on `--states` states (N x nq, N x nv arrays) against the Python loop
   `for k in range(N): pinocchio.rnea(model, data, Q[k], V[k], A[k])`, interleaved the same way,
   with a fresh output per call, with `out=` (one output array written by every call), and in
   rigid's layout with `out=` (no permutation of the free-flyer's velocity rows);
   speed-up = median over rounds of loop time / batch time. (What the fresh output's first
   touch costs, and when: bench/first_touch.py.)
"""
import argparse
import os
import statistics
import sys
import time

import numpy as np
import pinocchio as pin

import rigid

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "crates", "rigid", "tests", "pinocchio"))
from reference import ROBOTS, robots_dir  # noqa: E402

VERBS = {
    "rnea": (lambda pm, pd, q, v, a, t: pin.rnea(pm, pd, q, v, a),
             lambda m, d, q, v, a, t: rigid.rnea(m, d, q, v, a)),
    "crba": (lambda pm, pd, q, v, a, t: pin.crba(pm, pd, q),
             lambda m, d, q, v, a, t: rigid.crba(m, d, q)),
    "aba": (lambda pm, pd, q, v, a, t: pin.aba(pm, pd, q, v, t),
            lambda m, d, q, v, a, t: rigid.aba(m, d, q, v, t)),
    "nle": (lambda pm, pd, q, v, a, t: pin.nonLinearEffects(pm, pd, q, v),
            lambda m, d, q, v, a, t: rigid.nle(m, d, q, v)),
    "gravity": (lambda pm, pd, q, v, a, t: pin.computeGeneralizedGravity(pm, pd, q),
                lambda m, d, q, v, a, t: rigid.gravity(m, d, q)),
}


def timed(f, args, calls):
    n = len(args)
    t0 = time.perf_counter()
    for k in range(calls):
        f(*args[k % n])
    return (time.perf_counter() - t0) / calls


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--robot", default="ur5", choices=sorted(ROBOTS))
    ap.add_argument("--rounds", type=int, default=15)
    ap.add_argument("--calls", type=int, default=20000)
    ap.add_argument("--states", type=int, default=10000)
    args = ap.parse_args()

    rel, floating = ROBOTS[args.robot]
    path = os.path.join(robots_dir(), rel)
    pm = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating \
        else pin.buildModelFromUrdf(path)
    pd = pm.createData()
    m = rigid.Model.from_urdf(path, floating=floating, layout="pinocchio")
    d = m.create_data()
    lo, up = pm.lowerPositionLimit, pm.upperPositionLimit
    pm.lowerPositionLimit = np.where(np.abs(lo) < 1e10, lo, -1.0)
    pm.upperPositionLimit = np.where(np.abs(up) < 1e10, up, 1.0)
    pin.seed(0)
    rng = np.random.default_rng(0)
    nv = pm.nv
    states = [(pin.randomConfiguration(pm), rng.uniform(-1, 1, nv), rng.uniform(-1, 1, nv),
               rng.uniform(-10, 10, nv)) for _ in range(100)]
    p_args = [(pm, pd) + s for s in states]
    r_args = [(m, d) + s for s in states]

    print(f"robot {args.robot} (nq {pm.nq}, nv {nv}), Pinocchio {pin.__version__}, "
          f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f} at start")
    print(f"{args.rounds} rounds of {args.calls} calls per verb and side, interleaved\n")
    print("| verb | Pinocchio ns/call | rigid ns/call | rigid / Pinocchio (median) | "
          "per-round range |")
    print("| --- | ---: | ---: | ---: | --- |")
    for name, (pf, rf) in VERBS.items():
        timed(pf, p_args, 1000)
        timed(rf, r_args, 1000)
        tp, tr, ratios = [], [], []
        for r in range(args.rounds):
            if r % 2 == 0:
                a, b = timed(pf, p_args, args.calls), timed(rf, r_args, args.calls)
            else:
                b, a = timed(rf, r_args, args.calls), timed(pf, p_args, args.calls)
            tp.append(a)
            tr.append(b)
            ratios.append(b / a)
        print(f"| {name} | {statistics.median(tp) * 1e9:.0f} | {statistics.median(tr) * 1e9:.0f}"
              f" | **{statistics.median(ratios):.2f}** | {min(ratios):.2f}–{max(ratios):.2f} |")

    n = args.states
    pin.seed(1)
    Q = np.array([pin.randomConfiguration(pm) for _ in range(n)])
    V, A = rng.uniform(-1, 1, (n, nv)), rng.uniform(-1, 1, (n, nv))

    def loop():
        t0 = time.perf_counter()
        for k in range(n):
            pin.rnea(pm, pd, Q[k], V[k], A[k])
        return time.perf_counter() - t0

    TAU = np.empty((n, nv))
    # the same robot in rigid's layout (V and A then other numbers: the time is the same)
    mr = rigid.Model.from_urdf(path, floating=floating)
    assert mr.nq == pm.nq
    variants = {
        "rigid.rnea_batch": lambda: rigid.rnea_batch(m, Q, V, A),
        "rigid.rnea_batch(..., out=TAU)": lambda: rigid.rnea_batch(m, Q, V, A, out=TAU),
        "in rigid's layout, out=TAU": lambda: rigid.rnea_batch(mr, Q, V, A, out=TAU),
    }

    def timed_once(f):
        t0 = time.perf_counter()
        f()
        return time.perf_counter() - t0

    for f in variants.values():
        f()
    tl, tb = [], {k: [] for k in variants}
    speedups = {k: [] for k in variants}
    for r in range(args.rounds):
        # the loop first in even rounds, last in odd ones, the variants in turn around it
        order = list(variants) if r % 2 == 0 else list(reversed(variants))
        if r % 2 == 0:
            a = loop()
        times = {k: timed_once(variants[k]) for k in order}
        if r % 2 == 1:
            a = loop()
        tl.append(a)
        for k, t in times.items():
            tb[k].append(t)
            speedups[k].append(a / t)
    print(f"\nrnea on {n} states: Python loop of pinocchio.rnea {statistics.median(tl) * 1e3:.2f} "
          f"ms ({statistics.median(tl) / n * 1e9:.0f} ns/state)")
    for k in variants:
        t, s = tb[k], speedups[k]
        print(f"{k}: {statistics.median(t) * 1e3:.2f} ms ({statistics.median(t) / n * 1e9:.0f} "
              f"ns/state); speed-up **{statistics.median(s):.1f}x** (per-round "
              f"{min(s):.1f}–{max(s):.1f}x)")
    print(f"load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
