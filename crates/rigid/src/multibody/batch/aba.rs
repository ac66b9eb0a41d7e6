//! ABA on a pack of `W` states: [`aba`](crate::multibody::aba)'s three passes (Featherstone
//! 2008, Table 7.1), every quantity a lane vector, the articulated inertias in 3x3 blocks.

use super::lanes::{L, M3, T6, V3};
use super::pack::{momentum, s_dot, Pack, I6};
use super::pose::{fresh_pose, kept_pose, Pose};
use crate::mass::SpatialInertia;
use crate::multibody::{Data, Model, MultibodyError};
use crate::spatial::{Transform, Twist, Wrench};

/// `q̈ = FD(q, v, τ)` for the pack's states: `q`, `v`, `x = τ` in, `out = q̈`.
///
/// 1. i = 1..n: `V_i = [Ad_{liMi⁻¹}] V_λ + S_i q̇_i`, `c_i = V_i × S_i q̇_i + c_J`,
///    `I^A_i = G_i`, `p^A_i = V_i ×* G_i V_i`;
/// 2. i = n..1: `U_i = I^A_i S_i`, `D_i = S_iᵀ U_i + armature`, `u_i = τ_i − S_iᵀ p^A_i`, and
///    with `I^a = I^A_i − U_i D_i⁻¹ U_iᵀ`, `p^a = p^A_i + I^a c_i + U_i D_i⁻¹ u_i`:
///    `I^A_λ += X* I^a X⁻¹`, `p^A_λ += X* p^a` (`X = [Ad_{liMi}]`);
/// 3. i = 1..n: `a_i = [Ad_{liMi⁻¹}] a_λ + c_i` (`a_0 = -g`), `q̈_i = D_i⁻¹ (u_i − U_iᵀ a_i)`,
///    `a_i += S_i q̈_i`.
///
/// With `fext`, the wrench `fext[i]` (body i's frame, the same in every lane) acts on body i:
/// `p^A_i −= F_i^ext`.
///
/// # Errors
/// [`MultibodyError::NotPositiveDefinite`] when some `D_i` is not positive in some lane (a
/// massless subtree, as the single call says).
#[inline(always)]
pub(super) fn aba<const W: usize>(
    model: &Model,
    p: &mut Pack<W>,
    fext: Option<&[Wrench]>,
    mut keep: Option<&mut Keep>,
) -> Result<(), MultibodyError> {
    let joints = model.joints();
    p.update_subspaces(model);
    for (i, j) in joints.iter().enumerate() {
        let mut V = fresh_pose!(model, p, i, |X| match j.parent {
            Some(par) => X.inv_act(&p.V[par.0]),
            None => T6::zero(),
        });
        let mut c = p.joint_velocity(model, i, &mut V);
        if let Some(cJ) = p.joint_bias(model, i) {
            c += cJ;
        }
        let G = &model.inertias()[i];
        p.IA[i] = I6::from_inertia(G);
        p.F[i] = V.cross_star(&momentum(G, &V));
        if let Some(f) = fext {
            p.F[i] = p.F[i] - T6::splat_wrench(&f[i]);
        }
        p.V[i] = V;
        p.A[i] = c;
    }
    for i in (0..joints.len()).rev() {
        let j = &joints[i];
        let iv = j.idx_v;
        let (head, tail) = p.IA.split_at_mut(i);
        let IA = &mut tail[0];
        let pA = p.F[i];
        let mut pa = pA;
        // U = I^A S (a column of I^A for a coordinate-axis S_k), u = τ − Sᵀ p^A
        for k in j.dofs() {
            p.U[k] = match model.plan().dof_axis[k] {
                Some((c, s)) => IA.col(c).scale(L::splat(s)),
                None => IA.mul(&p.S[k]),
            };
            p.u[k] = p.x[k] - s_dot(model, &p.S, k, &pA);
        }
        let n = j.nv;
        if n == 1 {
            // one dof: D = Sᵀ U + armature and its inverse are lane scalars
            let D = s_dot(model, &p.S, iv, &p.U[iv]) + model.armature()[iv];
            positive(D)?;
            let dinv = D.map(|x| 1.0 / x);
            p.Dinv[i][0] = dinv;
            if let Some(k) = keep.as_deref_mut() {
                k.d_inv_1[iv] = dinv.0[0];
            }
            if j.parent.is_some() {
                let U = p.U[iv];
                IA.sub_outer(&U, &U.scale(dinv));
                pa += U.scale(dinv * p.u[iv]);
            }
        } else {
            // D = Sᵀ U + armature (nv x nv, row-major)
            let mut D = [L::zero(); 36];
            for a in 0..n {
                for b in 0..n {
                    D[a * n + b] = s_dot(model, &p.S, iv + a, &p.U[iv + b]);
                }
                D[a * n + a] += model.armature()[iv + a];
            }
            let Dinv = spd_inverse(&D, n)?;
            p.Dinv[i] = Dinv;
            if j.parent.is_some() {
                // I^a = I^A − Σ_a U_a (Σ_b D⁻¹_ab U_b)ᵀ, p^a = p^A + Σ_a U_a (Σ_b D⁻¹_ab u_b)
                for a in 0..n {
                    let mut Wa = T6::zero();
                    let mut s = L::zero();
                    for b in 0..n {
                        Wa += p.U[iv + b].scale(Dinv[a * n + b]);
                        s += Dinv[a * n + b] * p.u[iv + b];
                    }
                    IA.sub_outer(&p.U[iv + a], &Wa);
                    pa += p.U[iv + a].scale(s);
                }
            }
        }
        if let Some(par) = j.parent {
            // I^A now holds I^a; p^a += I^a c; both moved to the parent
            pa += IA.mul(&p.A[i]);
            let f = kept_pose!(model, p, i, |X| {
                head[par.0].add_congruence(IA, X);
                X.act_wrench(&pa)
            });
            p.F[par.0] += f;
        }
    }
    let a_world = T6 {
        w: V3::zero(),
        v: V3::splat(&-model.gravity()),
    };
    for (i, j) in joints.iter().enumerate() {
        let iv = j.idx_v;
        let a_parent = match j.parent {
            Some(par) => &p.A[par.0],
            None => &a_world,
        };
        let mut a = kept_pose!(model, p, i, |X| {
            if let Some(k) = keep.as_deref_mut() {
                k.placements[i] = X.lane(0);
            }
            X.inv_act(a_parent)
        }) + p.A[i];
        let n = j.nv;
        if n == 1 {
            p.out[iv] = p.Dinv[i][0] * (p.u[iv] - p.U[iv].dot(&a));
        } else {
            let mut r = [L::zero(); 6];
            for (b, rb) in r[..n].iter_mut().enumerate() {
                *rb = p.u[iv + b] - p.U[iv + b].dot(&a);
            }
            for a_ in 0..n {
                let mut x = L::zero();
                for (b, rb) in r[..n].iter().enumerate() {
                    x += p.Dinv[i][a_ * n + b] * *rb;
                }
                p.out[iv + a_] = x;
            }
        }
        p.add_joint_twist(model, i, &p.out, &mut a);
        p.A[i] = a;
        if let Some(k) = keep.as_deref_mut() {
            k.velocities[i] = p.V[i].lane(0);
            k.accelerations[i] = a.lane(0);
            for d in j.dofs() {
                k.ddq[d] = p.out[d].0[0];
            }
        }
    }
    Ok(())
}

