//! Inverse kinematics: joint positions `q` that put a frame at a target pose (or its origin at a
//! target point), by Newton-Raphson on the SE(3) log error (Lynch & Park, *Modern Robotics* §6.2,
//! `IKinBody` / `IKinSpace`) or its Levenberg-Marquardt (damped least-squares) form, with the
//! joints' position limits respected and restarts from random configurations.
//!
//! One iteration, at the current `q` with the frame at `T_sb(q)` and the target `T_sd`:
//!
//! - error twist, [`ErrorTwist::Body`]: `[V_b] = log(T_sb⁻¹ T_sd)` and the body Jacobian `J_b`;
//!   [`ErrorTwist::Space`]: `V_s = [Ad_{T_sb}] V_b` and the space Jacobian `J_s`;
//!   [`Target::Position`]: `e = p_d - p` and the linear rows of the world-aligned Jacobian;
//! - converged when `‖ω‖ ≤ ε_ω` and `‖v‖ ≤ ε_v` (the twist's angular and linear parts);
//! - step `Δ = J† e` (`damping = 0`: the textbook's Newton step, `J†` the Moore-Penrose
//!   pseudo-inverse by SVD, singular values below `1e-15 σ_max` dropped, as numpy's `pinv`), or
//!   `Δ = Jᵀ (J Jᵀ + λ² I)⁻¹ e` (`damping = λ₀ > 0`): a step that does not reduce `‖e‖` is
//!   refused and `λ` multiplied by 10, an accepted one divides it by 10 (down to `1e-12`);
//! - `q ← q ⊕ Δ` ([`integrate`]), then each coordinate with finite position limits clamped into
//!   them (a projection onto the box; quaternions are not limited). A joint already at a limit
//!   that the step would push further out is held still: its column of `J` is zeroed and the
//!   step solved again (an active set), so that the other joints make up for it.
//!
//! An attempt that has not converged after `max_iterations` steps is followed by up to `restarts`
//! more from random configurations within the limits ([`random_configuration`], seeded by
//! `seed`); the result is the first converged attempt, or [`IkError::NotConverged`] with the
//! attempt of smallest final error.
//!
//! ```
//! use rigid::kinematics::{inverse, Options, Site, Target};
//! use rigid::multibody::{builtin, forward_kinematics_q, Data};
//! use rigid::spatial::Vec3;
//! let model = builtin("puma560").unwrap();
//! let mut data = Data::new(&model);
//! let flange = Site::by_name(&model, "link6")?;
//! let target = Target::Position(Vec3::new(0.4, 0.2, 0.3));
//! let sol = inverse(&model, &mut data, flange, &target, &[0.1; 6], &Options::default())?;
//! forward_kinematics_q(&model, &mut data, &sol.q)?;
//! let p = flange.pose(&model, &data).translation;
//! assert!((p - Vec3::new(0.4, 0.2, 0.3)).norm() < 1e-9);
//! # Ok::<(), rigid::kinematics::IkError>(())
//! ```

use crate::multibody::{
    forward_kinematics_q, frame_jacobian, integrate, joint_jacobian, random_configuration, Data,
    FrameId, JointId, JointType, Model, MultibodyError, ReferenceFrame, Rng,
};
use crate::spatial::{Transform, Twist, Vec3};
use nalgebra::{DMatrix, DVector};
use thiserror::Error;

/// The frame whose pose is solved for: a joint's frame (as moved by the joint) or a named frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Site {
    /// The frame of a joint.
    Joint(JointId),
    /// A named frame (a link, a fixed joint, an operational frame).
    Frame(FrameId),
}

impl Site {
    /// The joint called `name`, or else the frame called `name`.
    ///
    /// # Errors
    /// [`IkError::UnknownSite`] when neither exists, or the frame lookup's error when several
    /// frames of different kinds share the name.
    pub fn by_name(model: &Model, name: &str) -> Result<Self, IkError> {
        if let Some(j) = model.joint_id(name) {
            return Ok(Self::Joint(j));
        }
        model.frame_id(name).map(Self::Frame).map_err(|e| match e {
            crate::multibody::FrameLookupError::NotFound { .. } => IkError::UnknownSite {
                name: name.to_string(),
            },
            e => IkError::AmbiguousSite {
                message: e.to_string(),
            },
        })
    }

