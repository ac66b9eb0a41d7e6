"""Scaling out (issue 27), without Dask or Ray: pickled models compute the same numbers bit for
bit (URDF, MJCF, floating, every example-robot-data model, in a spawned process too); the batch
verbs' threads= is honoured and read-only inputs are accepted; regressor_batch,
Model.with_dynamic_parameters and simulate_batch over a list of models."""

import glob
import multiprocessing
import os
import pickle
import sys
import time
import warnings

import numpy as np
import pytest

import rigid

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
MJCF = os.path.join(ROOT, "crates", "rigid", "tests", "mujoco", "models")
LOCAL = os.path.join(ROOT, "crates", "rigid", "tests", "pinocchio")


def erd_dir():
    """The robots/ folder of example-robot-data (pip's cmeel prefix), or None."""
    import site

    env = os.environ.get("EXAMPLE_ROBOT_DATA_MODEL_DIR")
    if env:
        return env
    for root in [sys.prefix] + site.getsitepackages():
        for pattern in ("cmeel.prefix/share/example-robot-data/robots",
                        "share/example-robot-data/robots"):
            hits = glob.glob(os.path.join(root, pattern))
            if hits:
                return hits[0]
    return None


def erd(rel):
    d = erd_dir()
    if d is None:
        pytest.skip("example-robot-data is not installed")
    return os.path.join(d, rel)


