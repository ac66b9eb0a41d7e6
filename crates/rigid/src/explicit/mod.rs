//! The explicit dynamic model of a robot (WIP docs).

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
    /// displacement).
    #[error("joint '{joint}' is {kind}: explicit models are derived for fixed-base trees of revolute and prismatic joints only (lock it, or use the recursive algorithms)")]
    UnsupportedJoint {
        /// The joint.
        joint: String,
        /// What it is, and why that does not fit.
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
    #[error("expression swell: {what} grew to {terms} terms (the limit is 5 000 000); the explicit form of this model is too large, use the recursive algorithms")]
    Swell {
        /// Which expression.
        what: String,
        /// Its number of terms (0: a parameter monomial or a frequency overflowed).
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
