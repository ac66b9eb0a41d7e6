//! The constant description of a kinematic tree: joints in depth-first order, their placements,
//! the bodies' spatial inertias, limits, armature, named frames and gravity.

use super::{JointType, ModelError};
use crate::error::DimensionError;
use crate::mass::SpatialInertia;
use crate::spatial::{Mat3, Transform, Twist, Vec3};

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
    /// `oM_λ X_T X_J(q)` of a revolute joint turns two columns of `R_λ` (no 3x3 product).
    pub(crate) unrotated: Vec<bool>,
    pub(crate) nq: usize,
    pub(crate) nv: usize,
}

impl Model {
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

/// Builds a [`Model`] joint by joint, in depth-first order.
///
/// ```
/// use rigid::mass::{RotationalInertia, SpatialInertia};
/// use rigid::multibody::{JointType, ModelBuilder};
/// use rigid::spatial::{Transform, Vec3};
/// // a 2-link planar arm: links of 1 kg, CoM 0.5 m along x, joints about z
/// let link = SpatialInertia::from_com(1.0, Vec3::new(0.5, 0.0, 0.0), RotationalInertia::diagonal(0.01, 0.08, 0.08));
/// let mut b = ModelBuilder::new("arm");
/// let j1 = b.add_joint(None, "shoulder", JointType::Revolute { axis: Vec3::z() }, Transform::identity(), link)?;
/// let j2 = b.add_joint(Some(j1), "elbow", JointType::Revolute { axis: Vec3::z() },
///                      Transform::from_translation(Vec3::new(1.0, 0.0, 0.0)), link)?;
/// b.add_frame(Some(j2), "tool", Transform::from_translation(Vec3::new(1.0, 0.0, 0.0)))?;
/// b.set_limits(j1, &[-2.0], &[2.0], &[3.0], &[50.0])?;
/// let model = b.build()?;
/// assert_eq!((model.nq(), model.nv(), model.total_mass()), (2, 2, 2.0));
/// # Ok::<(), rigid::multibody::ModelError>(())
/// ```
#[derive(Clone, Debug)]
pub struct ModelBuilder {
    model: Model,
    inertia_check: InertiaCheck,
    /// Joint names, and frame names by kind, for O(1) duplicate checks.
    names: std::collections::HashSet<(Option<FrameKind>, String)>,
    /// The chain of joints from the root to the last joint added (for the depth-first check).
    stack: Vec<usize>,
}

fn check_placement(name: &str, t: &Transform) -> Result<(), ModelError> {
    let finite = t
        .rotation
        .iter()
        .chain(t.translation.iter())
        .all(|x| x.is_finite());
    if !finite || crate::spatial::so3::check(&t.rotation, 1e-6).is_err() {
        return Err(ModelError::BadPlacement { name: name.into() });
    }
    Ok(())
}

/// What [`ModelBuilder`] accepts as a body inertia.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum InertiaCheck {
    /// Finite, mass `≥ 0`, and an inertia about the CoM positive semi-definite to
    /// `max(10⁻⁶ λ3, round-off)` (the rounding of published values; round-off as in
    /// [`SpatialInertia::round_off`]). The triangle inequality is not enforced: published models
    /// violate it (the PUMA 560's link 3); [`Model::inertia_issues`] reports it.
    #[default]
    Physical,
    /// Finite and mass `≥ 0` only: the inertia is kept as written, even when no mass
    /// distribution has it (a URDF loaded with the `warn` inertia policy, as other tools do).
    AsWritten,
}

fn check_inertia(name: &str, g: &SpatialInertia, check: InertiaCheck) -> Result<(), ModelError> {
    let bad = |source| ModelError::BadInertia {
        name: name.into(),
        source,
    };
    let finite = g.mass().is_finite()
        && g.first_moment().iter().all(|x| x.is_finite())
        && g.inertia_origin().matrix().iter().all(|x| x.is_finite());
    if !finite {
        return Err(bad(crate::error::InertiaError::NonFinite));
    }
    if g.mass() < 0.0 {
        return Err(bad(crate::error::InertiaError::BadMass { mass: g.mass() }));
    }
    if check == InertiaCheck::AsWritten {
        return Ok(());
    }
    let l = g.inertia_com().principal_moments();
    if l[0] < -(1e-6 * l[2].abs()).max(g.round_off()).max(1e-300) {
        return Err(bad(crate::error::InertiaError::NotPositiveSemiDefinite {
            moment: l[0],
        }));
    }
    Ok(())
}

