"""The shapes of hpp-fcl (``import hppfcl``) and coal (``import coal``) that Pinocchio's scripts
build geometry objects from, for ``python -m rigid.pinocchio``: each holds its dimensions under
hpp-fcl's names and becomes a ``rigid.Collider`` (parry, on rigid's collision layer) when a
collision or a distance is asked. A mesh (``BVHModelOBBRSS``, ``MeshLoader().load``) collides as
its convex hull (hpp-fcl: its triangles)."""

import os

import numpy as np

from .. import rigid as _r

__all__ = ["ShapeBase", "CollisionGeometry", "Sphere", "Box", "Cylinder", "Capsule", "Cone",
           "Ellipsoid", "BVHModelOBBRSS", "BVHModelBase", "MeshLoader", "CachedMeshLoader"]


class CollisionGeometry:
    """A shape: ``collider()`` is its ``rigid.Collider`` and the pose of rigid's shape frame in
    hpp-fcl's (None: the same)."""

    _kind = None

    def _size(self):
        raise NotImplementedError

    def collider(self):
        """The ``rigid.Collider`` of the current dimensions (made again when they changed)."""
        size = tuple(float(x) for x in self._size())
        made = getattr(self, "_made", None)
        if made is None or made[0] != size:
            self._made = (size, _r.Collider(self._kind, list(size)), self._offset())
        return self._made[1:]

    def _offset(self):
        return None

    def __repr__(self):
        return f"{type(self).__name__}({', '.join(f'{x:g}' for x in self._size())})"


ShapeBase = CollisionGeometry


class Sphere(CollisionGeometry):
    _kind = "sphere"

    def __init__(self, radius):
        self.radius = float(radius)

    def _size(self):
        return [self.radius]


class Box(CollisionGeometry):
    """``Box(x, y, z)`` (edge lengths) or ``Box(np.array([x, y, z]))``; ``halfSide``."""

    _kind = "box"

    def __init__(self, x, y=None, z=None):
        side = np.asarray(x, dtype=float) if y is None else np.array([x, y, z], dtype=float)
        self.halfSide = 0.5 * side

    def _size(self):
        return list(2.0 * self.halfSide)


class _Axial(CollisionGeometry):
    def __init__(self, radius, lz):
        self.radius = float(radius)
        self.halfLength = 0.5 * float(lz)

    def _size(self):
        return [self.radius, 2.0 * self.halfLength]


class Cylinder(_Axial):
    """Along z, centred: ``Cylinder(radius, length)``."""

    _kind = "cylinder"


class Capsule(_Axial):
    """Along z, centred: ``Capsule(radius, length of the cylindrical part)``."""

    _kind = "capsule"


class Cone(_Axial):
    """Along z, centred on its axis' middle (hpp-fcl): base at ``-halfLength``, apex at
    ``+halfLength``; rigid's cone has its origin at the centroid, a quarter of the height above
    the base."""

    _kind = "cone"

    def _offset(self):
        T = np.eye(4)
        T[2, 3] = -0.5 * self.halfLength
        return T


class Ellipsoid(CollisionGeometry):
    """Collides as the convex hull of 162 points of its surface (rigid's ellipsoid), so its
    distances are not exact (one of 0.15956 m measured 0.16025 m)."""

    _kind = "ellipsoid"

    def __init__(self, rx, ry=None, rz=None):
        self.radii = (np.asarray(rx, dtype=float) if ry is None
                      else np.array([rx, ry, rz], dtype=float))

    def _size(self):
        return list(self.radii)


class BVHModelOBBRSS(CollisionGeometry):
    """A mesh read from a file (``MeshLoader().load(path, scale)``, Pinocchio's URDF loader):
    its vertices are read when it first collides."""

    _kind = "mesh"

    def __init__(self, path=None, scale=None):
        self.path = None if path is None else os.fspath(path)
        self.scale = np.ones(3) if scale is None else np.asarray(scale, dtype=float)

    def collider(self):
        if getattr(self, "_made", None) is None or self._made[0] != (self.path, tuple(self.scale)):
            if self.path is None:
                raise NotImplementedError(
                    "BVHModelOBBRSS built triangle by triangle (beginModel/addTriangle): "
                    "rigid.pinocchio reads meshes from files only (MeshLoader().load(path))")
            self._made = ((self.path, tuple(self.scale)),
                          _r.Collider("mesh", path=self.path, scale=self.scale), None)
        return self._made[1:]

    def __repr__(self):
        return f"BVHModelOBBRSS({self.path!r})"


BVHModelBase = BVHModelOBBRSS


class MeshLoader:
    def load(self, path, scale=None):
        return BVHModelOBBRSS(path, scale)


CachedMeshLoader = MeshLoader
