"""Every verb against Pinocchio's Python module, to 1e-9, in both layouts.

With layout="pinocchio" the raw arrays must equal Pinocchio's (no reordering); with rigid's own
layout they must equal Pinocchio's once mapped joint by joint (by name: rigid keeps the file's
sibling order, angular-first free-flyer blocks and one angle per continuous joint).
"""

import json
import warnings

import numpy as np
import pytest

pin = pytest.importorskip("pinocchio")

import rigid
from conftest import assert_close, cli, every_urdf, pair, rel_err, symmetric, TOL

RFS = [("world_aligned", pin.LOCAL_WORLD_ALIGNED), ("body", pin.LOCAL), ("spatial", pin.WORLD)]
SWAP = [3, 4, 5, 0, 1, 2]  # rigid's Jacobian rows (ω, v) from Pinocchio's (v, ω)


def test_layout_pinocchio_has_pinocchio_sizes_names_and_indices(robot):
    pm, m = robot.pm, robot.rp
    assert (m.nq, m.nv, m.njoints) == (pm.nq, pm.nv, pm.njoints - 1)
    assert m.names == list(pm.names)[1:]
    assert m.idx_qs == [pm.joints[i].idx_q for i in range(1, pm.njoints)]
    assert m.nqs == [pm.joints[i].nq for i in range(1, pm.njoints)]
    assert m.idx_vs == [pm.joints[i].idx_v for i in range(1, pm.njoints)]
    assert np.array_equal(m.gravity, pm.gravity.linear)


def test_dynamics_layout_pinocchio_raw_arrays_equal_pinocchio(robot):
    pm, pd, m = robot.pm, robot.pd, robot.rp
    d = m.create_data()
    for q, v, a, tau in robot.states:
        assert_close(rigid.rnea(m, d, q, v, a), pin.rnea(pm, pd, q, v, a), "rnea")
        assert_close(rigid.crba(m, d, q), symmetric(pin.crba(pm, pd, q)), "crba")
        assert_close(rigid.aba(m, d, q, v, tau), pin.aba(pm, pd, q, v, tau), "aba")
        assert_close(rigid.nle(m, d, q, v), pin.nonLinearEffects(pm, pd, q, v), "nle")
        assert_close(rigid.gravity(m, d, q), pin.computeGeneralizedGravity(pm, pd, q), "g")
        assert_close(rigid.minverse(m, d, q), symmetric(pin.computeMinverse(pm, pd, q)),
                     "minverse")
        assert_close(rigid.coriolis_matrix(m, d, q, v), pin.computeCoriolisMatrix(pm, pd, q, v),
                     "coriolis_matrix")
        assert_close(rigid.com(m, d, q), pin.centerOfMass(pm, pd, q), "com")
        assert_close(rigid.kinetic_energy(m, d, q, v), pin.computeKineticEnergy(pm, pd, q, v),
                     "kinetic_energy")
        assert_close(rigid.potential_energy(m, d, q), pin.computePotentialEnergy(pm, pd, q),
                     "potential_energy")


def test_data_fields_are_pinocchios_in_its_layout(robot):
    """`rigid.Data`'s fields (Pinocchio's names) after each algorithm, in Pinocchio's layout,
    against Pinocchio's Data (oMi without the universe; M symmetric in rigid)."""
    pm, pd, m = robot.pm, robot.pd, robot.rp
    d = m.create_data()
    q, v, a, tau = robot.states[0]
    rigid.rnea(m, d, q, v, a)
    pin.rnea(pm, pd, q, v, a)
    assert_close(d.tau, pd.tau, "data.tau")
    assert_close(d.v, np.array([x.vector for x in pd.v[1:]]), "data.v")
    assert_close(d.f, np.array([x.vector for x in pd.f[1:]]), "data.f")
    rigid.forward_kinematics(m, d, q)
    pin.forwardKinematics(pm, pd, q)
    assert_close(d.oMi, np.array([x.homogeneous for x in pd.oMi[1:]]), "data.oMi")
    assert_close(d.q_in, q, "data.q_in")
    rigid.crba(m, d, q)
    assert_close(d.M, symmetric(pin.crba(pm, pd, q)), "data.M")
    rigid.aba(m, d, q, v, tau)
    assert_close(d.ddq, pin.aba(pm, pd, q, v, tau), "data.ddq")
    rigid.nle(m, d, q, v)
    assert_close(d.nle, pin.nonLinearEffects(pm, pd, q, v), "data.nle")
    rigid.com(m, d, q)
    pin.centerOfMass(pm, pd, q)
    assert_close(d.com, pd.com[0], "data.com")


