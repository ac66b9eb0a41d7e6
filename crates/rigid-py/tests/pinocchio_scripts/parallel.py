# Pinocchio's parallel algorithms on a URDF (argv[1], free-flyer): rneaInParallel and
# abaInParallel on a pool, into given arrays and allocated, over 37 random states.
import sys

import numpy as np
import pinocchio as pin

model = pin.buildModelFromUrdf(sys.argv[1], pin.JointModelFreeFlyer())
model.lowerPositionLimit[:7] = -1.0
model.upperPositionLimit[:7] = 1.0
pool = pin.ModelPool(model, 2)
batch = 37
q = np.empty((model.nq, batch))
for k in range(batch):
    q[:, k] = pin.randomConfiguration(model)
v = np.random.rand(model.nv, batch) - 0.5
a = np.random.rand(model.nv, batch) - 0.5
res_rnea = np.empty((model.nv, batch))
pin.rneaInParallel(2, pool, q, v, a, res_rnea)
res_aba = pin.abaInParallel(2, pool, q, v, res_rnea)
data = model.createData()
loop = np.column_stack([pin.rnea(model, data, q[:, k], v[:, k], a[:, k]) for k in range(batch)])
print("|aba(rnea(a)) - a| =", np.abs(res_aba - a).max())
