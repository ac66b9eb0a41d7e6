"""rigid: rigid-body dynamics from Rust, with Pinocchio's verbs and numpy arrays.

Conventions (rigid's layout, the default; see docs/conventions.md):

- SI units: kg, m, s, N, N·m, rad. Every result is a fresh float64 numpy array.
- Twists and wrenches **angular first**: V = (ω, v), F = (m, f); Jacobian rows (ω, v).
- Joints depth-first from the root, sibling joints in the order the URDF file lists them.
- Free-flyer q = (x, y, z, qx, qy, qz, qw) (quaternion **x-y-z-w**), velocity the body twist
  (ω_b, v_b); spherical q = (qx, qy, qz, qw), velocity ω_b; continuous joint q = θ (one angle);
  planar q = (x, y, θ), velocity (v_x, v_y, ω).

Pinocchio's layout (``layout="pinocchio"``): the joints in Pinocchio's order (urdfdom sorts
sibling joints by name), a continuous joint's q = (cos θ, sin θ), a planar joint's
q = (x, y, cos θ, sin θ), free-flyer velocity, acceleration and force **linear first** (v_b, ω_b),
Jacobian rows (v, ω). Then q, v, a, τ, M, M⁻¹, C and Jacobians are Pinocchio's raw arrays, with
no reordering. Everything else (placements, CoM, energies) is the same in both layouts.

MuJoCo's layout (``layout="mujoco"``, for MJCF files and URDFs): q is MuJoCo's qpos (hinge and
slide counted from their ``ref``, quaternions **w-x-y-z**), v its qvel (free joint: the world
velocity of the body origin, then the body angular velocity), τ its qfrc; ``crba`` is
``mj_fullM`` (armature included), ``nle`` is ``qfrc_bias``. For a model with a free joint the map
from qvel depends on q, and only rnea, aba, nle, gravity, crba, minverse, jacobian (columns in
qvel), kinetic_energy, com, potential_energy and forward_kinematics accept it.

Inputs: any array-like of real numbers of the right length (a contiguous float64 numpy array is
used in place, without a copy). A wrong length or shape is a ValueError naming the argument, the
expected and the given length; complex numbers, strings and other non-numbers a TypeError; NaN
or infinity a ValueError; a missing file FileNotFoundError; a malformed URDF a ValueError with
the line.
"""

from os import PathLike
from typing import Any, Callable, Literal, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str
features: tuple[str, ...]
"""The optional capabilities of this build: ``"sdp"`` when it has the physically consistent
identification (``identify(..., physical=True)``; built with ``--features sdp``)."""

ArrayLike = npt.ArrayLike
Vector = npt.NDArray[np.float64]
Matrix = npt.NDArray[np.float64]
Path = Union[str, PathLike[str]]
Layout = Literal["rigid", "pinocchio", "mujoco"]
Frame = Union[Literal["world_aligned", "body", "spatial", "local_world_aligned", "local",
                      "world"], Any]

class MjcfWarning(UserWarning):
    """Something in an MJCF file that rigid reads past or tolerates (actuators, sensors, gravity
    compensation, ...): the model loads; the message names the element and the line."""

class SdfWarning(UserWarning):
    """Something in an SDF file that rigid reads past or leaves out (plugins, a gearbox, a loop a
    point or a weld cannot close, ...): the model loads; the message names the element and the
    line."""

class UrdfWarning(UserWarning):
    """Something in a URDF file that was tolerated (a non-physical inertia loaded as written, an
    unknown element, a massless moving link, ...): the message names the element and the line.
    Filter with ``warnings.simplefilter("ignore", rigid.UrdfWarning)``."""

class Model:
    """A kinematic tree (Pinocchio's ``Model``): joints depth-first from the root, their
    placements, the bodies' spatial inertias, limits and gravity. Constant but for ``gravity``.
    Picklable (``copy.deepcopy`` too) through its stable serialised form, which reads back bit
    for bit; subclassable (``rigid.pinocchio.Model`` is one)."""

    def __init__(self, json: str | None = None, layout: Layout = "rigid", *,
                 warnings: Sequence[str] = (), source: Path | None = None,
                 qpos0: ArrayLike | None = None) -> None:
        """A model from its serialised form (``model.to_json()``, what pickling stores) in
        ``layout``; without ``json`` the empty model (no joint; Pinocchio's ``pin.Model()``).
        ``warnings``, ``source`` (the file it was read from) and ``qpos0`` are kept as given."""
    def to_json(self) -> str:
        """The stable serialised form: joints, placements, inertias, frames, limits (null for
        none), armature, damping, friction, gravity, in rigid's layout (JSON)."""

    def save(self, path: str | PathLike[str]) -> list[str]:
        """Write the model as MJCF (``.xml``) or URDF (``.urdf``, its meshes as OBJ files in
        ``STEM_meshes/`` beside it), with the collision geometry of the file it was loaded from,
        as ``rigid convert`` does. Returns the notes on what the format cannot express (velocity
        limits in MJCF, armature in URDF, ...). ``ValueError`` for a joint the format has no
        type for (a ball joint in URDF, a planar joint in MJCF), naming it; nothing is written
        then."""

    def with_dynamic_parameters(self, pi: ArrayLike, *, check: bool = True) -> Model:
        """A new model (same layout) whose body inertias are ``pi`` (10·nb, as
        ``dynamic_parameters``), each checked to be physical: finite, mass ≥ 0, inertia about the
        CoM positive semi-definite with the triangle inequality; ``ValueError`` names the first
        body that is not. ``check=False`` takes them as they are (a model whose own bodies are
        not physical, e.g. a massless rotor inertia)."""

    @overload
    @staticmethod
    def from_urdf(path: Path, floating: bool = False,
                  inertia: Literal["strict", "warn", "repair"] = "warn",
                  layout: Layout = "rigid", mimic: Literal[False] = False) -> Model: ...
    @overload
    @staticmethod
    def from_urdf(path: Path, floating: bool = False,
                  inertia: Literal["strict", "warn", "repair"] = "warn",
                  layout: Layout = "rigid", *, mimic: Literal[True]) -> MimicModel: ...
    @staticmethod
    def from_urdf(path: Path, floating: bool = False,
                  inertia: Literal["strict", "warn", "repair"] = "warn",
                  layout: Layout = "rigid", mimic: bool = False) -> Model | MimicModel:
        """Load a URDF file (Pinocchio's ``buildModelFromUrdf``).

        floating: add a free-flyer root joint ``root_joint`` carrying the root link (Pinocchio's
        ``pin.JointModelFreeFlyer()`` root); otherwise the root link is welded to the world.
        inertia: non-physical inertias are refused (``strict``), loaded as written with a
        ``UrdfWarning`` (``warn``), or replaced by the inertia doctor's repair (``repair``).
        layout: ``"rigid"`` or ``"pinocchio"`` (see the module documentation).
        mimic: ``True`` returns a :class:`MimicModel` whose ``<mimic>`` joints follow their
        sources with no coordinate of their own (Pinocchio's ``mimic=True``)."""
    @overload
    @staticmethod
    def from_mjcf(path: Path, layout: Layout = "rigid",
                  mimic: Literal[False] = False) -> Model: ...
    @overload
    @staticmethod
    def from_mjcf(path: Path, layout: Layout = "rigid", *,
                  mimic: Literal[True]) -> MimicModel: ...
    @staticmethod
    def from_mjcf(path: Path, layout: Layout = "rigid",
                  mimic: bool = False) -> Model | MimicModel:
        """Load an MJCF file (MuJoCo's XML) with MuJoCo's compiled inertias (mass matrix and bias
        equal MuJoCo's to round-off); what rigid does not model is an ``MjcfWarning``. mimic:
        ``True`` returns a :class:`MimicModel` whose ``<equality joint>`` elements with a linear
        polynomial are couplings (``layout`` ``"rigid"`` or ``"pinocchio"``)."""
    @overload
    @staticmethod
    def from_sdf(path: Path, layout: Layout = "rigid",
                 mimic: Literal[False] = False) -> Model: ...
    @overload
    @staticmethod
    def from_sdf(path: Path, layout: Layout = "rigid", *,
                 mimic: Literal[True]) -> MimicModel: ...
    @staticmethod
    def from_sdf(path: Path, layout: Layout = "rigid",
                 mimic: bool = False) -> Model | MimicModel:
        """Load an SDF file (SDFormat 1.4–1.11, one model): links no joint holds float
        (free-flyers), loops are ``ConstraintModel.from_sdf(model)``; what rigid leaves out
        (plugins, gearboxes it cannot hold, a loop a point or a weld cannot close) is an
        ``SdfWarning``. mimic: ``True`` returns a :class:`MimicModel` whose gearboxes are
        couplings."""
    @staticmethod
    def from_file(path: Path, layout: Layout = "rigid", floating: bool = False,
                  inertia: Literal["strict", "warn", "repair"] = "warn") -> Model:
        """``from_mjcf`` for a ``.xml`` file, ``from_sdf`` for ``.sdf``, ``from_urdf``
        otherwise (``floating`` and ``inertia`` apply to URDF only)."""
    @property
    def qpos0(self) -> Vector | None:
        """MuJoCo's qpos0 (its layout: each body where the file puts it) for a model read from
        MJCF; None otherwise."""
    @staticmethod
    def builtin(name: Literal["puma560", "puma560_armature", "pendulum", "double_pendulum"],
                layout: Layout = "rigid") -> Model:
        """A built-in model: the standard-DH PUMA 560 of the Robotics Toolbox (with rotor inertia
        ``Jm G²`` for ``puma560_armature``), a pendulum, a double pendulum."""
    def create_data(self) -> Data:
        """A new workspace for this model (Pinocchio's ``model.createData()``)."""
    def createData(self) -> Data:
        """Alias of ``create_data`` (Pinocchio's name)."""
    @property
    def name(self) -> str: ...
    @property
    def nq(self) -> int:
        """Number of configuration coordinates, in this model's layout."""
    @property
    def nv(self) -> int:
        """Number of degrees of freedom (the length of v, a, τ)."""
    @property
    def njoints(self) -> int:
        """Number of moving joints (Pinocchio's ``njoints - 1``: rigid has no "universe")."""
    @property
    def layout(self) -> Layout: ...
    @property
    def names(self) -> list[str]:
        """The moving joints' names in order (Pinocchio's ``model.names[1:]``)."""
    @property
    def joint_types(self) -> list[str]:
        """Each joint's type: revolute, continuous, prismatic, spherical, free_flyer, planar."""
    @property
    def idx_qs(self) -> list[int]:
        """First index of each joint's coordinates in q (this layout; Pinocchio's
        ``idx_qs[1:]``)."""
    @property
    def nqs(self) -> list[int]: ...
    @property
    def idx_vs(self) -> list[int]:
        """First index of each joint's coordinates in v (Pinocchio's ``idx_vs[1:]``)."""
    @property
    def nvs(self) -> list[int]: ...
    @property
    def frame_names(self) -> list[str]:
        """The named frames: URDF links, fixed joints, operational frames."""
    @property
    def total_mass(self) -> float:
        """Mass of the moving bodies (kg); links welded to the world are left out."""
    @property
    def warnings(self) -> list[str]:
        """The URDF loader's warnings (each also issued as a ``UrdfWarning``)."""
    @property
    def gravity(self) -> Vector:
        """Gravity in the world frame, m/s², default [0, 0, -9.81] (Pinocchio's
        ``model.gravity.linear``). Settable: ``model.gravity = [0, 0, -1.62]``."""
    @gravity.setter
    def gravity(self, g: ArrayLike) -> None: ...

