//! Constrained dynamics: closed kinematic loops and rigid contacts, with the constraint forces,
//! as Pinocchio's `RigidConstraintModel` computes them (Carpentier, Budhiraja & Mansard,
//! "Proximal and sparse resolution of constrained dynamic equations", RSS 2021).
//!
//! A [`ConstraintModel`] ties two frames, `c1 = oMi[joint1] · placement1` and
//! `c2 = oMi[joint2] · placement2` (the world for `None`, Pinocchio's "universe"):
//!
//! | kind | rows | holds | `λ` |
//! | --- | --- | --- | --- |
//! | [`ConstraintKind::Point`] | 3 | the origins of c1 and c2 coincide | the force on joint1's body at c1's origin |
//! | [`ConstraintKind::Frame`] | 6 | c1 and c2 coincide | the wrench `(m, f)` on joint1's body, about c1's origin |
//! | [`ConstraintKind::JointCoordinate`] | 1 | `q_j1 = p(q_j2)`, `p` a polynomial (MJCF `<equality joint>`) | the generalised force on joint1 |
//!
//! `λ` is expressed in c1's axes ([`ReferenceFrame::Body`], Pinocchio's `LOCAL`) or in the world's
//! axes at c1's origin ([`ReferenceFrame::WorldAligned`], `LOCAL_WORLD_ALIGNED`); joint2's body
//! receives the opposite force or wrench (about the same point). The constraints enter the
//! equations of motion as
//!
//! `M(q) q̈ + c(q, q̇) + g(q) = τ + Jᵀ λ`,  `J q̈ + γ = 0`,
//!
//! with `J` the constraint Jacobian and `γ` the drift ([`ConstraintData::gamma`]): `γ = J̇ q̇`
//! minus the Baumgarte correction `−kp e − kd ė`, so that the error obeys `ë + kd ė + kp e = 0`.
//! Pinocchio's conventions, followed exactly (`contact-info.hxx`, `constrained-dynamics.hxx`):
//!
//! - point: `J q̇` is the velocity of c1's origin on body 1 minus that of c2's origin on body 2,
//!   in c1's axes (or the world's); `J̇ q̇` the difference of their classical accelerations
//!   (`v̇ + ω × v` of each point); the error `e = −c1Mc2.translation` (or `R_1 e`);
//! - frame: `J q̇ = V_c1 − [Ad_{c1Mc2}] V_c2`, the relative body twist in c1; `J̇ q̇` its time
//!   derivative `A_c1 − [Ad_{c1Mc2}] A_c2 + [ad_{J q̇}] [Ad_{c1Mc2}] V_c2`; the error
//!   `e = −log(c1Mc2)`. World-aligned: `J`, `J q̇` and `e` rotated by `R_1` (both halves), and
//!   `γ = R_1 (A_c1 − [Ad_{c1Mc2}] A_c2) + …` *without* the bracket term, as Pinocchio 4.1 does
//!   (the two agree when the constraint velocity is zero);
//! - joint coordinate: `e = q_1 − p(q_2)`, `J q̇ = q̇_1 − p'(q_2) q̇_2`,
//!   `J̇ q̇ = −p''(q_2) q̇_2²`.
//!
//! | verb | solves | source |
//! | --- | --- | --- |
//! | [`constraint_dynamics`] | `q̈`, `λ` | KKT system by the tree-sparse `M = LᵀL` and the Delassus matrix `J M⁻¹ Jᵀ`; proximal iterations for redundant constraints (RSS 2021, Alg. 1) |
//! | [`impulse_dynamics`] | `q̇⁺`, the impulse `Λ` | `M (q̇⁺ − q̇⁻) = Jᵀ Λ`, `J q̇⁺ = −e J q̇⁻` (Newton's impact law) |
//! | [`contact_inverse_dynamics`] | `τ`, `λ` | the least-norm `(τ_a, λ)` with `S_aᵀ τ_a + Jᵀ λ = M q̈ + c + g` |
//! | [`Simulator::with_constraints`](crate::simulation::Simulator::with_constraints) | `(q, q̇)(t)` | the one simulator: constrained dynamics (or bilateral rows beside the contacts), projection of `q` and `q̇` on the constraint manifold |
//!
//! The workspace [`ConstraintData`] is made once per (model, constraint set), like Pinocchio's
//! `initConstraintDynamics`; no verb allocates afterwards.
//!
//! ```
//! use rigid::multibody::constraints::{constraint_dynamics, ConstraintData, ConstraintModel, ProximalSettings};
//! use rigid::multibody::{builtin, Data, JointId};
//! use rigid::spatial::{Transform, Vec3};
//! // the double pendulum's tip held at the point where it hangs at rest
//! let model = builtin("double_pendulum").unwrap();
//! let tip = Transform::from_translation(Vec3::new(0.0, 0.0, -1.0));
//! let mut data = Data::new(&model);
//! rigid::multibody::forward_kinematics_q(&model, &mut data, &[0.0, 0.0])?;
//! let hold = data.placements[1] * tip;
//! let c = ConstraintModel::point(Some(JointId(1)), tip, None, hold);
//! let mut cdata = ConstraintData::new(&model, &[c])?;
//! // the pendulum moves in the x-z plane: the point's y row is redundant, so μ > 0
//! let settings = ProximalSettings::new(1e-12, 1e-6, 100);
//! constraint_dynamics(&model, &mut data, &mut cdata, &[0.0, 0.0], &[0.0, 0.0], &[0.0, 0.0], &settings)?;
//! assert!(cdata.ddq.amax() < 1e-12 && cdata.stats.converged); // held in place, at rest
//! # Ok::<(), rigid::multibody::constraints::ConstraintError>(())
//! ```

