"""Pinocchio's enums (``ReferenceFrame``, ``FrameType``, ...), joint models (``JointModelRX``,
``JointModelFreeFlyer``, ...) and ``Frame``, and how rigid's serialised model maps to them
(Pinocchio's frames from rigid's joints and frames)."""

import enum

import numpy as np

from .spatial import SE3, Inertia

__all__ = ["Frame", "FrameType", "ReferenceFrame", "KinematicLevel", "Convention", "JointModel",
           "JOINT_MODELS"]


class ReferenceFrame(enum.IntEnum):
    """The frame a Jacobian or a derivative is expressed in."""

    WORLD = 0
    LOCAL = 1
    LOCAL_WORLD_ALIGNED = 2

    def __str__(self):
        return self.name


ReferenceFrame.names = {m.name: m for m in ReferenceFrame}
ReferenceFrame.values = {int(m): m for m in ReferenceFrame}


class FrameType(enum.IntFlag):
    """What a frame stands for."""

    OP_FRAME = 1
    JOINT = 2
    FIXED_JOINT = 4
    BODY = 8
    SENSOR = 16

    def __str__(self):
        return self.name


FrameType.names = {m.name: m for m in FrameType}


class KinematicLevel(enum.IntEnum):
    POSITION = 0
    VELOCITY = 1
    ACCELERATION = 2


class Convention(enum.IntEnum):
    WORLD = 0
    LOCAL = 1


class ArgumentPosition(enum.IntEnum):
    ARG0 = 0
    ARG1 = 1
    ARG2 = 2
    ARG3 = 3
    ARG4 = 4


# rigid's frame kinds <-> Pinocchio's frame types
_KIND_OF_TYPE = {FrameType.BODY: "body", FrameType.FIXED_JOINT: "fixed_joint",
                 FrameType.OP_FRAME: "operational", FrameType.SENSOR: "operational"}
_TYPE_OF_KIND = {"body": FrameType.BODY, "fixed_joint": FrameType.FIXED_JOINT,
                 "operational": FrameType.OP_FRAME}


def _se3_json(M):
    return {"rotation": M.rotation.tolist(), "translation": M.translation.tolist()}


def _se3_of_json(t):
    return SE3(np.array(t["rotation"], dtype=float), np.array(t["translation"], dtype=float))


def _inertia_json(Y):
    m, c = Y.mass, Y.lever
    C = np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])
    return {"mass": m, "first_moment": (m * c).tolist(),
            "inertia_origin": (Y.inertia - m * C @ C).tolist()}


def _inertia_of_json(g):
    m = float(g["mass"])
    h = np.array(g["first_moment"], dtype=float)
    Io = np.array(g["inertia_origin"], dtype=float)
    c = h / m if m > 0 else np.zeros(3)
    C = np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])
    return Inertia(m, c, Io + m * C @ C)


# ---------------------------------------------------------------- joint models


# rigid's number of position coordinates of each kind of joint (the serialised form's "type"):
# one angle for a continuous joint and the planar one's heading, quaternions x-y-z-w
NQ_RIGID = {"revolute": 1, "prismatic": 1, "helical": 1, "universal": 2, "spherical": 4,
            "free_flyer": 7, "planar": 3}


class JointModel:
    """A joint type (Pinocchio's ``JointModel*``): the argument of ``addJoint`` and of the root
    joint of the loaders, and the entries of ``model.joints``."""

    _short = "JointModel"

    def __init__(self):
        self.id, self.idx_q, self.idx_v = -1, -1, -1

    # rigid's kind (the serialised form) and whether it is continuous
    def _kind(self):
        raise NotImplementedError(
            f"{self._short}: this joint type is not available in rigid.pinocchio (rigid's joints "
            "are revolute, prismatic, helical, universal, spherical, planar and free-flyer); "
            "use one of those")

    _continuous = False

    @property
    def nq(self):
        return self._nq

    @property
    def nv(self):
        return self._nv

    def shortname(self):
        return self._short

    def classname(self):
        return self._short

    def setIndexes(self, id, idx_q, idx_v):
        self.id, self.idx_q, self.idx_v = id, idx_q, idx_v

    def hasSameIndexes(self, other):
        return (self.id, self.idx_q, self.idx_v) == (other.id, other.idx_q, other.idx_v)

    def __eq__(self, other):
        return (type(self) is type(other) and self.__dict__ == other.__dict__)

    __hash__ = None

    def __str__(self):
        return (f"{self._short}\n  index: {self.id}\n  index q: {self.idx_q}\n"
                f"  index v: {self.idx_v}\n  nq: {self.nq}\n  nv: {self.nv}\n")

    __repr__ = __str__