    /// The world pose of the site from `data.placements` (run a forward kinematics first).
    #[must_use]
    pub fn pose(&self, model: &Model, data: &Data) -> Transform {
        match *self {
            Self::Joint(j) => data.placements[j.0],
            Self::Frame(f) => {
                let frame = &model.frames()[f.0];
                match frame.parent {
                    Some(p) => data.placements[p.0] * frame.placement,
                    None => frame.placement,
                }
            }
        }
    }

    fn check(&self, model: &Model) -> Result<(), IkError> {
        let (what, index, n) = match *self {
            Self::Joint(j) => ("joint", j.0, model.njoints()),
            Self::Frame(f) => ("frame", f.0, model.frames().len()),
        };
        if index < n {
            Ok(())
        } else {
            Err(IkError::Input(MultibodyError::OutOfRange { what, index }))
        }
    }

    fn jacobian<'a>(
        &self,
        model: &Model,
        data: &'a mut Data,
        q: &[f64],
        rf: ReferenceFrame,
    ) -> Result<&'a DMatrix<f64>, MultibodyError> {
        match *self {
            Self::Joint(j) => joint_jacobian(model, data, q, j, rf),
            Self::Frame(f) => frame_jacobian(model, data, q, f, rf),
        }
    }
}

/// Where the site should be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// The site's origin at this point of the world (m): 3 equations, the orientation free.
    Position(Vec3),
    /// The site's pose in the world, `T_sd`: 6 equations.
    Pose(Transform),
}

/// The twist whose norm is driven to zero (Lynch & Park §6.2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ErrorTwist {
    /// `[V_b] = log(T_sb⁻¹ T_sd)` with the body Jacobian (`IKinBody`).
    #[default]
    Body,
    /// `V_s = [Ad_{T_sb}] V_b` with the space Jacobian (`IKinSpace`); its linear part, and so
    /// the linear tolerance, depends on where the world origin is.
    Space,
}

/// The solver's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Body or space error twist (ignored for [`Target::Position`]).
    pub twist: ErrorTwist,
    /// `ε_ω`: converged when the error's angular part has at most this norm (rad).
    pub angular_tolerance: f64,
    /// `ε_v`: converged when the error's linear part has at most this norm (m).
    pub linear_tolerance: f64,
    /// Steps per attempt.
    pub max_iterations: usize,
    /// `λ₀` of the damped least-squares step (1/m scale, as the error); `0` is the textbook's
    /// undamped Newton step with the pseudo-inverse.
    pub damping: f64,
    /// Attempts from random configurations after the first (from `q0`) fails.
    pub restarts: usize,
    /// Seed of the random restarts.
    pub seed: u64,
    /// Keep every coordinate with finite position limits inside them (clamped after each step,
    /// and `q0` itself).
    pub respect_limits: bool,
}

impl Default for Options {
    /// Body twist, tolerances 1e-9 rad and 1e-9 m, 100 steps, `λ₀ = 1e-3`, 20 restarts, seed
    /// 0, limits respected.
    fn default() -> Self {
        Self {
            twist: ErrorTwist::Body,
            angular_tolerance: 1e-9,
            linear_tolerance: 1e-9,
            max_iterations: 100,
            damping: 1e-3,
            restarts: 20,
            seed: 0,
            respect_limits: true,
        }
    }
}

/// A solution (or, in [`IkError::NotConverged`], the best attempt).
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The joint positions (rigid's layout, `nq`).
    pub q: Vec<f64>,
    /// Both tolerances met.
    pub converged: bool,
    /// Norm of the error's angular part at `q` (rad; 0 for a position target).
    pub angular_error: f64,
    /// Norm of the error's linear part at `q` (m): `‖v_b‖`, `‖v_s‖`, or `‖p_d - p‖`.
    pub linear_error: f64,
    /// Distance from the site's origin to the target's (m).
    pub position_error: f64,
    /// Steps of the attempt that gave `q`.
    pub iterations: usize,
    /// Steps of every attempt made.
    pub total_iterations: usize,
    /// Attempts made (1 + the restarts used).
    pub attempts: usize,
}

