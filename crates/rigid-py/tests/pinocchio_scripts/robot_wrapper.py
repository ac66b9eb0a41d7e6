# RobotWrapper shortcuts on a URDF (argv[1], meshes under argv[2]).
import sys

import numpy as np
from pinocchio.robot_wrapper import RobotWrapper

import pinocchio as pin

robot = RobotWrapper.BuildFromURDF(sys.argv[1], [sys.argv[2]])
q = pin.randomConfiguration(robot.model)
v = np.linspace(-1.0, 1.0, robot.nv)
frame = robot.model.nframes - 1
oMf = robot.framePlacement(q, frame)
J = robot.computeFrameJacobian(q, frame)
com = robot.com(q)
M = robot.mass(q)
b = robot.nle(q, v)
g = robot.gravity(q)
q0 = robot.q0
print(robot.nq, robot.nv, oMf.translation)
