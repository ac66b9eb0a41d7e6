//! Building a [`Model`] joint by joint, in depth-first order, with every input checked.

use super::model::{Frame, FrameId, FrameKind, Joint, JointId, Model};
use super::{JointType, ModelError};
use crate::error::DimensionError;
use crate::mass::SpatialInertia;
use crate::spatial::{Transform, Vec3};

/// The parts of a model under construction ([`Model::from_parts`] compiles its plan).
#[derive(Clone, Debug)]
struct Parts {
    name: String,
    gravity: Vec3,
    joints: Vec<Joint>,
    inertias: Vec<SpatialInertia>,
    frames: Vec<Frame>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    velocity_limit: Vec<f64>,
    effort_limit: Vec<f64>,
    armature: Vec<f64>,
    damping: Vec<f64>,
    friction: Vec<f64>,
    nq: usize,
    nv: usize,
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
    model: Parts,
    inertia_check: InertiaCheck,
    /// Joint names, and frame names by kind, for O(1) duplicate checks.
    names: std::collections::HashSet<(Option<FrameKind>, String)>,
    /// The chain of joints from the root to the last joint added (for the depth-first check).
    stack: Vec<usize>,
}

pub(crate) fn check_placement(name: &str, t: &Transform) -> Result<(), ModelError> {
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

pub(crate) fn check_inertia(
    name: &str,
    g: &SpatialInertia,
    check: InertiaCheck,
) -> Result<(), ModelError> {
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

impl ModelBuilder {
    /// An empty model called `name`, with gravity `[0, 0, -9.81]` m/s².
    #[must_use]
    pub fn new(name: &str) -> Self {
        Self {
            model: Parts {
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
            continuous: false,
        });
        m.inertias.push(inertia);
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

    /// Mark a revolute joint as imported from a URDF `continuous` joint
    /// ([`Joint::continuous`](super::Joint::continuous)): the dynamics do not change, Pinocchio's
    /// layout writes its angle as `(cos θ, sin θ)`.
    ///
    /// # Errors
    /// An unknown joint, or one that is not revolute.
    pub fn set_continuous(&mut self, joint: JointId) -> Result<(), ModelError> {
        self.joint_checked(joint)?;
        let j = &mut self.model.joints[joint.0];
        match j.kind.shape() {
            super::joint::Shape::Revolute(_) => {
                j.continuous = true;
                Ok(())
            }
            super::joint::Shape::Prismatic(_)
            | super::joint::Shape::FreeFlyer
            | super::joint::Shape::General => Err(ModelError::Unsupported {
                index: joint.0,
                reason: "only a revolute joint can be continuous",
            }),
        }
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
        let m = self.model;
        Ok(Model::from_parts(
            m.name,
            m.gravity,
            m.joints,
            m.inertias,
            m.frames,
            [m.lower, m.upper, m.velocity_limit, m.effort_limit],
            m.armature,
            m.damping,
            m.friction,
        ))
    }
}
