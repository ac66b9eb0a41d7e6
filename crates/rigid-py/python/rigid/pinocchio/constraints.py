"""Pinocchio's constrained dynamics (``RigidConstraintModel``, ``initConstraintDynamics``,
``constraintDynamics``, ``impulseDynamics``, ``ProximalSettings``) on rigid's
(``rigid.ConstraintModel``, ``rigid.constraint_dynamics``, ``rigid.impulse_dynamics``). Without
them in this build of rigid, each raises NotImplementedError saying so."""

import enum

import numpy as np

from .. import rigid as _r
from .joints import ReferenceFrame
from .spatial import SE3

__all__ = ["ContactType", "RigidConstraintModel", "RigidConstraintData", "ProximalSettings",
           "initConstraintDynamics", "constraintDynamics", "impulseDynamics",
           "computeConstraintDynamicsDerivatives", "computeImpulseDynamicsDerivatives"]

AVAILABLE = all(hasattr(_r, n) for n in ("ConstraintModel", "ConstraintData",
                                         "constraint_dynamics", "impulse_dynamics"))


def _need(func):
    if not AVAILABLE:
        raise NotImplementedError(
            f"{func}: this build of rigid has no constrained dynamics (rigid.constraint_dynamics, "
            "rigid.ConstraintModel); use Pinocchio for contacts, or a rigid with them")


class ContactType(enum.IntEnum):
    CONTACT_3D = 0
    CONTACT_6D = 1
    CONTACT_UNDEFINED = 2

    def __str__(self):
        return self.name


class ProximalSettings:
    """The proximal iterations of ``constraintDynamics``: ``mu`` (0: one exact solve),
    ``max_iter``, ``accuracy``."""

    def __init__(self, accuracy=1e-12, mu=0.0, max_iter=1):
        self.accuracy, self.mu, self.max_iter = float(accuracy), float(mu), int(max_iter)
        self.iter = 0
        self.absolute_residual = self.relative_residual = 0.0


class RigidConstraintModel:
    """A point (``CONTACT_3D``) or frame (``CONTACT_6D``) constraint between
    ``joint1_placement`` in joint ``joint1_id``'s frame and ``joint2_placement`` in joint
    ``joint2_id``'s (0: the world)."""

    def __init__(self, contact_type, model, joint1_id, joint1_placement=None, *args):
        _need("RigidConstraintModel")
        joint2_id, joint2_placement, rf = 0, SE3(), ReferenceFrame.LOCAL
        rest = list(args)
        if rest and isinstance(rest[-1], ReferenceFrame):
            rf = rest.pop()
        if len(rest) == 2:
            joint2_id, joint2_placement = rest
        elif rest:
            raise TypeError("RigidConstraintModel(type, model, joint1_id, joint1_placement"
                            "[, joint2_id, joint2_placement][, reference_frame])")
        self.type = ContactType(contact_type)
        self.joint1_id, self.joint2_id = int(joint1_id), int(joint2_id)
        self.joint1_placement = SE3() if joint1_placement is None else SE3(joint1_placement)
        self.joint2_placement = SE3(joint2_placement)
        self.reference_frame = ReferenceFrame(rf)
        self.name = ""
        names = model.names
        self._c = _r.ConstraintModel(model, self.type.name.lower(), names[self.joint1_id],
                                     self.joint1_placement, names[self.joint2_id],
                                     self.joint2_placement, self.reference_frame.name.lower())

    def size(self):
        return 3 if self.type == ContactType.CONTACT_3D else 6

    def createData(self):
        return RigidConstraintData(self)


class RigidConstraintData:
    def __init__(self, constraint_model):
        self.model = constraint_model


def _constraint_data(model, data, contact_models):
    key = tuple(id(c) for c in contact_models)
    cache = data.__dict__.setdefault("_constraint_datas", {})
    if key not in cache:
        cache[key] = _r.ConstraintData(model, [c._c for c in contact_models])
    return cache[key]


def initConstraintDynamics(model, data, contact_models):
    """Makes the workspace of ``contact_models`` (once per set)."""
    _need("initConstraintDynamics")
    _constraint_data(model, data, contact_models)


