"""Pinocchio's algorithms, by rigid: most are rigid's own functions under Pinocchio's names (the
model and data are rigid's, in Pinocchio's layout); the rest call rigid's verbs and keep what
Pinocchio keeps in ``data``.
"""

import numpy as np

from .. import rigid as _r
from .joints import KinematicLevel, ReferenceFrame
from .spatial import SE3, Force, Motion, _seed

# ---------------------------------------------------------------- rigid's own functions

rnea = _r.rnea
aba = _r.aba
crba = _r.crba
forwardKinematics = _r.forward_kinematics
updateFramePlacements = _r.update_frame_placements
framesForwardKinematics = _r.frames_forward_kinematics
computeJointJacobians = _r.compute_joint_jacobians
nonLinearEffects = nle = _r.nle
computeGeneralizedGravity = _r.gravity
computeMinverse = _r.minverse
computeCoriolisMatrix = _r.coriolis_matrix
ccrba = _r.centroidal_momentum_matrix
integrate = _r.integrate
difference = _r.difference
interpolate = _r.interpolate
neutral = _r.neutral
normalize = _r.normalize
computeRNEADerivatives = _r.rnea_derivatives
def computeABADerivatives(model, data, *args):
    """``∂q̈/∂q``, ``∂q̈/∂v``, ``∂q̈/∂τ`` of ABA (``data.ddq_dq``, ``ddq_dv``, ``ddq_dtau``,
    replacing those of a constrained dynamics)."""
    data.__dict__.pop("_constrained", None)
    return _r.aba_derivatives(model, data, *args)
computeGeneralizedGravityDerivatives = _r.gravity_derivatives
computeJointTorqueRegressor = _r.regressor


def seed(s):
    """Seed ``randomConfiguration`` and the ``Random()`` constructors."""
    _r.seed(int(s))
    _seed(int(s))


def randomConfiguration(model, lower=None, upper=None):
    """A random configuration within ``lower``, ``upper`` (default: the model's position
    limits; where a bound is infinite or Pinocchio's ``±max double``, angles in ``[-π, π]`` and
    translations in ``[-1, 1]`` m; quaternions and continuous joints uniform)."""
    if lower is None and upper is None:
        lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    return _r.random_configuration(model, lower, upper)


def _frame_source(model, frame_id, func):
    n = model.nframes
    if not 0 <= frame_id < n:
        raise ValueError(f"{func}: frame_id {frame_id} out of range (nframes = {n})")
    return model._frames[frame_id][1]


def _place(src):
    """The native functions' name of a frame source (``None`` for the universe)."""
    return None if src[0] == "world" else (src[0], src[1])


def _joint(model, joint_id, func):
    if not 0 <= joint_id < model.njoints:
        raise ValueError(f"{func}: joint_id {joint_id} out of range (njoints = {model.njoints})")
    return None if joint_id == 0 else ("joint", joint_id - 1)


def _rf(rf):
    return ReferenceFrame(rf).name


def _last_q(data):
    q = _r.Data.q_in.__get__(data)
    if q.size != data._model.nq:
        raise ValueError("no configuration: call an algorithm with q first (forwardKinematics)")
    return q


# ---------------------------------------------------------------- kinematics


def updateFramePlacement(model, data, frame_id):
    """The world pose of frame ``frame_id`` from the joint placements (and every frame's)."""
    _r.update_frame_placements(model, data)
    return data.oMf[frame_id]


def computeJointJacobian(model, data, q, joint_id):
    """The Jacobian of joint ``joint_id`` in its own frame (LOCAL), 6 x nv."""
    p = _joint(model, joint_id, "computeJointJacobian")
    if p is None:
        return np.zeros((6, model.nv))
    return _r.jacobian(model, data, q, model.names[joint_id], "local")


def getJointJacobian(model, data, joint_id, rf):
    """The Jacobian of joint ``joint_id`` in ``rf`` from ``data.J`` (``computeJointJacobians``
    first)."""
    p = _joint(model, joint_id, "getJointJacobian")
    if p is None:
        return np.zeros((6, model.nv))
    return _r._stored_jacobian(model, data, p, _rf(rf))


def getFrameJacobian(model, data, frame_id, rf=ReferenceFrame.LOCAL):
    """The Jacobian of frame ``frame_id`` in ``rf`` from ``data.J`` (``computeJointJacobians``
    first)."""
    p = _place(_frame_source(model, frame_id, "getFrameJacobian"))
    if p is None:
        return np.zeros((6, model.nv))
    return _r._stored_jacobian(model, data, p, _rf(rf))


