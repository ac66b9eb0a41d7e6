"""`Model.save` (`rigid convert`) against the references, joints matched by name:

- URDF -> MJCF (UR5, Panda fixed; Solo-12 and TALOS on a free-flyer): MuJoCo 4.0 compiles the
  written file, and its mj_fullM and qfrc_bias equal Pinocchio's M and nle on the original URDF;
- MJCF -> URDF (gymnasium's ant and humanoid): Pinocchio loads the written file (with a
  free-flyer root, as URDF files of floating robots are loaded), and its M and nle equal
  MuJoCo's mj_fullM (less the armature, which URDF cannot hold) and qfrc_bias on the original.

MuJoCo's free joint has velocity (v in the world, w in the body), Pinocchio's (v, w) in the body:
with v_mj = J v_pin, M_pin = J^T M_mj J and nle_pin = J^T (bias_mj + M_mj dJ v_pin), where
dJ v_pin = (R (w x v), 0). Random states, 1e-9 relative to the largest entry.
"""

import os
import warnings

import numpy as np
import pytest

import rigid
from conftest import ROOT, robot_path

pin = pytest.importorskip("pinocchio")
mujoco = pytest.importorskip("mujoco")

MODELS = os.path.join(ROOT, "crates", "rigid", "tests", "mujoco", "models")
TOL = 1e-9


def quiet(f, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return f(*args, **kwargs)


def pinocchio_maps(pm, m, qm, vm):
    """Pinocchio's (q, v) of MuJoCo's (qm, vm), and J with vm = J v."""
    q, v = pin.neutral(pm), np.zeros(pm.nv)
    J = np.zeros((m.nv, pm.nv))
    dJv = np.zeros(m.nv)
    for k in range(m.njnt):
        a, d, t = m.jnt_qposadr[k], m.jnt_dofadr[k], int(m.jnt_type[k])
        if t == mujoco.mjtJoint.mjJNT_FREE:
            jid = 1  # the free-flyer root of both
            assert pm.joints[jid].shortname() == "JointModelFreeFlyer"
            iq, iv = pm.joints[jid].idx_q, pm.joints[jid].idx_v
            w, x, y, z = qm[a + 3:a + 7]
            q[iq:iq + 3], q[iq + 3:iq + 7] = qm[a:a + 3], (x, y, z, w)
            R = pin.Quaternion(w, x, y, z).toRotationMatrix()
            vb, omega = R.T @ vm[d:d + 3], vm[d + 3:d + 6]
            v[iv:iv + 3], v[iv + 3:iv + 6] = vb, omega
            J[d:d + 3, iv:iv + 3], J[d + 3:d + 6, iv + 3:iv + 6] = R, np.eye(3)
            dJv[d:d + 3] = R @ np.cross(omega, vb)
            continue
        assert t in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE)
        name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, k)
        jid = pm.getJointId(name)
        assert jid < pm.njoints, f"joint {name} not in Pinocchio's model"
        iq, iv, nq = pm.joints[jid].idx_q, pm.joints[jid].idx_v, pm.joints[jid].nq
        angle = qm[a] - m.qpos0[a]
        q[iq:iq + nq] = (np.cos(angle), np.sin(angle)) if nq == 2 else angle
        v[iv] = vm[d]
        J[d, iv] = 1.0
    return q, v, J, dJv


def states(m, n=4, seed=0):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        q = m.qpos0.copy()
        for k in range(m.njnt):
            a = m.jnt_qposadr[k]
            if m.jnt_type[k] == mujoco.mjtJoint.mjJNT_FREE:
                q[a:a + 3] = rng.uniform(-1, 1, 3)
                x = rng.normal(size=4)
                q[a + 3:a + 7] = x / np.linalg.norm(x)
            else:
                q[a] += rng.uniform(-1, 1)
        yield q, rng.uniform(-1, 1, m.nv)


def compare(pm, m, armature):
    """Largest relative difference of M and nle over random states."""
    d, pd = mujoco.MjData(m), pm.createData()
    worst = 0.0
    for qm, vm in states(m):
        d.qpos[:], d.qvel[:] = qm, vm
        mujoco.mj_forward(m, d)
        Mm = np.zeros((m.nv, m.nv))
        mujoco.mj_fullM(m, d, Mm)
        if not armature:
            Mm -= np.diag(m.dof_armature)
        q, v, J, dJv = pinocchio_maps(pm, m, qm, vm)
        M = pin.crba(pm, pd, q)
        M = np.triu(M) + np.triu(M, 1).T
        nle = pin.nle(pm, pd, q, v)
        for ours, ref in [(J.T @ Mm @ J, M), (J.T @ (d.qfrc_bias + Mm @ dJv), nle)]:
            worst = max(worst, np.max(np.abs(ours - ref)) / max(1.0, np.max(np.abs(ref))))
    return worst


