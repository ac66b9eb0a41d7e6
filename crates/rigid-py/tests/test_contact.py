"""Contacts from Python: ``simulate(..., ground=, friction=, restitution=)`` with the meaning of
``rigid simulate --ground --friction --restitution``: a URDF box falls onto the ground and rests
on its face, Solo-12 stands on its feet under ``controller="pd"``, bad values raise."""

import os

import numpy as np
import pytest

import rigid
from conftest import robot_path

BOX_URDF = """<robot name="crate">
  <link name="crate">
    <inertial><mass value="2"/><inertia ixx="0.0167" iyy="0.0283" izz="0.0417" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
</robot>"""


def crate(tmp_path):
    path = tmp_path / "crate.urdf"
    path.write_text(BOX_URDF)
    return rigid.Model.from_urdf(str(path), floating=True)


def test_a_box_falls_onto_the_ground_and_rests_on_its_face(tmp_path):
    m = crate(tmp_path)
    run = rigid.simulate(m, q0=[0, 0, 0.5, 0, 0, 0, 1], duration=1.0, ground=0.0, every=10)
    assert run["q"][-1, 2] == pytest.approx(0.05, abs=1e-4)
    assert run["contacts"][-1] == 4
    assert run["normal_force"][-1] == pytest.approx(2.0 * 9.81, rel=0.02)
    assert run["contacts"].shape == run["t"].shape


def test_the_admm_solver_rests_the_box_and_reports_its_residuals(tmp_path):
    m = crate(tmp_path)
    runs = {s: rigid.simulate(m, q0=[0, 0, 0.5, 0, 0, 0, 1], duration=1.0, ground=0.0,
                              every=10, contact_solver=s) for s in ("pgs", "admm")}
    for s, run in runs.items():
        assert run["q"][-1, 2] == pytest.approx(0.05, abs=1e-4), s
        assert run["contacts"][-1] == 4, s
        assert run["converged"][-1] == 1.0, s
        assert run["iterations"][-1] >= 1, s
        # at rest and solved: the residuals at round-off of the 0.02 N·s impulse
        for k in ("signorini", "coulomb", "dissipation"):
            assert abs(run[k][-1]) < 1e-12, (s, k, run[k][-1])
        assert run["velocity_error"][-1] < 1e-9, s
        assert run["signorini"].shape == run["t"].shape
    # the same rest reached either way
    assert np.max(np.abs(runs["pgs"]["q"][-1] - runs["admm"]["q"][-1])) < 1e-6
    with pytest.raises(ValueError, match="newton"):
        rigid.simulate(m, duration=0.01, ground=0.0, contact_solver="newton")
    with pytest.raises(ValueError, match="newton"):
        rigid.Simulator(m, ground=0.0, contact_solver="newton")


def test_solo12_stands_on_the_ground_under_pd():
    path, _ = robot_path("solo12")
    m = rigid.Model.from_urdf(path, floating=True)
    stance = [0, 0, 0.3, 0, 0, 0, 1, 0.1, 0.8, -1.6, -0.1, 0.8, -1.6, 0.1, -0.8, 1.6, -0.1,
              -0.8, 1.6]
    run = rigid.simulate(m, duration=0.5, ground=0.0, controller="pd", target=stance, every=50)
    z = run["q"][:, 2]
    assert np.max(np.abs(z - z[0])) < 1e-3
    assert np.all(run["contacts"][1:] == 4)
    assert run["normal_force"][-1] == pytest.approx(m.total_mass * 9.81, rel=0.05)


def test_bad_friction_and_restitution_raise(tmp_path):
    m = crate(tmp_path)
    with pytest.raises(ValueError, match="friction must be finite and >= 0"):
        rigid.simulate(m, duration=0.01, ground=0.0, friction=-1.0)
    with pytest.raises(ValueError, match=r"restitution must be in \[0, 1\]"):
        rigid.simulate(m, duration=0.01, ground=0.0, restitution=2.0)
    with pytest.raises(ValueError, match="applies when something can touch"):
        rigid.simulate(m, duration=0.01, friction=0.5)


FIX = os.path.join(os.path.dirname(__file__), "..", "..", "rigid", "tests", "fixtures")


def test_an_mjcf_world_stands_on_its_own_floor_without_flags():
    """stack.xml: three boxes and a capsule on the file's floor, every geom pair colliding (as
    MuJoCo): 1 s at the file's timestep, every body within 2 mm of its start, the contacts in the
    result, the step the file's."""
    m = rigid.Model.from_mjcf(os.path.join(FIX, "contact", "stack.xml"))
    run = rigid.simulate(m, duration=1.0, every=100)
    assert run["t"][1] == pytest.approx(0.1)  # the file's timestep, 1 ms, every 100 steps
    q = run["q"]
    for k in range(4):  # the free bodies' origins: 7 numbers each, position first
        assert np.max(np.linalg.norm(q[:, 7 * k:7 * k + 3] - q[0, 7 * k:7 * k + 3], axis=1)) < 2e-3
    assert run["contacts"][-1] >= 12
    assert "violation_position" not in run


