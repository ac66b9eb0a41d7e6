"""MJCF models and MuJoCo's layout against MuJoCo's own Python module (skipped without it).

With layout="mujoco" the raw arrays are MuJoCo's: qpos, qvel, qacc and qfrc in, mj_fullM
(armature included), qfrc_bias, the gravity forces and M qacc + qfrc_bias out, to 1e-9 relative
(the models of crates/rigid/tests/mujoco/models, copied from gymnasium, dm_control, brax and
mjx, plus two of rigid's own; the mesh model to 1e-6).
"""

import os
import warnings

import numpy as np
import pytest

import rigid
from conftest import ROOT

mujoco = pytest.importorskip("mujoco")

MODELS = os.path.join(ROOT, "crates", "rigid", "tests", "mujoco", "models")
NAMES = ["ant", "humanoid", "cheetah", "ball_joints", "capsule_armature", "convex", "features",
         "compiler"]


def load(name, layout="mujoco"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return rigid.Model.from_mjcf(os.path.join(MODELS, name + ".xml"), layout=layout)


def states(m, n=3, seed=0):
    """Random MuJoCo states: hinges and slides about qpos0, random unit quaternions."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        q = m.qpos0.copy()
        for j in range(m.njnt):
            a, t = m.jnt_qposadr[j], m.jnt_type[j]
            if t == 0:
                q[a:a + 3] = rng.uniform(-1, 1, 3)
                x = rng.normal(size=4)
                q[a + 3:a + 7] = x / np.linalg.norm(x)
            elif t == 1:
                x = rng.normal(size=4)
                q[a:a + 4] = x / np.linalg.norm(x)
            else:
                q[a] += rng.uniform(-1, 1)
        yield q, rng.uniform(-1, 1, m.nv), rng.uniform(-1, 1, m.nv)


def close(a, b, tol):
    scale = max(np.max(np.abs(b)), 1.0) if np.size(b) else 1.0
    assert np.max(np.abs(np.asarray(a) - b), initial=0.0) <= tol * scale, (a, b)


@pytest.mark.parametrize("name", NAMES)
def test_mujoco_layout_gives_mujocos_arrays(name):
    r = load(name)
    m = mujoco.MjModel.from_xml_path(os.path.join(MODELS, name + ".xml"))
    d = mujoco.MjData(m)
    tol = 1e-6 if name == "convex" else 1e-9
    assert (r.nq, r.nv, r.layout) == (m.nq, m.nv, "mujoco")
    close(r.qpos0[:3], m.qpos0[:3], 1e-12)
    rd = r.create_data()
    for q, v, a in states(m):
        d.qpos[:], d.qvel[:] = q, v
        mujoco.mj_forward(m, d)
        M = np.zeros((m.nv, m.nv))
        mujoco.mj_fullM(m, d, M)
        bias = d.qfrc_bias.copy()
        close(rigid.crba(r, rd, q), M, tol)
        close(rigid.nle(r, rd, q, v), bias, tol)
        close(rigid.rnea(r, rd, q, v, a), M @ a + bias, tol)
        close(rigid.aba(r, rd, q, v, M @ a + bias), a, 1e3 * tol)
        close(rigid.minverse(r, rd, q) @ M, np.eye(m.nv), 1e3 * tol)
        assert abs(rigid.kinetic_energy(r, rd, q, v) - 0.5 * v @ M @ v) <= tol * (1 + v @ M @ v)
        d.qvel[:] = 0
        mujoco.mj_forward(m, d)
        close(rigid.gravity(r, rd, q), d.qfrc_bias, tol)


def test_jacobian_columns_are_in_mujocos_velocity_coordinates():
    r = load("ant")
    m = mujoco.MjModel.from_xml_path(os.path.join(MODELS, "ant.xml"))
    d = mujoco.MjData(m)
    rd = r.create_data()
    q, v, _ = next(states(m))
    d.qpos[:], d.qvel[:] = q, v
    mujoco.mj_forward(m, d)
    body = m.body("torso").id
    jacp, jacr = np.zeros((3, m.nv)), np.zeros((3, m.nv))
    mujoco.mj_jacBody(m, d, jacp, jacr, body)
    J = rigid.jacobian(r, rd, q, "torso", frame="world_aligned")  # rows (ω, v)
    close(J[:3], jacr, 1e-12)
    close(J[3:], jacp, 1e-12)


def test_from_file_chooses_by_extension_and_rigid_layout_is_the_default():
    r = rigid.Model.from_file(os.path.join(MODELS, "cheetah.xml"))
    assert r.layout == "rigid" and r.nq == 9
    urdf = os.path.join(ROOT, "crates", "rigid", "tests", "pinocchio", "all_joints.urdf")
    assert rigid.Model.from_file(urdf).layout == "rigid"
    with pytest.raises(ValueError, match="floating"):
        rigid.Model.from_file(os.path.join(MODELS, "cheetah.xml"), floating=True)


def test_mjcf_errors_name_the_line_and_warnings_are_issued():
    with pytest.raises(FileNotFoundError):
        rigid.Model.from_mjcf("/no/such/model.xml")
    bad = os.path.join(ROOT, "crates", "rigid-cli", "tests", "corpus", "mjcf",
                       "fromto_zero_length.xml")
    with pytest.raises(ValueError, match="line 5.*fromto has zero length"):
        rigid.Model.from_mjcf(bad)
    with pytest.warns(rigid.MjcfWarning, match="gravcomp"):
        rigid.Model.from_mjcf(os.path.join(MODELS, "features.xml"))


def test_verbs_that_need_a_velocity_map_refuse_a_free_joint_in_mujocos_layout():
    r = load("ant")
    q = r.qpos0
    with pytest.raises(ValueError, match="free joint"):
        rigid.integrate(r, q, np.zeros(r.nv))
    with pytest.raises(ValueError, match="free joint"):
        rigid.rnea_batch(r, np.array([q]), np.zeros((1, r.nv)), np.zeros((1, r.nv)))
    # without a free joint, MuJoCo's layout is rigid's with hinges counted from ref: batches work
    c = load("cheetah")
    Q = np.array([c.qpos0, c.qpos0])
    tau = rigid.rnea_batch(c, Q, np.zeros((2, c.nv)), np.zeros((2, c.nv)))
    close(tau[0], rigid.gravity(c, c.create_data(), c.qpos0), 1e-12)