@pytest.mark.parametrize("name", ["ur5", "panda", "solo12", "talos"])
def test_urdf_to_mjcf_equals_pinocchio(name, tmp_path):
    path, floating = robot_path(name)
    model = quiet(rigid.Model.from_urdf, path, floating=floating)
    out = tmp_path / f"{name}.xml"
    notes = model.save(out)
    assert any("velocity limits are not written" in n for n in notes), notes
    m = mujoco.MjModel.from_xml_path(str(out))
    root = pin.JointModelFreeFlyer()
    pm = pin.buildModelFromUrdf(path, root) if floating else pin.buildModelFromUrdf(path)
    assert (m.nv, m.njnt) == (pm.nv, pm.njoints - 1)
    assert compare(pm, m, armature=True) <= TOL


@pytest.mark.parametrize("name", ["ant", "humanoid"])
def test_mjcf_to_urdf_equals_mujoco(name, tmp_path):
    path = os.path.join(MODELS, name + ".xml")
    model = quiet(rigid.Model.from_mjcf, path)
    out = tmp_path / f"{name}.urdf"
    notes = model.save(out)
    assert any("free-flyer" in n for n in notes), notes
    pm = pin.buildModelFromUrdf(str(out), pin.JointModelFreeFlyer())
    m = mujoco.MjModel.from_xml_path(path)
    assert m.nv == pm.nv
    assert compare(pm, m, armature=False) <= TOL
    # the written URDF reads back into rigid with its collision meshes
    back = quiet(rigid.Model.from_urdf, str(out), floating=True)
    assert back.nv == model.nv


def test_round_trip_keeps_the_dynamics(tmp_path):
    """URDF -> MJCF -> URDF: rigid's M and bias at the same states, bit-close."""
    path, _ = robot_path("panda")
    a = quiet(rigid.Model.from_urdf, path)
    a.save(tmp_path / "p.xml")
    b = quiet(rigid.Model.from_mjcf, str(tmp_path / "p.xml"))
    b.save(tmp_path / "p.urdf")
    c = quiet(rigid.Model.from_urdf, str(tmp_path / "p.urdf"))
    assert a.names == c.names
    rng = np.random.default_rng(1)
    for _ in range(3):
        q, v = rng.uniform(-1, 1, a.nq), rng.uniform(-1, 1, a.nv)
        ref = [rigid.crba(a, a.create_data(), q), rigid.nle(a, a.create_data(), q, v)]
        for other in (b, c):
            ours = [rigid.crba(other, other.create_data(), q), rigid.nle(other, other.create_data(), q, v)]
            for x, r in zip(ours, ref):
                assert np.max(np.abs(x - r)) <= 1e-12 * max(1.0, np.max(np.abs(r)))


def test_what_a_format_cannot_say_is_an_error_naming_the_joint(tmp_path):
    m = quiet(rigid.Model.from_mjcf, os.path.join(MODELS, "ball_joints.xml"))
    with pytest.raises(ValueError, match="URDF has no spherical joint"):
        m.save(tmp_path / "b.urdf")
    assert not (tmp_path / "b.urdf").exists()
    with pytest.raises(ValueError, match="unknown output format"):
        m.save(tmp_path / "b.sdf")


