"""Constrained dynamics against Pinocchio 4.1: rigid.constraint_dynamics / constraintDynamics,
impulse_dynamics / impulseDynamics (layout="pinocchio": Pinocchio's raw arrays, lambda_c and
impulse_c force first), and contact_inverse_dynamics checked on its own equation."""

import os

import numpy as np
import pytest

pin = pytest.importorskip("pinocchio")

import rigid
from conftest import ROOT, rel_err, TOL

FIX = os.path.join(ROOT, "crates", "rigid", "tests", "fixtures")
ERD = os.path.join(FIX, "robots", "example-robot-data", "robots")
CASES = [
    # (urdf, floating, kind, frames, reference frame, kp, kd)
    (os.path.join(ERD, "solo_description/robots/solo12.urdf"), True, "point",
     ["FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"], "local", 20.0, 5.0),
    (os.path.join(ERD, "talos_data/robots/talos_reduced.urdf"), True, "frame",
     ["left_sole_link", "right_sole_link"], "local_world_aligned", 10.0, 2.0),
]
PIN = {"point": pin.ContactType.CONTACT_3D, "frame": pin.ContactType.CONTACT_6D,
       "local": pin.LOCAL, "local_world_aligned": pin.LOCAL_WORLD_ALIGNED}


def state(pm, rng):
    q = pin.neutral(pm)
    q[:3] = rng.uniform(-0.5, 0.5, 3)
    quat = rng.standard_normal(4)
    q[3:7] = quat / np.linalg.norm(quat)
    q[7:] = rng.uniform(-1, 1, pm.nq - 7)
    return q, rng.uniform(-1, 1, pm.nv), rng.uniform(-5, 5, pm.nv)


@pytest.mark.parametrize("case", CASES, ids=["solo12_points", "talos_frames"])
def test_constraint_and_impulse_dynamics_equal_pinocchio(case):
    urdf, floating, kind, frames, rf, kp, kd = case
    pm = pin.buildModelFromUrdf(urdf, pin.JointModelFreeFlyer())
    pd = pm.createData()
    m = rigid.Model.from_urdf(urdf, floating=floating, layout="pinocchio")
    d = m.create_data()
    rng = np.random.default_rng(3)
    pin.framesForwardKinematics(pm, pd, pin.neutral(pm))
    cms, cs = [], []
    for f in frames:
        fr = pm.frames[pm.getFrameId(f)]
        target = pd.oMf[pm.getFrameId(f)] * pin.exp6(pin.Motion(0.02 * rng.standard_normal(6)))
        cm = pin.RigidConstraintModel(PIN[kind], pm, fr.parentJoint, fr.placement, 0, target, PIN[rf])
        cm.setBaumgarteCorrectorParameters(pin.BaumgarteCorrectorParameters(kp, kd))
        cms.append(cm)
        # the same by joint name and placements, and by the frame's name (placement1 equal)
        c = rigid.ConstraintModel(m, kind, pm.names[fr.parentJoint], fr.placement, "universe",
                                  (target.rotation, target.translation), rf, kp, kd)
        assert rigid.ConstraintModel.on_frames(m, PIN[kind], f).dim == c.dim
        cs.append(c)
    cds = [c.createData() for c in cms]
    pin.initConstraintDynamics(pm, pd, cms, cds)
    cd = rigid.ConstraintData(m, cs)
    for _ in range(2):
        q, v, tau = state(pm, rng)
        ddq = pin.constraintDynamics(pm, pd, q, v, tau, cms, cds)
        assert rel_err(rigid.constraintDynamics(m, d, q, v, tau, cd), ddq) < TOL
        assert rel_err(cd.lambda_c, pd.lambda_c) < TOL
        vp = pin.impulseDynamics(pm, pd, q, v, cms, cds, 0.3)
        assert rel_err(rigid.impulse_dynamics(m, d, q, v, cd, r_coeff=0.3), vp) < TOL
        assert rel_err(cd.impulse_c, pd.impulse_c) < TOL
        # inverse: the least-norm (τ, λ), τ zero on the free-flyer, the equation of motion holds
        a = rigid.constraint_dynamics(m, d, q, v, np.r_[np.zeros(6), tau[6:]], cd)
        t = rigid.contact_inverse_dynamics(m, d, q, v, a, cd)
        assert np.all(t[:6] == 0.0)
        lhs = pin.rnea(pm, pd, q, v, a)
        assert rel_err(t + cd.jacobian.T @ cd.lambda_c, lhs) < TOL
        assert cd.stats["dynamics_residual"] < 1e-9


