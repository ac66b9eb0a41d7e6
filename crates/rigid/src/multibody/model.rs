//! The constant description of a kinematic tree: joints in depth-first order, their placements,
//! the bodies' spatial inertias, limits, armature, named frames and gravity.

use super::{JointType, ModelError};
use crate::error::DimensionError;
use crate::mass::SpatialInertia;
use crate::spatial::{Transform, Twist, Vec3};

/// The depth-first index of a moving joint (0-based); it also names the body the joint moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct JointId(pub usize);

/// The index of a named frame in [`Model::frames`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FrameId(pub usize);

/// One moving joint and the body it carries.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The joint's name.
    pub name: String,
    /// Its type.
    pub kind: JointType,
    /// The parent joint (`None`: the world).
    pub parent: Option<JointId>,
    /// Pose of the joint frame in the parent joint's (moved) frame, or in the world, at
    /// `q = neutral`: Featherstone's `X_T`, Pinocchio's `jointPlacements`.
    pub placement: Transform,
    /// First index of the joint's coordinates in `q`.
    pub idx_q: usize,
    /// Number of configuration coordinates.
    pub nq: usize,
    /// First index of the joint's coordinates in `v`, `a`, `τ`.
    pub idx_v: usize,
    /// Number of degrees of freedom.
    pub nv: usize,
    /// One past the last joint of this joint's subtree: the subtree is `self..subtree_end`
    /// (depth-first order makes it contiguous).
    pub subtree_end: usize,
}

/// What a named frame stands for. Frame names are unique within a kind, and joint names among the
/// joints; a URDF link and a joint may share a name (links and joints are two namespaces in URDF,
/// as in Pinocchio, whose frames carry their type too).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FrameKind {
    /// A body's own frame (a URDF link): the link moved by a joint, or a link welded to its parent
    /// by a fixed joint (its inertia merged into the parent's).
    Body,
    /// The frame of a fixed joint (a URDF `fixed` joint, at its child link's frame).
    FixedJoint,
    /// An operational frame (a tool point, a sensor).
    Operational,
}

impl FrameKind {
    /// Lower-case name: `body`, `fixed joint`, `operational`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Body => "body",
            Self::FixedJoint => "fixed joint",
            Self::Operational => "operational",
        }
    }
}

/// Why [`Model::frame_id`] found no single frame.
#[derive(Clone, Debug, thiserror::Error, PartialEq, Eq)]
pub enum FrameLookupError {
    /// No frame has this name.
    #[error("no frame named \"{name}\"")]
    NotFound {
        /// The name looked up.
        name: String,
    },
    /// Several frames of different kinds have this name.
    #[error("frame name \"{name}\" is ambiguous: there is a {} frame of that name; ask for one kind (Model::frame_id_of_kind)", kinds.iter().map(|k| k.as_str()).collect::<Vec<_>>().join(" and a "))]
    Ambiguous {
        /// The name looked up.
        name: String,
        /// The kinds of the frames with that name.
        kinds: Vec<FrameKind>,
    },
}

/// A named frame fixed in a moving body (or in the world).
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The frame's name.
    pub name: String,
    /// The body it is fixed in (`None`: the world).
    pub parent: Option<JointId>,
    /// Its pose in the parent joint's frame (or in the world).
    pub placement: Transform,
    /// What it stands for.
    pub kind: FrameKind,
}