// loops over several per-row and per-dof arrays at once read better indexed
#![allow(clippy::needless_range_loop)]

mod derivatives;
mod dynamics;
mod impulse;
mod inverse;
mod jacobian;
pub(crate) mod kinematics;
mod partials;
pub(crate) mod solver;
pub(crate) mod workspace;

#[cfg(feature = "collision")]
pub(crate) use derivatives::velocity_level_partials;
pub use derivatives::{
    constraint_dynamics_derivatives, impulse_dynamics_derivatives, ConstraintDynamicsDerivatives,
    ImpulseDynamicsDerivatives,
};
pub use dynamics::constraint_dynamics;
pub(crate) use dynamics::constraint_rows;
pub use impulse::impulse_dynamics;
pub use inverse::contact_inverse_dynamics;
pub use jacobian::{jacobian_dynamics, jacobian_dynamics_from_terms};
pub use kinematics::ConstraintPlacement;
pub use workspace::ConstraintData;

pub use crate::multibody::ReferenceFrame;
use crate::multibody::{FrameLookupError, JointId, Model, MultibodyError};
use crate::spatial::{so3, Transform};
use thiserror::Error;

/// The name of the world in constraint files and name lookups (Pinocchio's joint 0).
pub const UNIVERSE: &str = "universe";

/// What a constraint holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ConstraintKind {
    /// 3 rows: the origins of c1 and c2 coincide (Pinocchio's `CONTACT_3D`; a ball joint, a
    /// point contact, MJCF `<equality connect>`).
    Point,
    /// 6 rows: c1 and c2 coincide (`CONTACT_6D`; a weld, a flat foot, MJCF `<equality weld>`).
    Frame,
    /// 1 row: `q_j1 = p(q_j2) = Σ_k c_k q_j2^k` for two one-dof joints (MJCF `<equality joint>`,
    /// whose `polycoef` has these five coefficients); without joint2, `q_j1 = c_0`.
    JointCoordinate {
        /// `c_0 … c_4`.
        polycoef: [f64; 5],
    },
}

impl ConstraintKind {
    /// The number of rows: 3, 6 or 1.
    #[must_use]
    pub fn dim(&self) -> usize {
        match self {
            Self::Point => 3,
            Self::Frame => 6,
            Self::JointCoordinate { .. } => 1,
        }
    }
}

