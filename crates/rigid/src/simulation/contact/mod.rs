//! Unilateral contacts with Coulomb friction, and joint limits as unilateral constraints, in the
//! velocity-level time-stepping form (Moreau 1988; Stewart & Trinkle 1996; Anitescu & Potra
//! 1997): over a step `h` the forces are impulses, and one problem per step decides them.
//!
//! With `M = M(q_k)`, the free velocity `v_f = v_k + h M⁻¹ (τ − c − g)` (a lone free body, a
//! free-flyer root with no child, takes its gyroscopic term by the implicit midpoint, which keeps
//! its energy), the contact Jacobian
//! `J` (three rows per contact: the normal `n` and two tangents, the relative velocity of the
//! two bodies at the contact point; one row per joint limit) and the Delassus operator
//! `G = J M⁻¹ Jᵀ`, the velocity after the step is `v⁺ = v_f + M⁻¹ Jᵀ λ` and the contact
//! velocity `σ = J v⁺ = σ_f + G λ`. Each contact's impulse `λ = (λ_n, λ_t)` obeys
//!
//! - Signorini at the velocity level: `0 ≤ λ_n ⊥ σ_n − σ*_n ≥ 0`, with the target
//!   `σ*_n = −φ/h` for a gap `φ > 0` (the bodies may close it in this step, and no more: a
//!   contact whose gap closes lands at `φ = 0`), `0` when touching or penetrating, and
//!   `e V` at the step after a gap closed at the speed `V` (Newton's impact law with restitution
//!   `e`; `V` the approach speed when the gap closed within that step, uniformly accelerated
//!   from `J_n v_k` to `J_n v_f`), or `e |σ_n⁻|` for a contact found already touching and
//!   approaching at `σ_n⁻ = J_n v_k`;
//! - Coulomb's law with maximal dissipation: `‖λ_t‖ ≤ μ λ_n`, and if the contact slides
//!   (`σ_t ≠ 0`), `λ_t = −μ λ_n σ_t / ‖σ_t‖`.
//!
//! This is the nonlinear complementarity problem of Signorini–Coulomb (not the convex relaxation
//! of Anitescu, whose sliding contacts drift apart by `μ ‖σ_t‖` per second). It is solved by
//! projected Gauss–Seidel over the contacts on the exact (second-order) cone, Jean & Moreau's
//! non-smooth Gauss–Seidel (Jean 1999, "The non-smooth contact dynamics method"; Pinocchio's
//! `PGSContactSolverTpl`): per contact, the normal impulse by a projected Newton step on its
//! row, then the tangential impulse by the 2×2 block and a radial projection on the disc
//! `μ λ_n`. `G` comes from the tree-sparse factor `M = LᵀL` of the constraint machinery
//! ([`constraints`](crate::multibody::constraints)): `Z = L⁻ᵀ Jᵀ`, `G = Zᵀ Z`.
//!
//! # What it guarantees
//!
//! **The contact impulses never add kinetic energy.** The change they make in a step is
//! `ΔK = ½ v⁺ᵀ M v⁺ − ½ v_fᵀ M v_f = λᵀ σ_f + ½ λᵀ G λ = λᵀ σ − ½ λᵀ G λ`. At a solution
//! `λ_n (σ_n − σ*_n) = 0` and `λ_t · σ_t ≤ 0` (maximal dissipation), so `λᵀ σ = Σ λ_n σ*_n`:
//! without a rebound every `σ*_n ≤ 0`, and `ΔK ≤ 0` because `G` is positive semi-definite. An
//! impact spans two steps, the one where the gap closes (the contact takes the approach's kinetic
//! energy, `E`) and the next (the rebound gives back at most `e² E`, e ≤ 1), so over the two
//! `ΔK ≤ −(1 − e²) E ≤ 0`. The iterations stop before exact convergence, and Newton's law at
//! several simultaneous impacts can add energy; so after the iterations `ΔK` is computed, and if
//! it exceeds the rebounds' credit `Σ e² E` (0 without rebound) the impulse is scaled by the
//! largest `α ∈ [0, 1]` that brings it back (the cone is a cone: `α λ` stays in it;
//! [`ContactStats::scaled`] counts it). So the kinetic energy taken by the contacts since the
//! start never becomes negative, converged or not; the tests check it on random impacts.
//!
//! Penetration (from finite steps, rotations within a step, or an initial state) is removed by
//! a second, position-only solve (post-stabilisation, Cline & Pai 2003): normal impulses `μ ≥ 0`
//! with `G_nn μ ≥ β max(0, −φ)/h`, moving `q` by `h M⁻¹ J_nᵀ μ` without touching `v`: no kinetic
//! energy is made (the potential energy changes by the weight lifted out of the ground).

// loops over several per-row arrays at once read better indexed
#![allow(clippy::needless_range_loop)]

mod admm;
mod pgs;
mod polish;
mod residuals;
#[cfg(feature = "collision")]
mod rows;
mod solver;

pub use residuals::ContactResiduals;

#[cfg(feature = "collision")]
pub(crate) use solver::Block;
pub(crate) use solver::ContactSolver;

/// The algorithm that solves a step's contact problem (both on the same rows, to the same
/// tolerance).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Solver {
    /// Projected Gauss–Seidel on the exact cone, contact by contact (Jean & Moreau).
    #[default]
    Pgs,
    /// The alternating direction method of multipliers on the exact cone with the De Saxcé
    /// shift, island by island (Carpentier et al. 2024; Pinocchio's ADMM): converges where the
    /// sweep stalls (stacks, redundant contacts) and spreads a load over a flat face.
    Admm,
}

