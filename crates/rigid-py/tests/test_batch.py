"""The batch verbs: each row is the single call's result, bit for bit (the batch computes several
states side by side in SIMD lanes, in the single call's order of operations), in both layouts;
the GIL is released while they run; shapes are checked."""

import threading
import time

import numpy as np
import pytest

pin = pytest.importorskip("pinocchio")

import rigid
from conftest import assert_close, pair


def states(m, n, seed):
    rigid.seed(seed)
    rng = np.random.default_rng(seed)
    Q = np.array([rigid.random_configuration(m) for _ in range(n)])
    return Q, rng.uniform(-1, 1, (n, m.nv)), rng.uniform(-1, 1, (n, m.nv))


@pytest.mark.parametrize("name", ["ur5", "anymal", "all_joints_floating"])
@pytest.mark.parametrize("layout", ["rigid", "pinocchio"])
def test_batch_rows_equal_single_calls(name, layout):
    p = pair(name)
    m = p.rp if layout == "pinocchio" else p.rr
    d = m.create_data()
    Q, V, A = states(m, 57, 3)
    tau = rigid.rnea_batch(m, Q, V, A)
    ddq = rigid.aba_batch(m, Q, V, tau)
    M = rigid.crba_batch(m, Q)
    assert tau.shape == (57, m.nv) and ddq.shape == (57, m.nv) and M.shape == (57, m.nv, m.nv)
    for k in range(len(Q)):
        assert np.array_equal(tau[k], rigid.rnea(m, d, Q[k], V[k], A[k])), ("rnea_batch", k)
        assert np.array_equal(ddq[k], rigid.aba(m, d, Q[k], V[k], tau[k])), ("aba_batch", k)
        assert np.array_equal(M[k], rigid.crba(m, d, Q[k])), ("crba_batch", k)
    # and ABA inverts RNEA
    assert_close(ddq, A, "aba_batch(rnea_batch(a))", tol=1e-8)


def test_batch_in_pinocchio_layout_equals_pinocchio():
    p = pair("solo12")
    pm, pd = p.pm, p.pd
    Q = np.array([s[0] for s in p.states])
    V = np.array([s[1] for s in p.states])
    A = np.array([s[2] for s in p.states])
    tau = rigid.rnea_batch(p.rp, Q, V, A)
    for k in range(len(Q)):
        assert_close(tau[k], pin.rnea(pm, pd, Q[k], V[k], A[k]), "rnea_batch")


def test_batch_accepts_array_likes_and_no_states():
    m = rigid.Model.builtin("double_pendulum")
    out = rigid.rnea_batch(m, [[0.1, 0.2]], [[0, 0]], [[0, 0]])
    d = m.create_data()
    assert np.array_equal(out[0], rigid.rnea(m, d, [0.1, 0.2], [0, 0], [0, 0]))
    # non-contiguous and float32 inputs are converted
    Q = np.zeros((4, 4))[:, ::2] + 0.3
    out = rigid.rnea_batch(m, Q, np.zeros((4, 2), np.float32), np.zeros((4, 2), int))
    assert out.shape == (4, 2)
    empty = rigid.rnea_batch(m, np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 2)))
    assert empty.shape == (0, 2)
    assert rigid.crba_batch(m, np.zeros((0, 2))).shape == (0, 2, 2)


def test_batch_shape_errors_name_the_argument():
    m = rigid.Model.builtin("puma560")
    Q = np.zeros((3, 6))
    with pytest.raises(ValueError, match=r"rnea_batch: Q must be an array of shape \(N, nq = 6\), got shape \(3, 5\)"):
        rigid.rnea_batch(m, np.zeros((3, 5)), Q, Q)
    with pytest.raises(ValueError, match=r"V has 2 rows, Q has 3"):
        rigid.rnea_batch(m, Q, np.zeros((2, 6)), Q)
    with pytest.raises(ValueError, match=r"shape \(N, nv = 6\), got shape \(18,\)"):
        rigid.aba_batch(m, Q, np.zeros(18), Q)
    bad = Q.copy()
    bad[1, 2] = np.nan
    with pytest.raises(ValueError, match=r"A\[1, 2\] is not finite"):
        rigid.rnea_batch(m, Q, Q, bad)
    with pytest.raises(ValueError, match=r"state 1 .*q\[2\] is not finite"):
        rigid.crba_batch(m, bad)
    with pytest.raises(TypeError, match="real numbers"):
        rigid.crba_batch(m, Q.astype(complex))