/// Where the single call keeps lane 0's results, written by the passes while they are at hand:
/// `D⁻¹` of the one-dof joints (the backward pass, so that a joint below one where the
/// recursion fails still has it); each joint's pose in its parent, the body twists and
/// accelerations (gravity as the base acceleration) and `q̈` (the last pass).
pub(super) struct Keep<'a> {
    placements: &'a mut [Transform],
    velocities: &'a mut [Twist],
    accelerations: &'a mut [Twist],
    ddq: &'a mut [f64],
    d_inv_1: &'a mut [f64],
}

/// The single call [`aba`](crate::multibody::aba): this kernel at one lane, in `data`'s own
/// pack, so that a single call and a batch give the same bits. Leaves `data.ddq` and what ABA
/// fills besides it: `parent_placements`, `velocities`, `accelerations_gravity` (with gravity as
/// the base acceleration), `S`, and each one-dof joint's `D⁻¹` (`d_inv_1`). The inputs were
/// checked.
///
/// # Errors
/// As the kernel.
pub(crate) fn aba_one(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: Option<&[Wrench]>,
) -> Result<(), MultibodyError> {
    let p = &mut data.one;
    p.gather(0, 0, q, v, tau);
    let mut keep = Keep {
        placements: &mut data.parent_placements,
        velocities: &mut data.velocities,
        accelerations: &mut data.accelerations_gravity,
        ddq: data.ddq.as_mut_slice(),
        d_inv_1: &mut data.d_inv_1,
    };
    aba(model, p, fext, Some(&mut keep))?;
    for &i in &model.plan().variable_subspace {
        for k in model.joints()[i].dofs() {
            data.S[k] = p.S[k].lane(0);
        }
    }
    Ok(())
}

