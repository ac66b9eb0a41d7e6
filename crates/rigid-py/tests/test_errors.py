"""Bad input raises a clear Python exception naming the argument (and the expected and given
length), never a crash and never a NaN result."""

import os
import subprocess
import sys

import numpy as np
import pytest

import rigid
from conftest import pair

PUMA = rigid.Model.builtin("puma560")
Z = np.zeros(6)


def test_wrong_lengths_name_the_argument_and_both_lengths():
    d = PUMA.create_data()
    with pytest.raises(ValueError, match=r"rnea: q has 5 entries, expected nq = 6"):
        rigid.rnea(PUMA, d, [0] * 5, Z, Z)
    with pytest.raises(ValueError, match=r"rnea: a has 7 entries, expected nv = 6"):
        rigid.rnea(PUMA, d, Z, Z, np.zeros(7))
    with pytest.raises(ValueError, match=r"aba: tau has 0 entries, expected nv = 6"):
        rigid.aba(PUMA, d, Z, Z, [])
    with pytest.raises(ValueError, match=r"difference: q1 has 3 entries, expected nq = 6"):
        rigid.difference(PUMA, Z, Z[:3])
    with pytest.raises(ValueError, match=r"integrate: v has 2 entries"):
        rigid.integrate(PUMA, Z, [1, 2])


def test_pinocchio_layout_lengths_are_pinocchios():
    m = pair("all_joints").rp
    assert m.nq == pair("all_joints").pm.nq
    with pytest.raises(ValueError, match=rf"q has {m.nq - 1} entries, expected nq = {m.nq}"):
        rigid.rnea(m, m.create_data(), np.zeros(m.nq - 1), np.zeros(m.nv), np.zeros(m.nv))


def test_wrong_dtype_and_types_are_type_errors_naming_the_argument():
    d = PUMA.create_data()
    with pytest.raises(TypeError, match=r"rnea: q must hold real numbers .*complex128"):
        rigid.rnea(PUMA, d, Z.astype(complex), Z, Z)
    with pytest.raises(TypeError, match=r"rnea: v must .*string"):
        rigid.rnea(PUMA, d, Z, "abcdef", Z)
    with pytest.raises(TypeError, match=r"rnea: a must be a sequence"):
        rigid.rnea(PUMA, d, Z, Z, [1, 2, "x", 4, 5, 6])
    with pytest.raises(TypeError, match=r"rnea: a must hold real numbers"):
        rigid.rnea(PUMA, d, Z, Z, np.array(["a"] * 6))
    with pytest.raises(TypeError, match=r"crba: q must be a sequence"):
        rigid.crba(PUMA, d, None)
    with pytest.raises(ValueError, match=r"rnea: q must be a vector .*shape \(2, 3\)"):
        rigid.rnea(PUMA, d, np.zeros((2, 3)), Z, Z)
    with pytest.raises(TypeError):
        rigid.rnea(PUMA, "not data", Z, Z, Z)


def test_other_real_dtypes_and_layouts_are_accepted():
    d = PUMA.create_data()
    q = np.linspace(-1, 1, 6)
    ref = rigid.rnea(PUMA, d, q, Z, Z)
    assert ref.dtype == np.float64
    assert np.array_equal(rigid.rnea(PUMA, d, list(q), [0] * 6, (0,) * 6), ref)
    assert np.array_equal(rigid.rnea(PUMA, d, q.reshape(6, 1), Z, Z), ref)
    assert np.array_equal(rigid.rnea(PUMA, d, np.repeat(q, 2)[::2], Z, Z), ref)
    q32 = q.astype(np.float32)
    assert np.array_equal(rigid.rnea(PUMA, d, q32, Z, Z), rigid.rnea(PUMA, d, q32.astype(float),
                                                                    Z, Z))
    assert np.array_equal(rigid.gravity(PUMA, d, np.zeros(6, int)), rigid.gravity(PUMA, d, Z))


def test_results_are_fresh_arrays():
    d = PUMA.create_data()
    a = rigid.rnea(PUMA, d, Z, Z, Z)
    b = rigid.rnea(PUMA, d, Z + 0.1, Z, Z)
    assert not np.shares_memory(a, b) and not np.array_equal(a, b)
    a[:] = 1.0
    assert not np.array_equal(rigid.rnea(PUMA, d, Z, Z, Z), a)


