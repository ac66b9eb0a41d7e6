#!/usr/bin/env python3
"""Pinocchio reference values for rigid's cross-check (crates/rigid/tests/it/pinocchio.rs).

Usage: python3 reference.py ROBOT [--states N] [--seed S] [--derivatives]   (ROBOT: see ROBOTS, or "list")

Loads the robot's URDF from the PyPI package example-robot-data with `pin.buildModelFromUrdf`
(a free-flyer root for the legged robots), draws N random states with a fixed seed and prints one
JSON object with Pinocchio's rnea, crba, aba, computeMinverse, nle, generalized gravity, kinetic
and potential energy, centre of mass, total mass and the joint placements data.oMi.

Everything printed is already in rigid's conventions (docs/conventions.md):
- free-flyer velocity, acceleration and force: Pinocchio stores (v, w) / (f, m), linear first;
  rigid stores (w, v) / (m, f), angular first: the two halves are swapped, in vectors and in the
  rows and columns of M;
- continuous joints: Pinocchio's q is (cos t, sin t), rigid's is the angle t; planar joints:
  Pinocchio's q is (x, y, cos t, sin t), rigid's (x, y, t);
- crba and computeMinverse fill only the upper triangle: M and M⁻¹ are symmetrised.
With --derivatives, each state also has "derivatives": random external wrenches "fext" (one per
joint, in the joint's frame, (m, f) angular first, in the joints' order below), computeRNEADerivatives
with them ("dtau_dq", "dtau_dv") and computeABADerivatives at (q, v, tau) ("dqdd_dq", "dqdd_dv",
"dqdd_dtau"); rows and columns permuted like M (derivatives along Pinocchio's integrate, which for
a free-flyer is q * exp(v) with v linear first: its halves are swapped to rigid's angular first).
The joints stay in Pinocchio's order (urdfdom sorts siblings by joint name; rigid keeps file
order): each joint is listed with its name and its slices in the vectors printed here, and the
Rust test matches joints by name.

Requirements: pip install -r scripts/requirements-test.txt (pin, example-robot-data).
The live cross-check (RIGID_CROSSCHECK=1) runs this script; every run reads reference.json, the
fixture gen_reference.py writes with it.
"""

import glob
import json
import os
import site
import sys

import numpy as np
import pinocchio as pin

# name: (path under example-robot-data's robots/, free-flyer root?)
ROBOTS = {
    "ur5": ("ur_description/urdf/ur5_robot.urdf", False),
    "panda": ("panda_description/urdf/panda.urdf", False),
    "solo12": ("solo_description/robots/solo12.urdf", True),
    "anymal": ("anymal_b_simple_description/robots/anymal.urdf", True),
    "talos": ("talos_data/robots/talos_full_v2.urdf", True),
    "double_pendulum": ("double_pendulum_description/urdf/double_pendulum.urdf", False),
    # Fixtures beside this script (every joint type rigid imports).
    "all_joints": ("local:all_joints.urdf", False),
    "all_joints_floating": ("local:all_joints.urdf", True),
}


def plain(x):
    """`x` with numpy arrays and scalars made JSON-serialisable."""
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, dict):
        return {k: plain(v) for k, v in x.items()}
    if isinstance(x, list):
        return [plain(v) for v in x]
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    return x


def robots_dir():
    """The robots/ folder of example-robot-data, wherever pip (cmeel) or conda put it."""
    env = os.environ.get("EXAMPLE_ROBOT_DATA_MODEL_DIR")
    if env:
        return env
    try:
        import example_robot_data  # noqa: F401  (not importable in every install)

        from example_robot_data.path import EXAMPLE_ROBOT_DATA_MODEL_DIR

        return EXAMPLE_ROBOT_DATA_MODEL_DIR
    except ImportError:
        pass
    roots = [sys.prefix, os.path.dirname(pin.__file__)]
    roots += site.getsitepackages() + [site.getusersitepackages()]
    for root in roots:
        for pattern in (
            "cmeel.prefix/share/example-robot-data/robots",
            "share/example-robot-data/robots",
            "../../../../share/example-robot-data/robots",
        ):
            hits = glob.glob(os.path.join(root, pattern))
            if hits:
                return os.path.normpath(hits[0])
    sys.exit("example-robot-data not found: pip install -r scripts/requirements-test.txt")


def joint_layout(model):
    """rigid's per-joint layout of Pinocchio's joints, in Pinocchio's order."""
    joints, iq, iv = [], 0, 0
    for i in range(1, model.njoints):
        j = model.joints[i]
        short = j.shortname()
        if short == "JointModelFreeFlyer":
            kind, nq, nv = "free_flyer", 7, 6
        elif j.nq == 2 and j.nv == 1:
            # RevoluteUnbounded (shortnames JointModelRUBX/Y/Z, ...Unaligned): (cos t, sin t)
            kind, nq, nv = "continuous", 1, 1
        elif short == "JointModelPlanar":
            kind, nq, nv = "planar", 3, 3
        elif j.nq == 1 and j.nv == 1:
            kind, nq, nv = "revolute_or_prismatic", 1, 1
        else:
            raise SystemExit(f"joint {model.names[i]}: {short} is not handled by this script")
        joints.append(
            dict(name=model.names[i], type=kind, idx_q=iq, nq=nq, idx_v=iv, nv=nv,
                 pin_idx_q=j.idx_q, pin_idx_v=j.idx_v)
        )
        iq += nq
        iv += nv
    return joints, iq, iv