class MimicModel:
    """A robot whose mimic joints follow their sources, ``q_m = multiplier · q_s + offset``, with
    no coordinate of their own (Pinocchio's ``buildModelFromUrdf(path, mimic=True)``; made by
    ``Model.from_urdf(path, mimic=True)``): ``nq``, ``nv`` and every vector and matrix leave them
    out. ``rnea``, ``crba``, ``nle`` are the full model's projected on the reduced coordinates
    (``τ = Gᵀ τ_full``, ``M = Gᵀ M_full G``); ``aba`` solves ``M q̈ = τ − nle`` (docs/mimic.md).

    >>> mm = rigid.Model.from_urdf("panda.urdf", mimic=True)   # doctest: +SKIP
    >>> mm.nq, mm.mimics                                        # doctest: +SKIP
    (8, [('panda_finger_joint2', 'panda_finger_joint1', 1.0, 0.0)])
    """
    @property
    def nq(self) -> int:
        """Configuration coordinates (mimic joints have none)."""
    @property
    def nv(self) -> int:
        """Degrees of freedom (mimic joints have none)."""
    @property
    def mimics(self) -> list[tuple[str, str, float, float]]:
        """``(joint, source, multiplier, offset)`` by name, chains composed."""
    @property
    def names(self) -> list[str]:
        """Every joint's name (mimics included), in the model's order."""
    def neutral(self) -> Vector: ...
    def expand_q(self, q: ArrayLike) -> Vector:
        """The full configuration (rigid's layout of the full model)."""
    def expand_v(self, v: ArrayLike) -> Vector:
        """The full velocity ``G v`` (rigid's layout of the full model)."""
    def rnea(self, q: ArrayLike, v: ArrayLike, a: ArrayLike) -> Vector: ...
    def crba(self, q: ArrayLike) -> Matrix: ...
    def nle(self, q: ArrayLike, v: ArrayLike) -> Vector: ...
    def aba(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike) -> Vector: ...
    def rnea_derivatives(self, q: ArrayLike, v: ArrayLike,
                         a: ArrayLike) -> tuple[Matrix, Matrix, Matrix]:
        """``(∂τ/∂q, ∂τ/∂v, M)``."""
    def aba_derivatives(self, q: ArrayLike, v: ArrayLike,
                        tau: ArrayLike) -> tuple[Matrix, Matrix, Matrix]:
        """``(∂q̈/∂q, ∂q̈/∂v, M⁻¹)``."""
    def frame_jacobian(self, q: ArrayLike, frame: str, reference: object = None) -> Matrix:
        """6 × nv; rows ``(ω, v)``, or ``(v, ω)`` in Pinocchio's layout."""


class Data:
    """The workspace of the algorithms for one model (Pinocchio's ``Data``), allocated once.
    Pickling or copying it gives a fresh workspace of the same model (pickle the pair,
    ``pickle.dumps((model, data))``, to keep them together)."""

    def __init__(self, model: Model) -> None:
        """A workspace for ``model`` (Pinocchio's ``pin.Data(model)``)."""
    def placement(self, name: str) -> tuple[Matrix, Vector]:
        """World pose ``(R, p)`` of a joint's frame (as moved by the joint; Pinocchio's
        ``data.oMi[model.getJointId(name)]``) or of a named frame (a link, a fixed joint;
        Pinocchio's ``data.oMf[model.getFrameId(name)]``), from the last ``forward_kinematics``:
        R (3, 3) a rotation, p (3,) in m, ``x_world = R x_frame + p``. A joint name is looked up
        first, then the frames."""

    # The fields (Pinocchio's names), each a fresh array in the model's layout of what the last
    # algorithm that fills it wrote: poses (n, 4, 4), spatial vectors (n, 6) angular first in
    # rigid's layout and linear first in Pinocchio's.
    oMi: Matrix
    liMi: Matrix
    oMf: Matrix
    v: Matrix
    a: Matrix
    a_gf: Matrix
    f: Matrix
    tau: Vector
    nle: Vector
    g: Vector
    ddq: Vector
    M: Matrix
    Minv: Matrix
    C: Matrix
    dtau_dq: Matrix
    dtau_dv: Matrix
    ddq_dq: Matrix
    ddq_dv: Matrix
    J: Matrix
    Jcom: Matrix
    Ag: Matrix
    hg: Vector
    Ig: tuple[float, Vector, Matrix]
    com: Vector
    vcom: Vector
    acom: Vector
    mass: float
    subtree_com: Matrix
    subtree_vcom: Matrix
    subtree_acom: Matrix
    subtree_mass: Vector
    q_in: Vector
    v_in: Vector