/// `Some((c, s))` if `S = s e_c` exactly (`s = ±1`), angular components first.
fn unit_axis(S: &Twist) -> Option<(usize, f64)> {
    let x = S.to_vector();
    let mut nonzero = (0..6).filter(|&c| x[c] != 0.0);
    match (nonzero.next(), nonzero.next()) {
        (Some(c), None) if x[c].abs() == 1.0 => Some((c, x[c])),
        _ => None,
    }
}

impl ModelBuilder {
    /// An empty model called `name`, with gravity `[0, 0, -9.81]` m/s².
    #[must_use]
    pub fn new(name: &str) -> Self {
        Self {
            model: Model {
                name: name.into(),
                gravity: Vec3::new(0.0, 0.0, -9.81),
                joints: Vec::new(),
                inertias: Vec::new(),
                frames: Vec::new(),
                lower: Vec::new(),
                upper: Vec::new(),
                velocity_limit: Vec::new(),
                effort_limit: Vec::new(),
                armature: Vec::new(),
                damping: Vec::new(),
                friction: Vec::new(),
                dof_S: Vec::new(),
                dof_joint: Vec::new(),
                dof_axis: Vec::new(),
                quaternions: Vec::new(),
                unrotated: Vec::new(),
                nq: 0,
                nv: 0,
            },
            stack: Vec::new(),
            inertia_check: InertiaCheck::Physical,
            names: std::collections::HashSet::new(),
        }
    }

    /// What the following `add_*` calls accept as a body inertia (default
    /// [`InertiaCheck::Physical`]).
    pub fn set_inertia_check(&mut self, check: InertiaCheck) {
        self.inertia_check = check;
    }

    /// Set gravity in the world frame (m/s²).
    pub fn set_gravity(&mut self, g: Vec3) {
        self.model.gravity = g;
    }

    /// Joint names are unique among joints; frame names within their kind.
    fn check_name(&self, name: &str, kind: Option<FrameKind>) -> Result<(), ModelError> {
        if self.names.contains(&(kind, name.to_string())) {
            Err(ModelError::DuplicateName { name: name.into() })
        } else {
            Ok(())
        }
    }

    fn check_parent(&self, name: &str, parent: Option<JointId>) -> Result<(), ModelError> {
        match parent {
            Some(p) if p.0 >= self.model.joints.len() => Err(ModelError::UnknownParent {
                name: name.into(),
                parent: p.0,
            }),
            _ => Ok(()),
        }
    }

    /// Add a moving joint and the body it carries; returns its [`JointId`].
    ///
    /// `placement` is the pose of the joint frame in the parent joint frame (the world if
    /// `parent` is `None`) at `q = neutral`; `inertia` is the child body's spatial inertia in
    /// the joint frame. Joints must come in depth-first order: `parent` is the last joint added
    /// or one of its ancestors (or `None`).
    ///
    /// # Errors
    /// Unknown or out-of-order parent, duplicate name, zero or non-finite axis, a placement that
    /// is not a rigid transform, a negative mass or a non-physical inertia.
    pub fn add_joint(
        &mut self,
        parent: Option<JointId>,
        name: &str,
        joint: JointType,
        placement: Transform,
        inertia: SpatialInertia,
    ) -> Result<JointId, ModelError> {
        self.check_name(name, None)?;
        self.check_parent(name, parent)?;
        let kind = joint
            .normalized_axis()
            .ok_or_else(|| ModelError::BadAxis { name: name.into() })?;
        check_placement(name, &placement)?;
        check_inertia(name, &inertia, self.inertia_check)?;
        // depth-first: pop the stack down to the parent
        match parent {
            None => self.stack.clear(),
            Some(p) => {
                let pos = self.stack.iter().rposition(|&s| s == p.0).ok_or_else(|| {
                    ModelError::NotDepthFirst {
                        name: name.into(),
                        parent: self.model.joints[p.0].name.clone(),
                    }
                })?;
                self.stack.truncate(pos + 1);
            }
        }
        let m = &mut self.model;
        let id = m.joints.len();
        let (nq, nv) = (kind.nq(), kind.nv());
        m.joints.push(Joint {
            name: name.into(),
            kind,
            parent,
            placement,
            idx_q: m.nq,
            nq,
            idx_v: m.nv,
            nv,
            subtree_end: id + 1,
        });
        m.inertias.push(inertia);
        m.unrotated.push(placement.rotation == Mat3::identity());
        if let Some(o) = kind.quaternion_offset() {
            m.quaternions.push((id, m.nq + o));
        }
        for k in 0..nv {
            let S = kind.motion_subspace(k);
            m.dof_S.push(S);
            m.dof_axis.push(unit_axis(&S));
            m.dof_joint.push(id);
        }
        m.lower.resize(m.nq + nq, f64::NEG_INFINITY);
        m.upper.resize(m.nq + nq, f64::INFINITY);
        m.velocity_limit.resize(m.nv + nv, f64::INFINITY);
        m.effort_limit.resize(m.nv + nv, f64::INFINITY);
        m.armature.resize(m.nv + nv, 0.0);
        m.damping.resize(m.nv + nv, 0.0);
        m.friction.resize(m.nv + nv, 0.0);
        m.nq += nq;
        m.nv += nv;
        self.stack.push(id);
        self.names.insert((None, name.to_string()));
        Ok(JointId(id))
    }

