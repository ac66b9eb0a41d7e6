"""rigid.pinocchio: Pinocchio's Python API for dynamics and kinematics, computed by rigid.

    import rigid.pinocchio as pin
    model = pin.buildModelFromUrdf("ur5.urdf")
    data = model.createData()
    tau = pin.rnea(model, data, q, v, a)

or, for a script written for Pinocchio, unchanged: ``python -m rigid.pinocchio script.py [args]``
(its ``import pinocchio`` is this module).

Names, signatures, return types and the fields algorithms fill in ``data`` are Pinocchio's
(4.1); so is the layout: ``Motion``/``Force`` linear first, free-flyer velocity ``(v, ω)``,
Jacobian rows ``(v, ω)``, continuous joints ``(cos θ, sin θ)``, sibling joints sorted by name.
Everything is computed by rigid (this module never imports Pinocchio). Geometry models,
collisions and distances run on rigid's collision layer (parry; ``rigid.pinocchio.fcl`` holds
hpp-fcl's shapes, a mesh collides as its convex hull); the viewers are absent and fail as
Pinocchio's do without their clients (``rigid.pinocchio.visualize``). What is not covered
(code generation, contact solvers beyond constraintDynamics, a few algorithms) raises
``NotImplementedError`` naming the function and what to use instead; ``COVERED`` lists what is.
"""

import sys as _sys

from .. import rigid as _r
from . import (algorithms, compose, constraints, data, explog, fcl, geometry, joints,  # noqa: F401
               loaders, model, parallel, spatial, utils, visualize)
from .algorithms import *  # noqa: F401,F403
from .compose import *  # noqa: F401,F403
from .constraints import *  # noqa: F401,F403
from .loaders import *  # noqa: F401,F403
from .data import *  # noqa: F401,F403
from .explog import *  # noqa: F401,F403
from .geometry import *  # noqa: F401,F403
from .joints import *  # noqa: F401,F403
from .joints import ArgumentPosition, JOINT_MODELS  # noqa: F401
from .model import *  # noqa: F401,F403
from .parallel import *  # noqa: F401,F403
from .robot_wrapper import RobotWrapper  # noqa: F401
from .spatial import *  # noqa: F401,F403

#: The Pinocchio API level this layer follows.
__version__ = "4.1.0"
PINOCCHIO_MAJOR_VERSION, PINOCCHIO_MINOR_VERSION, PINOCCHIO_PATCH_VERSION = 4, 1, 0
#: rigid's version.
rigid_version = _r.__version__

WITH_HPP_FCL = WITH_COLLISION = WITH_HPP_FCL_BINDINGS = True  # rigid's collision layer (parry)
WITH_URDFDOM = True
WITH_SDFORMAT = WITH_CPPAD = WITH_OPENMP = False
ScalarType = float

WORLD, LOCAL, LOCAL_WORLD_ALIGNED = (ReferenceFrame.WORLD, ReferenceFrame.LOCAL,  # noqa: F405
                                     ReferenceFrame.LOCAL_WORLD_ALIGNED)  # noqa: F405
OP_FRAME, JOINT, FIXED_JOINT, BODY, SENSOR = (FrameType.OP_FRAME, FrameType.JOINT,  # noqa: F405
                                              FrameType.FIXED_JOINT, FrameType.BODY,  # noqa: F405
                                              FrameType.SENSOR)  # noqa: F405
POSITION, VELOCITY, ACCELERATION = (KinematicLevel.POSITION, KinematicLevel.VELOCITY,  # noqa: F405
                                    KinematicLevel.ACCELERATION)  # noqa: F405
ARG0, ARG1, ARG2, ARG3, ARG4 = tuple(ArgumentPosition)
XAxis, YAxis, ZAxis = 0, 1, 2


def printVersion(*args):
    print(__version__, *args)


def checkVersionAtLeast(major, minor, patch):
    return (4, 1, 0) >= (major, minor, patch)


def inverse_kinematics(model, frame, target_pose, q0=None, **kwargs):
    """rigid's inverse kinematics (``rigid.inverse_kinematics``; not a Pinocchio function):
    ``frame`` a joint or frame name or a frame index of this model."""
    if isinstance(frame, int):
        frame = model.frames[frame].name
    return _r.inverse_kinematics(model, frame, target_pose, q0, **kwargs)


