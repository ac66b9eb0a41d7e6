"""``exp`` and ``log`` of SO(3) and SE(3) and their Jacobians (Pinocchio's ``exp3``, ``log3``,
``exp6``, ``log6``, ``Jexp3``, ``Jlog3``, ``Jexp6``, ``Jlog6``, ``exp``, ``log``), computed by rigid
(``rigid.rigid._exp6``, ``_log6``, ...: the crate's ``Transform::exp``/``log``, ``so3::exp``/
``log`` and the right Jacobians of SO(3) and SE(3)); ``Quaternion``, ``AngleAxis``, ``rpy`` and the XYZQUAT forms.
Twists linear first, as Pinocchio's ``Motion``."""

import numpy as np

from .. import rigid as _r
from .spatial import Motion, SE3, _vec

__all__ = [
    "Quaternion", "AngleAxis", "exp", "log", "exp3", "log3", "exp6", "log6", "Jexp3", "Jlog3",
    "Jexp6", "Jlog6", "SE3ToXYZQUAT", "SE3ToXYZQUATtuple", "XYZQUATToSE3", "rpy",
]


class Quaternion:
    """A unit quaternion ``x i + y j + z k + w`` (eigenpy's ``Quaternion`` as Pinocchio exposes
    it): ``Quaternion(w, x, y, z)``, ``Quaternion(R)``, ``Quaternion(coeffs)`` with coeffs
    ``[x, y, z, w]``."""

    __slots__ = ("_q",)

    def __init__(self, *args):
        if len(args) == 4:
            w, x, y, z = (float(a) for a in args)
            q = np.array([x, y, z, w])
        elif len(args) == 1 and isinstance(args[0], Quaternion):
            q = args[0]._q.copy()
        elif len(args) == 1:
            a = np.asarray(args[0], dtype=float)
            if a.shape == (3, 3):
                q = _quaternion_of(a)
            elif a.size == 4:
                q = a.reshape(4).copy()
            else:
                raise ValueError(f"Quaternion: expected a 3 x 3 rotation or 4 coefficients, "
                                 f"got shape {a.shape}")
        elif len(args) == 0:
            q = np.array([0.0, 0.0, 0.0, 1.0])
        else:
            raise TypeError("Quaternion() takes (w, x, y, z), a rotation matrix or coeffs")
        self._q = q

    @staticmethod
    def Identity():
        return Quaternion()

    x = property(lambda s: s._q[0])
    y = property(lambda s: s._q[1])
    z = property(lambda s: s._q[2])
    w = property(lambda s: s._q[3])

    def coeffs(self):
        return self._q

    def vec(self):
        return self._q[:3]

    def norm(self):
        return float(np.linalg.norm(self._q))

    def normalize(self):
        self._q /= np.linalg.norm(self._q)
        return self

    def normalized(self):
        return Quaternion(self._q / np.linalg.norm(self._q))

    def conjugate(self):
        return Quaternion(np.array([-self.x, -self.y, -self.z, self.w]))

    def inverse(self):
        return Quaternion(self.conjugate()._q / np.dot(self._q, self._q))

    def toRotationMatrix(self):
        x, y, z, w = self._q / np.linalg.norm(self._q)
        return np.array([
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ])

    matrix = toRotationMatrix

    def __mul__(self, o):
        if isinstance(o, Quaternion):
            x1, y1, z1, w1 = self._q
            x2, y2, z2, w2 = o._q
            return Quaternion(np.array([
                w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
                w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]))
        return self.toRotationMatrix() @ np.asarray(o, dtype=float)

    def angularDistance(self, o):
        d = abs(float(np.dot(self.normalized()._q, o.normalized()._q)))
        return 2.0 * np.arccos(min(1.0, d))

    def isApprox(self, o, prec=1e-12):
        return np.allclose(self._q, o._q, rtol=0, atol=prec)

    def __reduce__(self):
        return (Quaternion, (self._q.copy(),))

    def __repr__(self):
        return f"Quaternion(x={self.x}, y={self.y}, z={self.z}, w={self.w})"


