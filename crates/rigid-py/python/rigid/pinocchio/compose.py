"""Pinocchio's model surgery, on the layer's own ``addJoint``, ``appendBodyToJoint`` and
``addFrame``: ``appendModel`` (a model fixed to a frame of another, Pinocchio's
``algorithm/model.hxx``: A's joints up to the frame's subtree, B's, then the rest of A's) and
``buildReducedModel`` (joints locked at a reference configuration become ``FIXED_JOINT`` frames,
their bodies welded to their parents), with their geometry models."""

import numpy as np

from .. import rigid as _r
from .geometry import CollisionPair, GeometryModel
from .joints import Frame, FrameType
from .model import Model
from .spatial import SE3

__all__ = ["appendModel", "buildReducedModel"]


def _limits(src, j):
    """A joint's effort, velocity and position limits, friction and damping, for ``addJoint``."""
    iq, iv = src.joints[j].idx_q, src.joints[j].idx_v
    nq, nv = src.joints[j].nq, src.joints[j].nv
    return (src.effortLimit[iv:iv + nv], src.velocityLimit[iv:iv + nv],
            src.lowerPositionLimit[iq:iq + nq], src.upperPositionLimit[iq:iq + nq],
            src.friction[iv:iv + nv], src.damping[iv:iv + nv])


def _add_body(out, joint, Y, placement=None):
    """``appendBodyToJoint``; a body on the universe goes to the world's inertia (Pinocchio's
    ``inertias[0]``, not in rigid's dynamics)."""
    M = SE3.Identity() if placement is None else placement
    if Y.mass <= 0:
        return
    if joint == 0:
        out._world_inertia = out._world_inertia + M.act(Y)
    else:
        out.appendBodyToJoint(joint, Y, M)


def _world(model):
    """The inertia welded to the world (``inertias[0]`` in Pinocchio)."""
    return getattr(model, "_world_inertia", model.inertias[0])


def _frame_id(src, out, name, type_):
    """The frame of ``out`` that is ``src``'s frame ``name`` (the universe, maybe renamed)."""
    f = src.getFrameId(name)
    if f == 0 and src.frames[0].parentJoint == 0:
        return 0
    return out.getFrameId(name, type_)


