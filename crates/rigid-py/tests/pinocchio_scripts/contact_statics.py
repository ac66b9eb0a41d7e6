# Pinocchio's contact dynamics with explicit Jacobians (forwardDynamics with J and gamma, with and
# without damping) on a free-flyer URDF (argv[1]) with its feet argv[2:] held in 3D.
import sys

import numpy as np
import pinocchio as pin

model = pin.buildModelFromUrdf(sys.argv[1], pin.JointModelFreeFlyer())
model.lowerPositionLimit[:7] = -1.0
model.upperPositionLimit[:7] = 1.0
data = model.createData()
q = pin.randomConfiguration(model)
v = np.random.rand(model.nv) - 0.5
tau = np.random.rand(model.nv) - 0.5
feet = [model.getFrameId(n) for n in sys.argv[2:]]
J = np.vstack([pin.computeFrameJacobian(model, data, q, f, pin.LOCAL)[:3] for f in feet])
gamma = np.random.rand(J.shape[0])
a = pin.forwardDynamics(model, data, q, v, tau, J, gamma)
lam = data.lambda_c.copy()
a_damped = pin.forwardDynamics(model, data, q, v, tau, J, gamma, 1e-3)
lam_damped = data.lambda_c.copy()
constraint = J @ a + gamma
print("|J a + gamma| =", np.linalg.norm(constraint))
