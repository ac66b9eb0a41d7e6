"""rigid.pinocchio against Pinocchio 4.1: every field and function of issue 26's list on UR5,
Panda, Solo-12 and TALOS, each fixed to the world and on a free-flyer, to 1e-9 (relative to the
largest entry, at least 1), on the same random states; skipped without Pinocchio (`pin`).

Known, stated differences (not compared): `model.inertias[0]` (Pinocchio keeps the links welded
to the world there; rigid, whose welded links take no part in the dynamics, keeps none), each
frame's `parentFrame` and `inertia`, and random numbers (`randomConfiguration`, `Random()`).
"""

import os
import warnings

import numpy as np
import pytest

pin = pytest.importorskip("pinocchio")
import rigid  # noqa: E402
import rigid.pinocchio as R  # noqa: E402
from conftest import robot_path  # noqa: E402

TOL = 1e-9
CASES = [(name, floating) for name in ("ur5", "panda", "solo12", "talos")
         for floating in (False, True)]
RFS = [("WORLD", pin.WORLD, R.WORLD), ("LOCAL", pin.LOCAL, R.LOCAL),
       ("LOCAL_WORLD_ALIGNED", pin.LOCAL_WORLD_ALIGNED, R.LOCAL_WORLD_ALIGNED)]


def err(x, ref):
    x, ref = np.asarray(x, dtype=float), np.asarray(ref, dtype=float)
    if x.shape != ref.shape:
        return np.inf
    if x.size == 0:
        return 0.0
    e = np.max(np.abs(x - ref)) / max(1.0, np.max(np.abs(ref)))
    return np.inf if np.isnan(e) else float(e)


class Report:
    """The largest error per check; fails with every check beyond the tolerance."""

    def __init__(self, tag):
        self.tag, self.errors = tag, {}

    def __call__(self, what, x, ref):
        e = err(x, ref)
        self.errors[what] = max(self.errors.get(what, 0.0), e)

    def same(self, what, x, ref):
        self.errors[what] = max(self.errors.get(what, 0.0), 0.0 if x == ref else np.inf)

    def se3(self, what, M, ref):
        self(what, M.homogeneous, ref.homogeneous)

    def check(self):
        bad = {k: e for k, e in self.errors.items() if not e <= TOL}
        assert not bad, f"{self.tag}: " + ", ".join(f"{k} {e:.2e}" for k, e in sorted(bad.items()))


class Case:
    def __init__(self, name, floating, states=2, seed=3):
        path, _ = robot_path(name)
        self.tag = f"{name}{' free-flyer' if floating else ''}"
        self.pm = (pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating
                   else pin.buildModelFromUrdf(path))
        self.rm = (R.buildModelFromUrdf(path, R.JointModelFreeFlyer()) if floating
                   else R.buildModelFromUrdf(path))
        self.path = path
        pm = self.pm.copy()
        lo, up = pm.lowerPositionLimit, pm.upperPositionLimit
        pm.lowerPositionLimit = np.where(np.abs(lo) < 1e10, lo, -1.0)
        pm.upperPositionLimit = np.where(np.abs(up) < 1e10, up, 1.0)
        pin.seed(seed)
        rng = np.random.default_rng(seed)
        nv = pm.nv
        self.states = [(pin.randomConfiguration(pm), rng.uniform(-1, 1, nv),
                        rng.uniform(-1, 1, nv), rng.uniform(-10, 10, nv)) for _ in range(states)]
        self.fext_vectors = [rng.uniform(-1, 1, 6) for _ in range(self.pm.njoints)]


_CASES = {}


def case(name, floating):
    if (name, floating) not in _CASES:
        _CASES[(name, floating)] = Case(name, floating)
    return _CASES[(name, floating)]


@pytest.fixture(params=CASES, ids=[f"{n}{'-ff' if f else ''}" for n, f in CASES])
def c(request):
    return case(*request.param)


