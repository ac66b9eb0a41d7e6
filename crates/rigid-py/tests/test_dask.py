"""rigid.dask on a real distributed.LocalCluster (two worker processes, one thread each): every
verb equals the plain batch verb bit for bit, zero-row chunks included, and the model is shipped
once per worker. Skipped without dask[distributed]."""

import os
import warnings

import numpy as np
import pytest

da = pytest.importorskip("dask.array")
distributed = pytest.importorskip("distributed")

import rigid  # noqa: E402
import rigid.dask as rd  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None, silence_logs=40)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.fixture(scope="module")
def model():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return rigid.Model.from_urdf(
            os.path.join(ROOT, "crates", "rigid", "tests", "pinocchio", "all_joints.urdf"),
            floating=True, layout="pinocchio")


def run(client, x):
    """x computed on the cluster, bounded in time (a hung cluster fails the test)."""
    return client.compute(x).result(timeout=120)


def states(m, n, seed=0):
    rigid.seed(seed)
    rng = np.random.default_rng(seed)
    Q = np.array([rigid.random_configuration(m) for _ in range(n)])
    return Q, rng.uniform(-1, 1, (n, m.nv)), rng.uniform(-1, 1, (n, m.nv))


def test_every_verb_equals_the_plain_batch_bit_for_bit(client, model):
    Q, V, A = states(model, 1000)
    # uneven chunks, one of zero rows
    chunks = ((300, 0, 450, 250),)
    dQ = da.from_array(Q, chunks=chunks + ((model.nq,),))
    dV = da.from_array(V, chunks=(200, -1))  # other row chunks: aligned to Q's
    dA = da.from_array(A, chunks=chunks + ((model.nv,),))
    tau = rd.rnea(model, dQ, dV, dA)
    assert isinstance(tau, da.Array) and tau.chunks[0] == chunks[0]
    assert tau.shape == (1000, model.nv) and tau.dtype == np.float64
    ref = rigid.rnea_batch(model, Q, V, A)
    assert run(client, tau).tobytes() == ref.tobytes()
    assert run(client, rd.aba(model, dQ, dV, dA)).tobytes() == \
        rigid.aba_batch(model, Q, V, A).tobytes()
    M = rd.crba(model, dQ)
    assert M.shape == (1000, model.nv, model.nv)
    assert run(client, M).tobytes() == rigid.crba_batch(model, Q).tobytes()
    Y = rd.regressor(model, dQ, dV, dA, threads=1)
    assert Y.shape == (1000, model.nv, 10 * model.njoints)
    assert run(client, Y).tobytes() == rigid.regressor_batch(model, Q, V, A).tobytes()


def test_simulate_equals_simulate_batch(client):
    m = rigid.Model.builtin("puma560")
    Q0 = np.random.default_rng(1).uniform(-0.5, 0.5, (6, m.nq))
    opts = dict(duration=0.05, dt=1e-3, every=5, controller="gravity")
    q = rd.simulate(m, da.from_array(Q0, chunks=(4, -1)), **opts)
    ref = rigid.simulate_batch(m, Q0, **opts)["q"]
    assert q.shape == ref.shape
    assert run(client, q).tobytes() == ref.tobytes()


def test_model_is_in_the_graph_once(client, model):
    """40 chunks, one copy of the model in the pickled graph (its own task, on which every chunk
    task depends): the scheduler ships it once to each worker that runs a chunk."""
    import cloudpickle  # how distributed pickles a graph

    Q, V, A = states(model, 400)
    dQ = da.from_array(Q, chunks=(10, -1))  # 40 chunks
    tau = rd.rnea(model, dQ, V, A)
    blob = cloudpickle.dumps(dict(tau.__dask_graph__()))
    marker = model.to_json()[:300].encode()
    assert blob.count(marker) == 1
    assert run(client, tau).tobytes() == rigid.rnea_batch(model, Q, V, A).tobytes()


def test_numpy_inputs_and_errors(client, model):
    Q, V, A = states(model, 7)
    assert run(client, rd.rnea(model, Q, V, A)).tobytes() == \
        rigid.rnea_batch(model, Q, V, A).tobytes()
    with pytest.raises(ValueError, match="V has 6 rows, Q has 7"):
        rd.rnea(model, da.from_array(Q), da.from_array(V[:6]), A)
    with pytest.raises(ValueError, match=r"Q must be a 2-D array of shape \(N, %d\)" % model.nq):
        rd.crba(model, da.zeros((3, model.nq + 1)))
    # the plain verbs refuse a dask array, pointing here
    with pytest.raises(TypeError, match=r"rigid\.dask\.rnea"):
        rigid.rnea_batch(model, da.from_array(Q), V, A)


def test_zero_rows(client, model):
    Q, V, A = states(model, 0)
    Q = Q.reshape(0, model.nq)
    tau = rd.rnea(model, da.from_array(Q, chunks=(1, -1)), V, A)
    assert run(client, tau).shape == (0, model.nv)
