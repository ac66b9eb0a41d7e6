"""Mimic joints as couplings: `rigid.Model.from_urdf(path, mimic=True)` against Pinocchio 4.1's
`buildModelFromUrdf(path, mimic=True)` on the example-robot-data robots that have mimic joints,
both in Pinocchio's layout so that the arrays compare as they are, and the robots Pinocchio
refuses (a mimic's source later in the tree) against the identities."""

import os
import warnings

import numpy as np
import pytest

import rigid
from conftest import TOL, assert_close, pin, symmetric

# the files' own findings (non-physical inertias, unknown elements) are warned as they load
pytestmark = [pytest.mark.skipif(pin is None, reason="needs Pinocchio (pip install pin)"),
              pytest.mark.filterwarnings("ignore::rigid.UrdfWarning")]

if pin is not None:
    from reference import robots_dir

PINOCCHIO = ["panda_description/urdf/panda.urdf", "baxter_description/urdf/baxter.urdf",
             "pr2_description/urdf/pr2.urdf", "tiago_pro_description/robots/tiago_pro.urdf"]
REFUSED = ["talos_data/robots/talos_full_v2.urdf", "romeo_description/urdf/romeo.urdf"]


@pytest.mark.parametrize("rel", PINOCCHIO)
def test_mimic_equals_pinocchio_mimic_true(rel):
    path = os.path.join(robots_dir(), rel)
    pm = pin.buildModelFromUrdf(path, mimic=True)
    pd = pm.createData()
    mm = rigid.Model.from_urdf(path, mimic=True, layout="pinocchio")
    assert isinstance(mm, rigid.MimicModel)
    assert (mm.nq, mm.nv) == (pm.nq, pm.nv)
    mimic_names = {n for j, n in zip(pm.joints[1:], pm.names[1:]) if "Mimic" in j.shortname()}
    assert {m[0] for m in mm.mimics} == mimic_names
    rng = np.random.default_rng(7)
    for _ in range(3):
        q = pin.integrate(pm, pin.neutral(pm), rng.uniform(-1, 1, pm.nv))
        v, a, tau = (rng.uniform(-1, 1, pm.nv) for _ in range(3))
        M = symmetric(pin.crba(pm, pd, q))
        nle = pin.nonLinearEffects(pm, pd, q, v)
        assert_close(mm.rnea(q, v, a), pin.rnea(pm, pd, q, v, a), f"{rel}: rnea")
        assert_close(mm.crba(q), M, f"{rel}: crba")
        assert_close(mm.nle(q, v), nle, f"{rel}: nle")
        # Pinocchio's aba refuses mimic joints: M⁻¹ (τ − nle) from its own M and nle
        assert_close(mm.aba(q, v, tau), np.linalg.solve(M, tau - nle), f"{rel}: aba")
        frame = pm.frames[-1].name
        J = pin.computeFrameJacobian(pm, pd, q, pm.getFrameId(frame), pin.LOCAL_WORLD_ALIGNED)
        assert_close(mm.frame_jacobian(q, frame), J, f"{rel}: frame Jacobian")
        joint = pm.names[-1]
        J = pin.computeJointJacobian(pm, pd, q, pm.getJointId(joint))
        assert_close(mm.frame_jacobian(q, joint, "body"), J, f"{rel}: joint Jacobian")