# ---------------------------------------------------------------- what is not covered

# Pinocchio 4.1's top-level names this layer does not provide, by what to use instead.
_GEOMETRY = (
    "rigid.pinocchio's geometry covers GeometryModel, buildGeomFromUrdf, computeCollisions and "
    "computeDistances (meshes as convex hulls); not this function: use Pinocchio with coal")
_VIEWER = "rigid.pinocchio has no viewer; draw a motion with rigid.replay_html(model, run, path)"
_CONSTRAINT = (
    "rigid.pinocchio covers constraintDynamics, impulseDynamics and initConstraintDynamics "
    "with RigidConstraintModel (rigid.constraint_dynamics); not this solver or cone")
_AUTODIFF = (
    "rigid has no automatic differentiation or code generation: use the analytical derivatives "
    "(computeRNEADerivatives, computeABADerivatives, computeForwardKinematicsDerivatives) or "
    "`rigid explicit` for code")
_DEFAULT = (
    "not covered by rigid.pinocchio (the dynamics and kinematics of Pinocchio's API: see "
    "rigid.pinocchio.COVERED)")

_HINTS = {
    "dIntegrate": "rigid's library has them (rigid::multibody::integrate_jacobians); not in Python",
    "dDifference": "rigid's library has them (rigid::multibody::difference_jacobians); not in "
                   "Python",
    "computeJointJacobiansTimeVariation": "rigid's library has it "
                                          "(rigid::multibody::compute_joint_jacobians_time_"
                                          "variation); not in Python yet",
    "getJointJacobianTimeVariation": "rigid's library has it "
                                     "(rigid::multibody::joint_jacobian_time_variation)",
    "getFrameJacobianTimeVariation": "rigid's library has it "
                                     "(rigid::multibody::frame_jacobian_time_variation)",
    "frameJacobianTimeVariation": "rigid's library has it "
                                  "(rigid::multibody::frame_jacobian_time_variation)",
    "bodyRegressor": "rigid.regressor (computeJointTorqueRegressor) and rigid.dynamic_parameters",
    "jointBodyRegressor": "rigid.regressor (computeJointTorqueRegressor)",
    "frameBodyRegressor": "rigid.regressor (computeJointTorqueRegressor)",
    "computeStaticRegressor": "rigid.regressor",
    "computeKineticEnergyRegressor": "rigid.regressor",
    "computePotentialEnergyRegressor": "rigid.regressor",
    "contactInverseDynamics": "rigid.contact_inverse_dynamics (a least-norm law, not Pinocchio's "
                              "compliant one)",
}


def _hint(name):
    if name in _HINTS:
        return _HINTS[name]
    low = name.lower()
    if any(k in low for k in ("collision", "geom", "distance", "broadphase", "coal", "hppfcl",
                              "mesh", "contactpatch", "bodyradius")):
        return _GEOMETRY
    if "viewer" in low or "visual" in low:
        return _VIEWER
    if any(k in low for k in ("constraint", "contact", "delassus", "admm", "pgs", "cone",
                              "friction", "impulse", "kkt", "proximal", "baumgarte", "lcaba")):
        return _CONSTRAINT
    if any(k in low for k in ("codegen", "casadi", "cppad", "autodiff", "cast")):
        return _AUTODIFF
    return _DEFAULT


