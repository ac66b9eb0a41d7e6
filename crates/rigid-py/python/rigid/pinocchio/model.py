"""Pinocchio's ``Model`` on rigid's (``Data`` is in data.py, joint models, frames and enums in
joints.py; this module re-exports them).

``Model`` and ``Data`` are subclasses of ``rigid.Model`` and ``rigid.Data`` (in Pinocchio's
layout), so every verb of ``rigid`` takes them, and the hot ones (``rnea``, ``crba``, ``aba``,
``forwardKinematics``, ...) are rigid's own functions, with nothing in between. What differs from
rigid's view is presented here: the universe joint 0 (``names[0] == "universe"``, ``njoints``
counts it, ``parents``, ``inertias``, ``jointPlacements`` have an entry for it), Pinocchio's
frames (a JOINT frame per joint, fixed joints before their child links), position limits with
Pinocchio's conventions, and the fields of ``Data`` (``oMi``, ``oMf``, ``M``, ``nle``, ``J``,
...) read from rigid's workspace in Pinocchio's layout when asked for.
"""

import json

import numpy as np

from .. import rigid as _r
from .data import Data
from .joints import *  # noqa: F401,F403  (the names Pinocchio's users reach through the model)
from .joints import (JOINT_MODELS, NQ_RIGID, ArgumentPosition, Frame, FrameType,  # noqa: F401
                     _KIND_OF_TYPE, _Universe, _frames_of, _inertia_json, _inertia_of_json,
                     _joint_model_of, _se3_json, _se3_of_json)
from .spatial import SE3, Inertia, Motion

MAX = np.finfo(float).max

__all__ = ["Model", "Data"]


# ---------------------------------------------------------------- bound objects


class _BoundSE3(SE3):
    """An ``SE3`` of a model's list whose assignments write back (``model.jointPlacements[i]
    .translation = p``)."""

    __slots__ = ("_owner",)

    def __init__(self, M, owner):
        super().__init__(M)
        self._owner = owner

    @SE3.rotation.setter
    def rotation(self, R):
        SE3.rotation.fset(self, R)
        self._owner(self)

    @SE3.translation.setter
    def translation(self, p):
        SE3.translation.fset(self, p)
        self._owner(self)


class _BoundInertia(Inertia):
    __slots__ = ("_owner",)

    def __init__(self, Y, owner):
        super().__init__(Y)
        self._owner = owner

    @Inertia.mass.setter
    def mass(self, m):
        Inertia.mass.fset(self, m)
        self._owner(self)

    @Inertia.lever.setter
    def lever(self, c):
        Inertia.lever.fset(self, c)
        self._owner(self)

    @Inertia.inertia.setter
    def inertia(self, I):
        Inertia.inertia.fset(self, I)
        self._owner(self)


class _ModelList(list):
    """A list of a model (``inertias``, ``jointPlacements``, ``frames``) whose item assignment
    writes back into the model."""

    def __init__(self, items, setter):
        super().__init__(items)
        self._setter = setter

    def __setitem__(self, i, x):
        super().__setitem__(i, x)
        self._setter(i, x)


class _GravityMotion(Motion):
    """``model.gravity``: assigning its parts sets the model's gravity."""

    __slots__ = ("_model",)

    def __init__(self, v, model):
        super().__init__(v)
        self._model = model

    def _push(self):
        self._model.gravity = Motion(self._v)

    @Motion.linear.setter
    def linear(self, x):
        Motion.linear.fset(self, x)
        self._push()

    @Motion.angular.setter
    def angular(self, x):
        Motion.angular.fset(self, x)
        self._push()

    @Motion.vector.setter
    def vector(self, x):
        Motion.vector.fset(self, x)
        self._push()


# ---------------------------------------------------------------- model


def _limit_array(xs, none):
    return np.array([none if x is None else x for x in xs], dtype=float)