def test_model_fields_equal_pinocchio(c):
    pm, rm = c.pm, c.rm
    r = Report(c.tag)
    for k in ("nq", "nv", "njoints", "nframes"):
        r.same(k, getattr(rm, k), getattr(pm, k))
    r.same("names", list(rm.names), list(pm.names))
    r.same("parents", list(rm.parents), list(pm.parents))
    for k in ("idx_qs", "nqs", "idx_vs", "nvs"):
        r.same(k, list(getattr(rm, k)), list(getattr(pm, k)))
    r.same("joints", [j.shortname() for j in rm.joints], [j.shortname() for j in pm.joints])
    r.same("joint indices", [(j.idx_q, j.idx_v, j.nq, j.nv) for j in rm.joints[1:]],
           [(j.idx_q, j.idx_v, j.nq, j.nv) for j in pm.joints[1:]])
    r.same("frames (name, parentJoint, type)",
           [(f.name, f.parentJoint, int(f.type)) for f in rm.frames],
           [(f.name, f.parentJoint, int(f.type)) for f in pm.frames])
    for f, g in zip(rm.frames, pm.frames):
        r.se3("frames placement", f.placement, g.placement)
    for i in range(1, pm.njoints):
        r("inertias", rm.inertias[i].matrix(), pm.inertias[i].matrix())
        r("inertias (mass, lever, inertia)",
          np.concatenate([[rm.inertias[i].mass], rm.inertias[i].lever,
                          rm.inertias[i].inertia.ravel()]),
          np.concatenate([[pm.inertias[i].mass], pm.inertias[i].lever,
                          pm.inertias[i].inertia.ravel()]))
    for i in range(pm.njoints):
        r.se3("jointPlacements", rm.jointPlacements[i], pm.jointPlacements[i])
    for k in ("lowerPositionLimit", "upperPositionLimit", "velocityLimit", "effortLimit",
              "armature"):
        a, b = getattr(rm, k), getattr(pm, k)
        r.same(k, np.array_equal(a, b), True)
    r("gravity", rm.gravity.vector, pm.gravity.vector)
    r.same("getFrameId", [rm.getFrameId(f.name) for f in pm.frames],
           [pm.getFrameId(f.name) for f in pm.frames])
    r.same("getFrameId (typed)", [rm.getFrameId(f.name, R.FrameType(int(f.type)))
                                  for f in pm.frames],
           [pm.getFrameId(f.name, f.type) for f in pm.frames])
    r.same("getJointId", [rm.getJointId(n) for n in list(pm.names) + ["nope"]],
           [pm.getJointId(n) for n in list(pm.names) + ["nope"]])
    r.same("existFrame", [rm.existFrame(n) for n in ["nope"] + [f.name for f in pm.frames]],
           [pm.existFrame(n) for n in ["nope"] + [f.name for f in pm.frames]])
    r.same("getFrameId missing", rm.getFrameId("nope"), pm.getFrameId("nope"))
    r.check()


def test_kinematics_and_jacobians_equal_pinocchio(c):
    pm, rm = c.pm, c.rm
    pd, rd = pm.createData(), rm.createData()
    r = Report(c.tag)
    for q, v, a, _ in c.states:
        pin.forwardKinematics(pm, pd, q, v, a)
        R.forwardKinematics(rm, rd, q, v, a)
        for i in range(pm.njoints):
            r.se3("oMi", rd.oMi[i], pd.oMi[i])
            r.se3("liMi", rd.liMi[i], pd.liMi[i])
            r("v", rd.v[i].vector, pd.v[i].vector)
            r("a", rd.a[i].vector, pd.a[i].vector)
        pin.updateFramePlacements(pm, pd)
        R.updateFramePlacements(rm, rd)
        for i in range(pm.nframes):
            r.se3("oMf", rd.oMf[i], pd.oMf[i])
        R.framesForwardKinematics(rm, rd, q)
        pin.framesForwardKinematics(pm, pd, q)
        for i in range(pm.nframes):
            r.se3("framesForwardKinematics", rd.oMf[i], pd.oMf[i])
        k = pm.nframes - 1
        r.se3("updateFramePlacement", R.updateFramePlacement(rm, rd, k),
              pin.updateFramePlacement(pm, pd, k))
        r("computeJointJacobians", R.computeJointJacobians(rm, rd, q),
          pin.computeJointJacobians(pm, pd, q))
        r("data.J", rd.J, pd.J)
        for name, prf, rrf in RFS:
            for i in range(pm.njoints):
                r(f"getJointJacobian {name}", R.getJointJacobian(rm, rd, i, rrf),
                  pin.getJointJacobian(pm, pd, i, prf))
            for i in range(pm.nframes):
                r(f"getFrameJacobian {name}", R.getFrameJacobian(rm, rd, i, rrf),
                  pin.getFrameJacobian(pm, pd, i, prf))
        for i in range(0, pm.nframes, 3):
            for name, prf, rrf in RFS:
                r(f"computeFrameJacobian {name}", R.computeFrameJacobian(rm, rd, q, i, rrf),
                  pin.computeFrameJacobian(pm, pd, q, i, prf))
        for i in range(pm.njoints):
            r("computeJointJacobian", R.computeJointJacobian(rm, rd, q, i),
              pin.computeJointJacobian(pm, pd, q, i))
        pin.forwardKinematics(pm, pd, q, v, a)
        R.forwardKinematics(rm, rd, q, v, a)
        pin.updateFramePlacements(pm, pd)
        for i in range(0, pm.nframes, 2):
            for name, prf, rrf in RFS:
                r(f"getFrameVelocity {name}", R.getFrameVelocity(rm, rd, i, rrf).vector,
                  pin.getFrameVelocity(pm, pd, i, prf).vector)
                r(f"getFrameAcceleration {name}", R.getFrameAcceleration(rm, rd, i, rrf).vector,
                  pin.getFrameAcceleration(pm, pd, i, prf).vector)
            for name, prf, rrf in RFS[1:]:
                r(f"getFrameClassicalAcceleration {name}",
                  R.getFrameClassicalAcceleration(rm, rd, i, rrf).vector,
                  pin.getFrameClassicalAcceleration(pm, pd, i, prf).vector)
    r.check()


