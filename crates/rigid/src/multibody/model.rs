//! The constant description of a kinematic tree: joints in depth-first order, their placements,
//! the bodies' spatial inertias, limits, armature, named frames and gravity.

use super::plan::Plan;
use super::{JointType, ModelError};
use crate::error::DimensionError;
use crate::mass::SpatialInertia;
use crate::spatial::{Transform, Twist, Vec3};

/// The depth-first index of a moving joint (0-based); it also names the body the joint moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(transparent))]
pub struct JointId(pub usize);

/// The index of a named frame in [`Model::frames`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FrameId(pub usize);

/// One moving joint and the body it carries.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
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
    /// A revolute joint imported from a URDF `continuous` joint (no position limits): the
    /// dynamics are those of any revolute joint, and only Pinocchio's layout differs (it writes
    /// the angle as `(cos θ, sin θ)`, [`JointType::pinocchio_coords`]).
    pub continuous: bool,
}

impl Joint {
    /// The type's name as the files write it: [`JointType::name`], or `continuous` for a
    /// revolute joint imported from a URDF `continuous` joint.
    #[must_use]
    pub fn type_name(&self) -> &'static str {
        if self.continuous {
            "continuous"
        } else {
            self.kind.name()
        }
    }

    /// The joint's degrees of freedom as a range of indices into `v`, `a`, `τ`.
    #[must_use]
    #[inline]
    pub fn dofs(&self) -> std::ops::Range<usize> {
        self.idx_v..self.idx_v + self.nv
    }

    /// The joint's configuration coordinates as a range of indices into `q`.
    #[must_use]
    #[inline]
    pub fn coordinates(&self) -> std::ops::Range<usize> {
        self.idx_q..self.idx_q + self.nq
    }
}

/// What a named frame stands for. Frame names are unique within a kind, and joint names among the
/// joints; a URDF link and a joint may share a name (links and joints are two namespaces in URDF,
/// as in Pinocchio, whose frames carry their type too).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
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
/// Build one with [`ModelBuilder`](super::ModelBuilder); evaluate it with a [`Data`](super::Data) workspace.
#[derive(Clone, Debug)]
pub struct Model {
    pub(crate) name: String,
    pub(crate) gravity: Vec3,
    joints: Vec<Joint>,
    inertias: Vec<SpatialInertia>,
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
    /// The speed caches, derived from `joints` and `inertias` by [`Plan::new`] and rebuilt by
    /// every method that changes them.
    plan: Plan,
    pub(crate) nq: usize,
    pub(crate) nv: usize,
}

impl Model {
    /// A model of these parts, with its plan built (the builder's last step).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn from_parts(
        name: String,
        gravity: Vec3,
        joints: Vec<Joint>,
        inertias: Vec<SpatialInertia>,
        frames: Vec<Frame>,
        limits: [Vec<f64>; 4],
        armature: Vec<f64>,
        damping: Vec<f64>,
        friction: Vec<f64>,
    ) -> Self {
        let [lower, upper, velocity_limit, effort_limit] = limits;
        let (nq, nv) = joints
            .last()
            .map_or((0, 0), |j| (j.idx_q + j.nq, j.idx_v + j.nv));
        let plan = Plan::new(&joints, &inertias);
        Self {
            name,
            gravity,
            joints,
            inertias,
            frames,
            lower,
            upper,
            velocity_limit,
            effort_limit,
            armature,
            damping,
            friction,
            plan,
            nq,
            nv,
        }
    }

    /// The compiled plan of the fast algorithms.
    #[inline(always)]
    pub(crate) fn plan(&self) -> &Plan {
        &self.plan
    }

    /// Replace the body inertias (one per joint, in the joints' order), rebuilding the plan.
    ///
    /// # Errors
    /// A wrong number of inertias, or one that is not finite or has a negative mass
    /// ([`ModelError::BadInertia`] names the body).
    pub fn set_inertias(&mut self, inertias: &[SpatialInertia]) -> Result<(), ModelError> {
        DimensionError::check("inertias", self.joints.len(), inertias.len()).map_err(|e| {
            ModelError::Dimension {
                joint: "<model>".into(),
                source: e,
            }
        })?;
        for (j, g) in self.joints.iter().zip(inertias) {
            super::builder::check_inertia(&j.name, g, super::InertiaCheck::AsWritten)?;
        }
        self.replace_inertias(inertias.to_vec());
        Ok(())
    }

    /// Replace the body inertias as they are (no check: identification's estimates may be
    /// non-physical), rebuilding the plan. `inertias.len()` must be the number of joints.
    pub(crate) fn replace_inertias(&mut self, inertias: Vec<SpatialInertia>) {
        assert_eq!(inertias.len(), self.joints.len(), "one inertia per joint");
        self.inertias = inertias;
        self.plan = Plan::new(&self.joints, &self.inertias);
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
    /// The motion-subspace column of degree of freedom `k`, in its body's frame, at the neutral
    /// configuration (the same at every `q` when the joint's
    /// [`constant_subspace`](JointType::constant_subspace) holds; otherwise see
    /// [`JointType::subspace`]).
    #[must_use]
    pub fn motion_subspace(&self, k: usize) -> Twist {
        self.plan.dof_S[k]
    }
    /// The joint owning degree of freedom `k`.
    #[must_use]
    pub fn dof_joint(&self, k: usize) -> JointId {
        JointId(self.plan.dof_joint[k])
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

    /// The joints whose whole subtree is massless (the body they move and every body below it
    /// weigh nothing): their rows of the mass matrix are zero, so `M` is singular and ABA is
    /// undefined. The model-level twin of the URDF check
    /// [`InertiaIssueKind::ZeroMassMovingLink`](crate::io::urdf::InertiaIssueKind), for models
    /// not read from a URDF file.
    ///
    /// ```
    /// use rigid::mass::SpatialInertia;
    /// use rigid::multibody::{JointId, JointType, ModelBuilder};
    /// use rigid::spatial::{Transform, Vec3};
    /// let mut b = ModelBuilder::new("arm");
    /// let g = SpatialInertia::from_com(1.0, Vec3::zeros(), rigid::mass::RotationalInertia::diagonal(1.0, 1.0, 1.0));
    /// let z = JointType::Revolute { axis: Vec3::z() };
    /// let shoulder = b.add_joint(None, "shoulder", z, Transform::identity(), g)?;
    /// b.add_joint(Some(shoulder), "wrist", z, Transform::identity(), SpatialInertia::zero())?;
    /// let model = b.build()?;
    /// assert_eq!(model.massless_subtrees(), vec![JointId(1)]);
    /// # Ok::<(), rigid::multibody::ModelError>(())
    /// ```
    #[must_use]
    pub fn massless_subtrees(&self) -> Vec<JointId> {
        (0..self.joints.len())
            .filter(|&i| {
                self.inertias[i..self.joints[i].subtree_end]
                    .iter()
                    .all(|g| g.mass() == 0.0)
            })
            .map(JointId)
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
