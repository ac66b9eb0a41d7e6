//! Batches over states and over parameters: the regressor of many states at once across the
//! cores ([`regressor_batch`], so that `τ` for many parameter vectors is one matrix product
//! `Y π`), and a model with other inertial parameters, checked body by body
//! ([`model_with_checked_parameters`]).

use super::regressor::model_with_parameters;
#[cfg(feature = "parallel")]
use super::regressor::Regressor;
use crate::error::DimensionError;
use crate::mass::{Consistency, SpatialInertia, Verdict};
use crate::multibody::Model;
#[cfg(feature = "parallel")]
use crate::multibody::MultibodyError;
#[cfg(feature = "parallel")]
use rayon::prelude::*;
use thiserror::Error;

/// Tasks per rayon thread (as `multibody::batch`): a few, each with its own workspace.
#[cfg(feature = "parallel")]
const TASKS_PER_THREAD: usize = 2;

/// `Y(q_k, v_k, a_k)` for every state `k` (see [`Regressor::compute`]) into `out`: `N` blocks of
/// `nv × 10 n_bodies`, each row-major (`out[k nv 10n + r 10n + c] = Y_k[r, c]`), so that a numpy
/// array of shape `(N, nv, 10 n)` over it is `Y` state by state. Inputs row-major, one state a
/// row. Runs on the current rayon pool (`ThreadPool::install` chooses the threads); each state's
/// block is that of a single [`Regressor::compute`], bit for bit, for any number of threads.
///
/// ```
/// use rigid::identification::{model_parameters, regressor_batch};
/// use rigid::multibody::{batch, builtin};
/// let model = builtin("double_pendulum").unwrap();
/// let (q, v, a) = ([0.1, 0.2, 0.3, 0.4], [1.0; 4], [0.5; 4]); // two states
/// let mut y = vec![0.0; 2 * 2 * 20];
/// regressor_batch(&model, &q, &v, &a, &mut y)?;
/// let pi = model_parameters(&model);
/// let mut tau = [0.0; 4];
/// batch::rnea_batch(&model, &q, &v, &a, &mut tau)?;
/// for (r, t) in tau.iter().enumerate() {
///     let yp: f64 = (0..20).map(|c| y[r * 20 + c] * pi[c]).sum();
///     assert!((yp - t).abs() < 1e-12);
/// }
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
///
/// # Errors
/// Lengths that are not `N nq` / `N nv` / `N nv 10 n`, or the first failing state's error.
#[cfg(feature = "parallel")]
pub fn regressor_batch(
    model: &Model,
    qs: &[f64],
    vs: &[f64],
    as_: &[f64],
    out: &mut [f64],
) -> Result<(), MultibodyError> {
    let (nq, nv) = (model.nq(), model.nv());
    let cols = 10 * model.njoints();
    let per = nv * cols;
    let n = qs.len().checked_div(nq).unwrap_or(0);
    DimensionError::check("qs", n * nq, qs.len())?;
    DimensionError::check("vs", n * nv, vs.len())?;
    DimensionError::check("as", n * nv, as_.len())?;
    DimensionError::check("out", n * per, out.len())?;
    if n == 0 || per == 0 {
        return Ok(());
    }
    let tasks = (rayon::current_num_threads() * TASKS_PER_THREAD).max(1);
    let per_task = n.div_ceil(tasks);
    out.par_chunks_mut(per_task * per)
        .enumerate()
        .try_for_each(|(c, block)| {
            let mut reg = Regressor::new(model);
            for (j, y_k) in block.chunks_exact_mut(per).enumerate() {
                let k = c * per_task + j;
                let y = reg.compute(
                    model,
                    &qs[k * nq..(k + 1) * nq],
                    &vs[k * nv..(k + 1) * nv],
                    &as_[k * nv..(k + 1) * nv],
                )?;
                for (r, row) in y_k.chunks_exact_mut(cols).enumerate() {
                    for (col, x) in row.iter_mut().enumerate() {
                        *x = y[(r, col)];
                    }
                }
            }
            Ok(())
        })
}

/// Why [`model_with_checked_parameters`] refuses a parameter vector.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ParameterError {
    /// `π` of the wrong length.
    #[error(transparent)]
    Dimension(#[from] DimensionError),
    /// A body whose ten parameters are not those of a physical body.
    #[error("body {body} (moved by joint '{joint}'): {why} (parameters {first}..{end} of pi)", end = first + 10)]
    NotPhysical {
        /// Index of the body (its joint's index).
        body: usize,
        /// The name of the joint that moves it.
        joint: String,
        /// The first of its ten parameters in `π`.
        first: usize,
        /// What is wrong.
        why: String,
    },
}

/// What a failing [`Verdict`] means, for a message.
fn verdict_text(c: &Consistency) -> Option<String> {
    let l = c.principal_moments;
    match c.verdict() {
        Verdict::NonFinite => Some("a parameter is not finite".into()),
        Verdict::BadMass => Some(format!(
            "mass {} (negative, or zero with a non-zero first moment or inertia)",
            c.mass
        )),
        Verdict::NotPositiveSemiDefinite => Some(format!(
            "the rotational inertia about the centre of mass is not positive semi-definite \
             (principal moments {:e}, {:e}, {:e})",
            l[0], l[1], l[2]
        )),
        Verdict::TriangleInequality => Some(format!(
            "the principal moments {:e}, {:e}, {:e} break the triangle inequality \
             (λ1 + λ2 ≥ λ3): no distribution of mass has them",
            l[0], l[1], l[2]
        )),
        Verdict::Degenerate | Verdict::RoundOff | Verdict::Consistent | Verdict::Massless => None,
    }
}

/// A copy of `model` whose body inertias are `pi` (ten per body, [`model_parameters`]'s order
/// and frames), each checked to be that of a physical body ([`Consistency`]: finite, a
/// non-negative mass, a positive semi-definite inertia about the centre of mass that keeps the
/// triangle inequality; round-off, degenerate and massless bodies are accepted). The unchecked
/// form is [`model_with_parameters`].
///
/// [`model_parameters`]: super::model_parameters
///
/// ```
/// use rigid::identification::{model_parameters, model_with_checked_parameters, ParameterError};
/// let model = rigid::multibody::builtin("double_pendulum").unwrap();
/// let mut pi = model_parameters(&model);
/// assert!(model_with_checked_parameters(&model, pi.as_slice()).is_ok());
/// pi[10] = -1.0; // a negative mass for the second body
/// let e = model_with_checked_parameters(&model, pi.as_slice()).unwrap_err();
/// assert!(matches!(e, ParameterError::NotPhysical { body: 1, .. }));
/// ```
///
/// # Errors
/// `pi` of the wrong length; the first body that is not physical, named.
pub fn model_with_checked_parameters(model: &Model, pi: &[f64]) -> Result<Model, ParameterError> {
    DimensionError::check("pi", 10 * model.njoints(), pi.len())?;
    for (body, p) in pi.chunks_exact(10).enumerate() {
        let g = SpatialInertia::from_parameters(p.try_into().expect("chunks of 10"));
        let c = Consistency::of(&g);
        let why = if p.iter().all(|x| x.is_finite()) {
            verdict_text(&c)
        } else {
            Some("a parameter is not finite".into())
        };
        if let Some(why) = why {
            return Err(ParameterError::NotPhysical {
                body,
                joint: model.joints()[body].name.clone(),
                first: 10 * body,
                why,
            });
        }
    }
    Ok(model_with_parameters(model, pi)?)
}
