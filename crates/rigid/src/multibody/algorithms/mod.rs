//! The recursive algorithms, one file each. All take `(model, data, inputs...)`, check the inputs
//! (lengths, finiteness, unit quaternions) and write into `data`.

mod aba;
mod centroidal;
mod cholesky;
mod coriolis;
mod crba;
pub mod derivatives;
mod energy;
mod jacobian;
mod kinematics;
mod minverse;
mod rnea;

pub(crate) use aba::check_inputs as check_aba_inputs;
pub use aba::{aba, aba_with_external};
pub use centroidal::{
    centroidal_momentum, centroidal_momentum_matrix, jacobian_center_of_mass,
    subtree_centers_of_mass, KinematicLevel,
};
pub use cholesky::forward_dynamics_cholesky;
pub(crate) use cholesky::{ltl_factor, ltl_solve_lower, ltl_solve_transposed, NONE as NO_DOF};
pub use coriolis::coriolis_matrix;
pub use crba::crba;
pub use derivatives::{
    aba_derivatives, aba_derivatives_with_external, frame_kinematics_derivatives,
    gravity_derivatives, joint_kinematics_derivatives, rnea_derivatives,
    rnea_derivatives_with_external, AbaDerivatives, Derivatives, KinematicsDerivatives,
    RneaDerivatives,
};
pub use energy::{center_of_mass, kinetic_energy, potential_energy};
pub use jacobian::{
    compute_joint_jacobians, compute_joint_jacobians_time_variation, frame_jacobian,
    frame_jacobian_time_variation, joint_jacobian, joint_jacobian_time_variation,
    stored_frame_jacobian, stored_joint_jacobian, ReferenceFrame,
};
pub use kinematics::{
    forward_kinematics, forward_kinematics_q, forward_kinematics_qv, update_frame_placements,
};
pub use minverse::compute_minverse;
pub(crate) use minverse::minverse_unchecked;
pub(crate) use rnea::check_fext;
pub use rnea::{gravity_torques, nonlinear_effects, rnea, rnea_with_external};

use super::joint::Shape;
use super::plan::PlacementKind;
use super::Model;
use crate::mass::SpatialInertia;
use crate::spatial::{compose, mat3_vec, rotate_about_sc, trig, Mat3, Transform, Twist, Vec3};

/// `S_i x_i = Σ_k S_k x_k` over the degrees of freedom of joint `i` (child frame), with `S` the
/// motion-subspace columns at the current `q` (`Data::S`).
#[inline]
pub(crate) fn joint_motion(model: &Model, S: &[Twist], i: usize, x: &[f64]) -> Twist {
    let r = model.joints()[i].dofs();
    let mut t = Twist::zero();
    for (S, xk) in S[r.clone()].iter().zip(&x[r]) {
        t += *S * *xk;
    }
    t
}

/// Writes `S(q)` of the joints whose motion subspace depends on `q` (`Plan::variable_subspace`)
/// into `S`; the other columns are constant and `Data::new` set them. The first thing every
/// algorithm that reads `Data::S` does.
#[inline]
pub(crate) fn update_subspaces(model: &Model, q: &[f64], S: &mut [Twist]) {
    for &i in &model.plan().variable_subspace {
        let j = &model.joints()[i];
        j.kind.subspace(&q[j.coordinates()], &mut S[j.dofs()]);
    }
}

/// `c_J = Ṡ q̇` of joint `i`, or `None` when its motion subspace is constant (then `c_J = 0`).
#[inline(always)]
pub(crate) fn joint_bias(model: &Model, i: usize, q: &[f64], v: &[f64]) -> Option<Twist> {
    if !model.plan().varies[i] {
        return None;
    }
    let j = &model.joints()[i];
    Some(j.kind.bias(&q[j.coordinates()], &v[j.dofs()]))
}

