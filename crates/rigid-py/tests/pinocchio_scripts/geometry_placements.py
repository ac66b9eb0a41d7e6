# The collision and visual geometry of a URDF (argv[1], its meshes under argv[2]): every object's
# joint, frame, local placement and scale, and its world placement at a random configuration.
import sys

import numpy as np
import pinocchio as pin

model, collision_model, visual_model = pin.buildModelsFromUrdf(sys.argv[1], sys.argv[2])
data, collision_data, visual_data = pin.createDatas(model, collision_model, visual_model)
q = pin.randomConfiguration(model)
pin.updateGeometryPlacements(model, data, collision_model, collision_data, q)
pin.updateGeometryPlacements(model, data, visual_model, visual_data)

ngeoms = (collision_model.ngeoms, visual_model.ngeoms)
collision_joints = np.array([g.parentJoint for g in collision_model.geometryObjects], float)
collision_frames = np.array([g.parentFrame for g in collision_model.geometryObjects], float)
visual_joints = np.array([g.parentJoint for g in visual_model.geometryObjects], float)
visual_frames = np.array([g.parentFrame for g in visual_model.geometryObjects], float)
collision_local = [g.placement for g in collision_model.geometryObjects]
visual_scales = np.array([g.meshScale for g in visual_model.geometryObjects])
collision_world = list(collision_data.oMg)
visual_world = list(visual_data.oMg)
names_agree = float(all(g.name == f"{model.frames[g.parentFrame].name}_{g.name.split('_')[-1]}"
                        for g in collision_model.geometryObjects))
print(f"{ngeoms[0]} collision and {ngeoms[1]} visual objects")
