//! A pack of `W` states: the workspace of the lane kernels ([`Pack`]), the states moved in and out
//! of it (row-major arrays transposed to one lane per state), and what every kernel needs of a
//! joint, per lane, besides its pose (`pose.rs`): its motion subspace `S(q)` and the joint twist
//! `S q̇` with its bias terms.

use super::derivatives::DerivPack;
use super::lanes::{Aligned, L, M3, S3, T6, V3, X};
use super::rows::Mirror;
use crate::mass::SpatialInertia;
use crate::multibody::Model;
use crate::spatial::Mat3;

/// The workspace of one pack of `W` states, made once per model (see
/// [`Batch`](super::Batch)): the inputs and output transposed to lanes, and each algorithm's
/// per-joint quantities, each buffer starting on a cache line ([`Aligned`]).
#[derive(Clone, Debug)]
pub(crate) struct Pack<const W: usize> {
    /// `q` (nq lanes), `v` and the third input (`a` or `τ`), and the `nv` outputs.
    pub(crate) q: Aligned<L<W>>,
    pub(crate) v: Aligned<L<W>>,
    pub(crate) x: Aligned<L<W>>,
    pub(crate) out: Aligned<L<W>>,
    /// `S_k` per degree of freedom, in the child frame (the constant ones set once).
    pub(crate) S: Aligned<T6<W>>,
    /// Per joint: `liMi` (RNEA, ABA: of the joints without a
    /// [`Turn`](super::pose::Turn)), the body's twist `V_i`, acceleration `A_i` (RNEA: with gravity; ABA:
    /// the bias `c_i` then the acceleration), wrench `F_i` (ABA: `p^A_i`).
    pub(crate) X: Aligned<X<W>>,
    pub(crate) V: Aligned<T6<W>>,
    pub(crate) A: Aligned<T6<W>>,
    pub(crate) F: Aligned<T6<W>>,
    /// CRBA: per joint the pose in its tree's root frame and the composite inertia there; per
    /// dof the column `J_k` and the force `F_k = Ic J_k` in that frame; `M`'s lower triangle,
    /// packed by columns, and where the full matrices' entries are in it.
    pub(crate) rX: Aligned<X<W>>,
    pub(crate) Ic: Aligned<I3<W>>,
    pub(crate) J: Aligned<T6<W>>,
    pub(crate) Fk: Aligned<T6<W>>,
    pub(crate) M: Aligned<L<W>>,
    pub(crate) mirror: Mirror,
    /// Sines and cosines of joint angles, as each kernel keeps them (a kernel writes the entries
    /// it reads before it reads them, so the two uses do not meet): RNEA and ABA, per joint with
    /// a [`Turn`](super::pose::Turn) (`Plan::turn`), `(s sin θ, cos θ)` of its pose about
    /// `s e_K`, for the backward passes; CRBA and the RNEA derivatives, `(sin θ, cos θ)` per
    /// revolute joint below a root's child whose `X_T` is not a general rotation
    /// ([`turn_angles`](super::crba::turn_angles)).
    pub(crate) sc: Aligned<[L<W>; 2]>,
    /// ABA: per joint the articulated inertia `I^A_i` and `D⁻¹` (`nv x nv`, row-major); per
    /// dof `U_k = I^A S_k` and `u_k = τ_k − S_kᵀ p^A`.
    pub(crate) IA: Aligned<I6<W>>,
    pub(crate) Dinv: Aligned<[L<W>; 36]>,
    pub(crate) U: Aligned<T6<W>>,
    pub(crate) u: Aligned<L<W>>,
    /// The RNEA derivatives' workspace, made on their first call.
    pub(crate) deriv: Option<Box<DerivPack<W>>>,
}

impl<const W: usize> Pack<W> {
    /// The workspace for `model`.
    pub(crate) fn new(model: &Model) -> Self {
        let (n, nq, nv) = (model.njoints(), model.nq(), model.nv());
        let z = L::zero();
        Self {
            q: Aligned::new(z, nq),
            v: Aligned::new(z, nv),
            x: Aligned::new(z, nv),
            out: Aligned::new(z, nv),
            S: {
                let mut S = Aligned::new(T6::zero(), nv);
                for (Sk, c) in S.iter_mut().zip(&model.plan().dof_S) {
                    *Sk = T6::splat(c);
                }
                S
            },
            X: Aligned::new(X::identity(), n),
            V: Aligned::new(T6::zero(), n),
            A: Aligned::new(T6::zero(), n),
            F: Aligned::new(T6::zero(), n),
            sc: Aligned::new([z; 2], n),
            rX: Aligned::new(X::identity(), n),
            Ic: Aligned::new(I3::zero(), n),
            J: Aligned::new(T6::zero(), nv),
            Fk: Aligned::new(T6::zero(), nv),
            M: Aligned::new(z, nv * (nv + 1) / 2),
            mirror: Mirror::of(model),
            IA: Aligned::new(I6::zero(), n),
            Dinv: Aligned::new([z; 36], n),
            U: Aligned::new(T6::zero(), nv),
            u: Aligned::new(z, nv),
            deriv: None,
        }
    }

