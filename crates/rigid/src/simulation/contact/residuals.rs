//! How far a contact impulse is from solving the problem of its step: the criteria of
//! ContactBench (Le Lidec, Jallet, Montaut, Laptev, Stasse, Carpentier 2023, "Contact models in
//! robotics: a comparative analysis", §V-A), the largest over the contacts and limits.
//!
//! With `σ̄ = σ − σ*` (the contact velocity past its target) and, for a contact, the De Saxcé
//! shift `Γ(σ̄) = (μ ‖σ̄_t‖, 0, 0)`, the impulse solves the Signorini–Coulomb problem exactly when
//! `λ ∈ K_μ` (the cone `‖λ_t‖ ≤ μ λ_n`), `σ̄ + Γ(σ̄) ∈ K_μ*` and `λ ⊥ σ̄ + Γ(σ̄)`. The last splits
//! into Signorini's `λ_n σ̄_n = 0` and the maximal dissipation `λ_t · σ̄_t + μ λ_n ‖σ̄_t‖ = 0`
//! (the friction opposes the slip at the cone's edge), each non-negative on the cone.

use super::solver::Block;

/// The residuals of one step's contact solve (0 at an exact solution). Bilateral rows (loops,
/// welds) enter only `velocity_error`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactResiduals {
    /// Signorini's complementarity `max |λ_n σ̄_n|` (J): an impulse on a contact that separates
    /// faster than its target.
    pub signorini: f64,
    /// The Coulomb cone's violation `max (‖λ_t‖ − μ λ_n)⁺` (N·s; a limit: `(−λ)⁺`).
    pub coulomb: f64,
    /// The maximal-dissipation gap `max |λ_t · σ̄_t + μ λ_n ‖σ̄_t‖|` (J): friction that does not
    /// oppose the slip at the edge of the cone.
    pub dissipation: f64,
    /// The dual feasibility `max (−σ̄_n)⁺` over the contacts and limits (`σ̄ + Γ(σ̄) ∈ K_μ*` is
    /// `σ̄_n ≥ 0`) and `|σ̄|` over the bilateral rows (m/s or rad/s): a contact approaching
    /// faster than its target, a constraint violated at the velocity level.
    pub velocity_error: f64,
}

impl ContactResiduals {
    /// The larger of each residual of `self` and `other` (the worst over several steps).
    #[must_use]
    pub fn max(self, other: Self) -> Self {
        Self {
            signorini: self.signorini.max(other.signorini),
            coulomb: self.coulomb.max(other.coulomb),
            dissipation: self.dissipation.max(other.dissipation),
            velocity_error: self.velocity_error.max(other.velocity_error),
        }
    }

    /// The residuals of `lambda` with `sigma = σ_f + G λ` and the targets `target` over
    /// `blocks`; `friction`: whether the tangent rows are part of the problem (the position
    /// correction has none).
    pub(crate) fn of(
        blocks: &[Block],
        target: &[f64],
        lambda: &[f64],
        sigma: &[f64],
        friction: bool,
    ) -> Self {
        let mut r = Self::default();
        for b in blocks {
            let k = b.row;
            let s = |i: usize| sigma[k + i] - target[k + i];
            if b.bilateral {
                for i in 0..b.dim {
                    r.velocity_error = r.velocity_error.max(s(i).abs());
                }
                continue;
            }
            let (ln, sn) = (lambda[k], s(0));
            r.signorini = r.signorini.max((ln * sn).abs());
            if b.dim == 3 && friction {
                let mu = b.friction;
                let (l1, l2, s1, s2) = (lambda[k + 1], lambda[k + 2], s(1), s(2));
                let st = (s1 * s1 + s2 * s2).sqrt();
                r.coulomb = r.coulomb.max((l1 * l1 + l2 * l2).sqrt() - mu * ln);
                r.dissipation = r.dissipation.max((l1 * s1 + l2 * s2 + mu * ln * st).abs());
            } else {
                r.coulomb = r.coulomb.max(-ln);
            }
            r.velocity_error = r.velocity_error.max(-sn);
        }
        r
    }
}