def test_batch_reads_inputs_in_place_and_leaves_them_alone():
    """Contiguous float64 inputs are read where they are (no copy), never written, and may be
    one array passed twice; a NaN far into a long array is found at its row and column."""
    p = pair("talos")
    for m in (p.rr, p.rp):  # the pinocchio layout permutes TALOS's velocity rows
        Q, V, _ = states(m, 300, 11)
        before = (Q.copy(), V.copy())
        tau = rigid.rnea_batch(m, Q, V, V)
        assert np.array_equal(Q, before[0]) and np.array_equal(V, before[1])
        d = m.create_data()
        assert_close(tau[299], rigid.rnea(m, d, Q[299], V[299], V[299]), "rnea_batch", tol=1e-13)
        bad = V.copy()
        bad[250, 7] = np.inf
        with pytest.raises(ValueError, match=r"aba_batch: TAU\[250, 7\] is not finite"):
            rigid.aba_batch(m, Q, V, bad)


def test_batch_writes_into_out():
    p = pair("anymal")
    for m in (p.rr, p.rp):
        Q, V, A = states(m, 21, 4)
        out = np.full((21, m.nv), np.nan)
        tau = rigid.rnea_batch(m, Q, V, A, out=out)
        assert tau is out
        assert np.array_equal(out, rigid.rnea_batch(m, Q, V, A))
        ddq = rigid.aba_batch(m, Q, V, tau, out=np.empty((21, m.nv)))
        assert_close(ddq, A, "aba_batch(out=)", tol=1e-8)
        with pytest.raises(ValueError, match=r"out must be a writeable, C-contiguous float64 array of shape \(21, 18\)"):
            rigid.rnea_batch(m, Q, V, A, out=np.empty((20, m.nv)))
        with pytest.raises(ValueError, match="out must be"):
            rigid.rnea_batch(m, Q, V, A, out=np.empty((m.nv, 21)).T)
        with pytest.raises(ValueError, match="out overlaps an input"):
            rigid.rnea_batch(m, Q, V, A, out=A)
        # two arrays over one buffer: not seen by rust-numpy's borrows, refused all the same
        buf = bytearray(8 * 22 * m.nv)
        x1, x2 = (np.frombuffer(memoryview(buf)).reshape(22, m.nv) for _ in range(2))
        x1[:] = A[0]
        with pytest.raises(ValueError, match="out overlaps an input"):
            rigid.rnea_batch(m, Q, V, x1[:21], out=x2[1:])
        frozen = np.empty((21, m.nv))
        frozen.flags.writeable = False
        with pytest.raises(ValueError, match="out cannot be written"):
            rigid.rnea_batch(m, Q, V, A, out=frozen)


def test_batch_releases_the_gil():
    """Another Python thread runs while a batch computes: with the GIL held it could not. The
    batch is called until the calls add up to 0.1 s (a fast machine computes one in ~30 ms); a
    tick counts when it falls inside a call, more than 10 ms (twice Python's switch interval)
    after the call began, so that it cannot be a tick taken before the GIL was released."""
    p = pair("talos")
    m = p.rr
    Q, V, A = states(m, 2000, 5)
    Q, V, A = (np.tile(x, (60, 1)) for x in (Q, V, A))
    ticks, stop, calls = [], threading.Event(), []

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.0005)

    t = threading.Thread(target=tick)
    t.start()
    try:
        time.sleep(0.01)
        while sum(t1 - t0 for t0, t1 in calls) < 0.1 and len(calls) < 20:
            t0 = time.perf_counter()
            rigid.rnea_batch(m, Q, V, A)
            calls.append((t0, time.perf_counter()))
    finally:
        stop.set()
        t.join()
    longest = max(t1 - t0 for t0, t1 in calls)
    assert longest > 0.015, f"calls too short to tell: the longest took {longest:.3f} s"
    inside = [x for x in ticks if any(t0 + 0.01 < x < t1 - 0.001 for t0, t1 in calls)]
    assert len(inside) >= 3, f"{len(inside)} ticks of the other thread in {len(calls)} calls"