@pytest.mark.parametrize("case", CASES, ids=["solo12_points", "talos_frames"])
def test_constraint_and_impulse_derivatives_equal_pinocchio(case):
    """rigid.constraint_dynamics_derivatives / impulse_dynamics_derivatives and the Pinocchio
    layer's computeConstraintDynamicsDerivatives / computeImpulseDynamicsDerivatives against
    Pinocchio 4.1's, feet on the world with Baumgarte gains, e = 0.5. ∂/∂q is also checked
    against central differences of Pinocchio's constraintDynamics: Pinocchio 4.1's own ∂/∂q is
    off from them for a world-aligned frame constraint with Baumgarte gains (TALOS here), and
    there rigid is compared with the central differences only."""
    import rigid.pinocchio as rp
    urdf, floating, kind, frames, rf, kp, kd = case
    pm = pin.buildModelFromUrdf(urdf, pin.JointModelFreeFlyer())
    pd = pm.createData()
    m = rigid.Model.from_urdf(urdf, floating=floating, layout="pinocchio")
    d = m.create_data()
    rng = np.random.default_rng(4)
    pin.framesForwardKinematics(pm, pd, pin.neutral(pm))
    cms = []
    for f in frames:
        fr = pm.frames[pm.getFrameId(f)]
        target = pd.oMf[pm.getFrameId(f)] * pin.exp6(pin.Motion(0.05 * rng.standard_normal(6)))
        cm = pin.RigidConstraintModel(PIN[kind], pm, fr.parentJoint, fr.placement, 0, target,
                                      PIN[rf])
        cm.setBaumgarteCorrectorParameters(pin.BaumgarteCorrectorParameters(kp, kd))
        cms.append(cm)
    cs = [rigid.ConstraintModel(m, kind, pm.names[c.joint1_id], c.joint1_placement, "universe",
                                (c.joint2_placement.rotation, c.joint2_placement.translation),
                                rf, kp, kd) for c in cms]
    cd = rigid.ConstraintData(m, cs)
    cds = [c.createData() for c in cms]
    pin.initConstraintDynamics(pm, pd, cms, cds)
    q, v, tau = state(pm, rng)

    def forward(q):
        return np.r_[pin.constraintDynamics(pm, pd, q, v, tau, cms, cds), pd.lambda_c]
    h = 1e-6
    fd = np.array([(forward(pin.integrate(pm, q, h * e)) - forward(pin.integrate(pm, q, -h * e)))
                   / (2 * h) for e in np.eye(pm.nv)]).T
    pin.constraintDynamics(pm, pd, q, v, tau, cms, cds)
    pin.computeConstraintDynamicsDerivatives(pm, pd, cms, cds)
    pinocchio_right = rel_err(np.r_[pd.ddq_dq, pd.dlambda_dq], fd) < 1e-6
    assert pinocchio_right == (case is CASES[0])
    ours = rigid.constraint_dynamics_derivatives(m, d, q, v, tau, cd)
    assert rel_err(np.r_[ours["ddq_dq"], ours["dlambda_dq"]], fd) < 1e-6
    keys = ["ddq_dv", "ddq_dtau", "dlambda_dv", "dlambda_dtau"]
    keys += ["ddq_dq", "dlambda_dq"] if pinocchio_right else []
    for k in keys:
        assert rel_err(ours[k], getattr(pd, k)) < 1e-9, k
    # the Pinocchio layer's verbs and conventions (data fields, ddq_dv of the impulse); the layer
    # has no Baumgarte setter, so each constraint is given rigid's, gains included
    rm = rp.buildModelFromUrdf(urdf, rp.JointModelFreeFlyer())
    rd = rm.createData()
    rcms = [rp.RigidConstraintModel(rp.ContactType(int(c.type)), rm, c.joint1_id) for c in cms]
    for rc, c in zip(rcms, cms):
        rc._c = rigid.ConstraintModel(rm, kind, pm.names[c.joint1_id], c.joint1_placement,
                                      "universe", (c.joint2_placement.rotation,
                                                   c.joint2_placement.translation), rf, kp, kd)
    rp.initConstraintDynamics(rm, rd, rcms)
    rp.constraintDynamics(rm, rd, q, v, tau, rcms)
    rp.computeConstraintDynamicsDerivatives(rm, rd, rcms)
    for k in ["ddq_dq", "ddq_dv", "ddq_dtau", "dlambda_dq", "dlambda_dv", "dlambda_dtau"]:
        assert rel_err(getattr(rd, k), ours[k]) < 1e-12, k
    pin.impulseDynamics(pm, pd, q, v, cms, cds, 0.5)
    pin.computeImpulseDynamicsDerivatives(pm, pd, cms, cds, 0.5)
    imp = rigid.impulse_dynamics_derivatives(m, d, q, v, cd, r_coeff=0.5)
    assert rel_err(imp["dvplus_dq"], pd.ddq_dq) < 1e-9
    assert rel_err(imp["dvplus_dv"] - np.eye(pm.nv), pd.ddq_dv) < 1e-9
    assert rel_err(imp["dimpulse_dq"], pd.dlambda_dq) < 1e-9
    assert rel_err(imp["dimpulse_dv"], pd.dlambda_dv) < 1e-9
    rp.impulseDynamics(rm, rd, q, v, rcms, r_coeff=0.5)
    rp.computeImpulseDynamicsDerivatives(rm, rd, rcms, r_coeff=0.5)
    assert rel_err(rd.ddq_dq, pd.ddq_dq) < 1e-9 and rel_err(rd.ddq_dv, pd.ddq_dv) < 1e-9
    assert rel_err(rd.dlambda_dq, pd.dlambda_dq) < 1e-9
    # ABA's derivatives replace the constrained ones in data.ddq_dq
    rp.computeABADerivatives(rm, rd, q, v, tau)
    assert rel_err(rd.ddq_dq, pin.computeABADerivatives(pm, pm.createData(), q, v, tau)[0]) < 1e-9


