#!/usr/bin/env python3
"""Pinocchio 4.1's `buildModelFromUrdf(path, mimic=True)` on URDF files: one JSON line per file.

    python3 crates/rigid/tests/pinocchio/mimic.py FILE.urdf [...]
    python3 crates/rigid/tests/pinocchio/mimic.py --fixture > crates/rigid/tests/pinocchio/mimic.json

Each line: the file's name, nq, nv, the joints (name, idx_q, nq, idx_v, nv, mimic or not) and
three states `q = neutral ⊕ δ` (δ uniform in [-1, 1]), `v`, `a`, `tau` with Pinocchio's `rnea`,
`crba` (M, made symmetric), `nle`, and `ddq = M⁻¹ (tau − nle)`: Pinocchio's ABA refuses a mimic
joint ("This algorithm does not support Joint Mimic type"), its `crba` and `nle` do not. All in
Pinocchio's layout (continuous joints as (cos θ, sin θ)). `--fixture` runs on the checked-in
Panda of tests/fixtures/robots.
"""
import json
import os
import sys

import numpy as np
import pinocchio as pin


def run(path):
    m = pin.buildModelFromUrdf(path, mimic=True)
    d = m.createData()
    rng = np.random.default_rng(53)
    joints = []
    for j, name in zip(m.joints[1:], m.names[1:]):
        joints.append({"name": name, "idx_q": j.idx_q, "nq": j.nq, "idx_v": j.idx_v,
                       "nv": j.nv, "mimic": "Mimic" in j.shortname()})
    cases = []
    for _ in range(3):
        q = pin.integrate(m, pin.neutral(m), rng.uniform(-1, 1, m.nv))
        v, a, tau = (rng.uniform(-1, 1, m.nv) for _ in range(3))
        rnea = pin.rnea(m, d, q, v, a).copy()
        M = pin.crba(m, d, q).copy()
        M = np.triu(M) + np.triu(M, 1).T
        nle = pin.nonLinearEffects(m, d, q, v).copy()
        ddq = np.linalg.solve(M, tau - nle)
        cases.append({k: x.tolist() for k, x in
                      dict(q=q, v=v, a=a, tau=tau, rnea=rnea, M=M, nle=nle, ddq=ddq).items()})
    return {"file": os.path.basename(path), "nq": m.nq, "nv": m.nv, "joints": joints,
            "cases": cases}


if __name__ == "__main__":
    paths = sys.argv[1:]
    if paths == ["--fixture"]:
        here = os.path.dirname(os.path.abspath(__file__))
        paths = [os.path.join(here, "..", "fixtures", "robots", "example-robot-data", "robots",
                              "panda_description", "urdf", "panda.urdf")]
    for p in paths:
        print(json.dumps(run(p)))