def quiet(f, *args, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return f(*args, **kw)


def states(m, n, seed):
    rigid.seed(seed)
    rng = np.random.default_rng(seed)
    Q = np.array([rigid.random_configuration(m) for _ in range(n)]).reshape(n, m.nq)
    return Q, rng.uniform(-1, 1, (n, m.nv)), rng.uniform(-1, 1, (n, m.nv))


def _try(f):
    """f()'s value, or its error's message (a model whose M is singular refuses aba)."""
    try:
        return f()
    except ValueError as e:
        return np.frombuffer(str(e).encode(), dtype=np.uint8)


def outputs(m, n=5, seed=1):
    """Every batch verb and a few single verbs on fixed random states."""
    Q, V, A = states(m, n, seed)
    d = m.create_data()
    out = {
        "rnea": lambda: rigid.rnea_batch(m, Q, V, A),
        "aba": lambda: rigid.aba_batch(m, Q, V, A),
        "crba": lambda: rigid.crba_batch(m, Q),
        "regressor": lambda: rigid.regressor_batch(m, Q, V, A),
        "nle": lambda: np.array([rigid.nle(m, d, q, v) for q, v in zip(Q, V)]),
        "gravity": lambda: np.array([rigid.gravity(m, d, q) for q in Q]),
        "com": lambda: np.array([rigid.com(m, d, q) for q in Q]),
        "kinetic": lambda: np.array([rigid.kinetic_energy(m, d, q, v) for q, v in zip(Q, V)]),
        "potential": lambda: np.array([rigid.potential_energy(m, d, q) for q in Q]),
        "params": lambda: rigid.dynamic_parameters(m),
        "gravity_vector": lambda: m.gravity,
        "rnea_derivatives": lambda: np.array(rigid.rnea_derivatives(m, d, Q[0], V[0], A[0])),
        "aba_derivatives": lambda: np.array(rigid.aba_derivatives(m, d, Q[0], V[0], A[0])),
    }
    return {k: _try(f) for k, f in out.items()}


def assert_bit_equal(a, b, what):
    assert a.keys() == b.keys()
    for k in a:
        x, y = np.asarray(a[k]), np.asarray(b[k])
        assert x.shape == y.shape and x.tobytes() == y.tobytes(), f"{what}: {k} differs"


CASES = [
    ("urdf panda", lambda: quiet(rigid.Model.from_urdf,
                                 erd("panda_description/urdf/panda.urdf"))),
    ("urdf talos floating", lambda: quiet(
        rigid.Model.from_urdf, erd("talos_data/robots/talos_reduced.urdf"), floating=True)),
    ("urdf solo12 floating pinocchio", lambda: quiet(
        rigid.Model.from_urdf, erd("solo_description/robots/solo12.urdf"), floating=True,
        layout="pinocchio")),
    ("urdf all joints", lambda: quiet(rigid.Model.from_urdf,
                                      os.path.join(LOCAL, "all_joints.urdf"))),
    ("mjcf ant (free joint)", lambda: quiet(rigid.Model.from_mjcf,
                                            os.path.join(MJCF, "ant.xml"), layout="rigid")),
    ("mjcf ball joints", lambda: quiet(
        rigid.Model.from_mjcf, os.path.join(MJCF, "ball_joints.xml"), layout="rigid")),
    ("mjcf cheetah mujoco layout", lambda: quiet(
        rigid.Model.from_mjcf, os.path.join(MJCF, "cheetah.xml"), layout="mujoco")),
    ("builtin puma560", lambda: rigid.Model.builtin("puma560")),
]


@pytest.mark.parametrize("what,load", CASES, ids=[c[0] for c in CASES])
def test_pickle_round_trip_is_bit_exact(what, load):
    m = load()
    back = pickle.loads(pickle.dumps(m))
    assert type(back) is type(m)
    assert back.to_json() == m.to_json()
    assert (back.nq, back.nv, back.layout, back.names) == (m.nq, m.nv, m.layout, m.names)
    assert back.warnings == m.warnings
    assert_bit_equal(outputs(m), outputs(back), what)


def _child(blob, q):
    import pickle as p

    import rigid as r  # noqa: F401 (unpickling imports it anyway)

    m = p.loads(blob)
    q.put(p.dumps(outputs(m)))


def test_pickle_in_a_spawned_process_is_bit_exact():
    m = quiet(rigid.Model.from_urdf, erd("talos_data/robots/talos_reduced.urdf"), floating=True)
    ctx = multiprocessing.get_context("spawn")
    q = ctx.Queue()
    sys.path.insert(0, HERE)
    p = ctx.Process(target=_child, args=(pickle.dumps(m), q))
    p.start()
    there = pickle.loads(q.get(timeout=120))
    p.join(60)
    assert p.exitcode == 0
    assert_bit_equal(outputs(m), there, "spawned process")


def every_erd_urdf():
    d = erd_dir()
    return sorted(glob.glob(os.path.join(d, "**", "*.urdf"), recursive=True)) if d else []


def test_pickle_every_example_robot_data_model():
    """Issue 27's bar: every example-robot-data model (fixed and floating) pickles to a model
    that computes every verb's output bit for bit."""
    files = every_erd_urdf()
    if not files:
        pytest.skip("example-robot-data is not installed")
    checked = 0
    for f in files:
        for floating in (False, True):
            try:
                m = quiet(rigid.Model.from_urdf, f, floating=floating)
            except (ValueError, OSError):
                continue  # a file rigid refuses (its own tests say why)
            assert_bit_equal(outputs(m, n=2), outputs(pickle.loads(pickle.dumps(m)), n=2), f)
            checked += 1
    assert checked >= 40, f"only {checked} models loaded"


# ----------------------------------------------------------------------------------- threads=

@pytest.fixture(scope="module")
def talos():
    return quiet(rigid.Model.from_urdf, erd("talos_data/robots/talos_reduced.urdf"),
                 floating=True)


def test_threads_one_gives_the_same_numbers_bit_for_bit(talos):
    Q, V, A = states(talos, 200, 4)
    for verb, args in [(rigid.rnea_batch, (Q, V, A)), (rigid.aba_batch, (Q, V, A)),
                       (rigid.crba_batch, (Q,)), (rigid.regressor_batch, (Q, V, A))]:
        ref = verb(talos, *args)
        for t in (1, 2, 3):
            assert verb(talos, *args, threads=t).tobytes() == ref.tobytes(), (verb, t)


def test_threads_is_honoured_exactly():
    # inside the pool: rayon's count and the distinct threads that ran 64 sleeping tasks
    assert rigid._pool_threads(1) == (1, 1)
    assert rigid._pool_threads(3) == (3, 3)
    assert rigid._pool_threads(2) == (2, 2)
    # the default: rayon's global pool, one thread per available core (cgroup- and
    # affinity-aware, so it may be below os.cpu_count())
    assert 1 <= rigid._pool_threads(None)[0] <= os.cpu_count()


def test_threads_one_uses_one_core_measured(talos):
    """CPU time over wall time of a long rnea_batch with threads=1 is about 1 (one core busy)."""
    Q, V, A = states(talos, 20000, 5)
    rigid.rnea_batch(talos, Q, V, A, threads=1)  # the pool made, warm
    c0, w0 = time.process_time(), time.perf_counter()
    rigid.rnea_batch(talos, Q, V, A, threads=1)
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    assert cpu / wall < 1.25, f"threads=1 used {cpu / wall:.2f} cores"


@pytest.mark.parametrize("bad", [0, -1, -8, 100000])
def test_threads_out_of_range_is_a_value_error(talos, bad):
    Q, V, A = states(talos, 2, 1)
    for call in (lambda: rigid.rnea_batch(talos, Q, V, A, threads=bad),
                 lambda: rigid.crba_batch(talos, Q, threads=bad),
                 lambda: rigid.regressor_batch(talos, Q, V, A, threads=bad),
                 lambda: rigid.simulate_batch(talos, threads=bad, duration=0.01)):
        with pytest.raises(ValueError, match="threads must be a number of threads from 1"):
            call()


def test_read_only_arrays_are_accepted(talos):
    Q, V, A = states(talos, 10, 2)
    ref = [rigid.rnea_batch(talos, Q, V, A), rigid.crba_batch(talos, Q),
           rigid.regressor_batch(talos, Q, V, A), rigid.aba_batch(talos, Q, V, A)]
    for x in (Q, V, A):
        x.flags.writeable = False
    got = [rigid.rnea_batch(talos, Q, V, A), rigid.crba_batch(talos, Q),
           rigid.regressor_batch(talos, Q, V, A), rigid.aba_batch(talos, Q, V, A)]
    for r, g in zip(ref, got):
        assert r.tobytes() == g.tobytes()
    # a read-only view from a buffer, as Ray's object store hands out
    buf = bytes(Q.tobytes())
    Qro = np.frombuffer(buf, dtype=np.float64).reshape(Q.shape)
    assert not Qro.flags.writeable
    assert rigid.rnea_batch(talos, Qro, V, A).tobytes() == ref[0].tobytes()
    # unaligned (what dask's workers may unpickle): copied, the same numbers
    Qun = np.frombuffer(b"\0" + Q.tobytes(), dtype=np.float64, offset=1).reshape(Q.shape)
    assert not Qun.flags.aligned
    assert rigid.rnea_batch(talos, Qun, V, A).tobytes() == ref[0].tobytes()
    assert rigid.crba_batch(talos, Qun).tobytes() == ref[1].tobytes()


def test_plain_batch_verbs_refuse_a_dask_array_by_duck_typing(talos):
    class FakeDask:  # anything with __dask_graph__; no dask needed
        def __dask_graph__(self):
            return {}

    Q, V, A = states(talos, 2, 1)
    with pytest.raises(TypeError, match=r"rnea_batch: Q is a dask array.*rigid\.dask\.rnea"):
        rigid.rnea_batch(talos, FakeDask(), V, A)
    with pytest.raises(TypeError, match=r"TAU is a dask array.*rigid\.dask\.aba"):
        rigid.aba_batch(talos, Q, V, FakeDask())
    with pytest.raises(TypeError, match=r"rigid\.dask\.crba"):
        rigid.crba_batch(talos, FakeDask())
    with pytest.raises(TypeError, match=r"rigid\.dask\.regressor"):
        rigid.regressor_batch(talos, Q, FakeDask(), A)


# ---------------------------------------------------------------- batches over parameters

@pytest.mark.parametrize("rel,floating,layout", [
    ("panda_description/urdf/panda.urdf", False, "rigid"),
    ("talos_data/robots/talos_reduced.urdf", True, "rigid"),
    ("solo_description/robots/solo12.urdf", True, "pinocchio"),
])
def test_regressor_batch_times_parameters_is_rnea(rel, floating, layout):
    m = quiet(rigid.Model.from_urdf, erd(rel), floating=floating, layout=layout)
    Q, V, A = states(m, 50, 7)
    Y = rigid.regressor_batch(m, Q, V, A)
    assert Y.shape == (50, m.nv, 10 * m.njoints)
    pi = rigid.dynamic_parameters(m)
    tau = rigid.rnea_batch(m, Q, V, A)
    assert np.max(np.abs(Y @ pi - tau)) <= 1e-10 * max(1.0, np.max(np.abs(tau)))
    # each block is the single regressor, bit for bit
    d = m.create_data()
    for k in (0, 17, 49):
        assert Y[k].tobytes() == np.asarray(rigid.regressor(m, d, Q[k], V[k], A[k])).tobytes()
    # zero rows
    assert rigid.regressor_batch(m, Q[:0], V[:0], A[:0]).shape == (0, m.nv, 10 * m.njoints)


def test_with_dynamic_parameters_round_trips_and_validates():
    m = quiet(rigid.Model.from_urdf, erd("panda_description/urdf/panda.urdf"))
    pi = rigid.dynamic_parameters(m)
    same = m.with_dynamic_parameters(pi)
    assert np.max(np.abs(rigid.dynamic_parameters(same) - pi)) <= 1e-15 * np.max(np.abs(pi))
    Q, V, A = states(m, 20, 3)
    assert np.allclose(rigid.rnea_batch(same, Q, V, A), rigid.rnea_batch(m, Q, V, A),
                       rtol=0, atol=1e-12)
    heavier = pi.copy()
    heavier[10 * 3] *= 2.0  # mass of the fourth body, same first moment and inertia
    h = m.with_dynamic_parameters(heavier)
    assert rigid.dynamic_parameters(h)[30] == 2.0 * pi[30]
    assert h.nq == m.nq and h.names == m.names and h.layout == m.layout
    bad = pi.copy()
    bad[10 * 2] = -1.0
    with pytest.raises(ValueError, match=r"body 2 \(moved by joint '" + m.names[2] + "'\\): mass"):
        m.with_dynamic_parameters(bad)
    assert rigid.dynamic_parameters(m.with_dynamic_parameters(bad, check=False))[20] == -1.0
    bad = pi.copy()
    bad[10 * 5 + 4] = -5.0  # Ixx < 0
    with pytest.raises(ValueError, match=r"body 5 .*(positive semi-definite|triangle)"):
        m.with_dynamic_parameters(bad)
    with pytest.raises(ValueError, match="pi has 3 entries"):
        m.with_dynamic_parameters([1.0, 2.0, 3.0])
    bad = pi.copy()
    bad[7] = np.nan
    with pytest.raises(ValueError, match="body 0 .*not finite"):
        m.with_dynamic_parameters(bad)


def test_simulate_batch_over_models_equals_separate_simulate_calls():
    m = quiet(rigid.Model.from_urdf, erd("ur_description/urdf/ur5_robot.urdf"))
    pi = rigid.dynamic_parameters(m)
    rng = np.random.default_rng(0)
    models = []
    for _ in range(5):
        p = pi.copy()
        p *= np.repeat(rng.uniform(0.8, 1.2, m.njoints), 10)  # each body scaled
        models.append(m.with_dynamic_parameters(p))
    q0 = np.full(m.nq, 0.2)
    opts = dict(duration=0.2, dt=1e-3, controller="gravity", every=10)
    out = rigid.simulate_batch(models, q0, **opts)
    T = len(out["t"])
    assert out["q"].shape == (5, T, m.nq) and out["energy"].shape == (5, T)
    for i, mi in enumerate(models):
        one = rigid.simulate(mi, q0, **opts)
        assert one["t"].tobytes() == out["t"].tobytes()
        for k in ("q", "v", "tau", "energy"):
            assert one[k].tobytes() == out[k][i].tobytes(), (i, k)
    # one model, many initial states; and threads=1 the same
    Q0 = np.array([q0, q0 + 0.1, q0 - 0.1])
    many = rigid.simulate_batch(m, Q0, **opts)
    assert many["q"].shape[0] == 3
    assert many["q"][1].tobytes() == rigid.simulate(m, Q0[1], **opts)["q"].tobytes()
    assert rigid.simulate_batch(m, Q0, threads=1, **opts)["q"].tobytes() == many["q"].tobytes()


def test_simulate_batch_releases_the_gil():
    import threading

    m = rigid.Model.builtin("puma560")
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    t0 = time.perf_counter()
    rigid.simulate_batch([m] * 4, duration=0.5, dt=1e-4, threads=1)
    elapsed = time.perf_counter() - t0
    done.set()
    t.join()
    assert elapsed > 0.05 and len(ticks) > 0.3 * elapsed / 0.002


def test_simulate_batch_errors():
    m = rigid.Model.builtin("puma560")
    with pytest.raises(TypeError, match=r"models\[1\] is not a rigid.Model"):
        rigid.simulate_batch([m, 3])
    with pytest.raises(ValueError, match="empty list"):
        rigid.simulate_batch([])
    with pytest.raises(ValueError, match=r"models\[1\] has nq"):
        rigid.simulate_batch([m, rigid.Model.builtin("pendulum")])
    with pytest.raises(ValueError, match="q0 has 2 rows for 3 rollouts"):
        rigid.simulate_batch([m] * 3, np.zeros((2, m.nq)))
