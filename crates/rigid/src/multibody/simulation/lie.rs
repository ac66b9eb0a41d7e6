//! The Lie-algebra operations of each joint's configuration group that the integrators need:
//! the bracket `[x, y] = ad_x y`, the differential of the exponential
//! `dexp_x = Σ_k ad_xᵏ / (k + 1)!` and its inverse, applied to vectors or, transposed, to
//! momenta. Vector joints (revolute, prismatic) are abelian: `ad = 0`, `dexp = 1`.
//!
//! Conventions: with `q(t) = q₀ exp(Θ(t))` the body velocity is `v = dexp_{-Θ}(Θ̇)`, so
//! `Θ̇ = dexp⁻¹_{-Θ}(v)` (Iserles, Munthe-Kaas, Nørsett & Zanna, "Lie-group methods", Acta
//! Numerica 2000, §2.3).

use crate::multibody::{JointType, Model};
use crate::spatial::{Twist, Vec3, Wrench};
use nalgebra::{SMatrix, SVector};

/// `out = ad_x y` (`transpose = false`) or `out = ad_xᵀ y` (`transpose = true`) in the Lie
/// algebra of one joint: so(3) for a spherical joint (`ad_ω η = ω × η`), se(3) for a free-flyer
/// (angular first, [`Twist::cross`] and [`Twist::ad_transpose`]), se(2) for a planar joint
/// (`(v_x, v_y, ω)`), zero for the others.
fn ad(kind: &JointType, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
    match kind {
        JointType::Revolute { .. } | JointType::Continuous { .. } | JointType::Prismatic { .. } => {
            out[0] = 0.0;
        }
        JointType::Spherical => {
            let (w, e) = (Vec3::new(x[0], x[1], x[2]), Vec3::new(y[0], y[1], y[2]));
            // ad_ωᵀ = [ω]ᵀ = -[ω]
            let r = if transpose { e.cross(&w) } else { w.cross(&e) };
            out[..3].copy_from_slice(r.as_slice());
        }
        JointType::FreeFlyer => {
            let t = Twist::from_slice(&x[..6]);
            let r = if transpose {
                t.ad_transpose(&Wrench::from_slice(&y[..6])).to_vector()
            } else {
                t.cross(&Twist::from_slice(&y[..6])).to_vector()
            };
            out[..6].copy_from_slice(r.as_slice());
        }
        JointType::Planar => {
            // ad_x = [[0, -ω, v_y], [ω, 0, -v_x], [0, 0, 0]] for x = (v_x, v_y, ω)
            let (vx, vy, w) = (x[0], x[1], x[2]);
            if transpose {
                out[0] = w * y[1];
                out[1] = -w * y[0];
                out[2] = vy * y[0] - vx * y[1];
            } else {
                out[0] = -w * y[1] + vy * y[2];
                out[1] = w * y[0] - vx * y[2];
                out[2] = 0.0;
            }
        }
    }
}

/// Most terms of the `dexp` series: `|x|ᵏ/(k + 1)!` is below round-off long before for the
/// steps a simulation takes (`|x| = |v| dt`).
const MAX_TERMS: usize = 60;

/// `out = dexp_x y` or `dexp_xᵀ y`, `dexp_x = Σ_{k≥0} ad_xᵏ / (k + 1)!`, by summing the series
/// until a term is below round-off (an entire function: it converges for every `x`).
fn dexp_one(kind: &JointType, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
    let n = kind.nv();
    let mut term = [0.0; 6];
    let mut next = [0.0; 6];
    term[..n].copy_from_slice(&y[..n]);
    out[..n].copy_from_slice(&y[..n]);
    if matches!(
        kind,
        JointType::Revolute { .. } | JointType::Continuous { .. } | JointType::Prismatic { .. }
    ) {
        return;
    }
    for k in 1..MAX_TERMS {
        ad(kind, x, &term[..n], transpose, &mut next[..n]);
        let scale = 1.0 / (k as f64 + 1.0);
        let mut size = 0.0f64;
        let mut total = 0.0f64;
        for i in 0..n {
            term[i] = next[i] * scale;
            out[i] += term[i];
            size = size.max(term[i].abs());
            total = total.max(out[i].abs());
        }
        if size <= 1e-18 * total || size == 0.0 {
            break;
        }
    }
}

/// Solve `dexp_x z = y` (or `dexp_xᵀ z = y`) for one joint: the `n x n` matrix of `dexp_x`
/// (n ≤ 6), built column by column, then an LU solve on the stack.
fn dexp_solve_one(kind: &JointType, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
    let n = kind.nv();
    if n == 1 {
        out[0] = y[0];
        return;
    }
    let mut a = SMatrix::<f64, 6, 6>::identity();
    let mut e = [0.0; 6];
    let mut col = [0.0; 6];
    for c in 0..n {
        e.fill(0.0);
        e[c] = 1.0;
        dexp_one(kind, x, &e[..n], transpose, &mut col[..n]);
        for r in 0..n {
            a[(r, c)] = col[r];
        }
    }
    let mut b = SVector::<f64, 6>::zeros();
    b.as_mut_slice()[..n].copy_from_slice(&y[..n]);
    // the unused block is the identity: the solve leaves its zeros alone
    match a.lu().solve(&b) {
        Some(z) => out[..n].copy_from_slice(&z.as_slice()[..n]),
        None => out[..n].copy_from_slice(&y[..n]),
    }
}