def test_dynamics_equal_pinocchio(c):
    pm, rm = c.pm, c.rm
    pd, rd = pm.createData(), rm.createData()
    r = Report(c.tag)
    fp = [pin.Force(f) for f in c.fext_vectors]
    fr = [R.Force(f) for f in c.fext_vectors]
    for q, v, a, tau in c.states:
        r("rnea", R.rnea(rm, rd, q, v, a), pin.rnea(pm, pd, q, v, a))
        r("data.tau", rd.tau, pd.tau)
        for i in range(1, pm.njoints):  # f[0]: Pinocchio leaves there what an earlier algorithm did
            r("data.f (rnea)", rd.f[i].vector, pd.f[i].vector)
            r("data.v (rnea)", rd.v[i].vector, pd.v[i].vector)
            r("data.a_gf (rnea)", rd.a_gf[i].vector, pd.a_gf[i].vector)
        r("rnea fext", R.rnea(rm, rd, q, v, a, fr), pin.rnea(pm, pd, q, v, a, fp))
        r("crba", R.crba(rm, rd, q), pin.crba(pm, pd, q))
        r("data.M", rd.M, pd.M)
        r("aba", R.aba(rm, rd, q, v, tau), pin.aba(pm, pd, q, v, tau))
        r("data.ddq", rd.ddq, pd.ddq)
        r("aba fext", R.aba(rm, rd, q, v, tau, fr), pin.aba(pm, pd, q, v, tau, fp))
        r("nonLinearEffects", R.nonLinearEffects(rm, rd, q, v), pin.nonLinearEffects(pm, pd, q, v))
        r("data.nle", rd.nle, pd.nle)
        r("computeGeneralizedGravity", R.computeGeneralizedGravity(rm, rd, q),
          pin.computeGeneralizedGravity(pm, pd, q))
        r("data.g", rd.g, pd.g)
        r("computeMinverse", R.computeMinverse(rm, rd, q), pin.computeMinverse(pm, pd, q))
        r("data.Minv", rd.Minv, pd.Minv)
        r("computeCoriolisMatrix", R.computeCoriolisMatrix(rm, rd, q, v),
          pin.computeCoriolisMatrix(pm, pd, q, v))
        r("data.C", rd.C, pd.C)
        r("computeKineticEnergy", R.computeKineticEnergy(rm, rd, q, v),
          pin.computeKineticEnergy(pm, pd, q, v))
        r("data.kinetic_energy", rd.kinetic_energy, pd.kinetic_energy)
        r("computePotentialEnergy", R.computePotentialEnergy(rm, rd, q),
          pin.computePotentialEnergy(pm, pd, q))
        r("data.potential_energy", rd.potential_energy, pd.potential_energy)
    r.check()


def test_centre_of_mass_and_centroidal_terms_equal_pinocchio(c):
    pm, rm = c.pm, c.rm
    pd, rd = pm.createData(), rm.createData()
    r = Report(c.tag)
    for q, v, a, _ in c.states:
        r("centerOfMass(q)", R.centerOfMass(rm, rd, q), pin.centerOfMass(pm, pd, q))
        r("centerOfMass(q, v, a)", R.centerOfMass(rm, rd, q, v, a),
          pin.centerOfMass(pm, pd, q, v, a))
        for k in ("com", "vcom", "acom"):
            r(f"data.{k} (centerOfMass)", np.array(getattr(rd, k)), np.array(getattr(pd, k)))
        r("data.mass", rd.mass, list(pd.mass))
        r("jacobianCenterOfMass", R.jacobianCenterOfMass(rm, rd, q),
          pin.jacobianCenterOfMass(pm, pd, q))
        r("data.Jcom", rd.Jcom, pd.Jcom)
        r("data.com (jacobianCenterOfMass)", np.array(rd.com), np.array(pd.com))
        r("ccrba", R.ccrba(rm, rd, q, v), pin.ccrba(pm, pd, q, v))
        r("data.Ag", rd.Ag, pd.Ag)
        r("data.hg (ccrba)", rd.hg.vector, pd.hg.vector)
        r("data.Ig", rd.Ig.matrix(), pd.Ig.matrix())
        r("computeCentroidalMomentum", R.computeCentroidalMomentum(rm, rd, q, v).vector,
          pin.computeCentroidalMomentum(pm, pd, q, v).vector)
        r("data.com[0], vcom[0] (centroidal momentum)", [rd.com[0], rd.vcom[0]],
          [pd.com[0], pd.vcom[0]])
        pd2, rd2 = pm.createData(), rm.createData()
        pin.computeAllTerms(pm, pd2, q, v)
        R.computeAllTerms(rm, rd2, q, v)
        for k in ("M", "nle", "g", "J", "Jcom", "Ag"):
            r(f"computeAllTerms {k}", getattr(rd2, k), getattr(pd2, k))
        r("computeAllTerms hg", rd2.hg.vector, pd2.hg.vector)
        r("computeAllTerms com", np.array(rd2.com), np.array(pd2.com))
        r("computeAllTerms vcom[0]", rd2.vcom[0], pd2.vcom[0])
        r("computeAllTerms energies", [rd2.kinetic_energy, rd2.potential_energy],
          [pd2.kinetic_energy, pd2.potential_energy])
        for i in range(pm.njoints):
            r.se3("computeAllTerms oMi", rd2.oMi[i], pd2.oMi[i])
    r.check()


