# The sample arm: inverse dynamics at rest, then the placement of every joint at a random
# configuration (Pinocchio's style: `import pinocchio`, numpy column vectors, data fields).
import numpy as np
import pinocchio

model = pinocchio.buildSampleModelManipulator()
data = model.createData()

q = pinocchio.neutral(model)
v = pinocchio.utils.zero(model.nv)
a = pinocchio.utils.zero(model.nv)
tau_rest = pinocchio.rnea(model, data, q, v, a)
print("tau =", tau_rest.T)

q = pinocchio.randomConfiguration(model)
v = pinocchio.utils.rand(model.nv)
pinocchio.forwardKinematics(model, data, q, v)
placements = [M.copy() for M in data.oMi]
velocities = [pinocchio.getVelocity(model, data, i, pinocchio.LOCAL_WORLD_ALIGNED)
              for i in range(model.njoints)]
for name, oMi in zip(model.names, data.oMi):
    print("{:<24} : {: .2f} {: .2f} {: .2f}".format(name, *oMi.translation.T.flat))
pinocchio.updateFramePlacements(model, data)
effector = data.oMf[model.getFrameId("effector_body")]
tau = pinocchio.rnea(model, data, q, v, np.zeros(model.nv))
