"""One rigid body from Python: mass properties (file or dict, the keys of `rigid mass --json`),
the shape helpers, spatial_inertia, simulate_body; and the inertia doctor."""

import os
import tomllib

import numpy as np
import pytest

import rigid
from conftest import ROOT, cli, every_urdf

COMPOUND = os.path.join(ROOT, "examples", "compound.toml")
# docs/conventions.md, "The command-line contract": the keys of `rigid mass --json`
MASS_KEYS = {"mass", "com", "inertia_com", "inertia_origin", "principal_moments",
             "principal_axes", "spatial_inertia_origin"}


def test_mass_properties_of_the_compound_example_by_hand():
    p = rigid.mass_properties(COMPOUND)
    assert MASS_KEYS <= set(p) and p["valid"] and p["validity_error"] is None
    # cylinder 2 kg (r 0.1, L 0.2) at the origin, box 1 kg (0.3 x 0.1 x 0.1) at x = 0.25
    assert p["mass"] == pytest.approx(3.0, abs=1e-15)
    assert np.allclose(p["com"], [0.25 / 3, 0, 0], atol=1e-15)
    izz_cyl = 0.5 * 2.0 * 0.1 ** 2
    izz_box = 1.0 / 12.0 * (0.3 ** 2 + 0.1 ** 2)
    izz_origin = izz_cyl + izz_box + 1.0 * 0.25 ** 2
    assert p["inertia_origin"][2, 2] == pytest.approx(izz_origin, rel=1e-14)
    assert p["inertia_com"][2, 2] == pytest.approx(izz_origin - 3.0 * (0.25 / 3) ** 2, rel=1e-14)
    G = p["spatial_inertia_origin"]
    assert G.shape == (6, 6) and np.allclose(G, G.T)
    assert np.allclose(G[:3, :3], p["inertia_origin"]) and np.allclose(G[3:, 3:], 3 * np.eye(3))
    R, lam = p["principal_axes"], p["principal_moments"]
    assert np.all(np.diff(lam) >= 0)
    assert np.allclose(R @ np.diag(lam) @ R.T, p["inertia_com"], atol=1e-15)


def test_a_dict_spec_equals_its_toml_file():
    with open(COMPOUND, "rb") as f:
        spec = tomllib.load(f)
    a, b = rigid.mass_properties(COMPOUND), rigid.mass_properties(spec)
    for k in MASS_KEYS:
        assert np.array_equal(a[k], b[k]), k
    c = rigid.mass_properties(spec["part"])  # a list of parts
    assert np.array_equal(a["inertia_com"], c["inertia_com"])


def test_shapes_are_parts_with_their_closed_forms():
    box = rigid.mass_properties(rigid.box([0.1, 0.2, 0.3], mass=2.0))
    assert np.allclose(np.diag(box["inertia_com"]),
                       [2 / 12 * (0.04 + 0.09), 2 / 12 * (0.01 + 0.09), 2 / 12 * (0.01 + 0.04)],
                       rtol=1e-14)
    cyl = rigid.mass_properties(rigid.cylinder(0.1, 0.4, density=1000.0, position=[0, 0, 1]))
    m = 1000.0 * np.pi * 0.01 * 0.4
    assert cyl["mass"] == pytest.approx(m, rel=1e-14)
    assert cyl["inertia_com"][2, 2] == pytest.approx(0.5 * m * 0.01, rel=1e-14)
    assert cyl["com"][2] == pytest.approx(1.0)
    ball = rigid.mass_properties(rigid.sphere(0.5, mass=1.0))
    assert np.allclose(ball["inertia_com"], 0.4 * 0.25 * np.eye(3), rtol=1e-14)
    body = rigid.mass_properties([rigid.point(mass=1.0, position=[1, 0, 0]),
                                  rigid.point(mass=1.0, position=[-1, 0, 0])])
    assert np.allclose(np.diag(body["inertia_com"]), [0, 2, 2])
    for part in (rigid.ellipsoid([0.1, 0.2, 0.3], mass=1.0), rigid.capsule(0.1, 0.2, mass=1.0),
                 rigid.cone(0.1, 0.3, mass=1.0), rigid.rod(1.0, mass=1.0)):
        assert rigid.mass_properties(part)["mass"] == pytest.approx(1.0)
    assert rigid.box([1, 1, 1], mass=1.0, rpy=[0, 0, 0.5])["rpy"] == [0, 0, 0.5]


def test_bad_parts_are_refused_where_they_are_made():
    with pytest.raises(ValueError, match="radius"):
        rigid.sphere(-1.0, mass=1.0)
    with pytest.raises(ValueError, match="mass"):
        rigid.box([1, 1, 1])  # neither mass nor density
    with pytest.raises(ValueError, match="colour"):
        rigid.box([1, 1, 1], mass=1.0, colour="red")
    with pytest.raises(TypeError, match="spec"):
        rigid.mass_properties(3.0)


def test_spatial_inertia_is_the_notes_formula():
    c, I = np.array([0.1, -0.2, 0.3]), np.diag([0.01, 0.02, 0.025])
    G = rigid.spatial_inertia(2.0, c, I)
    skew = np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])
    ref = np.block([[I + 2.0 * skew.T @ skew, 2.0 * skew], [2.0 * skew.T, 2.0 * np.eye(3)]])
    assert np.allclose(G, ref, atol=1e-15)
    with pytest.raises(ValueError, match="mass"):
        rigid.spatial_inertia(-1.0)