/// Why [`inverse()`] gives no solution.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum IkError {
    /// A wrong `q0` (length, non-finite entry, non-unit quaternion) or site index.
    #[error(transparent)]
    Input(#[from] MultibodyError),
    /// No joint or frame of that name.
    #[error("no joint or frame named \"{name}\"")]
    UnknownSite {
        /// The name.
        name: String,
    },
    /// Frames of different kinds share the name.
    #[error("{message}")]
    AmbiguousSite {
        /// The lookup's message.
        message: String,
    },
    /// A target that is not finite, or whose rotation is not a rotation.
    #[error("target: {reason}")]
    BadTarget {
        /// What is wrong.
        reason: String,
    },
    /// A setting out of its range.
    #[error("option {name} = {value}: {reason}")]
    BadOption {
        /// The setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The range.
        reason: &'static str,
    },
    /// No attempt met the tolerances; the best one (smallest final error) is kept.
    #[error("no solution within the tolerances after {} attempts ({} steps): best angular error {:.3e} rad, linear error {:.3e} m", best.attempts, best.total_iterations, best.angular_error, best.linear_error)]
    NotConverged {
        /// The attempt with the smallest final error.
        best: Box<Solution>,
    },
}

fn check_options(o: &Options) -> Result<(), IkError> {
    let bad = |name, value: f64, reason| {
        Err(IkError::BadOption {
            name,
            value,
            reason,
        })
    };
    for (name, value) in [
        ("angular_tolerance", o.angular_tolerance),
        ("linear_tolerance", o.linear_tolerance),
        ("damping", o.damping),
    ] {
        if !(value.is_finite() && value >= 0.0) {
            return bad(name, value, "must be finite and non-negative");
        }
    }
    if o.max_iterations == 0 {
        return bad("max_iterations", 0.0, "must be at least 1");
    }
    Ok(())
}

fn check_target(t: &Target) -> Result<(), IkError> {
    let finite = |x: &[f64]| x.iter().all(|v| v.is_finite());
    match t {
        Target::Position(p) if finite(p.as_slice()) => Ok(()),
        Target::Pose(T) if finite(T.translation.as_slice()) && finite(T.rotation.as_slice()) => {
            crate::spatial::so3::check(&T.rotation, 1e-6).map_err(|e| IkError::BadTarget {
                reason: format!("its rotation: {e}"),
            })
        }
        _ => Err(IkError::BadTarget {
            reason: "non-finite entry".into(),
        }),
    }
}

/// A coordinate of `q` with finite position limits: its index, and the index of the velocity
/// coordinate that moves it alone (`q_i ⊕ δ = q_i + δ_k`: revolute, prismatic, helical and
/// universal joints), if any.
#[derive(Clone, Copy)]
struct Limited {
    q: usize,
    v: Option<usize>,
}

/// The coordinates of `q` that limits apply to: those with a finite bound, less the
/// quaternions'.
fn limited(model: &Model) -> Vec<Limited> {
    let (lo, up) = (model.lower_limits(), model.upper_limits());
    let mut out = Vec::new();
    for j in model.joints() {
        let (skip, additive) = match j.kind {
            JointType::FreeFlyer => (3..7, false),
            JointType::Spherical => (0..4, false),
            JointType::Planar => (0..0, false),
            JointType::Revolute { .. }
            | JointType::Prismatic { .. }
            | JointType::Helical { .. }
            | JointType::Universal { .. } => (0..0, true),
        };
        for k in 0..j.nq {
            let i = j.idx_q + k;
            if !skip.contains(&k) && (lo[i].is_finite() || up[i].is_finite()) {
                out.push(Limited {
                    q: i,
                    v: additive.then_some(j.idx_v + k),
                });
            }
        }
    }
    out
}