def constraintDynamics(model, data, q, v, tau, contact_models, contact_datas=None,
                       prox_settings=None):
    """``q̈`` with ``M q̈ + c + g = τ + Jᵀ λ`` and the constraints' accelerations zero (with
    Baumgarte terms); ``λ`` in ``data.lambda_c`` (forces first)."""
    _need("constraintDynamics")
    cd = _constraint_data(model, data, contact_models)
    s = prox_settings or ProximalSettings()
    ddq = _r.constraint_dynamics(model, data, q, v, tau, cd, mu=s.mu, max_iter=max(1, s.max_iter),
                                 accuracy=s.accuracy)
    data.lambda_c = cd.lambda_c
    data._constraint_state = (q, v, tau, s)
    return ddq


def impulseDynamics(model, data, q, v_before, contact_models, contact_datas=None, r_coeff=0.0,
                    prox_settings=None):
    """The velocity after an impact that starts the constraints; ``data.impulse_c``,
    ``data.dq_after``."""
    _need("impulseDynamics")
    cd = _constraint_data(model, data, contact_models)
    s = prox_settings or ProximalSettings()
    dq = _r.impulse_dynamics(model, data, q, v_before, cd, r_coeff=r_coeff, mu=s.mu,
                             max_iter=max(1, s.max_iter), accuracy=s.accuracy)
    data.impulse_c, data.dq_after = cd.impulse_c, np.asarray(dq)
    data._impulse_state = (q, v_before, r_coeff, s)
    return dq


def _last(data, key, func, before):
    state = data.__dict__.get(key)
    if state is None:
        raise RuntimeError(f"{func}: call {before} first (the derivatives are taken at its state)")
    return state


def computeConstraintDynamicsDerivatives(model, data, contact_models, contact_datas=None,
                                         prox_settings=None):
    """The derivatives of the last ``constraintDynamics`` into ``data.ddq_dq``, ``ddq_dv``,
    ``ddq_dtau``, ``dlambda_dq``, ``dlambda_dv``, ``dlambda_dtau``."""
    _need("computeConstraintDynamicsDerivatives")
    q, v, tau, s = _last(data, "_constraint_state", "computeConstraintDynamicsDerivatives",
                         "constraintDynamics")
    s = prox_settings or s
    cd = _constraint_data(model, data, contact_models)
    d = _r.constraint_dynamics_derivatives(model, data, q, v, tau, cd, mu=s.mu,
                                           max_iter=max(1, s.max_iter), accuracy=s.accuracy)
    data._constrained = {k: d[k] for k in ("ddq_dq", "ddq_dv", "ddq_dtau")}
    data.dlambda_dq, data.dlambda_dv, data.dlambda_dtau = (
        d["dlambda_dq"], d["dlambda_dv"], d["dlambda_dtau"])


def computeImpulseDynamicsDerivatives(model, data, contact_models, contact_datas=None,
                                      r_coeff=0.0, prox_settings=None):
    """The derivatives of the last ``impulseDynamics``: ``data.ddq_dq`` (∂v⁺/∂q),
    ``data.ddq_dv`` (∂(v⁺ − v⁻)/∂v⁻, Pinocchio's convention), ``data.dlambda_dq``,
    ``data.dlambda_dv`` (of the impulse)."""
    _need("computeImpulseDynamicsDerivatives")
    q, v, _, s = _last(data, "_impulse_state", "computeImpulseDynamicsDerivatives",
                       "impulseDynamics")
    s = prox_settings or s
    cd = _constraint_data(model, data, contact_models)
    d = _r.impulse_dynamics_derivatives(model, data, q, v, cd, r_coeff=r_coeff, mu=s.mu,
                                        max_iter=max(1, s.max_iter), accuracy=s.accuracy)
    data._constrained = {"ddq_dq": d["dvplus_dq"], "ddq_dv": d["dvplus_dv"] - np.eye(model.nv)}
    data.dlambda_dq, data.dlambda_dv = d["dimpulse_dq"], d["dimpulse_dv"]
