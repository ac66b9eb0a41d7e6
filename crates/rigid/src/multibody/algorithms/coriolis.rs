//! The Coriolis matrix `C(q, v)` with `c(q, v) = C v` and `Ṁ - 2C` skew-symmetric: the
//! Christoffel-symbol matrix, computed as Pinocchio's `computeCoriolisMatrix`.

use super::compute_joint_jacobians_time_variation;
use crate::multibody::{Data, Model, MultibodyError};
use crate::spatial::{skew, Mat6, Twist, Vec6, Wrench};
use nalgebra::DMatrix;

/// `B = ½ Ġ + ½ (G V)×̄*` for a body with world inertia matrix `G` and spatial twist `V`:
/// `Ġ = V×* G - G V× = -[ad_V]ᵀ G - G [ad_V]`, and `h×̄*` is the 6x6 matrix with
/// `(h×̄*) X = X ×* h = -[ad_X]ᵀ h`, i.e. `[[-[m], -[f]], [-[f], 0]]` for `h = (m, f)`.
fn body_b(G: &Mat6, V: &Twist, h: &Wrench) -> Mat6 {
    let ad = V.ad();
    let mut B = (ad.transpose() * G + G * ad) * -0.5;
    let (km, kf) = (skew(&h.m) * 0.5, skew(&h.f) * 0.5);
    let mut top = B.fixed_view_mut::<3, 3>(0, 0);
    top -= km;
    let mut tr = B.fixed_view_mut::<3, 3>(0, 3);
    tr -= kf;
    let mut bl = B.fixed_view_mut::<3, 3>(3, 0);
    bl -= kf;
    B
}

/// The Coriolis matrix of the Lagrangian dynamics, `C_ij = Σ_k Γ_ijk v_k` with the Christoffel
/// symbols `Γ_ijk = ½ (∂M_ij/∂q_k + ∂M_ik/∂q_j - ∂M_jk/∂q_i)` (Lynch & Park §8.1.2), so that
/// `c(q, v) = C v` and `Ṁ - 2C` is skew-symmetric.
///
/// In world coordinates, with `J_i` the spatial Jacobian of body i (columns
/// `J_k = [Ad_{oMi}] S_k` of its supporting joints), `J̇_k = [ad_{V_j(k)}] J_k`, `G_i` the body's
/// world inertia and `V_i` its spatial twist:
///
/// `C = Σ_i J_iᵀ (G_i J̇_i + B_i J_i)`, `B_i = ½ Ġ_i + ½ (G_i V_i)×̄*`, `Ġ_i = V_i×* G_i - G_i V_i×`.
///
/// Then `C v = Σ J_iᵀ (G_i J̇_i v + V_i ×* G_i V_i)` (Newton-Euler), and
/// `Ṁ - 2C = Σ (J̇ᵀGJ - JᵀGJ̇) - Σ Jᵀ (G V)×̄* J` is skew since `h×̄*` is. Entries are sums over
/// subtrees: for dofs k, l on one branch and d the deeper joint of the two,
/// `C_lk = J_lᵀ (Gc_d J̇_k + Bc_d J_k)` with the composite `Gc_d = Σ_{i ⪰ d} G_i`,
/// `Bc_d = Σ_{i ⪰ d} B_i` (the structure of Pinocchio's `computeCoriolisMatrix`). Returns
/// `data.coriolis`. O(n d) 6x6 products.
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
    let n = model.njoints();
    for i in 0..n {
        let Gs = model.inertias()[i].transformed(&data.placements[i]);
        let Vs = data.spatial_velocities[i];
        data.world_inertias[i] = Gs;
        data.world_b[i] = body_b(&Gs.matrix(), &Vs, &Gs.momentum(&Vs));
    }
    for i in (0..n).rev() {
        if let Some(p) = model.joints()[i].parent {
            let (g, b) = (data.world_inertias[i], data.world_b[i]);
            data.world_inertias[p.0] += g;
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
        let (Gc, Bc) = (data.world_inertias[i], data.world_b[i]);
        // Y(k) = Gc J̇_k + Bc J_k
        let Y = |k: usize| -> Wrench {
            let Jk = col(&data.jacobian, k);
            let dJk = col(&data.jacobian_dot, k);
            Gc.momentum(&dJk) + Wrench::from_vector(&(Bc * Jk.to_vector()))
        };
        let ji = &model.joints()[i];
        for k in ji.idx_v..ji.idx_v + ji.nv {
            let Yk = Y(k);
            let Jk = col(&data.jacobian, k);
            let mut j = Some(i);
            while let Some(a) = j {
                let ja = &model.joints()[a];
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