def rnea(model: Model, data: Data, q: ArrayLike, v: ArrayLike, a: ArrayLike,
         fext: ArrayLike | Sequence[Any] | None = None) -> Vector:
    """Inverse dynamics ``τ = M(q) a + C(q, v) v + g(q)`` (N·m or N, length nv) by the recursive
    Newton-Euler algorithm (Featherstone 2008, Table 5.1). ``fext``: one external wrench per
    moving joint on its body, in its joint frame, ``(njoints, 6)`` — moment first ``(m, f)`` in
    rigid's layout, force first ``(f, m)`` in Pinocchio's, where a list of ``pin.Force`` (with
    the universe's first, ignored) is accepted too: ``τ = ID(q, v, a) - Σ Jᵢᵀ Fᵢ``. Pinocchio:
    ``rnea``."""

def aba(model: Model, data: Data, q: ArrayLike, v: ArrayLike, tau: ArrayLike,
        fext: ArrayLike | Sequence[Any] | None = None) -> Vector:
    """Forward dynamics ``a = M(q)⁻¹ (τ - C(q, v) v - g(q))`` by the articulated-body algorithm
    (Featherstone 2008, Table 7.1); ``fext`` as in ``rnea``. A singular M is a ValueError.
    Pinocchio: ``aba``."""

def jacobian_dynamics(model: Model, data: Data, q: ArrayLike, v: ArrayLike, tau: ArrayLike,
                      J: ArrayLike, gamma: ArrayLike,
                      damping: float = 0.0) -> tuple[Vector, Vector]:
    """Forward dynamics under constraints given by their Jacobian ``J`` (m × nv, columns in the
    model's layout) and drift ``γ``: ``(q̈, λ)`` with ``M q̈ + c + g = τ + Jᵀ λ`` and
    ``J q̈ + γ = −damping λ`` (Featherstone's range-space method); ``q̈`` also in ``data.ddq``.
    Redundant rows with ``damping = 0`` are a ValueError. Pinocchio: ``forwardDynamics`` with
    ``J`` and ``gamma``."""

def jacobian_dynamics_from_terms(model: Model, data: Data, tau: ArrayLike, J: ArrayLike,
                                 gamma: ArrayLike, damping: float = 0.0) -> tuple[Vector, Vector]:
    """``jacobian_dynamics`` on the ``M`` and ``nle`` of the last ``crba`` and ``nle`` on
    ``data``. Pinocchio: ``forwardDynamics(model, data, tau, J, gamma, damping)`` after
    ``computeAllTerms``."""

def crba(model: Model, data: Data, q: ArrayLike) -> Matrix:
    """The joint-space mass matrix ``M(q)`` (nv, nv), full and symmetric, armature on the
    diagonal, by the composite rigid-body algorithm (Featherstone 2008, Table 6.2). Pinocchio:
    ``crba`` (which fills the upper triangle only)."""

def nle(model: Model, data: Data, q: ArrayLike, v: ArrayLike) -> Vector:
    """Nonlinear effects ``b = C(q, v) v + g(q) = rnea(q, v, 0)``. Pinocchio:
    ``nonLinearEffects``."""

def gravity(model: Model, data: Data, q: ArrayLike) -> Vector:
    """Generalised gravity ``g(q) = rnea(q, 0, 0)``. Pinocchio: ``computeGeneralizedGravity``."""

def minverse(model: Model, data: Data, q: ArrayLike) -> Matrix:
    """``M(q)⁻¹`` (nv, nv), full and symmetric, by the articulated-body method (Carpentier &
    Mansard 2018). Pinocchio: ``computeMinverse`` (upper triangle only)."""

def coriolis_matrix(model: Model, data: Data, q: ArrayLike, v: ArrayLike) -> Matrix:
    """The Coriolis matrix ``C(q, v)`` (nv, nv) with ``C v`` the Coriolis and centrifugal
    torques and ``Ṁ - 2C`` skew-symmetric (Christoffel symbols; Lynch & Park §8.1.2).
    Pinocchio: ``computeCoriolisMatrix``."""

def forward_kinematics(model: Model, data: Data, q: ArrayLike, v: ArrayLike | None = None,
                       a: ArrayLike | None = None) -> None:
    """World pose of every joint frame ``oMi = oM_parent X_T X_J(q)`` (then
    ``data.placement(name)``), with v (and a) the body twists (and accelerations) too.
    Pinocchio: ``forwardKinematics``."""

def jacobian(model: Model, data: Data, q: ArrayLike, name: str,
             frame: Frame = "world_aligned") -> Matrix:
    """The Jacobian (6, nv) of a joint's frame or a named frame, ``V = J v``:
    ``"world_aligned"`` (ω and the velocity of the frame's origin, world axes; Pinocchio's
    LOCAL_WORLD_ALIGNED), ``"body"`` (the body twist; LOCAL) or ``"spatial"`` (the spatial
    twist, world frame; WORLD). ``pin.ReferenceFrame`` values are accepted too. Rows (ω, v) in
    rigid's layout, (v, ω) in Pinocchio's. Pinocchio: ``computeFrameJacobian`` /
    ``getJointJacobian``."""

def com(model: Model, data: Data, q: ArrayLike) -> Vector:
    """Centre of mass of the moving bodies in the world, ``Σ mᵢ cᵢ / Σ mᵢ`` (m, shape (3,)).
    Pinocchio: ``centerOfMass``."""

def kinetic_energy(model: Model, data: Data, q: ArrayLike, v: ArrayLike) -> float:
    """``K = ½ vᵀ M(q) v`` (J). Pinocchio: ``computeKineticEnergy``."""

def potential_energy(model: Model, data: Data, q: ArrayLike) -> float:
    """``U = -Σ mᵢ gᵀ cᵢ`` (J, zero at the world origin). Pinocchio:
    ``computePotentialEnergy``."""

def neutral(model: Model) -> Vector:
    """The neutral configuration: zeros, identity quaternions (and (1, 0) cos/sin pairs in
    Pinocchio's layout). Pinocchio: ``neutral``."""

def random_configuration(model: Model, lower: ArrayLike | None = None,
                         upper: ArrayLike | None = None) -> Vector:
    """A random configuration within the position limits, or within ``lower``, ``upper`` (nq
    each, this layout; a continuous joint's (cos, sin) bounds are not used, ±1e300 and beyond is
    no bound): angles in [-π, π] and translations in [-1, 1] m where a bound is infinite;
    quaternions uniform on SO(3). Pinocchio: ``randomConfiguration`` (a different generator: the
    numbers differ)."""

def seed(seed: int) -> None:
    """Seed the generator of ``random_configuration``. Pinocchio: ``pin.seed``."""

def integrate(model: Model, q: ArrayLike, v: ArrayLike) -> Vector:
    """``q ⊕ v``: the configuration reached from q moving with the constant velocity v for 1 s,
    joint by joint on each joint's Lie group (SE(3) exponential for a free-flyer). Pinocchio:
    ``integrate`` (in Pinocchio's layout also its quaternion signs)."""

