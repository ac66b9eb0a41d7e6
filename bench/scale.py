"""The numbers of docs/scaling.md (issue 27's bars), measured on this machine:

1. threads=: rnea_batch on TALOS (free-flyer) with threads=1 and threads=all, wall time and
   CPU time / wall time (the cores in use).
2. Dask: RNEA for N random TALOS states (default 10^6) on a distributed.LocalCluster of two worker
   processes with one thread each, the states generated on the workers chunk by chunk, against
   the same states through one local rnea_batch: equal bit for bit, both throughputs.
3. Monte-Carlo: τ for K parameter vectors (default 10^4) x S states (10^3) of the Panda through
   regressor_batch and one matrix product, against K models (Model.with_dynamic_parameters)
   evaluated one by one with rnea_batch: the largest difference and both times.

    python bench/scale.py [--states 1000000] [--params 10000] [--skip-dask]
"""

import argparse
import os
import time
import warnings

import numpy as np

import rigid

import glob
import site
import sys

ERD = next(h for root in [sys.prefix] + site.getsitepackages() for h in glob.glob(
    os.path.join(root, "cmeel.prefix/share/example-robot-data/robots")))


def load(rel, floating):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return rigid.Model.from_urdf(os.path.join(ERD, rel), floating=floating)


TALOS = "talos_data/robots/talos_reduced.urdf"
PANDA = "panda_description/urdf/panda.urdf"


def talos_states(nq, nv, n, seed):
    """n random states of a free-flyer whose other joints are 1-dof (TALOS): deterministic in
    seed, made by numpy alone (so that a worker makes the same rows as this process)."""
    rng = np.random.default_rng(seed)
    quat = rng.normal(size=(n, 4))
    quat /= np.linalg.norm(quat, axis=1, keepdims=True)
    Q = np.hstack([rng.uniform(-1, 1, (n, 3)), quat, rng.uniform(-1.5, 1.5, (n, nq - 7))])
    return Q, rng.uniform(-1, 1, (n, nv)), rng.uniform(-1, 1, (n, nv))


def timed(f, *args, **kw):
    c0, w0 = time.process_time(), time.perf_counter()
    out = f(*args, **kw)
    return out, time.perf_counter() - w0, time.process_time() - c0


def bench_threads(model):
    Q, V, A = talos_states(model.nq, model.nv, 100_000, 1)
    print(f"## threads= (TALOS, nv = {model.nv}, 100000 states)")
    ref = None
    for t in (1, None):
        rigid.rnea_batch(model, Q[:100], V[:100], A[:100], threads=t)  # pool made
        out, wall, cpu = timed(rigid.rnea_batch, model, Q, V, A, threads=t)
        ref = out if ref is None else ref
        assert out.tobytes() == ref.tobytes()
        print(f"threads={t}: {wall * 1e3:8.1f} ms, {len(Q) / wall:10.0f} states/s, "
              f"CPU/wall = {cpu / wall:.2f} cores")


