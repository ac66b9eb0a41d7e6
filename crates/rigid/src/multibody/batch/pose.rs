//! A joint's pose in its parent per lane, `liMi = X_T X_J(q)` (Featherstone's `jcalc`): the
//! general [`X`] ([`placement`]) and, for a revolute joint about a coordinate axis with an
//! unrotated `X_T`, the cheaper [`Turn`]; RNEA and ABA take either as a [`Pose`], chosen per
//! joint by [`fresh_pose`] and [`kept_pose`].

use super::lanes::{L, M3, T6, V3, X};
use super::pack::{read_lane, Pack, I6};
use crate::multibody::{JointType, Model};
use crate::spatial::{trig, Mat3, Transform, Vec3};

/// `liMi = X_T X_J(q_i)` of joint `i` per lane (Featherstone's `jcalc`). Revolute, prismatic and
/// free-flyer joints in lanes; the other joints one lane at a time through
/// [`JointType::placed_transform`].
#[inline(always)]
pub(crate) fn placement<const W: usize>(model: &Model, i: usize, q: &[L<W>]) -> X<W> {
    let j = &model.joints()[i];
    let T = &j.placement;
    let iq = j.idx_q;
    match j.kind {
        JointType::Revolute { axis } => {
            let (s, c) = trig::sin_cos_lanes(q[iq].0);
            X {
                r: rotate_about(&M3::splat(&T.rotation), &axis, L(s), L(c)),
                p: V3::splat(&T.translation),
            }
        }
        JointType::Prismatic { axis } => X {
            r: M3::splat(&T.rotation),
            // R_T (a q) + t_T, in the single call's order (not (R_T a) q)
            p: V3::c_mat(&T.rotation, &V3::c_scale(&axis, q[iq])) + V3::splat(&T.translation),
        },
        JointType::FreeFlyer => {
            let r = quat_to_rot(q[iq + 3], q[iq + 4], q[iq + 5], q[iq + 6]);
            let p = V3([q[iq], q[iq + 1], q[iq + 2]]);
            if T.rotation == Mat3::identity() {
                X {
                    r,
                    p: p + V3::splat(&T.translation),
                }
            } else {
                X {
                    r: M3::c_mul(&T.rotation, &r),
                    p: V3::c_mat(&T.rotation, &p) + V3::splat(&T.translation),
                }
            }
        }
        JointType::Spherical
        | JointType::Planar
        | JointType::Helical { .. }
        | JointType::Universal { .. } => {
            let mut out = X::identity();
            let mut ql = [0.0; 7];
            for l in 0..W {
                read_lane(&q[j.coordinates()], l, &mut ql[..j.nq]);
                let m = j.kind.placed_transform(T, &ql[..j.nq]);
                for r in 0..3 {
                    for c in 0..3 {
                        out.r.0[r][c].0[l] = m.rotation[(r, c)];
                    }
                    out.p.0[r].0[l] = m.translation[r];
                }
            }
            out
        }
    }
}

/// What RNEA and ABA do with a joint's pose in its parent `liMi = (R, p)`: [`X`] in general,
/// [`Turn`] when `R` turns about a coordinate axis.
pub(crate) trait Pose<const W: usize> {
    /// `[Ad_{X⁻¹}] T`, a twist of the parent frame in the child frame.
    fn inv_act(&self, t: &T6<W>) -> T6<W>;
    /// `[Ad_X]⁻ᵀ F`, a wrench of the child frame in the parent frame.
    fn act_wrench(&self, f: &T6<W>) -> T6<W>;
    /// The blocks of a 6x6 inertia turned, `(R A Rᵀ, R B Rᵀ, R C Rᵀ)`, `A` and `C` symmetric.
    fn turn_inertia(&self, i: &I6<W>) -> I6<W>;
    /// `p`.
    fn translation(&self) -> &V3<W>;
    /// Lane `l` as a [`Transform`] (the single call's `data.parent_placements`).
    fn lane(&self, l: usize) -> Transform;
}

