# Centre of mass and centroidal momentum of a floating robot (argv[1]).
import sys

import numpy as np
import pinocchio as pin

model = pin.buildModelFromUrdf(sys.argv[1], pin.JointModelFreeFlyer())
data = model.createData()
model.lowerPositionLimit[:3] = -1.0
model.upperPositionLimit[:3] = 1.0
lower, upper = model.lowerPositionLimit.copy(), model.upperPositionLimit.copy()
lower[:3], upper[:3] = -1.0, 1.0
q = pin.randomConfiguration(model, lower, upper)
v = np.random.rand(model.nv)
a = np.random.rand(model.nv)

com = pin.centerOfMass(model, data, q, v, a)
vcom, acom = data.vcom[0].copy(), data.acom[0].copy()
Jcom = pin.jacobianCenterOfMass(model, data, q)
Ag = pin.ccrba(model, data, q, v)
hg = data.hg.copy()
Ig = data.Ig.copy()
h = pin.computeCentroidalMomentum(model, data, q, v)
pin.computeAllTerms(model, data, q, v)
terms = (data.M.copy(), data.nle.copy(), data.Jcom.copy(), data.Ag.copy())
energies = (data.kinetic_energy, data.potential_energy)
mass = pin.computeTotalMass(model)
print("mass", mass, "com", com)
