# A URDF (argv[1]): joint and frame placements at a random configuration.
import sys

import pinocchio

model = pinocchio.buildModelFromUrdf(sys.argv[1])
print("model name: " + model.name)
data = model.createData()
q = pinocchio.randomConfiguration(model)
print(f"q: {q.T}")
pinocchio.forwardKinematics(model, data, q)
joints = [data.oMi[i].translation.copy() for i in range(model.njoints)]
for name, oMi in zip(model.names, data.oMi):
    print("{:<24} : {: .2f} {: .2f} {: .2f}".format(name, *oMi.translation.T.flat))
pinocchio.framesForwardKinematics(model, data, q)
frames = [(f.name, data.oMf[i]) for i, f in enumerate(model.frames)]
frame_placements = [M for _, M in frames]
last = model.frames[-1].name
tip = data.oMf[model.getFrameId(last)]
print(last, tip.translation)
