"""``rigid.Simulator``: one step at a time from any state with an open-loop torque, and
``step_derivatives`` against central differences of ``step`` itself (``q`` perturbed with
``rigid.integrate``, ``q⁺`` compared with ``rigid.difference``): a URDF crate resting on its face,
sliding on an edge, in flight; in rigid's and in Pinocchio's layout; bad input raises."""

import numpy as np
import pytest

import rigid

BOX_URDF = """<robot name="crate">
  <link name="crate">
    <inertial><mass value="2"/><inertia ixx="0.0167" iyy="0.0283" izz="0.0417" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
</robot>"""


def crate(tmp_path, layout="rigid"):
    path = tmp_path / "crate.urdf"
    path.write_text(BOX_URDF)
    return rigid.Model.from_urdf(str(path), floating=True, layout=layout)


def pose(p, rotvec):
    """A free-flyer configuration (rigid's layout: position, then quaternion x, y, z, w)."""
    theta = np.linalg.norm(rotvec)
    axis = rotvec / theta if theta > 0 else np.zeros(3)
    return np.concatenate([p, axis * np.sin(theta / 2), [np.cos(theta / 2)]])


def central(sim, model, q, v, tau, eps=1e-7):
    """Central differences of ``sim.step`` from ``(q, v, tau)``: the six matrices."""
    nv = model.nv
    q0, _ = sim.step(q, v, tau)
    out = {k: np.zeros((nv, nv)) for k in ("dq_dq", "dq_dv", "dq_dtau", "dv_dq", "dv_dv", "dv_dtau")}
    for wrt in ("q", "v", "tau"):
        for k in range(nv):
            ends = []
            for sign in (1.0, -1.0):
                e = np.zeros(nv)
                e[k] = sign * eps
                qp = rigid.integrate(model, q, e) if wrt == "q" else q
                vp = v + e if wrt == "v" else v
                tp = tau + e if wrt == "tau" else tau
                q1, v1 = sim.step(qp, vp, tp)
                ends.append((rigid.difference(model, q0, q1), v1))
            out["dq_d" + wrt][:, k] = (ends[0][0] - ends[1][0]) / (2 * eps)
            out["dv_d" + wrt][:, k] = (ends[0][1] - ends[1][1]) / (2 * eps)
    return out


def check(sim, model, q, v, tau):
    d = sim.step_derivatives(q, v, tau)
    fd = central(sim, model, q, v, tau)
    for k, m in fd.items():
        scale = max(1e-3, np.abs(m).max())
        assert np.abs(d[k] - m).max() <= 1e-5 * scale, (k, np.abs(d[k] - m).max())
    return d


def test_a_crate_resting_on_its_face(tmp_path):
    m = crate(tmp_path)
    sim = rigid.Simulator(m, dt=1e-3, ground=0.0, friction=0.8)
    q = pose([0.0, 0.0, 0.05 + 3e-6], np.zeros(3))
    d = check(sim, m, q, np.zeros(6), np.array([0.1, 0.0, 0.05, 0.5, -0.2, 0.0]))
    assert d["modes"] == ["sticking"] * 4
    # a small push is held by friction and by the ground
    assert np.abs(d["dv_dtau"]).max() < 1e-9
    # the step from the same state (its warm start the last step's: equal to round-off)
    q1, _ = sim.step(q, np.zeros(6), np.array([0.1, 0.0, 0.05, 0.5, -0.2, 0.0]))
    assert np.allclose(d["q_next"], q1, rtol=0, atol=1e-12)


def test_a_crate_sliding_on_an_edge_and_in_flight_in_pinocchio_layout(tmp_path):
    for layout in ("rigid", "pinocchio"):
        m = crate(tmp_path, layout)
        sim = rigid.Simulator(m, dt=1e-3, ground=0.0, friction=0.3)
        r = 0.3  # turned about x: resting on the edge at y = -0.15, z = -0.05
        low = -0.15 * np.sin(r) - 0.05 * np.cos(r)
        q = pose([0.1, -0.2, -low + 3e-6], np.array([r, 0.0, 0.0]))
        # Pinocchio's layout: (v, ω) in the body frame
        vb = np.array([1.5, 0.2 * np.cos(r), -0.2 * np.sin(r)])
        v = np.concatenate([np.zeros(3), vb]) if layout == "rigid" else np.concatenate([vb, np.zeros(3)])
        d = check(sim, m, q, v, np.zeros(6))
        assert d["modes"].count("sliding") == 2, d["modes"]
        q = pose([0.0, 0.0, 1.0], np.array([0.3, -0.2, 0.9]))
        v = np.array([2.0, -5.0, 3.0, 1.0, 0.5, -0.3])
        d = check(sim, m, q, v, np.array([0.1, 0.2, -0.3, 1.0, 0.0, 2.0]))
        assert d["modes"] == []


def test_bad_input_raises(tmp_path):
    m = crate(tmp_path)
    with pytest.raises(ValueError, match="nothing can touch"):
        rigid.Simulator(m)
    sim = rigid.Simulator(m, ground=0.0)
    assert sim.dt == 1e-3
    with pytest.raises(ValueError, match="nv"):
        sim.step(pose([0, 0, 1], np.zeros(3)), np.zeros(5), np.zeros(6))
    with pytest.raises(ValueError):
        sim.step_derivatives(pose([0, 0, 1], np.zeros(3)), np.zeros(6), [np.nan] * 6)


def test_the_push_through_contact_example_converges():
    """examples/python/push_through_contact.py: its gradient against central differences of the
    whole rollout, and Gauss-Newton to the mark and to rest."""
    import importlib.util
    import os

    path = os.path.join(os.path.dirname(__file__), "..", "..", "..", "examples", "python",
                        "push_through_contact.py")
    spec = importlib.util.spec_from_file_location("push_through_contact", path)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    u, q, v, history = example.optimise(n=300, verbose=False)
    assert abs(q[0] - example.TARGET) < 1e-8 and abs(v[3]) < 1e-7, (q[0], v[3], history)
    assert len(history) <= 5