impl<const W: usize> Pose<W> for X<W> {
    #[inline(always)]
    fn inv_act(&self, t: &T6<W>) -> T6<W> {
        X::inv_act(self, t)
    }
    #[inline(always)]
    fn act_wrench(&self, f: &T6<W>) -> T6<W> {
        X::act_wrench(self, f)
    }
    #[inline(always)]
    fn turn_inertia(&self, i: &I6<W>) -> I6<W> {
        let r = &self.r;
        I6 {
            a: r.mul(&i.a).mul_tr_sym(r),
            b: r.mul(&i.b).mul_tr(r),
            c: r.mul(&i.c).mul_tr_sym(r),
        }
    }
    #[inline(always)]
    fn translation(&self) -> &V3<W> {
        &self.p
    }
    fn lane(&self, l: usize) -> Transform {
        X::lane(self, l)
    }
}

/// `$body` with `$X` bound to joint `$i`'s pose at the pack `$p`'s `q`, made for the forward
/// pass: a [`Turn`] for the joints of `Plan::turn` (its sine and cosine kept in `$p.sc`), else
/// [`placement`]'s [`X`] (kept in `$p.X`).
macro_rules! fresh_pose {
    ($model:expr, $p:expr, $i:expr, |$X:ident| $body:expr) => {
        match $model.plan().turn[$i] {
            Some((0, sign)) => {
                let $X = &$p.turn::<0>($model, $i, sign);
                $body
            }
            Some((1, sign)) => {
                let $X = &$p.turn::<1>($model, $i, sign);
                $body
            }
            // `Plan::turn`'s axes are 0, 1, 2
            Some((_, sign)) => {
                let $X = &$p.turn::<2>($model, $i, sign);
                $body
            }
            None => {
                let x = $crate::multibody::batch::pose::placement($model, $i, &$p.q);
                $p.X[$i].set(&x);
                let $X = &x;
                $body
            }
        }
    };
}

/// `$body` with `$X` bound to joint `$i`'s pose as [`fresh_pose`] kept it in the pack `$p`.
macro_rules! kept_pose {
    ($model:expr, $p:expr, $i:expr, |$X:ident| $body:expr) => {
        match $model.plan().turn[$i] {
            Some((0, _)) => {
                let $X =
                    &$crate::multibody::batch::pose::Turn::<_, 0>::kept($model, $i, &$p.sc[$i]);
                $body
            }
            Some((1, _)) => {
                let $X =
                    &$crate::multibody::batch::pose::Turn::<_, 1>::kept($model, $i, &$p.sc[$i]);
                $body
            }
            // `Plan::turn`'s axes are 0, 1, 2
            Some(_) => {
                let $X =
                    &$crate::multibody::batch::pose::Turn::<_, 2>::kept($model, $i, &$p.sc[$i]);
                $body
            }
            None => {
                let $X = &$p.X[$i];
                $body
            }
        }
    };
}
pub(super) use {fresh_pose, kept_pose};

/// `liMi = (Rot_K(θ), p)` per lane, of a revolute joint about `±e_K` whose `X_T` has no rotation
/// (`Plan::turn`): `sin θ` (the axis's sign folded in), `cos θ` and `p = t_T`. `R x` and `Rᵀ x`
/// turn the components `j, l = K + 1, K + 2 (mod 3)` with 4 products where [`X`]'s matrix takes
/// 9, and `R` is not composed. The numbers are [`placement`]'s (its product of `R_T = 1` and the
/// turn, and its matrix products with `R`, only add zeros).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Turn<const W: usize, const K: usize> {
    s: L<W>,
    c: L<W>,
    p: V3<W>,
}

impl<const W: usize> Pack<W> {
    /// Joint `i`'s pose as a [`Turn`] about `sign e_K` at the pack's `q`, its `(sin θ, cos θ)`
    /// kept for [`Turn::kept`].
    #[inline(always)]
    pub(crate) fn turn<const K: usize>(
        &mut self,
        model: &Model,
        i: usize,
        sign: f64,
    ) -> Turn<W, K> {
        let (s, c) = trig::sin_cos_lanes(self.q[model.joints()[i].idx_q].0);
        self.sc[i] = [L(s) * sign, L(c)];
        Turn::kept(model, i, &self.sc[i])
    }
}