@pytest.mark.parametrize("name", ["ur5", "talos", "all_joints_floating"])
@pytest.mark.parametrize("layout", ["rigid", "pinocchio"])
def test_rnea_derivatives_batch_equals_single_calls(name, layout):
    p = pair(name)
    m = p.rr if layout == "rigid" else p.rp
    d = m.create_data()
    Q, V, A = states(m, 11, 4)
    dq, dv = rigid.rnea_derivatives_batch(m, Q, V, A)
    assert dq.shape == dv.shape == (11, m.nv, m.nv)
    for k in range(len(Q)):
        sq, sv, _ = rigid.rnea_derivatives(m, d, Q[k], V[k], A[k])
        assert_close(dq[k], sq, "rnea_derivatives_batch dtau_dq", tol=1e-12)
        assert_close(dv[k], sv, "rnea_derivatives_batch dtau_dv", tol=1e-12)
    if layout == "pinocchio":
        for k in range(3):
            pdq, pdv, _ = pin.computeRNEADerivatives(p.pm, p.pd, Q[k], V[k], A[k])
            assert_close(dq[k], pdq, "rnea_derivatives_batch vs Pinocchio dtau_dq")
            assert_close(dv[k], pdv, "rnea_derivatives_batch vs Pinocchio dtau_dv")


def test_rnea_derivatives_batch_refuses_bad_states():
    m = rigid.Model.builtin("puma560")
    Q = np.zeros((3, 6))
    bad = Q.copy()
    bad[2, 1] = np.inf
    with pytest.raises(ValueError, match=r"rnea_derivatives_batch: V\[2, 1\] is not finite"):
        rigid.rnea_derivatives_batch(m, Q, bad, Q)
    with pytest.raises(ValueError, match=r"rnea_derivatives_batch: state 2 .*q\[1\] is not finite"):
        rigid.rnea_derivatives_batch(m, bad, Q, Q)
    with pytest.raises(ValueError, match=r"A has 2 rows, Q has 3"):
        rigid.rnea_derivatives_batch(m, Q, Q, np.zeros((2, 6)))


@pytest.mark.parametrize("layout", ["rigid", "pinocchio"])
def test_fresh_outputs_reuse_only_arrays_nothing_refers_to(layout):
    p = pair("talos")
    m = p.rp if layout == "pinocchio" else p.rr
    d = m.create_data()
    Q, V, A = states(m, 23, 5)

    def address(x):
        return x.__array_interface__["data"][0]

    previous = rigid.set_output_cache(1 << 30)
    try:
        assert previous == 0  # off unless a caller opts in
        tau = rigid.rnea_batch(m, Q, V, A)
        first = address(tau)
        tau[:] = np.nan  # a result the next call must overwrite entirely
        del tau
        tau = rigid.rnea_batch(m, Q, V, A)
        assert address(tau) == first  # the dropped array, made again
        held = rigid.rnea_batch(m, Q, V, A)
        assert address(held) != first  # not the one still held
        row = tau[3]  # a view keeps the whole array in use
        del tau
        again = rigid.rnea_batch(m, Q, V, A)
        assert address(again) not in (first, address(held))
        assert np.array_equal(row, again[3]) and np.array_equal(held, again)
        for k in range(len(Q)):
            assert_close(again[k], rigid.rnea(m, d, Q[k], V[k], A[k]), "rnea_batch", tol=1e-13)
        # an array made read-only through a result's base is not made again
        again.base.flags.writeable = False
        del row, again, held
        assert rigid.rnea_batch(m, Q, V, A).flags.writeable

        # every verb overwrites every entry of a kept array
        for _ in range(2):
            ddq = rigid.aba_batch(m, Q, V, A)
            M = rigid.crba_batch(m, Q)
            dq, dv = rigid.rnea_derivatives_batch(m, Q, V, A)
            Y = rigid.regressor_batch(m, Q, V, A)
            assert address(dq) != address(dv)
            for k in range(len(Q)):
                assert_close(ddq[k], rigid.aba(m, d, Q[k], V[k], A[k]), "aba_batch", tol=1e-11)
                assert_close(M[k], rigid.crba(m, d, Q[k]), "crba_batch", tol=1e-13)
                sq, sv, _ = rigid.rnea_derivatives(m, d, Q[k], V[k], A[k])
                assert_close(dq[k], sq, "dtau_dq", tol=1e-12)
                assert_close(dv[k], sv, "dtau_dv", tol=1e-12)
                assert_close(Y[k], rigid.regressor(m, d, Q[k], V[k], A[k]), "regressor_batch",
                             tol=1e-13)
            for x in (ddq, M, dq, dv, Y):
                x[:] = np.nan
            del ddq, M, dq, dv, Y

        # no cache: every fresh output is a new array that owns its memory
        assert rigid.set_output_cache(0) == 1 << 30
        tau = rigid.rnea_batch(m, Q, V, A)
        assert tau.flags.owndata
        with pytest.raises(ValueError, match="max_bytes must be 0 or more"):
            rigid.set_output_cache(-1)
    finally:
        rigid.set_output_cache(previous)