def test_dynamics_rigid_layout_equal_pinocchio_mapped_by_joint_name(robot):
    pm, pd, m = robot.pm, robot.pd, robot.rr
    d = m.create_data()
    V, M = robot.v_rigid, robot.m_rigid
    for q, v, a, tau in robot.states:
        qr, vr, ar, tr = robot.q_rigid(q), V(v), V(a), V(tau)
        assert_close(rigid.rnea(m, d, qr, vr, ar), V(pin.rnea(pm, pd, q, v, a)), "rnea")
        assert_close(rigid.crba(m, d, qr), M(symmetric(pin.crba(pm, pd, q))), "crba")
        assert_close(rigid.aba(m, d, qr, vr, tr), V(pin.aba(pm, pd, q, v, tau)), "aba")
        assert_close(rigid.nle(m, d, qr, vr), V(pin.nonLinearEffects(pm, pd, q, v)), "nle")
        assert_close(rigid.gravity(m, d, qr), V(pin.computeGeneralizedGravity(pm, pd, q)), "g")
        assert_close(rigid.minverse(m, d, qr), M(symmetric(pin.computeMinverse(pm, pd, q))),
                     "minverse")
        assert_close(rigid.coriolis_matrix(m, d, qr, vr),
                     M(pin.computeCoriolisMatrix(pm, pd, q, v)), "coriolis_matrix")
        assert_close(rigid.com(m, d, qr), pin.centerOfMass(pm, pd, q), "com")
        assert_close(rigid.kinetic_energy(m, d, qr, vr), pin.computeKineticEnergy(pm, pd, q, v),
                     "kinetic_energy")
        assert_close(rigid.potential_energy(m, d, qr), pin.computePotentialEnergy(pm, pd, q),
                     "potential_energy")


def frames_to_check(pm, m):
    """Pinocchio's BODY frames (URDF links) whose name rigid resolves to that link: not a joint
    name, and one frame of that name."""
    names = m.frame_names
    return [(i, f.name) for i, f in enumerate(pm.frames)
            if f.type == pin.FrameType.BODY and f.name not in m.names
            and names.count(f.name) == 1]


@pytest.mark.parametrize("layout", ["pinocchio", "rigid"])
def test_placements_and_jacobians_equal_pinocchio(robot, layout):
    pm, pd = robot.pm, robot.pd
    m = robot.rp if layout == "pinocchio" else robot.rr
    d = m.create_data()
    frames = frames_to_check(pm, m)
    for q, v, a, _ in robot.states[:2]:
        qm = q if layout == "pinocchio" else robot.q_rigid(q)
        rigid.forward_kinematics(m, d, qm)
        pin.forwardKinematics(pm, pd, q)
        pin.updateFramePlacements(pm, pd)
        for i in range(1, pm.njoints):
            R, p = d.placement(pm.names[i])
            assert_close(R, pd.oMi[i].rotation, f"placement {pm.names[i]}")
            assert_close(p, pd.oMi[i].translation, f"placement {pm.names[i]}")
        for fid, name in frames:
            R, p = d.placement(name)
            assert_close(R, pd.oMf[fid].rotation, f"placement of frame {name}")
            assert_close(p, pd.oMf[fid].translation, f"placement of frame {name}")
        pin.computeJointJacobians(pm, pd, q)
        for rf_name, rf in RFS:
            for i in range(1, pm.njoints):
                ref = pin.getJointJacobian(pm, pd, i, rf)
                if layout == "rigid":
                    ref = ref[SWAP][:, robot.v_map]
                J = rigid.jacobian(m, d, qm, pm.names[i], frame=rf_name)
                assert_close(J, ref, f"jacobian {pm.names[i]} {rf_name}")
            for fid, name in frames[:5]:
                ref = pin.computeFrameJacobian(pm, pd, q, fid, rf)
                if layout == "rigid":
                    ref = ref[SWAP][:, robot.v_map]
                assert_close(rigid.jacobian(m, d, qm, name, rf_name), ref,
                             f"jacobian of frame {name} {rf_name}")


def test_jacobian_accepts_pinocchio_reference_frames(robot):
    pm, m = robot.pm, robot.rp
    d = m.create_data()
    q = robot.states[0][0]
    name = m.names[-1]
    for rf_name, rf in RFS:
        assert np.array_equal(rigid.jacobian(m, d, q, name, rf), rigid.jacobian(m, d, q, name,
                                                                               rf_name))


