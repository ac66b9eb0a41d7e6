"""Pinocchio's spatial algebra on numpy arrays: ``SE3``, ``Motion``, ``Force``, ``Inertia``
(``Quaternion``, ``AngleAxis``, ``rpy`` and the maps ``exp``/``log`` of SO(3) and SE(3) with their
Jacobians are in explog.py).

Layout as Pinocchio's: a ``Motion`` is ``(v, ω)`` and a ``Force`` ``(f, τ)``, **linear first**
(rigid's own verbs are angular first); an ``Inertia`` is ``(m, c, I_c)``, the mass, the centre of
mass and the rotational inertia about it; ``SE3(R, p)`` maps ``x ↦ R x + p``. The rotation and
translation of an ``SE3``, and the linear and angular parts of a ``Motion`` or ``Force``, are
views of the object's arrays, as in Pinocchio (``M.translation[0] = 1`` changes ``M``).

Composition and the action of a transform are written out here (a few products of 3 x 3
matrices).
"""

import numpy as np

__all__ = ["SE3", "Motion", "Force", "Inertia", "skew", "unSkew", "skewSquare"]

_GEN = [np.random.default_rng()]


def _seed(s):
    """Seed the generator of the ``Random()`` constructors (``pin.seed``)."""
    _GEN[0] = np.random.default_rng(s)


def _vec(x, n, what):
    a = np.asarray(x, dtype=float)
    if a.size != n:
        raise ValueError(f"{what}: expected {n} numbers, got an array of shape {a.shape}")
    return a.reshape(n)


def skew(w):
    """``[ω]``, so that ``[ω] x = ω × x``."""
    w = _vec(w, 3, "skew")
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def unSkew(m):
    """``ω`` of ``[ω]`` (the antisymmetric part of ``m``)."""
    m = np.asarray(m, dtype=float)
    return 0.5 * np.array([m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1]])


def skewSquare(u, v):
    """``[u][v]``."""
    return skew(u) @ skew(v)


def _random_rotation():
    from .explog import Quaternion  # noqa: PLC0415  (explog.py builds on this module)

    q = _GEN[0].normal(size=4)
    return Quaternion(q / np.linalg.norm(q)).toRotationMatrix()


