"""rigid.mobile against the Modern Robotics code library (modern_robotics, skipped without it):
the capstone's milestone 3 (its published numbers and random cases), FKinBody/JacobianBody,
ScrewTrajectory; and the book's H for each base, odometry, a capstone run, bad input."""

import numpy as np
import pytest

import rigid.mobile as mobile

mr = pytest.importorskip("modern_robotics")

BLIST = np.array(
    [
        [0, 0, 1, 0, 0.033, 0],
        [0, -1, 0, -0.5076, 0, 0],
        [0, -1, 0, -0.3526, 0, 0],
        [0, -1, 0, -0.2176, 0, 0],
        [0, 0, 1, 0, 0, 0],
    ]
).T
M0E = np.array([[1, 0, 0, 0.033], [0, 1, 0, 0], [0, 0, 1, 0.6546], [0, 0, 0, 1.0]])
TB0 = np.array([[1, 0, 0, 0.1662], [0, 1, 0, 0], [0, 0, 1, 0.0026], [0, 0, 0, 1.0]])


def mr_feedback(X, Xd, Xdn, Kp, theta, dt=0.01):
    """Milestone 3 from the library's functions (Ki = 0)."""
    r, l, w = 0.0475, 0.235, 0.15
    F = r / 4 * np.array([[-1 / (l + w), 1 / (l + w), 1 / (l + w), -1 / (l + w)], [1, 1, 1, 1], [-1, 1, -1, 1]])
    F6 = np.vstack([np.zeros((2, 4)), F, np.zeros((1, 4))])
    T0e = mr.FKinBody(M0E, BLIST, theta)
    Je = np.hstack([mr.Adjoint(mr.TransInv(T0e) @ mr.TransInv(TB0)) @ F6, mr.JacobianBody(BLIST, theta)])
    Xerr = mr.se3ToVec(mr.MatrixLog6(mr.TransInv(X) @ Xd))
    Vd = mr.se3ToVec(mr.MatrixLog6(mr.TransInv(Xd) @ Xdn)) / dt
    V = mr.Adjoint(mr.TransInv(X) @ Xd) @ Vd + Kp @ Xerr
    return V, np.linalg.pinv(Je) @ V, Xerr, Je