impl<const W: usize, const K: usize> Turn<W, K> {
    /// Joint `i`'s pose from the `(sin θ, cos θ)` [`Pack::turn`] kept.
    #[inline(always)]
    pub(crate) fn kept(model: &Model, i: usize, sc: &[L<W>; 2]) -> Self {
        Self {
            s: sc[0],
            c: sc[1],
            p: V3::splat(&model.joints()[i].placement.translation),
        }
    }

    /// `R x`: `(c x_j − s x_l, s x_j + c x_l)` in components `j, l`.
    #[inline(always)]
    fn mul_v(&self, x: &V3<W>) -> V3<W> {
        let (j, l) = ((K + 1) % 3, (K + 2) % 3);
        let mut y = *x;
        y.0[j] = self.c * x.0[j] - self.s * x.0[l];
        y.0[l] = self.s * x.0[j] + self.c * x.0[l];
        y
    }

    /// `Rᵀ x`: `(c x_j + s x_l, c x_l − s x_j)` in components `j, l`.
    #[inline(always)]
    fn tr_mul_v(&self, x: &V3<W>) -> V3<W> {
        let (j, l) = ((K + 1) % 3, (K + 2) % 3);
        let mut y = *x;
        y.0[j] = self.c * x.0[j] + self.s * x.0[l];
        y.0[l] = self.c * x.0[l] - self.s * x.0[j];
        y
    }

    /// `R M Rᵀ`: rows `j, l` of `M` turned, then its columns `j, l`.
    #[inline(always)]
    fn conjugate(&self, m: &M3<W>) -> M3<W> {
        let (j, l, c, s) = ((K + 1) % 3, (K + 2) % 3, self.c, self.s);
        let mut y = *m;
        for t in 0..3 {
            y.0[j][t] = c * m.0[j][t] - s * m.0[l][t];
            y.0[l][t] = s * m.0[j][t] + c * m.0[l][t];
        }
        let rm = y;
        for t in 0..3 {
            y.0[t][j] = c * rm.0[t][j] - s * rm.0[t][l];
            y.0[t][l] = s * rm.0[t][j] + c * rm.0[t][l];
        }
        y
    }

    /// [`Turn::conjugate`] of a symmetric `M`, its lower triangle copied to the upper (as
    /// [`M3::mul_tr_sym`]).
    #[inline(always)]
    fn conjugate_sym(&self, m: &M3<W>) -> M3<W> {
        let mut y = self.conjugate(m);
        for r in 1..3 {
            for c in 0..r {
                y.0[c][r] = y.0[r][c];
            }
        }
        y
    }
}

impl<const W: usize, const K: usize> Pose<W> for Turn<W, K> {
    /// `(Rᵀ ω, Rᵀ (v − p × ω))`, as [`X::inv_act`].
    #[inline(always)]
    fn inv_act(&self, t: &T6<W>) -> T6<W> {
        T6 {
            w: self.tr_mul_v(&t.w),
            v: self.tr_mul_v(&(t.v - self.p.cross(&t.w))),
        }
    }

    /// `(R m + p × R f, R f)`, as [`X::act_wrench`].
    #[inline(always)]
    fn act_wrench(&self, f: &T6<W>) -> T6<W> {
        let rf = self.mul_v(&f.v);
        T6 {
            w: self.mul_v(&f.w) + self.p.cross(&rf),
            v: rf,
        }
    }

    #[inline(always)]
    fn turn_inertia(&self, i: &I6<W>) -> I6<W> {
        I6 {
            a: self.conjugate_sym(&i.a),
            b: self.conjugate(&i.b),
            c: self.conjugate_sym(&i.c),
        }
    }

    #[inline(always)]
    fn translation(&self) -> &V3<W> {
        &self.p
    }