class SE3:
    """A rigid transform ``(R, p)``: ``x ↦ R x + p`` (Pinocchio's ``SE3``)."""

    __slots__ = ("_R", "_p")

    def __init__(self, *args):
        if len(args) == 0:
            R, p = np.eye(3), np.zeros(3)
        elif len(args) == 1:
            a = args[0]
            if isinstance(a, SE3):
                R, p = a._R.copy(), a._p.copy()
            elif isinstance(a, (int, float)) and not isinstance(a, bool):
                if a != 1:
                    raise ValueError("SE3(x): only SE3(1), the identity, is a scalar constructor")
                R, p = np.eye(3), np.zeros(3)
            else:
                H = np.asarray(a, dtype=float)
                if H.shape != (4, 4):
                    raise ValueError(f"SE3(H): H must be 4 x 4, got shape {H.shape}")
                R, p = H[:3, :3].copy(), H[:3, 3].copy()
        elif len(args) == 2:
            R, p = args
            if not isinstance(R, np.ndarray) and hasattr(R, "toRotationMatrix"):  # a Quaternion
                R = R.toRotationMatrix()
            R = np.array(R, dtype=float)
            if R.shape != (3, 3):
                raise ValueError(f"SE3(R, p): R must be 3 x 3, got shape {R.shape}")
            p = _vec(p, 3, "SE3(R, p): p").copy()
        else:
            raise TypeError("SE3() takes R and p, a 4 x 4 matrix, another SE3, or 1")
        self._R = np.ascontiguousarray(R)
        self._p = np.ascontiguousarray(p)

    @staticmethod
    def Identity():
        return SE3()

    @staticmethod
    def Random():
        return SE3(_random_rotation(), _GEN[0].uniform(-1.0, 1.0, 3))

    @staticmethod
    def Interpolate(A, B, t):
        """``A exp(t log(A⁻¹ B))``."""
        from .explog import exp6, log6  # noqa: PLC0415  (explog.py builds on this module)

        return A * exp6(t * log6(A.actInv(B)))

    @property
    def rotation(self):
        return self._R

    @rotation.setter
    def rotation(self, R):
        R = np.asarray(R, dtype=float)
        if R.shape != (3, 3):
            raise ValueError(f"SE3.rotation: expected a 3 x 3 matrix, got shape {R.shape}")
        self._R[...] = R

    @property
    def translation(self):
        return self._p

    @translation.setter
    def translation(self, p):
        self._p[...] = _vec(p, 3, "SE3.translation")

    @property
    def homogeneous(self):
        H = np.eye(4)
        H[:3, :3] = self._R
        H[:3, 3] = self._p
        return H

    np = homogeneous

    @property
    def action(self):
        """``[[R, [p] R], [0, R]]`` (linear first)."""
        A = np.zeros((6, 6))
        A[:3, :3] = A[3:, 3:] = self._R
        A[:3, 3:] = skew(self._p) @ self._R
        return A

    @property
    def actionInverse(self):
        return self.inverse().action

    @property
    def dualAction(self):
        """``[[R, 0], [[p] R, R]]``, the action on forces."""
        A = np.zeros((6, 6))
        A[:3, :3] = A[3:, 3:] = self._R
        A[3:, :3] = skew(self._p) @ self._R
        return A

    def toActionMatrix(self):
        return self.action

    def toActionMatrixInverse(self):
        return self.actionInverse

    def toDualActionMatrix(self):
        return self.dualAction

    def inverse(self):
        Rt = self._R.T
        return SE3(Rt, -(Rt @ self._p))

    def act(self, x):
        """``self * x`` for an ``SE3``, ``Motion``, ``Force``, ``Inertia`` or a point (3,) or
        points (3, n)."""
        R, p = self._R, self._p
        if isinstance(x, SE3):
            return SE3(R @ x._R, R @ x._p + p)
        if isinstance(x, Motion):
            w = R @ x.angular
            return Motion(R @ x.linear + np.cross(p, w), w)
        if isinstance(x, Force):
            f = R @ x.linear
            return Force(f, R @ x.angular + np.cross(p, f))
        if isinstance(x, Inertia):
            return Inertia(x.mass, R @ x.lever + p, R @ x.inertia @ R.T)
        a = np.asarray(x, dtype=float)
        if a.shape == (3,):
            return R @ a + p
        if a.ndim == 2 and a.shape[0] == 3:
            return R @ a + p[:, None]
        raise TypeError(f"SE3.act: cannot act on {type(x).__name__}")

    def actInv(self, x):
        """``self.inverse() * x``."""
        R, p = self._R, self._p
        if isinstance(x, SE3):
            return SE3(R.T @ x._R, R.T @ (x._p - p))
        if isinstance(x, Motion):
            w = x.angular
            return Motion(R.T @ (x.linear - np.cross(p, w)), R.T @ w)
        if isinstance(x, Force):
            f = x.linear
            return Force(R.T @ f, R.T @ (x.angular - np.cross(p, f)))
        if isinstance(x, Inertia):
            return Inertia(x.mass, R.T @ (x.lever - p), R.T @ x.inertia @ R)
        a = np.asarray(x, dtype=float)
        if a.shape == (3,):
            return R.T @ (a - p)
        if a.ndim == 2 and a.shape[0] == 3:
            return R.T @ (a - p[:, None])
        raise TypeError(f"SE3.actInv: cannot act on {type(x).__name__}")

    def __mul__(self, x):
        return self.act(x)

    def isApprox(self, other, prec=1e-12):
        return (np.allclose(self._R, other._R, rtol=0, atol=prec * max(1.0, np.abs(other._R).max()))
                and np.allclose(self._p, other._p, rtol=0,
                                atol=prec * max(1.0, np.abs(other._p).max())))

    def isIdentity(self, prec=1e-12):
        return self.isApprox(SE3(), prec)

    def setIdentity(self):
        self._R[...] = np.eye(3)
        self._p[...] = 0.0
        return self

    def setRandom(self):
        r = SE3.Random()
        self._R[...], self._p[...] = r._R, r._p
        return self

    def copy(self):
        return SE3(self)

    __copy__ = copy

    def __deepcopy__(self, memo):
        return SE3(self)

    def __eq__(self, other):
        return (isinstance(other, SE3) and np.array_equal(self._R, other._R)
                and np.array_equal(self._p, other._p))

    def __ne__(self, other):
        return not self == other

    __hash__ = None

    def __reduce__(self):
        return (SE3, (self._R.copy(), self._p.copy()))

    def __str__(self):
        rows = "\n".join(" ".join(f"{x:.6g}" for x in r) for r in self._R)
        return f"  R =\n{rows}\n  p = {' '.join(f'{x:.6g}' for x in self._p)}\n"

    def __repr__(self):
        return f"SE3({np.array2string(self.homogeneous, separator=', ')})".replace("\n", "")


