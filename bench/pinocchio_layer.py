#!/usr/bin/env python3
"""Per-call cost of the Pinocchio layer (`import rigid.pinocchio as pin`) against Pinocchio's own
Python module, in one process (bench/PINOCCHIO_LAYER.md).

    python3 bench/pinocchio_layer.py                     # UR5, 15 rounds
    python3 bench/pinocchio_layer.py --robot talos --rounds 31

Needs `pip install ./crates/rigid-py` and scripts/requirements-test.txt (pin, example-robot-data).

The same script runs both sides, written as a Pinocchio user writes it: the model loaded by each
library's `buildModelFromUrdf` (with `JointModelFreeFlyer()` for a floating robot), `data =
model.createData()`, and the calls `rnea(model, data, q, v, a)`, `crba(model, data, q)`,
`aba(model, data, q, v, tau)`, `forwardKinematics(model, data, q)` followed by
`updateFramePlacements(model, data)`, and `computeJointJacobians(model, data, q)` on the same
arrays (contiguous float64, 100 random states cycled). Rounds of `--calls` calls of one side then
the other (the order alternates round by round); a side's time per call is the median over
rounds, the ratio the median over rounds of layer / Pinocchio within the round.
"""
import argparse
import os
import statistics
import sys
import time

import numpy as np
import pinocchio as pin

import rigid
import rigid.pinocchio as rpin

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "crates", "rigid", "tests", "pinocchio"))
from reference import ROBOTS, robots_dir  # noqa: E402


def verbs(lib):
    def fk(m, d, q, v, a, t):
        lib.forwardKinematics(m, d, q)
        lib.updateFramePlacements(m, d)

    return {
        "rnea": lambda m, d, q, v, a, t: lib.rnea(m, d, q, v, a),
        "crba": lambda m, d, q, v, a, t: lib.crba(m, d, q),
        "aba": lambda m, d, q, v, a, t: lib.aba(m, d, q, v, t),
        "forwardKinematics + updateFramePlacements": fk,
        "computeJointJacobians": lambda m, d, q, v, a, t: lib.computeJointJacobians(m, d, q),
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
    args = ap.parse_args()

    rel, floating = ROBOTS[args.robot]
    path = os.path.join(robots_dir(), rel)
    pm = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating \
        else pin.buildModelFromUrdf(path)
    rm = rpin.buildModelFromUrdf(path, rpin.JointModelFreeFlyer()) if floating \
        else rpin.buildModelFromUrdf(path)
    pd, rd = pm.createData(), rm.createData()
    lo, up = pm.lowerPositionLimit, pm.upperPositionLimit
    bounds = np.where(np.abs(lo) < 1e10, lo, -1.0), np.where(np.abs(up) < 1e10, up, 1.0)
    pin.seed(0)
    rng = np.random.default_rng(0)
    nv = pm.nv
    states = [(pin.randomConfiguration(pm, *bounds), rng.uniform(-1, 1, nv),
               rng.uniform(-1, 1, nv), rng.uniform(-10, 10, nv)) for _ in range(100)]
    p_args = [(pm, pd) + s for s in states]
    r_args = [(rm, rd) + s for s in states]

    print(f"robot {args.robot} (nq {pm.nq}, nv {nv}, {pm.nframes} frames), Pinocchio "
          f"{pin.__version__}, rigid {rigid.__version__}, {os.cpu_count()} CPUs, load average "
          f"{os.getloadavg()[0]:.1f} at start")
    print(f"{args.rounds} rounds of {args.calls} calls per verb and side, interleaved\n")
    print("| call | Pinocchio ns/call | rigid.pinocchio ns/call | layer / Pinocchio (median) | "
          "per-round range |")
    print("| --- | ---: | ---: | ---: | --- |")
    pv, rv = verbs(pin), verbs(rpin)
    for name in pv:
        pf, rf = pv[name], rv[name]
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
        print(f"| `{name}` | {statistics.median(tp) * 1e9:.0f} | "
              f"{statistics.median(tr) * 1e9:.0f} | **{statistics.median(ratios):.2f}** | "
              f"{min(ratios):.2f}–{max(ratios):.2f} |")
    print(f"\nload average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
