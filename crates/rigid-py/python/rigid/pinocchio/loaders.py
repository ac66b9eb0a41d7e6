"""Making models: Pinocchio's URDF (and MJCF) loaders, and its sample models with Pinocchio's
kinematics and inertias (``buildSampleModelManipulator``, ``buildSampleModelHumanoid``; the
random humanoid draws its placements and inertias from rigid.pinocchio's generator, ``seed``)."""

import json
import os
import tempfile
import warnings

import numpy as np

from .. import rigid as _r
from .joints import (NQ_RIGID, JointModel, JointModelFreeFlyer, JointModelRX, JointModelRY,
                     JointModelRZ)
from .model import Model
from .geometry import GeometryModel, GeometryType, buildGeomFromUrdf
from .explog import exp3
from .spatial import SE3, Inertia, _GEN

__all__ = [
    "buildModelFromUrdf", "buildModelsFromUrdf", "buildModelFromXML", "buildModelFromMJCF",
    "buildModelsFromMJCF", "buildSampleModelManipulator", "buildSampleModelHumanoid",
    "buildSampleModelHumanoidRandom",
]


def _root(root_joint, func):
    """Whether the URDF is read on a root joint (a free-flyer, replaced by `root_joint` after)."""
    if root_joint is None:
        return False
    if isinstance(root_joint, Model):
        raise NotImplementedError(f"{func}(filename, model): pass the root joint or nothing; the "
                                  "model is returned")
    if isinstance(root_joint, JointModel) and root_joint._kind()["type"] in NQ_RIGID:
        return True
    raise NotImplementedError(
        f"{func}: root joint {type(root_joint).__name__}: rigid.pinocchio has no such joint")


def _root_kind(d, root_joint):
    """Makes the free-flyer root of the serialised model `d` the joint `root_joint` (same place,
    same body; Pinocchio's root joint has no limits)."""
    r = d["joints"][0]
    kind = root_joint._kind()
    nq, nv = NQ_RIGID[kind["type"]], root_joint.nv
    dq, dv = nq - r["nq"], nv - r["nv"]
    r.update(kind=kind, nq=nq, nv=nv, continuous=bool(root_joint._continuous))
    for j in d["joints"][1:]:
        j["idx_q"] += dq
        j["idx_v"] += dv
    for k, n0, n in (("lower", 7, nq), ("upper", 7, nq)):
        d[k] = [None] * n + d[k][n0:]
    for k in ("velocity_limit", "effort_limit"):
        d[k] = [None] * nv + d[k][6:]
    for k in ("armature", "damping", "friction"):
        d[k] = [0.0] * nv + d[k][6:]


def _model_of(m, path, floating, root_joint_name=None, root_joint=None):
    """The layer's model of a native one read from a file (on a free-flyer root when
    `floating`, which becomes `root_joint` if that is another joint)."""
    origins = ["root" if floating and i == 0 else "urdf" for i in range(m.njoints)]
    model = Model(m.to_json(), _warnings=m.warnings, _source=path, _origins=origins)
    other = floating and root_joint is not None and not isinstance(root_joint,
                                                                    JointModelFreeFlyer)
    if other or (root_joint_name is not None and floating and root_joint_name != "root_joint"):
        d = model.desc()
        if other:
            _root_kind(d, root_joint)
        if root_joint_name is not None:
            d["joints"][0]["name"] = root_joint_name
        model = Model(json.dumps(d), _warnings=m.warnings, _source=path, _origins=origins)
    return model


