//! The composite-rigid-body algorithm for the joint-space mass matrix (Featherstone 2008,
//! Table 6.2), in body coordinates.

use super::kinematics::placements_unchecked;
use crate::multibody::{check_q, Data, Model, MultibodyError};
use nalgebra::DMatrix;

/// The joint-space inertia matrix `M(q)` (full symmetric), plus the armature on the diagonal:
///
/// - `Ic_i = G_i`; for i = n..1: `Ic_{λ(i)} += [Ad_{liMi⁻¹}]ᵀ Ic_i [Ad_{liMi⁻¹}]`
/// - `F = Ic_i S_i`, `M_ii = S_iᵀ F`; then up the chain `j = i`, while `λ(j) ≠ 0`:
///   `F = [Ad_{ljMj⁻¹}]ᵀ F`, `j = λ(j)`, `M_ji = M_ijᵀ = S_jᵀ F`
/// - `M_kk += armature_k`
///
/// (Featherstone 2008, Table 6.2; `M = Σ_i J_iᵀ G_i J_i`, Lynch & Park §8.3.3). Returns
/// `data.mass_matrix`; also fills `placements` and `composite_inertias`. O(n d), d the depth.
///
/// # Errors
/// Wrong length, non-finite entry or non-unit quaternion in `q`.
pub fn crba<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_q(model, q)?;
    placements_unchecked(model, data, q);
    let n = model.joints.len();
    data.composite_inertias.copy_from_slice(&model.inertias);
    let M = &mut data.mass_matrix;
    for i in (0..n).rev() {
        let ji = &model.joints[i];
        let Ic = data.composite_inertias[i];
        for k in ji.idx_v..ji.idx_v + ji.nv {
            let mut F = Ic.momentum(&model.dof_S[k]);
            for l in ji.idx_v..ji.idx_v + ji.nv {
                M[(l, k)] = model.dof_S[l].dot(&F);
            }
            let mut j = i;
            while let Some(p) = model.joints[j].parent {
                F = data.parent_placements[j].act_wrench(&F);
                j = p.0;
                let jj = &model.joints[j];
                for l in jj.idx_v..jj.idx_v + jj.nv {
                    let m = model.dof_S[l].dot(&F);
                    M[(l, k)] = m;
                    M[(k, l)] = m;
                }
            }
        }
        if let Some(p) = ji.parent {
            let t = super::inertia_to_parent(&Ic, &data.parent_placements[i]);
            data.composite_inertias[p.0] += t;
        }
    }
    // Entries of joints in different branches are never written: they stay 0 from Data::new.
    for k in 0..model.nv {
        M[(k, k)] += model.armature[k];
    }
    Ok(&data.mass_matrix)
}
