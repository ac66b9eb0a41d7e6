//! Identification of a robot's inertial parameters from measured motion.
//!
//! The joint torques are linear in the ten inertial parameters of every body,
//! `τ = Y(q, v, a) π` (Atkeson, An & Hollerbach 1986): with the regressor `Y` of many samples
//! stacked into `W`, identification is a least-squares problem. Only some combinations of the
//! parameters act on the joints, the **base parameters** `β = π_B + K π_D` (Gautier 1990); plain
//! least squares returns them, and may return bodies that no mass distribution has (a negative
//! mass, an inertia that violates the triangle inequality), on which ABA fails. The **physically
//! consistent** estimate constrains every body's pseudo-inertia to be positive definite, a
//! semidefinite program (Wensing, Kim & Slotine 2017), regularised towards the model's values.
//!
//! | notes | code | source |
//! | --- | --- | --- |
//! | `π_i = (m, m c, Ī_O)` | [`SpatialInertia::to_parameters`](crate::mass::SpatialInertia::to_parameters) | Pinocchio's `toDynamicParameters` order |
//! | `F = Φ(V, A) π_i` | [`body_regressor`] | Atkeson et al. 1986 |
//! | `τ = Y(q, v, a) π` | [`Regressor`] | Pinocchio's `computeJointTorqueRegressor` |
//! | `β = π_B + K π_D`, `W π = W_B β` | [`BaseParameters`] | Gautier 1990 (numerical base parameters) |
//! | `min ‖W_B β − τ‖`, weighted | [`Identification::least_squares`] | Gautier & Khalil 1990 |
//! | `min ‖W π − τ‖² + λ‖D(π − π⁰)‖²`, `J(π_i) ≻ 0` | [`Identification::physically_consistent`] | Wensing, Kim & Slotine 2017 |
//! | `q(t) = q₀ + Σ a_l/(lω) sin(lωt) − b_l/(lω) cos(lωt)` | [`excitation`] | Swevers, Ganseman et al. 1997 |
//! | `q̇`, `q̈` from samples | [`SavitzkyGolay`] | Savitzky & Golay 1964 |
//!
//! **Composite bodies.** A [`Model`](crate::multibody::Model) merges the links welded by fixed
//! joints into the body of their moving parent (as Pinocchio does): a body's parameters are
//! those of the composite, about its joint frame, and only the composite can be identified.
//!
//! ```
//! use rigid::identification::{Identification, JointTerms, Samples, Weighting};
//! use rigid::multibody::{builtin, rnea, Data, Rng, random_configuration};
//! let model = builtin("double_pendulum").unwrap();
//! // samples of the model itself: least squares gives back its base parameters
//! let (mut rng, mut data, mut s) = (Rng::new(5), Data::new(&model), Samples::default());
//! for k in 0..50 {
//!     let q = random_configuration(&model, &mut rng);
//!     let (v, a) = ([rng.normal(), rng.normal()], [rng.normal(), rng.normal()]);
//!     s.t.push(k as f64);
//!     s.tau.extend(rnea(&model, &mut data, &q, &v, &a)?.iter());
//!     s.q.extend(q); s.v.extend(v); s.a.extend(a);
//! }
//! let id = Identification::new(&model, &s, JointTerms::default())?;
//! let est = id.least_squares(Weighting::None)?;
//! let truth = id.base.project(&id.prior);
//! assert!((est.base - truth).norm() < 1e-10);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod base;
mod batch;
mod estimate;
pub mod excitation;
mod physical;
mod regressor;
mod samples;

pub use base::{BaseParameters, JointTerms, ParameterLayout};
#[cfg(feature = "parallel")]
pub use batch::regressor_batch;
pub use batch::{model_with_checked_parameters, ParameterError};
pub use estimate::{Estimate, Identification, Weighting, RANK_TOLERANCE};
pub use physical::PhysicalOptions;
pub use regressor::{body_regressor, model_parameters, model_with_parameters, Regressor};
pub use samples::{CsvLayout, Samples, SavitzkyGolay};

use crate::multibody::MultibodyError;
use thiserror::Error;

/// What can go wrong in an identification. Each message says what to do.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum IdentificationError {
    /// A CSV file of samples that cannot be read.
    #[error("line {line}{}: {message}", column.as_ref().map_or(String::new(), |(c, n)| if n.is_empty() { format!(", column {c}") } else { format!(", column {c} ({n})") }))]
    Csv {
        /// Line of the file (1-based).
        line: usize,
        /// Column (1-based) and its name, when one is at fault.
        column: Option<(usize, String)>,
        /// What is wrong and what to do.
        message: String,
    },
    /// Fewer equations than base parameters.
    #[error("{samples} samples give {equations} equations for {base} base parameters: record at least {needed} samples (in practice many more, over a motion that moves every joint)")]
    TooFewSamples {
        /// Samples given.
        samples: usize,
        /// Equations (`samples × nv`).
        equations: usize,
        /// Base parameters.
        base: usize,
        /// Samples needed at the least.
        needed: usize,
    },
    /// The motion does not excite every base parameter.
    #[error("the motion excites only {rank} of the {base} base parameters (rank-deficient regressor, condition number over 1e10); not excited: {}{}; record a richer motion (`rigid excite` makes one)", unexcited.join(", "), if still.is_empty() { String::new() } else { format!("; joint(s) that never move: {}", still.join(", ")) })]
    RankDeficient {
        /// Numerical rank of the base regressor.
        rank: usize,
        /// Number of base parameters.
        base: usize,
        /// The base parameters that the motion does not tell apart (those most involved in
        /// the smallest singular directions).
        unexcited: Vec<String>,
        /// Joints whose position never changes.
        still: Vec<String>,
    },
    /// An algorithm refused a sample.
    #[error(transparent)]
    Multibody(#[from] MultibodyError),
    /// The conic solver did not solve the physically consistent problem.
    #[error("{0}")]
    Solver(String),
    /// A capability this build of rigid leaves out (the message says how to build it in).
    #[error("{0}")]
    NotBuilt(String),
    /// A bad option or argument (the message says which).
    #[error("{0}")]
    Invalid(String),
}