/// `Ok` when every lane of `d` is positive (not NaN), else
/// [`MultibodyError::NotPositiveDefinite`].
#[inline(always)]
fn positive<const W: usize>(d: L<W>) -> Result<(), MultibodyError> {
    let mut ok = true;
    for x in d.0 {
        ok &= x > 0.0;
    }
    if ok {
        Ok(())
    } else {
        Err(MultibodyError::NotPositiveDefinite)
    }
}

/// `D⁻¹` of a symmetric positive definite `n x n` matrix per lane (row-major), by Gauss-Jordan
/// elimination without pivoting (whose pivots are the Schur complements, positive for such a
/// matrix).
///
/// # Errors
/// [`MultibodyError::NotPositiveDefinite`] when a pivot is not positive (or NaN) in some lane.
#[inline(always)]
fn spd_inverse<const W: usize>(D: &[L<W>; 36], n: usize) -> Result<[L<W>; 36], MultibodyError> {
    let mut m = *D;
    let mut inv = [L::zero(); 36];
    for k in 0..n {
        inv[k * n + k] = L::splat(1.0);
    }
    for k in 0..n {
        let piv = m[k * n + k];
        if piv
            .0
            .iter()
            .any(|x| x.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater))
        {
            return Err(MultibodyError::NotPositiveDefinite);
        }
        let r = piv.map(|x| 1.0 / x);
        for j in 0..n {
            m[k * n + j] *= r;
            inv[k * n + j] *= r;
        }
        for i in (0..n).filter(|&i| i != k) {
            let f = m[i * n + k];
            for j in 0..n {
                let (mk, ik) = (m[k * n + j], inv[k * n + j]);
                m[i * n + j] -= f * mk;
                inv[i * n + j] -= f * ik;
            }
        }
    }
    Ok(inv)
}

impl<const W: usize> I6<W> {
    /// The constant body inertia `(m, h, I_O)` as `[[I_O, [h]×], [[h]×ᵀ, m 1]]`.
    #[inline(always)]
    fn from_inertia(G: &SpatialInertia) -> Self {
        let h = G.first_moment();
        let m = G.mass();
        let hx = crate::spatial::Mat3::new(0.0, -h.z, h.y, h.z, 0.0, -h.x, -h.y, h.x, 0.0);
        Self {
            a: M3::splat(G.inertia_origin_matrix()),
            b: M3::splat(&hx),
            c: M3::splat(&(crate::spatial::Mat3::identity() * m)),
        }
    }

    /// `I T = (A ω + B v, Bᵀ ω + C v)`.
    #[inline(always)]
    fn mul(&self, t: &T6<W>) -> T6<W> {
        T6 {
            w: self.a.mul_v(&t.w) + self.b.mul_v(&t.v),
            v: self.b.tr_mul_v(&t.w) + self.c.mul_v(&t.v),
        }
    }

    /// Column `c` (angular first).
    #[inline(always)]
    fn col(&self, c: usize) -> T6<W> {
        if c < 3 {
            T6 {
                w: self.a.col(c),
                v: V3(self.b.0[c]),
            }
        } else {
            T6 {
                w: self.b.col(c - 3),
                v: self.c.col(c - 3),
            }
        }
    }