    /// Whether this workspace has the shape of `model`'s.
    pub(crate) fn fits(&self, model: &Model) -> bool {
        self.q.len() == model.nq() && self.v.len() == model.nv() && self.X.len() == model.njoints()
    }

    /// Lane `l` of the inputs from state `k` of the row-major inputs (`vs` and `xs` may be
    /// empty).
    #[inline(always)]
    pub(crate) fn gather(&mut self, l: usize, k: usize, qs: &[f64], vs: &[f64], xs: &[f64]) {
        let (nq, nv) = (self.q.len(), self.v.len());
        for (y, x) in self.q.iter_mut().zip(&qs[k * nq..][..nq]) {
            y.0[l] = *x;
        }
        if !vs.is_empty() {
            for (y, x) in self.v.iter_mut().zip(&vs[k * nv..][..nv]) {
                y.0[l] = *x;
            }
        }
        if !xs.is_empty() {
            for (y, x) in self.x.iter_mut().zip(&xs[k * nv..][..nv]) {
                y.0[l] = *x;
            }
        }
    }

    /// `S(q)` per lane for the joints whose motion subspace depends on `q` (the others were set
    /// by [`Pack::new`]).
    #[inline(always)]
    pub(crate) fn update_subspaces(&mut self, model: &Model) {
        let mut q = [0.0; 7];
        let mut S = [crate::spatial::Twist::zero(); 6];
        for &i in &model.plan().variable_subspace {
            let j = &model.joints()[i];
            for l in 0..W {
                read_lane(&self.q[j.coordinates()], l, &mut q[..j.nq]);
                j.kind.subspace(&q[..j.nq], &mut S[..j.nv]);
                for (k, Sk) in S[..j.nv].iter().enumerate() {
                    set_lane(&mut self.S[j.idx_v + k], l, Sk);
                }
            }
        }
    }

    /// `S_i v_i` of joint `i`, the joint twist (per lane), with `S` as [`Pack::update_subspaces`]
    /// left it: a column that is a coordinate axis `s e_c` (`Plan::dof_axis`: a revolute or
    /// prismatic axis, a free-flyer's or spherical joint's columns) adds `s v_k` to component
    /// `c`, any other column `S_k v_k`.
    #[inline(always)]
    pub(crate) fn joint_twist(&self, model: &Model, i: usize, v: &[L<W>]) -> T6<W> {
        let mut t = T6::zero();
        for k in model.joints()[i].dofs() {
            match model.plan().dof_axis[k] {
                Some((c, s)) => *t.get_mut(c) += v[k] * s,
                None => t += self.S[k].scale(v[k]),
            }
        }
        t
    }

    /// `t += S_i x_i` (joint `i`'s twist for the rates `x` added): one component for a one-dof
    /// joint whose `S` is a coordinate axis `s e_c`, else [`Pack::joint_twist`] added.
    #[inline(always)]
    pub(crate) fn add_joint_twist(&self, model: &Model, i: usize, x: &[L<W>], t: &mut T6<W>) {
        let j = &model.joints()[i];
        if j.nv == 1 {
            if let Some((c, s)) = model.plan().dof_axis[j.idx_v] {
                *t.get_mut(c) += x[j.idx_v] * s;
                return;
            }
        }
        *t += self.joint_twist(model, i, x);
    }

    /// The velocity step of a forward pass: `V += S_i q̇_i`, and `V × S_i q̇_i` returned
    /// (Featherstone's `crm(v) vJ`), by [`T6::cross_axis`] for a one-dof joint whose `S` is a
    /// coordinate axis.
    #[inline(always)]
    pub(crate) fn joint_velocity(&self, model: &Model, i: usize, V: &mut T6<W>) -> T6<W> {
        let j = &model.joints()[i];
        if j.nv == 1 {
            if let Some((c, s)) = model.plan().dof_axis[j.idx_v] {
                let x = self.v[j.idx_v] * s;
                *V.get_mut(c) += x;
                return V.cross_axis(c, x);
            }
        }
        let vJ = self.joint_twist(model, i, &self.v);
        *V += vJ;
        V.cross(&vJ)
    }

