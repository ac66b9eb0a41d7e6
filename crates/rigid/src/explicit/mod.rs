//! The explicit dynamic model of a robot, derived symbolically: the kinetic-energy matrix
//! `a_ij = M_ij(q)`, the Coriolis terms `b_ijk`, the centrifugal terms `c_ij` and the gravity
//! terms `g_i(q)` of
//!
//! `τ_i = Σ_j a_ij q̈_j + Σ_{j<k} b_ijk q̇_j q̇_k + Σ_j c_ij q̇_j² + g_i`,
//!
//! as expressions in the sines and cosines of the joint angles, abbreviated into numbered
//! constants and pruned by significance with a proven error bound, as Armstrong, Khatib & Burdick
//! (1986, "The explicit dynamic model and inertial parameters of the PUMA 560 arm") wrote them by
//! hand (the tables at the start of lecture note 000), and as code (Rust, C, Python) that beats
//! the recursive algorithms on such arms.
//!
//! ```
//! use rigid::explicit::{EntryKind, ExplicitModel, TableOptions};
//! use rigid::multibody::double_pendulum;
//! let model = double_pendulum();
//! let explicit = ExplicitModel::derive(&model)?;
//! let tables = explicit.tables(&TableOptions::default());
//! // a11 = I_1 + 2·I_2·C2 = 5/3 + cos θ2 (I_1 = YY1 + M2·pz2² + YY2, I_2 = MZ2·pz2)
//! let a11 = tables.entry(EntryKind::Mass(0, 0)).unwrap();
//! assert_eq!(a11.terms.len(), 2);
//! assert!((tables.eval(a11, &[0.3, 0.0]) - 8.0 / 3.0).abs() < 1e-12);
//! println!("{}", tables.to_text());
//! # Ok::<(), rigid::explicit::ExplicitError>(())
//! ```
//!
//! ## Pipeline
//!
//! | step | what | where |
//! | --- | --- | --- |
//! | symbols | the model's nonzero parameters: Khalil's standard inertial parameters (`M3`, `MX3`, `XX3`, …), joint offsets (`px3`), armature, gravity; axes and placement rotations stay numbers | [`Parameters`] |
//! | derivation | `M` by composite inertias, `b`, `c` from its Christoffel symbols, `g = ∂U/∂q` (Lagrange); the symbolic RNEA ([`symbolic_rnea`]) derives the same and the tests compare term by term | [`ExplicitModel`] |
//! | tables | the expressions in the tables' variables (`C2`, `S23`, `SS5`, `SC4`), coefficients abbreviated into constants `I_k`, `g_k` in order of first use, terms pruned with a bound | [`Tables`] |
//! | output | text and LaTeX tables like the paper's; Rust, C and Python functions `mass_matrix(q)`, `coriolis_centrifugal(q, v)`, `gravity(q)` | [`Tables::to_text`], [`Tables::to_code`] |
//!
//! ## Design, and why
//!
//! **One canonical form, flat.** An [`Expr`] is a sorted list of plain terms
//! `coef · h(q) · π₁π₂π₃`: a harmonic `h = cos(k·q)` or `sin(k·q)` (integer frequencies per
//! revolute joint, powers per prismatic joint) times a monomial in at most three parameters
//! (`mass · length²` and `g · mass · length` are the highest degrees the dynamics reach). The
//! harmonics form a basis of the trigonometric polynomials, so equal functions have equal term
//! lists: `s² + c² = 1` is not a rewriting rule but a consequence (`cos²q = ½ + ½ cos 2q`,
//! `sin²q = ½ - ½ cos 2q`), products go to sums (`cos x cos y = ½ cos(x-y) + ½ cos(x+y)`), a sum
//! of angles of parallel joints (`sin(q2 + q3)`) is one harmonic, and `∂/∂q_j` maps a term to one
//! term. The alternative, monomials in `sin q_j`, `cos q_j` with `s² → 1 - c²` rewriting, needs a
//! reduction order and is not canonical once `S23` is admitted. With the placement rotations of
//! most robots exact (`0, ±1` after snapping the round-off of `cos(π/2)`), the arithmetic is in
//! dyadic rationals and cancellations are exact: the Lagrange and RNEA derivations of the PUMA
//! 560 agree to the last bit.
//!
//! **Symbolic coefficients.** The coefficients are polynomials in the model's parameters, not
//! numbers, so that every abbreviated constant has a definition (`I_3 = MY3·px3 + MZ4·px3 + …`),
//! as the paper's `I_1 … I_23` do, and the tables say which inertial parameters matter. A
//! parameter that is zero in the model is not a symbol, so the expressions are specific to the
//! model's zero pattern (the paper's were too). Carrying the monomial in the flat term costs three
//! bytes and keeps products allocation-free; numeric coefficients with parameter provenance would
//! have lost the definitions.
//!
//! **The tables' form.** Harmonics are compact for parallel joints (`S23`) and wasteful for
//! the others (`S4·C5` is two harmonics). The tables therefore write each entry in products of
//! per-variable factors where a variable is the cumulative angle of a chain of consecutive
//! parallel joints (`θ2`, `θ2 + θ3`) or a single joint, each factor `S^n` or `C·S^n`
//! (`C² = 1 - S²`): again a basis, chosen per entry from the joints it depends on, so `a22`
//! of the PUMA reads `I + I'·S3` and `g2` reads `c1 C2 + c2 S23 + c3 S2` as in 1986. For the Panda's
//! mass matrix this is 3 269 terms against 20 814 harmonics.
//!
//! **Pruning with a proof.** A term's bound is `|coefficient| · sup |monomial|` over the joint
//! ranges (the limits, shifted by angle offsets, or the whole circle), exact per variable
//! (`sup |C^c S^s|` over an interval is attained at an end or a stationary point) and a product
//! over variables; an entry's error is at most the sum of its dropped terms' bounds. See
//! [`Tables`].
//!
//! **Code.** Straight-line code with every sine, cosine and monomial computed once (a trie of
//! prefix products) and constants folded by the compiler; above 2 000 terms per function, tables
//! and loops instead, because compilers take super-linear time on huge functions (gcc -O1: more
//! than 3 minutes on the Panda's 26 000 Coriolis terms as straight-line code, under a second as
//! tables).
//!
//! **Crates compared.** `symbolica` (a general computer-algebra system; not free for commercial
//! use), `egg` (e-graph rewriting: finds small forms but has no canonical trigonometric basis and
//! its saturation cost is unbounded), `cas-poly`, `ocas-poly`, `rssn` (generic sparse multivariate
//! polynomials over coefficient rings; no trigonometric basis, and nested coefficient rings
//! allocate per coefficient). None fits the two-kinds-of-variables structure better than ~400
//! lines of flat terms, so no dependency is added.
//!
//! ## Limits
//!
//! Fixed-base trees of revolute, continuous and prismatic joints, at most [`MAX_JOINTS`] = 12 (the
//! number of trigonometric products grows like `5^n`), every expression below a million terms
//! (checked as the composite inertias grow, with the next joint's growth predicted);
//! a free-flyer, spherical or planar joint, or more joints, is an [`ExplicitError`] that says why.
//! Locked joints ([`lock_joints`]) turn a model with extra joints (the Panda's fingers) into one
//! that fits. Measured (release, this 2-core machine): the PUMA 560 derives in 0.02 s, the UR5 in
//! 0.01 s, the 7-joint Panda in 0.25 s plus 0.9 s for its tables.