/// `Err(Unsupported)` naming the first joint whose motion subspace depends on `q`, for the
/// algorithms that assume a constant `S` in body coordinates (the analytical derivatives, `J̇`
/// and the Coriolis matrix).
pub(crate) fn require_constant_subspaces(
    model: &Model,
    algorithm: &'static str,
) -> Result<(), crate::multibody::MultibodyError> {
    match model.plan().variable_subspace.first() {
        Some(&i) => Err(crate::multibody::MultibodyError::Unsupported {
            joint: model.joints()[i].name.clone(),
            kind: model.joints()[i].kind.name(),
            algorithm,
        }),
        None => Ok(()),
    }
}

/// For a one-dof joint whose motion subspace is a coordinate axis (`S = s e_c`, angular first,
/// `Model::dof_axis`): `(c, s x_i)`, the one nonzero component of the joint twist `S x_i`.
#[inline(always)]
pub(crate) fn axis_motion(model: &Model, i: usize, x: &[f64]) -> Option<(usize, f64)> {
    let j = &model.joints()[i];
    if j.nv != 1 {
        return None;
    }
    model.plan().dof_axis[j.idx_v].map(|(c, s)| (c, s * x[j.idx_v]))
}

/// `T + x e_c`: adds the joint twist of [`axis_motion`] (component `c`, angular first).
#[inline(always)]
pub(crate) fn add_axis(T: &mut Twist, c: usize, x: f64) {
    if c < 3 {
        T.w[c] += x;
    } else {
        T.v[c - 3] += x;
    }
}

/// `[ad_V] (x e_c)` = [`Twist::cross`] with the joint twist of [`axis_motion`], written out:
/// `(ω × w, v × w)` for an angular `w = x e_c`, `(0, ω × u)` for a linear `u = x e_(c-3)`
/// (4 products instead of 18).
#[inline(always)]
pub(crate) fn cross_axis(V: &Twist, c: usize, x: f64) -> Twist {
    // a × (x e_k)
    fn cross_e(a: &Vec3, k: usize, x: f64) -> Vec3 {
        match k {
            0 => Vec3::new(0.0, a.z * x, -(a.y * x)),
            1 => Vec3::new(-(a.z * x), 0.0, a.x * x),
            _ => Vec3::new(a.y * x, -(a.x * x), 0.0),
        }
    }
    if c < 3 {
        Twist::new(cross_e(&V.w, c, x), cross_e(&V.v, c, x))
    } else {
        Twist::new(Vec3::zeros(), cross_e(&V.w, c - 3, x))
    }
}