/// Baumgarte stabilisation: the constraint error `e` is driven by `ë = −kp e − kd ė`
/// (Baumgarte 1972; Pinocchio's `BaumgarteCorrectorParameters`). Zero gains: the acceleration
/// constraint `J q̈ + J̇ q̇ = 0` only, and a simulation drifts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Baumgarte {
    /// Position gain (1/s²).
    pub kp: f64,
    /// Velocity gain (1/s).
    pub kd: f64,
}

/// A bilateral constraint between two frames (or two joint coordinates): Pinocchio's
/// `RigidConstraintModel(type, model, joint1_id, joint1_placement, joint2_id, joint2_placement,
/// reference_frame)` with joint ids 0-based and `None` for the world.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstraintModel {
    /// A label for messages (may be empty).
    pub name: String,
    /// What it holds.
    pub kind: ConstraintKind,
    /// The body the force `λ` acts on (`None`: the world).
    pub joint1: Option<JointId>,
    /// c1 in joint1's frame (in the world for `None`).
    pub placement1: Transform,
    /// The other body (`None`: the world).
    pub joint2: Option<JointId>,
    /// c2 in joint2's frame (in the world for `None`).
    pub placement2: Transform,
    /// The axes of `J`, `γ`, `e` and `λ`: [`ReferenceFrame::Body`] (c1's axes, `LOCAL`) or
    /// [`ReferenceFrame::WorldAligned`] (`LOCAL_WORLD_ALIGNED`). Ignored by joint-coordinate
    /// constraints.
    pub reference: ReferenceFrame,
    /// Baumgarte gains.
    pub baumgarte: Baumgarte,
}

impl ConstraintModel {
    fn new(
        kind: ConstraintKind,
        joint1: Option<JointId>,
        placement1: Transform,
        joint2: Option<JointId>,
        placement2: Transform,
    ) -> Self {
        Self {
            name: String::new(),
            kind,
            joint1,
            placement1,
            joint2,
            placement2,
            reference: ReferenceFrame::Body,
            baumgarte: Baumgarte::default(),
        }
    }

    /// A point constraint (3 rows), local reference frame, no Baumgarte correction.
    #[must_use]
    pub fn point(
        joint1: Option<JointId>,
        placement1: Transform,
        joint2: Option<JointId>,
        placement2: Transform,
    ) -> Self {
        Self::new(
            ConstraintKind::Point,
            joint1,
            placement1,
            joint2,
            placement2,
        )
    }

    /// A frame constraint (6 rows), local reference frame, no Baumgarte correction.
    #[must_use]
    pub fn frame(
        joint1: Option<JointId>,
        placement1: Transform,
        joint2: Option<JointId>,
        placement2: Transform,
    ) -> Self {
        Self::new(
            ConstraintKind::Frame,
            joint1,
            placement1,
            joint2,
            placement2,
        )
    }

    /// `q_j1 = Σ_k polycoef[k] q_j2^k` (`q_j1 = polycoef[0]` without joint2).
    #[must_use]
    pub fn joint_coordinate(joint1: JointId, joint2: Option<JointId>, polycoef: [f64; 5]) -> Self {
        let id = Transform::identity();
        Self::new(
            ConstraintKind::JointCoordinate { polycoef },
            Some(joint1),
            id,
            joint2,
            id,
        )
    }

    /// A constraint's reference frame by its name, as [`ReferenceFrame`]'s `FromStr` reads it
    /// (`local` or `body`, `local_world_aligned` or `world_aligned`, any case), the world's
    /// (`WORLD`) refused: `λ` is in the axes of c1 or of the world at c1, as in Pinocchio.
    ///
    /// # Errors
    /// Another name, or `world`: the message names it and the two a constraint takes.
    pub fn reference_named(name: &str) -> Result<ReferenceFrame, String> {
        match name.parse() {
            Ok(ReferenceFrame::Spatial) | Err(_) => Err(format!(
                "\"reference_frame\" is \"{name}\" (expected \"local\" or \"local_world_aligned\")"
            )),
            Ok(frame) => Ok(frame),
        }
    }