def test_derivatives_equal_pinocchio(c):
    pm, rm = c.pm, c.rm
    pd, rd = pm.createData(), rm.createData()
    r = Report(c.tag)
    for q, v, a, tau in c.states[:1]:
        for x, y in zip(R.computeRNEADerivatives(rm, rd, q, v, a),
                        pin.computeRNEADerivatives(pm, pd, q, v, a)):
            r("computeRNEADerivatives", x, y)
        for k in ("dtau_dq", "dtau_dv", "M"):
            r(f"data.{k}", getattr(rd, k), getattr(pd, k))
        for x, y in zip(R.computeABADerivatives(rm, rd, q, v, tau),
                        pin.computeABADerivatives(pm, pd, q, v, tau)):
            r("computeABADerivatives", x, y)
        for k in ("ddq_dq", "ddq_dv", "Minv", "ddq"):
            r(f"data.{k}", getattr(rd, k), getattr(pd, k))
        r("computeGeneralizedGravityDerivatives",
          R.computeGeneralizedGravityDerivatives(rm, rd, q),
          pin.computeGeneralizedGravityDerivatives(pm, pd, q))
        pin.computeForwardKinematicsDerivatives(pm, pd, q, v, a)
        R.computeForwardKinematicsDerivatives(rm, rd, q, v, a)
        joints = sorted({1, pm.njoints // 2, pm.njoints - 1})
        for name, prf, rrf in RFS:
            for i in joints:
                for x, y in zip(R.getJointVelocityDerivatives(rm, rd, i, rrf),
                                pin.getJointVelocityDerivatives(pm, pd, i, prf)):
                    r(f"getJointVelocityDerivatives {name}", x, y)
                for x, y in zip(R.getJointAccelerationDerivatives(rm, rd, i, rrf),
                                pin.getJointAccelerationDerivatives(pm, pd, i, prf)):
                    r(f"getJointAccelerationDerivatives {name}", x, y)
            for i in (pm.nframes - 1, pm.nframes // 2):
                for x, y in zip(R.getFrameVelocityDerivatives(rm, rd, i, rrf),
                                pin.getFrameVelocityDerivatives(pm, pd, i, prf)):
                    r(f"getFrameVelocityDerivatives {name}", x, y)
                for x, y in zip(R.getFrameAccelerationDerivatives(rm, rd, i, rrf),
                                pin.getFrameAccelerationDerivatives(pm, pd, i, prf)):
                    r(f"getFrameAccelerationDerivatives {name}", x, y)
    r.check()


def test_configurations_equal_pinocchio(c):
    pm, rm = c.pm, c.rm
    r = Report(c.tag)
    r("neutral", R.neutral(rm), pin.neutral(pm))
    for (q0, v, _, _), (q1, _, _, _) in zip(c.states, c.states[1:] + c.states[:1]):
        r("integrate", R.integrate(rm, q0, v), pin.integrate(pm, q0, v))
        r("difference", R.difference(rm, q0, q1), pin.difference(pm, q0, q1))
        for u in (0.0, 0.3, 1.0):
            r("interpolate", R.interpolate(rm, q0, q1, u), pin.interpolate(pm, q0, q1, u))
        bad = q0 * 1.3
        r("normalize", R.normalize(rm, bad), pin.normalize(pm, bad))
        for x in (q0, bad, q0 + 1e-9):
            assert R.isNormalized(rm, x) == pin.isNormalized(pm, x), "isNormalized"
            assert R.isNormalized(rm, x, 1e-6) == pin.isNormalized(pm, x, 1e-6), "isNormalized"
        r("column vectors (n, 1)", R.integrate(rm, q0[:, None], v[:, None]),
          pin.integrate(pm, q0, v))
    rigid.seed(1)
    lo, up = np.full(rm.nq, -0.5), np.full(rm.nq, 0.5)
    q = R.randomConfiguration(rm, lo, up)
    assert q.shape == (pm.nq,) and np.allclose(R.normalize(rm, q), q)
    r.check()


def test_spatial_algebra_equals_pinocchio():
    r = Report("spatial")
    rng = np.random.default_rng(4)
    for _ in range(20):
        w, p = rng.uniform(-2, 2, 3), rng.uniform(-2, 2, 3)
        Mp = pin.exp6(pin.Motion(rng.uniform(-1, 1, 6)))
        Mr = R.SE3(Mp.rotation.copy(), Mp.translation.copy())
        Np = pin.SE3(pin.exp3(w), p)
        Nr = R.SE3(Np.rotation.copy(), Np.translation.copy())
        vp, fp = pin.Motion(rng.uniform(-1, 1, 6)), pin.Force(rng.uniform(-1, 1, 6))
        vr, fr = R.Motion(vp.vector.copy()), R.Force(fp.vector.copy())
        Yp = pin.Inertia(1.3, rng.uniform(-1, 1, 3), np.diag([0.3, 0.4, 0.5]))
        Yr = R.Inertia(Yp.mass, Yp.lever.copy(), Yp.inertia.copy())
        r("SE3 *", (Mr * Nr).homogeneous, (Mp * Np).homogeneous)
        r("SE3.inverse", Mr.inverse().homogeneous, Mp.inverse().homogeneous)
        r("SE3.actInv(SE3)", Mr.actInv(Nr).homogeneous, Mp.actInv(Np).homogeneous)
        r("SE3.action", Mr.action, Mp.action)
        r("SE3.actionInverse", Mr.actionInverse, Mp.actionInverse)
        r("SE3.dualAction", Mr.dualAction, Mp.dualAction)
        r("SE3.act(Motion)", Mr.act(vr).vector, Mp.act(vp).vector)
        r("SE3.actInv(Motion)", Mr.actInv(vr).vector, Mp.actInv(vp).vector)
        r("SE3.act(Force)", Mr.act(fr).vector, Mp.act(fp).vector)
        r("SE3.actInv(Force)", Mr.actInv(fr).vector, Mp.actInv(fp).vector)
        r("SE3.act(Inertia)", Mr.act(Yr).matrix(), Mp.act(Yp).matrix())
        r("SE3.actInv(Inertia)", Mr.actInv(Yr).matrix(), Mp.actInv(Yp).matrix())
        r("SE3 * point", Mr * p, Mp * p)
        r("Motion ^ Motion", (vr ^ R.Motion(fp.vector)).vector, (vp ^ pin.Motion(fp.vector)).vector)
        r("Motion ^ Force", (vr ^ fr).vector, (vp ^ fp).vector)
        r("Motion.action", vr.action, vp.action)
        r("Motion.dualAction", vr.dualAction, vp.dualAction)
        r("Motion.homogeneous", vr.homogeneous, vp.homogeneous)
        r("Motion.dot", vr.dot(fr), vp.dot(fp))
        r("Inertia * Motion", (Yr * vr).vector, (Yp * vp).vector)
        r("Inertia.matrix", Yr.matrix(), Yp.matrix())
        r("Inertia +", (Yr + Yr.se3Action(Mr)).matrix(), (Yp + Yp.se3Action(Mp)).matrix())
        r("Inertia.vxiv", Yr.vxiv(vr).vector, Yp.vxiv(vp).vector)
        r("Inertia.variation", Yr.variation(vr), Yp.variation(vp))
        r("Inertia.toDynamicParameters", Yr.toDynamicParameters(), Yp.toDynamicParameters())
        r("Inertia.FromDynamicParameters",
          R.Inertia.FromDynamicParameters(Yp.toDynamicParameters()).matrix(), Yp.matrix())
        r("log6", R.log6(Mr).vector, pin.log6(Mp).vector)
        r("log", R.log(Mr).vector, pin.log(Mp).vector)
        r("exp6", R.exp6(vr).homogeneous, pin.exp6(vp).homogeneous)
        r("exp", R.exp(vr).homogeneous, pin.exp(vp).homogeneous)
        r("log3", R.log3(Np.rotation), pin.log3(Np.rotation))
        r("exp3", R.exp3(w), pin.exp3(w))
        r("Jlog6", R.Jlog6(Mr), pin.Jlog6(Mp))
        r("Jexp6", R.Jexp6(vr), pin.Jexp6(vp))
        r("Jlog3", R.Jlog3(Np.rotation), pin.Jlog3(Np.rotation))
        r("Jexp3", R.Jexp3(w), pin.Jexp3(w))
        r("SE3.Interpolate", R.SE3.Interpolate(Mr, Nr, 0.3).homogeneous,
          pin.SE3.Interpolate(Mp, Np, 0.3).homogeneous)
        r("SE3ToXYZQUAT", R.SE3ToXYZQUAT(Mr), pin.SE3ToXYZQUAT(Mp))
        r("XYZQUATToSE3", R.XYZQUATToSE3(pin.SE3ToXYZQUAT(Mp)).homogeneous, Mp.homogeneous)
        r("Quaternion", R.Quaternion(Mr.rotation).toRotationMatrix(), Mp.rotation)
        r("rpy", R.rpy.matrixToRpy(Mr.rotation), pin.rpy.matrixToRpy(Mp.rotation))
        r("rpyToMatrix", R.rpy.rpyToMatrix(*w), pin.rpy.rpyToMatrix(*w))
        r("skew", R.skew(w), pin.skew(w))
    r.same("SE3 views", True, _views_are_shared())
    for f in ("Identity", "Zero"):
        for cls in ("SE3", "Motion", "Force", "Inertia"):
            if hasattr(getattr(pin, cls), f):
                ref = getattr(getattr(pin, cls), f)()
                ours = getattr(getattr(R, cls), f)()
                r(f"{cls}.{f}", getattr(ours, "homogeneous", getattr(ours, "np", None)),
                  getattr(ref, "homogeneous", getattr(ref, "np", None)))
    r.check()


def _views_are_shared():
    M = R.SE3.Identity()
    M.translation[0] = 2.0
    v = R.Motion.Zero()
    v.linear[1] = 3.0
    return M.homogeneous[0, 3] == 2.0 and v.vector[1] == 3.0


def test_robot_wrapper_and_loaders_equal_pinocchio():
    path, _ = robot_path("ur5")
    from pinocchio.robot_wrapper import RobotWrapper as PW

    # Pinocchio's BuildFromURDF also reads the meshes, which the checked-in files lack
    pr, rr = PW(pin.buildModelFromUrdf(path)), R.RobotWrapper.BuildFromURDF(path)
    r = Report("RobotWrapper")
    r("q0", rr.q0, pr.q0)
    r.same("nq, nv", (rr.nq, rr.nv), (pr.nq, pr.nv))
    q = pin.randomConfiguration(pr.model)
    v = np.linspace(-1, 1, pr.nv)
    fid = pr.model.getFrameId("tool0")
    r.se3("framePlacement", rr.framePlacement(q, fid), pr.framePlacement(q, fid))
    r("computeFrameJacobian", rr.computeFrameJacobian(q, fid), pr.computeFrameJacobian(q, fid))
    r("com", rr.com(q), pr.com(q))
    r("mass", rr.mass(q), pr.mass(q))
    r("nle", rr.nle(q, v), pr.nle(q, v))
    r("gravity", rr.gravity(q), pr.gravity(q))
    r("Jcom", rr.Jcom(q), pr.Jcom(q))
    r.se3("placement", rr.placement(q, 3), pr.placement(q, 3))
    r("velocity", rr.velocity(q, v, 3).vector, pr.velocity(q, v, 3).vector)
    # (the geometry models against Pinocchio's: test_pinocchio_scripts.py, with the meshes)
    import xml.etree.ElementTree as ET

    root = ET.parse(path).getroot()
    counts = tuple(len(root.findall(f"link/{kind}")) for kind in ("collision", "visual"))
    model, cm, vm = R.buildModelsFromUrdf(path)
    r.same("buildModelsFromUrdf", (model.nq, cm.ngeoms, vm.ngeoms), (pr.model.nq, *counts))
    r.same("collision_model", (rr.collision_model.ngeoms, rr.visual_model.ngeoms), counts)
    r.check()


ROOTS = [("JointModelRX", ()), ("JointModelPZ", ()), ("JointModelRUBZ", ()),
         ("JointModelPlanar", ()), ("JointModelSpherical", ()),
         ("JointModelRevoluteUnaligned", (0.0, 0.6, 0.8)), ("JointModelFreeFlyer", ())]


@pytest.mark.parametrize("robot", ["ur5", "solo12"])
def test_urdf_on_any_root_joint_equals_pinocchio(robot):
    """buildModelFromUrdf(path, root_joint, root_joint_name) with each kind of root joint: the
    tree, limits (Pinocchio's root joint has none), frames and the dynamics equal Pinocchio's."""
    path, _ = robot_path(robot)
    r = Report(f"{robot} roots")
    rng = np.random.default_rng(5)
    for J, args in ROOTS:
        pm = pin.buildModelFromUrdf(path, getattr(pin, J)(*args), "base_root")
        rm = R.buildModelFromUrdf(path, getattr(R, J)(*args), "base_root")
        pd, rd = pm.createData(), rm.createData()
        r.same(f"{J} names, nq, nv", (list(rm.names), rm.nq, rm.nv), (list(pm.names), pm.nq, pm.nv))
        r.same(f"{J} frames", [(f.name, f.parentJoint, int(f.type)) for f in rm.frames],
               [(f.name, f.parentJoint, int(f.type)) for f in pm.frames])
        for k in ("lowerPositionLimit", "upperPositionLimit", "velocityLimit", "effortLimit"):
            r.same(f"{J} {k}", np.array_equal(getattr(rm, k), getattr(pm, k)), True)
        q = pin.randomConfiguration(pm, np.full(pm.nq, -1.0), np.full(pm.nq, 1.0))
        v, a = rng.uniform(-1, 1, pm.nv), rng.uniform(-1, 1, pm.nv)
        r(f"{J} rnea", R.rnea(rm, rd, q, v, a), pin.rnea(pm, pd, q, v, a))
        r(f"{J} crba", R.crba(rm, rd, q), pin.crba(pm, pd, q))
        r(f"{J} computeJointJacobians", R.computeJointJacobians(rm, rd, q),
          pin.computeJointJacobians(pm, pd, q))
    r.check()


def test_sample_models_have_pinocchios_kinematics_and_inertias():
    r = Report("sample models")
    for name in ("buildSampleModelManipulator", "buildSampleModelHumanoid"):
        pm, rm = getattr(pin, name)(), getattr(R, name)()
        pd, rd = pm.createData(), rm.createData()
        r.same(f"{name} names", list(rm.names), list(pm.names))
        r.same(f"{name} frames", [(f.name, f.parentJoint, int(f.type)) for f in rm.frames],
               [(f.name, f.parentJoint, int(f.type)) for f in pm.frames])
        for k in ("lowerPositionLimit", "upperPositionLimit", "velocityLimit", "effortLimit"):
            r(f"{name} {k}", getattr(rm, k), getattr(pm, k))
        for i in range(1, pm.njoints):
            r(f"{name} inertias", rm.inertias[i].matrix(), pm.inertias[i].matrix())
            r.se3(f"{name} jointPlacements", rm.jointPlacements[i], pm.jointPlacements[i])
        q = pin.neutral(pm)
        q = pin.integrate(pm, q, np.linspace(-0.7, 0.9, pm.nv))
        v, a = np.linspace(1, -1, pm.nv), np.linspace(-0.5, 0.5, pm.nv)
        r(f"{name} rnea", R.rnea(rm, rd, q, v, a), pin.rnea(pm, pd, q, v, a))
        r(f"{name} crba", R.crba(rm, rd, q), pin.crba(pm, pd, q))
    pm, rm = pin.buildSampleModelHumanoidRandom(), R.buildSampleModelHumanoidRandom()
    r.same("buildSampleModelHumanoidRandom tree", (list(rm.names), list(rm.parents),
                                                    [f.name for f in rm.frames]),
           (list(pm.names), list(pm.parents), [f.name for f in pm.frames]))
    r.check()


def test_pickle_and_copy_keep_models_and_data():
    import copy
    import pickle

    path, _ = robot_path("solo12")
    for m in (R.buildModelFromUrdf(path, R.JointModelFreeFlyer()), R.buildSampleModelHumanoid(),
              rigid.Model.from_urdf(path, floating=True, layout="pinocchio")):
        d = m.createData()
        m2, d2 = pickle.loads(pickle.dumps((m, d)))
        assert type(m2) is type(m) and type(d2) is type(d)
        assert m2.to_json() == m.to_json()
        q = R.neutral(m)
        v = np.linspace(-1, 1, m.nv)
        assert np.array_equal(rigid.rnea(m2, d2, q, v, v), rigid.rnea(m, d, q, v, v))
        m3 = copy.deepcopy(m)
        assert m3.to_json() == m.to_json() and m3 is not m
        assert copy.copy(m) is m or copy.copy(m).to_json() == m.to_json()
        d3 = copy.deepcopy(d)
        assert np.array_equal(rigid.rnea(m, d3, q, v, v), rigid.rnea(m, d, q, v, v))
        if isinstance(m, R.Model):
            assert [f.name for f in m2.frames] == [f.name for f in m.frames]
            assert np.array_equal(m2.lowerPositionLimit, m.lowerPositionLimit)
    M = R.SE3.Random()
    assert pickle.loads(pickle.dumps(M)) == M


def test_model_edits_write_through():
    path, _ = robot_path("ur5")
    pm, rm = pin.buildModelFromUrdf(path), R.buildModelFromUrdf(path)
    pd, rd = pm.createData(), rm.createData()
    q = pin.neutral(pm) + 0.3
    for m, lib in ((pm, pin), (rm, R)):
        m.gravity.linear = np.array([0.0, 0.0, -1.62])
        Y = m.inertias[2]
        m.inertias[2] = lib.Inertia(2 * Y.mass, Y.lever, Y.inertia)
        M = m.jointPlacements[3]
        m.jointPlacements[3] = lib.SE3(M.rotation, M.translation + 0.01)
        m.inertias[4].mass = 3.0
        m.lowerPositionLimit = -np.ones(m.nq)
        m.armature = np.full(m.nv, 0.1)
    r = Report("edits")
    r("gravity", rm.gravity.vector, pm.gravity.vector)
    r("rnea after edits", R.rnea(rm, rd, q, q, q), pin.rnea(pm, pd, q, q, q))
    r("crba after edits", R.crba(rm, rd, q), pin.crba(pm, pd, q))
    r("limits", rm.lowerPositionLimit, pm.lowerPositionLimit)
    r.check()


def test_what_is_not_covered_raises_not_implemented_naming_it():
    with pytest.raises(NotImplementedError, match="computeContactPatches.*coal"):
        R.computeContactPatches(None, None)
    with pytest.raises(NotImplementedError, match="JointModelSphericalZYX"):
        R.JointModelSphericalZYX()
    with pytest.raises(NotImplementedError, match=r"buildModelFromUrdf\(filename, model\)"):
        R.buildModelFromUrdf(robot_path("ur5")[0], R.Model())
    with pytest.raises(NotImplementedError, match="viewer"):
        R.RobotWrapper.BuildFromURDF(robot_path("ur5")[0]).initViewer()
    with pytest.raises(NotImplementedError, match="dIntegrate"):
        R.dIntegrate(None, None, None)
    with pytest.raises(NotImplementedError, match="data.oYcrb"):
        R.buildSampleModelManipulator().createData().oYcrb
    with pytest.raises(AttributeError):
        R.definitely_not_a_pinocchio_name  # noqa: B018
    from rigid.pinocchio.__main__ import PinocchioFinder  # noqa: F401


def test_hot_verbs_are_rigids_own_functions():
    for name, native in [("rnea", "rnea"), ("crba", "crba"), ("aba", "aba"),
                         ("forwardKinematics", "forward_kinematics"),
                         ("updateFramePlacements", "update_frame_placements"),
                         ("computeJointJacobians", "compute_joint_jacobians")]:
        assert getattr(R, name) is getattr(rigid, native)


def test_mjcf_loader_is_wired_when_rigid_reads_mjcf(tmp_path):
    f = tmp_path / "arm.xml"
    f.write_text("""<mujoco><worldbody><body name="a"><joint name="j" type="hinge" axis="0 1 0"/>
      <geom type="capsule" size="0.05" fromto="0 0 0 0 0 -0.5" mass="1"/></body></worldbody>
      </mujoco>""")
    if not hasattr(rigid.Model, "from_mjcf"):
        with pytest.raises(NotImplementedError, match="MJCF"):
            R.buildModelFromMJCF(str(f))
        return
    m = R.buildModelFromMJCF(str(f))
    pm = pin.buildModelFromMJCF(str(f))
    assert (m.nq, m.nv, list(m.names)) == (pm.nq, pm.nv, list(pm.names))
    q = np.array([0.4])
    assert err(R.rnea(m, m.createData(), q, q, q), pin.rnea(pm, pm.createData(), q, q, q)) < TOL


def test_inverse_kinematics_reaches_a_pose_of_its_forward_kinematics():
    path, _ = robot_path("panda")
    m = R.buildModelFromUrdf(path)
    d = m.createData()
    q_star = R.neutral(m) + 0.2
    R.framesForwardKinematics(m, d, q_star)
    target = d.oMf[m.getFrameId("panda_hand")]
    sol = R.inverse_kinematics(m, "panda_hand", target, R.neutral(m))
    assert sol["converged"], sol
    R.framesForwardKinematics(m, d, sol["q"])
    assert np.linalg.norm(R.log6(d.oMf[m.getFrameId("panda_hand")].actInv(target)).vector) < 1e-9
    sol = rigid.inverse_kinematics(m, "panda_hand", target.translation, damping=0.0,
                                   restarts=0, max_iterations=50)
    assert sol["converged"] and sol["position_error"] < 1e-9
    with pytest.raises(ValueError, match="tolerance"):
        rigid.inverse_kinematics(m, "panda_hand", target, tolerance=-1.0)
    with pytest.raises(ValueError, match="nope"):
        rigid.inverse_kinematics(m, "nope", target)


_ = os
warnings.filterwarnings("ignore", category=DeprecationWarning)