def buildModelFromUrdf(filename, root_joint=None, root_joint_name=None, verbose=False,
                       mimic=False):
    """The model of a URDF file (sibling joints in urdfdom's order, as Pinocchio), fixed to the
    world or on a free-flyer root joint ``root_joint`` (``pin.JointModelFreeFlyer()``). Non
    physical inertias load as written (rigid's ``UrdfWarning``s are silenced here; ``model
    .warnings`` keeps them)."""
    if isinstance(root_joint, str):
        root_joint, root_joint_name = None, root_joint
    floating = _root(root_joint, "buildModelFromUrdf")
    if mimic:
        raise NotImplementedError(
            "buildModelFromUrdf(mimic=True): the models of rigid.pinocchio have no mimic joints; "
            "rigid.Model.from_urdf(path, mimic=True, layout='pinocchio') is a rigid.MimicModel "
            "with rnea, crba, nle, aba, their derivatives and frame_jacobian in Pinocchio's "
            "mimic=True coordinates")
    path = os.fspath(filename)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", _r.UrdfWarning)
        m = _r.Model.from_urdf(path, floating=floating, inertia="warn", layout="pinocchio")
    model = _model_of(m, path, floating, root_joint_name, root_joint)
    if root_joint is None:
        # the links welded to the world (Pinocchio's inertias[0]; not in rigid's dynamics)
        model._world_inertia = Inertia(*_r._urdf_welded_inertia(path))
    return model


def buildModelFromXML(xml, root_joint=None, root_joint_name=None, verbose=False, mimic=False):
    """The model of a URDF given as a string."""
    fd, path = tempfile.mkstemp(suffix=".urdf")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(xml)
        return buildModelFromUrdf(path, root_joint, root_joint_name, verbose, mimic)
    finally:
        os.unlink(path)


def buildModelsFromUrdf(filename, package_dirs=None, root_joint=None, verbose=False,
                        meshLoader=None, geometry_types=None, **kwargs):
    """``(model, collision_model, visual_model)``: the model and its geometry models
    (``buildGeomFromUrdf``); with one ``geometry_types``, ``(model, geometry)``, with a list, one
    geometry model each. ``package_dirs`` may also be the root joint, as Pinocchio's overloads."""
    if root_joint is None and isinstance(package_dirs, JointModel):
        package_dirs, root_joint = None, package_dirs
    model = buildModelFromUrdf(filename, root_joint, kwargs.get("root_joint_name"))
    if geometry_types is None:
        geometry_types = [GeometryType.COLLISION, GeometryType.VISUAL]
    elif not isinstance(geometry_types, (list, tuple)):
        return model, buildGeomFromUrdf(model, filename, geometry_types, package_dirs)
    return (model,) + tuple(buildGeomFromUrdf(model, filename, t, package_dirs)
                            for t in geometry_types)


def buildModelFromMJCF(filename, root_joint=None, root_joint_name=None, verbose=False):
    """The model of an MJCF (MuJoCo XML) file, by rigid's MJCF importer (MuJoCo's compiled
    inertias)."""
    if not hasattr(_r.Model, "from_mjcf"):
        raise NotImplementedError(
            "buildModelFromMJCF: this build of rigid has no MJCF importer; use "
            "buildModelFromUrdf, or rigid.Model.from_mjcf once it is available")
    if root_joint is not None:
        raise NotImplementedError(
            "buildModelFromMJCF(root_joint=...): an MJCF model's root joints are in its file "
            "(<freejoint/>); load it without root_joint")
    path = os.fspath(filename)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = _r.Model.from_mjcf(path, layout="pinocchio")
    return _model_of(m, path, False)


def buildModelsFromMJCF(filename, *args, **kwargs):
    model = buildModelFromMJCF(filename)
    return model, GeometryModel(), GeometryModel()


# ---------------------------------------------------------------- sample models


def _rotate(angle, axis):
    return exp3(angle * np.asarray(axis, dtype=float))


_IJOINT = Inertia(0.1, np.zeros(3), np.eye(3) * 0.01)
_IARM = Inertia(1.0, np.array([0.0, 0.0, 0.5]), np.eye(3))


