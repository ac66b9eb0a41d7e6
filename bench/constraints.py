#!/usr/bin/env python3
"""rigid vs Pinocchio on constrained dynamics, timed from the same Python process.

    python3 bench/constraints.py                 # 7 rounds, the table of bench/CONSTRAINTS.md
    python3 bench/constraints.py --rounds 3 --calls 2000

Needs `pin` (4.1) and rigid's Python module (`pip install ./crates/rigid-py`, or
`maturin develop -m crates/rigid-py/Cargo.toml`) in the same interpreter.

Both sides are called through their Python bindings with the same numpy arrays (Pinocchio's
layout on rigid's side, so that no array is converted): rigid.constraint_dynamics (RNEA, CRBA,
the Jacobians, the tree-sparse LᵀL and the Delassus matrix) against pin.constraintDynamics
(its ContactCholeskyDecomposition; the constraint models and datas in Pinocchio's own
StdVec containers, made once, so that no list is converted per call), and rigid.impulse_dynamics against pin.impulseDynamics, each
with mu = 0 (one exact solve). Each round times `--calls` calls of each side, back to back,
alternating which side goes first; the process is pinned to one core. A time is the median
over rounds of the per-call mean within a round; the ratio is the median of the per-round
ratios. The per-call overhead of each binding is measured the same way on a 1-dof pendulum's
ABA (three vectors in, one out), and subtracted in the last column ("work" = time − overhead).
"""
import argparse
import os
import platform
import statistics
import time

import numpy as np
import pinocchio as pin

import rigid

HERE = os.path.dirname(os.path.abspath(__file__))
ERD = os.path.join(HERE, "..", "crates", "rigid", "tests", "fixtures", "robots",
                   "example-robot-data", "robots")
CASES = [
    ("Solo-12, 4 point contacts", "solo_description/robots/solo12.urdf",
     pin.ContactType.CONTACT_3D, ["FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"]),
    ("ANYmal, 4 point contacts", "anymal_b_simple_description/robots/anymal.urdf",
     pin.ContactType.CONTACT_3D, ["LF_FOOT", "RF_FOOT", "LH_FOOT", "RH_FOOT"]),
    ("TALOS, 2 frame (6D) contacts", "talos_data/robots/talos_reduced.urdf",
     pin.ContactType.CONTACT_6D, ["left_sole_link", "right_sole_link"]),
]


def per_call(f, calls):
    t0 = time.perf_counter()
    for _ in range(calls):
        f()
    return (time.perf_counter() - t0) / calls


def setup(path, kind, feet):
    urdf = os.path.join(ERD, path)
    pm = pin.buildModelFromUrdf(urdf, pin.JointModelFreeFlyer())
    pd = pm.createData()
    m = rigid.Model.from_urdf(urdf, floating=True, layout="pinocchio")
    d = m.create_data()
    q0 = pin.neutral(pm)
    pin.framesForwardKinematics(pm, pd, q0)
    cms, cs = [], []
    for f in feet:
        fid = pm.getFrameId(f)
        fr = pm.frames[fid]
        cms.append(pin.RigidConstraintModel(kind, pm, fr.parentJoint, fr.placement, 0,
                                            pd.oMf[fid], pin.LOCAL))
        cs.append(rigid.ConstraintModel(m, kind, pm.names[fr.parentJoint], fr.placement,
                                        "universe", pd.oMf[fid], "local"))
    # Pinocchio's own containers, made once: a Python list would be converted at every call
    models, cds = pin.StdVec_RigidConstraintModel(), pin.StdVec_RigidConstraintData()
    for c in cms:
        models.append(c)
        cds.append(c.createData())
    cms = models
    pin.initConstraintDynamics(pm, pd, cms, cds)
    cd = rigid.ConstraintData(m, cs)
    rng = np.random.default_rng(0)
    q = q0.copy()
    q[7:] += rng.uniform(-0.3, 0.3, pm.nq - 7)
    v = rng.uniform(-1, 1, pm.nv)
    tau = rng.uniform(-1, 1, pm.nv)
    # same numbers first
    a_pin = pin.constraintDynamics(pm, pd, q, v, tau, cms, cds)
    a_rig = rigid.constraint_dynamics(m, d, q, v, tau, cd)
    err = np.max(np.abs(a_pin - a_rig)) / max(1, np.max(np.abs(a_pin)))
    err = max(err, np.max(np.abs(pd.lambda_c - cd.lambda_c)) / max(1, np.max(np.abs(pd.lambda_c))))
    assert err < 1e-9, err
    return {
        "constraint dynamics": (lambda: rigid.constraint_dynamics(m, d, q, v, tau, cd),
                                lambda: pin.constraintDynamics(pm, pd, q, v, tau, cms, cds)),
        "impulse dynamics": (lambda: rigid.impulse_dynamics(m, d, q, v, cd),
                             lambda: pin.impulseDynamics(pm, pd, q, v, cms, cds)),
    }, err, pm.nv


def overhead_pair():
    """A 1-dof pendulum's ABA on both sides: the binding's cost of 3 vectors in, 1 out."""
    m = rigid.Model.builtin("pendulum")
    d = m.create_data()
    pm = pin.Model()
    j = pm.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "j")
    pm.appendBodyToJoint(j, pin.Inertia.FromCylinder(1.0, 0.05, 1.0), pin.SE3.Identity())
    pd = pm.createData()
    x = np.array([0.3])
    return (lambda: rigid.aba(m, d, x, x, x), lambda: pin.aba(pm, pd, x, x, x))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--calls", type=int, default=5000)
    args = ap.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[-1]})
    rows = []
    benches = [("binding overhead (1-dof ABA)", {"call": overhead_pair()}, 0.0, 1)]
    for name, path, kind, feet in CASES:
        fns, err, nv = setup(path, kind, feet)
        benches.append((name, fns, err, nv))
    overhead = None
    for name, fns, err, nv in benches:
        for verb, (fr, fp) in fns.items():
            tr, tp, ratio = [], [], []
            for k in range(args.rounds):
                per_call(fr, args.calls // 10)
                per_call(fp, args.calls // 10)
                if k % 2 == 0:
                    a, b = per_call(fr, args.calls), per_call(fp, args.calls)
                else:
                    b, a = per_call(fp, args.calls), per_call(fr, args.calls)
                tr.append(a)
                tp.append(b)
                ratio.append(a / b)
            r, p = statistics.median(tr), statistics.median(tp)
            if overhead is None:
                overhead = (r, p)
            rows.append((name, verb, nv, r, p, statistics.median(ratio), min(ratio), max(ratio),
                         err))
    print(f"machine: {platform.processor() or platform.machine()}, {platform.platform()}, "
          f"python {platform.python_version()}, pin {pin.__version__}, rigid {rigid.__version__}")
    print(f"{args.rounds} rounds of {args.calls} calls per side, one core\n")
    print("| model | verb | nv | rigid (µs) | Pinocchio (µs) | rigid / Pinocchio (spread) | "
          "work ratio (minus overhead) | max rel. diff |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, verb, nv, r, p, ratio, lo, hi, err in rows:
        work = (r - overhead[0]) / (p - overhead[1]) if name[0] != "b" else float("nan")
        print(f"| {name} | {verb} | {nv} | {r * 1e6:.2f} | {p * 1e6:.2f} | {ratio:.2f} "
              f"({lo:.2f}–{hi:.2f}) | {work:.2f} | {err:.0e} |")


if __name__ == "__main__":
    main()
