"""Pinocchio's geometry models: ``GeometryObject``, ``GeometryModel``, ``GeometryData``, the
URDF's ``<collision>`` and ``<visual>`` elements (``buildGeomFromUrdf``, read by rigid), their
world placements, and the collisions and distances of their pairs on rigid's collision layer
(``rigid.Collider``, ``rigid.proximity``: parry; a mesh collides as its convex hull, where
hpp-fcl tests its triangles). SRDF files (``removeCollisionPairs``,
``loadReferenceConfigurations``) are read by ``rigid.read_srdf``."""

import os
import warnings

import numpy as np

from .. import rigid as _r
from . import fcl
from .joints import FrameType
from .spatial import SE3

__all__ = [
    "GeometryType", "GeometryObject", "GeometryModel", "GeometryData", "CollisionPair",
    "CollisionResult", "DistanceResult", "buildGeomFromUrdf", "createDatas",
    "updateGeometryPlacements", "computeCollision", "computeCollisions", "computeDistance",
    "computeDistances", "removeCollisionPairs", "loadReferenceConfigurations",
]


class GeometryType:
    VISUAL = 0
    COLLISION = 1


class GeometryObject:
    """A shape fixed in a joint's body, Pinocchio's overloads: ``GeometryObject(name,
    parent_joint, parent_frame, placement, shape[, mesh_path, mesh_scale, override_material,
    mesh_color, mesh_texture_path])``, ``(name, parent_joint, placement, shape, ...)``, and the
    deprecated ``(name, parent_frame, parent_joint, shape, placement, ...)``; keywords as
    Pinocchio's. A frame not given is ``2**64 - 1`` (none), as in Pinocchio."""

    NO_FRAME = 2**64 - 1
    _OPTIONAL = ("mesh_path", "mesh_scale", "override_material", "mesh_color", "mesh_texture_path")

    def __init__(self, name, *args, **kwargs):
        args = list(args)
        ints = []
        while args and isinstance(args[0], (int, np.integer)) and len(ints) < 2:
            ints.append(int(args.pop(0)))
        kw = dict(kwargs)
        joint = kw.pop("parent_joint", None)
        frame = kw.pop("parent_frame", None)
        if len(args) >= 2 and not isinstance(args[0], SE3) and isinstance(args[1], SE3):
            # (name, parent_frame, parent_joint, shape, placement): Pinocchio 3's deprecated form
            shape, placement = args[0], args[1]
            if len(ints) == 2:
                frame, joint = ints
            args = args[2:]
        else:
            placement = args.pop(0) if args and isinstance(args[0], SE3) else kw.pop("placement", None)
            shape = args.pop(0) if args else kw.pop("collision_geometry", None)
            if len(ints) == 2:
                joint, frame = ints
            elif len(ints) == 1:
                joint = ints[0]
        if joint is None or shape is None or placement is None:
            raise TypeError(f"GeometryObject('{name}'): GeometryObject(name, parent_joint, "
                            "[parent_frame,] placement, shape, ...)")
        for key, value in zip(self._OPTIONAL, args):
            kw.setdefault(key, value)
        unknown = set(kw) - set(self._OPTIONAL) - {"collision_geometry", "placement"}
        if unknown:
            raise TypeError(f"GeometryObject('{name}'): unknown arguments {sorted(unknown)}")
        self.name = name
        self.parentJoint = int(joint)
        self.parentFrame = self.NO_FRAME if frame is None else int(frame)
        self.placement = SE3(placement)
        self.geometry = shape
        self.meshPath = kw.get("mesh_path", "")
        scale, color = kw.get("mesh_scale"), kw.get("mesh_color")
        self.meshScale = np.ones(3) if scale is None else np.array(scale, dtype=float)
        self.meshColor = (np.array([0.0, 0.0, 0.0, 1.0]) if color is None
                          else np.array(color, dtype=float))
        self.overrideMaterial = bool(kw.get("override_material", False))
        self.meshTexturePath = kw.get("mesh_texture_path", "")
        self.disableCollision = False

    parentJointId = property(lambda s: s.parentJoint)

    def copy(self):
        """A copy (its own placement, scale and colour; the same shape object, as Pinocchio's
        shared pointer)."""
        g = GeometryObject(self.name, self.parentJoint, self.parentFrame, self.placement.copy(),
                           self.geometry, mesh_path=self.meshPath, mesh_scale=self.meshScale,
                           override_material=self.overrideMaterial, mesh_color=self.meshColor,
                           mesh_texture_path=self.meshTexturePath)
        g.disableCollision = self.disableCollision
        return g

    def __repr__(self):
        return (f"Name: \t \n{self.name}\nParent frame ID: \t \n{self.parentFrame}\n"
                f"Parent joint ID: \t \n{self.parentJoint}\nPosition in parent frame: \t \n"
                f"{self.placement}\nAbsolute path to mesh file: \t \n{self.meshPath}\n"
                f"Scale of the mesh: \t \n{self.meshScale}\nColor of the mesh: \t \n"
                f"{self.meshColor}\n")


