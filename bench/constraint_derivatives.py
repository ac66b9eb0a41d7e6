#!/usr/bin/env python3
"""The constrained-dynamics derivatives, rigid beside Pinocchio 4.1, same process, same states:
constraintDynamics + computeConstraintDynamicsDerivatives against
rigid.constraint_dynamics_derivatives (which runs the forward dynamics too), on Solo-12 with its
four feet (3D, local, Baumgarte) and TALOS with its two soles (6D, local, Baumgarte). Prints the
median time of each and the ratio rigid / Pinocchio. Needs `pin` and the rigid module.

    python3 bench/constraint_derivatives.py [--repeat N]
"""
import os
import sys
import time

import numpy as np
import pinocchio as pin

import rigid

HERE = os.path.dirname(os.path.abspath(__file__))
ERD = os.path.join(HERE, "..", "crates", "rigid", "tests", "fixtures", "robots",
                   "example-robot-data", "robots")
CASES = [("Solo-12, 4 feet (3D)", "solo_description/robots/solo12.urdf", "point",
          ["FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"]),
         ("TALOS, 2 soles (6D)", "talos_data/robots/talos_reduced.urdf", "frame",
          ["left_sole_link", "right_sole_link"])]


def median_time(f, repeat):
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t)
    return float(np.median(ts))


def main():
    repeat = int(sys.argv[sys.argv.index("--repeat") + 1]) if "--repeat" in sys.argv else 300
    print("| model | Pinocchio (µs) | rigid (µs) | rigid / Pinocchio |")
    print("| --- | --- | --- | --- |")
    for name, rel, kind, frames in CASES:
        urdf = os.path.join(ERD, rel)
        pm = pin.buildModelFromUrdf(urdf, pin.JointModelFreeFlyer())
        pd = pm.createData()
        m = rigid.Model.from_urdf(urdf, floating=True, layout="pinocchio")
        d = m.create_data()
        t = pin.ContactType.CONTACT_3D if kind == "point" else pin.ContactType.CONTACT_6D
        cms, cs = [], []
        pin.framesForwardKinematics(pm, pd, pin.neutral(pm))
        for f in frames:
            fr = pm.frames[pm.getFrameId(f)]
            target = pd.oMf[pm.getFrameId(f)]
            cm = pin.RigidConstraintModel(t, pm, fr.parentJoint, fr.placement, 0, target, pin.LOCAL)
            cm.setBaumgarteCorrectorParameters(pin.BaumgarteCorrectorParameters(10.0, 2.0))
            cms.append(cm)
            cs.append(rigid.ConstraintModel(m, kind, pm.names[fr.parentJoint], fr.placement,
                                            "universe", (target.rotation, target.translation),
                                            "local", 10.0, 2.0))
        cds = [c.createData() for c in cms]
        pin.initConstraintDynamics(pm, pd, cms, cds)
        cd = rigid.ConstraintData(m, cs)
        rng = np.random.default_rng(0)
        q = pin.randomConfiguration(pm, -np.ones(pm.nq), np.ones(pm.nq))
        v, tau = rng.uniform(-1, 1, pm.nv), rng.uniform(-5, 5, pm.nv)
        ps = pin.ProximalSettings(1e-12, 0.0, 1)

        def p():
            pin.constraintDynamics(pm, pd, q, v, tau, cms, cds, ps)
            pin.computeConstraintDynamicsDerivatives(pm, pd, cms, cds, ps)

        def r():
            rigid.constraint_dynamics_derivatives(m, d, q, v, tau, cd)
        for f in (p, r):
            f()
        tp, tr = median_time(p, repeat), median_time(r, repeat)
        print(f"| {name} | {tp * 1e6:.1f} | {tr * 1e6:.1f} | {tr / tp:.2f} |")


if __name__ == "__main__":
    main()