def _axis_class(name, kind, nq, nv, axis, continuous=False):
    def _kind(self):
        return {"type": kind, "axis": list(axis)}

    return type(name, (JointModel,), {"_short": name, "_nq": nq, "_nv": nv, "_kind": _kind,
                                      "_continuous": continuous,
                                      "axis": property(lambda s: np.array(axis, dtype=float))})


JointModelRX = _axis_class("JointModelRX", "revolute", 1, 1, (1.0, 0.0, 0.0))
JointModelRY = _axis_class("JointModelRY", "revolute", 1, 1, (0.0, 1.0, 0.0))
JointModelRZ = _axis_class("JointModelRZ", "revolute", 1, 1, (0.0, 0.0, 1.0))
JointModelRUBX = _axis_class("JointModelRUBX", "revolute", 2, 1, (1.0, 0.0, 0.0), True)
JointModelRUBY = _axis_class("JointModelRUBY", "revolute", 2, 1, (0.0, 1.0, 0.0), True)
JointModelRUBZ = _axis_class("JointModelRUBZ", "revolute", 2, 1, (0.0, 0.0, 1.0), True)
JointModelPX = _axis_class("JointModelPX", "prismatic", 1, 1, (1.0, 0.0, 0.0))
JointModelPY = _axis_class("JointModelPY", "prismatic", 1, 1, (0.0, 1.0, 0.0))
JointModelPZ = _axis_class("JointModelPZ", "prismatic", 1, 1, (0.0, 0.0, 1.0))


def _unit(args, what):
    a = np.array(args[0] if len(args) == 1 else args, dtype=float).reshape(3)
    n = np.linalg.norm(a)
    if not n > 0:
        raise ValueError(f"{what}: the axis must not be zero")
    return a / n


class _Unaligned(JointModel):
    _kindname = "revolute"
    _nq = _nv = 1

    def __init__(self, *axis):
        super().__init__()
        self.axis = _unit(axis, self._short) if axis else np.array([1.0, 0.0, 0.0])

    def _kind(self):
        return {"type": self._kindname, "axis": self.axis.tolist()}


class JointModelRevoluteUnaligned(_Unaligned):
    _short = "JointModelRevoluteUnaligned"


class JointModelRevoluteUnboundedUnaligned(_Unaligned):
    _short = "JointModelRevoluteUnboundedUnaligned"
    _nq = 2
    _continuous = True


class JointModelPrismaticUnaligned(_Unaligned):
    _short = "JointModelPrismaticUnaligned"
    _kindname = "prismatic"


class _Helical(JointModel):
    _nq = _nv = 1

    def __init__(self, pitch=0.0):
        super().__init__()
        self.pitch = float(pitch)

    def _kind(self):
        return {"type": "helical", "axis": list(self._axis), "pitch": self.pitch}


class JointModelHX(_Helical):
    _short, _axis = "JointModelHX", (1.0, 0.0, 0.0)


class JointModelHY(_Helical):
    _short, _axis = "JointModelHY", (0.0, 1.0, 0.0)


class JointModelHZ(_Helical):
    _short, _axis = "JointModelHZ", (0.0, 0.0, 1.0)


class JointModelHelicalUnaligned(JointModel):
    _short = "JointModelHelicalUnaligned"
    _nq = _nv = 1

    def __init__(self, axis=(1.0, 0.0, 0.0), pitch=0.0):
        super().__init__()
        self.axis, self.pitch = _unit([axis], self._short), float(pitch)

    def _kind(self):
        return {"type": "helical", "axis": self.axis.tolist(), "pitch": self.pitch}


class JointModelUniversal(JointModel):
    _short = "JointModelUniversal"
    _nq = _nv = 2

    def __init__(self, axis1=(1.0, 0.0, 0.0), axis2=(0.0, 1.0, 0.0)):
        super().__init__()
        self.axis1, self.axis2 = _unit([axis1], self._short), _unit([axis2], self._short)

    def _kind(self):
        return {"type": "universal", "axis1": self.axis1.tolist(), "axis2": self.axis2.tolist()}