/// The first pass of [`crba`], [`compute_minverse`] and [`rnea_derivatives`]: every body posed
/// in the frame {r} of its
/// tree's root body (the body moved by a joint without a parent), `rMi = rM_{λ(i)} liMi` with
/// `rM_root = 1`, its joint columns `J_k = [Ad_{rMi}] S_k` into `J` and its inertia
/// `rG_i = [Ad_{rMi⁻¹}]ᵀ G_i [Ad_{rMi⁻¹}]` into `G`. The sines and cosines of the angles it
/// turns by (`Model::chain_angles`) are computed first, several at a time (four per AVX2
/// register, else two), into `sc` (indexed by `q`'s entries), so that they are off the chain's
/// critical path.
///
/// `M` and `M⁻¹` pair twists with wrenches, so any frame common to a tree gives them, and trees
/// share no dof. In the root body's frame the root's columns are its constant `S` and its `q` is
/// not used (`M` does not depend on it), its children's placements are their `liMi` (no
/// composition), and a revolute joint whose `X_T` has no rotation turns two columns of `R_λ`
/// instead of a 3x3 product (when `R_T` is a signed permutation, a URDF `rpy` in multiples of
/// π/2, `R_λ R_T` picks and signs columns first; when it turns about one coordinate axis, as
/// UR5's `rpy="0 1.570796325 0"`, `R_λ R_T` turns two columns too), and an unrotated prismatic
/// joint keeps `R_λ` (one whose `X_T` turns about a coordinate axis takes `R_λ R_T` by two
/// columns, `p = p_λ + R_λ t + R a q`).
/// Revolute, prismatic and free-flyer columns skip the products with the zeros of `S`. Each
/// non-root body's inertia is moved by its [`PrincipalForm`](crate::mass::PrincipalForm)
/// (≈ 86 operations against ≈ 136 for `(R I) Rᵀ` and the shift), or by the adjoint congruence
/// when it has none.
#[inline(always)]
pub(crate) fn root_frame_bodies(
    model: &Model,
    q: &[f64],
    rM: &mut [Transform],
    J: &mut [Twist],
    G: &mut [SpatialInertia],
    sc: &mut [[f64; 2]],
) {
    let plan = model.plan();
    let joints = model.joints();
    trig::sin_cos_at(q, &plan.chain_angles, sc);
    for (i, j) in joints.iter().enumerate() {
        // the joint's precomputed (sin q, cos q): read only by the arms `reads_chain_angle` names
        let angle = || {
            debug_assert!(
                plan.reads_chain_angle(joints, i),
                "joint {i} has no precomputed angle"
            );
            let [s, c] = sc[j.idx_q];
            (s, c)
        };
        let shape = j.kind.shape();
        let rMi = match j.parent {
            None => {
                G[i] = model.inertias()[i];
                J[j.dofs()].copy_from_slice(&plan.dof_S[j.dofs()]);
                rM[i] = Transform::identity();
                if !j.kind.constant_subspace() {
                    j.kind.subspace(&q[j.coordinates()], &mut J[j.dofs()]);
                }
                continue;
            }
            // a root's child: rMi = liMi = X_T X_J(q)
            Some(p) if joints[p.0].parent.is_none() => match shape {
                Shape::Revolute(axis) => {
                    let (s, c) = angle();
                    Transform::new(
                        rotate_about_sc(&j.placement.rotation, &axis, s, c),
                        j.placement.translation,
                    )
                }
                Shape::Prismatic(_) | Shape::FreeFlyer | Shape::General => {
                    parent_placement(model, i, q)
                }
            },
            Some(p) => {
                let rMp = &rM[p.0];
                let t = plan.placement_translation[i];
                match (shape, plan.placement[i]) {
                    // X_T without rotation: R_λ exp([a] q) turns two columns of R_λ
                    (Shape::Revolute(axis), PlacementKind::Identity) => {
                        let (s, c) = angle();
                        Transform::new(
                            rotate_about_sc(&rMp.rotation, &axis, s, c),
                            t.rotated(&rMp.rotation) + rMp.translation,
                        )
                    }
                    // R_T a signed permutation: R_λ R_T picks and signs columns of R_λ
                    (Shape::Revolute(axis), PlacementKind::SignedPermutation(perm)) => {
                        let R = &rMp.rotation;
                        let RT = Mat3::from_columns(&[
                            R.column(perm[0].0) * perm[0].1,
                            R.column(perm[1].0) * perm[1].1,
                            R.column(perm[2].0) * perm[2].1,
                        ]);
                        let (s, c) = angle();
                        Transform::new(
                            rotate_about_sc(&RT, &axis, s, c),
                            t.rotated(R) + rMp.translation,
                        )
                    }
                    // R_T a turn about e_k: R_λ R_T turns two columns of R_λ, then the joint two
                    (
                        Shape::Revolute(axis),
                        PlacementKind::AxisTurn {
                            axis: e,
                            s: sT,
                            c: cT,
                        },
                    ) => {
                        let (s, c) = angle();
                        let RT = rotate_about_sc(&rMp.rotation, &e, sT, cT);
                        Transform::new(
                            rotate_about_sc(&RT, &axis, s, c),
                            t.rotated(&rMp.rotation) + rMp.translation,
                        )
                    }
                    // the same for a prismatic joint: R = R_λ R_T, p = p_λ + R_λ t + R (a q)
                    (
                        Shape::Prismatic(axis),
                        PlacementKind::AxisTurn {
                            axis: e,
                            s: sT,
                            c: cT,
                        },
                    ) => {
                        let R = rotate_about_sc(&rMp.rotation, &e, sT, cT);
                        let p = t.rotated(&rMp.rotation)
                            + mat3_vec(&R, &(axis * q[j.idx_q]))
                            + rMp.translation;
                        Transform::new(R, p)
                    }
                    // X_T without rotation: R = R_λ, p = p_λ + R_λ (t + a q)
                    (Shape::Prismatic(axis), PlacementKind::Identity) => Transform::new(
                        rMp.rotation,
                        mat3_vec(
                            &rMp.rotation,
                            &(j.placement.translation + axis * q[j.idx_q]),
                        ) + rMp.translation,
                    ),
                    (Shape::Revolute(_), PlacementKind::General)
                    | (
                        Shape::Prismatic(_),
                        PlacementKind::SignedPermutation(_) | PlacementKind::General,
                    )
                    | (Shape::FreeFlyer | Shape::General, _) => {
                        compose(rMp, &parent_placement(model, i, q))
                    }
                }
            }
        };
        rM[i] = rMi;
        G[i] = match &plan.principal[i] {
            Some(form) => form.transformed(&rMi),
            None => model.inertias()[i].transformed(&rMi),
        };
        match shape {
            // S = (a, 0): J = (R a, p × R a), without the product R 0 of the general path
            Shape::Revolute(axis) => {
                let w = match plan.dof_axis[j.idx_v] {
                    Some((c, s)) => rMi.rotation.column(c) * s, // R (s e_c)
                    None => mat3_vec(&rMi.rotation, &axis),
                };
                J[j.idx_v] = Twist::new(w, rMi.translation.cross(&w));
            }
            // S = (0, a): J = (0, R a)
            Shape::Prismatic(axis) => {
                let u = match plan.dof_axis[j.idx_v] {
                    Some((c, s)) => rMi.rotation.column(c - 3) * s, // R (s e_(c-3))
                    None => mat3_vec(&rMi.rotation, &axis),
                };
                J[j.idx_v] = Twist::new(Vec3::zeros(), u);
            }
            // S_k = (e_k, 0) for k < 3, (0, e_(k-3)) after: columns of R, no products
            Shape::FreeFlyer => {
                let (R, p) = (&rMi.rotation, &rMi.translation);
                for c in 0..3 {
                    let r: Vec3 = R.column(c).into();
                    J[j.idx_v + c] = Twist::new(r, p.cross(&r));
                    J[j.idx_v + 3 + c] = Twist::new(Vec3::zeros(), r);
                }
            }
            Shape::General => {
                let Jj = &mut J[j.dofs()];
                Jj.copy_from_slice(&plan.dof_S[j.dofs()]);
                if !j.kind.constant_subspace() {
                    j.kind.subspace(&q[j.coordinates()], Jj);
                }
                for Jk in Jj {
                    *Jk = rMi.act_twist(Jk);
                }
            }
        }
    }
}