    /// `R` is the identity but for `R_jj = R_ll = c`, `R_lj = s = −R_jl`.
    fn lane(&self, l: usize) -> Transform {
        let (j, k) = ((K + 1) % 3, (K + 2) % 3);
        let (s, c) = (self.s.0[l], self.c.0[l]);
        let mut r = Mat3::identity();
        r[(j, j)] = c;
        r[(k, k)] = c;
        r[(k, j)] = s;
        r[(j, k)] = -s;
        let p = &self.p.0;
        Transform::new(r, Vec3::new(p[0].0[l], p[1].0[l], p[2].0[l]))
    }
}

/// `R exp([a] q)` per lane given `s = sin q`, `c = cos q`: for `a = ±e_k` two columns of `R`
/// turn, otherwise `R` times Rodrigues' formula
/// ([`rotate_about_sc`](crate::spatial::rotate_about_sc)).
#[inline(always)]
pub(crate) fn rotate_about<const W: usize>(r: &M3<W>, a: &Vec3, s: L<W>, c: L<W>) -> M3<W> {
    // columns j and k turn: u' = u c + w s, w' = w c - u s
    #[inline(always)]
    fn turn<const W: usize>(r: &M3<W>, j: usize, k: usize, s: L<W>, c: L<W>) -> M3<W> {
        let mut out = *r;
        for t in 0..3 {
            let (u, w) = (r.0[t][j], r.0[t][k]);
            out.0[t][j] = u * c + w * s;
            out.0[t][k] = w * c - u * s;
        }
        out
    }
    if a.x == 0.0 && a.y == 0.0 {
        turn(r, 0, 1, s * a.z, c)
    } else if a.y == 0.0 && a.z == 0.0 {
        turn(r, 1, 2, s * a.x, c)
    } else if a.x == 0.0 && a.z == 0.0 {
        turn(r, 2, 0, s * a.y, c)
    } else {
        let t = L::splat(1.0) - c;
        let (x, y, z) = (a.x, a.y, a.z);
        // in the order of the single call's `rodrigues`
        let rod = M3([
            [c + t * x * x, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, c + t * y * y, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, c + t * z * z],
        ]);
        r.mul(&rod)
    }
}

