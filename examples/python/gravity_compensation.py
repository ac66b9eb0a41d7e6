#!/usr/bin/env python3
"""Gravity compensation of a Franka Panda, simulated with rigid from Python.

    pip install ./crates/rigid-py example-robot-data     # then:
    python3 examples/python/gravity_compensation.py [--plot out.png]

The arm starts at rest in a bent pose. Three controllers are simulated for 2 s (semi-implicit
Euler on the joint Lie group, dt = 1 ms, forward dynamics by ABA):

- no torque: the arm falls;
- gravity compensation, tau = g(q): the arm stays where it is (up to the integrator's drift);
- 10 % too little compensation, tau = 0.9 g(q): the arm sags.

Then the mass matrix M(q) is evaluated over a sweep of the elbow joint with one batch call
(`rigid.crba_batch`, every core), and its diagonal printed (or plotted, with --plot and
matplotlib). Without example-robot-data the built-in PUMA 560 is used instead.
"""
import argparse
import glob
import os
import site
import sys

import numpy as np

import rigid


def panda_urdf():
    roots = [sys.prefix] + site.getsitepackages() + [site.getusersitepackages()]
    for root in roots:
        hits = glob.glob(os.path.join(
            root, "cmeel.prefix/share/example-robot-data/robots/panda_description/urdf/panda.urdf"))
        if hits:
            return hits[0]
    return None


def simulate(model, q0, torque, seconds=2.0, dt=1e-3):
    """Semi-implicit Euler: v += aba(q, v, tau) dt; q = q ⊕ v dt."""
    data = model.create_data()
    q, v = q0.copy(), np.zeros(model.nv)
    for _ in range(int(seconds / dt)):
        a = rigid.aba(model, data, q, v, torque(data, q, v))
        v = v + a * dt
        q = rigid.integrate(model, q, v * dt)
    return q


def main():
    ap = argparse.ArgumentParser(description="Gravity compensation of a Panda with rigid")
    ap.add_argument("--plot", help="draw the mass matrix sweep to this PNG (needs matplotlib)")
    ap.add_argument("--seconds", type=float, default=2.0)
    args = ap.parse_args()

    path = panda_urdf()
    if path:
        model = rigid.Model.from_urdf(path, layout="pinocchio")
        q0 = np.array([0.0, -0.6, 0.0, -2.2, 0.0, 1.6, 0.8, 0.02, 0.02])
    else:
        print("example-robot-data not found: using the built-in PUMA 560")
        model = rigid.Model.builtin("puma560")
        q0 = np.array([0.0, 0.6, -1.0, 0.0, 0.5, 0.0])
    print(model)
    zero = np.zeros(model.nv)

    def wrong_gravity(data, q, v):
        return 0.9 * rigid.gravity(model, data, q)

    runs = {
        "no torque": lambda data, q, v: zero,
        "tau = g(q)": lambda data, q, v: rigid.gravity(model, data, q),
        "tau = 0.9 g(q)": wrong_gravity,
    }
    for name, torque in runs.items():
        q = simulate(model, q0, torque, args.seconds)
        drift = np.linalg.norm(rigid.difference(model, q0, q))
        print(f"{name:>15}: |q(T) - q(0)| = {drift:.3e} rad after {args.seconds:g} s")

    # M(q) along a sweep of one joint, in one batch call
    k = 3 if model.nv > 6 else 2
    angles = np.linspace(-2.5, 0.0, 50)
    Q = np.tile(q0, (len(angles), 1))
    Q[:, k] = angles
    M = rigid.crba_batch(model, Q)
    diag = np.diagonal(M, axis1=1, axis2=2)
    print(f"\nM(q) diagonal (kg·m²) as joint {model.names[k]} sweeps {angles[0]:g} .. "
          f"{angles[-1]:g} rad:")
    for a, d in list(zip(angles, diag))[::7]:
        print(f"  q = {a:6.2f}: " + " ".join(f"{x:7.4f}" for x in d))
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4))
        for i in range(model.nv):
            ax.plot(angles, diag[:, i], label=f"M[{i},{i}]")
        ax.set_xlabel(f"{model.names[k]} (rad)")
        ax.set_ylabel("kg·m²")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=100)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