def computeFrameJacobian(model, data, q, frame_id, rf=ReferenceFrame.LOCAL):
    """The Jacobian of frame ``frame_id`` at ``q`` in ``rf``."""
    _r.compute_joint_jacobians(model, data, q)
    return getFrameJacobian(model, data, frame_id, rf)


def getVelocity(model, data, joint_id, rf=ReferenceFrame.LOCAL):
    """The joint's spatial velocity from ``data.v`` (``forwardKinematics(q, v)`` first)."""
    return _express(data.v[joint_id], data.oMi[joint_id], rf)


def getAcceleration(model, data, joint_id, rf=ReferenceFrame.LOCAL):
    return _express(data.a[joint_id], data.oMi[joint_id], rf)


def getClassicalAcceleration(model, data, joint_id, rf=ReferenceFrame.LOCAL):
    return _classical(data.v[joint_id], data.a[joint_id], data.oMi[joint_id], rf)


def _express(m, oMx, rf):
    """A body-frame motion ``m`` of the frame at ``oMx`` expressed in ``rf``."""
    rf = ReferenceFrame(rf)
    if rf == ReferenceFrame.LOCAL:
        return m
    if rf == ReferenceFrame.WORLD:
        return oMx.act(m)
    return SE3(oMx.rotation, np.zeros(3)).act(m)


def _classical(v, a, oMx, rf):
    """The classical acceleration ``(a + ω × v)`` of the frame's origin in ``rf``."""
    c = Motion(a.linear + np.cross(v.angular, v.linear), a.angular)
    rf = ReferenceFrame(rf)
    if rf == ReferenceFrame.LOCAL:
        return c
    if rf == ReferenceFrame.LOCAL_WORLD_ALIGNED:
        return SE3(oMx.rotation, np.zeros(3)).act(c)
    raise NotImplementedError("getClassicalAcceleration in WORLD: use LOCAL or "
                              "LOCAL_WORLD_ALIGNED (the classical acceleration of a point)")


def _frame_motion(model, data, frame_id, which):
    f = model.frames[frame_id]
    return f.placement.actInv(getattr(data, which)[f.parentJoint]), \
        data.oMi[f.parentJoint] * f.placement


def getFrameVelocity(model, data, frame_id, rf=ReferenceFrame.LOCAL):
    """The frame's spatial velocity from ``data.v`` (``forwardKinematics(q, v)`` first)."""
    m, oMf = _frame_motion(model, data, frame_id, "v")
    return _express(m, oMf, rf)


def getFrameAcceleration(model, data, frame_id, rf=ReferenceFrame.LOCAL):
    m, oMf = _frame_motion(model, data, frame_id, "a")
    return _express(m, oMf, rf)


def getFrameClassicalAcceleration(model, data, frame_id, rf=ReferenceFrame.LOCAL):
    v, oMf = _frame_motion(model, data, frame_id, "v")
    a, _ = _frame_motion(model, data, frame_id, "a")
    return _classical(v, a, oMf, rf)


# ---------------------------------------------------------------- centre of mass, momentum


def centerOfMass(model, data, *args, computeSubtreeComs=True):
    """The centre of mass (world frame) at ``q`` (and with ``v``, ``a``: its velocity and
    acceleration, ``data.vcom[0]``, ``data.acom[0]``); ``data.com[i]`` of the subtrees in joint
    i's frame, as Pinocchio. ``centerOfMass(model, data[, kinematic_level])`` uses the last
    ``q``."""
    args = list(args)
    if args and isinstance(args[-1], bool):
        computeSubtreeComs = args.pop()
    if not args or isinstance(args[0], (KinematicLevel, int)) and not isinstance(
            args[0], np.ndarray):
        args = [_last_q(data)]
    c = _r._subtree_centers_of_mass(model, data, *args[:3])
    data._com_local = True
    return c


def jacobianCenterOfMass(model, data, q=None, computeSubtreeComs=True):
    """The Jacobian of the centre of mass (3 x nv, world frame); ``data.com[i]`` of the subtrees
    in the world frame, as Pinocchio."""
    if q is None or isinstance(q, bool):
        q = _last_q(data)
    J = _r.com_jacobian(model, data, q)
    data._com_local = False
    return J