def _add_joint_and_body(model, joint, parent_name, name, placement=None, random_limits=True):
    """Pinocchio's ``addJointAndBody`` of its sample models: joint ``name_joint`` with a JOINT
    frame, a random body (``Inertia.Random()``), a BODY frame ``name_body``; random limits
    (effort and velocity in [0, 2], ``q`` in [-2, 0] x [0, 2]) or ±3.14, 10, 10."""
    if placement is None:
        placement = SE3.Random()
    g = _GEN[0]
    nq, nv = joint.nq, joint.nv
    if random_limits:
        eff, vel = g.uniform(0.0, 2.0, nv), g.uniform(0.0, 2.0, nv)
        lo, up = g.uniform(-2.0, 0.0, nq), g.uniform(0.0, 2.0, nq)
    else:
        eff, vel, lo, up = np.full(nv, 10.0), np.full(nv, 10.0), np.full(nq, -3.14), \
            np.full(nq, 3.14)
    idx = model.addJoint(model.getJointId(parent_name), joint, placement, name + "_joint", eff,
                         vel, lo, up)
    model.addJointFrame(idx)
    model.appendBodyToJoint(idx, Inertia.Random(), SE3())
    model.addBodyFrame(name + "_body", idx)
    return idx


def _add_manipulator(model, root_joint_idx=0, Mroot=None, pre=""):
    Marm = SE3(np.eye(3), np.array([0.0, 0.0, 1.0]))
    Id4 = SE3()
    root_name = model.names[root_joint_idx]
    j = _add_joint_and_body(model, JointModelRX(), root_name, pre + "shoulder1",
                            Mroot if Mroot is not None else SE3())
    root = j
    inertias = {j: _IJOINT}
    j = _add_joint_and_body(model, JointModelRY(), model.names[j], pre + "shoulder2", Id4)
    inertias[j] = _IJOINT
    j = _add_joint_and_body(model, JointModelRZ(), model.names[j], pre + "shoulder3", Id4)
    inertias[j] = _IARM
    model.addBodyFrame(pre + "upperarm_body", j, SE3(), -1)
    j = _add_joint_and_body(model, JointModelRY(), model.names[j], pre + "elbow", Marm)
    inertias[j] = _IARM
    model.addBodyFrame(pre + "lowerarm_body", j, SE3(), -1)
    model.addBodyFrame(pre + "elbow_body", j, SE3(), -1)
    j = _add_joint_and_body(model, JointModelRX(), model.names[j], pre + "wrist1", Marm)
    inertias[j] = _IJOINT
    j = _add_joint_and_body(model, JointModelRY(), model.names[j], pre + "wrist2", Id4)
    inertias[j] = _IARM
    model.addBodyFrame(pre + "effector_body", j, SE3(), -1)
    d = model.desc()
    for i, Y in inertias.items():
        from .joints import _inertia_json  # noqa: PLC0415

        d["inertias"][i - 1] = _inertia_json(Y)
    model._rebuild(d)
    iq, iv = model.idx_qs[root], model.idx_vs[root]
    lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    lower[iq:iq + 6], upper[iq:iq + 6] = -3.14, 3.14
    vel, eff = model.velocityLimit, model.effortLimit
    vel[iv:iv + 6], eff[iv:iv + 6] = 10.0, 10.0
    model.lowerPositionLimit, model.upperPositionLimit = lower, upper
    model.velocityLimit, model.effortLimit = vel, eff


def buildSampleModelManipulator(mimic=False):
    """Pinocchio's sample 6-dof arm (shoulder RX RY RZ, elbow RY, wrist RX RY), with its
    placements and inertias."""
    if mimic:
        raise NotImplementedError("buildSampleModelManipulator(mimic=True): rigid has no mimic "
                                  "joints")
    model = Model()
    _add_manipulator(model)
    return model