    /// The same with reference frame `reference`.
    #[must_use]
    pub fn with_reference(mut self, reference: ReferenceFrame) -> Self {
        self.reference = reference;
        self
    }

    /// The same with Baumgarte gains `kp`, `kd`.
    #[must_use]
    pub fn with_baumgarte(mut self, kp: f64, kd: f64) -> Self {
        self.baumgarte = Baumgarte { kp, kd };
        self
    }

    /// The same with a name.
    #[must_use]
    pub fn with_name(mut self, name: impl Into<String>) -> Self {
        self.name = name.into();
        self
    }

    /// A point or frame constraint between two joints given by name ([`UNIVERSE`] for the
    /// world), with placements relative to the joint frames (to the world for [`UNIVERSE`]):
    /// the form of `rigid eval --constraints`.
    ///
    /// # Errors
    /// [`ConstraintError::UnknownJoint`].
    pub fn on_joints(
        model: &Model,
        kind: ConstraintKind,
        joint1: &str,
        placement1: Transform,
        joint2: &str,
        placement2: Transform,
    ) -> Result<Self, ConstraintError> {
        let id = |name: &str| -> Result<Option<JointId>, ConstraintError> {
            if name == UNIVERSE {
                return Ok(None);
            }
            model
                .joint_id(name)
                .map(Some)
                .ok_or_else(|| ConstraintError::UnknownJoint { name: name.into() })
        };
        Ok(Self::new(kind, id(joint1)?, placement1, id(joint2)?, placement2).with_name(joint1))
    }

    /// A point or frame constraint between two named frames of the model (URDF links, fixed
    /// joints, operational frames; [`Model::frame_id`]), c1 and c2 at the frames' origins and
    /// axes; [`UNIVERSE`] is the world frame itself.
    ///
    /// # Errors
    /// [`ConstraintError::UnknownFrame`] (no frame of that name, or an ambiguous name).
    pub fn on_frames(
        model: &Model,
        kind: ConstraintKind,
        frame1: &str,
        frame2: &str,
    ) -> Result<Self, ConstraintError> {
        let at = |name: &str| -> Result<(Option<JointId>, Transform), ConstraintError> {
            if name == UNIVERSE {
                return Ok((None, Transform::identity()));
            }
            let f = &model.frames()[model.frame_id(name)?.0];
            Ok((f.parent, f.placement))
        };
        let ((j1, p1), (j2, p2)) = (at(frame1)?, at(frame2)?);
        Ok(Self::new(kind, j1, p1, j2, p2).with_name(frame1))
    }

    /// The number of rows (3, 6 or 1).
    #[must_use]
    pub fn dim(&self) -> usize {
        self.kind.dim()
    }

    /// Checks this constraint against `model` (`index` names it in the error).
    pub(crate) fn check(&self, model: &Model, index: usize) -> Result<(), ConstraintError> {
        for j in [self.joint1, self.joint2].into_iter().flatten() {
            if j.0 >= model.njoints() {
                return Err(ConstraintError::JointOutOfRange { index, joint: j.0 });
            }
        }
        let Baumgarte { kp, kd } = self.baumgarte;
        if !(kp.is_finite() && kd.is_finite() && kp >= 0.0 && kd >= 0.0) {
            return Err(ConstraintError::BadGains { index, kp, kd });
        }
        if let ConstraintKind::JointCoordinate { polycoef } = self.kind {
            if polycoef.iter().any(|c| !c.is_finite()) {
                return Err(ConstraintError::BadPolynomial { index });
            }
            for j in [self.joint1, self.joint2].into_iter().flatten() {
                let joint = model.joint(j);
                if joint.nv != 1 || joint.nq != 1 {
                    return Err(ConstraintError::NotOneDof {
                        index,
                        joint: joint.name.clone(),
                        nv: joint.nv,
                    });
                }
            }
            if self.joint1.is_none() || self.joint1 == self.joint2 {
                return Err(ConstraintError::SameBody { index });
            }
            return Ok(());
        }
        if self.reference == ReferenceFrame::Spatial {
            return Err(ConstraintError::SpatialReference { index });
        }
        for (which, p) in [
            ("placement1", &self.placement1),
            ("placement2", &self.placement2),
        ] {
            let finite = p
                .rotation
                .iter()
                .chain(p.translation.iter())
                .all(|x| x.is_finite());
            if !finite || so3::check(&p.rotation, 1e-9).is_err() {
                return Err(ConstraintError::BadPlacement { index, which });
            }
        }
        if self.joint1 == self.joint2 {
            return Err(ConstraintError::SameBody { index });
        }
        Ok(())
    }
}