def difference(model: Model, q0: ArrayLike, q1: ArrayLike) -> Vector:
    """``q1 ⊖ q0``: the velocity v with ``integrate(q0, v) = q1``. Rigid's layout does not wrap
    angles (θ1 - θ0); Pinocchio's takes the shortest way round. Pinocchio: ``difference``."""

def rnea_derivatives(model: Model, data: Data, q: ArrayLike, v: ArrayLike,
                     a: ArrayLike) -> tuple[Matrix, Matrix, Matrix]:
    """The partial derivatives of inverse dynamics ``τ = M(q) a + c(q, v) + g(q)``:
    ``(∂τ/∂q, ∂τ/∂v, ∂τ/∂a = M)``, each (nv, nv), in one recursive pass (Carpentier & Mansard,
    RSS 2018). ``∂/∂q`` is taken along ``q ⊕ δ = integrate(q, δ)`` (a free-flyer's ``δ`` is the
    body twist: angular first in rigid's layout, linear first in Pinocchio's; a continuous
    joint's is its angle). Pinocchio: ``computeRNEADerivatives``."""

def aba_derivatives(model: Model, data: Data, q: ArrayLike, v: ArrayLike,
                    tau: ArrayLike) -> tuple[Matrix, Matrix, Matrix]:
    """The partial derivatives of forward dynamics ``q̈ = M(q)⁻¹ (τ - c(q, v) - g(q))``:
    ``(∂q̈/∂q, ∂q̈/∂v, ∂q̈/∂τ = M⁻¹)``, each (nv, nv): ``-M⁻¹ ∂τ/∂(q, v)`` at ``a = q̈``. Pinocchio:
    ``computeABADerivatives``."""

def gravity_derivatives(model: Model, data: Data, q: ArrayLike) -> Matrix:
    """``∂g/∂q`` (nv, nv) of the generalised gravity, along ``q ⊕ δ``. Pinocchio:
    ``computeGeneralizedGravityDerivatives``."""

def compute_joint_jacobians(model: Model, data: Data, q: ArrayLike | None = None) -> Matrix:
    """The spatial (world-frame) Jacobian of every joint (6, nv): column k ``[Ad_{oMi}] S_k``;
    rows (ω, v) in rigid's layout, (v, ω) in Pinocchio's; without ``q``, at the last ``q`` used
    with ``data``. Pinocchio: ``computeJointJacobians`` (``data.J``)."""

def update_frame_placements(model: Model, data: Data) -> None:
    """World poses of the named frames ``oMf = oMi iMf`` from the last forward kinematics.
    Pinocchio: ``updateFramePlacements``."""

def frames_forward_kinematics(model: Model, data: Data, q: ArrayLike) -> None:
    """``forward_kinematics`` then ``update_frame_placements``. Pinocchio:
    ``framesForwardKinematics``."""

def com_jacobian(model: Model, data: Data, q: ArrayLike) -> Matrix:
    """The Jacobian of the centre of mass (3, nv), ``ċ = J_c v``, world frame:
    ``J_c[:, k] = (m_s v_k + ω_k × h_s) / m`` over the subtree each dof moves. Pinocchio:
    ``jacobianCenterOfMass``."""

def centroidal_momentum_matrix(model: Model, data: Data, q: ArrayLike, v: ArrayLike) -> Matrix:
    """The centroidal momentum matrix ``A_G`` (6, nv), ``h_G = A_G v`` about the centre of mass in
    world axes (Orin, Goswami & Lee 2013): rows (L_G, p) in rigid's layout, (p, L_G) in
    Pinocchio's. Pinocchio: ``ccrba``."""

def centroidal_momentum(model: Model, data: Data, q: ArrayLike, v: ArrayLike) -> Vector:
    """The centroidal momentum ``h_G`` (6,): (L_G, p) in rigid's layout, (p, L_G) in Pinocchio's
    (kg·m²/s, kg·m/s). Pinocchio: ``computeCentroidalMomentum``."""

def kinematics_derivatives(model: Model, data: Data, q: ArrayLike, v: ArrayLike, a: ArrayLike,
                           name: str, frame: Frame = "body"
                           ) -> tuple[Matrix, Matrix, Matrix, Matrix, Matrix]:
    """``(∂V/∂q, ∂V/∂v, ∂A/∂q, ∂A/∂v, ∂A/∂a)`` (each (6, nv)) of the twist V and acceleration A
    of a joint's or named frame in ``frame`` (as ``jacobian``; ``"world_aligned"`` is
    ``(ω, ṗ)`` and ``(ω̇, p̈)``), ``∂/∂q`` along ``q ⊕ δ`` (Carpentier & Mansard 2018). Pinocchio:
    ``getJointAccelerationDerivatives`` after ``computeForwardKinematicsDerivatives`` (whose
    LOCAL_WORLD_ALIGNED holds the frame's origin fixed: ``rigid.pinocchio`` gives that one)."""

def interpolate(model: Model, q0: ArrayLike, q1: ArrayLike, u: float) -> Vector:
    """``q0 ⊕ u (q1 ⊖ q0)``, a fraction ``u`` of the way along the joints' geodesics.
    Pinocchio: ``interpolate``."""

def normalize(model: Model, q: ArrayLike) -> Vector:
    """``q`` with every quaternion (and (cos, sin) pair) scaled to unit norm. Pinocchio:
    ``normalize``."""

def inverse_kinematics(model: Model, frame: str, target_pose: Any, q0: ArrayLike | None = None,
                       *, twist: Literal["body", "space"] = "body", tolerance: float = 1e-9,
                       max_iterations: int = 100, damping: float = 1e-3, restarts: int = 20,
                       seed: int = 0, respect_limits: bool = True,
                       data: Data | None = None) -> dict[str, Any]:
    """Joint positions that put the joint or frame ``frame`` at ``target_pose``: a position (3,)
    (the frame's origin; orientation free), a 4 x 4 homogeneous matrix, ``(R, p)`` or a
    ``pin.SE3``. Levenberg-Marquardt on the SE(3) log error of the body twist (``twist="space"``:
    the space twist; ``damping=0``: Modern Robotics' undamped IKinBody/IKinSpace step), from
    ``q0`` (default neutral) then up to ``restarts`` random configurations (``seed``), position
    limits respected, until the angular and linear errors are within ``tolerance`` (rad, m).
    Returns ``{"q", "converged", "angular_error", "linear_error", "position_error",
    "iterations", "total_iterations", "attempts"}`` (``q`` in this layout; the best attempt when
    not converged). The library's ``rigid::kinematics::inverse``; not in Pinocchio."""

computeJointJacobians = compute_joint_jacobians
updateFramePlacements = update_frame_placements
framesForwardKinematics = frames_forward_kinematics
ccrba = centroidal_momentum_matrix

computeRNEADerivatives = rnea_derivatives
computeABADerivatives = aba_derivatives
computeGeneralizedGravityDerivatives = gravity_derivatives

