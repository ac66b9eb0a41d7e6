"""rigid's batch verbs over dask arrays: ``rigid.dask.rnea(model, Q, V, A)`` and friends.

Each verb maps the plain batch verb (``rigid.rnea_batch`` ...) over the row chunks of its dask
arrays with ``map_blocks`` (explicit output chunks and dtype, so that dask never calls the verb
on a dummy array to guess them) and returns a dask array; nothing is computed until
``.compute()`` (or ``persist``, ``to_zarr``...). A chunk of zero rows gives zero rows.

The model is put into the graph once, as one task of its own (``dask.delayed(model,
pure=True)``, which pickles it through ``rigid.Model.__reduce__``: its JSON form, bit for bit);
every chunk task depends on that task, so a distributed scheduler ships the model to each
worker once, not once per chunk. With a ``distributed.Client`` you may also scatter it yourself
(``model = client.scatter(model, broadcast=True)``) and pass the future.

Inputs: dask arrays (or numpy arrays, wrapped with one chunk) with one state per row; ``Q`` is
``(N, nq)``, the others ``(N, nv)``; their row chunks are aligned to ``Q``'s (``rechunk``) and
they must not be chunked along the columns (rechunked to one column chunk). ``threads=`` is
passed to every chunk's batch call (``None``: every core of the worker; set it to the worker's
``threads_per_worker`` share when several worker threads run at once).

Requires dask (``pip install "dask[array]"``; ``distributed`` for a cluster). The verbs are the
same numbers as the plain batch verbs, bit for bit, for any chunking.
"""

from __future__ import annotations

import numpy as np

try:
    import dask
    import dask.array as da
except ImportError as e:  # pragma: no cover - exercised only without dask
    raise ImportError(
        "rigid.dask needs dask: pip install \"dask[array]\" (and \"dask[distributed]\" for a "
        "cluster)"
    ) from e

from . import rigid as _native

__all__ = ["rnea", "aba", "crba", "regressor", "simulate", "model_task"]


def model_task(model):
    """The model as one task of the graph (``dask.delayed(model, pure=True)``): pickled once
    into the graph and sent once to each worker that needs it. A delayed object or a
    ``distributed`` future (``client.scatter(model)``) is returned as it is."""
    if isinstance(model, _native.Model):
        return dask.delayed(model, pure=True, traverse=False)
    return model


def _rows(x, name, width, chunks=None):
    """``x`` as a dask array of shape ``(N, width)``, float64, one column chunk; rechunked to
    ``chunks`` along the rows when given."""
    if not hasattr(x, "__dask_graph__"):
        x = np.asarray(x, dtype=np.float64)
        x = da.from_array(x, chunks=(chunks if chunks is not None else max(len(x), 1), -1)
                          if x.ndim == 2 else -1)
    if x.ndim != 2 or x.shape[1] != width:
        raise ValueError(f"rigid.dask: {name} must be a 2-D array of shape (N, {width}), "
                         f"got shape {x.shape}")
    if chunks is not None and x.shape[0] != sum(chunks):
        raise ValueError(f"rigid.dask: {name} has {x.shape[0]} rows, Q has {sum(chunks)} "
                         "(one state per row)")
    if x.dtype != np.float64:
        x = x.astype(np.float64)
    want = (chunks if chunks is not None else x.chunks[0], (width,))
    if x.chunks != want:
        x = x.rechunk(want)
    return x


def _align(model, q, others):
    """Q and the velocity-space arrays with the same row chunks (Q's)."""
    q = _rows(q, "Q", model.nq)
    if any(np.isnan(c) for c in q.chunks[0]):
        raise ValueError("rigid.dask: Q has unknown chunk sizes; call Q.compute_chunk_sizes() "
                         "first")
    out = []
    for name, x in others:
        out.append(_rows(x, name, model.nv, q.chunks[0]))
    return q, out


