"""``pinocchio.visualize`` without a viewer: rigid.pinocchio draws nothing live (a motion is
drawn offline by ``rigid.replay_html(model, run, path)``). Each viewer fails the way Pinocchio's
does when its client is not installed, so that Pinocchio's examples take their own way out:
``MeshcatVisualizer`` and ``Panda3dVisualizer`` raise ImportError when made, ``RVizVisualizer``
on ``initViewer``; ``GepettoVisualizer.initViewer`` warns, and loading or displaying a model then
raises AttributeError (no ``viewer``)."""

import warnings
from enum import Enum

__all__ = ["BaseVisualizer", "GepettoVisualizer", "MeshcatVisualizer", "Panda3dVisualizer",
           "RVizVisualizer", "Visualizer"]

_HINT = "rigid.pinocchio has no live viewer: rigid.replay_html(model, run, path) draws a motion"


class BaseVisualizer:
    """Holds the models and their data, as Pinocchio's base class."""

    def __init__(self, model=None, collision_model=None, visual_model=None, copy_models=False,
                 data=None, collision_data=None, visual_data=None):
        self.model = model
        self.collision_model = collision_model
        self.visual_model = visual_model
        self.data = data if data is not None or model is None else model.createData()
        self.collision_data = (collision_data if collision_data is not None
                               or collision_model is None else collision_model.createData())
        self.visual_data = (visual_data if visual_data is not None or visual_model is None
                            else visual_model.createData())

    def rebuildData(self):
        self.data = self.model.createData()
        if self.collision_model is not None:
            self.collision_data = self.collision_model.createData()
        if self.visual_model is not None:
            self.visual_data = self.visual_model.createData()

    def initViewer(self, *args, **kwargs):
        raise ImportError(_HINT)

    def loadViewerModel(self, *args, **kwargs):
        raise ImportError(_HINT)

    def display(self, q=None):
        raise ImportError(_HINT)


class MeshcatVisualizer(BaseVisualizer):
    def __init__(self, *args, **kwargs):
        raise ImportError("Error while importing the viewer client.\n"
                          "Check whether meshcat is properly installed "
                          f"(pip install --user meshcat).\n({_HINT})")


class Panda3dVisualizer(BaseVisualizer):
    def __init__(self, *args, **kwargs):
        raise ImportError(f"Error while importing the viewer client (panda3d_viewer).\n({_HINT})")


class RVizVisualizer(BaseVisualizer):
    def initViewer(self, *args, **kwargs):
        raise ImportError(f"Error while importing the viewer client (rospy).\n({_HINT})")


class GepettoVisualizer(BaseVisualizer):
    def initViewer(self, *args, **kwargs):
        warnings.warn("Error while importing the viewer client.\nCheck whether gepetto-gui is "
                      f"properly installed\n({_HINT})", category=UserWarning, stacklevel=2)

    def _no_viewer(self, *args, **kwargs):
        raise AttributeError("'GepettoVisualizer' object has no attribute 'viewer'")

    loadViewerModel = display = displayCollisions = displayVisuals = _no_viewer


class Visualizer(Enum):
    BASE = BaseVisualizer
    GEPETTO = GepettoVisualizer
    MESHCAT = MeshcatVisualizer
    PANDA3D = Panda3dVisualizer
    RVIZ = RVizVisualizer

    @classmethod
    def default(cls):
        """No viewer client is installed for rigid.pinocchio: the base visualizer."""
        return cls.BASE