/// `out = dexp_x y` (or `dexp_xᵀ y`) joint by joint, `x` and `y` of length `nv`.
pub(crate) fn dexp(model: &Model, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
    for j in &model.joints {
        let r = j.idx_v..j.idx_v + j.nv;
        dexp_one(
            &j.kind,
            &x[r.clone()],
            &y[r.clone()],
            transpose,
            &mut out[r],
        );
    }
}

/// `out = dexp_x⁻¹ y` (or `dexp_x⁻ᵀ y`) joint by joint.
pub(crate) fn dexp_inv(model: &Model, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
    for j in &model.joints {
        let r = j.idx_v..j.idx_v + j.nv;
        dexp_solve_one(
            &j.kind,
            &x[r.clone()],
            &y[r.clone()],
            transpose,
            &mut out[r],
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multibody::{difference, integrate, Rng};

    /// `d/ds log(q₀⁻¹ (q₀ exp(x) exp(s η)))|₀ = dexp⁻¹_{-x} η`: checked by central differences
    /// through `integrate` and `difference` on every joint type of a free-flyer + spherical +
    /// planar + revolute model.
    #[test]
    fn dexp_matches_finite_differences_of_integrate() {
        use crate::mass::SpatialInertia;
        use crate::multibody::ModelBuilder;
        use crate::spatial::Transform;
        let mut b = ModelBuilder::new("lie");
        let g = SpatialInertia::zero();
        let root = b
            .add_joint(None, "f", JointType::FreeFlyer, Transform::identity(), g)
            .unwrap();
        let s = b
            .add_joint(
                Some(root),
                "s",
                JointType::Spherical,
                Transform::identity(),
                g,
            )
            .unwrap();
        let p = b
            .add_joint(Some(s), "p", JointType::Planar, Transform::identity(), g)
            .unwrap();
        b.add_joint(
            Some(p),
            "r",
            JointType::Revolute { axis: Vec3::z() },
            Transform::identity(),
            g,
        )
        .unwrap();
        let model = b.build().unwrap();
        let mut rng = Rng::new(5);
        let nv = model.nv();
        let q0 = crate::multibody::random_configuration(&model, &mut rng);
        let x: Vec<f64> = (0..nv).map(|_| rng.uniform(-0.8, 0.8)).collect();
        let eta: Vec<f64> = (0..nv).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let mut q1 = vec![0.0; model.nq()];
        integrate(&model, &q0, &x, 1.0, &mut q1).unwrap();
        let eps = 1e-6;
        let (mut qp, mut qm) = (vec![0.0; model.nq()], vec![0.0; model.nq()]);
        integrate(&model, &q1, &eta, eps, &mut qp).unwrap();
        integrate(&model, &q1, &eta, -eps, &mut qm).unwrap();
        let (mut xp, mut xm) = (vec![0.0; nv], vec![0.0; nv]);
        difference(&model, &q0, &qp, &mut xp).unwrap();
        difference(&model, &q0, &qm, &mut xm).unwrap();
        let fd: Vec<f64> = (0..nv).map(|i| (xp[i] - xm[i]) / (2.0 * eps)).collect();
        let minus_x: Vec<f64> = x.iter().map(|v| -v).collect();
        let mut z = vec![0.0; nv];
        dexp_inv(&model, &minus_x, &eta, false, &mut z);
        let err = fd
            .iter()
            .zip(&z)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(
            err < 1e-8,
            "dexp⁻¹ vs finite differences: {err:e}\n{fd:?}\n{z:?}"
        );
        // dexp ∘ dexp⁻¹ = 1, and the transpose pairs: ⟨dexpᵀ μ, η⟩ = ⟨μ, dexp η⟩
        let mut back = vec![0.0; nv];
        dexp(&model, &minus_x, &z, false, &mut back);
        assert!(back.iter().zip(&eta).all(|(a, b)| (a - b).abs() < 1e-14));
        let mu: Vec<f64> = (0..nv).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let (mut a, mut c) = (vec![0.0; nv], vec![0.0; nv]);
        dexp(&model, &x, &mu, true, &mut a);
        dexp(&model, &x, &eta, false, &mut c);
        let lhs: f64 = a.iter().zip(&eta).map(|(a, b)| a * b).sum();
        let rhs: f64 = mu.iter().zip(&c).map(|(a, b)| a * b).sum();
        assert!((lhs - rhs).abs() < 1e-14, "{lhs} {rhs}");
    }
}
