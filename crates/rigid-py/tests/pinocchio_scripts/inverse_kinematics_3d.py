# Position-only inverse kinematics of a URDF's last frame (argv[1]) to a point, in the world.
import sys

import numpy as np
import pinocchio as pin

model = pin.buildModelFromUrdf(sys.argv[1])
data = model.createData()
frame = model.nframes - 1
q = pin.neutral(model)
pin.framesForwardKinematics(model, data, q)
target = data.oMf[frame].translation + np.array([0.05, -0.1, 0.08])

trajectory = [q.copy()]
for it in range(200):
    pin.framesForwardKinematics(model, data, q)
    err = target - data.oMf[frame].translation
    if np.linalg.norm(err) < 1e-10:
        break
    J = pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL_WORLD_ALIGNED)[:3, :]
    v = J.T @ np.linalg.solve(J @ J.T + 1e-6 * np.eye(3), err)
    q = pin.integrate(model, q, v)
    trajectory.append(q.copy())
final_error = np.linalg.norm(err)
print(f"{it} iterations, error {final_error:.3e}")