/// The settings of the proximal iterations (Pinocchio's `ProximalSettings`): each iteration
/// solves `(J M⁻¹ Jᵀ + μ I) λ_{k+1} = −γ − J q̈_free + μ λ_k` (RSS 2021, Alg. 1), which converges
/// to a solution of the constrained problem for any `μ > 0`, also when the constraints are
/// redundant (then to the `λ` of least norm, starting from `λ_0 = 0`). With `μ = 0` one exact
/// solve is done and the constraints must be independent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProximalSettings {
    /// The proximal regularisation `μ ≥ 0`.
    pub mu: f64,
    /// Stop when the constraint residual `‖J q̈ + γ‖∞` is at most this (Pinocchio 4.1 compares
    /// `‖(J M⁻¹ Jᵀ) λ − rhs‖∞` here instead, which leaves out the free acceleration and rarely
    /// stops it: set this to 0 to stop on the relative test alone, as Pinocchio does).
    pub absolute_accuracy: f64,
    /// Stop when `‖λ_{k+1} − λ_k‖∞` is at most this.
    pub relative_accuracy: f64,
    /// The most iterations (at least 1).
    pub max_iter: usize,
}

impl Default for ProximalSettings {
    /// `μ = 0` (one exact solve), accuracies `1e-12`, at most 100 iterations.
    fn default() -> Self {
        Self {
            mu: 0.0,
            absolute_accuracy: 1e-12,
            relative_accuracy: 1e-12,
            max_iter: 100,
        }
    }
}

impl ProximalSettings {
    /// Pinocchio's `ProximalSettings(accuracy, mu, max_iter)`.
    #[must_use]
    pub fn new(accuracy: f64, mu: f64, max_iter: usize) -> Self {
        Self {
            mu,
            absolute_accuracy: accuracy,
            relative_accuracy: accuracy,
            max_iter,
        }
    }

    /// The settings that hold loops whose rows may be redundant (a planar loop closed by a 3D
    /// point, an MJCF file's `<equality>` elements): accuracy `1e-12`, `μ = 1e-6`, at most 1000
    /// proximal iterations.
    #[must_use]
    pub fn redundant() -> Self {
        Self::new(1e-12, 1e-6, 1000)
    }

    pub(crate) fn check(&self) -> Result<(), ConstraintError> {
        let ok = self.mu.is_finite()
            && self.mu >= 0.0
            && self.absolute_accuracy >= 0.0
            && self.relative_accuracy >= 0.0
            && self.max_iter >= 1;
        if ok {
            Ok(())
        } else {
            Err(ConstraintError::BadSettings)
        }
    }
}

/// What the last solve did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolverStats {
    /// Proximal iterations done.
    pub iterations: usize,
    /// `‖J x + γ‖∞` at the end (`x` = `q̈`, or the velocity change for impulses).
    pub absolute_residual: f64,
    /// `‖λ_k − λ_{k−1}‖∞` of the last iteration (`‖λ‖∞` after one).
    pub relative_residual: f64,
    /// Whether an accuracy was reached (always after one exact solve with `μ = 0`).
    pub converged: bool,
    /// [`contact_inverse_dynamics`] only: `‖S_aᵀ τ_a + Jᵀ λ − τ_ID‖∞`, zero (to rounding)
    /// unless no torques and forces produce `q̈` (then the least-squares answer's residual).
    pub dynamics_residual: f64,
}

