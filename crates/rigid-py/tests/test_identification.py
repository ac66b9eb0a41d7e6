"""The identification verbs: the regressor against Pinocchio's computeJointTorqueRegressor and
against rnea, an exciting trajectory identified back to the model's own base parameters (from a
dict of arrays and from the CSV it wrote), the physically consistent estimate (when the module is
built with the feature `sdp`, as scripts/test.sh does when OpenBLAS is installed), and errors."""

import math
import os

import numpy as np
import pytest

pin = pytest.importorskip("pinocchio")

import rigid
from conftest import assert_close, pair

SDP = "sdp" in rigid.features


def test_the_build_has_the_features_asked_for():
    # scripts/test.sh builds the module with `--features sdp` when OpenBLAS is there
    assert SDP == ("sdp" in os.environ.get("MATURIN_PEP517_ARGS", "")), rigid.features


@pytest.mark.parametrize("name", ["ur5", "panda", "solo12", "talos"])
def test_regressor_equals_pinocchio_and_rnea(name):
    r = pair(name)
    m, d = r.rp, r.rp.create_data()
    assert list(m.names) == list(r.pm.names)[1:]  # the same bodies in the same order
    pi = rigid.dynamic_parameters(m)
    pin_pi = np.concatenate([r.pm.inertias[i].toDynamicParameters()
                             for i in range(1, r.pm.njoints)])
    assert_close(pi, pin_pi, "parameters")
    for q, v, a, _ in r.states:
        y = rigid.computeJointTorqueRegressor(m, d, q, v, a)
        assert y.shape == (m.nv, 10 * len(m.names))
        assert_close(y, pin.computeJointTorqueRegressor(r.pm, r.pd, q, v, a), "regressor")
        tau = rigid.rnea(m, d, q, v, a)
        assert np.max(np.abs(y @ pi - tau)) <= 1e-12 * max(1.0, np.max(np.abs(tau)))


def test_excite_then_identify_recovers_the_base_parameters(tmp_path):
    m = rigid.Model.builtin("puma560")
    csv = tmp_path / "traj.csv"
    traj = rigid.excite(m, duration=4.0, rate=100.0, iterations=20, out=csv)
    n = len(traj["t"])
    assert traj["q"].shape == (n, 6) and traj["tau"].shape == (n, 6)
    assert math.isfinite(traj["condition_number"])
    d = m.create_data()
    k = n // 3
    assert_close(traj["tau"][k], rigid.rnea(m, d, traj["q"][k], traj["v"][k], traj["a"][k]),
                 "tau of the trajectory")
    for samples in (traj, csv, str(csv)):
        est = rigid.identify(m, samples)
        truth, ls = est["model_values"], est["least_squares"]
        assert len(est["base_parameters"]) == len(ls["base"]) == 36
        assert est["base_parameters"][0].startswith("Izz1 + ")
        err = np.max(np.abs(ls["base"] - truth["base"])) / np.max(np.abs(truth["base"]))
        assert err < 1e-8, err
        assert ls["relative_residual"] < 1e-8
        # the notes' PUMA 560 (Armstrong, Khatib & Burdick): link 1 is massless with Izz = 0.35,
        # link 3's principal moments (0.066, 0.086, 0.0125) break the triangle inequality
        assert truth["consistent"] == [False, True, False, True, True, True]
        assert est["physical"] is None


def test_physically_consistent_estimate_or_how_to_build_it():
    m = rigid.Model.builtin("puma560")
    traj = rigid.excite(m, duration=4.0, iterations=20)
    rng = np.random.default_rng(3)
    noisy = dict(traj)
    noisy["tau"] = traj["tau"] + 0.01 * np.sqrt(np.mean(traj["tau"] ** 2)) * \
        rng.standard_normal(traj["tau"].shape)
    if not SDP:
        with pytest.raises(ValueError, match="--features sdp"):
            rigid.identify(m, noisy, physical=True)
        return
    est = rigid.identify(m, noisy, physical=True)
    pc = est["physical"]
    assert all(pc["consistent"]), pc["consistent"]
    assert not all(est["least_squares"]["consistent"])
    # massless links 1 and 3 held to ±20 % of their mass (zero): no body can be that
    with pytest.raises(ValueError, match="mass bounds may be infeasible"):
        rigid.identify(m, noisy, physical=True, mass_tolerance=0.2)
    # the consistent model's prediction fits the samples nearly as well as least squares
    assert pc["residual_rms"] <= 1.05 * est["least_squares"]["residual_rms"]


def test_bad_samples_are_named():
    m = rigid.Model.builtin("double_pendulum")
    traj = rigid.excite(m, duration=2.0, iterations=5)
    with pytest.raises(ValueError, match='the key "tau"'):
        rigid.identify(m, {k: traj[k] for k in ("t", "q", "v", "a")})
    bad = dict(traj)
    bad["tau"] = traj["tau"].copy()
    bad["tau"][4, 1] = math.nan
    with pytest.raises(ValueError, match=r"tau\[4, 1\] is not finite"):
        rigid.identify(m, bad)
    with pytest.raises(ValueError, match=r"shape \(N, nv = 2\)"):
        rigid.identify(m, dict(traj, v=traj["v"][:, :1]))
    few = {k: traj[k][:2] for k in ("t", "q", "v", "a", "tau")}
    with pytest.raises(ValueError, match="record at least"):
        rigid.identify(m, few)
    still = {k: traj[k] for k in ("t", "q", "v", "a", "tau")}
    still["q"] = np.zeros_like(traj["q"])
    still["v"] = np.zeros_like(traj["v"])
    still["a"] = np.zeros_like(traj["a"])
    with pytest.raises(ValueError, match="excites only"):
        rigid.identify(m, still)
    with pytest.raises(ValueError, match="mass_tolerance"):
        rigid.identify(m, traj, mass_tolerance=0.1)
    with pytest.raises(FileNotFoundError):
        rigid.identify(m, "no/such/file.csv")
    with pytest.raises(ValueError, match="duration must be positive"):
        rigid.excite(m, duration=-1.0)