def buildSampleModelHumanoid(usingFF=True):
    """Pinocchio's sample humanoid (a free-flyer, two legs and two arms of the sample arm, a
    chest and a head), with its placements and inertias."""
    if not usingFF:
        raise NotImplementedError(
            "buildSampleModelHumanoid(usingFF=False): its root is a composite joint (translation "
            "and ZYX spherical), which rigid does not have; use usingFF=True")
    pi = np.pi
    model = Model()
    ff = model.addJoint(0, JointModelFreeFlyer(), SE3(), "root_joint")
    lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    lower[3:7], upper[3:7] = -1.0, 1.0
    model.lowerPositionLimit, model.upperPositionLimit = lower, upper
    model.appendBodyToJoint(ff, _IJOINT, SE3())
    model.addJointFrame(ff)
    _add_manipulator(model, ff, SE3(_rotate(pi, [1, 0, 0]), np.array([0.0, -0.2, -0.1])),
                     "rleg_")
    _add_manipulator(model, ff, SE3(_rotate(pi, [1, 0, 0]), np.array([0.0, 0.2, -0.1])), "lleg_")
    for k in (7, 13):  # rotate the feet
        M = model.jointPlacements[k]
        model.jointPlacements[k] = SE3(_rotate(pi / 2, [0, 1, 0]), M.translation)
    lim = (np.full(1, 10.0), np.full(1, 10.0), np.full(1, -3.14), np.full(1, 3.14))
    idx = model.addJoint(ff, JointModelRX(), SE3(), "chest1_joint", *lim)
    model.appendBodyToJoint(idx, _IJOINT, SE3())
    model.addJointFrame(idx)
    model.addBodyFrame("chest1_body", idx, SE3(), -1)
    idx = model.addJoint(idx, JointModelRY(), SE3(), "chest2_joint", *lim)
    model.appendBodyToJoint(idx, _IARM, SE3())
    model.addJointFrame(idx)
    model.addBodyFrame("chest2_body", idx, SE3(), -1)
    chest = idx
    idx = model.addJoint(idx, JointModelRX(), SE3(np.eye(3), np.array([0.0, 0.0, 1.0])),
                         "head1_joint", *lim)
    model.appendBodyToJoint(idx, _IJOINT, SE3())
    model.addJointFrame(idx)
    model.addBodyFrame("head1_body", idx, SE3(), -1)
    idx = model.addJoint(idx, JointModelRY(), SE3(), "head2_joint", *lim)
    model.appendBodyToJoint(idx, _IARM, SE3())
    model.addJointFrame(idx)
    model.addBodyFrame("head2_body", idx, SE3(), -1)
    _add_manipulator(model, chest, SE3(_rotate(pi, [1, 0, 0]), np.array([0.0, -0.3, 1.0])),
                     "rarm_")
    _add_manipulator(model, chest, SE3(_rotate(pi, [1, 0, 0]), np.array([0.0, 0.3, 1.0])),
                     "larm_")
    return model


def buildSampleModelHumanoidRandom(usingFF=True, mimic=False):
    """Pinocchio's random humanoid: its tree (a free-flyer, two 6-dof legs, a 2-dof torso, two
    6-dof arms) with random placements, inertias and limits drawn from rigid.pinocchio's
    generator (``pin.seed``): the same joints and frames as Pinocchio's, other numbers."""
    if not usingFF:
        raise NotImplementedError(
            "buildSampleModelHumanoidRandom(usingFF=False): its root is a composite joint, which "
            "rigid does not have; use usingFF=True")
    if mimic:
        raise NotImplementedError("buildSampleModelHumanoidRandom(mimic=True): rigid has no "
                                  "mimic joints")
    model = Model()
    _add_joint_and_body(model, JointModelFreeFlyer(), "universe", "root", SE3())
    lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    lower[3:7], upper[3:7] = -1.0, 1.0
    model.lowerPositionLimit, model.upperPositionLimit = lower, upper
    chain = [("lleg", "root_joint", "XYZYYX"), ("rleg", "root_joint", "XYZYYX")]
    J = {"X": JointModelRX, "Y": JointModelRY, "Z": JointModelRZ}
    for pre, parent, axes in chain:
        for k, a in enumerate(axes, start=1):
            _add_joint_and_body(model, J[a](), parent, f"{pre}{k}")
            parent = f"{pre}{k}_joint"
    _add_joint_and_body(model, JointModelRY(), "root_joint", "torso1")
    _add_joint_and_body(model, JointModelRZ(), "torso1_joint", "chest")
    for pre in ("rarm", "larm"):
        parent = "chest_joint"
        for k, a in enumerate("XYZYYX", start=1):
            _add_joint_and_body(model, J[a](), parent, f"{pre}{k}")
            parent = f"{pre}{k}_joint"
    return model