/// A kinematic tree, constant once built (Featherstone's `model`, Pinocchio's `Model`).
/// Build one with [`ModelBuilder`]; evaluate it with a [`Data`](super::Data) workspace.
#[derive(Clone, Debug)]
pub struct Model {
    pub(crate) name: String,
    pub(crate) gravity: Vec3,
    pub(crate) joints: Vec<Joint>,
    pub(crate) inertias: Vec<SpatialInertia>,
    pub(crate) frames: Vec<Frame>,
    pub(crate) lower: Vec<f64>,
    pub(crate) upper: Vec<f64>,
    pub(crate) velocity_limit: Vec<f64>,
    pub(crate) effort_limit: Vec<f64>,
    pub(crate) armature: Vec<f64>,
    /// Viscous joint damping per degree of freedom (URDF `<dynamics damping>`).
    pub(crate) damping: Vec<f64>,
    /// Coulomb (dry) joint friction per degree of freedom (URDF `<dynamics friction>`).
    pub(crate) friction: Vec<f64>,
    /// Motion subspace column per degree of freedom, in the child frame (constant).
    pub(crate) dof_S: Vec<Twist>,
    /// The joint of each degree of freedom.
    pub(crate) dof_joint: Vec<usize>,
    /// `Some((c, s))` when `S_k = s e_c` (a coordinate axis, angular first, `s = ±1`): then
    /// `I S_k` is a column of `I` and `S_kᵀ F` one component of `F`.
    pub(crate) dof_axis: Vec<Option<(usize, f64)>>,
    /// `(joint, index in q)` of every quaternion (spherical and free-flyer joints).
    pub(crate) quaternions: Vec<(usize, usize)>,
    /// Per joint: `X_T` has exactly the identity rotation (a URDF origin without `rpy`), so that
    /// `oM_λ X_T X_J(q)` of a revolute joint turns two columns of `R_λ` and that of a prismatic
    /// joint keeps `R_λ` (no 3x3 product).
    pub(crate) unrotated: Vec<bool>,
    /// Per joint: `X_T`'s rotation is a signed permutation (a URDF `rpy` in multiples of π/2,
    /// up to the rounding of `cos(π/2)`): column `c` of `R_T` is `s e_k` for `(k, s)` in slot
    /// `c`, so that `R_λ R_T` picks and signs columns of `R_λ` instead of a 3x3 product.
    pub(crate) placement_permutation: Vec<Option<[(usize, f64); 3]>>,
    /// The `q` indices of the joints for which [`Model::reads_chain_angle`] holds: the first pass
    /// of CRBA, `M⁻¹` and the RNEA derivatives computes their sines and cosines ahead of the
    /// chain, several at a time (four per AVX2 register, else two).
    pub(crate) chain_angles: Vec<usize>,
    /// Per joint, when `X_T`'s rotation is not a signed permutation: `Some((e_k, sin θ, cos θ))`
    /// if it turns by `θ` about a coordinate axis `e_k` (a URDF `rpy` with one nonzero angle), so
    /// that `R_λ R_T` turns two columns of `R_λ` (`rotate_about`) instead of a 3x3 product.
    pub(crate) placement_turn: Vec<Option<(crate::spatial::Vec3, f64, f64)>>,
    /// Per joint: `X_T`'s translation `t`, kept as `s e_k` when it lies on a coordinate axis
    /// (`R_λ t` is then a scaled column of `R_λ`).
    pub(crate) placement_translation: Vec<crate::spatial::ModelVec3>,
    /// Per body: its inertia in the form that is cheapest to rotate
    /// ([`PrincipalForm`](crate::mass::PrincipalForm)), `None` when it has none (see
    /// [`PrincipalForm::new`](crate::mass::PrincipalForm::new)). Derived from `inertias` by
    /// [`Model::refresh_inertia_forms`].
    pub(crate) principal: Vec<Option<crate::mass::PrincipalForm>>,
    pub(crate) nq: usize,
    pub(crate) nv: usize,
}

impl Model {
    /// Whether the first pass of CRBA, `M⁻¹` and the RNEA derivatives (`root_frame_bodies`)
    /// turns joint `i` by a sine and cosine computed ahead of the chain: a revolute joint that is
    /// a root's child, or deeper with `X_T` unrotated, a signed permutation or a turn about one
    /// coordinate axis. The one definition behind `chain_angles` and the pass's match arms.
    pub(crate) fn reads_chain_angle(&self, i: usize) -> bool {
        let j = &self.joints[i];
        matches!(
            j.kind,
            JointType::Revolute { .. } | JointType::Continuous { .. }
        ) && j.parent.is_some_and(|p| {
            self.joints[p.0].parent.is_none()
                || self.unrotated[i]
                || self.placement_permutation[i].is_some()
                || self.placement_turn[i].is_some()
        })
    }

