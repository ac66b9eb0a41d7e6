"""``pinocchio.utils``: small numpy helpers of Pinocchio's scripts."""

import numpy as np

from .explog import SE3ToXYZQUAT, XYZQUATToSE3, rpy
from .spatial import skew

__all__ = ["zero", "rand", "eye", "skew", "cross", "isapprox", "npToTuple", "npToTTuple",
           "mprint", "rotate", "rpyToMatrix", "matrixToRpy", "fromListToVectorOfString",
           "se3ToXYZQUAT", "XYZQUATToSe3"]


def zero(n):
    """Zeros: ``n`` numbers, or an ``(r, c)`` array for ``n = (r, c)``."""
    return np.zeros(n)


def rand(n):
    """Uniform numbers in [0, 1): ``n`` of them, or an ``(r, c)`` array."""
    return np.random.rand(n) if isinstance(n, int) else np.random.rand(*n)


def eye(n):
    return np.eye(n)


def cross(a, b):
    return np.cross(np.asarray(a).reshape(3), np.asarray(b).reshape(3))


def isapprox(a, b, epsilon=1e-6):
    a = getattr(a, "np", a)
    b = getattr(b, "np", b)
    if isinstance(a, (np.ndarray, list)) and isinstance(b, (np.ndarray, list)):
        return bool(np.allclose(np.squeeze(np.array(a)), np.squeeze(np.array(b)), epsilon))
    return abs(a - b) < epsilon


def npToTTuple(M):
    return tuple(tuple(r) for r in np.asarray(M).tolist())


def npToTuple(M):
    M = np.asarray(M)
    if M.ndim == 1 or 1 in M.shape:
        return tuple(M.reshape(-1).tolist())
    return npToTTuple(M)


def mprint(M, name="ans", eps=1e-15):
    """Prints ``M`` (an array or an SE3) with its name."""
    M = getattr(M, "homogeneous", M)
    M = np.atleast_2d(np.asarray(M, dtype=float))
    M = np.where(np.abs(M) < eps, 0.0, M)
    print(f"{name} = ")
    print(np.array2string(M, precision=5, suppress_small=True))


def fromListToVectorOfString(items):
    return list(items)


rotate = rpy.rotate
rpyToMatrix = rpy.rpyToMatrix
matrixToRpy = rpy.matrixToRpy
se3ToXYZQUAT = SE3ToXYZQUAT
XYZQUATToSe3 = XYZQUATToSE3
