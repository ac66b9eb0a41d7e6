# Collision pairs of a URDF's collision geometry (argv[1], free-flyer) less those its SRDF
# (argv[2]) disables, at the SRDF's configuration argv[3] (meshes under argv[4]): which pairs
# collide.
import sys

import numpy as np
import pinocchio as pin

model = pin.buildModelFromUrdf(sys.argv[1], pin.JointModelFreeFlyer())
geom_model = pin.buildGeomFromUrdf(model, sys.argv[1], pin.GeometryType.COLLISION, sys.argv[4])
geom_model.addAllCollisionPairs()
n_all = len(geom_model.collisionPairs)
pin.removeCollisionPairs(model, geom_model, sys.argv[2])
pairs = np.array([[p.first, p.second] for p in geom_model.collisionPairs], float)
pin.loadReferenceConfigurations(model, sys.argv[2])
q = model.referenceConfigurations[sys.argv[3]].copy()
# Pinocchio 4.1 leaves the base position of a free-flyer the SRDF does not give uninitialised
q[:3] = 0.0
data = model.createData()
geom_data = pin.GeometryData(geom_model)
any_collision = float(pin.computeCollisions(model, data, geom_model, geom_data, q, False))
collided = np.array([float(r.isCollision()) for r in geom_data.collisionResults])
print(f"{n_all} pairs, {len(pairs)} after the SRDF, {int(collided.sum())} colliding")