def appendModel(modelA, modelB, *args):
    """``appendModel(modelA, modelB, frameInModelA, aMb)``: the model of ``modelB`` fixed to
    frame ``frameInModelA`` of ``modelA`` at ``aMb``; ``appendModel(modelA, modelB,
    geomModelA, geomModelB, frameInModelA, aMb)``: ``(model, geomModel)``. Joint and frame names
    must differ between the two."""
    with_geometry = len(args) == 4
    if with_geometry:
        gA, gB, fid, aMb = args
    elif len(args) == 2:
        (fid, aMb), gA, gB = args, GeometryModel(), GeometryModel()
    else:
        raise TypeError("appendModel(modelA, modelB, [geomModelA, geomModelB,] frameInModelA, "
                        "aMb)")
    if not 0 <= fid < modelA.nframes:
        raise ValueError(f"appendModel: frameInModelA {fid} is not a frame of modelA "
                         f"({modelA.nframes} frames)")
    frame = modelA.frames[fid]
    out, gout = Model(), GeometryModel()
    out.gravity = modelA.gravity  # the name stays empty, as Pinocchio 4.1's

    def universe(src, gsrc, parent_frame, pfM):
        pframe = out.frames[parent_frame]
        jid = pframe.parentJoint
        _add_body(out, jid, _world(src), pframe.placement * pfM)
        for f in list(src.frames)[1:]:
            if f.parentJoint != 0:
                continue
            if out.existFrame(f.name, f.type):
                raise ValueError(f"appendModel: the two models have a frame '{f.name}' each")
            g = f.copy()
            g.parentJoint = jid
            g.parentFrame = (_frame_id(src, out, src.frames[f.parentFrame].name,
                                       src.frames[f.parentFrame].type)
                             if f.parentFrame != 0 else parent_frame)
            g.placement = pframe.placement * pfM * f.placement
            out.addFrame(g)
        for go in gsrc.geometryObjects:
            if go.parentJoint != 0:
                continue
            g = go.copy()
            g.parentJoint = jid
            g.parentFrame = (_frame_id(src, out, src.frames[go.parentFrame].name,
                                       src.frames[go.parentFrame].type)
                             if 0 < go.parentFrame < src.nframes else parent_frame)
            g.placement = pframe.placement * pfM * go.placement
            gout.addGeometryObject(g)

    def joint(src, gsrc, j, parent, pMi):
        if src.parents[j] > 0:
            parent = out.getJointId(src.names[src.parents[j]])
        if out.existJointName(src.names[j]):
            raise ValueError(f"appendModel: the two models have a joint '{src.names[j]}' each")
        jout = out.addJoint(parent, src.joints[j], pMi * src.jointPlacements[j], src.names[j],
                            *_limits(src, j))
        _add_body(out, jout, src.inertias[j])
        for f in list(src.frames)[1:]:
            if f.parentJoint != j:
                continue
            if out.existFrame(f.name, f.type):
                raise ValueError(f"appendModel: the two models have a frame '{f.name}' each")
            g = f.copy()
            g.parentJoint = jout
            if f.parentFrame != 0:
                g.parentFrame = _frame_id(src, out, src.frames[f.parentFrame].name,
                                          src.frames[f.parentFrame].type)
            out.addFrame(g)
        for go in gsrc.geometryObjects:
            if go.parentJoint != j:
                continue
            g = go.copy()
            g.parentJoint = jout
            if 0 < go.parentFrame < src.nframes:
                g.parentFrame = _frame_id(src, out, src.frames[go.parentFrame].name,
                                          src.frames[go.parentFrame].type)
            gout.addGeometryObject(g)

    universe(modelA, gA, 0, SE3.Identity())
    p = frame.parentJoint
    before = [j for j in range(1, modelA.njoints) if j <= p or p in modelA.supports[j]]
    after = [j for j in range(1, modelA.njoints) if j not in before]
    for j in before:
        joint(modelA, gA, j, 0, SE3.Identity())
    universe(modelB, gB, _frame_id(modelA, out, frame.name, frame.type), aMb)
    for j in range(1, modelB.njoints):
        root = modelB.parents[j] == 0
        joint(modelB, gB, j, p, frame.placement * aMb if root else SE3.Identity())
    for j in after:
        joint(modelA, gA, j, 0, SE3.Identity())
    # the reference configurations: A's, then B's joints set in those B has (neutral elsewhere)
    refs = out.referenceConfigurations
    for src in (modelA, modelB):
        for name, q_src in src.referenceConfigurations.items():
            q = refs.setdefault(name, _r.neutral(out))
            for j in range(1, src.njoints):
                a, b = src.joints[j], out.joints[out.getJointId(src.names[j])]
                q[b.idx_q:b.idx_q + b.nq] = q_src[a.idx_q:a.idx_q + a.nq]
    # the pairs: A's, B's, and every pair of an A and a B geometry on different joints
    index = {g.name: i for i, g in enumerate(gout.geometryObjects)}
    for src in (gA, gB):
        for cp in src.collisionPairs:
            gout.addCollisionPair(CollisionPair(index[src.geometryObjects[cp.first].name],
                                                index[src.geometryObjects[cp.second].name]))
    for a in gA.geometryObjects:
        for b in gB.geometryObjects:
            i, j = index[a.name], index[b.name]
            if gout.geometryObjects[i].parentJoint != gout.geometryObjects[j].parentJoint:
                gout.addCollisionPair(CollisionPair(i, j))
    return (out, gout) if with_geometry else out