@pytest.mark.parametrize("rel", REFUSED)
def test_sources_later_in_the_tree_load_and_pass_the_identities(rel):
    path = os.path.join(robots_dir(), rel)
    with pytest.raises(Exception, match="not in the kinematic tree"):
        pin.buildModelFromUrdf(path, mimic=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mm = rigid.Model.from_urdf(path, mimic=True)
    assert mm.mimics and mm.nv < len(mm.expand_v(np.zeros(mm.nv)))
    rng = np.random.default_rng(3)
    for _ in range(3):
        q = mm.neutral() + rng.uniform(-0.5, 0.5, mm.nq)
        v, tau = rng.uniform(-1, 1, mm.nv), rng.uniform(-1, 1, mm.nv)
        M = mm.crba(q)
        assert np.allclose(M, M.T, rtol=0, atol=1e-12 * np.abs(M).max())
        assert_close(mm.rnea(q, v, tau), M @ tau + mm.nle(q, v), f"{rel}: rnea = M a + nle")
        if "romeo" in rel:
            # Romeo's finger links weigh nothing: M is singular with or without the couplings
            assert np.linalg.eigvalsh(M).min() > -1e-12 * np.abs(M).max()
            continue
        assert np.linalg.eigvalsh(M).min() > 0
        ddq = mm.aba(q, v, tau)
        assert_close(mm.rnea(q, v, ddq), tau, f"{rel}: rnea(aba(tau))")
        dq, dv, minv = mm.aba_derivatives(q, v, tau)
        assert_close(minv @ M, np.eye(mm.nv), f"{rel}: M⁻¹ M")
        # ∂q̈/∂x = −M⁻¹ ∂τ/∂x at a = q̈
        dtq, dtv, _ = mm.rnea_derivatives(q, v, ddq)
        assert_close(dq, -minv @ dtq, f"{rel}: ∂q̈/∂q")
        assert_close(dv, -minv @ dtv, f"{rel}: ∂q̈/∂v")


def test_alex_mimics_name_joints_it_does_not_have_and_are_warned():
    # "index_q1" for "Left_index_q1": the reason Pinocchio refuses the file
    path = os.path.join(robots_dir(), "alex_description/urdf/alex_psyonic_hands.urdf")
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        mm = rigid.Model.from_urdf(path, mimic=True)
    assert sum("which is not defined" in str(w.message) for w in record) == 8
    assert mm.mimics == []


def test_mimic_errors_are_named():
    path = os.path.join(robots_dir(), PINOCCHIO[0])
    mm = rigid.Model.from_urdf(path, mimic=True)
    with pytest.raises(ValueError, match="MimicModel.rnea: .*q"):
        mm.rnea(np.zeros(mm.nq + 1), np.zeros(mm.nv), np.zeros(mm.nv))
    with pytest.raises(ValueError, match="not finite"):
        mm.aba(np.full(mm.nq, np.nan), np.zeros(mm.nv), np.zeros(mm.nv))


def test_the_pinocchio_layer_points_at_the_mimic_model():
    import rigid.pinocchio as rpin
    path = os.path.join(robots_dir(), PINOCCHIO[0])
    with pytest.raises(NotImplementedError, match="rigid.Model.from_urdf\\(path, mimic=True"):
        rpin.buildModelFromUrdf(path, mimic=True)


ARM_MJCF = """<mujoco>
  <worldbody>
    <body name="upper">
      <joint name="a" type="hinge" axis="0 0 1"/>
      <inertial pos="0.5 0 0" mass="1" diaginertia="0.01 0.1 0.1"/>
      <body name="lower" pos="1 0 0">
        <joint name="b" type="hinge" axis="0 1 0"/>
        <inertial pos="0.4 0 0.1" mass="2" diaginertia="0.05 0.2 0.22"/>
      </body>
    </body>
  </worldbody>
  <equality><joint joint1="b" joint2="a" polycoef="0.1 2 0 0 0"/></equality>
</mujoco>"""

GEARBOX_SDF = """<?xml version="1.0"?>
<sdf version="1.9"><model name="m">
  <link name="rotor"><pose>0 0 0 0 0 0</pose><inertial><mass>1</mass></inertial></link>
  <link name="out"><pose>0.1 0 0 0 0 0</pose><inertial><mass>2</mass></inertial></link>
  <joint name="ip" type="revolute"><parent>world</parent><child>rotor</child>
    <axis><xyz>1 0 0</xyz></axis></joint>
  <joint name="op" type="revolute"><parent>world</parent><child>out</child>
    <axis><xyz>-1 0 0</xyz></axis></joint>
  <joint name="gear" type="gearbox"><parent>rotor</parent><child>out</child>
    <gearbox_reference_body>world</gearbox_reference_body><gearbox_ratio>0.25</gearbox_ratio>
    <axis><xyz>1 0 0</xyz></axis><axis2><xyz>1 0 0</xyz></axis2></joint>
</model></sdf>"""


@pytest.mark.parametrize("kind", ["mjcf", "sdf"])
def test_mjcf_and_sdf_couplings_with_mimic_true(tmp_path, kind):
    """`Model.from_mjcf(path, mimic=True)` (an `<equality joint>` with a linear polynomial) and
    `Model.from_sdf(path, mimic=True)` (a gearbox): one coordinate left, and the reduced dynamics
    equal the full model's (`mimic=False`, the same file) through the coupling's constant
    Jacobian `G = ∂q/∂q_r`: `M_r = Gᵀ M G`, `τ_r = Gᵀ rnea(q, G v, G a)`; MuJoCo's layout is
    refused."""
    path = tmp_path / ("arm.xml" if kind == "mjcf" else "gear.sdf")
    path.write_text(ARM_MJCF if kind == "mjcf" else GEARBOX_SDF)
    load = rigid.Model.from_mjcf if kind == "mjcf" else rigid.Model.from_sdf
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the files' own omissions (no geometry, ...)
        full, mm = load(path), load(path, mimic=True)
    assert isinstance(mm, rigid.MimicModel) and (full.nv, mm.nq, mm.nv) == (2, 1, 1)
    (driven, source, multiplier, offset), = mm.mimics
    assert (driven, source, multiplier, offset) == (("b", "a", 2.0, 0.1) if kind == "mjcf"
                                                      else ("op", "ip", 0.25, 0.0))
    ia, ib = full.names.index(source), full.names.index(driven)
    G = np.zeros((2, 1))
    G[ia, 0], G[ib, 0] = 1.0, multiplier
    d = full.create_data()
    rng = np.random.default_rng(4)
    for _ in range(3):
        qr, vr, ar = rng.uniform(-1, 1, (3, 1))
        q = mm.expand_q(qr)
        assert_close(q, G @ qr + np.eye(2)[ib] * offset, "expand_q", tol=1e-15)
        assert_close(mm.crba(qr), G.T @ rigid.crba(full, d, q) @ G, "M_r", tol=1e-13)
        assert_close(mm.rnea(qr, vr, ar), G.T @ rigid.rnea(full, d, q, G @ vr, G @ ar), "tau_r",
                     tol=1e-13)
    with pytest.raises(ValueError, match="mimic=True with layout=\"mujoco\""):
        load(path, layout="mujoco", mimic=True)
