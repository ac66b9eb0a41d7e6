"""Pinocchio's parallel algorithms on rigid's batches: ``ModelPool`` and ``rneaInParallel``,
``abaInParallel`` over the columns of ``(nq, batch)`` arrays, run by ``rigid.rnea_batch`` and
``rigid.aba_batch`` (SIMD lanes on ``num_threads`` threads; each column bit for bit the single
call's)."""

import os

import numpy as np

from .. import rigid as _r

__all__ = ["ModelPool", "omp_get_max_threads", "rneaInParallel", "abaInParallel"]


def omp_get_max_threads():
    """The threads a parallel call may use: ``OMP_NUM_THREADS`` if set, else the cores."""
    n = os.environ.get("OMP_NUM_THREADS", "")
    return int(n) if n.isdigit() and int(n) > 0 else (os.cpu_count() or 1)


class ModelPool:
    """Copies of one model and their data, one per thread (Pinocchio's pool; rigid's batches
    share the one model)."""

    def __init__(self, model, size=None):
        self._size = omp_get_max_threads() if size is None else int(size)
        self.update(model)

    def update(self, model):
        self._model = model
        self._models = [model] * self._size
        self._datas = [model.createData() for _ in range(self._size)]

    def size(self):
        return self._size

    def resize(self, n):
        self._size = int(n)
        self.update(self._model)

    def getModel(self, i=0):
        return self._models[i]

    def getModels(self):
        return list(self._models)

    def getData(self, i=0):
        return self._datas[i]

    def getDatas(self):
        return list(self._datas)


def _columns(name, x, rows, batch=None):
    x = np.asarray(x, dtype=float)
    if x.ndim != 2 or x.shape[0] != rows or (batch is not None and x.shape[1] != batch):
        want = f"({rows}, {'batch' if batch is None else batch})"
        raise ValueError(f"{name} must be an array of shape {want}, got {x.shape}")
    return np.ascontiguousarray(x.T)


def _in_parallel(verb, num_threads, pool, q, v, x, res):
    if pool.size() < num_threads:
        raise ValueError("The pool is too small")  # Pinocchio's check, and its message
    model = pool.getModel()
    Q = _columns("q", q, model.nq)
    n = Q.shape[0]
    out = verb(model, Q, _columns("v", v, model.nv, n), _columns("x", x, model.nv, n),
               threads=max(1, int(num_threads)))
    if res is None:
        return np.ascontiguousarray(out.T)
    if res.shape != (model.nv, n):
        raise ValueError(f"res must be an array of shape ({model.nv}, {n}), got {res.shape}")
    res[:] = out.T
    return None


def rneaInParallel(num_threads, pool, q, v, a, res=None):
    """``res[:, k] = rnea(model, data, q[:, k], v[:, k], a[:, k])`` for every column; returns
    the ``(nv, batch)`` array when ``res`` is not given."""
    return _in_parallel(_r.rnea_batch, num_threads, pool, q, v, a, res)


def abaInParallel(num_threads, pool, q, v, tau, res=None):
    """``res[:, k] = aba(model, data, q[:, k], v[:, k], tau[:, k])`` for every column; returns
    the ``(nv, batch)`` array when ``res`` is not given."""
    return _in_parallel(_r.aba_batch, num_threads, pool, q, v, tau, res)
