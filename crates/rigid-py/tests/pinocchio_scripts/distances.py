# Distances between primitive shapes (hpp-fcl's) on a chain of three revolute joints, at three
# configurations: every pair's distance and whether it collides.
import numpy as np
import hppfcl as fcl
import pinocchio as pin

model = pin.Model()
geom_model = pin.GeometryModel()
shapes = [fcl.Sphere(0.1), fcl.Box(0.2, 0.1, 0.3), fcl.Capsule(0.05, 0.3), fcl.Cylinder(0.08, 0.2)]
parent = 0
placement = pin.SE3.Identity()
for k in range(3):
    parent = model.addJoint(parent, pin.JointModelRY(), placement, f"joint_{k}")
    model.appendBodyToJoint(parent, pin.Inertia.FromSphere(1.0, 0.1), pin.SE3.Identity())
    placement = pin.SE3(pin.utils.rotate("x", 0.3 * k), np.array([0.05, 0.0, 0.35]))
    for i, shape in enumerate(shapes[k:k + 2]):
        M = pin.SE3(pin.utils.rotate("z", 0.4 * i), np.array([0.1 * i, 0.05, 0.1 + 0.1 * i]))
        geom_model.addGeometryObject(pin.GeometryObject(f"g{k}_{i}", parent, M, shape))
geom_model.addAllCollisionPairs()
geom_data = geom_model.createData()
data = model.createData()
distances, collisions, nearest = [], [], []
for q in (np.array([0.1, 0.2, -0.1]), np.array([0.5, -1.0, 0.8]), np.array([2.0, 2.5, -2.0])):
    pin.computeDistances(model, data, geom_model, geom_data, q)
    distances.append([r.min_distance for r in geom_data.distanceResults])
    pin.computeCollisions(geom_model, geom_data, False)
    collisions.append([float(r.isCollision()) for r in geom_data.collisionResults])
distances, collisions = np.array(distances), np.array(collisions)
print("distances:", distances.round(4))