/// What can go wrong with constraints.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ConstraintError {
    /// A bad `q`, `v`, `τ` or a workspace of another model.
    #[error(transparent)]
    Multibody(#[from] MultibodyError),
    /// No joint of that name.
    #[error("no joint named \"{name}\" (\"universe\" is the world)")]
    UnknownJoint {
        /// The name looked up.
        name: String,
    },
    /// No frame, or several of different kinds, of that name.
    #[error(transparent)]
    UnknownFrame(#[from] FrameLookupError),
    /// A joint index past the model's joints.
    #[error("constraint {index}: joint index {joint} out of range")]
    JointOutOfRange {
        /// The constraint's position in the set.
        index: usize,
        /// The joint index.
        joint: usize,
    },
    /// A placement with a non-finite entry or a rotation that is not orthonormal (1e-9).
    #[error("constraint {index}: {which} is not a finite rigid transform")]
    BadPlacement {
        /// The constraint's position in the set.
        index: usize,
        /// `placement1` or `placement2`.
        which: &'static str,
    },
    /// Negative or non-finite Baumgarte gains.
    #[error("constraint {index}: Baumgarte gains must be finite and non-negative (kp = {kp}, kd = {kd})")]
    BadGains {
        /// The constraint's position in the set.
        index: usize,
        /// The position gain given.
        kp: f64,
        /// The velocity gain given.
        kd: f64,
    },
    /// Both ends on one body (or both on the world): the constraint says nothing.
    #[error("constraint {index}: both ends are on the same body (or both on the world)")]
    SameBody {
        /// The constraint's position in the set.
        index: usize,
    },
    /// [`ReferenceFrame::Spatial`] asked for (Pinocchio refuses `WORLD` too).
    #[error("constraint {index}: the reference frame must be local or local_world_aligned")]
    SpatialReference {
        /// The constraint's position in the set.
        index: usize,
    },
    /// A joint-coordinate constraint on a joint that is not one-dof with one coordinate.
    #[error("constraint {index}: joint '{joint}' has {nv} degrees of freedom; a joint-coordinate constraint couples one-dof joints")]
    NotOneDof {
        /// The constraint's position in the set.
        index: usize,
        /// The joint.
        joint: String,
        /// Its degrees of freedom.
        nv: usize,
    },
    /// A non-finite polynomial coefficient.
    #[error("constraint {index}: polynomial coefficients must be finite")]
    BadPolynomial {
        /// The constraint's position in the set.
        index: usize,
    },
    /// `μ < 0` or not finite, a negative accuracy or `max_iter = 0`.
    #[error("proximal settings: mu must be finite and >= 0, accuracies >= 0, max_iter >= 1")]
    BadSettings,
    /// A restitution coefficient outside `[0, 1]`.
    #[error("restitution {0} is not in [0, 1]")]
    BadRestitution(f64),
    /// An unactuated-dof mask of the wrong length.
    #[error("the actuation mask has {got} entries, the model {nv} degrees of freedom")]
    BadActuation {
        /// Entries given.
        got: usize,
        /// `nv`.
        nv: usize,
    },
    /// A workspace made for another model (or with a constraint set of another size).
    #[error("the constraint workspace was made for another model")]
    DataMismatch,
    /// `J M⁻¹ Jᵀ + μ I` is not positive definite: the constraints are redundant or singular at
    /// this configuration.
    #[error("the constraints are redundant or singular at this configuration (J M⁻¹ Jᵀ + mu I is not positive definite): use mu > 0 for the proximal solution")]
    Singular,
    /// A constraint Jacobian of another width than `nv`, a drift `γ` of another length than its
    /// rows, a non-finite entry, or a negative or non-finite damping: the fault, named.
    #[error("jacobian_dynamics: {0}")]
    BadJacobian(String),
}