class CollisionPair:
    """A pair of geometry indices ``(first, second)``; equal in either order."""

    def __init__(self, first, second):
        if first == second:
            raise ValueError(f"CollisionPair({first}, {second}): a geometry with itself")
        self.first, self.second = int(first), int(second)

    def __eq__(self, o):
        return isinstance(o, CollisionPair) and {self.first, self.second} == {o.first, o.second}

    def __hash__(self):
        return hash(frozenset((self.first, self.second)))

    def __repr__(self):
        return f"({self.first},{self.second})"


class CollisionResult:
    """hpp-fcl's answer for one pair: ``isCollision()``, and its contact (``getContact(0)``:
    ``pos``, ``normal``, ``penetration_depth``)."""

    def __init__(self):
        self.clear()

    def clear(self):
        self._contacts = []

    def isCollision(self):
        return bool(self._contacts)

    def numContacts(self):
        return len(self._contacts)

    def getContact(self, i):
        return self._contacts[i]

    def getContacts(self):
        return list(self._contacts)


class _Contact:
    def __init__(self, pos, normal, depth):
        self.pos, self.normal, self.penetration_depth = pos, normal, depth


class DistanceResult:
    """hpp-fcl's distance of one pair: ``min_distance`` (negative: penetration depth), the
    nearest points, ``normal`` (out of the first towards the second)."""

    def __init__(self, d=np.inf, p1=None, p2=None, normal=None):
        self.min_distance = d
        self.nearest_points = [np.zeros(3) if p1 is None else p1, np.zeros(3) if p2 is None else p2]
        self.normal = np.zeros(3) if normal is None else normal

    def getNearestPoint1(self):
        return self.nearest_points[0]

    def getNearestPoint2(self):
        return self.nearest_points[1]


class GeometryModel:
    """Geometry objects and the pairs of them whose collisions are checked."""

    def __init__(self):
        self.geometryObjects = []
        self.collisionPairs = []

    @property
    def ngeoms(self):
        return len(self.geometryObjects)

    def addGeometryObject(self, obj, model=None):
        """Adds a copy of ``obj`` (as Pinocchio); with ``model``, an object without a frame
        gets its joint's frame. Returns its index."""
        obj = obj.copy()
        if model is not None and obj.parentFrame == GeometryObject.NO_FRAME:
            obj.parentFrame = next((i for i, f in enumerate(model.frames)
                                    if f.parentJoint == obj.parentJoint
                                    and f.type == FrameType.JOINT), 0)
        self.geometryObjects.append(obj)
        return len(self.geometryObjects) - 1

    def getGeometryId(self, name):
        for i, g in enumerate(self.geometryObjects):
            if g.name == name:
                return i
        return self.ngeoms

    def existGeometryName(self, name):
        return any(g.name == name for g in self.geometryObjects)

    def addCollisionPair(self, pair):
        if not (0 <= pair.first < self.ngeoms and 0 <= pair.second < self.ngeoms):
            raise ValueError(f"addCollisionPair{pair}: the model has {self.ngeoms} geometries")
        if pair not in self.collisionPairs:
            self.collisionPairs.append(pair)

    def addAllCollisionPairs(self):
        """Every pair of geometries on different joints (Pinocchio's rule)."""
        self.collisionPairs = []
        g = self.geometryObjects
        for i in range(len(g)):
            for j in range(i + 1, len(g)):
                if g[i].parentJoint != g[j].parentJoint:
                    self.collisionPairs.append(CollisionPair(i, j))

    def removeCollisionPair(self, pair):
        if pair in self.collisionPairs:
            self.collisionPairs.remove(pair)

    def removeAllCollisionPairs(self):
        self.collisionPairs = []

    def existCollisionPair(self, pair):
        return pair in self.collisionPairs

    def findCollisionPair(self, pair):
        return (self.collisionPairs.index(pair) if pair in self.collisionPairs
                else len(self.collisionPairs))

    def createData(self):
        return GeometryData(self)

    def copy(self):
        c = GeometryModel()
        c.geometryObjects = [g.copy() for g in self.geometryObjects]
        c.collisionPairs = [CollisionPair(p.first, p.second) for p in self.collisionPairs]
        return c

    clone = copy

    def __str__(self):
        return f"Nb geometry objects = {self.ngeoms}\n" + "".join(
            repr(g) for g in self.geometryObjects)