def test_fresh_outputs_from_several_python_threads():
    # numpy releases the GIL while it allocates: the cache must not hold its lock across that
    p = pair("solo12")
    m = p.rr
    inputs = [states(m, 200, seed) for seed in range(4)]
    want = [rigid.rnea_batch(m, *x) for x in inputs]
    results, errors = [[] for _ in inputs], []

    def work(t):
        try:
            for _ in range(25):
                results[t].append(rigid.rnea_batch(m, *inputs[t], threads=1)[7].copy())
                rigid.crba_batch(m, inputs[t][0], threads=1)
        except Exception as e:  # noqa: BLE001 (reported below)
            errors.append(e)

    workers = [threading.Thread(target=work, args=(t,)) for t in range(len(inputs))]
    for w in workers:
        w.start()
    for w in workers:
        w.join(timeout=120)
    assert not any(w.is_alive() for w in workers), "a batch verb did not return"
    assert not errors, errors
    for t, rows in enumerate(results):
        assert len(rows) == 25 and all(np.array_equal(r, want[t][7]) for r in rows)


_LANES_SCRIPT = """
import sys
import numpy as np
import rigid
path, floating, out = sys.argv[1], sys.argv[2] == "1", sys.argv[3]
m = rigid.Model.from_urdf(path, floating=floating)
rigid.seed(7)
rng = np.random.default_rng(7)
Q = np.array([rigid.random_configuration(m) for _ in range(67)])
V, A = rng.uniform(-1, 1, (67, m.nv)), rng.uniform(-1, 1, (67, m.nv))
res = {"Q": Q, "V": V, "A": A}
for t in (1, 2):
    res[f"rnea{t}"] = rigid.rnea_batch(m, Q, V, A, threads=t)
    res[f"aba{t}"] = rigid.aba_batch(m, Q, V, A, threads=t)
    res[f"crba{t}"] = rigid.crba_batch(m, Q, threads=t)
    res[f"dq{t}"], res[f"dv{t}"] = rigid.rnea_derivatives_batch(m, Q, V, A, threads=t)
np.savez(out, **res)
"""


def test_rigid_lanes_fixes_the_width_and_never_the_bits(tmp_path):
    """RIGID_LANES=2|4|8 (docs/simd.md) on Panda (fixed), Solo-12 and TALOS (free-flyers), 67
    random states (a partial last pack at every width): RNEA, ABA, CRBA and the RNEA derivatives
    give the same bits at every width on 1 and 2 threads, and the same bits as a loop of single
    calls; a value other than 2, 4 or 8 is named on stderr."""
    import os
    import subprocess
    import sys

    from conftest import robot_path

    script = tmp_path / "lanes.py"
    script.write_text(_LANES_SCRIPT)
    for name in ("panda", "solo12", "talos"):
        path, floating = robot_path(name)
        runs = {}
        for lanes in ("2", "4", "8"):
            out = tmp_path / f"{name}_{lanes}.npz"
            env = dict(os.environ, RIGID_LANES=lanes)
            subprocess.run([sys.executable, str(script), path, "1" if floating else "0", str(out)],
                           env=env, check=True)
            runs[lanes] = np.load(out)
        first = runs["2"]
        for lanes, r in runs.items():
            for key in ("rnea", "aba", "crba", "dq", "dv"):
                for t in (1, 2):
                    assert np.array_equal(r[f"{key}{t}"], first[f"{key}1"]), (name, lanes, key, t)
        m = rigid.Model.from_urdf(path, floating=floating)
        d = m.create_data()
        Q, V, A = first["Q"], first["V"], first["A"]
        for k in range(len(Q)):
            tau = rigid.rnea(m, d, Q[k], V[k], A[k])
            assert np.array_equal(first["rnea1"][k], tau), (name, "rnea", k)
            assert np.array_equal(first["aba1"][k], rigid.aba(m, d, Q[k], V[k], A[k])), (
                name, "aba", k)
            assert np.array_equal(first["crba1"][k], rigid.crba(m, d, Q[k])), (name, "crba", k)
            dq, dv = rigid.rnea_derivatives(m, d, Q[k], V[k], A[k])[:2]
            assert np.array_equal(first["dq1"][k], dq) and np.array_equal(first["dv1"][k], dv), (
                name, "rnea_derivatives", k)
    env = dict(os.environ, RIGID_LANES="16")
    bad = subprocess.run([sys.executable, str(script), path, "1", str(tmp_path / "bad.npz")],
                         env=env, check=True, capture_output=True, text=True)
    assert "RIGID_LANES" in bad.stderr and "16" in bad.stderr, bad.stderr