    /// A body welded (fixed joint) to `parent` at `placement` (its pose in the parent joint
    /// frame): its inertia `G` is merged into the parent body as `[Ad_{T⁻¹}]ᵀ G [Ad_{T⁻¹}]` (or
    /// dropped if `parent` is `None`, the world), and a named frame is kept.
    ///
    /// # Errors
    /// As [`add_joint`](Self::add_joint).
    pub fn add_fixed_body(
        &mut self,
        parent: Option<JointId>,
        name: &str,
        placement: Transform,
        inertia: SpatialInertia,
    ) -> Result<FrameId, ModelError> {
        self.check_name(name, Some(FrameKind::Body))?;
        self.check_parent(name, parent)?;
        check_placement(name, &placement)?;
        check_inertia(name, &inertia, self.inertia_check)?;
        if let Some(p) = parent {
            self.model.inertias[p.0] += inertia.transformed(&placement);
        }
        self.model.frames.push(Frame {
            name: name.into(),
            parent,
            placement,
            kind: FrameKind::Body,
        });
        self.names.insert((Some(FrameKind::Body), name.to_string()));
        Ok(FrameId(self.model.frames.len() - 1))
    }

    /// A named operational frame fixed in `parent` (or the world) at `placement`.
    ///
    /// # Errors
    /// Unknown parent, duplicate name, or a placement that is not a rigid transform.
    pub fn add_frame(
        &mut self,
        parent: Option<JointId>,
        name: &str,
        placement: Transform,
    ) -> Result<FrameId, ModelError> {
        self.add_frame_of_kind(parent, name, placement, FrameKind::Operational)
    }

    /// A named frame of kind `kind` fixed in `parent` (or the world) at `placement`, carrying no
    /// inertia (for a body frame with an inertia, use [`add_fixed_body`](Self::add_fixed_body)).
    ///
    /// # Errors
    /// Unknown parent, a frame of the same kind and name, or a placement that is not a rigid
    /// transform.
    pub fn add_frame_of_kind(
        &mut self,
        parent: Option<JointId>,
        name: &str,
        placement: Transform,
        kind: FrameKind,
    ) -> Result<FrameId, ModelError> {
        self.check_name(name, Some(kind))?;
        self.check_parent(name, parent)?;
        check_placement(name, &placement)?;
        self.model.frames.push(Frame {
            name: name.into(),
            parent,
            placement,
            kind,
        });
        self.names.insert((Some(kind), name.to_string()));
        Ok(FrameId(self.model.frames.len() - 1))
    }

    fn joint_checked(&self, joint: JointId) -> Result<&Joint, ModelError> {
        self.model
            .joints
            .get(joint.0)
            .ok_or(ModelError::UnknownJoint { index: joint.0 })
    }