def test_configuration_verbs_layout_pinocchio_equal_pinocchio(robot):
    pm, m = robot.pm, robot.rp
    assert np.array_equal(rigid.neutral(m), pin.neutral(pm))
    for (q0, v, _, _), (q1, _, _, _) in zip(robot.states, robot.states[1:]):
        assert_close(rigid.integrate(m, q0, v), pin.integrate(pm, q0, v), "integrate")
        assert_close(rigid.integrate(m, q0, 4.0 * v), pin.integrate(pm, q0, 4.0 * v),
                     "integrate (large step)")
        assert_close(rigid.difference(m, q0, q1), pin.difference(pm, q0, q1), "difference")


def same_configuration(m, q, ref):
    """Rigid-layout configurations equal up to the sign of each quaternion and 2π per angle."""
    for t, iq, nq in zip(m.joint_types, m.idx_qs, m.nqs):
        a, b = q[iq:iq + nq], ref[iq:iq + nq]
        if t in ("free_flyer", "spherical"):
            o = 3 if t == "free_flyer" else 0
            if np.dot(a[o:], b[o:]) < 0:
                b = np.concatenate([b[:o], -b[o:]])
        elif t in ("continuous", "planar"):
            k = 0 if t == "continuous" else 2
            b = b.copy()
            b[k] = a[k] + np.arctan2(np.sin(b[k] - a[k]), np.cos(b[k] - a[k]))
        assert rel_err(a, b) <= TOL, f"joint {t} at q[{iq}]: {a} != {b}"


def test_configuration_verbs_rigid_layout_equal_pinocchio_mapped(robot):
    pm, m = robot.pm, robot.rr
    assert np.array_equal(rigid.neutral(m), robot.q_rigid(pin.neutral(pm)))
    for (q0, v, _, _), (q1, _, _, _) in zip(robot.states, robot.states[1:]):
        qr0, qr1 = robot.q_rigid(q0), robot.q_rigid(q1)
        same_configuration(m, rigid.integrate(m, qr0, robot.v_rigid(v)),
                           robot.q_rigid(pin.integrate(pm, q0, v)))
        # rigid's difference does not wrap angles (θ1 - θ0): both reach q1 from q0
        ref = robot.v_rigid(pin.difference(pm, q0, q1))
        got = rigid.difference(m, qr0, qr1)
        same_configuration(m, rigid.integrate(m, qr0, got), qr1)
        same_configuration(m, rigid.integrate(m, qr0, ref), qr1)


def test_random_configuration_is_within_limits_and_seeded(robot):
    m = robot.rp
    rigid.seed(7)
    a = rigid.random_configuration(m)
    rigid.seed(7)
    b = rigid.randomConfiguration(m)
    assert np.array_equal(a, b) and a.shape == (m.nq,)
    d = m.create_data()
    assert np.all(np.isfinite(rigid.rnea(m, d, a, np.zeros(m.nv), np.zeros(m.nv))))


def test_pinocchio_aliases_are_the_same_verbs():
    for alias, name in [("nonLinearEffects", "nle"), ("computeGeneralizedGravity", "gravity"),
                        ("computeMinverse", "minverse"), ("centerOfMass", "com"),
                        ("computeCoriolisMatrix", "coriolis_matrix"),
                        ("forwardKinematics", "forward_kinematics"),
                        ("computeKineticEnergy", "kinetic_energy"),
                        ("computePotentialEnergy", "potential_energy")]:
        assert getattr(rigid, alias) is getattr(rigid, name)


def test_gravity_is_settable_and_used():
    m = rigid.Model.builtin("puma560")
    d = m.create_data()
    q = np.array([0.1, 0.2, -0.3, 0.4, 0.5, 0.6])
    g0 = rigid.gravity(m, d, q)
    m.gravity = [0.0, 0.0, -2 * 9.81]
    assert np.array_equal(m.gravity, [0.0, 0.0, -19.62])
    assert_close(rigid.gravity(m, d, q), 2 * g0, "gravity doubled")
    m.gravity = np.zeros(3)
    assert np.all(rigid.gravity(m, d, q) == 0)


def every_erd_file():
    return [(f, fl) for f in every_urdf() for fl in (False, True)]