class GeometryData:
    """The workspace of a ``GeometryModel``: ``oMg`` (each geometry's world placement, after
    ``updateGeometryPlacements``), and per pair ``activeCollisionPairs``,
    ``collisionResults``, ``distanceResults``."""

    def __init__(self, geom_model):
        n, p = geom_model.ngeoms, len(geom_model.collisionPairs)
        self.oMg = [SE3.Identity() for _ in range(n)]
        self.activeCollisionPairs = [True] * p
        self.collisionResults = [CollisionResult() for _ in range(p)]
        self.distanceResults = [DistanceResult() for _ in range(p)]

    def _check(self, geom_model):
        p, n = len(geom_model.collisionPairs), geom_model.ngeoms
        if len(self.collisionResults) != p or len(self.oMg) != n:
            raise ValueError(f"GeometryData: made for {len(self.oMg)} geometries and "
                             f"{len(self.collisionResults)} pairs, the model has {n} and {p}: "
                             "make it again (geom_model.createData()) after adding any")


def createDatas(model, *geom_models):
    """``(data, geom_data, ...)``: a ``Data`` for the model and one per geometry model."""
    return (model.createData(),) + tuple(g.createData() for g in geom_models)


def updateGeometryPlacements(model, data, geom_model, geom_data, q=None):
    """``oMg[i] = oMi[parentJoint] * placement``, after ``forwardKinematics(model, data, q)``
    when ``q`` is given."""
    if q is not None:
        _r.forward_kinematics(model, data, q)
    oMi = data.oMi
    for i, g in enumerate(geom_model.geometryObjects):
        geom_data.oMg[i] = oMi[g.parentJoint] * g.placement
    return geom_data


def _pair_proximity(geom_model, geom_data, k):
    pair = geom_model.collisionPairs[k]
    ends = []
    for i in (pair.first, pair.second):
        g = geom_model.geometryObjects[i]
        try:
            collider, offset = g.geometry.collider()
        except (ValueError, OSError) as e:
            raise ValueError(f"collision pair {k} {pair}: geometry {i} '{g.name}': {e}") from None
        M = geom_data.oMg[i].homogeneous
        ends.append((collider, M if offset is None else M @ offset))
    return _r.proximity(ends[0][0], ends[0][1], ends[1][0], ends[1][1])


def _checked(geom_model, geom_data, k):
    """Whether pair ``k`` is checked: active, and neither geometry's collisions disabled."""
    p, g = geom_model.collisionPairs[k], geom_model.geometryObjects
    return (geom_data.activeCollisionPairs[k] and not g[p.first].disableCollision
            and not g[p.second].disableCollision)