def _qvx(verb, model, q, v, x, names, threads):
    def block(qb, vb, xb, model):
        if qb.shape[0] == 0:
            return np.empty((0, model.nv), dtype=np.float64)
        return verb(model, qb, vb, xb, threads=threads)

    q, (v, x) = _align(model, q, [(names[0], v), (names[1], x)])
    return da.map_blocks(block, q, v, x, model=model_task(model), dtype=np.float64,
                         chunks=(q.chunks[0], (model.nv,)), meta=np.empty((0, 0)))


def rnea(model, Q, V, A, *, threads=None):
    """Inverse dynamics of every row, ``(N, nv)``, as ``rigid.rnea_batch``; a dask array."""
    return _qvx(_native.rnea_batch, model, Q, V, A, ("V", "A"), threads)


def aba(model, Q, V, TAU, *, threads=None):
    """Forward dynamics of every row, ``(N, nv)``, as ``rigid.aba_batch``; a dask array."""
    return _qvx(_native.aba_batch, model, Q, V, TAU, ("V", "TAU"), threads)


def crba(model, Q, *, threads=None):
    """The mass matrix of every row, ``(N, nv, nv)``, as ``rigid.crba_batch``; a dask array."""
    nv = model.nv

    def block(qb, model):
        if qb.shape[0] == 0:
            return np.empty((0, nv, nv), dtype=np.float64)
        return _native.crba_batch(model, qb, threads=threads)

    q, _ = _align(model, Q, [])
    return da.map_blocks(block, q, model=model_task(model), dtype=np.float64,
                         chunks=(q.chunks[0], (nv,), (nv,)), new_axis=2,
                         meta=np.empty((0, 0, 0)))


def regressor(model, Q, V, A, *, threads=None):
    """The regressor of every row, ``(N, nv, 10·nbodies)``, as ``rigid.regressor_batch``
    (``τ = Y @ π``); a dask array."""
    nv, cols = model.nv, 10 * model.njoints

    def block(qb, vb, ab, model):
        if qb.shape[0] == 0:
            return np.empty((0, nv, cols), dtype=np.float64)
        return _native.regressor_batch(model, qb, vb, ab, threads=threads)

    q, (v, a) = _align(model, Q, [("V", V), ("A", A)])
    return da.map_blocks(block, q, v, a, model=model_task(model), dtype=np.float64,
                         chunks=(q.chunks[0], (nv,), (cols,)), new_axis=2,
                         meta=np.empty((0, 0, 0)))


def simulate(model, Q0, V0=None, *, duration=1.0, dt=1e-3, every=1, threads=None, **options):
    """One rollout per row of ``Q0`` (``(M, nq)``; ``V0`` ``(M, nv)`` or None for rest), as
    ``rigid.simulate_batch(model, Q0, V0, ...)`` with the built-in controllers' ``options``
    (``controller``, ``target``, ``integrator``...). Returns a dask array ``(M, T, nq)`` of the
    configurations, one row every ``every`` steps and the last (the times are
    ``rigid.simulate_batch``'s ``t``); run ``rigid.simulate_batch`` itself for ``v``, ``tau`` and
    ``energy``."""
    if not (dt > 0 and duration > 0) or every < 1:
        raise ValueError("rigid.dask.simulate: duration and dt must be positive, every >= 1")
    steps = max(int(round(duration / dt)), 1)
    count = 1 + sum(1 for k in range(1, steps + 1) if k % every == 0 or k == steps)
    nq = model.nq
    q0 = _rows(Q0, "Q0", nq)
    v0 = None if V0 is None else _rows(V0, "V0", model.nv, q0.chunks[0])

    def block(qb, *rest, model):
        if qb.shape[0] == 0:
            return np.empty((0, count, nq), dtype=np.float64)
        vb = rest[0] if rest else None
        run = _native.simulate_batch(model, qb, vb, duration=duration, dt=dt, every=every,
                                     threads=threads, **options)
        return run["q"]

    args = (q0,) if v0 is None else (q0, v0)
    return da.map_blocks(block, *args, model=model_task(model), dtype=np.float64,
                         chunks=(q0.chunks[0], (count,), (nq,)), new_axis=2,
                         meta=np.empty((0, 0, 0)))