def test_nan_and_bad_quaternions_are_value_errors():
    d = PUMA.create_data()
    q = Z.copy()
    q[3] = np.nan
    with pytest.raises(ValueError, match=r"rnea: q\[3\] is not finite"):
        rigid.rnea(PUMA, d, q, Z, Z)
    with pytest.raises(ValueError, match=r"aba: tau\[0\] is not finite"):
        rigid.aba(PUMA, d, Z, Z, [np.inf, 0, 0, 0, 0, 0])
    p = pair("anymal")
    m, pm = p.rp, p.pm
    q, v = p.states[0][0].copy(), np.zeros(m.nv)
    v[0] = np.nan
    with pytest.raises(ValueError, match=r"nle: v\[0\] is not finite"):
        rigid.nle(m, m.create_data(), q, v)
    q[3:7] = [0, 0, 0, 2.0]
    with pytest.raises(ValueError, match=r"root_joint.*quaternion norm 2"):
        rigid.crba(m, m.create_data(), q)
    aj = pair("all_joints").rp
    q = rigid.neutral(aj)
    k = aj.idx_qs[aj.joint_types.index("continuous")]
    q[k:k + 2] = [3.0, 0.0]
    with pytest.raises(ValueError, match=r"\(cos θ, sin θ\) = \(3, 0\) has norm 3"):
        rigid.gravity(aj, aj.create_data(), q)


def test_missing_and_malformed_files(tmp_path):
    with pytest.raises(FileNotFoundError, match="no_such.urdf"):
        rigid.Model.from_urdf(str(tmp_path / "no_such.urdf"))
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='r'><link name='a'></robot>")
    with pytest.raises(ValueError, match=r"bad.urdf.*malformed XML at line 1"):
        rigid.Model.from_urdf(bad)
    wrong = tmp_path / "wrong.urdf"
    wrong.write_text("<robot name='r'>\n<link name='a'/>\n<link name='b'/>\n"
                     "<joint name='j' type='screw'><parent link='a'/><child link='b'/></joint>\n"
                     "</robot>")
    with pytest.raises(ValueError, match=r"line 4: joint \"j\""):
        rigid.Model.from_urdf(wrong)
    with pytest.raises(ValueError, match=r"inertia: unknown inertia policy"):
        rigid.Model.from_urdf(wrong, inertia="lenient")
    with pytest.raises(ValueError, match=r"layout must be \"rigid\", \"pinocchio\" or \"mujoco\""):
        rigid.Model.from_urdf(wrong, layout="drake")
    with pytest.raises(ValueError, match=r"unknown model \"puma\" .*puma560"):
        rigid.Model.builtin("puma")
    with pytest.raises(FileNotFoundError):
        rigid.mass_properties(str(tmp_path / "none.toml"))
    with pytest.raises(FileNotFoundError):
        rigid.doctor(tmp_path / "none.urdf")


def test_unknown_names_and_foreign_data():
    d = PUMA.create_data()
    with pytest.raises(ValueError, match=r"jacobian: no frame named \"hand\""):
        rigid.jacobian(PUMA, d, Z, "hand")
    with pytest.raises(ValueError, match=r"jacobian: the reference frame must be \"local\""):
        rigid.jacobian(PUMA, d, Z, "link6", frame="mars")
    with pytest.raises(ValueError, match=r"Data.placement: no frame named"):
        d.placement("nowhere")
    other = rigid.Model.builtin("puma560_armature")
    with pytest.raises(ValueError, match=r"data was made for model 'puma560.*create_data"):
        rigid.rnea(other, d, Z, Z, Z)
    with pytest.raises(ValueError, match=r"gravity\[2\] is not finite"):
        PUMA.gravity = [0, 0, np.nan]
    with pytest.raises(ValueError, match=r"a given without v"):
        rigid.forward_kinematics(PUMA, d, Z, None, Z)


def test_a_singular_mass_matrix_is_a_value_error_not_nan(tmp_path):
    urdf = tmp_path / "massless.urdf"
    urdf.write_text("""<robot name="massless"><link name="a"/><link name="b"/>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>""")
    with pytest.warns(rigid.UrdfWarning, match="zero mass"):
        m = rigid.Model.from_urdf(urdf)
    d = m.create_data()
    assert np.array_equal(rigid.rnea(m, d, [0.5], [1.0], [1.0]), [0.0])
    with pytest.raises(ValueError, match=r"aba: mass matrix is not positive definite"):
        rigid.aba(m, d, [0.5], [1.0], [1.0])
    with pytest.raises(ValueError, match=r"minverse: mass matrix is not positive definite"):
        rigid.minverse(m, d, [0.5])
    assert m.warnings and "zero mass" in m.warnings[0]


def test_the_readme_one_liner_works_in_a_fresh_interpreter():
    code = ("import rigid; m = rigid.Model.builtin('puma560'); "
            "print(rigid.rnea(m, m.create_data(), [0]*6, [0]*6, [0]*6))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=os.path.dirname(__file__), check=True)
    tau = np.array(out.stdout.strip().strip("[]").split(), dtype=float)
    d = PUMA.create_data()
    assert np.array_equal(tau.round(6), rigid.gravity(PUMA, d, Z).round(6))
    assert abs(tau[1]) > 1.0  # the shoulder holds the arm up