def computeCollision(geom_model, geom_data, pair_index, *args):
    """Whether pair ``pair_index`` touches at ``geom_data.oMg``; ``collisionResults[pair_index]``
    holds its contact."""
    geom_data._check(geom_model)
    d, pa, pb, n = _pair_proximity(geom_model, geom_data, pair_index)
    r = geom_data.collisionResults[pair_index]
    r.clear()
    if d <= 0.0:
        r._contacts.append(_Contact(0.5 * (pa + pb), n, d))
    return r.isCollision()


def computeCollisions(*args, stop_at_first_collision=False):
    """``computeCollisions(model, data, geom_model, geom_data, q, stop_at_first_collision=False)``
    (placements updated first) or ``computeCollisions(geom_model, geom_data,
    stop_at_first_collision=False)``: whether any active pair collides."""
    if len(args) >= 5:
        model, data, geom_model, geom_data, q = args[:5]
        stop = args[5] if len(args) > 5 else stop_at_first_collision
        updateGeometryPlacements(model, data, geom_model, geom_data, q)
    else:
        geom_model, geom_data = args[:2]
        stop = args[2] if len(args) > 2 else stop_at_first_collision
    geom_data._check(geom_model)
    any_ = False
    for k in range(len(geom_model.collisionPairs)):
        if not _checked(geom_model, geom_data, k):
            geom_data.collisionResults[k].clear()
            continue
        if computeCollision(geom_model, geom_data, k):
            any_ = True
            if stop:
                break
    return any_


def computeDistance(geom_model, geom_data, pair_index):
    """The ``DistanceResult`` of pair ``pair_index`` at ``geom_data.oMg`` (also stored in
    ``distanceResults``)."""
    geom_data._check(geom_model)
    d, pa, pb, n = _pair_proximity(geom_model, geom_data, pair_index)
    geom_data.distanceResults[pair_index] = DistanceResult(d, pa, pb, n)
    return geom_data.distanceResults[pair_index]


def computeDistances(*args):
    """``computeDistances(model, data, geom_model, geom_data[, q])`` or ``(geom_model,
    geom_data)``: every active pair's distance; returns the index of the nearest pair."""
    if len(args) >= 4:
        model, data, geom_model, geom_data = args[:4]
        updateGeometryPlacements(model, data, geom_model, geom_data,
                                 args[4] if len(args) > 4 else None)
    else:
        geom_model, geom_data = args[:2]
    geom_data._check(geom_model)
    best, nearest = np.inf, len(geom_model.collisionPairs)
    for k in range(len(geom_model.collisionPairs)):
        if _checked(geom_model, geom_data, k):
            d = computeDistance(geom_model, geom_data, k).min_distance
            if d < best:
                best, nearest = d, k
    return nearest


_PRIMITIVE = {"box": ("BOX", lambda s: fcl.Box(*s)),
              "cylinder": ("CYLINDER", lambda s: fcl.Cylinder(*s)),
              "sphere": ("SPHERE", lambda s: fcl.Sphere(*s)),
              "capsule": ("CAPSULE", lambda s: fcl.Capsule(*s))}


def _mesh_file(e, package_dirs):
    """The file of a ``<mesh>``: where rigid finds it (``package://`` against the URDF's folders
    and ``ROS_PACKAGE_PATH``), else ``package://PKG/rest`` as ``DIR/PKG/rest`` or ``DIR/rest`` of
    a ``package_dirs`` folder; ValueError naming it, as Pinocchio, when none exists."""
    if e["mesh_path"]:
        return e["mesh_path"]
    name = e["filename"]
    rest = name[len("package://"):] if name.startswith("package://") else name
    for d in package_dirs:
        for candidate in (os.path.join(d, rest), os.path.join(d, rest.split("/", 1)[-1])):
            if os.path.isfile(candidate):
                return candidate
    raise ValueError(f"Mesh {name} could not be found.")