_PINOCCHIO_NAMES = set("""
ADMMConstraintSolver ADMMProximalRule ADMMSolverResult ADMMSolverSettings ADMMSolverStats
ADMMUpdateRule BaumgarteCorrectorParameters BoxSet CachedMeshLoader CollisionCallBackBase
CollisionCallBackCollect CollisionCallBackDefault CollisionGeometry CollisionObject
CollisionPair CollisionResult ComputeCollision ComputeDistance ConstraintCholeskyDecomposition
ConstraintData ConstraintModel Contact ContactCholeskyDecomposition CoulombFrictionCone
DelassusCholeskyExpression DelassusOperatorCholeskyExpression DelassusOperatorDense
DelassusOperatorSparse DistanceResult DualCoulombFrictionCone FrameAnchorConstraintData
FrameAnchorConstraintModel FrictionCoefficientMatrix FullSpaceCone GeometryNoMaterial
GeometryPhongMaterial GeometryPool Hlog3 JointData JointFrictionConstraintData
JointFrictionConstraintModel JointLimitConstraintData JointLimitConstraintModel
LanczosDecomposition LieGroup LogCholeskyParameters MeshLoader NonNegativeOrthantCone
PGSConstraintSolver PGSSolverResult PGSSolverSettings PGSSolverStats PhysicsMaterial
PointAnchorConstraintData PointAnchorConstraintModel PointContactConstraintData
PointContactConstraintModel PseudoInertia Symmetric3 TridiagonalSymmetricMatrix ZeroCone
bodyRegressor buildGeomFromMJCF buildGeomFromUrdfString
buildModelAndConstraintsFromMJCF buildModelAndLegacyConstraintsFromMJCF
buildModelFromMJCFAndRootJoint buildModelsAndConstraintsFromMJCF
buildModelsAndConstraintsFromSdf buildModelsFromSdf 
buildSampleGeometryModelHumanoid buildSampleGeometryModelManipulator cholesky compactTangentMap
computeBodyRadius computeCentroidalDynamicsDerivatives computeCentroidalMap
computeCentroidalMapTimeVariation computeCentroidalMomentumTimeVariation
computeCollisionsInParallel computeConstraintDynamicsDerivatives computeContactPatch
computeContactPatches computeDampedDelassusMatrixInverse computeDelassusMatrix
computeFrameKinematicRegressor computeImpulseDynamicsDerivatives
computeInverseDynamicsConstraintForces computeJointJacobiansTimeVariation
computeJointKinematicHessians computeJointKinematicRegressor computeJointMinimalOrdering
computeKKTContactDynamicMatrixInverse computeKineticEnergyRegressor
computePotentialEnergyRegressor computeStaticRegressor computeStaticTorque
computeStaticTorqueDerivatives computeSupportedForceByFrame computeSupportedInertiaByFrame
contactInverseDynamics convertToRigidConstraintModel dDifference dIntegrate dIntegrateTransport
dccrba exp3_quat exp6_quat explog findCommonAncestor frameBodyRegressor
frameJacobianTimeVariation getCenterOfMassVelocityDerivatives getCentroidalDynamicsDerivatives
getConstraintJacobian getConstraintsJacobian getCoriolisMatrix getFrameJacobianTimeVariation
getFrameKinematicHessian getFrictionCoefficientMatrix getJacobianSubtreeCenterOfMass
getJointJacobianTimeVariation getJointKinematicHessian getKKTContactDynamicMatrixInverse
getPointClassicAccelerationDerivatives getPointVelocityDerivatives
getTangentToConfigurationSparsitySegment jacobianSubtreeCenterOfMass jointBodyRegressor lcaba
lieGroup liegroups loadReferenceConfigurationsFromXML loadRotorParameters log6_quat
orthogonalization orthonormalization removeCollisionPairsFromXML serialization sharedMemory
tangentMap tangentMapProduct tangentMapTransposeProduct transformJointIntoMimic
updateGlobalPlacements casadi cppad codegen
""".split())


class _Missing:
    """A name of Pinocchio's API that this layer does not provide: calling it (or an attribute
    of it) raises NotImplementedError naming it and what to use instead."""

    def __init__(self, name):
        self._name = name

    def __call__(self, *args, **kwargs):
        raise NotImplementedError(f"pinocchio.{self._name}: {_hint(self._name.split('.')[0])}")

    def __getattr__(self, attr):
        if attr.startswith("__"):
            raise AttributeError(attr)
        return _Missing(f"{self._name}.{attr}")

    def __repr__(self):
        return f"<not provided by rigid.pinocchio: pinocchio.{self._name}>"


def __getattr__(name):
    if name in _PINOCCHIO_NAMES:
        return _Missing(name)
    raise AttributeError(f"module 'rigid.pinocchio' has no attribute '{name}' (not a name of "
                         "Pinocchio's API that rigid.pinocchio knows)")


COVERED = sorted(n for n in dir(_sys.modules[__name__]) if not n.startswith("_")
                 and n not in ("algorithms", "compose", "constraints", "data", "explog", "fcl", "geometry",
                               "joints", "loaders", "model", "parallel", "spatial", "utils",
                               "visualize"))
