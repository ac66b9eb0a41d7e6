//! The composite-rigid-body algorithm for the joint-space mass matrix (Featherstone 2008,
//! Table 6.2), with the composite inertias accumulated in one frame per tree (the root body's),
//! so that no force is carried up the chain.
//!
//! Read [`reference::crba`](crate::multibody::reference::crba) first (spatial_v2's `HandC.m`).
//! Line by line, this is the same algorithm expressed in the root body's frame {r}:
//!
//! | `HandC.m` | here |
//! | --- | --- |
//! | `IC{λ(i)} += Xup{i}' * IC{i} * Xup{i}` | `rG_i` computed once per body by `root_frame_bodies` ([`SpatialInertia::transformed`](crate::mass::SpatialInertia::transformed) or its principal-form variant), then `Ic_λ(i) += Ic_i`: a plain sum, every term already in {r} |
//! | `fh = IC{i} * S{i}` | `F_k = Ic_i J_k`, `J_k = [Ad_{rMi}] S_k` |
//! | `fh = Xup{j}' * fh; H(i,j) = S{j}' * fh` | `M_kl = J_kᵀ F_l`: no force carried up, `J_k` already in {r} |
//!
//! `root_frame_bodies` composes `rMi = rM_λ(i) X_T X_J(q_i)` with the shortcuts of the
//! [plan](crate::multibody) (`X_T` a signed permutation or a turn about a coordinate axis, sines
//! ahead of the chain); a free-flyer root's 6x6 block is `Ic` itself.

use super::root_frame_bodies;
use crate::multibody::{check_data, check_q, Data, JointType, Model, MultibodyError};
use nalgebra::DMatrix;

/// The joint-space inertia matrix `M(q)` (full symmetric), plus the armature on the diagonal:
///
/// - per tree, a reference frame {r} fixed to the root body (the body moved by a joint without a
///   parent): `rMi = rM_{λ(i)} liMi` with `rM_root = 1`
/// - quantities in {r}: `rG_i = [Ad_{rMi⁻¹}]ᵀ G_i [Ad_{rMi⁻¹}]`, `J_k = [Ad_{rMi}] S_k`
/// - composite inertias, i = n..1: `Ic_i = rG_i + Σ_{children c} Ic_c`
/// - for each dof k of joint i: `F_k = Ic_i J_k`; for every dof l in i's subtree (l ≥ k):
///   `M_kl = M_lk = J_kᵀ F_l`, where `F_l = Ic_{j(l)} J_l` uses the composite inertia of l's own
///   joint (the deeper one)
/// - `M_kk += armature_k`
///
/// This is Featherstone 2008, Table 6.2 (`M_ij = S_iᵀ Ic_i S_j` for j ⪯ i) with every quantity in
/// one frame per tree; `M = Σ_i J_iᵀ G_i J_i` (Lynch & Park §8.3.3). Each `M_kl = J_kᵀ F_l` pairs a
/// twist with a wrench, so it is the same in every frame: Pinocchio's WORLD convention uses the
/// world frame; taking the root body's frame instead makes the root's columns constant
/// (`J_k = S_k`) and the root joint's `q` unused (`M` does not depend on it), so the root's
/// placement, its children's compositions and, for a free-flyer root, every product of its six
/// rows (`M_{root, l} = F_l`, `M_{root, root} = Ic_root`) drop out. Distinct trees share no dof,
/// so their blocks of `M` are zero and each can have its own frame.
///
/// Returns `data.mass_matrix`; `data.composite_inertias` holds the composite inertias in the
/// root body frame of each tree. `data.placements` is not updated (run
/// [`forward_kinematics_q`](super::forward_kinematics_q) for world poses). O(n d) dot products,
/// d the depth.
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
    root_frame_bodies(
        model,
        q,
        &mut data.root_placements,
        &mut data.dof_J,
        &mut data.composite_inertias,
        &mut data.sin_cos,
    );
    let n = model.njoints();
    let nv = model.nv;
    let M = data.mass_matrix.as_mut_slice(); // column-major, M[(k, l)] = M[l * nv + k]
    for i in (0..n).rev() {
        let ji = &model.joints()[i];
        let Ic = data.composite_inertias[i];
        let end_v = model.plan().subtree_end_v[i];
        let dofs = ji.idx_v..ji.idx_v + ji.nv;
        if ji.parent.is_none() && ji.kind == JointType::FreeFlyer {
            // J = 1₆ in the root frame: the 6x6 block is Ic itself, row r of column l is F_l[r]
            let (r0, G) = (ji.idx_v, Ic.matrix());
            let forces = &data.crba_forces[r0 + 6..end_v];
            let mut cols = M[r0 * nv..(r0 + 6) * nv].chunks_exact_mut(nv);
            let mut col = |c: usize| {
                let col = cols.next().expect("six columns");
                col[r0..r0 + 6].copy_from_slice(G.column(c).as_slice());
                &mut col[r0 + 6..end_v]
            };
            // the columns cut to the length of `forces`, so that the loop below has no index test
            let len = forces.len();
            let [c0, c1, c2, c3, c4, c5] =
                [col(0), col(1), col(2), col(3), col(4), col(5)].map(|c| &mut c[..len]);
            // lower triangle, rows l of the root's columns: M[l, r0 + c] = F_l[c], one pass over
            // the F_l with six stores each
            for (t, F) in forces.iter().enumerate() {
                (c0[t], c1[t], c2[t]) = (F.m.x, F.m.y, F.m.z);
                (c3[t], c4[t], c5[t]) = (F.f.x, F.f.y, F.f.z);
            }
            // upper triangle, the root's rows of the later columns l: F_l
            for (col, F) in M.chunks_exact_mut(nv).take(end_v).skip(r0 + 6).zip(forces) {
                col[r0..r0 + 6].copy_from_slice(&[F.m.x, F.m.y, F.m.z, F.f.x, F.f.y, F.f.z]);
            }
            for k in dofs {
                M[k * nv + k] += model.armature[k];
            }
            continue;
        }
        if ji.nv == 1 {
            // one dof (revolute, prismatic): no loops over the joint's dofs
            let k = ji.idx_v;
            let Jk = data.dof_J[k];
            data.crba_forces[k] = Ic.momentum(&Jk);
            let column = &mut M[k * nv + k..k * nv + end_v];
            for (m, F) in column.iter_mut().zip(&data.crba_forces[k..end_v]) {
                *m = Jk.dot(F);
            }
            column[0] += model.armature[k];
            for l in k + 1..end_v {
                M[l * nv + k] = M[k * nv + l];
            }
            if let Some(p) = ji.parent {
                data.composite_inertias[p.0] += Ic;
            }
            continue;
        }
        for k in dofs.clone() {
            data.crba_forces[k] = Ic.momentum(&data.dof_J[k]);
        }
        for k in dofs {
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
