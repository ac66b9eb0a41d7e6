# Pinocchio's simulation examples without a viewer: a cart with a chain of N pendulums built
# through the API with hpp-fcl geometry, integrated by aba and integrate for 300 steps.
import numpy as np
import hppfcl as fcl
import pinocchio as pin

model = pin.Model()
geom_model = pin.GeometryModel()
cart = model.addJoint(0, pin.JointModelPY(), pin.SE3.Identity(), "joint_cart")
model.appendBodyToJoint(cart, pin.Inertia.FromCylinder(2.0, 0.1, 0.5), pin.SE3.Identity())
geom_model.addGeometryObject(
    pin.GeometryObject("shape_cart", cart, pin.SE3.Identity(), fcl.Cylinder(0.1, 0.5)))
parent, placement = cart, pin.SE3.Identity()
for k in range(4):
    j = model.addJoint(parent, pin.JointModelRX(), placement, f"joint_{k + 1}")
    body = placement.copy()
    body.translation[2] = 1.0
    model.appendBodyToJoint(j, pin.Inertia.FromSphere(1.0, 0.1), body)
    geom_model.addGeometryObject(pin.GeometryObject(f"ball_{k + 1}", j, body, fcl.Sphere(0.1)))
    parent, placement = j, body.copy()
data = model.createData()
geom_data = geom_model.createData()
q = pin.neutral(model)
q[1:] = [0.3, -0.2, 0.1, 0.4]
v = np.zeros(model.nv)
dt = 0.005
energy = [pin.computeMechanicalEnergy(model, data, q, v)]
for k in range(300):
    a = pin.aba(model, data, q, v, -0.1 * v)
    v += a * dt
    q = pin.integrate(model, q, v * dt)
    energy.append(pin.computeMechanicalEnergy(model, data, q, v))
pin.updateGeometryPlacements(model, data, geom_model, geom_data, q)
balls = [M.translation.copy() for M in geom_data.oMg]
print("final q:", q.round(4))