    /// Recomputes what is derived from the body inertias; called whenever `inertias` changes.
    pub(crate) fn refresh_inertia_forms(&mut self) {
        self.principal = self
            .inertias
            .iter()
            .map(crate::mass::PrincipalForm::new)
            .collect();
    }

    /// The model's name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }
    /// Number of configuration coordinates.
    #[must_use]
    pub fn nq(&self) -> usize {
        self.nq
    }
    /// Number of degrees of freedom.
    #[must_use]
    pub fn nv(&self) -> usize {
        self.nv
    }
    /// Number of moving joints (= moving bodies).
    #[must_use]
    pub fn njoints(&self) -> usize {
        self.joints.len()
    }
    /// The joints in depth-first order.
    #[must_use]
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }
    /// One joint (panics if `id` is out of range).
    #[must_use]
    pub fn joint(&self, id: JointId) -> &Joint {
        &self.joints[id.0]
    }
    /// The joint called `name`.
    #[must_use]
    pub fn joint_id(&self, name: &str) -> Option<JointId> {
        self.joints.iter().position(|j| j.name == name).map(JointId)
    }
    /// The spatial inertia of the body moved by `id`, in its joint frame, including the bodies
    /// welded to it.
    #[must_use]
    pub fn inertia(&self, id: JointId) -> &SpatialInertia {
        &self.inertias[id.0]
    }
    /// All body inertias, indexed like the joints.
    #[must_use]
    pub fn inertias(&self) -> &[SpatialInertia] {
        &self.inertias
    }
    /// Gravity in the world frame (m/s²).
    #[must_use]
    pub fn gravity(&self) -> Vec3 {
        self.gravity
    }
    /// Named frames (welded bodies and operational frames).
    #[must_use]
    pub fn frames(&self) -> &[Frame] {
        &self.frames
    }
    /// The frame called `name`, whatever its kind.
    ///
    /// # Errors
    /// [`FrameLookupError::NotFound`], or [`FrameLookupError::Ambiguous`] when frames of several
    /// kinds have this name (a URDF link and a fixed joint of the same name): then use
    /// [`frame_id_of_kind`](Self::frame_id_of_kind).
    pub fn frame_id(&self, name: &str) -> Result<FrameId, FrameLookupError> {
        let mut hits = self
            .frames
            .iter()
            .enumerate()
            .filter(|(_, f)| f.name == name);
        match (hits.next(), hits.next()) {
            (Some((i, _)), None) => Ok(FrameId(i)),
            (None, _) => Err(FrameLookupError::NotFound { name: name.into() }),
            (Some(_), Some(_)) => Err(FrameLookupError::Ambiguous {
                name: name.into(),
                kinds: self
                    .frames
                    .iter()
                    .filter(|f| f.name == name)
                    .map(|f| f.kind)
                    .collect(),
            }),
        }
    }
    /// The frame of kind `kind` called `name` (names are unique within a kind).
    #[must_use]
    pub fn frame_id_of_kind(&self, name: &str, kind: FrameKind) -> Option<FrameId> {
        self.frames
            .iter()
            .position(|f| f.name == name && f.kind == kind)
            .map(FrameId)
    }
    /// The total mass of the moving bodies (welded-to-world links excluded).
    #[must_use]
    pub fn total_mass(&self) -> f64 {
        self.inertias.iter().map(SpatialInertia::mass).sum()
    }
    /// Lower position limits, per configuration coordinate (`-∞` when none).
    #[must_use]
    pub fn lower_limits(&self) -> &[f64] {
        &self.lower
    }
    /// Upper position limits, per configuration coordinate (`+∞` when none).
    #[must_use]
    pub fn upper_limits(&self) -> &[f64] {
        &self.upper
    }
    /// Velocity limits per degree of freedom (`+∞` when none).
    #[must_use]
    pub fn velocity_limits(&self) -> &[f64] {
        &self.velocity_limit
    }
    /// Effort limits per degree of freedom (`+∞` when none).
    #[must_use]
    pub fn effort_limits(&self) -> &[f64] {
        &self.effort_limit
    }
    /// Joint armature per degree of freedom (kg·m² or kg): added to the diagonal of `M` and to
    /// ABA's joint inertia `D = Sᵀ I^A S + armature` (e.g. a reflected rotor inertia `Jm G²`).
    #[must_use]
    pub fn armature(&self) -> &[f64] {
        &self.armature
    }
    /// Viscous joint damping `b` per degree of freedom (N·m·s/rad or N·s/m; `0` when none): the
    /// simulator ([`simulation`](super::simulation)) applies `τ = -b v`. The algorithms (RNEA,
    /// ABA, ...) ignore it, as Pinocchio does.
    ///
    /// ```
    /// let model = rigid::io::urdf::load_urdf_str(r#"<robot name="r"><link name="a"/>
    ///   <link name="b"><inertial><mass value="1"/>
    ///     <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    ///   <joint name="j" type="continuous"><parent link="a"/><child link="b"/>
    ///     <dynamics damping="0.5" friction="0.1"/></joint></robot>"#, false).unwrap();
    /// assert_eq!((model.damping(), model.friction()), (&[0.5][..], &[0.1][..]));
    /// ```
    #[must_use]
    pub fn damping(&self) -> &[f64] {
        &self.damping
    }
    /// Coulomb joint friction `F_c` per degree of freedom (N·m or N; `0` when none): the
    /// simulator applies a regularised `τ = -F_c tanh(v / v_s)`. The algorithms ignore it.
    #[must_use]
    pub fn friction(&self) -> &[f64] {
        &self.friction
    }
    /// The motion-subspace column of degree of freedom `k`, in its body's frame.
    #[must_use]
    pub fn motion_subspace(&self, k: usize) -> Twist {
        self.dof_S[k]
    }
    /// The joint owning degree of freedom `k`.
    #[must_use]
    pub fn dof_joint(&self, k: usize) -> JointId {
        JointId(self.dof_joint[k])
    }
    /// The moving bodies whose inertia is not physical, with the reason: zero mass, or a
    /// rotational inertia about the CoM violating the triangle inequality `λ1 + λ2 ≥ λ3`
    /// (relative tolerance 1e-6). The builder rejects negative masses and inertias that are not
    /// positive semi-definite; these milder defects occur in published models (PUMA 560).
    #[must_use]
    pub fn inertia_issues(&self) -> Vec<(JointId, crate::error::InertiaError)> {
        self.inertias
            .iter()
            .enumerate()
            .filter_map(|(i, g)| g.validate(1e-6).err().map(|e| (JointId(i), e)))
            .collect()
    }

    /// A copy of this model with gravity `g`.
    #[must_use]
    pub fn with_gravity(mut self, g: Vec3) -> Self {
        self.gravity = g;
        self
    }
    /// Replace the armature vector (length `nv`, entries finite and `≥ 0`).
    ///
    /// # Errors
    /// Wrong length or a negative or non-finite entry.
    pub fn set_armature(&mut self, armature: &[f64]) -> Result<(), ModelError> {
        DimensionError::check("armature", self.nv, armature.len()).map_err(|e| {
            ModelError::Dimension {
                joint: "<model>".into(),
                source: e,
            }
        })?;
        if armature.iter().any(|a| !a.is_finite() || *a < 0.0) {
            return Err(ModelError::BadArmature {
                joint: "<model>".into(),
            });
        }
        self.armature.copy_from_slice(armature);
        Ok(())
    }
}