def computeCentroidalMomentum(model, data, q=None, v=None):
    """The centroidal momentum ``h_G`` (a ``Force``: linear, then angular momentum about the
    centre of mass); also ``data.hg``, ``data.com[0]``, ``data.vcom[0]``."""
    if q is None:
        q, v = _last_q(data), _r.Data.v_in.__get__(data)
    return Force(_r.centroidal_momentum(model, data, q, v))


def computeTotalMass(model, data=None):
    """The mass of the moving bodies."""
    return model.total_mass


def computeSubtreeMasses(model, data):
    _r._subtree_centers_of_mass(model, data, _last_q(data))


# ---------------------------------------------------------------- energies and all terms


def computeKineticEnergy(model, data, q=None, v=None):
    """``½ vᵀ M v``, also in ``data.kinetic_energy`` (without ``q``, ``v``: the last ones)."""
    if q is None:
        q, v = _last_q(data), _r.Data.v_in.__get__(data)
    data.kinetic_energy = _r.kinetic_energy(model, data, q, v)
    return data.kinetic_energy


def computePotentialEnergy(model, data, q=None):
    """``-Σ mᵢ gᵀ cᵢ``, also in ``data.potential_energy``."""
    if q is None:
        q = _last_q(data)
    data.potential_energy = _r.potential_energy(model, data, q)
    return data.potential_energy


def computeMechanicalEnergy(model, data, q=None, v=None):
    computeKineticEnergy(model, data, q, v)
    computePotentialEnergy(model, data, q)
    return data.mechanical_energy


def computeAllTerms(model, data, q, v):
    """``M``, ``nle``, ``g``, the Jacobians ``J``, the centre of mass (subtrees in their joints'
    frames, as ``centerOfMass``), ``Jcom``, ``Ag``, ``hg``, ``Ig``, ``vcom[0]``, the energies, and the placements and
    velocities of ``forwardKinematics(q, v)``."""
    _r.crba(model, data, q)
    _r.nle(model, data, q, v)
    _r.gravity(model, data, q)
    data.potential_energy = _r.potential_energy(model, data, q)
    _r.com_jacobian(model, data, q)
    _r.centroidal_momentum_matrix(model, data, q, v)
    _r.centroidal_momentum(model, data, q, v)
    data.kinetic_energy = _r.kinetic_energy(model, data, q, v)
    data._com_local = True


# ---------------------------------------------------------------- kinematics derivatives


def computeForwardKinematicsDerivatives(model, data, q, v, a):
    """Forward kinematics at ``(q, v, a)`` and ``data.J``; the derivatives themselves are read
    by ``getJointVelocityDerivatives``, ``getJointAccelerationDerivatives``,
    ``getFrameVelocityDerivatives``, ``getFrameAccelerationDerivatives``."""
    _r.forward_kinematics(model, data, q, v, a)
    _r.compute_joint_jacobians(model, data, q)
    data._fk_state = (np.array(q, dtype=float).reshape(-1), np.array(v, dtype=float).reshape(-1),
                      np.array(a, dtype=float).reshape(-1))


def _kin_derivatives(model, data, place, rf, func, oMx=None):
    """The five derivatives of ``kinematics_derivatives``. Pinocchio's LOCAL_WORLD_ALIGNED ones
    are the WORLD ones moved to the frame's origin ``p`` as a fixed point (``linear -= p ×
    angular``, ``p`` held still), not the derivatives of ``(ω, ṗ)`` (rigid's
    ``"world_aligned"``)."""
    state = getattr(data, "_fk_state", None)
    if state is None:
        raise ValueError(f"{func}: call computeForwardKinematicsDerivatives first")
    if place is None:
        z = np.zeros((6, model.nv))
        return z, z.copy(), z.copy(), z.copy(), z.copy()
    if ReferenceFrame(rf) != ReferenceFrame.LOCAL_WORLD_ALIGNED:
        return _r.kinematics_derivatives(model, data, *state, place, _rf(rf))
    out = _r.kinematics_derivatives(model, data, *state, place, "WORLD")
    P = oMx().translation
    S = np.array([[0.0, -P[2], P[1]], [P[2], 0.0, -P[0]], [-P[1], P[0], 0.0]])
    for m in out:
        m[:3] -= S @ m[3:]
    return out


