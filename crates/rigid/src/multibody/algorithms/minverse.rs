//! The inverse of the joint-space mass matrix, `M(q)⁻¹`, by the articulated-body algorithm run
//! for every unit torque at once (Featherstone 2008, §7.3; Carpentier & Mansard 2018), in one
//! frame per tree (the root body's, as [`crba`](super::crba)) so that no spatial transform is
//! applied on the way.

use super::root_frame_bodies;
use crate::multibody::{check_data, check_q, Data, Model, MultibodyError};
use crate::spatial::mat6_twist;
use crate::spatial::{Mat6, Twist, Wrench};
use nalgebra::DMatrix;

/// `M(q)⁻¹`, the inverse of the joint-space inertia matrix with the armature on its diagonal
/// (the inverse of exactly what [`crba`](super::crba) returns), full symmetric, in O(n nv)
/// without forming or factorising `M`.
///
/// The articulated-body algorithm (Featherstone 2008, Table 7.1, §7.3) at `q̇ = 0`, no gravity,
/// maps `τ` linearly to `q̈ = M⁻¹ τ`; running it for the `nv` unit torques `τ = e_j` together
/// gives the columns of `M⁻¹` (Carpentier & Mansard 2018, "Analytical derivatives of rigid
/// body dynamics algorithms", RSS, the `M⁻¹` recursion; Pinocchio's `computeMinverse`). With
/// no velocity the bias terms vanish, and in one frame common to a tree (here its root body's
/// frame {r}, as in [`crba`](super::crba): `J_i = [Ad_{rMi}] S_i`,
/// `oG_i = [Ad_{rMi⁻¹}]ᵀ G_i [Ad_{rMi⁻¹}]`) a parent and a child share their frame, so:
///
/// - forward (i = 1..n): `rMi`, `J_i`, `I^A_i = oG_i`
/// - backward (i = n..1), with `P` the 6 x nv matrix of the bias forces `p^a` for every unit
///   torque (the columns of a subtree are contiguous and only its own joints write them):
///   `U_i = I^A_i J_i`, `D_i = J_iᵀ U_i + diag(armature_i)`;
///   `M⁻¹(i, i) = D_i⁻¹`, `M⁻¹(i, s) = -D_i⁻¹ J_iᵀ P(:, s)` for the columns `s` of i's
///   descendants (`u_i = τ_i - J_iᵀ p^A_i`, and `p^A_i` is what the children left in `P`);
///   `P(:, i) = U_i D_i⁻¹`, `P(:, s) += U_i M⁻¹(i, s)` (`p^a = p^A + U D⁻¹ u`);
///   `I^A_{λ(i)} += I^A_i - U_i D_i⁻¹ U_iᵀ`
/// - forward (i = 1..n), columns `c ≥ idx_v(i)` only (the upper triangle), with `A_j` the
///   6 x nv accelerations (tree frame) of body j for every unit torque (`A_world = 0`):
///   `M⁻¹(i, c) -= (U_i D_i⁻¹)ᵀ A_{λ(i)}(:, c)` (`q̈_i = D_i⁻¹ (u_i - U_iᵀ a_λ)`),
///   `A_i(:, c) = A_{λ(i)}(:, c) + J_i M⁻¹(i, c)`
/// - the upper triangle is mirrored into the lower one.
///
/// The backward pass costs O(nv_i · subtree) per joint, the last pass O(nv_i · nv): O(n nv)
/// overall, against O(nv³) for a dense inverse. Returns `data.minv` (`data.placements` is not
/// updated). Nothing is allocated.
///
/// # Errors
/// Wrong length, non-finite entry or non-unit quaternion in `q` (as [`crba`](super::crba)), a
/// `data` made for another model, or [`MultibodyError::NotPositiveDefinite`] when a joint's
/// articulated inertia `D_i` is not positive definite (`M` is singular: a joint that moves no
/// mass and has no armature).
///
/// ```
/// use rigid::multibody::{compute_minverse, crba, double_pendulum, Data};
/// let model = double_pendulum();
/// let mut data = Data::new(&model);
/// let q = [0.3, -0.7];
/// let m = crba(&model, &mut data, &q)?.clone();
/// let minv = compute_minverse(&model, &mut data, &q)?;
/// let eye = m * minv;
/// for i in 0..2 {
///     for j in 0..2 {
///         assert!((eye[(i, j)] - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
///     }
/// }
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn compute_minverse<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    minverse_unchecked(model, data, q)?;
    Ok(&data.minv)
}