def buildGeomFromUrdf(model, filename, geom_type, *args, package_dirs=None, mesh_loader=None):
    """The ``<collision>`` (``GeometryType.COLLISION``) or ``<visual>`` elements of the URDF's
    links as a ``GeometryModel`` on ``model`` (built from the same file): named ``link_k``, on the
    link's body frame and its joint, placed at the frame's placement times the element's origin,
    links in the model's order; a mesh's ``meshPath`` is its file, a primitive's ``BOX``,
    ``CYLINDER``, ... Pinocchio's forms: ``(model, filename, type[, package_dirs])`` and
    ``(model, filename, type, geom_model[, package_dirs])``, which fills ``geom_model``."""
    out = GeometryModel()
    args = list(args)
    if args and isinstance(args[0], GeometryModel):
        out = args.pop(0)
    if args:
        package_dirs = args.pop(0)
    if isinstance(package_dirs, (str, os.PathLike)):
        package_dirs = [package_dirs]
    dirs = [os.fspath(d) for d in (package_dirs or [])]
    kind = "visual" if int(geom_type) == GeometryType.VISUAL else "collision"
    by_link = {}
    for e in _r.urdf_link_geometries(os.fspath(filename), kind):
        by_link.setdefault(e["link"], []).append(e)
    for fid, f in enumerate(model.frames):
        if f.type != FrameType.BODY or f.name not in by_link:
            continue
        for e in by_link.pop(f.name):
            if e["shape"] == "mesh":
                path = _mesh_file(e, dirs)
                shape, mesh_path, scale = fcl.BVHModelOBBRSS(path, e["scale"]), path, e["scale"]
            else:
                mesh_path, make = _PRIMITIVE[e["shape"]]
                shape, scale = make(e["size"]), np.ones(3)
            # Pinocchio: the material's colour on a visual, light grey otherwise
            color = e["rgba"] if kind == "visual" and e["rgba"] is not None \
                else np.array([0.9, 0.9, 0.9, 1.0])
            g = GeometryObject(f"{f.name}_{e['index']}", f.parentJoint, fid,
                               f.placement * SE3(e["origin"]), shape, mesh_path=mesh_path,
                               mesh_scale=scale, mesh_color=color,
                               override_material=kind == "visual" and e["rgba"] is not None)
            out.addGeometryObject(g)
    return out


def removeCollisionPairs(model, geom_model, srdf_filename, verbose=False):
    """Removes the pairs of geometries of the links an SRDF file disables
    (``<disable_collisions link1 link2>``): the geometries on those links' body frames."""
    srdf = _r.read_srdf(os.fspath(srdf_filename))
    frame_of = {f.name: i for i, f in enumerate(model.frames) if f.type == FrameType.BODY}
    geoms = geom_model.geometryObjects
    for l1, l2 in srdf["disabled"]:
        if l1 not in frame_of or l2 not in frame_of:
            continue
        f1, f2 = frame_of[l1], frame_of[l2]
        for i, a in enumerate(geoms):
            for j, b in enumerate(geoms):
                if i != j and a.parentFrame == f1 and b.parentFrame == f2:
                    geom_model.removeCollisionPair(CollisionPair(i, j))


def loadReferenceConfigurations(model, srdf_filename, verbose=False):
    """``model.referenceConfigurations[name]`` for each ``<group_state>`` of an SRDF file: the
    neutral configuration with the state's joints set (joints the model lacks are skipped; a
    free-flyer's or ball joint's quaternion as the file gives it, x y z w; a joint given the wrong
    number of values is skipped with a warning)."""
    from .algorithms import neutral

    srdf = _r.read_srdf(os.fspath(srdf_filename))
    refs = model.referenceConfigurations
    for state in srdf["group_states"]:
        q = neutral(model)
        for name, values in state["joints"]:
            if not model.existJointName(name):
                continue
            j = model.joints[model.getJointId(name)]
            if len(values) == 1 and j.nq == 2:  # a continuous joint: (cos θ, sin θ)
                values = [np.cos(values[0]), np.sin(values[0])]
            if len(values) != j.nq:
                warnings.warn(f"{srdf_filename}: group_state {state['name']}: joint {name} has "
                              f"{j.nq} coordinates, the file gives {len(values)}: skipped")
                continue
            q[j.idx_q:j.idx_q + j.nq] = values
        refs.setdefault(state["name"], q)  # the first of two states of one name, as Pinocchio