def q_to_rigid(joints, q, nq):
    out = np.zeros(nq)
    for j in joints:
        s = q[j["pin_idx_q"]:]
        if j["type"] == "continuous":
            out[j["idx_q"]] = np.arctan2(s[1], s[0])
        elif j["type"] == "planar":
            # Pinocchio (x, y, cos t, sin t); rigid (x, y, t). Velocities agree: (vx, vy, w).
            out[j["idx_q"]:j["idx_q"] + 3] = [s[0], s[1], np.arctan2(s[3], s[2])]
        else:
            out[j["idx_q"]:j["idx_q"] + j["nq"]] = s[:j["nq"]]
    return out


def v_perm(joints, nv):
    """p such that rigid_vector = pin_vector[p] (free-flyer halves swapped)."""
    p = np.zeros(nv, dtype=int)
    for j in joints:
        src = list(range(j["pin_idx_v"], j["pin_idx_v"] + j["nv"]))
        if j["type"] == "free_flyer":
            src = src[3:] + src[:3]
        p[j["idx_v"]:j["idx_v"] + j["nv"]] = src
    return p


def reference_derivatives(model, data, joints, p, rs, q, v, a, tau):
    """computeRNEADerivatives (with random external wrenches) and computeABADerivatives."""
    fext = [pin.Force.Zero()] + [pin.Force(rs.uniform(-5, 5, 3), rs.uniform(-5, 5, 3)) for _ in joints]
    dq, dv, _ = pin.computeRNEADerivatives(model, data, q, v, a, fext)
    out = dict(
        fext=[np.concatenate([f.angular, f.linear]) for f in fext[1:]],
        dtau_dq=dq[np.ix_(p, p)].copy(),
        dtau_dv=dv[np.ix_(p, p)].copy(),
    )
    dq, dv, minv = pin.computeABADerivatives(model, data, q, v, tau)
    minv = np.triu(minv) + np.triu(minv, 1).T
    out.update(dqdd_dq=dq[np.ix_(p, p)].copy(), dqdd_dv=dv[np.ix_(p, p)].copy(),
               dqdd_dtau=minv[np.ix_(p, p)].copy())
    return out


def reference(name, states=5, seed=0, derivatives=False):
    """Pinocchio's results on robot `name` (a key of ROBOTS) at `states` random states drawn with
    `seed`, in rigid's conventions: the JSON object this script prints."""
    rel, floating = ROBOTS[name]
    if rel.startswith("local:"):
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), rel[len("local:"):])
    else:
        path = os.path.join(robots_dir(), rel)
    if floating:
        model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
    else:
        model = pin.buildModelFromUrdf(path)
    # Unbounded coordinates (free-flyer and planar translations) are drawn in [-1, 1].
    lo, up = model.lowerPositionLimit, model.upperPositionLimit
    model.lowerPositionLimit = np.where(np.abs(lo) < 1e10, lo, -1.0)
    model.upperPositionLimit = np.where(np.abs(up) < 1e10, up, 1.0)
    data = model.createData()
    joints, nq, nv = joint_layout(model)
    p = v_perm(joints, nv)

    np.random.seed(seed)
    pin.seed(seed)
    # the derivatives' wrenches have their own stream: the states are those without the flag
    rs = np.random.RandomState(seed + 1)
    out_states = []
    for _ in range(states):
        q = pin.randomConfiguration(model)
        v = np.random.uniform(-1.0, 1.0, model.nv)
        a = np.random.uniform(-1.0, 1.0, model.nv)
        tau = np.random.uniform(-10.0, 10.0, model.nv)
        M = pin.crba(model, data, q).copy()
        M = np.triu(M) + np.triu(M, 1).T
        Minv = pin.computeMinverse(model, data, q).copy()
        Minv = np.triu(Minv) + np.triu(Minv, 1).T
        st = dict(
            q=q_to_rigid(joints, q, nq),
            v=v[p],
            a=a[p],
            tau=tau[p],
            rnea=pin.rnea(model, data, q, v, a)[p],
            mass_matrix=M[np.ix_(p, p)],
            minverse=Minv[np.ix_(p, p)],
            aba=pin.aba(model, data, q, v, tau)[p],
            nonlinear_effects=pin.nonLinearEffects(model, data, q, v)[p],
            gravity_torques=pin.computeGeneralizedGravity(model, data, q)[p],
            kinetic_energy=pin.computeKineticEnergy(model, data, q, v),
            potential_energy=pin.computePotentialEnergy(model, data, q),
            com=pin.centerOfMass(model, data, q).copy(),
        )
        if derivatives:
            st["derivatives"] = reference_derivatives(model, data, joints, p, rs, q, v, a, tau)
        pin.forwardKinematics(model, data, q)
        st["placements"] = {
            model.names[i]: dict(
                translation=data.oMi[i].translation.copy(), rotation=data.oMi[i].rotation.copy()
            )
            for i in range(1, model.njoints)
        }
        out_states.append(st)

    return plain(dict(
        robot=name,
        urdf=path,
        floating=floating,
        pinocchio_version=pin.__version__,
        seed=seed,
        nq=nq,
        nv=nv,
        gravity=model.gravity.linear.copy(),
        total_mass=pin.computeTotalMass(model),
        joints=joints,
        states=out_states,
    ))


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        return
    if args[0] == "list":
        print(json.dumps(sorted(ROBOTS)))
        return
    name = args[0]
    states = int(args[args.index("--states") + 1]) if "--states" in args else 5
    seed = int(args[args.index("--seed") + 1]) if "--seed" in args else 0
    derivatives = "--derivatives" in args
    if name not in ROBOTS:
        sys.exit(f"unknown robot {name!r}; known: {', '.join(sorted(ROBOTS))}")
    print(json.dumps(reference(name, states, seed, derivatives)))


if __name__ == "__main__":
    main()
