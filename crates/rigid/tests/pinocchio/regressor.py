#!/usr/bin/env python3
"""Pinocchio's joint-torque regressor for every URDF file of a robot-description package
(crates/rigid/tests/it/identification_packages.rs).

Usage: python3 regressor.py PACKAGE [--states N] [--seed S]

For each URDF file the package ships (found by walking its folder, as packages.py does), loaded
with `pin.buildModelFromUrdf` with a fixed base and with a free-flyer root, one JSON object per
line: `{"file", "floating", "refused"}` when Pinocchio cannot load it, else `{"file", "floating",
"nq", "nv", "joints", "states"}` with, per random state (fixed seed), q, v, a (rigid's
conventions, see reference.py) and `regressor`: `pin.computeJointTorqueRegressor(q, v, a)` with
its rows in rigid's order (free-flyer rows angular first) and its columns in Pinocchio's joint
order (10 per joint, `Inertia.toDynamicParameters` order), and `parameters`: the 10 dynamic
parameters of each of Pinocchio's joints, in the same order.

The live cross-check (RIGID_CROSSCHECK=1) runs this script on every file; every run reads
regressor.json, the fixture gen_packages.py writes with it for a few checked-in files.
"""

import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from packages import each_file, load  # noqa: E402
from reference import joint_layout, q_to_rigid, v_perm  # noqa: E402


def one(path, floating, states, seed):
    model, refused = load(path, floating)
    if refused:
        return refused
    data = model.createData()
    joints, nq, nv = joint_layout(model)
    p = v_perm(joints, nv)
    np.random.seed(seed)
    pin.seed(seed)
    out = []
    for _ in range(states):
        q = pin.randomConfiguration(model)
        v = np.random.uniform(-1.0, 1.0, model.nv)
        a = np.random.uniform(-1.0, 1.0, model.nv)
        Y = pin.computeJointTorqueRegressor(model, data, q, v, a).copy()
        out.append(dict(q=q_to_rigid(joints, q, nq), v=v[p], a=a[p], regressor=Y[p, :]))
    params = [model.inertias[i].toDynamicParameters() for i in range(1, model.njoints)]
    return dict(nq=nq, nv=nv, joints=joints, parameters=params, states=out)


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        return
    each_file(args, one, states=2)


if __name__ == "__main__":
    main()