    /// Position limits (`nq` each), velocity and effort limits (`nv` each) of one joint. Use
    /// infinities for "none".
    ///
    /// # Errors
    /// Unknown joint, wrong lengths, NaN, `lower > upper`, negative velocity or effort limit.
    pub fn set_limits(
        &mut self,
        joint: JointId,
        lower: &[f64],
        upper: &[f64],
        velocity: &[f64],
        effort: &[f64],
    ) -> Result<(), ModelError> {
        let j = self.joint_checked(joint)?.clone();
        let dim = |what, n, got| {
            DimensionError::check(what, n, got).map_err(|source| ModelError::Dimension {
                joint: j.name.clone(),
                source,
            })
        };
        dim("lower limits", j.nq, lower.len())?;
        dim("upper limits", j.nq, upper.len())?;
        dim("velocity limits", j.nv, velocity.len())?;
        dim("effort limits", j.nv, effort.len())?;
        let bad = lower
            .iter()
            .zip(upper)
            .any(|(l, u)| l.is_nan() || u.is_nan() || l > u)
            || velocity
                .iter()
                .chain(effort)
                .any(|x| x.is_nan() || *x < 0.0);
        if bad {
            return Err(ModelError::BadLimits { joint: j.name });
        }
        let m = &mut self.model;
        m.lower[j.idx_q..j.idx_q + j.nq].copy_from_slice(lower);
        m.upper[j.idx_q..j.idx_q + j.nq].copy_from_slice(upper);
        m.velocity_limit[j.idx_v..j.idx_v + j.nv].copy_from_slice(velocity);
        m.effort_limit[j.idx_v..j.idx_v + j.nv].copy_from_slice(effort);
        Ok(())
    }

    /// The armature of one joint (`nv` entries, `≥ 0`), added to the diagonal of `M` and to
    /// ABA's `D`.
    ///
    /// # Errors
    /// Unknown joint, wrong length, negative or non-finite entry.
    pub fn set_armature(&mut self, joint: JointId, armature: &[f64]) -> Result<(), ModelError> {
        let j = self.joint_checked(joint)?.clone();
        DimensionError::check("armature", j.nv, armature.len()).map_err(|source| {
            ModelError::Dimension {
                joint: j.name.clone(),
                source,
            }
        })?;
        if armature.iter().any(|a| !a.is_finite() || *a < 0.0) {
            return Err(ModelError::BadArmature { joint: j.name });
        }
        self.model.armature[j.idx_v..j.idx_v + j.nv].copy_from_slice(armature);
        Ok(())
    }

    /// The viscous damping and Coulomb friction of one joint (`nv` entries each, finite and
    /// `≥ 0`; URDF `<dynamics damping friction>`), used by the simulator only.
    ///
    /// # Errors
    /// Unknown joint, wrong lengths, a negative or non-finite entry.
    pub fn set_joint_dynamics(
        &mut self,
        joint: JointId,
        damping: &[f64],
        friction: &[f64],
    ) -> Result<(), ModelError> {
        let j = self.joint_checked(joint)?.clone();
        for (what, x) in [("damping", damping), ("friction", friction)] {
            DimensionError::check(what, j.nv, x.len()).map_err(|source| ModelError::Dimension {
                joint: j.name.clone(),
                source,
            })?;
            if x.iter().any(|a| !a.is_finite() || *a < 0.0) {
                return Err(ModelError::BadDynamics { joint: j.name });
            }
        }
        let r = j.idx_v..j.idx_v + j.nv;
        self.model.damping[r.clone()].copy_from_slice(damping);
        self.model.friction[r].copy_from_slice(friction);
        Ok(())
    }

    /// Freeze the model (computes each joint's subtree range).
    ///
    /// # Errors
    /// Non-finite gravity.
    pub fn build(mut self) -> Result<Model, ModelError> {
        if self.model.gravity.iter().any(|g| !g.is_finite()) {
            return Err(ModelError::BadGravity);
        }
        let n = self.model.joints.len();
        for i in (0..n).rev() {
            if let Some(p) = self.model.joints[i].parent {
                let e = self.model.joints[i].subtree_end;
                let pe = &mut self.model.joints[p.0].subtree_end;
                *pe = (*pe).max(e);
            }
        }
        Ok(self.model)
    }
}