/// The rotation of the unit quaternion `(x, y, z, w)` per lane
/// ([`quat_to_rot`](crate::spatial::quat_to_rot)).
#[inline(always)]
fn quat_to_rot<const W: usize>(x: L<W>, y: L<W>, z: L<W>, w: L<W>) -> M3<W> {
    let n2 = x * x + y * y + z * z + w * w;
    let s = n2.map(|n| 2.0 / n);
    let (xx, yy, zz) = (x * x * s, y * y * s, z * z * s);
    let (xy, xz, yz) = (x * y * s, x * z * s, y * z * s);
    let (wx, wy, wz) = (w * x * s, w * y * s, w * z * s);
    let one = L::splat(1.0);
    M3([
        [one - yy - zz, xy - wz, xz + wy],
        [xy + wz, one - xx - zz, yz - wx],
        [xz - wy, yz + wx, one - xx - yy],
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multibody::Rng;

    fn lanes(rng: &mut Rng) -> L<2> {
        L([rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)])
    }

    fn v3(rng: &mut Rng) -> V3<2> {
        V3([lanes(rng), lanes(rng), lanes(rng)])
    }

    /// A random twist and a random 6x6 inertia's blocks (`A`, `C` symmetric).
    fn moved_things(rng: &mut Rng) -> (T6<2>, I6<2>) {
        let mut m3 = || M3([[(); 3]; 3].map(|r| r.map(|()| lanes(rng))));
        let (a, b, c) = (m3(), m3(), m3());
        let t = T6 {
            w: v3(rng),
            v: v3(rng),
        };
        let i = I6 {
            a: a.mul_tr_sym(&a),
            b,
            c: c.mul_tr_sym(&c),
        };
        (t, i)
    }

    /// What `x` makes of `t` (as a twist and as a wrench) and of the inertia `i`, entry by entry.
    fn numbers(x: &impl Pose<2>, t: &T6<2>, i: &I6<2>) -> Vec<L<2>> {
        let (a, b, y) = (x.inv_act(t), x.act_wrench(t), x.turn_inertia(i));
        [a.w, a.v, b.w, b.v]
            .iter()
            .flat_map(|v| v.0)
            .chain([y.a, y.b, y.c].iter().flat_map(|m| m.0.concat()))
            .collect()
    }

    /// A [`Turn`] about `±e_K` gives [`placement`]'s pose's numbers (the rotation about that
    /// axis composed with `R_T = 1`) bit for bit, up to the sign of zeros (`==`): twists,
    /// wrenches and inertias moved.
    fn turn_is_the_pose<const K: usize>(sign: f64) {
        let mut rng = Rng::new(7 + K as u64);
        for _ in 0..20 {
            let (s, c) = trig::sin_cos_lanes(lanes(&mut rng).0.map(|x| 3.0 * x));
            let p = v3(&mut rng);
            let turn = Turn::<2, K> {
                s: L(s) * sign,
                c: L(c),
                p,
            };
            let axis = Vec3::ith(K, sign);
            let x = X {
                r: rotate_about(&M3::splat(&Mat3::identity()), &axis, L(s), L(c)),
                p,
            };
            let (t, i) = moved_things(&mut rng);
            assert_eq!(
                numbers(&turn, &t, &i),
                numbers(&x, &t, &i),
                "K {K}, sign {sign}"
            );
            for l in 0..2 {
                assert_eq!(turn.lane(l), x.lane(l), "K {K}, sign {sign}, lane {l}");
            }
        }
    }

    #[test]
    fn turns_give_the_general_poses_numbers() {
        for sign in [1.0, -1.0] {
            turn_is_the_pose::<0>(sign);
            turn_is_the_pose::<1>(sign);
            turn_is_the_pose::<2>(sign);
        }
    }

    /// On a built model, `Plan::turn` marks exactly the revolute joints about `±e_K` with an
    /// unrotated `X_T`, for each axis and sign, and what `fresh_pose!` and `kept_pose!` give
    /// them (`Pack::turn`'s sign, the kept sine and cosine) moves twists, wrenches and inertias
    /// as `placement` does, up to the sign of zeros; the other joints get `placement` itself.
    #[test]
    fn the_plan_and_the_macros_give_turns_the_placements_numbers() {
        use crate::mass::{RotationalInertia, SpatialInertia};
        use crate::multibody::ModelBuilder;
        use crate::spatial::Transform;
        let g = SpatialInertia::from_com(
            1.2,
            Vec3::new(0.1, -0.2, 0.05),
            RotationalInertia::new(0.3, 0.2, 0.4, 0.01, 0.02, -0.03),
        );
        let mut b = ModelBuilder::new("turns");
        let mut parent = None;
        let mut want = Vec::new();
        for (n, k) in [0, 1, 2, 0, 1, 2].into_iter().enumerate() {
            let sign = if n < 3 { 1.0 } else { -1.0 };
            let at = Vec3::new(0.1 * n as f64, -0.2, 0.3);
            // every other joint's X_T also turns a little: no Turn
            let rotated = n % 2 == 1 && k == 2;
            let t = if rotated {
                Transform::new(crate::spatial::so3::exp(&Vec3::new(0.0, 0.0, 0.3)), at)
            } else {
                Transform::from_translation(at)
            };
            let axis = Vec3::ith(k, sign);
            parent = Some(
                b.add_joint(parent, &format!("j{n}"), JointType::Revolute { axis }, t, g)
                    .unwrap(),
            );
            want.push((!rotated).then_some((k, sign)));
        }
        let model = b.build().unwrap();
        assert_eq!(model.plan().turn, want);
        let mut p = Pack::<2>::new(&model);
        let mut rng = Rng::new(11);
        for q in &mut p.q {
            *q = lanes(&mut rng) * 3.0;
        }
        let (t, i6) = moved_things(&mut rng);
        for i in 0..model.njoints() {
            let want = numbers(&placement(&model, i, &p.q), &t, &i6);
            let fresh = fresh_pose!(&model, p, i, |X| numbers(X, &t, &i6));
            let kept = kept_pose!(&model, p, i, |X| numbers(X, &t, &i6));
            assert_eq!(fresh, want, "joint {i}: fresh pose");
            assert_eq!(kept, want, "joint {i}: kept pose");
        }
    }
}
