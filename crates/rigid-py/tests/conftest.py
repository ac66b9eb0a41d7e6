"""Shared fixtures of the Python tests: the example-robot-data robots, Pinocchio models of them,
and the map between rigid's layout and Pinocchio's (by joint name, as the Rust cross-check does).

The reference is Pinocchio 4.1 (`pin`, with `example-robot-data`), installed by scripts/test.sh.
"""

import glob
import json
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

try:  # the reference; without it the tests that compare with Pinocchio skip
    import pinocchio as pin
except ImportError:
    pin = None

import rigid

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "crates", "rigid", "tests", "pinocchio"))
if pin is not None:
    from reference import ROBOTS, robots_dir  # noqa: E402

# The agreement asked of every verb: max |rigid - Pinocchio| / max(1, max |Pinocchio|).
TOL = 1e-9

# Robots of the cross-check: (name, path, floating). UR5 and Panda fixed, the legged robots and
# Talos on a free-flyer, and a fixture with every joint type (continuous, planar, a free-flyer
# below the root, prismatic on unaligned axes, siblings out of name order).
NAMES = ["ur5", "panda", "solo12", "anymal", "talos", "double_pendulum", "all_joints",
         "all_joints_floating"]


def robot_path(name):
    rel, floating = ROBOTS[name]
    if rel.startswith("local:"):
        return os.path.join(ROOT, "crates", "rigid", "tests", "pinocchio", rel[6:]), floating
    return os.path.join(robots_dir(), rel), floating


def every_urdf():
    """Every URDF file of example-robot-data (found by walking its folder)."""
    return sorted(glob.glob(os.path.join(robots_dir(), "**", "*.urdf"), recursive=True))


def cli(*args):
    """`rigid ARGS --json` of the command-line tool (built by `cargo test --workspace`)."""
    out = subprocess.run(["cargo", "run", "-q", "-p", "rigid-cli", "--", *args, "--json"],
                         cwd=ROOT, capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def rel_err(x, ref):
    x, ref = np.asarray(x, dtype=float), np.asarray(ref, dtype=float)
    assert x.shape == ref.shape, f"shape {x.shape} != reference {ref.shape}"
    if x.size == 0:
        return 0.0
    e = np.max(np.abs(x - ref)) / max(1.0, np.max(np.abs(ref)))
    return np.inf if np.isnan(e) else e


def assert_close(x, ref, what, tol=TOL):
    e = rel_err(x, ref)
    assert e <= tol, f"{what}: differs from Pinocchio by {e:.3e} (tolerance {tol:g})"


def symmetric(m):
    """Pinocchio's crba and computeMinverse fill the upper triangle only."""
    m = np.array(m)
    return np.triu(m) + np.triu(m, 1).T


class Pair:
    """One robot loaded by Pinocchio and by rigid in both layouts, with random states."""

    def __init__(self, name, states=3, seed=0):
        path, floating = robot_path(name)
        self.name, self.path, self.floating = name, path, floating
        if floating:
            self.pm = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
        else:
            self.pm = pin.buildModelFromUrdf(path)
        self.pd = self.pm.createData()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", rigid.UrdfWarning)  # ANYmal's dummy base inertia
            self.rp = rigid.Model.from_urdf(path, floating=floating, layout="pinocchio")
            self.rr = rigid.Model.from_urdf(path, floating=floating)
        lo, up = self.pm.lowerPositionLimit, self.pm.upperPositionLimit
        self.pm.lowerPositionLimit = np.where(np.abs(lo) < 1e10, lo, -1.0)
        self.pm.upperPositionLimit = np.where(np.abs(up) < 1e10, up, 1.0)
        rng = np.random.default_rng(seed)
        pin.seed(seed)
        nv = self.pm.nv
        self.states = [
            (pin.randomConfiguration(self.pm), rng.uniform(-1, 1, nv), rng.uniform(-1, 1, nv),
             rng.uniform(-10, 10, nv))
            for _ in range(states)
        ]
        self._maps()

    def _maps(self):
        """Index maps from Pinocchio's layout to rigid's, joint by joint by name."""
        pm, rr = self.pm, self.rr
        pin_joint = {pm.names[i]: pm.joints[i] for i in range(1, pm.njoints)}
        self.v_map = np.zeros(rr.nv, dtype=int)  # rigid v[k] = pin v[v_map[k]]
        self.q_parts = []  # (rigid slice start, kind, pin idx_q, nq)
        for name, t, iq, nq, iv, nv in zip(rr.names, rr.joint_types, rr.idx_qs, rr.nqs,
                                            rr.idx_vs, rr.nvs):
            j = pin_joint[name]
            src = list(range(j.idx_v, j.idx_v + nv))
            if t == "free_flyer":
                src = src[3:] + src[:3]
            self.v_map[iv:iv + nv] = src
            self.q_parts.append((iq, t, j.idx_q, nq))

    def q_rigid(self, q):
        out = np.zeros(self.rr.nq)
        for iq, t, pq, nq in self.q_parts:
            s = q[pq:]
            if t == "continuous":
                out[iq] = np.arctan2(s[1], s[0])
            elif t == "planar":
                out[iq:iq + 3] = [s[0], s[1], np.arctan2(s[3], s[2])]
            else:
                out[iq:iq + nq] = s[:nq]
        return out

    def v_rigid(self, v):
        return np.asarray(v)[self.v_map]

    def m_rigid(self, m):
        return np.asarray(m)[np.ix_(self.v_map, self.v_map)]


_PAIRS = {}


def pair(name):
    if pin is None:
        pytest.skip("Pinocchio is not installed (pip install pin)")
    if name not in _PAIRS:
        _PAIRS[name] = Pair(name)
    return _PAIRS[name]


@pytest.fixture(params=NAMES)
def robot(request):
    return pair(request.param)