mod bound;
mod chain;
mod codegen;
mod expr;
mod lagrange;
mod langs;
mod lock;
mod paper;
mod params;
mod rnea;
mod sym;
mod tables;
mod text;

pub use codegen::Lang;
pub use expr::{Expr, Freq, Mono, Space, Term, MAX_DEGREE, MAX_JOINTS};
pub use lock::lock_joints;
pub use paper::{Monomial, ParamPoly, Power, Var};
pub use params::{ParamKind, Parameter, Parameters};
pub use rnea::symbolic_rnea;
pub use tables::{Constant, Entry, EntryKind, TableOptions, TableTerm, Tables};

use crate::multibody::Model;
use thiserror::Error;

/// Why an explicit model cannot be derived or printed.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ExplicitError {
    /// A joint type whose motion is not a polynomial in one angle's sine and cosine (or one
    /// displacement): any joint but a revolute or prismatic one.
    #[error("joint '{joint}' is of type {kind}: explicit models are derived for fixed-base trees of revolute and prismatic joints only (a quaternion or several coordinates in one joint have no finite trigonometric form); use the recursive algorithms for this model")]
    UnsupportedJoint {
        /// The joint.
        joint: String,
        /// Its type ([`JointType::name`](crate::multibody::JointType::name)).
        kind: &'static str,
    },
    /// More joints than the explicit form can hold.
    #[error("{n} joints: explicit models are derived for at most 12 joints (the number of trigonometric products grows like 5^n with the chain's length; lock joints, or use the recursive algorithms)")]
    TooManyJoints {
        /// The number of joints.
        n: usize,
    },
    /// A model without moving joints.
    #[error("the model has no moving joint")]
    NoJoints,
    /// A joint name that the model does not have.
    #[error("no joint named '{name}'")]
    UnknownJoint {
        /// The name.
        name: String,
    },
    /// A joint that cannot be locked at the value given.
    #[error(
        "joint '{joint}' cannot be locked: only joints with one coordinate are, at a finite value"
    )]
    BadLock {
        /// The joint.
        joint: String,
    },
    /// The reduced model could not be built.
    #[error("reduced model: {0}")]
    Model(String),
    /// An expression grew beyond the limit during the derivation.
    #[error("expression swell: {what} would reach {terms} terms (the limit is 1 000 000 per expression): the explicit form of this model is too large; use the recursive algorithms, or lock joints")]
    Swell {
        /// Which expression.
        what: String,
        /// Its (predicted) number of terms (0: a parameter monomial or a frequency overflowed).
        terms: usize,
    },
}