impl Solver {
    /// Its name, as [`FromStr`](std::str::FromStr) reads it: `pgs` or `admm`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Pgs => "pgs",
            Self::Admm => "admm",
        }
    }

    /// What one of its [`ContactStats::iterations`] is: `sweeps` (PGS) or `iterations` (ADMM).
    #[must_use]
    pub fn iterations_name(self) -> &'static str {
        match self {
            Self::Pgs => "sweeps",
            Self::Admm => "iterations",
        }
    }
}

impl std::str::FromStr for Solver {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "pgs" => Ok(Self::Pgs),
            "admm" => Ok(Self::Admm),
            _ => Err(format!("unknown contact solver `{s}`: `pgs` or `admm`")),
        }
    }
}

/// The solver's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactSettings {
    /// The algorithm.
    pub solver: Solver,
    /// The most sweeps (PGS) or iterations (ADMM) per island of a step.
    pub max_iterations: usize,
    /// Stop when no impulse changed by more than `tolerance × (largest impulse)` in a sweep (PGS)
    /// or an iteration, with the split `x = z` held to the same (ADMM).
    pub tolerance: f64,
    /// `β ∈ [0, 1]`: the share of a penetration removed by the position correction of one step
    /// (1: all of it, post-stabilisation; 0: none).
    pub stabilization: f64,
    /// The approach speed (m/s) below which an impact is plastic whatever the restitution: a
    /// body resting on another does not bounce on the speed gravity gives it in one step.
    pub restitution_speed: f64,
    /// PGS: polish the sweep by its active set (`contact/polish.rs`: Newton's method on the
    /// modes read from the impulses, after sweeps 4, 8, 16, …; a kept polish ends the solve
    /// at a solution of the same problem, every residual at round-off, but where the problem
    /// has more than one not always the sweep's: docs/contact.md). On by default; ADMM has none.
    pub polish: bool,
}

impl Default for ContactSettings {
    /// PGS with the polish, 200 sweeps, tolerance `1e-10`, `β = 1`, restitution below 1 cm/s
    /// ignored.
    fn default() -> Self {
        Self {
            polish: true,
            solver: Solver::Pgs,
            max_iterations: 200,
            tolerance: 1e-10,
            stabilization: 1.0,
            restitution_speed: 0.01,
        }
    }
}

impl ContactSettings {
    pub(crate) fn is_valid(&self) -> bool {
        self.max_iterations >= 1
            && self.tolerance >= 0.0
            && self.tolerance.is_finite()
            && (0.0..=1.0).contains(&self.stabilization)
            && self.restitution_speed >= 0.0
            && self.restitution_speed.is_finite()
    }
}

/// What the last step's contact solve did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactStats {
    /// Contacts and joint limits given to the solver (a gap the step may close: see
    /// `docs/contact.md`).
    pub candidates: usize,
    /// Of those, the ones that pushed (`λ_n > 0`).
    pub active: usize,
    /// Sweeps (PGS) or iterations (ADMM) done: the most of an island (each island of blocks
    /// that share no dof with another's is solved on its own).
    pub iterations: usize,
    /// Whether the tolerance was met within `max_iterations`.
    pub converged: bool,
    /// How far the velocity solve's impulse is from an exact solution (after the energy
    /// safeguard's scaling).
    pub residuals: ContactResiduals,
    /// Whether the impulse was scaled down so as not to add kinetic energy (see the
    /// [module](self) documentation).
    pub scaled: bool,
    /// `ΔK = ½ v⁺ᵀ M v⁺ − ½ v_fᵀ M v_f` (J): the kinetic energy the contact impulses gave
    /// (negative: taken); positive only at a rebound, by at most `e²` times what the same
    /// contact took when its gap closed in the step before.
    pub kinetic_change: f64,
    /// The work of the step's impulses, `λᵀ J (v + v⁺)/2` (J; negative: taken): with the work
    /// of the smooth forces at the mean velocity, the step's change of kinetic energy (for `M`
    /// constant over the step). Zero for a body at rest, where `kinetic_change` is the
    /// `½ h² gᵀ M g` that gravity's kick in the free velocity gave and the contacts took back.
    pub work: f64,
    /// The sum of the normal impulses of the contacts, `Σ λ_n` (N·s; divide by `h` for the force).
    pub normal_impulse: f64,
    /// The deepest penetration among the candidates before the step's position correction (m,
    /// positive; 0 when none penetrates).
    pub penetration: f64,
}

impl ContactStats {
    /// The names of [`solve_row`](Self::solve_row)'s entries: the CSV columns of `rigid
    /// simulate --residuals` and the keys of Python's `simulate`.
    pub const SOLVE_COLUMNS: [&'static str; 6] = [
        "iterations",
        "converged",
        "signorini",
        "coulomb",
        "dissipation",
        "velocity_error",
    ];

    /// The solve as numbers, in the order of [`SOLVE_COLUMNS`](Self::SOLVE_COLUMNS):
    /// iterations, converged (1 or 0), then the four [`ContactResiduals`].
    #[must_use]
    pub fn solve_row(&self) -> [f64; 6] {
        let r = &self.residuals;
        [
            self.iterations as f64,
            f64::from(u8::from(self.converged)),
            r.signorini,
            r.coulomb,
            r.dissipation,
            r.velocity_error,
        ]
    }
}