fn clamp(model: &Model, limited: &[Limited], q: &mut [f64]) {
    let (lo, up) = (model.lower_limits(), model.upper_limits());
    for l in limited {
        q[l.q] = q[l.q].clamp(lo[l.q], up[l.q]);
    }
}

/// The step, with the joints at a limit that it would push further out held still: their
/// columns of `J` are zeroed and the step solved again, until no step pushes a held joint out
/// (at most once per limited coordinate). Without limits, the plain step.
fn step(
    model: &Model,
    mut J: DMatrix<f64>,
    e: &DVector<f64>,
    lambda: Option<f64>,
    q: &[f64],
    limited: &[Limited],
) -> DVector<f64> {
    let solve = |J: &DMatrix<f64>| match lambda {
        None => pinv_solve(J.clone(), e),
        Some(l) => damped_solve(J, e, l),
    };
    let mut delta = solve(&J);
    let (lo, up) = (model.lower_limits(), model.upper_limits());
    for _ in 0..limited.len() {
        let mut held = false;
        for l in limited {
            let Some(k) = l.v else { continue };
            let out_low = q[l.q] <= lo[l.q] && delta[k] < 0.0;
            let out_high = q[l.q] >= up[l.q] && delta[k] > 0.0;
            if out_low || out_high {
                J.column_mut(k).fill(0.0);
                held = true;
            }
        }
        if !held {
            break;
        }
        delta = solve(&J);
    }
    delta
}

/// The error `e` at `q` and the (angular, linear, position) norms; fills `data.placements`.
fn error(
    model: &Model,
    data: &mut Data,
    site: Site,
    target: &Target,
    twist: ErrorTwist,
    q: &[f64],
) -> Result<(DVector<f64>, [f64; 3]), MultibodyError> {
    forward_kinematics_q(model, data, q)?;
    let T = site.pose(model, data);
    Ok(match target {
        Target::Position(p) => {
            let e = p - T.translation;
            let n = e.norm();
            (DVector::from_column_slice(e.as_slice()), [0.0, n, n])
        }
        Target::Pose(Td) => {
            let Vb = (T.inverse() * *Td).log();
            let V: Twist = match twist {
                ErrorTwist::Body => Vb,
                ErrorTwist::Space => T.act_twist(&Vb),
            };
            let pos = (Td.translation - T.translation).norm();
            (
                DVector::from_column_slice(V.to_vector().as_slice()),
                [V.w.norm(), V.v.norm(), pos],
            )
        }
    })
}

/// The error's Jacobian with respect to `q ⊕ δ` (up to sign: `e` decreases along `J Δ`).
fn error_jacobian(
    model: &Model,
    data: &mut Data,
    site: Site,
    target: &Target,
    twist: ErrorTwist,
    q: &[f64],
) -> Result<DMatrix<f64>, MultibodyError> {
    Ok(match (target, twist) {
        (Target::Position(_), _) => site
            .jacobian(model, data, q, ReferenceFrame::WorldAligned)?
            .rows(3, 3)
            .into_owned(),
        (Target::Pose(_), ErrorTwist::Body) => {
            site.jacobian(model, data, q, ReferenceFrame::Body)?.clone()
        }
        (Target::Pose(_), ErrorTwist::Space) => site
            .jacobian(model, data, q, ReferenceFrame::Spatial)?
            .clone(),
    })
}

/// `J† e` by SVD, singular values below `1e-15 σ_max` dropped (numpy's `pinv`).
fn pinv_solve(J: DMatrix<f64>, e: &DVector<f64>) -> DVector<f64> {
    let svd = J.svd(true, true);
    let smax = svd.singular_values.max();
    let eps = smax * 1e-15;
    match svd.pseudo_inverse(eps) {
        Ok(p) => p * e,
        Err(_) => DVector::zeros(e.len()),
    }
}