/// `liMi = X_T X_J(q_i)`: the pose of body i in its parent (one match on the joint type).
/// Always inlined: out of line, the 96-byte `Transform` goes back through memory.
#[inline(always)]
pub(crate) fn parent_placement(model: &Model, i: usize, q: &[f64]) -> Transform {
    let j = &model.joints()[i];
    j.kind
        .placed_transform(&j.placement, &q[j.idx_q..j.idx_q + j.nq])
}

#[cfg(test)]
mod tests {
    use super::{add_axis, cross_axis};
    use crate::spatial::{Twist, Vec3};

    /// The written-out `[ad_V] (x e_c)` and `T + x e_c` equal the general cross product and sum
    /// with the twist `x e_c`, for every coordinate axis (angular and linear) and both signs.
    #[test]
    fn axis_twist_products_equal_the_general_ones() {
        let V = Twist::new(Vec3::new(0.3, -1.2, 0.7), Vec3::new(-0.4, 0.9, 1.5));
        for c in 0..6 {
            for x in [0.8, -2.5] {
                let mut e = [0.0; 6];
                e[c] = x;
                let S = Twist::new(Vec3::new(e[0], e[1], e[2]), Vec3::new(e[3], e[4], e[5]));
                let d = (cross_axis(&V, c, x) - V.cross(&S)).to_vector();
                assert!(d.amax() < 1e-15, "cross, axis {c}: {d}");
                let mut T = V;
                add_axis(&mut T, c, x);
                assert!(((T - (V + S)).to_vector()).amax() < 1e-15, "sum, axis {c}");
            }
        }
    }
}