class _Spatial6:
    """A 6-vector of two 3-vector halves (linear, angular)."""

    __slots__ = ("_v",)

    def __init__(self, *args):
        if len(args) == 0:
            v = np.zeros(6)
        elif len(args) == 1:
            a = args[0]
            v = a._v.copy() if isinstance(a, type(self)) else _vec(a, 6, type(self).__name__).copy()
        elif len(args) == 2:
            v = np.concatenate([_vec(args[0], 3, "linear"), _vec(args[1], 3, "angular")])
        else:
            raise TypeError(f"{type(self).__name__}() takes a 6-vector or (linear, angular)")
        self._v = np.ascontiguousarray(v, dtype=float)

    @classmethod
    def Zero(cls):
        return cls()

    @classmethod
    def Random(cls):
        return cls(_GEN[0].uniform(-1.0, 1.0, 6))

    @property
    def vector(self):
        return self._v

    @vector.setter
    def vector(self, x):
        self._v[...] = _vec(x, 6, "vector")

    np = vector

    @property
    def linear(self):
        return self._v[:3]

    @linear.setter
    def linear(self, x):
        self._v[:3] = _vec(x, 3, "linear")

    @property
    def angular(self):
        return self._v[3:]

    @angular.setter
    def angular(self, x):
        self._v[3:] = _vec(x, 3, "angular")

    def se3Action(self, M):
        return M.act(self)

    def se3ActionInverse(self, M):
        return M.actInv(self)

    def isApprox(self, other, prec=1e-12):
        return np.allclose(self._v, other._v, rtol=0, atol=prec * max(1.0, np.abs(other._v).max()))

    def isZero(self, prec=1e-12):
        return bool(np.all(np.abs(self._v) <= prec))

    def setZero(self):
        self._v[...] = 0.0
        return self

    def setRandom(self):
        self._v[...] = _GEN[0].uniform(-1.0, 1.0, 6)
        return self

    def copy(self):
        return type(self)(self._v.copy())

    __copy__ = copy

    def __deepcopy__(self, memo):
        return self.copy()

    def __reduce__(self):
        return (type(self), (self._v.copy(),))

    def __add__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return type(self)(self._v + other._v)

    def __iadd__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        self._v += other._v
        return self

    def __sub__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return type(self)(self._v - other._v)

    def __isub__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        self._v -= other._v
        return self

    def __neg__(self):
        return type(self)(-self._v)

    def __mul__(self, s):
        if isinstance(s, (int, float, np.floating, np.integer)):
            return type(self)(self._v * s)
        return NotImplemented

    __rmul__ = __mul__

    def __truediv__(self, s):
        return type(self)(self._v / s)

    def __eq__(self, other):
        return type(other) is type(self) and np.array_equal(self._v, other._v)

    def __ne__(self, other):
        return not self == other

    __hash__ = None

    def __repr__(self):
        return f"{type(self).__name__}({np.array2string(self._v, separator=', ')})"


def _fmt3(x):
    return " ".join(f"{v:.6g}" for v in x)