class Model(_r.Model):
    """A kinematic tree with Pinocchio's fields (``rigid.Model`` in Pinocchio's layout, plus the
    universe joint 0 and Pinocchio's frames). ``Model()`` is the empty model (the universe only);
    ``buildModelFromUrdf`` and the sample models make full ones; ``addJoint``,
    ``appendBodyToJoint``, ``addJointFrame``, ``addBodyFrame``, ``addFrame`` grow one (joints in
    depth-first order, which rigid keeps)."""

    def __new__(cls, json_text=None, *, _warnings=(), _source=None, _qpos0=None, **_):
        return super().__new__(cls, json_text, "pinocchio", warnings=list(_warnings),
                               source=_source, qpos0=_qpos0)

    def __init__(self, json_text=None, *, _warnings=(), _source=None, _qpos0=None,
                 _frames=None, _origins=None, _limits=None):
        self._desc = None
        self._origins = list(_origins) if _origins is not None else \
            ["api"] * super().njoints
        self._frames = _frames if _frames is not None else _frames_of(self.desc())
        self._set_limits(_limits)
        self.referenceConfigurations = {}
        #: the inertia of the bodies welded to the world (Pinocchio's ``inertias[0]``), which
        #: takes no part in rigid's dynamics; ``appendModel`` and ``buildReducedModel`` carry it
        self._world_inertia = Inertia.Zero()

    # ---- the serialised form and edits
    def desc(self):
        """rigid's serialised form of the model (a dict, rigid's layout)."""
        if self._desc is None:
            self._desc = json.loads(self.to_json())
        return self._desc

    def _rebuild(self, desc, keep_id=True):
        new = _r.Model(json.dumps(desc), "pinocchio", warnings=self.warnings)
        _r._model_assign(self, new, keep_id)
        self._desc = None

    def _set_limits(self, limits):
        """Pinocchio's position, velocity and effort limits (the model's layout)."""
        if limits is not None:
            self._lower, self._upper, self._vlim, self._elim = (np.array(x, dtype=float)
                                                                for x in limits)
            return
        d = self.desc()
        lo_r, up_r = _limit_array(d["lower"], -np.inf), _limit_array(d["upper"], np.inf)
        lo, up = np.empty(self.nq), np.empty(self.nq)
        for jd, origin, iq, nq in zip(d["joints"], self._origins, super().idx_qs, super().nqs):
            t = jd["kind"]["type"]
            rq = slice(jd["idx_q"], jd["idx_q"] + jd["nq"])
            if origin == "api" or origin == "root":
                a = np.where(np.isfinite(lo_r[rq]), lo_r[rq], -MAX)
                b = np.where(np.isfinite(up_r[rq]), up_r[rq], MAX)
                if nq != jd["nq"]:  # (cos, sin)
                    a, b = np.append(a[:-1], [-MAX, -MAX]), np.append(b[:-1], [MAX, MAX])
                lo[iq:iq + nq], up[iq:iq + nq] = a, b
            elif jd.get("continuous"):
                lo[iq:iq + nq], up[iq:iq + nq] = -1.01, 1.01
            elif t == "planar":
                lo[iq:iq + nq] = [-np.inf, -np.inf, -1.01, -1.01]
                up[iq:iq + nq] = [np.inf, np.inf, 1.01, 1.01]
            elif t == "free_flyer":
                lo[iq:iq + nq] = [-np.inf] * 3 + [-1.01] * 4
                up[iq:iq + nq] = [np.inf] * 3 + [1.01] * 4
            elif t == "spherical":
                lo[iq:iq + nq], up[iq:iq + nq] = -1.01, 1.01
            else:
                lo[iq:iq + nq], up[iq:iq + nq] = lo_r[rq], up_r[rq]
        self._lower, self._upper = lo, up
        perm = self._perm()
        self._vlim = np.where(np.isfinite(_limit_array(d["velocity_limit"], np.inf)),
                              _limit_array(d["velocity_limit"], np.inf), MAX)[perm]
        self._elim = np.where(np.isfinite(_limit_array(d["effort_limit"], np.inf)),
                              _limit_array(d["effort_limit"], np.inf), MAX)[perm]

    def _perm(self):
        """rigid's velocity index of each of Pinocchio's (free-flyer halves swapped)."""
        perm = []
        for j in self.desc()["joints"]:
            if j["kind"]["type"] == "free_flyer":
                perm += [j["idx_v"] + (k + 3) % 6 for k in range(6)]
            else:
                perm += list(range(j["idx_v"], j["idx_v"] + j["nv"]))
        return perm

    def _push_limits(self):
        """Writes Pinocchio's limits into the rigid model (cos/sin bounds are not limits)."""
        d = self.desc()
        lo, up = _r._bounds_to_rigid(self, self._lower, self._upper)
        d["lower"] = [None if not np.isfinite(x) else float(x) for x in lo]
        d["upper"] = [None if not np.isfinite(x) else float(x) for x in up]
        perm = self._perm()
        for key, pin in (("velocity_limit", self._vlim), ("effort_limit", self._elim)):
            r = np.empty(self.nv)
            r[perm] = pin
            d[key] = [None if (not np.isfinite(x) or x >= MAX) else float(x) for x in r]
        self._rebuild(d)

    # ---- sizes and names
    @property
    def njoints(self):
        return super().njoints + 1

    @property
    def nbodies(self):
        return self.njoints

    @property
    def nframes(self):
        return len(self._frames)

    @property
    def name(self):
        return super().name

    @name.setter
    def name(self, n):
        d = self.desc()
        d["name"] = str(n)
        self._rebuild(d)

    @property
    def names(self):
        return ["universe"] + super().names

    @property
    def joints(self):
        out = [_Universe()]
        for i, (j, iq, nq, iv) in enumerate(zip(self.desc()["joints"], super().idx_qs,
                                                 super().nqs, super().idx_vs)):
            jm = _joint_model_of(j)
            jm.setIndexes(i + 1, iq, iv)
            out.append(jm)
        return out

    @property
    def parents(self):
        return [0] + [0 if j["parent"] is None else j["parent"] + 1
                      for j in self.desc()["joints"]]

    @property
    def children(self):
        ch = [[] for _ in range(self.njoints)]
        for i, p in enumerate(self.parents[1:], start=1):
            ch[p].append(i)
        return ch

    @property
    def subtrees(self):
        out = [list(range(self.njoints))]
        for i, j in enumerate(self.desc()["joints"]):
            out.append(list(range(i + 1, j["subtree_end"] + 1)))
        return out

    @property
    def supports(self):
        par = self.parents
        out = [[0]]
        for i in range(1, self.njoints):
            out.append(out[par[i]] + [i])
        return out

    @property
    def idx_qs(self):
        return [0] + super().idx_qs

    @property
    def nqs(self):
        return [0] + super().nqs

    @property
    def idx_vs(self):
        return [0] + super().idx_vs

    @property
    def nvs(self):
        return [0] + super().nvs

    # ---- bodies and placements
    @property
    def inertias(self):
        d = self.desc()
        items = [Inertia()] + [_BoundInertia(_inertia_of_json(g), self._inertia_setter(i + 1))
                               for i, g in enumerate(d["inertias"])]
        return _ModelList(items, lambda i, Y: self._set_inertia(i, Y))

    def _inertia_setter(self, i):
        return lambda Y: self._set_inertia(i, Y)

    def _set_inertia(self, i, Y):
        if i == 0:
            raise NotImplementedError(
                "model.inertias[0]: rigid keeps no inertia for the universe (links welded to the "
                "world take no part in the dynamics)")
        d = self.desc()
        d["inertias"][i - 1] = _inertia_json(Y)
        self._rebuild(d)

    @property
    def jointPlacements(self):
        d = self.desc()
        items = [SE3()] + [_BoundSE3(_se3_of_json(j["placement"]), self._placement_setter(i + 1))
                           for i, j in enumerate(d["joints"])]
        return _ModelList(items, lambda i, M: self._set_placement(i, M))

    def _placement_setter(self, i):
        return lambda M: self._set_placement(i, M)

    def _set_placement(self, i, M):
        if i == 0:
            raise ValueError("model.jointPlacements[0]: the universe has no placement")
        d = self.desc()
        d["joints"][i - 1]["placement"] = _se3_json(M)
        self._rebuild(d)

    @property
    def frames(self):
        return _ModelList([f for f, _ in self._frames],
                          lambda i, F: self._replace_frame(i, F))

    def _replace_frame(self, i, F):
        old, src = self._frames[i]
        if src[0] != "frame":
            raise NotImplementedError(
                f"model.frames[{i}] = ...: frame '{old.name}' is a joint's or the universe's and "
                "moves with it; add an operational frame with model.addFrame instead")
        d = self.desc()
        d["frames"][src[1]]["placement"] = _se3_json(F.placement)
        d["frames"][src[1]]["name"] = F.name
        self._frames[i] = (F.copy(), src)
        self._rebuild(d)

    # ---- limits and joint parameters
    def _vector_property(name, doc):  # noqa: N805 (a property factory)
        def get(self):
            return getattr(self, name)

        def set_(self, x):
            x = np.asarray(x, dtype=float).reshape(-1)
            cur = getattr(self, name)
            if x.shape != cur.shape:
                raise ValueError(f"model.{doc}: expected {cur.size} numbers, got {x.size}")
            cur[...] = x
            self._push_limits()

        return property(get, set_, doc=doc)

    lowerPositionLimit = _vector_property("_lower", "lowerPositionLimit")
    upperPositionLimit = _vector_property("_upper", "upperPositionLimit")
    velocityLimit = _vector_property("_vlim", "velocityLimit")
    effortLimit = _vector_property("_elim", "effortLimit")
    del _vector_property

    def _dof_property(key):  # noqa: N805
        def get(self):
            r = np.array(self.desc()[key], dtype=float)
            return r[self._perm()]

        def set_(self, x):
            x = np.asarray(x, dtype=float).reshape(-1)
            if x.size != self.nv:
                raise ValueError(f"model.{key}: expected nv = {self.nv} numbers, got {x.size}")
            d = self.desc()
            r = np.empty(self.nv)
            r[self._perm()] = x
            d[key] = r.tolist()
            self._rebuild(d)

        return property(get, set_)

    armature = _dof_property("armature")
    damping = _dof_property("damping")
    friction = _dof_property("friction")
    del _dof_property

    @property
    def rotorInertia(self):
        return np.zeros(self.nv)

    @property
    def rotorGearRatio(self):
        return np.ones(self.nv)

    @property
    def gravity(self):
        g = _r.Model.gravity.__get__(self)
        return _GravityMotion(np.concatenate([g, np.zeros(3)]), self)

    @gravity.setter
    def gravity(self, g):
        v = g.vector if isinstance(g, Motion) else np.asarray(g, dtype=float).reshape(-1)
        if v.size == 6:
            if np.any(v[3:] != 0):
                raise NotImplementedError(
                    "model.gravity: rigid's gravity is a linear acceleration; an angular part "
                    "is not supported")
            v = v[:3]
        _r.Model.gravity.__set__(self, v)
        self._desc = None

    gravity981 = np.array([0.0, 0.0, -9.81])

    # ---- lookups
    def getJointId(self, name):
        """The index of the joint called ``name`` (``njoints`` if there is none)."""
        names = self.names
        return names.index(name) if name in names else self.njoints

    def existJointName(self, name):
        return name in self.names

    def getFrameId(self, name, type=None):  # noqa: A002 (Pinocchio's name)
        """The index of the first frame called ``name`` (of ``type``, any type by default;
        ``nframes`` if there is none)."""
        for i, (f, _) in enumerate(self._frames):
            if f.name == name and (type is None or f.type & type):
                return i
        return len(self._frames)

    def existFrame(self, name, type=None):  # noqa: A002
        return self.getFrameId(name, type) < len(self._frames)

    def getBodyId(self, name):
        return self.getFrameId(name, FrameType.BODY)

    def existBodyName(self, name):
        return self.existFrame(name, FrameType.BODY)

    def hasConfigurationLimit(self):
        return [True] * self.nq

    def createData(self):
        return Data(self)

    def check(self, data=None):
        return data is None or isinstance(data, _r.Data)

    def copy(self):
        import copy as _copy  # noqa: PLC0415

        return _copy.deepcopy(self)

    # ---- growing the model
    def addJoint(self, parent_id, joint_model, joint_placement, joint_name, *limits, **kw):
        """Adds a joint (a body with no mass until ``appendBodyToJoint``) below ``parent_id``;
        optional limits ``max_effort, max_velocity, min_config, max_config``, then ``friction``
        and ``damping`` (per velocity coordinate, as Pinocchio); returns its index. Joints must be added
        depth-first (a new joint's parent on the latest branch), as rigid keeps them."""
        d = self.desc()
        joints = d["joints"]
        n = len(joints)
        parent = None if parent_id == 0 else parent_id - 1
        if parent is not None and not (0 <= parent < n):
            raise ValueError(f"addJoint: parent_id {parent_id} does not exist")
        # the depth-first order: the parent is the last joint or one of its ancestors
        if n and parent != n - 1:
            a, ok = n - 1, parent is None
            while a is not None and not ok:
                a = joints[a]["parent"]
                ok = a == parent
            if not ok and parent is not None:
                raise NotImplementedError(
                    f"addJoint('{joint_name}'): rigid keeps joints depth-first, and joint "
                    f"{parent_id} is not on the latest branch; add each subtree's joints before "
                    "its siblings'")
        if joint_name in self.names:
            raise ValueError(f"addJoint: a joint is already called '{joint_name}'")
        kind = joint_model._kind()
        nq_r = NQ_RIGID[kind["type"]]
        nv = joint_model.nv
        idx_q = sum(j["nq"] for j in joints)
        idx_v = sum(j["nv"] for j in joints)
        joints.append({"name": joint_name, "kind": kind, "parent": parent,
                       "placement": _se3_json(SE3(joint_placement)), "idx_q": idx_q, "nq": nq_r,
                       "idx_v": idx_v, "nv": nv, "subtree_end": n + 1,
                       "continuous": bool(joint_model._continuous)})
        a = parent
        while a is not None:
            joints[a]["subtree_end"] = n + 1
            a = joints[a]["parent"]
        d["inertias"].append(_inertia_json(Inertia()))
        lim = list(limits) + [None] * 6
        eff, vel = kw.get("max_effort", lim[0]), kw.get("max_velocity", lim[1])
        lo, up = kw.get("min_config", lim[2]), kw.get("max_config", lim[3])
        pin_nq = joint_model.nq

        def pin_to_rigid(x, none):
            if x is None:
                return [None] * nq_r
            x = np.asarray(x, dtype=float).reshape(-1)
            if pin_nq != nq_r:  # cos/sin: no limit on the angle
                x = np.append(x[:-2], [np.nan])
            return [None if (np.isnan(v) or abs(v) >= 1e300) else float(v) for v in x]

        d["lower"] += pin_to_rigid(lo, None)
        d["upper"] += pin_to_rigid(up, None)

        def per_dof(x):
            if x is None:
                return [None] * nv
            x = np.asarray(x, dtype=float).reshape(-1)
            x = x[[(k + 3) % 6 for k in range(6)]] if kind["type"] == "free_flyer" else x
            return [None if abs(v) >= 1e300 else float(v) for v in x]

        d["velocity_limit"] += per_dof(vel)
        d["effort_limit"] += per_dof(eff)
        d["armature"] += [0.0] * nv
        for key, given in (("friction", kw.get("friction", lim[4])),
                           ("damping", kw.get("damping", lim[5]))):
            x = np.zeros(nv) if given is None else np.asarray(given, dtype=float).reshape(-1)
            if kind["type"] == "free_flyer":
                x = x[[(k + 3) % 6 for k in range(6)]]
            d[key] += [float(v) for v in x]
        self._rebuild(d, keep_id=False)
        self._origins.append("api")
        lo_p, up_p = (np.full(pin_nq, -MAX) if lo is None else np.asarray(lo, float).reshape(-1),
                      np.full(pin_nq, MAX) if up is None else np.asarray(up, float).reshape(-1))
        self._lower = np.concatenate([self._lower, lo_p])
        self._upper = np.concatenate([self._upper, up_p])
        self._vlim = np.concatenate([self._vlim, np.full(nv, MAX) if vel is None
                                     else np.asarray(vel, float).reshape(-1)])
        self._elim = np.concatenate([self._elim, np.full(nv, MAX) if eff is None
                                     else np.asarray(eff, float).reshape(-1)])
        return n + 1

    def appendBodyToJoint(self, joint_id, body_inertia, body_placement=None):
        """Adds a body of inertia ``body_inertia`` at ``body_placement`` (in the joint's frame)
        to the joint's body."""
        if joint_id == 0:
            raise NotImplementedError(
                "appendBodyToJoint(0, ...): bodies welded to the world take no part in the "
                "dynamics in rigid; nothing to add")
        d = self.desc()
        M = SE3() if body_placement is None else body_placement
        Y = _inertia_of_json(d["inertias"][joint_id - 1]) + M.act(body_inertia)
        d["inertias"][joint_id - 1] = _inertia_json(Y)
        self._rebuild(d)

    def _add_rigid_frame(self, frame):
        d = self.desc()
        d["frames"].append({"name": frame.name,
                            "parent": None if frame.parentJoint == 0 else frame.parentJoint - 1,
                            "placement": _se3_json(frame.placement),
                            "kind": _KIND_OF_TYPE[FrameType(frame.type)]})
        self._rebuild(d, keep_id=False)
        return ("frame", len(d["frames"]) - 1)

    def addFrame(self, frame, append_inertia=True):
        """Adds ``frame``; returns its index (an existing frame of the same name and type keeps
        its index)."""
        for i, (f, _) in enumerate(self._frames):
            if f.name == frame.name and f.type == frame.type:
                return i
        if frame.type == FrameType.JOINT:
            src = ("joint", frame.parentJoint - 1)
        else:
            src = self._add_rigid_frame(frame)
        self._frames.append((frame.copy(), src))
        return len(self._frames) - 1

    def addJointFrame(self, joint_index, frame_index=-1):
        name = self.names[joint_index]
        prev = frame_index if frame_index >= 0 else 0
        return self.addFrame(Frame(name, joint_index, prev, SE3(), FrameType.JOINT))

    def addBodyFrame(self, body_name, parentJoint, body_placement=None, previous_frame=-1):
        prev = previous_frame if previous_frame >= 0 else 0
        return self.addFrame(Frame(body_name, parentJoint, prev,
                                   SE3() if body_placement is None else body_placement,
                                   FrameType.BODY))

    # ---- pickling
    def __reduce__(self):
        frames = [(f, src) for f, src in self._frames]
        return (_rebuild_model, (self.to_json(), list(self.warnings), frames,
                                 list(self._origins), (self._lower, self._upper, self._vlim,
                                                       self._elim), self._world_inertia,
                                 self.referenceConfigurations))

    def __copy__(self):
        return self

    def __deepcopy__(self, memo):
        fn, args = self.__reduce__()
        import copy as _copy  # noqa: PLC0415

        out = fn(*_copy.deepcopy(args, memo))
        memo[id(self)] = out
        return out

    def __repr__(self):
        return f"rigid.pinocchio.Model('{self.name}', nq={self.nq}, nv={self.nv}, " \
               f"njoints={self.njoints}, nframes={self.nframes})"

    def __str__(self):
        lines = [f"Nb joints = {self.njoints} (nq={self.nq},nv={self.nv})"]
        par = self.parents
        for i, n in enumerate(self.names):
            lines.append(f"  Joint {i} {n}: parent={par[i]}")
        return "\n".join(lines) + "\n"


def _rebuild_model(text, warnings, frames, origins, limits, world=None, references=None):
    m = Model(text, _warnings=warnings, _frames=frames, _origins=origins, _limits=limits)
    if world is not None:
        m._world_inertia = world
    m.referenceConfigurations = dict(references or {})
    return m