def test_milestone3_equals_the_code_library():
    youbot = mobile.MobileManipulator.youbot()
    theta = np.array([0, 0, 0.2, -1.6, 0])
    X = youbot.forward([0, 0, 0], theta)
    Tsb = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.0963], [0, 0, 0, 1.0]])
    np.testing.assert_allclose(X, Tsb @ TB0 @ mr.FKinBody(M0E, BLIST, theta), atol=1e-12)
    Xd = np.array([[0, 0, 1, 0.5], [0, 1, 0, 0], [-1, 0, 0, 0.5], [0, 0, 0, 1.0]])
    Xdn = np.array([[0, 0, 1, 0.6], [0, 1, 0, 0], [-1, 0, 0, 0.3], [0, 0, 0, 1.0]])
    for kp, V_pub, u_pub in [
        (0.0, [0, 0, 0, 21.409, 0, 6.455], [157.2] * 4 + [0, -652.9, 1398.6, -745.7, 0]),
        (1.0, [0, 0.171, 0, 21.488, 0, 6.562], [157.5] * 4 + [0, -654.3, 1400.9, -746.8, 0]),
    ]:
        V, speeds, Xerr = youbot.feedback(X, Xd, Xdn, kp, 0.0, 0.01, theta)
        V_mr, speeds_mr, Xerr_mr, Je = mr_feedback(X, Xd, Xdn, kp * np.eye(6), theta)
        np.testing.assert_allclose(youbot.jacobian(theta), Je, atol=1e-12)
        np.testing.assert_allclose(V, V_mr, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(speeds, speeds_mr, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(Xerr, Xerr_mr, atol=1e-12)
        # the course's published (rounded) answers
        np.testing.assert_allclose(np.round(V, 3), V_pub, atol=1e-12)
        np.testing.assert_allclose(np.round(speeds, 1), u_pub, atol=1e-12)
    np.testing.assert_allclose(np.round(Xerr, 3), [0, 0.171, 0, 0.080, 0, 0.107], atol=1e-12)


def test_random_steps_and_poe_equal_the_code_library():
    rng = np.random.default_rng(7)
    youbot = mobile.MobileManipulator.youbot()
    for _ in range(5):
        theta = rng.uniform(-1.5, 1.5, 5)
        q = rng.uniform(-1, 1, 3)
        X = youbot.forward(q, theta)
        Xd = X @ mr.MatrixExp6(mr.VecTose3(rng.normal(size=6) * 0.1))
        Xdn = Xd @ mr.MatrixExp6(mr.VecTose3(rng.normal(size=6) * 0.01))
        V, speeds, _ = youbot.feedback(X, Xd, Xdn, 2.0, 0.0, 0.01, theta)
        V_mr, speeds_mr, _, _ = mr_feedback(X, Xd, Xdn, 2.0 * np.eye(6), theta)
        np.testing.assert_allclose(V, V_mr, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(speeds, speeds_mr, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(mobile.fkin_body(M0E, BLIST, theta), mr.FKinBody(M0E, BLIST, theta), atol=1e-12)
        np.testing.assert_allclose(mobile.jacobian_body(BLIST, theta), mr.JacobianBody(BLIST, theta), atol=1e-12)
        S = mr.Adjoint(M0E) @ BLIST
        np.testing.assert_allclose(mobile.fkin_space(M0E, S, theta), mr.FKinSpace(M0E, S, theta), atol=1e-12)
        np.testing.assert_allclose(mobile.jacobian_space(S, theta), mr.JacobianSpace(S, theta), atol=1e-12)


def test_the_books_bases_and_odometry():
    r, l, w = 0.05, 0.3, 0.2
    H0 = np.array([[-l - w, 1, -1], [l + w, 1, 1], [l + w, 1, -1], [-l - w, 1, 1]]) / r
    base = mobile.Base.mecanum(r, l, w)
    phi = 0.7
    R = np.array([[1, 0, 0], [0, np.cos(phi), np.sin(phi)], [0, -np.sin(phi), np.cos(phi)]])
    np.testing.assert_allclose(base.H(phi), H0 @ R, atol=1e-12)
    np.testing.assert_allclose(base.F, np.linalg.pinv(H0), atol=1e-12)
    # odometry: sideways by r for the wheels (-1, 1, -1, 1)
    np.testing.assert_allclose(base.odometry([0, 0, 0], [-1, 1, -1, 1]), [0, 0, r], atol=1e-15)
    dd = mobile.Base.diff_drive(0.1, 0.5)
    assert dd.kind == "nonholonomic" and base.kind == "omnidirectional"
    np.testing.assert_allclose(dd.constraint([0.3, 0, 0]), [0, np.sin(0.3), -np.cos(0.3)])
    assert base.constraint([0, 0, 0]) is None


def test_a_capstone_run_converges():
    run = mobile.capstone()
    assert run["states"].shape[1] == 13 and run["reference"].shape[1] == 13
    err = np.linalg.norm(run["errors"], axis=1)
    assert err[0] > 0.3 and err[int(5 / run["dt"]):].max() < 1e-3
    ref = mobile.pick_and_place(np.array([[0, 0, 1, 0], [0, 1, 0, 0], [-1, 0, 0, 0.5], [0, 0, 0, 1.0]]))
    np.testing.assert_allclose(ref, run["reference"], atol=1e-12)


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="rank 2"):
        mobile.Base.mecanum(0.05, 0.0, 0.0)
    with pytest.raises(ValueError, match="wheel 0"):
        mobile.Base.omni3(-0.05, 0.2)
    youbot = mobile.MobileManipulator.youbot()
    with pytest.raises(ValueError, match="theta"):
        youbot.jacobian([0, 0, 0])
    with pytest.raises(ValueError, match="homogeneous"):
        youbot.feedback(np.eye(3), np.eye(4), np.eye(4), 1.0, 0.0, 0.01, np.zeros(5))
    with pytest.raises(ValueError, match="dt"):
        youbot.feedback(np.eye(4), np.eye(4), np.eye(4), 1.0, 0.0, 0.0, np.zeros(5))
    # NaN and infinities are refused, never passed through
    with pytest.raises(ValueError, match="phi"):
        mobile.Base.mecanum(0.05, 0.2, 0.2).H(float("nan"))
    with pytest.raises(ValueError, match="non-finite"):
        mobile.fkin_body(M0E, BLIST, [0, np.nan, 0, 0, 0])
    bad = TB0.copy()
    bad[0, 3] = np.inf
    with pytest.raises(ValueError, match="T_b0"):
        mobile.MobileManipulator(mobile.Base.mecanum(0.05, 0.2, 0.2), bad, M0E, BLIST)
    with pytest.raises(ValueError, match="non-finite"):
        mobile.pick_and_place(np.array([[1, 0, 0, np.nan], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]))


def test_drive_rolls_as_the_kinematic_model_says():
    import pathlib

    urdf = pathlib.Path(__file__).resolve().parents[3] / "examples" / "diff_drive.urdf"
    run = mobile.drive(str(urdf), ["left_wheel_joint", "right_wheel_joint"], [5.0, 7.0], time=2.0)
    base = mobile.Base.diff_drive(0.08, 0.36)
    late = run["t"] >= 0.5
    model = np.array([base.body_twist(u) for u in run["wheel_speeds"][late]])
    np.testing.assert_allclose(run["omega"][late], model[:, 0], rtol=0.02)
    np.testing.assert_allclose(run["v"][late], model[:, 1], rtol=0.02)
    assert run["q"].shape == (len(run["t"]), 7 + 4)
    with pytest.raises(ValueError, match="no joint"):
        mobile.drive(str(urdf), ["left_wheel"], [1.0])
