"""Reference trajectory of rigid's built-in `double_pendulum` by SciPy, for tests/it/simulation.rs.

Two uniform thin rods (m = 1 kg, l = 1 m) hanging along -z, joints about y, the second at the tip
of the first; q2 is the relative angle. With a = l/2 and I = m l^2/12 (about the CoM, the rods'
own axis has no inertia and no motion), the closed-form equations of the planar two-link arm:

    M11 = I1 + m1 a1^2 + I2 + m2 (l1^2 + a2^2 + 2 l1 a2 cos q2)
    M12 = I2 + m2 (a2^2 + l1 a2 cos q2),   M22 = I2 + m2 a2^2
    c   = (-h (2 q1' q2' + q2'^2), h q1'^2),   h = m2 l1 a2 sin q2
    g   = (m1 g a1 sin q1 + m2 g (l1 sin q1 + a2 sin(q1 + q2)), m2 g a2 sin(q1 + q2))

integrated by solve_ivp (DOP853, rtol = atol = 1e-12). Prints JSON: {"t": [...], "q": [[...]],
"v": [[...]]} at the requested sample times.

    python3 double_pendulum.py Q1 Q2 V1 V2 DURATION SAMPLES

The live cross-check (RIGID_CROSSCHECK=1) runs it; every run reads double_pendulum.json, the
fixture gen_double_pendulum.py writes with it.
"""

import json
import sys

import numpy as np
from scipy.integrate import solve_ivp

M1 = M2 = 1.0
L1 = L2 = 1.0
G = 9.81
A1, A2 = L1 / 2, L2 / 2
I1, I2 = M1 * L1**2 / 12, M2 * L2**2 / 12


def rhs(_t, y):
    q1, q2, v1, v2 = y
    c2, s2 = np.cos(q2), np.sin(q2)
    m11 = I1 + M1 * A1**2 + I2 + M2 * (L1**2 + A2**2 + 2 * L1 * A2 * c2)
    m12 = I2 + M2 * (A2**2 + L1 * A2 * c2)
    m22 = I2 + M2 * A2**2
    h = M2 * L1 * A2 * s2
    c = np.array([-h * (2 * v1 * v2 + v2**2), h * v1**2])
    g = np.array(
        [
            M1 * G * A1 * np.sin(q1) + M2 * G * (L1 * np.sin(q1) + A2 * np.sin(q1 + q2)),
            M2 * G * A2 * np.sin(q1 + q2),
        ]
    )
    a = np.linalg.solve(np.array([[m11, m12], [m12, m22]]), -c - g)
    return [v1, v2, a[0], a[1]]


def main():
    q1, q2, v1, v2, duration = map(float, sys.argv[1:6])
    samples = int(sys.argv[6])
    ts = np.linspace(0.0, duration, samples + 1)
    sol = solve_ivp(
        rhs, (0.0, duration), [q1, q2, v1, v2], method="DOP853", rtol=1e-12, atol=1e-12, t_eval=ts
    )
    assert sol.success, sol.message
    print(
        json.dumps(
            {
                "t": ts.tolist(),
                "q": sol.y[:2].T.tolist(),
                "v": sol.y[2:].T.tolist(),
            }
        )
    )


if __name__ == "__main__":
    main()
