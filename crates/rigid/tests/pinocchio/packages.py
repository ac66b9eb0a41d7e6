#!/usr/bin/env python3
"""Pinocchio reference values for every URDF file of whole robot-description packages
(crates/rigid/tests/it/pinocchio_packages.rs).

Usage: python3 packages.py PACKAGE [--states N] [--seed S]
       python3 packages.py list
       python3 packages.py roots     (each package's folder, as JSON)

PACKAGE is one of PACKAGES below (PyPI packages pinned in scripts/requirements-test.txt). For each
URDF file the package ships (found by walking its folder, not from a hand-picked list), the file
is loaded with `pin.buildModelFromUrdf`, once with a fixed base and once with a free-flyer root.
One JSON object per line is printed:

- `{"file", "floating", "refused": "<Pinocchio's error>"}` when Pinocchio cannot load it;
- otherwise `{"file", "floating", "nq", "nv", "joints", "states"}` with, per random state (fixed
  seed), q, v, a, tau and Pinocchio's rnea, crba (symmetrised) and aba, in rigid's conventions
  (see reference.py: angular-first free-flyer blocks, one angle per continuous joint). `aba` is
  null when Pinocchio's M is singular (a massless moving subtree) or its result is not finite.

The live cross-check (RIGID_CROSSCHECK=1) runs this script on every file; every run reads
packages.json, the fixture gen_packages.py writes with it for a few checked-in files.
"""

import glob
import json
import os
import site
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference import joint_layout, plain, q_to_rigid, robots_dir, v_perm  # noqa: E402


def site_dirs():
    return site.getsitepackages() + [site.getusersitepackages()]


def under_site(sub):
    for d in site_dirs():
        p = os.path.join(d, sub)
        if os.path.isdir(p):
            return p
    return None


def icub_models():
    for root in [sys.prefix] + site_dirs():
        for p in (os.path.join(root, "share/iCub/robots"),
                  os.path.join(root, "../../../share/iCub/robots")):
            if os.path.isdir(p):
                return os.path.normpath(p)
    return None


# name: function returning the package's folder (None when it is not installed)
PACKAGES = {
    "example-robot-data": robots_dir,
    "icub-models": icub_models,
    "upkie-description": lambda: under_site("upkie_description"),
    "jvrc-description": lambda: under_site("jvrc_description"),
    "gym-ignition-models": lambda: under_site("gym_ignition_models"),
    "airo-models": lambda: under_site("airo_models"),
    "cookie-description": lambda: under_site("cookie_description"),
}


def load(path, floating):
    """`(model, None)`, Pinocchio's model of the file (a free-flyer root when `floating`) with
    unbounded position limits replaced by [-1, 1] for random configurations, or
    `(None, {"refused": why})`."""
    try:
        if floating:
            model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
        else:
            model = pin.buildModelFromUrdf(path)
    except Exception as e:  # noqa: BLE001 (Pinocchio raises plain exceptions)
        return None, dict(refused=str(e).strip().splitlines()[-1] if str(e).strip() else repr(e))
    lo, up = model.lowerPositionLimit, model.upperPositionLimit
    model.lowerPositionLimit = np.where(np.abs(lo) < 1e10, lo, -1.0)
    model.upperPositionLimit = np.where(np.abs(up) < 1e10, up, 1.0)
    return model, None


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
        tau = np.random.uniform(-10.0, 10.0, model.nv)
        M = pin.crba(model, data, q).copy()
        M = np.triu(M) + np.triu(M, 1).T
        aba = None
        if nv > 0 and np.linalg.cond(M) < 1e10:
            x = pin.aba(model, data, q, v, tau)
            if np.all(np.isfinite(x)):
                aba = x[p]
        out.append(dict(
            q=q_to_rigid(joints, q, nq), v=v[p], a=a[p], tau=tau[p],
            rnea=pin.rnea(model, data, q, v, a)[p],
            mass_matrix=M[np.ix_(p, p)],
            aba=aba,
        ))
    return dict(nq=nq, nv=nv, joints=joints, states=out)


def each_file(args, one, states=3):
    """`PACKAGE [--states N] [--seed S]`: for every URDF file of the package, fixed and floating,
    one JSON line `{"package", "file", "floating", **one(file, floating, states, seed)}`."""
    name = args[0]
    states = int(args[args.index("--states") + 1]) if "--states" in args else states
    seed = int(args[args.index("--seed") + 1]) if "--seed" in args else 0
    if name not in PACKAGES:
        sys.exit(f"unknown package {name!r}; known: {', '.join(sorted(PACKAGES))}")
    root = PACKAGES[name]()
    if root is None:
        sys.exit(f"package {name} is not installed: pip install -r scripts/requirements-test.txt")
    files = sorted(glob.glob(os.path.join(root, "**", "*.urdf"), recursive=True))
    if not files:
        sys.exit(f"no .urdf file under {root}")
    for f in files:
        for floating in (False, True):
            rec = dict(package=name, file=f, floating=floating)
            rec.update(one(f, floating, states, seed))
            print(json.dumps(plain(rec)), flush=True)


def main():
    args = sys.argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        return
    if args[0] == "list":
        print(json.dumps(sorted(PACKAGES)))
        return
    if args[0] == "roots":
        print(json.dumps({name: find() for name, find in PACKAGES.items()}))
        return
    each_file(args, one)


if __name__ == "__main__":
    main()