def simulate(model: Model, q0: ArrayLike | None = None, v0: ArrayLike | None = None,
             duration: float = 1.0, dt: float | None = None, integrator: str = "rk4",
             controller: str = "none", target: ArrayLike | None = None,
             move_time: float | None = None, profile: str = "quintic", limits: str = "spring",
             joint_dynamics: bool = True,
             control: Callable[[float, Vector, Vector], ArrayLike] | None = None,
             every: int = 1, ground: float | None = None, friction: float | None = None,
             restitution: float | None = None, self_collision: bool = False,
             constraints: list[ConstraintModel] | None = None, srdf: Path | None = None,
             contact_solver: str = "pgs",
             polish: bool = True) -> dict[str, npt.NDArray[np.float64]]:
    """Simulate the robot from ``(q0, v0)`` (default: its home, at rest) for ``duration`` s with
    a fixed step ``dt`` (default: an MJCF file's ``timestep``, else 1 ms), as ``rigid simulate``
    (the library's ``Scenario``): forward dynamics by ABA, ``integrator`` ``"semi-implicit"``
    (symplectic Euler), ``"rk4"`` (Runge-Kutta-Munthe-Kaas on the joint groups, quaternions never
    renormalised) or ``"variational"`` (a 4th-order Lie-group variational integrator); joint
    damping and friction from the URDF (``joint_dynamics``), limits as a stiff spring-damper
    (``limits="spring"``), ``"ignored"`` or ``"unilateral"``. ``controller``: ``"none"``,
    ``"gravity"`` (compensation), ``"pd"`` (to ``target`` with gravity compensation) or
    ``"track"`` (computed torque along a ``profile`` ``"quintic"``/``"trapezoidal"`` motion from
    ``q0`` to ``target`` in ``move_time``); or ``control(t, q, v) -> τ``, a Python function (its
    exceptions propagate).

    The world: an MJCF file's own floor (its ``plane``), its geom pairs (``contype``/
    ``conaffinity``, not parent and child, ``<contact><exclude>``/``<pair>``, the larger friction
    of the two) and its ``<equality>`` loops, without being asked; ``ground`` (a height, m)
    adds the plane ``z = ground`` under a robot without a floor (URDF ``<collision>``, MJCF
    geoms), with Coulomb ``friction`` (default: the file's, else 0.8) and ``restitution``
    (default 0); ``self_collision`` makes a URDF's bodies collide with each other (less the
    pairs of links an ``srdf`` file's ``<disable_collisions>`` name);
    ``constraints`` (``ConstraintModel`` of this model) replaces the file's loops. Anything that
    can touch is stepped by ``"semi-implicit"`` time stepping (``"rk4"`` is replaced), a
    floating robot without ``q0`` starts set down at ``target`` (or its home), and
    ``controller="pd"`` holds that stance on its feet. Loops are held exactly by the same step.
    ``contact_solver``: ``"pgs"`` (projected Gauss-Seidel) or ``"admm"`` (the alternating
    direction method of multipliers, island by island), the same problem to the same tolerance.
    ``polish``: with ``"pgs"``, end a solve early by Newton's method on the active set the
    impulses show when it stands (the sweep's own solution, to round-off; docs/contact.md).

    Returns ``t`` (N,), ``q`` (N, nq), ``v`` (N, nv), ``tau`` (N, nv; the control torques) and
    ``energy`` (N,; J), one row every ``every`` steps and the last, in the model's layout; when
    anything can touch also ``contacts`` (N,; active contacts), ``normal_force`` (N,; their
    normal force sum, N) and the step's contact solve: ``iterations``, ``converged`` (1 or 0)
    and its ContactBench residuals ``signorini`` (J), ``coulomb`` (N·s), ``dissipation`` (J),
    ``velocity_error`` (m/s); with constraints ``violation_position`` and ``violation_velocity``
    (N,; the largest constraint error, m or rad, and its rate): the columns of ``rigid simulate
    --csv``."""

class Simulator:
    """The time-stepping simulation with contacts (``simulate``'s ``"semi-implicit"`` scheme:
    Signorini-Coulomb impulses, the position correction) one step at a time from any state with
    an open-loop torque, and the derivatives of that step. The world as ``simulate``'s: an MJCF
    file's own floor, geom pairs and ``<equality>`` loops; ``ground`` (a height, m) adds the
    plane ``z = ground`` under a URDF's ``<collision>`` geometry, with ``friction`` (default: the
    file's, else 0.8) and ``restitution`` (default 0); ``dt`` defaults to an MJCF file's
    ``timestep``, else 1 ms; ``contact_solver`` ``"pgs"`` or ``"admm"`` and ``polish`` as ``simulate``'s. A model
    with nothing that can touch raises ``ValueError``. The contacts' memory (warm starts, an impact of the last step) is the last ``step``'s: call it in
    sequence along a trajectory (a ``step`` from a state other than the last one's result
    starts its contacts cold)."""

    def __init__(self, model: Model, dt: float | None = None, ground: float | None = None,
                 friction: float | None = None, restitution: float | None = None,
                 self_collision: bool = False, contact_solver: str = "pgs",
                 polish: bool = True) -> None: ...
    @property
    def dt(self) -> float:
        """The step (s)."""
    def step(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike) -> tuple[Vector, Vector]:
        """``(q⁺, v⁺)`` after one step from ``(q, v)`` with the joint torques ``tau`` (length nv;
        with the model's joint damping and friction), in the model's layout."""
    def step_derivatives(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike
                         ) -> dict[str, Any]:
        """The derivatives of ``step(q, v, tau)``, analytical (the implicit function theorem on
        the step's contact problem at its solution, each contact separated, sticking or
        sliding): ``dq_dq``, ``dq_dv``, ``dq_dtau``, ``dv_dq``, ``dv_dv``, ``dv_dtau`` (each
        nv × nv, the model's layout; ``q`` perturbed by ``integrate``, ``q⁺`` compared by
        ``difference``), ``q_next``, ``v_next`` (the step's result), ``modes`` (one per contact,
        then per joint limit: ``"separated"``, ``"sticking"``, ``"sliding"``), ``at_switch``
        (indices into ``modes`` of those at a mode switch: touching without pushing, pushing at a
        zero gap, sticking on the cone's edge; there each column is the one-sided derivative
        along ``+δ``), ``held_normal`` (indices of the pushing contacts whose normal's turn is
        left out: two faces' clipped edges crossing, a cylinder against anything but a face, a
        non-convex mesh's triangle; elsewhere the normal turns with the bodies), ``contact_points``
        (the step's contact points, in the order of ``modes``, world frame) and ``scaled`` (the
        energy safeguard scaled the impulse: the derivatives are those of the unscaled one). The
        state is not advanced; an MJCF file's ``<equality>`` loops are differentiated with the
        contacts. Not covered: the ``mujoco`` layout with a free joint (raises); see
        docs/contact.md. Not in Pinocchio's Python; MuJoCo has finite differences
        (``mjd_transitionFD``)."""

def replay_html(model: Model, traj: Any, path: Path, title: str | None = None) -> None:
    """Write the 3D replay of ``traj`` (a dict or object with ``t`` (N,) and ``q`` (N, nq), such
    as the result of ``simulate``) to one self-contained HTML file (WebGL; the URDF's visual
    geometry, or a stick figure), 60 frames per second; it opens offline, nothing is fetched."""

def urdf_link_geometries(path: Path, kind: str = "collision") -> list[dict[str, Any]]:
    """The ``<collision>`` (``kind="collision"``) or ``<visual>`` elements of every link of a
    URDF file, links in file order: one dict each with ``link``, ``index`` (within the link),
    ``origin`` (4 x 4, link frame), ``shape`` (``"box"``, ``"cylinder"``, ``"sphere"``,
    ``"capsule"``, ``"mesh"``), ``size``, ``filename`` and ``mesh_path`` (meshes), ``scale``,
    ``rgba``."""

class Collider:
    """A collision shape made ready for ``proximity``: ``kind`` ``"sphere"`` (``size =
    [radius]``), ``"box"`` (edges), ``"cylinder"`` / ``"capsule"`` (``[radius, length]``, along
    z), ``"cone"`` (``[radius, height]``, origin at the centroid), ``"ellipsoid"`` (semi-axes), or
    ``"mesh"`` (``path``, ``scale``: its convex hull)."""

    def __init__(self, kind: str, size: ArrayLike | None = None, path: Path | None = None,
                 scale: ArrayLike | None = None) -> None: ...

def proximity(a: Collider, pose_a: ArrayLike, b: Collider,
              pose_b: ArrayLike) -> tuple[float, Vector, Vector, Vector]:
    """``(distance, point_a, point_b, normal)`` of ``a`` at the world pose ``pose_a`` (4 x 4) and
    ``b`` at ``pose_b``: the signed distance (negative: the penetration's depth), the nearest
    points, the unit normal out of ``a``."""

