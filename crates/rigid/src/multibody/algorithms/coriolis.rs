//! The Coriolis matrix `C(q, v)` with `c(q, v) = C v` and `Ṁ - 2C` skew-symmetric.

use super::compute_joint_jacobians_time_variation;
use crate::multibody::{Data, Model, MultibodyError};
use crate::spatial::{Twist, Vec6, Wrench};
use nalgebra::DMatrix;

/// The Coriolis matrix, from the body-wise factorisation `M = Σ_i J_iᵀ G_i J_i` (body Jacobians):
///
/// `C = Σ_i J_iᵀ (G_i J̇_i + B_i J_i)` with `B_i = (G_i V_i) ×̄*`, the 6x6 matrix with
/// `B_i X = X ×* (G_i V_i) = -[ad_X]ᵀ G_i V_i`. Then `C v = Σ_i J_iᵀ (G_i J̇_i v - [ad_{V_i}]ᵀ G_i V_i)`
/// is the velocity-product term of the Newton-Euler equations, and since `B_i` is skew and `G_i`
/// constant in body coordinates, `Ṁ - 2C = Σ_i (J̇_iᵀ G_i J_i - J_iᵀ G_i J̇_i) - 2 Σ_i J_iᵀ B_i J_i` is
/// skew (Garofalo et al., ICRA 2013, in twist form).
///
/// Computed in world coordinates (`J̇_b = [Ad_{oMi⁻¹}](J̇_s - [ad_{V^s_i}] J_s)`), with composite
/// sums over subtrees `Gc`, `Hc = Σ G^s_i V^s_i`, `Bc = Σ G^s_i [ad_{V^s_i}]`: for dofs k, l on one
/// branch and d the deeper joint of the two, `C_lk = J_lᵀ (Gc_d J̇_k + (Hc_d ×̄* - Bc_d) J_k)`.
/// Returns `data.coriolis`. O(n d).
///
/// # Errors
/// Wrong lengths, non-finite entries, or a non-unit quaternion.
pub fn coriolis_matrix<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    compute_joint_jacobians_time_variation(model, data, q, v)?;
    let n = model.joints.len();
    for i in 0..n {
        let oMi = data.placements[i];
        let Gs = super::inertia_to_parent(&model.inertias[i], &oMi);
        let Vs = data.spatial_velocities[i];
        data.world_inertias[i] = Gs;
        data.world_momenta[i] = Gs.momentum(&Vs);
        data.world_b[i] = Gs.matrix() * Vs.ad();
    }
    for i in (0..n).rev() {
        if let Some(p) = model.joints[i].parent {
            let (g, h, b) = (
                data.world_inertias[i],
                data.world_momenta[i],
                data.world_b[i],
            );
            data.world_inertias[p.0] += g;
            data.world_momenta[p.0] += h;
            data.world_b[p.0] += b;
        }
    }
    let col = |m: &DMatrix<f64>, k: usize| -> Twist {
        let c = m.column(k);
        Twist::from_vector(&Vec6::new(c[0], c[1], c[2], c[3], c[4], c[5]))
    };
    let C = &mut data.coriolis;
    C.fill(0.0);
    for i in 0..n {
        let (Gc, Hc, Bc) = (
            data.world_inertias[i],
            data.world_momenta[i],
            data.world_b[i],
        );
        // Y(k) = Gc J̇_k + (Hc ×̄*) J_k - Bc J_k
        let Y = |k: usize| -> Wrench {
            let Jk = col(&data.jacobian, k);
            let dJk = col(&data.jacobian_dot, k);
            Gc.momentum(&dJk) - Jk.ad_transpose(&Hc) - Wrench::from_vector(&(Bc * Jk.to_vector()))
        };
        let ji = &model.joints[i];
        for k in ji.idx_v..ji.idx_v + ji.nv {
            let Yk = Y(k);
            let Jk = col(&data.jacobian, k);
            let mut j = Some(i);
            while let Some(a) = j {
                let ja = &model.joints[a];
                for l in ja.idx_v..ja.idx_v + ja.nv {
                    let Jl = col(&data.jacobian, l);
                    C[(l, k)] = Jl.dot(&Yk);
                    if a != i {
                        C[(k, l)] = Jk.dot(&Y(l));
                    }
                }
                j = ja.parent.map(|p| p.0);
            }
        }
    }
    Ok(&data.coriolis)
}