/// [`compute_minverse`] on checked inputs: fills `data.minv`, and `data.root_placements`,
/// `data.dof_J`, `data.root_frame_inertias` (every body in its tree's root frame).
pub(crate) fn minverse_unchecked(
    model: &Model,
    data: &mut Data,
    q: &[f64],
) -> Result<(), MultibodyError> {
    root_frame_bodies(
        model,
        q,
        &mut data.root_placements,
        &mut data.dof_J,
        &mut data.root_frame_inertias,
        &mut data.sin_cos,
    );
    let n = model.njoints();
    let nv = model.nv;
    for i in 0..n {
        data.ia[i] = data.root_frame_inertias[i].matrix();
        data.minv_depth[i] = model.joints()[i]
            .parent
            .map_or(0, |p| data.minv_depth[p.0] + 1);
    }
    // Until the final mirror, column k of `minv` (contiguous) holds row k of M⁻¹ for the columns
    // c ≥ idx_v(joint of k): the "upper triangle" is computed in the lower one's storage.
    let minv = data.minv.as_mut_slice();
    for i in (0..n).rev() {
        let j = &model.joints()[i];
        let end = model.plan().subtree_end_v[i];
        let (head, tail) = data.ia.split_at_mut(i);
        let parent_ia = j.parent.map(|p| &mut head[p.0]);
        let bw = Backward {
            iv: j.idx_v,
            end,
            nv,
            ia: &tail[0],
            parent_ia,
            J: &data.dof_J,
            armature: &model.armature,
            ud: &mut data.minv_ud,
            p: &mut data.minv_p,
            minv: &mut *minv,
        };
        match j.nv {
            1 => bw.run::<1>(),
            2 => bw.run::<2>(),
            3 => bw.run::<3>(),
            4 => bw.run::<4>(),
            5 => bw.run::<5>(),
            _ => bw.run::<6>(),
        }?;
    }
    for i in 0..n {
        let j = &model.joints()[i];
        let end = model.plan().subtree_end_v[i];
        let d = data.minv_depth[i];
        // rows of the depth stack: A of the joint being processed at depth d, its parent at d - 1
        // (depth-first order: the last joint seen at depth d - 1 is the parent)
        let (above, here) = data.minv_a.split_at_mut(d * nv);
        let parent_a = j.parent.map(|_| &above[(d - 1) * nv..]);
        let fw = Forward {
            iv: j.idx_v,
            end,
            nv,
            J: &data.dof_J,
            ud: &data.minv_ud,
            parent_a,
            a: &mut here[..nv],
            leaf: j.subtree_end == i + 1,
            minv: &mut *minv,
        };
        match j.nv {
            1 => fw.run::<1>(),
            2 => fw.run::<2>(),
            3 => fw.run::<3>(),
            4 => fw.run::<4>(),
            5 => fw.run::<5>(),
            _ => fw.run::<6>(),
        }
    }
    // lower triangle (rows c > k of column k) into the upper one
    for k in 0..nv {
        for c in k + 1..nv {
            minv[c * nv + k] = minv[k * nv + c];
        }
    }
    Ok(())
}

/// One joint of the backward pass (the borrowed slices of `Data`).
struct Backward<'d> {
    /// First dof of the joint; one past the last dof of its subtree; `nv` of the model.
    iv: usize,
    end: usize,
    nv: usize,
    ia: &'d Mat6,
    parent_ia: Option<&'d mut Mat6>,
    J: &'d [Twist],
    armature: &'d [f64],
    ud: &'d mut [Wrench],
    p: &'d mut [Wrench],
    minv: &'d mut [f64],
}

