# A URDF (argv[1], meshes under argv[2]) with a spherical pendulum appended at its frame argv[3],
# and with a second URDF (argv[4]; its base link, welded to the world, joins the frame's body);
# and the first URDF with its last three joints locked: the models' dynamics and geometry.
import sys

import numpy as np
import hppfcl as fcl
import pinocchio as pin

model1, collision1, visual1 = pin.buildModelsFromUrdf(sys.argv[1], sys.argv[2])
model2 = pin.Model()
model2.name = "pendulum"
geom2 = pin.GeometryModel()
j = model2.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "joint_spherical")
body = pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.1]))
model2.appendBodyToJoint(j, pin.Inertia.FromSphere(1.0, 0.01), body)
model2.addFrame(pin.Frame("pendulum_body", j, 0, body, pin.FrameType.BODY))
geom2.addGeometryObject(pin.GeometryObject("ball", j, body, fcl.Sphere(0.01)))
model, visual = pin.appendModel(model1, model2, visual1, geom2,
                                model1.getFrameId(sys.argv[3]), pin.SE3.Identity())
data = model.createData()
shape = (model.nq, model.nv, model.njoints, model.nframes, visual.ngeoms)
q = pin.randomConfiguration(model)
v = np.linspace(-1.0, 1.0, model.nv)
M = pin.crba(model, data, q)
tau = pin.rnea(model, data, q, v, v)
pin.framesForwardKinematics(model, data, q)
frames = list(data.oMf)
frame_parents = np.array([f.parentJoint for f in model.frames], float)
visual_data = visual.createData()
pin.updateGeometryPlacements(model, data, visual, visual_data)
visual_world = list(visual_data.oMg)

model_b = pin.buildModelFromUrdf(sys.argv[4])
both = pin.appendModel(model1, model_b, model1.getFrameId(sys.argv[3]),
                       pin.SE3(pin.utils.rotate("z", 0.5), np.array([0.0, 0.1, 0.2])))
data_both = both.createData()
q_both = pin.randomConfiguration(both)
M_both = pin.crba(both, data_both, q_both)
tau_both = pin.rnea(both, data_both, q_both, np.ones(both.nv), np.ones(both.nv))

lock = list(range(model1.njoints - 3, model1.njoints))
q1 = pin.randomConfiguration(model1)
reduced, (collision_r, visual_r) = pin.buildReducedModel(
    model1, list_of_geom_models=[collision1, visual1], list_of_joints_to_lock=lock,
    reference_configuration=q1)
data_r = reduced.createData()
reduced_shape = (reduced.nq, reduced.nv, reduced.njoints, reduced.nframes)
qr = pin.randomConfiguration(reduced)
M_reduced = pin.crba(reduced, data_r, qr)
tau_reduced = pin.rnea(reduced, data_r, qr, np.ones(reduced.nv), np.ones(reduced.nv))
pin.framesForwardKinematics(reduced, data_r, qr)
reduced_frames = list(data_r.oMf)
reduced_frame_types = np.array([int(f.type) for f in reduced.frames], float)
collision_data_r = collision_r.createData()
pin.updateGeometryPlacements(reduced, data_r, collision_r, collision_data_r)
reduced_collision_world = list(collision_data_r.oMg)
print("appended:", shape, "reduced:", reduced_shape)