def _reduced(model, locked, q_ref):
    """Pinocchio's ``buildReducedModel`` on one model (``algorithm/model.hxx``)."""
    locked = sorted(int(j) for j in locked)
    if len(set(locked)) != len(locked):
        raise ValueError("buildReducedModel: list_of_joints_to_lock holds a joint twice")
    if any(not 0 < j < model.njoints for j in locked):
        raise ValueError(f"buildReducedModel: a joint to lock is not one of the model's "
                         f"1..{model.njoints - 1}: {locked}")
    q_ref = np.asarray(q_ref, dtype=float)
    if q_ref.shape != (model.nq,):
        raise ValueError(f"buildReducedModel: reference_configuration has {q_ref.size} entries, "
                         f"the model nq = {model.nq}")
    data = model.createData()
    _r.forward_kinematics(model, data, q_ref)
    oMi = data.oMi
    out = Model()
    out.name, out.gravity = model.name, model.gravity
    out._world_inertia = _world(model)
    frames = list(model.frames)

    def add_frame(f):
        support = model.names[f.parentJoint]
        g = f.copy()
        if f.parentJoint in locked:
            if (f.type == FrameType.JOINT and out.existFrame(f.name)
                    and support == f.name):
                return  # the locked joint, now its FIXED_JOINT frame
            jf = out.frames[out.getFrameId(support)]
            g.placement = jf.placement * f.placement
            g.parentJoint = jf.parentJoint
        else:
            g.parentJoint = out.getJointId(support)
        g.parentFrame = out.getFrameId(frames[f.parentFrame].name)
        out.addFrame(g, False)

    k = 0  # the next input frame
    for j in range(1, model.njoints):
        name, parent = model.names[j], model.parents[j]
        parent_name = model.names[parent]
        if out.existJointName(parent_name):
            new_parent, pf_placement, prev = out.getJointId(parent_name), SE3.Identity(), 0
        else:
            prev = out.getFrameId(parent_name)
            new_parent, pf_placement = out.frames[prev].parentJoint, out.frames[prev].placement
        if j in locked:
            while frames[k].name != name:
                k += 1
                if frames[k].name == name:
                    break
                add_frame(frames[k])
            liMi = pf_placement * (oMi[parent].inverse() * oMi[j])
            Y = model.inertias[j]
            fid = out.addFrame(Frame(name, new_parent, prev, liMi, FrameType.FIXED_JOINT, Y))
            _add_body(out, new_parent, Y, liMi)
            out.frames[fid].parentFrame = fid
        else:
            jout = out.addJoint(new_parent, model.joints[j], pf_placement * model.jointPlacements[j],
                                name, *_limits(model, j))
            _add_body(out, jout, model.inertias[j])
    for name, q in model.referenceConfigurations.items():
        r = np.empty(out.nq)
        for j in range(1, out.njoints):
            a, b = model.joints[model.getJointId(out.names[j])], out.joints[j]
            r[b.idx_q:b.idx_q + b.nq] = q[a.idx_q:a.idx_q + a.nq]
        out.referenceConfigurations[name] = r
    for f in frames[k:]:
        add_frame(f)
    return out


def _reduced_geometry(model, out, geom):
    g_out = GeometryModel()
    for go in geom.geometryObjects:
        parent = model.names[go.parentJoint]
        g = go.copy()
        if out.existJointName(parent):
            g.parentJoint, rel = out.getJointId(parent), SE3.Identity()
        else:
            f = out.frames[out.getFrameId(parent)]
            g.parentJoint, rel = f.parentJoint, f.placement
        g.parentFrame = out.getBodyId(model.frames[go.parentFrame].name)
        g.placement = rel * go.placement
        g_out.addGeometryObject(g)
    g_out.collisionPairs = list(geom.collisionPairs)
    return g_out


def buildReducedModel(model, *args, list_of_geom_models=None, list_of_joints_to_lock=None,
                      reference_configuration=None):
    """``buildReducedModel(model, list_of_joints_to_lock, reference_configuration)``: the model
    with those joints (indices) locked at the configuration; ``(model, geom_model, joints, q)``:
    ``(reduced, reduced_geom)``; ``(model, list_of_geom_models=[...], list_of_joints_to_lock=...,
    reference_configuration=...)``: ``(reduced, [reduced geometry models])``."""
    geoms = None
    if args and isinstance(args[0], GeometryModel):
        geoms, args = args[0], args[1:]
    if args and isinstance(args[0], (list, tuple)) and args[0] \
            and isinstance(args[0][0], GeometryModel):
        list_of_geom_models, args = args[0], args[1:]
    if args:
        list_of_joints_to_lock = args[0]
    if len(args) > 1:
        reference_configuration = args[1]
    if list_of_joints_to_lock is None or reference_configuration is None:
        raise TypeError("buildReducedModel(model, [geom_model | list_of_geom_models,] "
                        "list_of_joints_to_lock, reference_configuration)")
    out = _reduced(model, list_of_joints_to_lock, reference_configuration)
    if geoms is not None:
        return out, _reduced_geometry(model, out, geoms)
    if list_of_geom_models is not None:
        return out, [_reduced_geometry(model, out, g) for g in list_of_geom_models]
    return out
