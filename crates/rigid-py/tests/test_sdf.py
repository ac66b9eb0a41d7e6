"""SDF import against Drake's MultibodyPlant (`pip install drake`; skipped without it) and the
identities on Cassie's SDF files (example-robot-data), whose loops are constraints.

Drake: the acrobot and the cart-pole that ship with Drake, M and the bias `C v - tau_g` at random
states, joints matched by name, to 1e-9 relative to the largest entry. Cassie: each file loads
with its loops; M symmetric positive definite, `M aba(tau) + nle = tau`, and the constrained
dynamics hold the loops (`J qdd + dJ v = 0`) with multipliers that satisfy `M qdd + nle = tau +
J^T lambda`.
"""

import glob
import os
import warnings

import numpy as np
import pytest

import rigid
from conftest import ROOT  # noqa: F401  (sets up the path)

TOL = 1e-9


def quiet(f, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return f(*args, **kwargs)


def drake_examples():
    pydrake = pytest.importorskip("pydrake")
    root = os.path.join(os.path.dirname(pydrake.__file__), "share", "drake", "examples")
    return {"acrobot": os.path.join(root, "acrobot", "Acrobot.sdf"),
            "cart_pole": os.path.join(root, "multibody", "cart_pole", "cart_pole.sdf")}


@pytest.mark.parametrize("name", ["acrobot", "cart_pole"])
def test_drake_models_equal_drakes_multibody_plant(name):
    path = drake_examples()[name]
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    plant = MultibodyPlant(0.0)
    Parser(plant).AddModels(path)
    plant.Finalize()
    context = plant.CreateDefaultContext()
    model = quiet(rigid.Model.from_sdf, path)
    data = model.create_data()
    assert (model.nq, model.nv) == (plant.num_positions(), plant.num_velocities())
    # rigid's dof k is Drake's perm[k], by joint name
    perm = []
    for name_k in model.names:
        j = plant.GetJointByName(name_k)
        assert j.num_velocities() == 1
        perm.append(j.velocity_start())
    rng = np.random.default_rng(0)
    worst = 0.0
    for _ in range(4):
        q, v = rng.uniform(-1, 1, model.nq), rng.uniform(-1, 1, model.nv)
        qd, vd = np.zeros(model.nq), np.zeros(model.nv)
        qd[perm], vd[perm] = q, v
        plant.SetPositions(context, qd)
        plant.SetVelocities(context, vd)
        M = plant.CalcMassMatrix(context)[np.ix_(perm, perm)]
        bias = (plant.CalcBiasTerm(context) - plant.CalcGravityGeneralizedForces(context))[perm]
        for ours, ref in [(rigid.crba(model, data, q), M), (rigid.nle(model, data, q, v), bias)]:
            worst = max(worst, np.max(np.abs(ours - ref)) / max(1.0, np.max(np.abs(ref))))
    print(f"{name}: {worst:.2e}")
    assert worst <= TOL, worst


def cassie_files():
    from conftest import pin
    if pin is None:
        pytest.skip("example-robot-data comes with Pinocchio's wheels")
    from reference import robots_dir
    return sorted(glob.glob(os.path.join(robots_dir(), "cassie_description", "robots", "*.sdf")))


def test_cassie_loads_with_its_loops_and_the_identities_hold():
    files = cassie_files()
    assert len(files) >= 4, files
    rng = np.random.default_rng(1)
    for path in files:
        model = quiet(rigid.Model.from_sdf, path)
        loops = rigid.ConstraintModel.from_sdf(model)
        assert len(loops) >= 6, (path, len(loops))
        data = model.create_data()
        q = rigid.random_configuration(model)
        v, tau = rng.uniform(-1, 1, model.nv), rng.uniform(-1, 1, model.nv)
        M = rigid.crba(model, data, q)
        assert np.allclose(M, M.T, atol=0) and np.linalg.eigvalsh(M).min() > 0, path
        a = rigid.aba(model, data, q, v, tau)
        assert np.max(np.abs(M @ a + rigid.nle(model, data, q, v) - tau)) < 1e-9, path


def test_cassie_loops_close_at_the_files_configuration_and_hold_in_the_dynamics():
    files = [f for f in cassie_files() if f.endswith("cassie_v2.sdf")]
    model = quiet(rigid.Model.from_sdf, files[0])
    loops = rigid.ConstraintModel.from_sdf(model)
    cd = rigid.ConstraintData(model, loops)
    data = model.create_data()
    q = rigid.neutral(model)
    rng = np.random.default_rng(2)
    v, tau = np.zeros(model.nv), rng.uniform(-1, 1, model.nv)
    # a revolute loop joint is two points on its axis: one redundant row, hence mu > 0
    a = rigid.constraint_dynamics(model, data, q, v, tau, cd, mu=1e-8, max_iter=200)
    assert cd.violation < 1e-9  # the file's configuration closes every loop
    J = cd.jacobian
    assert np.max(np.abs(J @ a + cd.gamma)) < 1e-8
    M, nle = rigid.crba(model, data, q), rigid.nle(model, data, q, v)
    assert np.max(np.abs(M @ a + nle - tau - J.T @ cd.lambda_c)) < 1e-8