    /// `I −= U Wᵀ` (the blocks of the 6x6 outer product).
    #[inline(always)]
    fn sub_outer(&mut self, u: &T6<W>, w: &T6<W>) {
        for r in 0..3 {
            for c in 0..3 {
                self.a.0[r][c] -= u.w.0[r] * w.w.0[c];
                self.b.0[r][c] -= u.w.0[r] * w.v.0[c];
                self.c.0[r][c] -= u.v.0[r] * w.v.0[c];
            }
        }
    }

    /// `I += X* J X⁻¹` for `X = [Ad_{(R, p)}]`: `J`, an inertia of the child frame, moved to the
    /// parent frame and added. Turned first, `(A, B, C) ← (R A Rᵀ, R B Rᵀ, R C Rᵀ)`
    /// ([`Pose::turn_inertia`]), then moved by `p`: `C' = C`, `B' = B + [p] C`,
    /// `A' = A − B [p] + [p] B'ᵀ`.
    #[inline(always)]
    fn add_congruence(&mut self, j: &Self, x: &impl Pose<W>) {
        let I6 { a, b, c } = x.turn_inertia(j);
        let p = x.translation();
        let mut bn = b;
        for k in 0..3 {
            let pc = p.cross(&c.col(k));
            for i in 0..3 {
                bn.0[i][k] += pc.0[i];
            }
        }
        let mut an = a;
        for i in 0..3 {
            let e = p.cross(&V3(b.0[i])); // −(B [p]) row i
            let h = p.cross(&V3(bn.0[i])); // ([p] B'ᵀ) column i
            for k in 0..3 {
                an.0[i][k] += e.0[k];
                an.0[k][i] += h.0[k];
            }
        }
        for r in 0..3 {
            for k in 0..3 {
                self.a.0[r][k] += an.0[r][k];
                self.b.0[r][k] += bn.0[r][k];
                self.c.0[r][k] += c.0[r][k];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::I6;
    use crate::multibody::batch::lanes::{M3, V3, X};
    use crate::spatial::{so3, Mat3, Mat6, Transform, Vec3};

    /// `I6::add_congruence` adds `[Ad_{T⁻¹}]ᵀ I [Ad_{T⁻¹}]` (the dense product) to what it
    /// holds, on a general symmetric 6x6 (an articulated inertia has no spatial-inertia
    /// structure), for a general pose and one about a coordinate axis.
    #[test]
    fn add_congruence_adds_the_dense_product() {
        let A = Mat6::from_fn(|r, c| ((r * 7 + c * 3) % 5) as f64 * 0.1 - 0.2);
        let I = A * A.transpose() + Mat6::identity();
        let blocks = |m: &Mat6| I6::<1> {
            a: M3::splat(&m.fixed_view::<3, 3>(0, 0).into()),
            b: M3::splat(&m.fixed_view::<3, 3>(0, 3).into()),
            c: M3::splat(&m.fixed_view::<3, 3>(3, 3).into()),
        };
        let start = Mat6::from_fn(|r, c| (r + c) as f64 * 0.01);
        for w in [Vec3::new(0.3, -1.1, 0.7), Vec3::new(0.0, 0.0, -2.3)] {
            let T = Transform::new(so3::exp(&w), Vec3::new(0.4, -0.2, 0.9));
            let X = T.inverse().adjoint();
            let want = start + X.transpose() * I * X;
            let mut got = blocks(&start);
            let pose = X::<1> {
                r: M3::splat(&T.rotation),
                p: V3::splat(&T.translation),
            };
            got.add_congruence(&blocks(&I), &pose);
            let get = |m: &M3<1>| Mat3::from_fn(|r, c| m.0[r][c].0[0]);
            let (a, b, c) = (get(&got.a), get(&got.b), get(&got.c));
            let tol = 1e-12 * want.amax();
            assert!((a - want.fixed_view::<3, 3>(0, 0)).amax() < tol, "{w}: A");
            assert!((b - want.fixed_view::<3, 3>(0, 3)).amax() < tol, "{w}: B");
            assert!((c - want.fixed_view::<3, 3>(3, 3)).amax() < tol, "{w}: C");
        }
    }
}