@pytest.mark.parametrize("name", ["humanoid", "ant"])
def test_mjcf_to_mjcf_equals_mujoco(name, tmp_path):
    """MJCF -> MJCF: MuJoCo's M (armature included) and bias on the written file equal its own on
    the original, joints by name (humanoid's bodies of several joints come back as such)."""
    path = os.path.join(MODELS, name + ".xml")
    out = tmp_path / f"{name}.xml"
    quiet(rigid.Model.from_mjcf, path).save(out)
    a, b = mujoco.MjModel.from_xml_path(path), mujoco.MjModel.from_xml_path(str(out))
    assert (a.nq, a.nv, a.njnt) == (b.nq, b.nv, b.njnt)
    qmap, vmap = [], []
    for k in range(a.njnt):
        name_k = mujoco.mj_id2name(a, mujoco.mjtObj.mjOBJ_JOINT, k)
        kb = mujoco.mj_name2id(b, mujoco.mjtObj.mjOBJ_JOINT, name_k)
        n = {0: 7, 1: 4}.get(int(a.jnt_type[k]), 1)
        qmap += range(b.jnt_qposadr[kb], b.jnt_qposadr[kb] + n)
        vmap += range(b.jnt_dofadr[kb], b.jnt_dofadr[kb] + (6 if n == 7 else 3 if n == 4 else 1))
    da, db = mujoco.MjData(a), mujoco.MjData(b)
    for qm, vm in states(a):
        da.qpos[:], da.qvel[:] = qm, vm
        db.qpos[qmap] = qm - a.qpos0 + b.qpos0  # hinges from their ref, the free joint as is
        for k in range(a.njnt):
            if a.jnt_type[k] == mujoco.mjtJoint.mjJNT_FREE:
                s = slice(a.jnt_qposadr[k], a.jnt_qposadr[k] + 7)
                db.qpos[np.array(qmap)[s]] = qm[s]
        db.qvel[vmap] = vm
        mujoco.mj_forward(a, da)
        mujoco.mj_forward(b, db)
        Ma, Mb = np.zeros((a.nv, a.nv)), np.zeros((b.nv, b.nv))
        mujoco.mj_fullM(a, da, Ma)
        mujoco.mj_fullM(b, db, Mb)
        Mb = Mb[np.ix_(vmap, vmap)]
        for x, ref in [(Mb, Ma), (db.qfrc_bias[vmap], da.qfrc_bias)]:
            assert np.max(np.abs(x - ref)) <= TOL * max(1.0, np.max(np.abs(ref)))


def test_urdf_to_urdf_equals_pinocchio_on_talos(tmp_path):
    """TALOS (full v2, 45 joints, 121 frames) written as URDF: Pinocchio loads it with the same
    joints and frames, and its M and nle equal Pinocchio's on the original."""
    path, _ = robot_path("talos")
    out = tmp_path / "talos.urdf"
    quiet(rigid.Model.from_urdf, path, floating=True).save(out)
    root = pin.JointModelFreeFlyer()
    a, b = pin.buildModelFromUrdf(path, root), pin.buildModelFromUrdf(str(out), root)
    assert (a.nq, a.nv, len(a.frames)) == (b.nq, b.nv, len(b.frames))
    P, pairs = np.zeros((a.nv, b.nv)), []
    for j in range(1, a.njoints):
        ja = a.joints[j]
        jb = b.joints[1 if a.names[j] == "root_joint" else b.getJointId(a.names[j])]
        pairs.append((ja, jb))
        P[ja.idx_v:ja.idx_v + ja.nv, jb.idx_v:jb.idx_v + jb.nv] = np.eye(ja.nv)
    da, db = a.createData(), b.createData()
    rng = np.random.default_rng(0)
    for _ in range(3):
        q = pin.randomConfiguration(a, -np.ones(a.nq), np.ones(a.nq))
        v = rng.uniform(-1, 1, a.nv)
        qb = pin.neutral(b)
        for ja, jb in pairs:
            qb[jb.idx_q:jb.idx_q + jb.nq] = q[ja.idx_q:ja.idx_q + ja.nq]
        Ma, Mb = pin.crba(a, da, q), pin.crba(b, db, qb)
        Ma, Mb = np.triu(Ma) + np.triu(Ma, 1).T, np.triu(Mb) + np.triu(Mb, 1).T
        assert np.max(np.abs(Ma - P @ Mb @ P.T)) <= TOL * max(1.0, np.max(np.abs(Ma)))
        nle_a, nle_b = pin.nle(a, da, q, v), pin.nle(b, db, qb, P.T @ v)
        assert np.max(np.abs(nle_a - P @ nle_b)) <= TOL * max(1.0, np.max(np.abs(nle_a)))


def _support(points, directions):
    """max over the points of each direction's dot product: the same for any two point sets of
    one convex hull, whatever their order, duplicates or inner points."""
    return np.max(points @ directions.T, axis=0)


@pytest.mark.parametrize("name,rel,floating", [
    ("ur5", "ur_description/urdf/ur5_robot.urdf", False),
    ("talos", "talos_data/robots/talos_reduced.urdf", True)])
