#!/usr/bin/env python3
"""Generate centroidal.json: Pinocchio's centres of mass, centre-of-mass Jacobian and centroidal
momentum on UR5, Panda, Solo-12 and TALOS, the fixture of crates/rigid/tests/it/centroidal.rs.

    python3 -m venv /tmp/v && /tmp/v/bin/pip install -r scripts/requirements-test.txt
    /tmp/v/bin/python crates/rigid/tests/pinocchio/gen_centroidal.py [--check]

writes crates/rigid/tests/pinocchio/centroidal.json (`--check` compares a fresh generation with the
committed file, as gen_reference.py does, and exits 1 if anything differs).

Each robot is loaded with `pin.buildModelFromUrdf` (a free-flyer root for Solo-12 and TALOS) from
example-robot-data; STATES states are drawn with a fixed seed (`pin.randomConfiguration` with the
infinite bounds replaced by ±1, v and a uniform in [-1, 1]). Everything is in Pinocchio's raw
layout (joints in urdfdom's order, free-flyer velocity linear first, Jacobian rows linear first,
continuous joints as (cos, sin)); the Rust test loads the URDF with sibling joints sorted by name
and converts through `rigid::interop::PinocchioLayout`. Per state:

- "mass", "com", "vcom", "acom": `pin.centerOfMass(model, data, q, v, a)`: the whole model's
  `data.mass[0]`, `data.com[0]`, `data.vcom[0]`, `data.acom[0]` (world frame);
- "subtree_com", "subtree_vcom", "subtree_acom", "subtree_mass": one entry per joint (no universe),
  the same call's subtree values rotated to the world frame (Pinocchio keeps `com[i]`, `vcom[i]`,
  `acom[i]` of i > 0 in joint i's frame: `oMi * com[i]`, `oMi.rotation @ vcom[i]`, ...);
- "Jcom": `pin.jacobianCenterOfMass(model, data, q)` (3 x nv);
- "Ag", "hg", "Ig_mass", "Ig_inertia": `pin.ccrba(model, data, q, v)`, `data.hg` (linear first),
  `data.Ig` (mass, rotational inertia about the centre of mass in world axes);
- "hg_direct", "vcom_direct": `pin.computeCentroidalMomentum(model, data, q, v)` and `data.vcom[0]`.
"""

import json
import os
import sys
from importlib import metadata

import numpy as np
import pinocchio as pin

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from gen_reference import differences  # noqa: E402
from reference import ROBOTS, plain, robots_dir  # noqa: E402

NAMES = ["ur5", "panda", "solo12", "talos"]
STATES = 2
SEED = 11
OUT = os.path.join(HERE, "centroidal.json")


def robot(name):
    rel, floating = ROBOTS[name]
    path = os.path.join(robots_dir(), rel)
    model = (pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating
             else pin.buildModelFromUrdf(path))
    data = model.createData()
    lo, up = model.lowerPositionLimit.copy(), model.upperPositionLimit.copy()
    model.lowerPositionLimit = np.where(np.abs(lo) < 1e10, lo, -1.0)
    model.upperPositionLimit = np.where(np.abs(up) < 1e10, up, 1.0)
    pin.seed(SEED)
    rng = np.random.default_rng(SEED)
    states = []
    for _ in range(STATES):
        q = pin.randomConfiguration(model)
        v, a = rng.uniform(-1, 1, model.nv), rng.uniform(-1, 1, model.nv)
        st = dict(q=q, v=v, a=a)
        pin.centerOfMass(model, data, q, v, a)
        st.update(mass=data.mass[0], com=data.com[0].copy(), vcom=data.vcom[0].copy(),
                  acom=data.acom[0].copy())
        n = model.njoints
        st["subtree_mass"] = [data.mass[i] for i in range(1, n)]
        st["subtree_com"] = [data.oMi[i].act(data.com[i]) for i in range(1, n)]
        st["subtree_vcom"] = [data.oMi[i].rotation @ data.vcom[i] for i in range(1, n)]
        st["subtree_acom"] = [data.oMi[i].rotation @ data.acom[i] for i in range(1, n)]
        st["Jcom"] = pin.jacobianCenterOfMass(model, data, q).copy()
        st["Ag"] = pin.ccrba(model, data, q, v).copy()
        st["hg"] = data.hg.vector.copy()
        st["Ig_mass"] = data.Ig.mass
        st["Ig_inertia"] = data.Ig.inertia.copy()
        st["hg_direct"] = pin.computeCentroidalMomentum(model, data, q, v).vector.copy()
        st["vcom_direct"] = data.vcom[0].copy()
        states.append(plain(st))
    return dict(urdf=rel, floating=floating, nq=model.nq, nv=model.nv, states=states)


def generate():
    head = dict(
        generator="crates/rigid/tests/pinocchio/gen_centroidal.py",
        pinocchio_version=pin.__version__,
        example_robot_data_version=metadata.version("example-robot-data"),
        numpy_version=np.__version__,
        states=STATES,
        seed=SEED,
    )
    return head, {name: robot(name) for name in NAMES}


def dump(head, robots):
    lines = [json.dumps(head)[:-1] + ', "robots": {']
    lines.append(",\n".join(f"{json.dumps(k)}: {json.dumps(v)}" for k, v in robots.items()))
    lines.append("}}")
    return "\n".join(lines) + "\n"


def main():
    head, robots = generate()
    if "--check" in sys.argv[1:]:
        with open(OUT) as f:
            committed = json.load(f)
        diff = differences(json.loads(dump(head, robots))["robots"], committed["robots"])
        for d in diff:
            print(d)
        sys.exit(1 if diff else 0)
    with open(OUT, "w") as f:
        f.write(dump(head, robots))
    print(f"wrote {OUT} ({os.path.getsize(OUT)} bytes)", file=sys.stderr)


if __name__ == "__main__":
    main()
