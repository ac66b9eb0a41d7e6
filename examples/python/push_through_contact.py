#!/usr/bin/env python3
"""Optimise through frictional contact: the push that slides a crate to a mark and stops it.

    pip install ./crates/rigid-py     # then:
    python3 examples/python/push_through_contact.py

A 2 kg crate rests on the ground (Coulomb friction 0.5). A horizontal force u_k acts on it at
each step k of 1 ms for 0.5 s; we want it at x* = 0.2 m and at rest at the end. The force
sequence is found by Gauss-Newton on the two residuals (x_N - x*, v_N), whose gradients with
respect to all 500 forces come from one backward pass through the step derivatives
(`rigid.Simulator.step_derivatives`: analytical, each contact sticking or sliding):

    lambda_N = dr/ds_N,  lambda_k = A_k^T lambda_{k+1},  dr/du_k = B_k^T lambda_{k+1},

with s = (q in the tangent space, v), A_k = d(q+, v+)/d(q, v) and B_k = d(q+, v+)/du_k. The
gradient is first checked against central differences of the whole rollout.

Where the crate sticks, a small change of force moves nothing and the gradient is zero: the
first guess (12 N, more than friction's 9.8 N) makes it slide.
"""
import os
import tempfile

import numpy as np

import rigid

CRATE = """<robot name="crate">
  <link name="crate">
    <inertial><mass value="2"/><inertia ixx="0.0167" iyy="0.0283" izz="0.0417" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
</robot>"""

TARGET = 0.2  # m
SPEED_WEIGHT = 0.1  # s: the residual v_N weighed against x_N


def crate():
    # the simulator reads the file's <collision> when it is made: the file must stay
    path = os.path.join(tempfile.mkdtemp(), "crate.urdf")
    with open(path, "w") as f:
        f.write(CRATE)
    return rigid.Model.from_urdf(path, floating=True)


def rollout(sim, u, derivatives=False):
    """The states from rest with the forces u (N,) along x; with the step derivatives."""
    q = np.array([0.0, 0.0, 0.05, 0.0, 0.0, 0.0, 1.0])
    v = np.zeros(6)
    steps = []
    for uk in u:
        tau = np.array([0, 0, 0, uk, 0, 0], dtype=float)
        if derivatives:
            steps.append(sim.step_derivatives(q, v, tau))
        q, v = sim.step(q, v, tau)
    return q, v, steps


def residuals(q, v):
    # the crate does not turn (pushed through its centre): x and v_x are q[0] and v[3]
    return np.array([q[0] - TARGET, SPEED_WEIGHT * v[3]])


def jacobian(steps):
    """d(residuals)/du (2 x N) by one backward pass per residual."""
    nv = 6
    rows = []
    for seed in (np.eye(2 * nv)[3], SPEED_WEIGHT * np.eye(2 * nv)[nv + 3]):
        # dr/ds_N for s = (dq, v): x is the tangent's linear x (no rotation), v_x is v[3]
        lam = seed.copy()
        grad = np.zeros(len(steps))
        for k in reversed(range(len(steps))):
            d = steps[k]
            A = np.block([[d["dq_dq"], d["dq_dv"]], [d["dv_dq"], d["dv_dv"]]])
            B = np.concatenate([d["dq_dtau"][:, 3], d["dv_dtau"][:, 3]])
            grad[k] = B @ lam
            lam = A.T @ lam
        rows.append(grad)
    return np.array(rows)


def optimise(n=500, iterations=8, check=True, verbose=True):
    model = crate()
    sim = rigid.Simulator(model, dt=1e-3, ground=0.0, friction=0.5)
    u = np.full(n, 12.0)
    q, v, steps = rollout(sim, u, derivatives=True)
    J = jacobian(steps)
    if check:
        # the gradient against central differences of the whole rollout
        for k in (0, n // 3, n - 1):
            e = np.zeros(n)
            e[k] = 1e-5
            rp = residuals(*rollout(sim, u + e)[:2])
            rm = residuals(*rollout(sim, u - e)[:2])
            fd = (rp - rm) / 2e-5
            err = np.abs(fd - J[:, k]).max()
            if verbose:
                print(f"d r / d u_{k}: analytical {J[:, k]}, central {fd}, |diff| {err:.1e}")
            assert err <= 1e-6 * max(1.0, np.abs(fd).max()), (k, J[:, k], fd)
    history = []
    for it in range(iterations):
        r = residuals(q, v)
        history.append(np.abs(r).max())
        if verbose:
            print(f"iteration {it}: x_N = {q[0]:.6f} m, v_N = {v[3]:+.6f} m/s, "
                  f"force in [{u.min():.2f}, {u.max():.2f}] N")
        if history[-1] < 1e-9:
            break
        # the least-norm Gauss-Newton step on the 2 residuals
        du = -J.T @ np.linalg.solve(J @ J.T + 1e-12 * np.eye(2), r)
        u = u + du
        q, v, steps = rollout(sim, u, derivatives=True)
        J = jacobian(steps)
    return u, q, v, history


if __name__ == "__main__":
    u, q, v, history = optimise()
    print(f"reached x = {q[0]:.6f} m (target {TARGET}), v = {v[3]:+.2e} m/s "
          f"in {len(history)} iterations")