def test_simulate_body_conserves_momentum_and_flips_the_racket():
    racket = os.path.join(ROOT, "examples", "racket.toml")
    # x is the intermediate principal axis of this box (0.3 x 0.6 x 0.03 m)
    tr = rigid.simulate_body(racket, omega=[3.0, 0.01, 0.01], duration=6.0, dt=1e-3)
    n = 6001
    assert tr["t"].shape == (n,) and tr["quaternion"].shape == (n, 4)
    assert tr["position"].shape == tr["omega"].shape == tr["velocity"].shape == (n, 3)
    assert np.allclose(np.linalg.norm(tr["quaternion"], axis=1), 1.0, atol=1e-12)
    e = tr["energy"]
    assert np.max(np.abs(e - e[0])) / e[0] < 1e-6
    # the tennis-racket flip: the spin about the intermediate axis reverses
    assert tr["omega"][:, 0].min() < -2.9
    with pytest.raises(ValueError, match="dt"):
        rigid.simulate_body(racket, dt=0.0)
    with pytest.raises(ValueError, match="integrator"):
        rigid.simulate_body(racket, integrator="euler")


def test_simulate_body_free_fall_and_pivot():
    ball = rigid.sphere(0.1, mass=1.0)
    tr = rigid.simulate_body(ball, velocity=[1.0, 0, 0], gravity=[0, 0, -9.81], duration=1.0,
                             dt=1e-3, integrator="rk4")
    assert np.allclose(tr["position"][-1], [1.0, 0.0, -9.81 / 2], atol=1e-9)
    top = os.path.join(ROOT, "examples", "top.toml")
    tr = rigid.simulate_body(top, pivot=[0, 0, 0], omega=[0, 0.5, 100], gravity=[0, 0, -9.81],
                             duration=0.5, dt=1e-4)
    assert np.all(np.isfinite(tr["quaternion"]))
    with pytest.raises(ValueError, match="pivot"):
        rigid.simulate_body(top, pivot=[0, 0, 0], velocity=[1, 0, 0])


def test_doctor_returns_the_json_report_as_dicts(tmp_path):
    anymal = [f for f in every_urdf() if f.endswith("anymal_b_simple_description/robots/anymal.urdf")][0]
    report = rigid.doctor(anymal)
    assert set(report) >= {"robot", "bodies"} and report["robot"] == "anymal"
    body = report["bodies"][0]
    assert {"name", "line", "status", "findings", "likely_cause", "explanation",
            "repair"} <= set(body)
    # a 1.5 kg box of 5 x 5 x 20 cm with its mass written in grams
    grams = tmp_path / "grams.urdf"
    grams.write_text("""<robot name="g"><link name="base"/>
      <link name="arm"><inertial><origin xyz="0 0 0.1"/><mass value="1500"/>
        <inertia ixx="0.0053125" iyy="0.0053125" izz="0.000625" ixy="0" ixz="0" iyz="0"/>
        </inertial>
        <visual><origin xyz="0 0 0.1"/><geometry><box size="0.05 0.05 0.2"/></geometry></visual>
      </link>
      <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
        <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    </robot>""")
    fixed = tmp_path / "fixed.urdf"
    report = rigid.doctor(str(grams), fix=str(fixed))
    arm = [b for b in report["bodies"] if b["name"] == "arm"][0]
    assert arm["status"] != "ok" and arm["likely_cause"] == "units_grams"
    fixed_arm = [b for b in rigid.doctor(fixed)["bodies"] if b["name"] == "arm"][0]
    assert fixed_arm["status"] == "ok"


def test_doctor_reads_sdf_and_fixes_it_in_sdf(tmp_path):
    # a 48 kg box of 0.2 x 0.4 x 0.6 m whose izz is written ten times too large
    box = tmp_path / "box.sdf"
    box.write_text("""<?xml version="1.0"?><sdf version="1.9"><model name="m">
      <link name="b"><inertial><mass>48</mass>
        <inertia><ixx>2.08</ixx><iyy>1.6</iyy><izz>8</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>0.2 0.4 0.6</size></box></geometry></collision>
      </link></model></sdf>""")
    fixed = tmp_path / "fixed.sdf"
    b = rigid.doctor(box, fix=fixed)["bodies"][0]
    assert b["status"] == "invalid" and b["likely_cause"] == "digit_typo"
    assert rigid.doctor(fixed)["bodies"][0]["status"] == "ok"
    assert "<izz>0.8</izz>" in fixed.read_text()
    assert rigid.Model.from_file(str(fixed)).nv == 6


def test_doctor_warns_what_its_fix_cannot_do(tmp_path):
    # MuJoCo ignores every <inertial> under inertiafromgeom="true": the fix says so
    xml = tmp_path / "geoms.xml"
    xml.write_text("""<mujoco><compiler inertiafromgeom="true"/><worldbody>
      <body name="b"><joint/><inertial pos="0 0 0" mass="1" diaginertia="0.05 0.05 0.05"/>
        <geom type="box" size="0.1 0.1 0.1"/></body></worldbody></mujoco>""")
    with pytest.warns(UserWarning, match="inertiafromgeom"):
        rigid.doctor(xml, fix=tmp_path / "fixed.xml")


def test_mass_properties_and_doctor_equal_the_command_line_json():
    p, ref = rigid.mass_properties(COMPOUND), cli("mass", COMPOUND)
    assert set(ref) <= set(p)
    for k, v in ref.items():
        assert np.array_equal(np.asarray(p[k]) + 0.0, np.asarray(v)), k
    anymal = [f for f in every_urdf() if f.endswith("anymal_b_simple_description/robots/anymal.urdf")][0]
    assert rigid.doctor(anymal) == cli("doctor", anymal)
