"""``RobotWrapper``: a model, its data and its geometry models, with Pinocchio's shortcuts
(``framePlacement``, ``computeFrameJacobian``, ``com``, ``mass``, ``nle``, ``gravity``, ...)."""

import numpy as np

from . import algorithms as alg
from .compose import buildReducedModel
from .geometry import GeometryModel, updateGeometryPlacements
from .loaders import buildModelFromMJCF, buildModelsFromUrdf
from .joints import ReferenceFrame

__all__ = ["RobotWrapper"]


class RobotWrapper:
    """A robot: ``model``, ``data``, ``collision_model`` and ``visual_model`` (a URDF's
    ``<collision>`` and ``<visual>`` elements), ``q0`` (the neutral configuration), and
    shortcuts."""

    @staticmethod
    def BuildFromURDF(filename, package_dirs=None, root_joint=None, verbose=False,
                      meshLoader=None, *args, **kwargs):
        robot = RobotWrapper()
        robot.initFromURDF(filename, package_dirs, root_joint, verbose, meshLoader)
        return robot

    @staticmethod
    def BuildFromMJCF(filename, root_joint=None, verbose=False, meshLoader=None):
        robot = RobotWrapper(buildModelFromMJCF(filename, root_joint))
        return robot

    def initFromURDF(self, filename, package_dirs=None, root_joint=None, verbose=False,
                     meshLoader=None):
        self.__init__(*buildModelsFromUrdf(filename, package_dirs, root_joint))

    def __init__(self, model=None, collision_model=None, visual_model=None, verbose=False):
        if model is None:
            return
        self.model = model
        self.collision_model = collision_model if collision_model is not None \
            else GeometryModel()
        self.visual_model = visual_model if visual_model is not None else GeometryModel()
        self.data, self.collision_data, self.visual_data = self.createData()
        self.v0 = np.zeros(model.nv)
        self.q0 = alg.neutral(model)
        self.viz = None

    def buildReducedRobot(self, list_of_joints_to_lock, reference_configuration=None):
        """The robot with those joints (names or indices) locked at ``reference_configuration``
        (default the neutral one), its geometry models reduced alike."""
        ids = [self.model.getJointId(j) if isinstance(j, str) else int(j)
               for j in list_of_joints_to_lock]
        q = alg.neutral(self.model) if reference_configuration is None \
            else reference_configuration
        model, (collision, visual) = buildReducedModel(
            self.model, list_of_geom_models=[self.collision_model, self.visual_model],
            list_of_joints_to_lock=ids, reference_configuration=q)
        return RobotWrapper(model, collision, visual)

    def createData(self):
        self.data = self.model.createData()
        self.collision_data = self.collision_model.createData()
        self.visual_data = self.visual_model.createData()
        return self.data, self.collision_data, self.visual_data

    @property
    def nq(self):
        return self.model.nq

    @property
    def nv(self):
        return self.model.nv

    def com(self, q=None, v=None, a=None):
        if q is None:
            alg.centerOfMass(self.model, self.data)
            return self.data.com[0]
        if v is not None:
            if a is None:
                alg.centerOfMass(self.model, self.data, q, v)
                return self.data.com[0], self.data.vcom[0]
            alg.centerOfMass(self.model, self.data, q, v, a)
            return self.data.com[0], self.data.vcom[0], self.data.acom[0]
        return alg.centerOfMass(self.model, self.data, q)

    def vcom(self, q, v):
        alg.centerOfMass(self.model, self.data, q, v)
        return self.data.vcom[0]

    def acom(self, q, v, a):
        alg.centerOfMass(self.model, self.data, q, v, a)
        return self.data.acom[0]

    def centroidalMomentum(self, q, v):
        return alg.computeCentroidalMomentum(self.model, self.data, q, v)

    def centroidalMap(self, q):
        return alg.ccrba(self.model, self.data, q, np.zeros(self.nv))

    def centroidal(self, q, v):
        alg.ccrba(self.model, self.data, q, v)
        return self.data.hg, self.data.Ag, self.data.Ig

    def Jcom(self, q):
        return alg.jacobianCenterOfMass(self.model, self.data, q)

    def mass(self, q):
        return alg.crba(self.model, self.data, q)

    def nle(self, q, v):
        return alg.nonLinearEffects(self.model, self.data, q, v)

    def gravity(self, q):
        return alg.computeGeneralizedGravity(self.model, self.data, q)

    def forwardKinematics(self, q, v=None, a=None):
        alg.forwardKinematics(self.model, self.data, q, v, a)

    def placement(self, q, index, update_kinematics=True):
        if update_kinematics:
            alg.forwardKinematics(self.model, self.data, q)
        return self.data.oMi[index]

    def velocity(self, q, v, index, update_kinematics=True, reference_frame=ReferenceFrame.LOCAL):
        if update_kinematics:
            alg.forwardKinematics(self.model, self.data, q, v)
        return alg.getVelocity(self.model, self.data, index, reference_frame)

    def acceleration(self, q, v, a, index, update_kinematics=True,
                     reference_frame=ReferenceFrame.LOCAL):
        if update_kinematics:
            alg.forwardKinematics(self.model, self.data, q, v, a)
        return alg.getAcceleration(self.model, self.data, index, reference_frame)

    def classicalAcceleration(self, q, v, a, index, update_kinematics=True,
                              reference_frame=ReferenceFrame.LOCAL):
        if update_kinematics:
            alg.forwardKinematics(self.model, self.data, q, v, a)
        return alg.getClassicalAcceleration(self.model, self.data, index, reference_frame)

    def framePlacement(self, q, index, update_kinematics=True):
        if update_kinematics:
            alg.forwardKinematics(self.model, self.data, q)
        return alg.updateFramePlacement(self.model, self.data, index)

    def frameVelocity(self, q, v, index, update_kinematics=True,
                      reference_frame=ReferenceFrame.LOCAL):
        if update_kinematics:
            alg.forwardKinematics(self.model, self.data, q, v)
        return alg.getFrameVelocity(self.model, self.data, index, reference_frame)

    def frameAcceleration(self, q, v, a, index, update_kinematics=True,
                          reference_frame=ReferenceFrame.LOCAL):
        if update_kinematics:
            alg.forwardKinematics(self.model, self.data, q, v, a)
        return alg.getFrameAcceleration(self.model, self.data, index, reference_frame)

    def frameClassicalAcceleration(self, q, v, a, index, update_kinematics=True,
                                   reference_frame=ReferenceFrame.LOCAL):
        if update_kinematics:
            alg.forwardKinematics(self.model, self.data, q, v, a)
        return alg.getFrameClassicalAcceleration(self.model, self.data, index, reference_frame)

    def jointJacobian(self, q, index, *args, **kwargs):
        return alg.computeJointJacobian(self.model, self.data, q, index)

    def getJointJacobian(self, index, rf=ReferenceFrame.LOCAL):
        return alg.getJointJacobian(self.model, self.data, index, rf)

    def computeJointJacobians(self, q):
        return alg.computeJointJacobians(self.model, self.data, q)

    def updateGeometryPlacements(self, q=None, visual=False):
        """The collision (or, with ``visual``, the visual) objects' world placements, after the
        forward kinematics at ``q`` when given."""
        gm, gd = ((self.visual_model, self.visual_data) if visual
                  else (self.collision_model, self.collision_data))
        updateGeometryPlacements(self.model, self.data, gm, gd, q)

    def framesForwardKinematics(self, q):
        alg.framesForwardKinematics(self.model, self.data, q)

    def computeFrameJacobian(self, q, frame_id):
        return alg.computeFrameJacobian(self.model, self.data, q, frame_id)

    def getFrameJacobian(self, frame_id, rf=ReferenceFrame.LOCAL):
        return alg.getFrameJacobian(self.model, self.data, frame_id, rf)

    def rebuildData(self):
        self.createData()

    def _viewer(self, *args, **kwargs):
        raise NotImplementedError(
            "RobotWrapper viewers (initViewer, display, loadViewerModel, play): rigid.pinocchio "
            "has no viewer; draw a motion with rigid.replay_html(model, run, 'out.html')")

    initViewer = loadViewerModel = display = displayCollisions = displayVisuals = play = \
        setVisualizer = _viewer