class Motion(_Spatial6):
    """A spatial velocity or acceleration ``(v, ω)``, linear first (Pinocchio's ``Motion``)."""

    __slots__ = ()

    def cross(self, x):
        """``self × x``: ``[ad_self] x`` for a ``Motion``, ``-[ad_self]ᵀ x`` for a ``Force``."""
        v, w = self.linear, self.angular
        if isinstance(x, Motion):
            return Motion(np.cross(w, x.linear) + np.cross(v, x.angular), np.cross(w, x.angular))
        if isinstance(x, Force):
            return Force(np.cross(w, x.linear), np.cross(w, x.angular) + np.cross(v, x.linear))
        raise TypeError(f"Motion.cross: cannot cross with {type(x).__name__}")

    def __xor__(self, x):
        return self.cross(x)

    def dot(self, f):
        return float(np.dot(self._v, f._v))

    @property
    def action(self):
        """``[[[ω], [v]], [0, [ω]]]``: ``[ad_self]`` (linear first)."""
        A = np.zeros((6, 6))
        A[:3, :3] = A[3:, 3:] = skew(self.angular)
        A[:3, 3:] = skew(self.linear)
        return A

    @property
    def dualAction(self):
        return -self.action.T

    @property
    def homogeneous(self):
        H = np.zeros((4, 4))
        H[:3, :3] = skew(self.angular)
        H[:3, 3] = self.linear
        return H

    def __str__(self):
        return f"  v = {_fmt3(self.linear)}\n  w = {_fmt3(self.angular)}\n"


class Force(_Spatial6):
    """A wrench ``(f, τ)``, linear first (Pinocchio's ``Force``)."""

    __slots__ = ()

    def dot(self, v):
        return float(np.dot(self._v, v._v))

    def __str__(self):
        return f"  f = {_fmt3(self.linear)}\ntau = {_fmt3(self.angular)}\n"