def read_srdf(path: Path) -> dict[str, Any]:
    """An SRDF file: ``{"disabled": [(link1, link2), ...], "group_states": [{"name", "group",
    "joints": [(joint, values), ...]}, ...]}``."""

def rnea_batch(model: Model, Q: ArrayLike, V: ArrayLike, A: ArrayLike, *,
               threads: int | None = None, out: Matrix | None = None) -> Matrix:
    """``rnea`` for every row: Q (N, nq), V and A (N, nv) → τ (N, nv), on ``threads`` threads
    (None: every core; a pool per size, made once) with the GIL released, several states side
    by side in SIMD lanes; each row equals the single call bit for bit, the same bits for any
    ``threads``. Contiguous float64 inputs are read in place (do
    not write to them from another thread during the call); read-only arrays are accepted; a
    dask array is refused (use ``rigid.dask``). ``out``: a writeable C-contiguous float64
    (N, nv) array that overlaps no input, to write τ into (and return), so that repeated calls
    allocate nothing (on an error its contents are unspecified). Not in Pinocchio's Python."""

def aba_batch(model: Model, Q: ArrayLike, V: ArrayLike, TAU: ArrayLike, *,
              threads: int | None = None, out: Matrix | None = None) -> Matrix:
    """``aba`` for every row: (N, nv) accelerations, on ``threads`` threads, GIL released;
    ``out`` as ``rnea_batch``."""

def crba_batch(model: Model, Q: ArrayLike, *, threads: int | None = None
               ) -> npt.NDArray[np.float64]:
    """``crba`` for every row: (N, nv, nv) mass matrices, on ``threads`` threads, GIL released."""