/// The exact explicit model: `M(q)`, the Coriolis and centrifugal terms and `g(q)` as
/// expressions in the joint angles and the model's parameters.
#[derive(Clone, Debug)]
pub struct ExplicitModel {
    chain: chain::Chain,
    mass: Vec<Expr>,
    coriolis: Vec<Expr>,
    centrifugal: Vec<Expr>,
    gravity: Vec<Expr>,
}

impl ExplicitModel {
    /// Derives the explicit model of `model` (see the module documentation).
    ///
    /// # Errors
    /// A joint other than revolute, continuous or prismatic; more than 12 joints; expression
    /// swell.
    pub fn derive(model: &Model) -> Result<Self, ExplicitError> {
        let chain = chain::Chain::new(model)?;
        let e = lagrange::energies(&chain)?;
        let (coriolis, centrifugal) = lagrange::christoffel(&e.mass, chain.n());
        Ok(Self {
            chain,
            mass: e.mass,
            coriolis,
            centrifugal,
            gravity: e.gravity,
        })
    }

    /// Number of joints.
    #[must_use]
    pub fn n(&self) -> usize {
        self.chain.n()
    }

    /// Whether joint `j` (0-based) is prismatic.
    #[must_use]
    pub fn is_prismatic(&self, j: usize) -> bool {
        self.chain.space.is_prismatic(j)
    }

    /// The symbols.
    #[must_use]
    pub fn parameters(&self) -> &Parameters {
        &self.chain.params
    }

    /// `a_ij = M_ij(q)` (0-based).
    #[must_use]
    pub fn mass(&self, i: usize, j: usize) -> &Expr {
        &self.mass[i * self.n() + j]
    }

    /// `b_ijk` (0-based, `j < k`): the coefficient of `q̇_j q̇_k` in `c_i(q, q̇)`.
    #[must_use]
    pub fn coriolis(&self, i: usize, j: usize, k: usize) -> &Expr {
        let n = self.n();
        &self.coriolis[(i * n + j) * n + k]
    }

    /// `c_ij` (0-based): the coefficient of `q̇_j²` in `c_i(q, q̇)`.
    #[must_use]
    pub fn centrifugal(&self, i: usize, j: usize) -> &Expr {
        &self.centrifugal[i * self.n() + j]
    }

    /// The tables: entries in the tables' form, abbreviated and pruned (see [`Tables`]).
    #[must_use]
    pub fn tables(&self, options: &TableOptions) -> Tables {
        Tables::new(self, options)
    }

    /// `g_i(q)` (0-based).
    #[must_use]
    pub fn gravity(&self, i: usize) -> &Expr {
        &self.gravity[i]
    }
}