class JointModelSpherical(JointModel):
    _short, _nq, _nv = "JointModelSpherical", 4, 3

    def _kind(self):
        return {"type": "spherical"}


class JointModelFreeFlyer(JointModel):
    _short, _nq, _nv = "JointModelFreeFlyer", 7, 6

    def _kind(self):
        return {"type": "free_flyer"}


class JointModelPlanar(JointModel):
    _short, _nq, _nv = "JointModelPlanar", 4, 3

    def _kind(self):
        return {"type": "planar"}


def _unsupported_joint(name, nq, nv):
    def __init__(self, *args, **kwargs):
        raise NotImplementedError(
            f"{name} is not available in rigid.pinocchio: rigid's joints are revolute (RX, "
            "RevoluteUnaligned, RUBX, ...), prismatic, helical, universal, spherical, planar and "
            "free-flyer (JointModelFreeFlyer); compose them with several joints instead")

    return type(name, (JointModel,), {"_short": name, "_nq": nq, "_nv": nv,
                                      "__init__": __init__})


JointModelSphericalZYX = _unsupported_joint("JointModelSphericalZYX", 3, 3)
JointModelTranslation = _unsupported_joint("JointModelTranslation", 3, 3)
JointModelComposite = _unsupported_joint("JointModelComposite", 0, 0)
JointModelMimic = _unsupported_joint("JointModelMimic", 0, 0)
JointModelEllipsoid = _unsupported_joint("JointModelEllipsoid", 3, 3)

JOINT_MODELS = {c.__name__: c for c in [
    JointModelRX, JointModelRY, JointModelRZ, JointModelRUBX, JointModelRUBY, JointModelRUBZ,
    JointModelPX, JointModelPY, JointModelPZ, JointModelRevoluteUnaligned,
    JointModelRevoluteUnboundedUnaligned, JointModelPrismaticUnaligned, JointModelHX,
    JointModelHY, JointModelHZ, JointModelHelicalUnaligned, JointModelUniversal,
    JointModelSpherical, JointModelFreeFlyer, JointModelPlanar, JointModelSphericalZYX,
    JointModelTranslation, JointModelComposite, JointModelMimic, JointModelEllipsoid]}
__all__ += list(JOINT_MODELS)


def _joint_model_of(j):
    """The Pinocchio joint model of a joint of rigid's serialised form."""
    k = j["kind"]
    t = k["type"]
    if t in ("revolute", "prismatic"):
        axis = np.array(k["axis"], dtype=float)
        cont = j.get("continuous", False)
        for i, e in enumerate(np.eye(3)):
            if np.array_equal(axis, e):
                letter = "XYZ"[i]
                name = ("JointModelRUB" if cont else "JointModelR") + letter \
                    if t == "revolute" else "JointModelP" + letter
                return JOINT_MODELS[name]()
        if t == "prismatic":
            return JointModelPrismaticUnaligned(axis)
        return (JointModelRevoluteUnboundedUnaligned if cont else JointModelRevoluteUnaligned)(axis)
    if t == "helical":
        axis = np.array(k["axis"], dtype=float)
        for i, e in enumerate(np.eye(3)):
            if np.array_equal(axis, e):
                return JOINT_MODELS["JointModelH" + "XYZ"[i]](k["pitch"])
        return JointModelHelicalUnaligned(axis, k["pitch"])
    if t == "universal":
        return JointModelUniversal(k["axis1"], k["axis2"])
    if t == "spherical":
        return JointModelSpherical()
    if t == "free_flyer":
        return JointModelFreeFlyer()
    if t == "planar":
        return JointModelPlanar()
    raise NotImplementedError(f"joint type {t}")


class _Universe(JointModel):
    """Joint 0: the world (Pinocchio's universe, a fixed 'joint' with no coordinate)."""

    _short, _nq, _nv = "JointModelRX", 1, 1

    def __init__(self):
        super().__init__()
        self.id, self.idx_q, self.idx_v = 2 ** 64 - 1, -1, -1


# ---------------------------------------------------------------- frames