    /// `c_J = Ṡ q̇` of joint `i` per lane, or `None` when its motion subspace is constant.
    #[inline(always)]
    pub(crate) fn joint_bias(&self, model: &Model, i: usize) -> Option<T6<W>> {
        if !model.plan().varies[i] {
            return None;
        }
        let j = &model.joints()[i];
        let (mut q, mut v) = ([0.0; 7], [0.0; 6]);
        let mut out = T6::zero();
        for l in 0..W {
            read_lane(&self.q[j.coordinates()], l, &mut q[..j.nq]);
            read_lane(&self.v[j.dofs()], l, &mut v[..j.nv]);
            set_lane(&mut out, l, &j.kind.bias(&q[..j.nq], &v[..j.nv]));
        }
        Some(out)
    }
}

/// `S_kᵀ F` of degree of freedom `k` (per lane), with the motion subspaces `S` of [`Pack::S`]:
/// `s F_c` for a column `s e_c` (`Plan::dof_axis`), else the dot product.
#[inline(always)]
pub(crate) fn s_dot<const W: usize>(model: &Model, S: &[T6<W>], k: usize, F: &T6<W>) -> L<W> {
    match model.plan().dof_axis[k] {
        Some((c, s)) => F.get(c) * s,
        None => S[k].dot(F),
    }
}

/// Lane `l` of `src` into `dst`.
#[inline(always)]
pub(super) fn read_lane<const W: usize>(src: &[L<W>], l: usize, dst: &mut [f64]) {
    for (d, x) in dst.iter_mut().zip(src) {
        *d = x.0[l];
    }
}

/// Lane `l` of `t` set to the twist `x`.
#[inline(always)]
fn set_lane<const W: usize>(t: &mut T6<W>, l: usize, x: &crate::spatial::Twist) {
    for c in 0..3 {
        t.w.0[c].0[l] = x.w[c];
        t.v.0[c].0[l] = x.v[c];
    }
}

/// `G T` of a body's constant spatial inertia `G = (m, h, I_O)` (mass, first moment `h = m c`,
/// rotational inertia about the frame origin) and a twist per lane:
/// `(I_O ω + h × v, m v − h × ω)` ([`SpatialInertia::momentum`]).
#[inline(always)]
pub(crate) fn momentum<const W: usize>(G: &SpatialInertia, t: &T6<W>) -> T6<W> {
    let h = G.first_moment();
    T6 {
        w: V3::c_mat(G.inertia_origin_matrix(), &t.w) + V3::c_cross(&h, &t.v),
        v: t.v.scale(L::splat(G.mass())) - V3::c_cross(&h, &t.w),
    }
}

/// A spatial inertia per lane `(m, h, I_O)`: mass, first moment, rotational inertia about the
/// frame origin (CRBA's composite inertias in the world frame), 10 lane vectors.
#[derive(Clone, Copy, Debug)]
pub(crate) struct I3<const W: usize> {
    pub(crate) m: L<W>,
    pub(crate) h: V3<W>,
    pub(crate) i: S3<W>,
}

impl<const W: usize> I3<W> {
    /// A constant inertia in every lane.
    pub(crate) fn splat(g: &SpatialInertia) -> Self {
        Self {
            m: L::splat(g.mass()),
            h: V3::splat(&g.first_moment()),
            i: S3::splat(g.inertia_origin_matrix()),
        }
    }

    pub(crate) fn zero() -> Self {
        Self {
            m: L::zero(),
            h: V3::zero(),
            i: S3([L::zero(); 6]),
        }
    }
}

impl<const W: usize> std::ops::AddAssign<&I3<W>> for I3<W> {
    /// The inertia of two bodies rigidly joined, both in the same frame (entry by entry, as
    /// [`SpatialInertia`]'s `+=`), `y` borrowed (a copy of its 10 lane vectors would be a call to
    /// `memcpy`).
    #[inline(always)]
    fn add_assign(&mut self, y: &Self) {
        self.m += y.m;
        self.h += y.h;
        self.i += &y.i;
    }
}

/// A symmetric 6x6 inertia per lane in blocks, angular first: `[[A, B], [Bᵀ, C]]` (ABA's
/// articulated inertias).
#[derive(Clone, Copy, Debug)]
pub(crate) struct I6<const W: usize> {
    pub(crate) a: M3<W>,
    pub(crate) b: M3<W>,
    pub(crate) c: M3<W>,
}

impl<const W: usize> I6<W> {
    pub(crate) fn zero() -> Self {
        let z = M3::splat(&Mat3::zeros());
        Self { a: z, b: z, c: z }
    }
}
