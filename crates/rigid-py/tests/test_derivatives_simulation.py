"""The derivative verbs against Pinocchio's computeRNEADerivatives / computeABADerivatives /
computeGeneralizedGravityDerivatives (raw arrays in Pinocchio's layout, mapped by joint name in
rigid's), and the simulation verbs: energy kept by RK4, gravity compensation holding a robot
still, a Python control law equal to the built-in one, errors raised, and the HTML replay."""

import math

import numpy as np
import pytest

pin = pytest.importorskip("pinocchio")

import rigid
from conftest import assert_close, pair, robot_path, symmetric

DERIV_ROBOTS = ["ur5", "solo12", "talos", "all_joints_floating"]


@pytest.mark.parametrize("name", DERIV_ROBOTS)
def test_derivatives_layout_pinocchio_equal_pinocchio(name):
    r = pair(name)
    pm, pd, m = r.pm, r.pd, r.rp
    d = m.create_data()
    for q, v, a, tau in r.states:
        dq, dv, da = rigid.rnea_derivatives(m, d, q, v, a)
        pdq, pdv, pda = pin.computeRNEADerivatives(pm, pd, q, v, a)
        assert_close(dq, pdq, "dtau_dq")
        assert_close(dv, pdv, "dtau_dv")
        assert_close(da, symmetric(pda), "dtau_da")
        xq, xv, xt = rigid.aba_derivatives(m, d, q, v, tau)
        pxq, pxv, pxt = pin.computeABADerivatives(pm, pd, q, v, tau)
        assert_close(xq, pxq, "ddq_dq", tol=1e-8)
        assert_close(xv, pxv, "ddq_dv", tol=1e-8)
        assert_close(xt, symmetric(pxt), "ddq_dtau", tol=1e-8)
        assert_close(rigid.gravity_derivatives(m, d, q),
                     pin.computeGeneralizedGravityDerivatives(pm, pd, q), "dg_dq")


@pytest.mark.parametrize("name", ["ur5", "solo12"])
def test_derivatives_rigid_layout_equal_pinocchio_mapped(name):
    r = pair(name)
    pm, pd, m = r.pm, r.pd, r.rr
    d = m.create_data()
    for q, v, a, tau in r.states:
        dq, dv, _ = rigid.rnea_derivatives(m, d, r.q_rigid(q), r.v_rigid(v), r.v_rigid(a))
        pdq, pdv, _ = pin.computeRNEADerivatives(pm, pd, q, v, a)
        assert_close(dq, r.m_rigid(pdq), "dtau_dq")
        assert_close(dv, r.m_rigid(pdv), "dtau_dv")


def test_derivatives_have_pinocchio_names_and_check_inputs():
    assert rigid.computeRNEADerivatives is rigid.rnea_derivatives
    assert rigid.computeABADerivatives is rigid.aba_derivatives
    m = rigid.Model.builtin("puma560")
    with pytest.raises(ValueError, match="aba_derivatives: tau has 5 entries, expected nv = 6"):
        rigid.aba_derivatives(m, m.create_data(), [0] * 6, [0] * 6, [0] * 5)
    with pytest.raises(ValueError, match="not finite"):
        rigid.rnea_derivatives(m, m.create_data(), [math.nan] + [0] * 5, [0] * 6, [0] * 6)


def test_simulate_rk4_keeps_energy_of_a_double_pendulum():
    m = rigid.Model.builtin("double_pendulum")
    run = rigid.simulate(m, q0=[1.0, -0.5], duration=2.0, dt=1e-3, limits="ignored",
                         joint_dynamics=False)
    assert run["q"].shape == (2001, 2) and run["t"][-1] == pytest.approx(2.0)
    e = run["energy"]
    assert np.max(np.abs(e - e[0])) < 1e-8 * abs(e[0]) + 1e-10


def test_simulate_gravity_compensation_holds_ur5_still():
    path, _ = robot_path("ur5")
    m = rigid.Model.from_urdf(path)
    q0 = np.array([0.3, -1.0, 1.2, -0.4, 0.7, 0.1])
    run = rigid.simulate(m, q0=q0, duration=1.0, controller="gravity", every=100)
    assert np.max(np.abs(run["q"] - q0)) < 1e-9
    assert run["tau"].shape == (11, 6)


def test_a_python_control_law_equals_the_built_in_one():
    m = rigid.Model.builtin("double_pendulum")
    d = m.create_data()

    def u(t, q, v):
        return rigid.gravity(m, d, q)

    q0 = [0.4, 0.2]
    a = rigid.simulate(m, q0=q0, duration=0.5, control=u)
    b = rigid.simulate(m, q0=q0, duration=0.5, controller="gravity")
    assert np.array_equal(a["q"], b["q"]) and np.array_equal(a["tau"], b["tau"])


def test_simulate_errors_are_python_exceptions():
    m = rigid.Model.builtin("pendulum")
    with pytest.raises(ValueError, match="needs a target"):
        rigid.simulate(m, controller="pd", duration=0.01)
    with pytest.raises(ValueError, match="unknown controller"):
        rigid.simulate(m, controller="magic", duration=0.01)
    with pytest.raises(ValueError, match="positive and finite"):
        rigid.simulate(m, dt=0.0)
    with pytest.raises(ValueError, match="q0 has 2 entries"):
        rigid.simulate(m, q0=[0, 0])

    def bad(t, q, v):
        raise RuntimeError("controller failed")

    with pytest.raises(RuntimeError, match="controller failed"):
        rigid.simulate(m, control=bad, duration=0.01)


def test_track_follows_a_quintic_in_pinocchio_layout():
    path, _ = robot_path("ur5")
    m = rigid.Model.from_urdf(path, layout="pinocchio")
    q0 = np.zeros(m.nq)
    target = np.array([0.5, -0.5, 0.5, -0.5, 0.5, -0.5])
    run = rigid.simulate(m, q0=q0, target=target, controller="track", move_time=1.0,
                         duration=1.5, joint_dynamics=False, every=50)
    assert np.max(np.abs(run["q"][-1] - target)) < 1e-6


def test_replay_html_writes_a_self_contained_page(tmp_path):
    path, _ = robot_path("ur5")
    m = rigid.Model.from_urdf(path)
    run = rigid.simulate(m, q0=[0.0, -1.0, 1.0, 0.0, 0.5, 0.0], duration=0.5)
    out = tmp_path / "ur5.html"
    rigid.replay_html(m, run, str(out))
    page = out.read_text()
    assert len(page) > 10_000 and "<canvas" in page and "Content-Security-Policy" in page
    assert "https://" not in page and "http://" not in page.replace("http://www.w3.org", "")
    with pytest.raises(ValueError, match="has no \"q\""):
        rigid.replay_html(m, {"t": [0.0]}, str(out))