impl Backward<'_> {
    /// The joint's rows of M⁻¹ on its subtree's columns, its `P` columns and `I^a` to the
    /// parent, for a joint of `M` degrees of freedom.
    #[inline(always)]
    fn run<const M: usize>(self) -> Result<(), MultibodyError> {
        let (iv, nv) = (self.iv, self.nv);
        let J: &[Twist; M] = self.J[iv..iv + M].try_into().expect("joint columns");
        let U: [Wrench; M] = std::array::from_fn(|a| mat6_twist(self.ia, &J[a]));
        let mut D = [[0.0; M]; M];
        for a in 0..M {
            for b in 0..=a {
                let x = J[a].dot(&U[b]);
                D[a][b] = x;
                D[b][a] = x;
            }
            D[a][a] += self.armature[iv + a];
        }
        let Dinv = spd_inverse(&D).ok_or(MultibodyError::NotPositiveDefinite)?;
        // U D⁻¹ (D⁻¹ symmetric)
        let UD: [Wrench; M] = std::array::from_fn(|a| {
            let mut w = Wrench::zero();
            for b in 0..M {
                w += U[b] * Dinv[b][a];
            }
            w
        });
        self.ud[iv..iv + M].copy_from_slice(&UD);
        // own columns: M⁻¹(i, i) = D⁻¹, P(:, i) = U D⁻¹ (assigned: nothing stale survives)
        self.p[iv..iv + M].copy_from_slice(&UD);
        for (a, row) in Dinv.iter().enumerate() {
            self.minv[(iv + a) * nv + iv..(iv + a) * nv + iv + M].copy_from_slice(row);
        }
        // descendants' columns: M⁻¹(i, s) = -D⁻¹ Jᵀ P(:, s), P(:, s) += U M⁻¹(i, s)
        let (s0, s1) = (iv + M, self.end);
        if M == 1 {
            let (J0, U0, d) = (J[0], U[0], Dinv[0][0]);
            let row = &mut self.minv[iv * nv + s0..iv * nv + s1];
            for (m, P) in row.iter_mut().zip(&mut self.p[s0..s1]) {
                let y = -d * J0.dot(P);
                *m = y;
                *P += U0 * y;
            }
        } else {
            for s in s0..s1 {
                let P = self.p[s];
                let x: [f64; M] = std::array::from_fn(|a| J[a].dot(&P));
                let mut dP = Wrench::zero();
                for a in 0..M {
                    let mut y = 0.0;
                    for b in 0..M {
                        y -= Dinv[a][b] * x[b];
                    }
                    self.minv[(iv + a) * nv + s] = y;
                    dP += U[a] * y;
                }
                self.p[s] = P + dP;
            }
        }
        // I^A_λ += I^A_i - U D⁻¹ Uᵀ, by its upper triangle (kept exactly symmetric)
        if let Some(pia) = self.parent_ia {
            let ia: &[f64; 36] = self.ia.as_slice().try_into().expect("6x6");
            let out: &mut [f64; 36] = pia.as_mut_slice().try_into().expect("6x6");
            let ud: [[f64; 6]; M] = std::array::from_fn(|a| wrench_array(&UD[a]));
            let u: [[f64; 6]; M] = std::array::from_fn(|a| wrench_array(&U[a]));
            for c in 0..6 {
                for r in 0..=c {
                    let mut x = ia[c * 6 + r];
                    for a in 0..M {
                        x -= ud[a][r] * u[a][c];
                    }
                    out[c * 6 + r] += x;
                    if r != c {
                        out[r * 6 + c] += x;
                    }
                }
            }
        }
        Ok(())
    }
}

/// One joint of the last pass (the borrowed slices of `Data`).
struct Forward<'d> {
    /// First dof of the joint; one past the last dof of its subtree; `nv` of the model.
    iv: usize,
    end: usize,
    nv: usize,
    J: &'d [Twist],
    ud: &'d [Wrench],
    /// `A_λ(:, c)` of the parent for every column (`None` for a root: `A_world = 0`).
    parent_a: Option<&'d [Twist]>,
    /// `A_i(:, c)`, written for `c ≥ iv` (unless the joint is a leaf).
    a: &'d mut [Twist],
    leaf: bool,
    minv: &'d mut [f64],
}