def test_every_example_robot_data_urdf_layout_pinocchio_equals_pinocchio():
    """Every URDF of example-robot-data that Pinocchio loads, fixed and floating: nq, nv, the
    joint names and the raw rnea, crba and aba arrays equal Pinocchio's."""
    compared, failures = 0, []
    for path, floating in every_erd_file():
        try:
            pm = (pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating
                  else pin.buildModelFromUrdf(path))
        except Exception:  # noqa: BLE001 (Pinocchio refuses it: not compared)
            continue
        tag = f"{path.split('/robots/')[-1]}{' (floating)' if floating else ''}"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", rigid.UrdfWarning)
            m = rigid.Model.from_urdf(path, floating=floating, layout="pinocchio")
        if (m.nq, m.nv) != (pm.nq, pm.nv) or m.names != list(pm.names)[1:]:
            failures.append(f"{tag}: sizes or joint order differ")
            continue
        pd, d = pm.createData(), m.create_data()
        lo, up = pm.lowerPositionLimit, pm.upperPositionLimit
        pm.lowerPositionLimit = np.where(np.abs(lo) < 1e10, lo, -1.0)
        pm.upperPositionLimit = np.where(np.abs(up) < 1e10, up, 1.0)
        pin.seed(1)
        rng = np.random.default_rng(1)
        for _ in range(2):
            q = pin.randomConfiguration(pm)
            v, a = rng.uniform(-1, 1, pm.nv), rng.uniform(-1, 1, pm.nv)
            M = symmetric(pin.crba(pm, pd, q))
            errs = {"rnea": rel_err(rigid.rnea(m, d, q, v, a), pin.rnea(pm, pd, q, v, a)),
                    "crba": rel_err(rigid.crba(m, d, q), M)}
            if pm.nv and np.linalg.cond(M) < 1e10:
                tau = rng.uniform(-10, 10, pm.nv)
                errs["aba"] = rel_err(rigid.aba(m, d, q, v, tau), pin.aba(pm, pd, q, v, tau))
            bad = {k: e for k, e in errs.items() if not e <= TOL}
            if bad:
                failures.append(f"{tag}: {bad}")
        compared += 1
    assert compared > 40, f"only {compared} files compared"
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("name", ["all_joints_floating", "anymal"])
def test_cli_eval_layout_pinocchio_reads_and_writes_pinocchio_arrays(name, tmp_path):
    """`rigid eval --layout pinocchio`: cases and results in Pinocchio's raw layout."""
    p = pair(name)
    pm, pd = p.pm, p.pd
    cases = [dict(q=q.tolist(), v=v.tolist(), a=a.tolist(), tau=t.tolist())
             for q, v, a, t in p.states]
    f = tmp_path / "cases.json"
    f.write_text(json.dumps(dict(cases=cases)))
    args = ["eval", p.path, "--cases", str(f), "--layout", "pinocchio", "--derivatives"]
    out = cli(*(args + (["--floating"] if p.floating else [])))
    info = out["model"]
    assert (info["layout"], info["nq"], info["nv"]) == ("pinocchio", pm.nq, pm.nv)
    assert [j["name"] for j in info["joints"]] == list(pm.names)[1:]
    assert [j["idx_q"] for j in info["joints"]] == [pm.joints[i].idx_q for i in range(1, pm.njoints)]
    for (q, v, a, tau), r in zip(p.states, out["results"]):
        assert_close(r["rnea"], pin.rnea(pm, pd, q, v, a), "eval rnea")
        assert_close(r["mass_matrix"], symmetric(pin.crba(pm, pd, q)), "eval mass_matrix")
        assert_close(r["aba"], pin.aba(pm, pd, q, v, tau), "eval aba")
        assert_close(r["nonlinear_effects"], pin.nonLinearEffects(pm, pd, q, v), "eval nle")
        dq, dv, _ = pin.computeRNEADerivatives(pm, pd, q, v, a)
        assert_close(r["rnea_derivatives"]["dtau_dq"], dq, "eval dtau_dq")
        assert_close(r["rnea_derivatives"]["dtau_dv"], dv, "eval dtau_dv")
        dq, dv, dtau = pin.computeABADerivatives(pm, pd, q, v, tau)
        assert_close(r["aba_derivatives"]["dqdd_dq"], dq, "eval dqdd_dq")
        assert_close(r["aba_derivatives"]["dqdd_dv"], dv, "eval dqdd_dv")
        assert_close(r["aba_derivatives"]["dqdd_dtau"], symmetric(dtau), "eval dqdd_dtau")
