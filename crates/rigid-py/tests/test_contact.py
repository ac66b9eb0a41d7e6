"""Contacts from Python: ``simulate(..., ground=, friction=, restitution=)`` with the meaning of
``rigid simulate --ground --friction --restitution``: a URDF box falls onto the ground and rests
on its face, Solo-12 stands on its feet under ``controller="pd"``, bad values raise."""

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
    with pytest.raises(ValueError, match="apply with ground"):
        rigid.simulate(m, duration=0.01, friction=0.5)