def test_visuals_written_to_mjcf_sit_where_pinocchio_puts_them(name, rel, floating, tmp_path):
    """UR5 (COLLADA visual meshes) and TALOS (STL, some scaled by -1) of example-robot-data to
    MJCF: MuJoCo compiles their visual geoms (group 1, no contact, no mass; M unchanged), one per
    URDF <visual>, and at random states each geom's vertices in the world span the same hull as
    Pinocchio's visual object's (its oMg, hpp-fcl's vertices, already scaled), to MuJoCo's float32
    vertices; a primitive geom sits at its object's oMg."""
    from conftest import robots_dir

    path = os.path.join(robots_dir(), rel)
    meshes = os.path.dirname(os.path.dirname(robots_dir()))
    out = tmp_path / f"{name}_visual.xml"
    quiet(rigid.Model.from_urdf, path, floating=floating).save(out)
    m = mujoco.MjModel.from_xml_path(str(out))
    d = mujoco.MjData(m)
    root = (pin.JointModelFreeFlyer(),) if floating else ()
    pm, _, pv = quiet(pin.buildModelsFromUrdf, path, meshes, *root)
    pd, pvd = pm.createData(), pv.createData()
    visual = [g for g in range(m.ngeom) if m.geom_group[g] == 1]
    assert len(visual) == pv.ngeoms and all(m.geom_contype[g] == 0 for g in visual)
    assert compare(pm, m, armature=True) <= TOL
    directions = np.vstack([np.eye(3), -np.eye(3), np.random.default_rng(1).normal(size=(6, 3))])
    worst = 0.0
    for qm, vm in states(m, n=3):
        d.qpos[:] = qm
        mujoco.mj_forward(m, d)
        q, _, _, _ = pinocchio_maps(pm, m, qm, vm)
        pin.updateGeometryPlacements(pm, pd, pv, pvd, q)
        for g in visual:
            name = mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, g)
            k = pv.getGeometryId(name.replace("/visual/", "_"))
            obj = pv.geometryObjects[k]
            M = pvd.oMg[k]
            if m.geom_type[g] != mujoco.mjtGeom.mjGEOM_MESH:  # a primitive: the same frame
                R = d.geom_xmat[g].reshape(3, 3)
                worst = max(worst, np.max(np.abs(d.geom_xpos[g] - M.translation)),
                            np.max(np.abs(R - M.rotation)))
                continue
            mesh = m.geom_dataid[g]
            a, n = m.mesh_vertadr[mesh], m.mesh_vertnum[mesh]
            ours = d.geom_xpos[g] + m.mesh_vert[a:a + n].astype(float) @ d.geom_xmat[g].reshape(3, 3).T
            theirs = np.array(obj.geometry.vertices()) @ M.rotation.T + M.translation
            gap = np.max(np.abs(_support(ours, directions) - _support(theirs, directions)))
            worst = max(worst, gap)
    assert worst < 1e-5, worst


def test_visuals_written_to_urdf_equal_pinocchios_visual_model(tmp_path):
    """TALOS (example-robot-data, meshes and materials) to URDF: Pinocchio's visual model of the
    written file equals the original's, object by object (by name: the writer hangs the links
    welded to a body directly on its link, which reorders Pinocchio's depth-first walk): joint,
    placement, mesh file, scale and colour."""
    from conftest import robots_dir

    path = os.path.join(robots_dir(), "talos_data/robots/talos_reduced.urdf")
    meshes = os.path.dirname(os.path.dirname(robots_dir()))
    out = tmp_path / "talos_visual.urdf"
    quiet(rigid.Model.from_urdf, path, floating=True).save(out)
    root = pin.JointModelFreeFlyer()
    _, _, ref = quiet(pin.buildModelsFromUrdf, path, meshes, root)
    _, _, got = quiet(pin.buildModelsFromUrdf, str(out), [str(tmp_path), meshes], root)
    assert got.ngeoms == ref.ngeoms > 0
    ours = {g.name: g for g in got.geometryObjects}
    assert set(ours) == {g.name for g in ref.geometryObjects}
    for b in ref.geometryObjects:
        a = ours[b.name]
        assert a.parentJoint == b.parentJoint, b.name
        assert np.max(np.abs(a.placement.homogeneous - b.placement.homogeneous)) < 1e-12, a.name
        assert os.path.realpath(a.meshPath) == os.path.realpath(b.meshPath), a.name
        assert np.array_equal(a.meshScale, b.meshScale) and np.allclose(a.meshColor, b.meshColor)