class Inertia:
    """A spatial inertia ``(m, c, I_c)``: mass, centre of mass, rotational inertia about the
    centre of mass (Pinocchio's ``Inertia``)."""

    __slots__ = ("_m", "_c", "_I")

    def __init__(self, *args):
        if len(args) == 0:
            m, c, I = 0.0, np.zeros(3), np.zeros((3, 3))
        elif len(args) == 1 and isinstance(args[0], Inertia):
            m, c, I = args[0]._m, args[0]._c.copy(), args[0]._I.copy()
        elif len(args) == 3:
            m, c, I = float(args[0]), _vec(args[1], 3, "Inertia: lever").copy(), \
                np.array(args[2], dtype=float)
            if I.shape != (3, 3):
                raise ValueError(f"Inertia: inertia must be 3 x 3, got shape {I.shape}")
        else:
            raise TypeError("Inertia() takes (mass, lever, inertia) or another Inertia")
        self._m, self._c, self._I = m, np.ascontiguousarray(c), np.ascontiguousarray(I)

    @staticmethod
    def Zero():
        return Inertia()

    @staticmethod
    def Identity():
        return Inertia(1.0, np.zeros(3), np.eye(3))

    @staticmethod
    def Random():
        g = _GEN[0]
        A = g.uniform(-1.0, 1.0, (3, 3))
        return Inertia(g.uniform(0.1, 1.0), g.uniform(-1.0, 1.0, 3), A @ A.T + 0.1 * np.eye(3))

    @staticmethod
    def FromSphere(mass, radius):
        return Inertia(mass, np.zeros(3), np.eye(3) * (0.4 * mass * radius ** 2))

    @staticmethod
    def FromEllipsoid(mass, x, y, z):
        k = mass / 5.0
        return Inertia(mass, np.zeros(3), np.diag([k * (y * y + z * z), k * (x * x + z * z),
                                                   k * (x * x + y * y)]))

    @staticmethod
    def FromCylinder(mass, radius, length):
        """A solid cylinder along z."""
        a = mass * (radius ** 2 / 4.0 + length ** 2 / 12.0)
        return Inertia(mass, np.zeros(3), np.diag([a, a, mass * radius ** 2 / 2.0]))

    @staticmethod
    def FromBox(mass, x, y, z):
        """A solid box of side lengths ``x``, ``y``, ``z``."""
        k = mass / 12.0
        return Inertia(mass, np.zeros(3), np.diag([k * (y * y + z * z), k * (x * x + z * z),
                                                   k * (x * x + y * y)]))

    @staticmethod
    def FromDynamicParameters(pi):
        """From ``[m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz]`` (inertia about the
        origin)."""
        pi = _vec(pi, 10, "FromDynamicParameters")
        m = pi[0]
        c = pi[1:4] / m if m != 0 else np.zeros(3)
        Io = np.array([[pi[4], pi[5], pi[7]], [pi[5], pi[6], pi[8]], [pi[7], pi[8], pi[9]]])
        C = skew(c)
        return Inertia(m, c, Io + m * C @ C)

    def toDynamicParameters(self):
        m, c = self._m, self._c
        C = skew(c)
        Io = self._I - m * C @ C
        return np.array([m, *(m * c), Io[0, 0], Io[0, 1], Io[1, 1], Io[0, 2], Io[1, 2],
                         Io[2, 2]])

    @property
    def mass(self):
        return self._m

    @mass.setter
    def mass(self, m):
        self._m = float(m)

    @property
    def lever(self):
        return self._c

    @lever.setter
    def lever(self, c):
        self._c[...] = _vec(c, 3, "Inertia.lever")

    @property
    def inertia(self):
        return self._I

    @inertia.setter
    def inertia(self, I):
        self._I[...] = np.asarray(I, dtype=float)

    def matrix(self):
        """The 6 x 6 spatial inertia, linear first: ``[[m 1, -m [c]], [m [c], I_c - m [c]²]]``."""
        m, C = self._m, skew(self._c)
        G = np.zeros((6, 6))
        G[:3, :3] = m * np.eye(3)
        G[:3, 3:] = -m * C
        G[3:, :3] = m * C
        G[3:, 3:] = self._I - m * C @ C
        return G

    np = property(matrix)

    def __mul__(self, v):
        """``I v``: the momentum of the body moving with ``v``."""
        if not isinstance(v, Motion):
            return NotImplemented
        f = self._m * (v.linear - np.cross(self._c, v.angular))
        return Force(f, self._I @ v.angular + np.cross(self._c, f))

    def __add__(self, other):
        """The inertia of the two bodies together."""
        m = self._m + other._m
        if m == 0:
            return Inertia()
        c = (self._m * self._c + other._m * other._c) / m
        d1, d2 = skew(self._c - c), skew(other._c - c)
        return Inertia(m, c, self._I + other._I - self._m * d1 @ d1 - other._m * d2 @ d2)

    def __iadd__(self, other):
        s = self + other
        self._m, self._c, self._I = s._m, s._c, s._I
        return self

    def vxiv(self, v):
        return v.cross(self * v)

    def ivx(self, v):
        return self.matrix() @ v.action

    def vxi(self, v):
        return v.dualAction @ self.matrix()

    def variation(self, v):
        return self.vxi(v) - self.ivx(v)

    def se3Action(self, M):
        return M.act(self)

    def se3ActionInverse(self, M):
        return M.actInv(self)

    def isApprox(self, other, prec=1e-12):
        return np.allclose(self.matrix(), other.matrix(), rtol=0,
                           atol=prec * max(1.0, np.abs(other.matrix()).max()))

    def isZero(self, prec=1e-12):
        return bool(np.all(np.abs(self.matrix()) <= prec))

    def setZero(self):
        self._m, self._c[...], self._I[...] = 0.0, 0.0, 0.0
        return self

    def setIdentity(self):
        self._m, self._c[...], self._I[...] = 1.0, 0.0, np.eye(3)
        return self

    def setRandom(self):
        r = Inertia.Random()
        self._m, self._c[...], self._I[...] = r._m, r._c, r._I
        return self

    def copy(self):
        return Inertia(self)

    __copy__ = copy

    def __deepcopy__(self, memo):
        return Inertia(self)

    def __reduce__(self):
        return (Inertia, (self._m, self._c.copy(), self._I.copy()))

    def __eq__(self, other):
        return (isinstance(other, Inertia) and self._m == other._m
                and np.array_equal(self._c, other._c) and np.array_equal(self._I, other._I))

    __hash__ = None

    def __str__(self):
        rows = "\n".join(" ".join(f"{x:.6g}" for x in r) for r in self._I)
        return f"  m = {self._m:.6g}\n  c = {_fmt3(self._c)}\n  I = \n{rows}"

    def __repr__(self):
        return (f"Inertia({self._m!r}, {np.array2string(self._c, separator=', ')}, "
                f"{np.array2string(self._I, separator=', ')})").replace("\n", "")