def getJointVelocityDerivatives(model, data, joint_id, rf):
    """``(∂v/∂q, ∂v/∂v)`` of the joint's spatial velocity in ``rf``."""
    d = _kin_derivatives(model, data, _joint(model, joint_id, "getJointVelocityDerivatives"), rf,
                         "getJointVelocityDerivatives", lambda: data.oMi[joint_id])
    return d[0], d[1]


def getJointAccelerationDerivatives(model, data, joint_id, rf):
    """``(∂v/∂q, ∂a/∂q, ∂a/∂v, ∂a/∂a)`` of the joint's spatial velocity and acceleration."""
    d = _kin_derivatives(model, data, _joint(model, joint_id,
                                             "getJointAccelerationDerivatives"), rf,
                         "getJointAccelerationDerivatives", lambda: data.oMi[joint_id])
    return d[0], d[2], d[3], d[4]


def _frame_pose(model, data, frame_id):
    f = model.frames[frame_id]
    return data.oMi[f.parentJoint] * f.placement


def getFrameVelocityDerivatives(model, data, frame_id, rf):
    p = _place(_frame_source(model, frame_id, "getFrameVelocityDerivatives"))
    d = _kin_derivatives(model, data, p, rf, "getFrameVelocityDerivatives",
                         lambda: _frame_pose(model, data, frame_id))
    return d[0], d[1]


def getFrameAccelerationDerivatives(model, data, frame_id, rf):
    p = _place(_frame_source(model, frame_id, "getFrameAccelerationDerivatives"))
    d = _kin_derivatives(model, data, p, rf, "getFrameAccelerationDerivatives",
                         lambda: _frame_pose(model, data, frame_id))
    return d[0], d[2], d[3], d[4]


# ---------------------------------------------------------------- configurations


def isNormalized(model, q, prec=1e-12):
    """Every quaternion (and cos/sin pair) of ``q`` of unit norm within ``prec``."""
    return bool(np.allclose(_r.normalize(model, q), np.asarray(q, dtype=float).reshape(-1),
                            rtol=0, atol=prec))


def isSameConfiguration(model, q1, q2, prec=1e-12):
    return bool(np.all(np.abs(_r.difference(model, q1, q2)) <= prec))


def squaredDistance(model, q0, q1):
    return _r.difference(model, q0, q1) ** 2


def distance(model, q0, q1):
    return float(np.linalg.norm(_r.difference(model, q0, q1)))


def forwardDynamics(model, data, *args, **kwargs):
    """``forwardDynamics(model, data, q, v, tau)``: ``aba``. With contact Jacobians (Pinocchio's
    contact dynamics): ``forwardDynamics(model, data, q, v, tau, J, gamma, damping=0)``, or
    ``forwardDynamics(model, data, tau, J, gamma, damping=0)`` on the ``M`` and ``nle`` in
    ``data`` (of the last ``computeAllTerms``, or ``crba`` and ``nonLinearEffects``): rigid's
    ``jacobian_dynamics`` and ``jacobian_dynamics_from_terms`` (Featherstone's range-space
    method, as Pinocchio's); ``λ`` in ``data.lambda_c``, ``a`` in ``data.ddq`` and returned."""
    if len(args) == 3 and not kwargs and np.ndim(args[1]) == 1:
        return _r.aba(model, data, *args)
    with_state = len(args) >= 4 and np.ndim(args[3]) == 2 or "J" in kwargs and len(args) == 3
    names = ("q", "v", "tau", "J", "gamma", "damping") if with_state else \
        ("tau", "J", "gamma", "damping")
    if len(args) > len(names) or any(k not in names for k in kwargs):
        raise TypeError("forwardDynamics(model, data, q, v, tau[, J, gamma, damping=0.0]) or "
                        "(model, data, tau, J, gamma[, damping=0.0])")
    given = dict(zip(names, args))
    given.update(kwargs)
    if "J" not in given:
        raise TypeError("forwardDynamics: the contact form needs J (and gamma)")
    J = np.atleast_2d(np.asarray(given["J"], dtype=float))
    rest = (given["tau"], J, given.get("gamma", np.zeros(J.shape[0])),
            float(given.get("damping", 0.0)))
    if with_state:
        a, lam = _r.jacobian_dynamics(model, data, given["q"], given["v"], *rest)
    else:
        a, lam = _r.jacobian_dynamics_from_terms(model, data, *rest)
    data.lambda_c = lam
    return a


__all__ = [n for n in dir() if not n.startswith("_")
           and n not in ("np", "SE3", "Force", "Motion", "KinematicLevel", "ReferenceFrame")]