def test_rigid_layout_wrench_is_moment_first_and_errors_are_value_errors():
    urdf = CASES[1][0]
    lam = {}
    for layout in ["rigid", "pinocchio"]:
        # at the neutral configuration, at rest, no torque: the same state in both joint orders
        m = rigid.Model.from_urdf(urdf, floating=True, layout=layout)
        c = rigid.ConstraintModel.on_frames(m, "frame", "left_sole_link", kp=0.0)
        cd = rigid.ConstraintData(m, [c])
        d = m.create_data()
        q = rigid.neutral(m)
        rigid.constraint_dynamics(m, d, q, np.zeros(m.nv), np.zeros(m.nv), cd)
        lam[layout] = cd.lambda_c
    assert rel_err(lam["rigid"], np.r_[lam["pinocchio"][3:], lam["pinocchio"][:3]]) < TOL
    with pytest.raises(ValueError, match="no joint named"):
        rigid.ConstraintModel(m, "point", "elbow")
    with pytest.raises(ValueError, match=r'"reference_frame" is "world" \(expected "local" or'):
        rigid.ConstraintModel.on_frames(m, "point", "left_sole_link", reference_frame="world")
    other = rigid.Model.builtin("double_pendulum")
    with pytest.raises(ValueError, match="another model"):
        rigid.constraint_dynamics(other, other.create_data(), [0, 0], [0, 0], [0, 0], cd)


def test_mjcf_equalities_are_constraint_models():
    """ConstraintModel.from_mjcf: fourbar.xml's <connect> closes the loop as fourbar.urdf's
    constraint written by hand (q shifted by the assembly angles); equalities.xml's tendon and
    inactive equalities are MjcfWarnings; a URDF model is refused."""
    xml = os.path.join(FIX, "constraints", "fourbar.xml")
    m = rigid.Model.from_mjcf(xml)
    cs = rigid.ConstraintModel.from_mjcf(m)
    assert [c.dim for c in cs] == [3]
    u = rigid.Model.from_urdf(os.path.join(FIX, "constraints", "fourbar.urdf"))
    hand = rigid.ConstraintModel(u, "point", "coupler_joint", (np.eye(3), [0.8, 0, 0]),
                                 "rocker_joint", (np.eye(3), [0.6, 0, 0]),
                                 reference_frame="local_world_aligned")
    q, v, tau = np.array([0.1, -0.2, 0.05]), np.array([0.5, -1.0, 0.3]), np.array([0.2, 0, -0.1])
    assembly = np.array([0.5, 0.02116623166979137, 1.1280269456729848])
    cx, cu = rigid.ConstraintData(m, cs), rigid.ConstraintData(u, [hand])
    ax = rigid.constraint_dynamics(m, m.create_data(), q, v, tau, cx, mu=1e-6, max_iter=1000)
    au = rigid.constraint_dynamics(u, u.create_data(), q + assembly, v, tau, cu, mu=1e-6,
                                   max_iter=1000)
    assert rel_err(ax, au) < 1e-9 and rel_err(cx.lambda_c, cu.lambda_c) < 1e-9
    with pytest.warns(rigid.MjcfWarning, match="tendon equalities are not modelled"):
        more = rigid.ConstraintModel.from_mjcf(
            rigid.Model.from_mjcf(os.path.join(FIX, "constraints", "equalities.xml")))
    assert [c.dim for c in more] == [6, 1, 3, 6, 6]
    with pytest.raises(ValueError, match="not read from an MJCF file"):
        rigid.ConstraintModel.from_mjcf(u)