/// `Jᵀ (J Jᵀ + λ² I)⁻¹ e`.
fn damped_solve(J: &DMatrix<f64>, e: &DVector<f64>, lambda: f64) -> DVector<f64> {
    let m = J.nrows();
    let A = J * J.transpose() + DMatrix::identity(m, m) * (lambda * lambda);
    match A.cholesky() {
        Some(c) => J.transpose() * c.solve(e),
        None => DVector::zeros(J.ncols()),
    }
}

/// Smallest `λ` of the damped steps.
const LAMBDA_MIN: f64 = 1e-12;

/// One attempt from `q` (already within the limits when they are respected).
fn attempt(
    model: &Model,
    data: &mut Data,
    site: Site,
    target: &Target,
    o: &Options,
    limited: &[Limited],
    mut q: Vec<f64>,
) -> Result<(Solution, f64), MultibodyError> {
    let done = |n: &[f64; 3]| n[0] <= o.angular_tolerance && n[1] <= o.linear_tolerance;
    let (mut e, mut norms) = error(model, data, site, target, o.twist, &q)?;
    let mut lambda = o.damping;
    let mut steps = 0;
    let mut next = vec![0.0; q.len()];
    while !done(&norms) && steps < o.max_iterations {
        steps += 1;
        let J = error_jacobian(model, data, site, target, o.twist, &q)?;
        let lam = (o.damping > 0.0).then_some(lambda);
        let delta = if o.respect_limits {
            step(model, J, &e, lam, &q, limited)
        } else {
            step(model, J, &e, lam, &q, &[])
        };
        integrate(model, &q, delta.as_slice(), 1.0, &mut next)?;
        if o.respect_limits {
            clamp(model, limited, &mut next);
        }
        let (e2, n2) = error(model, data, site, target, o.twist, &next)?;
        if o.damping == 0.0 || e2.norm() < e.norm() {
            std::mem::swap(&mut q, &mut next);
            (e, norms) = (e2, n2);
            lambda = (lambda / 10.0).max(LAMBDA_MIN);
        } else {
            lambda *= 10.0;
        }
    }
    let residual = e.norm();
    Ok((
        Solution {
            converged: done(&norms),
            q,
            angular_error: norms[0],
            linear_error: norms[1],
            position_error: norms[2],
            iterations: steps,
            total_iterations: steps,
            attempts: 1,
        },
        residual,
    ))
}

/// Joint positions that put `site` at `target`, starting from `q0` (see the [module
/// documentation](self) for the iteration). `data` is the workspace of the forward kinematics
/// and Jacobians (its placements are those of the returned `q` at the end of a converged
/// attempt).
///
/// # Errors
/// A wrong `q0` or site ([`IkError::Input`]), a non-finite target or one whose rotation is not a
/// rotation ([`IkError::BadTarget`]), a setting out of range ([`IkError::BadOption`]), or no
/// attempt within the tolerances ([`IkError::NotConverged`], with the best attempt).
pub fn inverse(
    model: &Model,
    data: &mut Data,
    site: Site,
    target: &Target,
    q0: &[f64],
    options: &Options,
) -> Result<Solution, IkError> {
    check_options(options)?;
    check_target(target)?;
    site.check(model)?;
    let limited = limited(model);
    let mut q = q0.to_vec();
    forward_kinematics_q(model, data, &q)?; // q0's length, finiteness and quaternions
    if options.respect_limits {
        clamp(model, &limited, &mut q);
    }
    let mut rng = Rng::new(options.seed);
    let mut best: Option<(Solution, f64)> = None;
    let mut total = 0;
    for k in 0..=options.restarts {
        if k > 0 {
            q = random_configuration(model, &mut rng);
        }
        let (mut sol, residual) = attempt(model, data, site, target, options, &limited, q.clone())?;
        total += sol.iterations;
        sol.total_iterations = total;
        sol.attempts = k + 1;
        if sol.converged {
            return Ok(sol);
        }
        if best.as_ref().is_none_or(|(_, r)| residual < *r) {
            best = Some((sol, residual));
        }
    }
    let (mut best, _) = best.expect("at least one attempt");
    best.total_iterations = total;
    best.attempts = options.restarts + 1;
    Err(IkError::NotConverged {
        best: Box::new(best),
    })
}