def test_a_closed_loop_is_held_and_reported():
    """fourbar.xml: its <connect> held without being asked, and the same loop given as
    constraints= on the URDF: the violation columns in the result, 1e-9 at most."""
    xml = rigid.Model.from_mjcf(os.path.join(FIX, "constraints", "fourbar.xml"))
    run = rigid.simulate(xml, v0=[2.0, 0.0, 0.0], duration=0.5, every=50)
    assert np.max(run["violation_position"]) < 1e-9
    assert np.max(run["violation_velocity"]) < 1e-9
    assert abs(run["q"][-1, 0] - run["q"][0, 0]) > 0.1  # the crank turns
    assert "contacts" not in run
    # the URDF's angles are the MJCF's plus the assembly's (fourbar.xml's bodies are assembled)
    urdf = rigid.Model.from_urdf(os.path.join(FIX, "constraints", "fourbar.urdf"))
    pin = rigid.ConstraintModel(urdf, "point", "coupler_joint", (np.eye(3), [0.8, 0, 0]),
                                "rocker_joint", (np.eye(3), [0.6, 0, 0]))
    assembly = np.array([0.5, 0.02116623166979137, 1.1280269456729848])
    same = rigid.simulate(urdf, q0=run["q"][0] + assembly, v0=[2.0, 0.0, 0.0], duration=0.5,
                          every=50, constraints=[pin], limits="ignored", joint_dynamics=False)
    assert np.max(same["violation_position"]) < 1e-9
    np.testing.assert_allclose(same["q"] - assembly, run["q"], atol=1e-8)


# a 2 kg cylinder (axis z) with a 1.5 kg box bolted to its side, as tall as it, and a 0.5 kg
# point mass (which weighs but does not collide), like examples/compound.toml
COMPOUND = """
[[part]]
name = "drum"
shape = "cylinder"
radius = 0.1
length = 0.2
mass = 2.0
position = [0.0, 0.0, 0.0]

[[part]]
name = "arm"
shape = "box"
size = [0.3, 0.1, 0.2]
mass = 1.5
position = [0.25, 0.0, 0.0]

[[part]]
name = "bolt"
shape = "point"
mass = 0.5
position = [0.0, 0.05, 0.0]
"""


def test_a_body_spec_dropped_on_the_ground_comes_to_rest_carrying_its_weight(tmp_path):
    spec = tmp_path / "compound.toml"
    spec.write_text(COMPOUND)
    weight = 4.0 * 9.81  # the parts' masses
    # dropped from 0.4 m, tilted 20 degrees about x, spinning and sliding
    s, c = np.sin(np.radians(10)), np.cos(np.radians(10))
    run = rigid.simulate_body(str(spec), ground=0.0, q0=[0, 0, 0.4, s, 0, 0, c],
                              omega=[0.5, 1.0, 2.0], velocity=[0.3, 0, 0], duration=3.0)
    assert run["t"][-1] == pytest.approx(3.0)
    speed = np.hypot(np.linalg.norm(run["omega"][-1]), np.linalg.norm(run["velocity"][-1]))
    assert speed < 1e-3
    # at rest on the ground: CoM between the arm's half-thickness and the drum's radius above it
    assert 0.04 - 1e-3 < run["position"][-1, 2] < 0.2
    assert run["contacts"][-1] >= 3
    assert run["normal_force"][-1] == pytest.approx(weight, rel=0.01)
    # nothing added energy: it ends below where it started
    assert run["energy"][-1] < run["energy"][0]


def test_a_body_spec_set_down_on_the_ground_stays_and_bad_options_raise(tmp_path):
    spec = tmp_path / "compound.toml"
    spec.write_text(COMPOUND)
    with pytest.warns(UserWarning, match="bolt: has no shape to collide with"):
        run = rigid.simulate_body(str(spec), ground=0.0, duration=0.5)
    # set down upright on the drum's face: the CoM stays put
    assert np.max(np.abs(run["position"] - run["position"][0])) < 1e-4
    assert run["normal_force"][-1] == pytest.approx(4.0 * 9.81, rel=0.01)
    with pytest.raises(ValueError, match="pivot does not apply"):
        rigid.simulate_body(str(spec), ground=0.0, pivot=[0, 0, 0], duration=0.01)
    with pytest.raises(ValueError, match="apply with ground"):
        rigid.simulate_body(str(spec), friction=0.5, duration=0.01)
    with pytest.raises(TypeError, match="path to a TOML spec"):
        rigid.simulate_body({"part": []}, ground=0.0, duration=0.01)


def test_polish_false_leaves_the_sweep_alone():
    """`simulate(..., polish=False)`: PGS without its active-set polish. Gymnasium's ant
    (checked in) landing in its file's world at 1 ms takes 4 sweeps a step with the polish and
    ~32 without (docs/contact.md), every solve converged either way (the two stop at different
    solutions of its contact problem, which has more than one: docs/contact.md)."""
    ant = os.path.join(os.path.dirname(__file__), "..", "..", "rigid", "tests", "mujoco", "models",
                       "ant.xml")
    m = rigid.Model.from_mjcf(ant)
    runs = [rigid.simulate(m, duration=0.6, dt=1e-3, polish=p) for p in (True, False)]
    sweeps = [r["iterations"][r["iterations"] > 0].mean() for r in runs]
    assert sweeps[0] <= 6 and sweeps[1] >= 20, sweeps
    for r in runs:
        solved = r["iterations"] > 0
        assert r["converged"][solved].all() and r["velocity_error"][solved].max() < 1e-9
