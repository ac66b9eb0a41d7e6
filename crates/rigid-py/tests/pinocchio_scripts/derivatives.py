# Analytical derivatives of the dynamics and the kinematics on the random humanoid, as in
# Pinocchio's derivative examples.
import numpy as np
import pinocchio as pin

model = pin.buildSampleModelHumanoidRandom()
data = model.createData()
model.lowerPositionLimit = -np.ones((model.nq, 1))
model.upperPositionLimit = np.ones((model.nq, 1))

q = pin.randomConfiguration(model)
v = np.random.rand(model.nv, 1)
a = np.random.rand(model.nv, 1)
tau = np.random.rand(model.nv, 1)

pin.computeRNEADerivatives(model, data, q, v, a)
dtau_dq, dtau_dv, dtau_da = data.dtau_dq.copy(), data.dtau_dv.copy(), data.M.copy()

pin.computeABADerivatives(model, data, q, v, tau)
ddq_dq, ddq_dv, ddq_dtau = data.ddq_dq.copy(), data.ddq_dv.copy(), data.Minv.copy()

pin.computeForwardKinematicsDerivatives(model, data, q, v, a)
joint_id = model.getJointId("rleg6_joint")
dv_dq, dv_dv = pin.getJointVelocityDerivatives(model, data, joint_id, pin.ReferenceFrame.WORLD)
dv_dq_local, dv_dv_local = pin.getJointVelocityDerivatives(model, data, joint_id,
                                                           pin.ReferenceFrame.LOCAL)
(dv_dq_a, da_dq, da_dv, da_da) = pin.getJointAccelerationDerivatives(
    model, data, joint_id, pin.ReferenceFrame.WORLD)
(dv_dq_lwa, da_dq_lwa, da_dv_lwa, da_da_lwa) = pin.getJointAccelerationDerivatives(
    model, data, joint_id, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
dg_dq = pin.computeGeneralizedGravityDerivatives(model, data, q)
print("done")