impl Forward<'_> {
    /// `M⁻¹(i, c) -= (U D⁻¹)ᵀ A_λ(:, c)` and `A_i(:, c) = A_λ(:, c) + J_i M⁻¹(i, c)` for
    /// `c ≥ iv`, for a joint of `M` degrees of freedom. Columns past the subtree start from 0.
    #[inline(always)]
    fn run<const M: usize>(self) {
        let (iv, nv, split) = (self.iv, self.nv, self.end - self.iv);
        let (ain, aout) = self.a[iv..nv].split_at_mut(split);
        for k in 0..M {
            let (J, UD) = (self.J[iv + k], self.ud[iv + k]);
            let row = &mut self.minv[(iv + k) * nv + iv..(iv + k + 1) * nv];
            let (inside, outside) = row.split_at_mut(split);
            // the first dof assigns A_i (no copy of A_λ first), the others add to it
            match self.parent_a {
                // a leaf: nobody reads its A_i
                Some(pa) if self.leaf => {
                    let (pin, pout) = pa[iv..nv].split_at(split);
                    for (m, Ap) in inside.iter_mut().zip(pin) {
                        *m -= Ap.dot(&UD);
                    }
                    for (m, Ap) in outside.iter_mut().zip(pout) {
                        *m = -Ap.dot(&UD);
                    }
                }
                Some(pa) => {
                    let (pin, pout) = pa[iv..nv].split_at(split);
                    for ((m, Ap), Ai) in inside.iter_mut().zip(pin).zip(ain.iter_mut()) {
                        let y = *m - Ap.dot(&UD);
                        *m = y;
                        *Ai = if k == 0 { *Ap } else { *Ai } + J * y;
                    }
                    for ((m, Ap), Ai) in outside.iter_mut().zip(pout).zip(aout.iter_mut()) {
                        let y = -Ap.dot(&UD);
                        *m = y;
                        *Ai = if k == 0 { *Ap } else { *Ai } + J * y;
                    }
                }
                None => {
                    for (m, Ai) in inside.iter().zip(ain.iter_mut()) {
                        *Ai = if k == 0 { Twist::zero() } else { *Ai } + J * *m;
                    }
                    outside.fill(0.0);
                    if k == 0 {
                        aout.fill(Twist::zero());
                    }
                }
            }
        }
    }
}

/// `(m, f)` as six numbers.
#[inline(always)]
fn wrench_array(w: &Wrench) -> [f64; 6] {
    [w.m.x, w.m.y, w.m.z, w.f.x, w.f.y, w.f.z]
}

/// The inverse of a small symmetric positive-definite matrix by Cholesky, `D = L Lᵀ`,
/// `D⁻¹ = L⁻ᵀ L⁻¹`; `None` unless every pivot is positive and finite.
#[inline(always)]
fn spd_inverse<const M: usize>(D: &[[f64; M]; M]) -> Option<[[f64; M]; M]> {
    if M == 1 {
        let d = D[0][0];
        return (d > 0.0 && d.is_finite()).then(|| [[1.0 / d; M]; M]);
    }
    let mut L = [[0.0; M]; M];
    for j in 0..M {
        let s = D[j][j] - dot(&L[j][..j], &L[j][..j]);
        if !(s > 0.0 && s.is_finite()) {
            return None;
        }
        let l = s.sqrt();
        L[j][j] = l;
        for i in j + 1..M {
            L[i][j] = (D[i][j] - dot(&L[i][..j], &L[j][..j])) / l;
        }
    }
    // L⁻¹, lower triangular
    let mut Li = [[0.0; M]; M];
    for j in 0..M {
        Li[j][j] = 1.0 / L[j][j];
        for i in j + 1..M {
            let mut s = 0.0;
            for k in j..i {
                s += L[i][k] * Li[k][j];
            }
            Li[i][j] = -s / L[i][i];
        }
    }
    let mut X = [[0.0; M]; M];
    for a in 0..M {
        for b in 0..=a {
            let s: f64 = Li[a..].iter().map(|r| r[a] * r[b]).sum();
            X[a][b] = s;
            X[b][a] = s;
        }
    }
    Some(X)
}

/// `Σ x_k y_k`.
#[inline(always)]
fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}