class Frame:
    """A frame fixed in a joint's body (Pinocchio's ``Frame``): ``name``, ``parentJoint``,
    ``parentFrame``, ``placement`` (in the joint's frame), ``type``, ``inertia``."""

    def __init__(self, name, parentJoint=0, parentFrame=0, placement=None,
                 type=FrameType.OP_FRAME, inertia=None):  # noqa: A002 (Pinocchio's name)
        if isinstance(parentFrame, SE3):  # Frame(name, parentJoint, placement, type)
            parentFrame, placement, type = 0, parentFrame, placement  # noqa: A001
        self.name = name
        self.parentJoint = int(parentJoint)
        self.parentFrame = int(parentFrame)
        self.placement = SE3() if placement is None else SE3(placement)
        self.type = FrameType(type)
        self.inertia = Inertia() if inertia is None else Inertia(inertia)

    parent = property(lambda s: s.parentJoint, lambda s, x: setattr(s, "parentJoint", x))
    previousFrame = property(lambda s: s.parentFrame, lambda s, x: setattr(s, "parentFrame", x))

    def copy(self):
        return Frame(self.name, self.parentJoint, self.parentFrame, self.placement, self.type,
                     self.inertia)

    def __eq__(self, o):
        return (isinstance(o, Frame) and (self.name, self.parentJoint, self.type)
                == (o.name, o.parentJoint, o.type) and self.placement == o.placement)

    __hash__ = None

    def __reduce__(self):
        return (Frame, (self.name, self.parentJoint, self.parentFrame, self.placement,
                        int(self.type), self.inertia))

    def __str__(self):
        return (f"Frame name: {self.name} paired to (parent joint/ parent frame)"
                f"({self.parentJoint}/{self.parentFrame})\nwith relative placement wrt parent "
                f"joint:\n{self.placement}")

    __repr__ = __str__


def _frames_of(desc):
    """Pinocchio's frame list of a model read from a URDF file, from rigid's frames (each link
    a BODY frame, each fixed joint a FIXED_JOINT frame listed after its child link) and joints:
    the universe; then, depth-first, a JOINT frame for each joint followed by its child link's
    BODY frame, and each fixed joint's FIXED_JOINT frame before its child link's BODY frame.
    Each entry: (Frame, source) with source ``("world",)``, ``("joint", j)`` (rigid's index) or
    ``("frame", k)`` (rigid's frame index)."""
    joints, rf = desc["joints"], desc["frames"]
    out = [(Frame("universe", 0, 0, SE3(), FrameType.FIXED_JOINT), ("world",))]
    last_body = {}  # Pinocchio joint index -> its latest BODY frame

    def add(frame, src):
        out.append((frame, src))
        if frame.type == FrameType.BODY:
            last_body[frame.parentJoint] = len(out) - 1
        return len(out) - 1

    done = set()

    def joint_frame(j):
        p = joints[j]["parent"]
        pj = 0 if p is None else p + 1
        add(Frame(joints[j]["name"], j + 1, last_body.get(pj, 0), SE3(), FrameType.JOINT),
            ("joint", j))
        done.add(j)

    k = 0
    while k < len(rf):
        f = rf[k]
        p = f["parent"]
        pj = 0 if p is None else p + 1
        M = _se3_of_json(f["placement"])
        if f["kind"] == "body":
            nxt = rf[k + 1] if k + 1 < len(rf) else None
            if (nxt is not None and nxt["kind"] == "fixed_joint" and nxt["parent"] == p
                    and nxt["placement"] == f["placement"]):
                i = add(Frame(nxt["name"], pj, last_body.get(pj, 0), M, FrameType.FIXED_JOINT),
                        ("frame", k + 1))
                add(Frame(f["name"], pj, i, M, FrameType.BODY), ("frame", k))
                k += 2
                continue
            if p is not None and p not in done and M.isIdentity(0.0):
                joint_frame(p)
            add(Frame(f["name"], pj, len(out) - 1 if p is not None else 0, M, FrameType.BODY),
                ("frame", k))
        else:
            add(Frame(f["name"], pj, last_body.get(pj, 0), M, _TYPE_OF_KIND[f["kind"]]),
                ("frame", k))
        k += 1
    for j in range(len(joints)):
        if j not in done:
            joint_frame(j)
    return out