def _quaternion_of(R):
    """``[x, y, z, w]`` of a rotation matrix (Shepperd's method, ``w ≥ 0``)."""
    t = np.trace(R)
    if t > 0:
        s = 2.0 * np.sqrt(1.0 + t)
        q = [(R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s, s / 4]
    else:
        i = int(np.argmax(np.diag(R)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * np.sqrt(1.0 + R[i, i] - R[j, j] - R[k, k])
        q = [0.0, 0.0, 0.0, (R[k, j] - R[j, k]) / s]
        q[i] = s / 4
        q[j] = (R[j, i] + R[i, j]) / s
        q[k] = (R[k, i] + R[i, k]) / s
    q = np.array(q)
    return -q if q[3] < 0 else q


class AngleAxis:
    """A rotation by ``angle`` about the unit ``axis``."""

    __slots__ = ("angle", "axis")

    def __init__(self, angle, axis):
        self.angle, self.axis = float(angle), _vec(axis, 3, "AngleAxis: axis").copy()

    def toRotationMatrix(self):
        return exp3(self.angle * self.axis)

    matrix = toRotationMatrix


def _motion_vec(x, what):
    if isinstance(x, Motion):
        return x.vector
    return _vec(x, 6, what)


def exp3(w):
    """``exp([ω])`` (3 x 3)."""
    return _r._exp3(_vec(w, 3, "exp3"))


def log3(R):
    """``ω`` with ``exp([ω]) = R``, ``|ω| ≤ π``."""
    return _r._log3(np.asarray(R, dtype=float))


def exp6(v):
    """``exp`` of a twist (a ``Motion`` or 6-vector, linear first): an ``SE3``."""
    return SE3(_r._exp6(_motion_vec(v, "exp6")))


def _se3_of(M, what):
    if isinstance(M, SE3):
        return M
    H = np.asarray(M, dtype=float)
    if H.shape != (4, 4):
        raise ValueError(f"{what}: expected an SE3 or a 4 x 4 matrix, got shape {H.shape}")
    return SE3(H)


def log6(M):
    """``log`` of an ``SE3`` (or 4 x 4 matrix): a ``Motion``."""
    M = _se3_of(M, "log6")
    return Motion(_r._log6(M.rotation, M.translation))


def exp(x):
    """``exp3`` of a 3-vector, ``exp6`` of a ``Motion`` or 6-vector."""
    if isinstance(x, Motion):
        return exp6(x)
    a = np.asarray(x, dtype=float)
    if a.size == 3:
        return exp3(a)
    if a.size == 6:
        return exp6(a)
    raise ValueError(f"exp: expected 3 or 6 numbers or a Motion, got shape {a.shape}")


def log(x):
    """``log3`` of a rotation matrix, ``log6`` of an ``SE3`` or 4 x 4 matrix."""
    if isinstance(x, SE3):
        return log6(x)
    a = np.asarray(x, dtype=float)
    if a.shape == (3, 3):
        return log3(a)
    if a.shape == (4, 4):
        return log6(a)
    raise ValueError(f"log: expected a 3 x 3 rotation, an SE3 or a 4 x 4 matrix, got {a.shape}")


def Jexp3(w):
    """The right Jacobian of SO(3) at ``ω``: ``exp(ω + δ) ≈ exp(ω) exp(Jexp3(ω) δ)``."""
    return _r._jexp3(_vec(w, 3, "Jexp3"))


def Jlog3(R):
    """The derivative of ``log3`` in the body frame: ``Jexp3(log3 R)⁻¹``."""
    return _r._jlog3(np.asarray(R, dtype=float))


def Jexp6(v):
    """The right Jacobian of SE(3) at the twist ``v`` (linear first)."""
    return _r._jexp6(_motion_vec(v, "Jexp6"))


def Jlog6(M):
    """The derivative of ``log6`` in the body frame: ``Jexp6(log6 M)⁻¹`` (linear first)."""
    M = _se3_of(M, "Jlog6")
    return _r._jlog6(M.rotation, M.translation)


def SE3ToXYZQUAT(M):
    """``[x, y, z, qx, qy, qz, qw]``."""
    return np.concatenate([M.translation, _quaternion_of(M.rotation)])


def SE3ToXYZQUATtuple(M):
    return tuple(SE3ToXYZQUAT(M).tolist())


def XYZQUATToSE3(x):
    x = _vec(x, 7, "XYZQUATToSE3")
    return SE3(Quaternion(x[3:]).toRotationMatrix(), x[:3])


class _Rpy:
    """``pinocchio.rpy``: roll-pitch-yaw (``R = Rz(y) Ry(p) Rx(r)``)."""

    @staticmethod
    def rotate(axis, angle):
        a = {"x": 0, "y": 1, "z": 2}[axis]
        w = np.zeros(3)
        w[a] = angle
        return exp3(w)

    @staticmethod
    def rpyToMatrix(*args):
        r, p, y = _vec(args[0], 3, "rpyToMatrix") if len(args) == 1 else args
        return _Rpy.rotate("z", y) @ _Rpy.rotate("y", p) @ _Rpy.rotate("x", r)

    @staticmethod
    def matrixToRpy(R):
        R = np.asarray(R, dtype=float)
        p = np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0]))
        y = np.arctan2(R[1, 0], R[0, 0])
        r = np.arctan2(R[2, 1], R[2, 2])
        return np.array([r, p, y])


rpy = _Rpy()