def rnea_derivatives_batch(model: Model, Q: ArrayLike, V: ArrayLike, A: ArrayLike, *,
                           threads: int | None = None
                           ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """``rnea_derivatives`` for every row: ``(dtau_dq, dtau_dv)``, two (N, nv, nv) arrays, on
    ``threads`` threads with the GIL released, several states side by side in SIMD lanes; each
    block equals the single call's (bit for bit on revolute, prismatic and free-flyer joints). The third derivative, ``dtau_da = M``, is
    ``crba_batch(model, Q)``."""

def set_output_cache(max_bytes: int) -> int:
    """The most bytes of output arrays the batch verbs (``rnea_batch``, ``aba_batch``,
    ``crba_batch``, ``rnea_derivatives_batch``, ``regressor_batch``) keep for their next fresh
    outputs; returns the previous limit (default 0: keep none; setting 0 lets the kept ones
    go). A fresh output is made from a kept array of the same size that no Python object
    refers to any more (a result, or any view of it, keeps its array in use), so a loop that
    drops each result before the next call touches no new memory, as with ``out=``: on a
    virtual machine that gives freed memory back to its host, the first touch of a new array
    can cost more than the batch (BENCHMARKS.md). A kept result is a view of the cache's array
    (its ``base``); an empty result, one over the limit, or any with the cache off owns its
    memory. Off by default because a raw pointer to a result's data (``__array_interface__``,
    ctypes, a C extension) holds no reference: with the cache on, the next call may overwrite
    what it points to. Not in Pinocchio's Python."""

def regressor_batch(model: Model, Q: ArrayLike, V: ArrayLike, A: ArrayLike, *,
                    threads: int | None = None) -> npt.NDArray[np.float64]:
    """``regressor`` for every row: (N, nv, 10·nb), so that ``Y @ π`` is τ for a parameter
    vector ``π`` (``dynamic_parameters``' order; rigid's ``rnea`` adds ``armature ∘ a``) and
    ``Y @ P.T`` (N, nv, K) for K of them. Each block equals ``regressor`` bit for bit."""

def simulate_batch(models: Model | Sequence[Model], q0: ArrayLike | None = None,
                   v0: ArrayLike | None = None, duration: float = 1.0, dt: float = 1e-3,
                   integrator: str = "rk4", controller: str = "none",
                   target: ArrayLike | None = None, move_time: float | None = None,
                   profile: str = "quintic", limits: str = "spring",
                   joint_dynamics: bool = True, every: int = 1, *,
                   threads: int | None = None) -> dict[str, npt.NDArray[np.float64]]:
    """Many rollouts in parallel with the GIL released: one per model of a list (one kinematic
    structure, any parameters: MuJoCo's ``rollout``), or one model from each row of ``q0``
    (M, nq). ``q0``, ``v0``, ``target``: one vector for all or one row per rollout. Built-in
    controllers only. Returns ``t`` (T), ``q`` (M, T, nq), ``v``, ``tau`` (M, T, nv),
    ``energy`` (M, T); rollout i equals ``simulate`` of its model bit for bit."""

Spec = Union[Path, dict[str, Any], Sequence[dict[str, Any]]]

def mass_properties(spec: Spec) -> dict[str, Any]:
    """Mass properties of a body made of parts: a ``rigid mass`` TOML spec file, the same
    structure as a dict ``{"part": [{...}, ...]}``, a list of parts or one part (see the shape
    helpers). Returns the keys of ``rigid mass --json``: ``mass`` (kg), ``com`` (3,) (m),
    ``inertia_com`` and ``inertia_origin`` (3, 3) (kg·m², spec-frame axes, about the CoM and the
    origin), ``principal_moments`` (ascending) and ``principal_axes`` (columns),
    ``spatial_inertia_origin`` (6, 6) (angular first), ``valid`` and ``validity_error``."""

def box(size: ArrayLike, **options: Any) -> dict[str, Any]:
    """A part: a box of edge lengths [lx, ly, lz] (m) centred on its frame. Options: ``mass``
    (kg) or ``density`` (kg/m³), ``position`` [x, y, z] (m), ``rpy`` [r, p, y] (rad, URDF's
    fixed axes) or ``quaternion`` [x, y, z, w], ``name``. Checked when made."""
def cylinder(radius: float, length: float, **options: Any) -> dict[str, Any]:
    """A part: a solid cylinder, axis along z, centred (``I_zz = ½ m r²``)."""
def sphere(radius: float, **options: Any) -> dict[str, Any]:
    """A part: a solid ball (``I = ⅖ m r²``)."""
def ellipsoid(semi_axes: ArrayLike, **options: Any) -> dict[str, Any]:
    """A part: a solid ellipsoid of semi-axes [a, b, c]."""
def capsule(radius: float, length: float, **options: Any) -> dict[str, Any]:
    """A part: a cylinder of radius and length along z capped by two hemispheres."""
def cone(radius: float, height: float, **options: Any) -> dict[str, Any]:
    """A part: a solid cone, axis z, origin at its centroid (base at z = -h/4)."""
def rod(length: float, **options: Any) -> dict[str, Any]:
    """A part: a thin rod along z (give a mass)."""
def point(**options: Any) -> dict[str, Any]:
    """A part: a point mass (give a mass)."""
def mesh(file: Path, **options: Any) -> dict[str, Any]:
    """A part: a closed triangle mesh (STL or OBJ) of uniform density, in its own coordinates."""

def spatial_inertia(mass: float, com: ArrayLike | None = None,
                    inertia: ArrayLike | None = None) -> Matrix:
    """The spatial inertia ``G`` (6, 6) about the frame's origin, angular first:
    ``[[I_c + m[c]ᵀ[c], m[c]], [m[c]ᵀ, m 1]]`` for a mass (kg), a CoM c (m) and an inertia I_c
    (3, 3) about the CoM (kg·m²). Pinocchio: ``pin.Inertia(mass, c, I_c).matrix()`` with the
    blocks swapped (Pinocchio is linear first)."""

def simulate_body(spec: Spec, omega: ArrayLike | None = None, velocity: ArrayLike | None = None,
                  gravity: ArrayLike | None = None, pivot: ArrayLike | None = None,
                  duration: float = 10.0, dt: float = 1e-3,
                  integrator: Literal["rk4", "variational", "semi-implicit", "lgvi"] = "rk4",
                  ground: float | None = None, friction: float | None = None,
                  restitution: float | None = None, q0: ArrayLike | None = None,
                  ) -> dict[str, Vector]:
    """One rigid body (a spec, as for ``mass_properties``), free or on a spherical pivot (a point
    of the spec frame fixed at the world origin), integrated on SE(3) (``rigid simulate``):
    initial body angular velocity ``omega`` (rad/s) and CoM velocity ``velocity`` (m/s), spec-frame
    axes; world ``gravity`` (m/s², none by default). ``integrator``: those of ``simulate`` (the
    body is the one-joint case of a robot; ``"rk4"`` by default, as there), or ``"lgvi"``, the
    2nd-order Lie-group variational integrator of one body (momentum and energy of a torque-free
    body to round-off), which ``"variational"`` named here before. Returns arrays of N + 1 rows: ``t`` (s),
    ``position`` (N+1, 3) and ``quaternion`` (N+1, 4, x-y-z-w) of the frame at the CoM with the
    spec frame's axes, its body twist ``omega`` and ``velocity`` (N+1, 3), and the total
    ``energy`` (J).

    ``ground`` (a height, m; ``spec`` then a path to a TOML spec file) puts the body on the
    ground plane ``z = ground``, as ``rigid simulate SPEC.toml --ground``: it collides through
    its parts' shapes (meshes as convex hulls; points and given inertias do not) with Coulomb
    ``friction`` (default 0.8) and ``restitution`` (default 0), gravity defaults to
    ``(0, 0, -9.81)``, the integrator is the time-stepping ``"semi-implicit"`` (``"rk4"``
    replaced, others refused), ``pivot`` is refused, and ``q0`` is the pose
    ``(x, y, z, qx, qy, qz, qw)`` of the CoM frame (default: set down on the ground, spec axes
    upright). The dict gains ``contacts`` (N+1, active contacts) and ``normal_force`` (N+1, their
    normal force sum, N)."""

def regressor(model: Model, data: Data, q: ArrayLike, v: ArrayLike, a: ArrayLike) -> Matrix:
    """The joint-torque regressor ``Y(q, v, a)``, (nv, 10·nb), with ``rnea(q, v, a) = Y π``
    (gravity included; ``π = dynamic_parameters(model)``): linear in the ten inertial parameters
    ``(m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz)`` of every body about its joint frame
    (Atkeson, An & Hollerbach 1986). Rows in the model's velocity layout, bodies in joint order.
    Pinocchio: ``computeJointTorqueRegressor`` (the same column order)."""

def dynamic_parameters(model: Model) -> Vector:
    """The model's inertial parameters ``π`` (10·nb), ten per body as in ``regressor``
    (Pinocchio: ``model.inertias[i].toDynamicParameters()`` stacked)."""

def excite(model: Model, duration: float = 10.0, rate: float = 100.0, harmonics: int = 5,
           iterations: int = 300, friction: bool = False, seed: int = 1,
           out: Path | None = None) -> dict[str, Any]:
    """An exciting trajectory for identification (``rigid excite``): a finite Fourier series per
    joint, ``q(t) = q₀ + Σ_l a_l/(lω) sin(lωt) − b_l/(lω) cos(lωt)`` (Swevers et al. 1997),
    within the joint limits, optimised for the condition number of the base regressor. Returns
    ``t`` (N,), ``q`` (N, nq), ``v``, ``a`` and ``tau`` (N, nv: the torques the model predicts;
    replace them with measurements) and ``condition_number``; ``out`` also writes the CSV that
    ``identify`` reads. 1-dof joints only."""

def identify(model: Model, samples: Path | dict[str, ArrayLike], physical: bool = False,
             friction: bool = False, rotor_inertia: bool = False, weighted: bool = False,
             regularization: float = 1e-4, mass_tolerance: float | None = None,
             window: float = 0.05) -> dict[str, Any]:
    """The inertial parameters of ``model`` from measured motion (``rigid identify``).
    ``samples``: a CSV file (``t, q…, v…, a…, tau…``, or ``t, q…, v…, tau…`` / ``t, q…, tau…``
    with the missing derivatives by a Savitzky–Golay differentiator of ``window`` seconds;
    columns in rigid's joint layout, as ``excite`` writes them) or a dict of arrays ``t`` (N,),
    ``q`` (N, nq), ``v``, ``a``, ``tau`` (N, nv) in the model's layout. Returns
    ``parameter_names``, ``base_parameters`` (the identifiable combinations, e.g.
    ``"Izz1 + Iyy2 + …"``), and for ``model_values``, ``least_squares`` and (with ``physical``)
    ``physical``: ``base``, ``base_std``, ``parameters`` (the full vector: base parameters
    estimated, the rest from the model), residuals, ``condition_number`` and ``consistent`` per
    body. ``physical`` solves the semidefinite program of Wensing, Kim & Slotine (2017), every
    body's pseudo-inertia positive definite, regularised towards the model's values; it needs
    the module built with the feature ``sdp`` (OpenBLAS), else ``ValueError`` says how. Bad
    samples (NaN, wrong columns, too few, a motion that does not excite every base parameter):
    ``ValueError`` naming the row, column or parameter."""

def doctor(path: Path, fix: Path | None = None) -> dict[str, Any]:
    """The inertia doctor of a URDF, MJCF (``.xml``) or SDF (``.sdf``) file: the structure of
    ``rigid doctor --json``
    (``{"robot", "bodies": [{"name", "line", "status", "findings", "likely_cause",
    "explanation", "repair", ...}]}``). With ``fix``, writes a copy of the file in which the
    ``<inertial>`` blocks that needed a repair are replaced, in the file's own format; what it
    cannot repair (a body in an included file, MJCF's ``inertiafromgeom``) is a ``UserWarning``."""

# Pinocchio's names of the verbs with the same signature.
computeJointTorqueRegressor = regressor
nonLinearEffects = nle
computeGeneralizedGravity = gravity
computeMinverse = minverse
computeCoriolisMatrix = coriolis_matrix
forwardKinematics = forward_kinematics
centerOfMass = com
computeKineticEnergy = kinetic_energy
computePotentialEnergy = potential_energy
randomConfiguration = random_configuration

# --- constrained dynamics (closed loops, rigid contacts) ---

# kind: "point" (3 rows: two points coincide; Pinocchio's CONTACT_3D) or "frame" (6 rows: two
# frames coincide; CONTACT_6D), or a pin.ContactType value. reference_frame: "local" (c1's axes,
# Pinocchio's LOCAL) or "local_world_aligned" (the world's axes at c1's origin), or a
# pin.ReferenceFrame value. A placement: (R, p), a 4 x 4 homogeneous matrix, or a pin.SE3.

class ConstraintModel:
    """A bilateral constraint between the frames ``c1 = oMi[joint1] · placement1`` and
    ``c2 = oMi[joint2] · placement2`` (``"universe"``: the world; placements relative to the
    joint frame, to the world for ``"universe"``): Pinocchio's ``RigidConstraintModel``.
    ``λ`` is the force (point) or wrench (frame) the constraint applies to joint1's body, in c1's
    axes (``"local"``) or the world's (``"local_world_aligned"``); joint2's body gets the
    opposite. Baumgarte gains ``kp`` (1/s²), ``kd`` (1/s): the error obeys
    ``ë = −kp e − kd ė``, with ``e = −c1Mc2.translation`` (point) or ``−log6(c1Mc2)``
    (frame)."""

    def __init__(self, model: Model, kind: Literal["point", "frame"] | Any, joint1: str,
                 placement1: Any | None = None, joint2: str = "universe",
                 placement2: Any | None = None,
                 reference_frame: Literal["local", "local_world_aligned"] | Any = "local", kp: float = 0.0,
                 kd: float = 0.0) -> None: ...
    @staticmethod
    def on_frames(model: Model, kind: Literal["point", "frame"] | Any, frame1: str, frame2: str = "universe",
                  reference_frame: Literal["local", "local_world_aligned"] | Any = "local", kp: float = 0.0,
                  kd: float = 0.0) -> ConstraintModel:
        """Between two named frames (links, fixed joints), c1 and c2 at the frames;
        ``"universe"`` is the world frame."""
    @staticmethod
    def joint_coordinate(model: Model, joint1: str, joint2: str | None = None,
                         polycoef: Sequence[float] = (0.0, 1.0), kp: float = 0.0,
                         kd: float = 0.0) -> ConstraintModel:
        """``q_joint1 = Σ_k polycoef[k] q_joint2^k`` (at most 5 coefficients) for one-dof joints
        (MJCF ``<equality joint>``); ``λ`` the generalised force on joint1."""
    @staticmethod
    def from_sdf(model: Model) -> list[ConstraintModel]:
        """The loops of the SDF file ``model`` was read from: a ball joint a point, a fixed
        joint a weld, a revolute joint two points on its axis."""
    @staticmethod
    def from_mjcf(model: Model) -> list[ConstraintModel]:
        """The ``<equality>`` elements of the MJCF file ``model`` was read from: ``connect`` a
        point, ``weld`` a frame, ``joint`` a joint coordinate (hard, world-aligned); tendon and
        inactive equalities are left out with an ``MjcfWarning`` naming the line."""
    @property
    def dim(self) -> int:
        """3, 6 or 1."""

class ConstraintData:
    """The workspace of a constraint set on a model (Pinocchio's ``initConstraintDynamics`` and
    its constraint datas), made once; no verb allocates afterwards."""

    def __init__(self, model: Model, constraints: Sequence[ConstraintModel]) -> None: ...
    @property
    def dim(self) -> int:
        """The number of constraint rows (3, 6 or 1 per constraint)."""
    @property
    def lambda_c(self) -> Vector:
        """``λ`` of the last ``constraint_dynamics`` or ``contact_inverse_dynamics``, in the
        constraints' order and reference frames: a wrench moment first in rigid's layout, force
        first in Pinocchio's (Pinocchio's ``data.lambda_c``)."""
    @property
    def impulse_c(self) -> Vector:
        """The impulse of the last ``impulse_dynamics`` (N·s; Pinocchio's ``data.impulse_c``)."""
    @property
    def gamma(self) -> Vector:
        """The drift ``γ`` of the last ``constraint_dynamics``: ``J q̈ + γ = 0``, ``γ = J̇ q̇``
        plus the Baumgarte terms ``kp e + kd ė``."""
    @property
    def jacobian(self) -> Matrix:
        """The constraint Jacobian (dim, nv) at the last q, in the model's layout."""
    @property
    def violation(self) -> float:
        """The largest constraint error ``‖e‖∞`` at the last q (m, rad)."""
    @property
    def stats(self) -> dict[str, Any]:
        """The last solve: ``iterations``, ``absolute_residual`` (``‖J q̈ + γ‖∞``),
        ``relative_residual`` (``‖λ_k − λ_{k−1}‖∞``), ``converged``, ``dynamics_residual``
        (inverse dynamics)."""

def constraint_dynamics(model: Model, data: Data, q: ArrayLike, v: ArrayLike, tau: ArrayLike,
                        constraint_data: ConstraintData, mu: float = 0.0, max_iter: int = 100,
                        accuracy: float = 1e-12) -> Vector:
    """Forward dynamics with constraints: ``q̈`` with ``M q̈ + c + g = τ + Jᵀ λ`` and
    ``J q̈ + γ = 0``, by the tree-sparse factorisation of M and the Delassus matrix
    ``J M⁻¹ Jᵀ`` (Carpentier, Budhiraja & Mansard, RSS 2021); ``λ`` in
    ``constraint_data.lambda_c``. ``mu > 0``: proximal iterations
    ``(J M⁻¹ Jᵀ + μ I) λ_{k+1} = … + μ λ_k`` (redundant constraints; ``mu = 0``: one exact
    solve, and redundant constraints are a ValueError). Pinocchio: ``constraintDynamics``."""

def impulse_dynamics(model: Model, data: Data, q: ArrayLike, v: ArrayLike,
                     constraint_data: ConstraintData, r_coeff: float = 0.0, mu: float = 0.0,
                     max_iter: int = 100, accuracy: float = 1e-12) -> Vector:
    """The velocity just after an impact that starts the constraints:
    ``M (q̇⁺ − q̇⁻) = Jᵀ Λ``, ``J q̇⁺ = −r_coeff J q̇⁻`` (Newton's law, every constraint); ``Λ`` in
    ``constraint_data.impulse_c``. Pinocchio: ``impulseDynamics``, whose right-hand side uses
    joint1's velocity only: the same law when joint2 is the world, another one between two
    moving bodies; with mu > 0 it does one regularised solve (``max_iter=1`` here)."""

def contact_inverse_dynamics(model: Model, data: Data, q: ArrayLike, v: ArrayLike, a: ArrayLike,
                             constraint_data: ConstraintData) -> Vector:
    """Inverse dynamics with constraints: the least-norm ``(τ, λ)`` with
    ``M a + c + g = τ + Jᵀ λ`` and τ zero on a free-flyer's six dofs (least squares when no
    such pair exists, ``constraint_data.stats["dynamics_residual"]`` says how far); returns τ,
    ``λ`` in ``constraint_data.lambda_c``. Not Pinocchio 4.1's ``contactInverseDynamics``, which
    takes λ from a compliant point-contact law, ``λ = proj_cone(−(c_ref − μ λ_prev) / (R + μ))``
    with ``c_ref = (J (v + dt a) + correction) / dt`` (no mass matrix), and returns
    ``rnea(q, v, a) − Jᵀ λ``."""

def constraint_dynamics_derivatives(model: Model, data: Data, q: ArrayLike, v: ArrayLike,
                                    tau: ArrayLike, constraint_data: ConstraintData,
                                    mu: float = 0.0, max_iter: int = 100,
                                    accuracy: float = 1e-12) -> dict[str, Matrix]:
    """Runs ``constraint_dynamics`` and returns its derivatives: ``ddq_dq``, ``ddq_dv``,
    ``ddq_dtau`` (nv × nv) and ``dlambda_dq``, ``dlambda_dv``, ``dlambda_dtau`` (dim × nv), by
    differentiating the KKT system at its solution; q along ``q ⊕ δ``. Pinocchio:
    ``computeConstraintDynamicsDerivatives``."""

def impulse_dynamics_derivatives(model: Model, data: Data, q: ArrayLike, v: ArrayLike,
                                 constraint_data: ConstraintData, r_coeff: float = 0.0,
                                 mu: float = 0.0, max_iter: int = 100,
                                 accuracy: float = 1e-12) -> dict[str, Matrix]:
    """Runs ``impulse_dynamics`` and returns ``dvplus_dq``, ``dvplus_dv`` (the full
    ``∂q̇⁺/∂q̇⁻``; Pinocchio's ``ddq_dv`` is this minus the identity), ``dimpulse_dq``,
    ``dimpulse_dv``. Pinocchio: ``computeImpulseDynamicsDerivatives``."""

constraintDynamics = constraint_dynamics
impulseDynamics = impulse_dynamics
contactInverseDynamics = contact_inverse_dynamics