def bench_dask(model, n, chunk):
    import dask.array as da
    import distributed

    import rigid.dask as rd

    nq, nv = model.nq, model.nv
    nchunks = (n + chunk - 1) // chunk
    sizes = tuple(min(chunk, n - k * chunk) for k in range(nchunks))
    print(f"## Dask (TALOS, {n} states, {nchunks} chunks of {chunk}, LocalCluster 2 workers x 1 "
          "thread)")

    def part(which, width):
        def gen(block_info=None):
            k = block_info[None]["chunk-location"][0]
            return talos_states(nq, nv, sizes[k], 1000 + k)[which]
        return da.map_blocks(gen, dtype=np.float64, chunks=(sizes, (width,)),
                             meta=np.empty((0, 0)))

    Q, V, A = part(0, nq), part(1, nv), part(2, nv)
    # the same states here, and the local batch on every core of this process
    parts = [talos_states(nq, nv, s, 1000 + k) for k, s in enumerate(sizes)]
    Ql, Vl, Al = (np.concatenate([p[i] for p in parts]) for i in range(3))
    del parts
    local, t_local, _ = timed(rigid.rnea_batch, model, Ql, Vl, Al)
    t0 = time.perf_counter()
    t_gen = timed(lambda: [talos_states(nq, nv, s, 1000 + k) for k, s in enumerate(sizes)])[1]
    del Ql, Vl, Al
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=40)
    client = distributed.Client(cluster)
    try:
        tau = rd.rnea(model, Q, V, A, threads=1)
        tau.sum().compute()  # warm: workers import rigid, receive the model
        gen_only, t_gen_dask, _ = timed(lambda: (Q.sum() + V.sum() + A.sum()).compute())
        out, t_dask, _ = timed(tau.compute)
        same = out.tobytes() == local.tobytes()
        print(f"local rnea_batch (all cores)    : {t_local:7.2f} s, {n / t_local:10.0f} "
              "states/s (inputs made beforehand)")
        print(f"dask, states made on the workers: {t_dask:7.2f} s, {n / t_dask:10.0f} "
              f"states/s (of which making the states: {t_gen_dask:.2f} s on the cluster, "
              f"{t_gen:.2f} s in one process)")
        print(f"dask result equals the local batch bit for bit: {same}")
        assert same
    finally:
        client.close()
        cluster.close()
    del t0


def bench_monte_carlo(model, k, s):
    print(f"## Monte-Carlo (Panda, nv = {model.nv}, {k} parameter vectors x {s} states)")
    rigid.seed(3)
    rng = np.random.default_rng(3)
    Q = np.array([rigid.random_configuration(model) for _ in range(s)])
    V, A = rng.uniform(-1, 1, (s, model.nv)), rng.uniform(-1, 1, (s, model.nv))
    pi = rigid.dynamic_parameters(model)
    nb = model.njoints
    # masses scaled by 0.8..1.2 and first moments with them: the same bodies, heavier or lighter
    scale = np.repeat(rng.uniform(0.8, 1.2, (k, nb)), 10, axis=1)
    P = pi[None, :] * scale
    t0 = time.perf_counter()
    Y = rigid.regressor_batch(model, Q, V, A).reshape(s * model.nv, 10 * nb)
    t_y = time.perf_counter() - t0
    t0 = time.perf_counter()
    block = 1000
    worst = 0.0
    taus = []
    for b in range(0, k, block):
        taus.append(Y @ P[b:b + block].T)  # (s nv, block)
    t_mm = time.perf_counter() - t0
    t0 = time.perf_counter()
    for j in range(k):
        m = model.with_dynamic_parameters(P[j])
        tau = rigid.rnea_batch(m, Q, V, A).reshape(-1)
        ref = taus[j // block][:, j % block]
        worst = max(worst, np.max(np.abs(tau - ref)) / max(1.0, np.max(np.abs(tau))))
    t_one = time.perf_counter() - t0
    print(f"regressor_batch: {t_y * 1e3:.1f} ms; matrix products: {t_mm:.2f} s; "
          f"together {t_y + t_mm:.2f} s")
    print(f"{k} models one by one (with_dynamic_parameters + rnea_batch): {t_one:.2f} s")
    print(f"largest difference: {worst:.2e} (relative to max(1, |tau|))")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--states", type=int, default=1_000_000)
    ap.add_argument("--chunk", type=int, default=50_000)
    ap.add_argument("--params", type=int, default=10_000)
    ap.add_argument("--mc-states", type=int, default=1000)
    ap.add_argument("--skip-dask", action="store_true")
    args = ap.parse_args()
    print(f"cores: {os.cpu_count()}; rigid {rigid.__version__}")
    talos = load(TALOS, True)
    bench_threads(talos)
    bench_monte_carlo(load(PANDA, False), args.params, args.mc_states)
    if not args.skip_dask:
        bench_dask(talos, args.states, args.chunk)


if __name__ == "__main__":
    main()
