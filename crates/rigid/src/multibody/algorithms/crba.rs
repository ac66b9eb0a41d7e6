//! The composite-rigid-body algorithm for the joint-space mass matrix (Featherstone 2008,
//! Table 6.2), with the composite inertias accumulated in world coordinates (as Pinocchio's
//! `crba`), so that no force is carried up the chain.

use super::kinematics::placements_unchecked;
use super::{inertia_to_parent, world_joint_columns};
use crate::multibody::{check_data, check_q, Data, Model, MultibodyError};
use nalgebra::DMatrix;

/// The joint-space inertia matrix `M(q)` (full symmetric), plus the armature on the diagonal:
///
/// - world quantities: `oG_i = [Ad_{oMi⁻¹}]ᵀ G_i [Ad_{oMi⁻¹}]`, `J_k = [Ad_{oMi}] S_k`
/// - composite inertias, i = n..1: `Ic_i = oG_i + Σ_{children c} Ic_c`
/// - for each dof k of joint i: `F_k = Ic_i J_k`; for every dof l in i's subtree (l ≥ k):
///   `M_kl = M_lk = J_kᵀ F_l`, where `F_l = Ic_{j(l)} J_l` uses the composite inertia of l's own
///   joint (the deeper one)
/// - `M_kk += armature_k`
///
/// This is Featherstone 2008, Table 6.2 (`M_ij = S_iᵀ Ic_i S_j` for j ⪯ i), with every quantity
/// in world coordinates; `M = Σ_i J_iᵀ G_i J_i` (Lynch & Park §8.3.3). Returns
/// `data.mass_matrix`; also fills `placements`, `parent_placements` and `composite_inertias` (in world coordinates). O(n d) dot products, d the depth.
///
/// # Errors
/// Wrong length, non-finite entry or non-unit quaternion in `q`.
///
/// ```
/// use rigid::multibody::{crba, double_pendulum, Data};
/// let model = double_pendulum();
/// let mut data = Data::new(&model);
/// let m = crba(&model, &mut data, &[0.3, 0.0])?;
/// // straight: M22 = 1/3, M12 = 1/3 + 1/2, M11 = 1/3 + 1 + 1/3 + 1
/// assert!((m[(1, 1)] - 1.0 / 3.0).abs() < 1e-12 && (m[(0, 1)] - 5.0 / 6.0).abs() < 1e-12);
/// assert!((m[(0, 0)] - 8.0 / 3.0).abs() < 1e-12);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn crba<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    placements_unchecked(model, data, q);
    let n = model.joints.len();
    for i in 0..n {
        let oMi = data.placements[i];
        data.composite_inertias[i] = inertia_to_parent(&model.inertias[i], &oMi);
        world_joint_columns(model, i, &oMi, &mut data.dof_J);
    }
    let nv = model.nv;
    let M = data.mass_matrix.as_mut_slice(); // column-major, M[(k, l)] = M[l * nv + k]
    for i in (0..n).rev() {
        let ji = &model.joints[i];
        let Ic = data.composite_inertias[i];
        let end_v = {
            let last = &model.joints[ji.subtree_end - 1];
            last.idx_v + last.nv
        };
        for k in ji.idx_v..ji.idx_v + ji.nv {
            data.crba_forces[k] = Ic.momentum(&data.dof_J[k]);
        }
        for k in ji.idx_v..ji.idx_v + ji.nv {
            // lower triangle, column k, rows k..end_v (contiguous): M_lk = J_kᵀ F_l
            let Jk = data.dof_J[k];
            let column = &mut M[k * nv + k..k * nv + end_v];
            for (m, F) in column.iter_mut().zip(&data.crba_forces[k..end_v]) {
                *m = Jk.dot(F);
            }
            // the upper triangle of row k from column k, inside the subtree only (entries of
            // joints in different branches are never written: they stay 0 from Data::new)
            for l in k + 1..end_v {
                M[l * nv + k] = M[k * nv + l];
            }
            M[k * nv + k] += model.armature[k];
        }
        if let Some(p) = ji.parent {
            data.composite_inertias[p.0] += Ic;
        }
    }
    Ok(&data.mass_matrix)
}
