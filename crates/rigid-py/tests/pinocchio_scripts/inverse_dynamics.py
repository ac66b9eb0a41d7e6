# Inverse and forward dynamics of a URDF (argv[1], its meshes under argv[2]) at a random state,
# with column vectors.
import sys

import numpy as np
import pinocchio as pin

model, collision_model, visual_model = pin.buildModelsFromUrdf(sys.argv[1], [sys.argv[2]])
data = model.createData()

q = pin.randomConfiguration(model)
v = np.random.rand(model.nv, 1)
a = np.random.rand(model.nv, 1)

tau = pin.rnea(model, data, q, v, a)
print("Joint torques: " + str(tau))
forces = [data.f[i].vector.copy() for i in range(1, model.njoints)]
M = pin.crba(model, data, q)
b = pin.nonLinearEffects(model, data, q, v)
g = pin.computeGeneralizedGravity(model, data, q)
ddq = pin.aba(model, data, q, v, tau)
Minv = pin.computeMinverse(model, data, q)
C = pin.computeCoriolisMatrix(model, data, q, v)
residual = M @ a.ravel() + b - tau
fext = [pin.Force(np.array([0.0, 0.0, 1.0, 0.1, 0.0, 0.0])) for _ in range(model.njoints)]
tau_ext = pin.rnea(model, data, q, v, a, fext)
ddq_ext = pin.aba(model, data, q, v, tau, fext)
energy = (pin.computeKineticEnergy(model, data, q, v), pin.computePotentialEnergy(model, data, q))
print("|ddq - a| =", np.linalg.norm(ddq - a.ravel()))
