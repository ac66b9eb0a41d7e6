//! The generalised momentum `p = M(q) v` and the configuration gradient of the kinetic energy
//! at fixed velocity, `∇_q K(q, v)`, in one O(n) pass each way: what a variational integrator
//! needs, with no mass matrix.
//!
//! With `H_i = Σ_{j ⪰ i} [Ad_{iMj}]⁻ᵀ G_j V_j` the momentum of the subtree of body i in its
//! frame, `(M v)_k = S_kᵀ H_i + armature_k v_k`. Moving joint i's configuration on the right,
//! `q_i ← q_i exp(η)`, turns `X_J` into `X_J exp(S_i η)`, so the twist of body i changes by
//! `δV_i = [ad_{W_i}] S_i η` with `W_i = V_i - S_i v_i` (the parent's twist seen in body i) and
//! the subtree follows rigidly: `δK = H_iᵀ δV_i`, hence `(∇_q K)_k = S_kᵀ [ad_{W_i}]ᵀ H_i`
//! (left-trivialised; the ordinary partial derivative for a 1-dof joint). A free-flyer root has
//! `W = 0`: `K` does not depend on where the robot is, the symmetry behind momentum
//! conservation.

use crate::multibody::algorithms::{joint_motion, parent_placement, update_subspaces};
use crate::multibody::{Data, Model};
use crate::spatial::{Twist, Wrench};

/// `p = M(q) v` and, if `grad` is given, `∇_q K(q, v)` (see the module documentation).
/// Uses `data.parent_placements`, `data.velocities`, `data.c_bias` (the `W_i`) and
/// `data.forces` (the `H_i`). `q` and `v` are not checked (the simulator checks its state).
pub(crate) fn momentum(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    p: &mut [f64],
    mut grad: Option<&mut [f64]>,
) {
    let n = model.njoints();
    update_subspaces(model, q, &mut data.S);
    for i in 0..n {
        let liMi = parent_placement(model, i, q);
        data.parent_placements[i] = liMi;
        let W = match model.joints()[i].parent {
            Some(pj) => liMi.inv_act_twist(&data.velocities[pj.0]),
            None => Twist::zero(),
        };
        let V = W + joint_motion(model, &data.S, i, v);
        data.c_bias[i] = W;
        data.velocities[i] = V;
        data.forces[i] = model.inertias()[i].momentum(&V);
    }
    for i in (0..n).rev() {
        let j = &model.joints()[i];
        let H = data.forces[i];
        let adH = match grad {
            Some(_) => data.c_bias[i].ad_transpose(&H),
            None => Wrench::zero(),
        };
        for k in j.idx_v..j.idx_v + j.nv {
            let S = &data.S[k];
            p[k] = S.dot(&H) + model.armature[k] * v[k];
            if let Some(g) = grad.as_deref_mut() {
                g[k] = S.dot(&adH);
            }
        }
        if let Some(pj) = j.parent {
            let Hp = data.parent_placements[i].act_wrench(&H);
            data.forces[pj.0] += Hp;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multibody::{crba, integrate, kinetic_energy, random_configuration, Rng};

    fn tree() -> Model {
        use crate::mass::{RotationalInertia, SpatialInertia};
        use crate::multibody::{JointType, ModelBuilder};
        use crate::spatial::{so3, Transform, Vec3};
        let mut rng = Rng::new(11);
        let mut b = ModelBuilder::new("t");
        let body = |rng: &mut Rng| {
            SpatialInertia::from_com(
                rng.uniform(0.5, 2.0),
                Vec3::new(rng.uniform(-0.3, 0.3), 0.1, rng.uniform(-0.3, 0.3)),
                RotationalInertia::diagonal(0.05, 0.06, 0.08),
            )
        };
        let place = |rng: &mut Rng| {
            Transform::new(
                so3::exp(&Vec3::new(rng.uniform(-1.0, 1.0), 0.4, -0.3)),
                Vec3::new(0.2, rng.uniform(-0.5, 0.5), 0.3),
            )
        };
        let f = b
            .add_joint(
                None,
                "f",
                JointType::FreeFlyer,
                place(&mut rng),
                body(&mut rng),
            )
            .unwrap();
        let s = b
            .add_joint(
                Some(f),
                "s",
                JointType::Spherical,
                place(&mut rng),
                body(&mut rng),
            )
            .unwrap();
        let axis = Vec3::new(0.3, -0.5, 0.8);
        b.add_joint(
            Some(s),
            "r",
            JointType::Revolute { axis },
            place(&mut rng),
            body(&mut rng),
        )
        .unwrap();
        b.add_joint(
            Some(f),
            "p",
            JointType::Planar,
            place(&mut rng),
            body(&mut rng),
        )
        .unwrap();
        let pr = b
            .add_joint(
                Some(f),
                "x",
                JointType::Prismatic { axis },
                place(&mut rng),
                body(&mut rng),
            )
            .unwrap();
        b.set_armature(pr, &[0.3]).unwrap();
        b.build().unwrap()
    }

    /// `p = M v` against CRBA, and `∇_q K` against central differences of `K(q ⊕ ε e_k, v)`.
    #[test]
    fn momentum_and_gradient_match_crba_and_finite_differences() {
        let model = tree();
        let mut data = Data::new(&model);
        let mut rng = Rng::new(2);
        let q = random_configuration(&model, &mut rng);
        let nv = model.nv();
        let v: Vec<f64> = (0..nv).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let (mut p, mut g) = (vec![0.0; nv], vec![0.0; nv]);
        momentum(&model, &mut data, &q, &v, &mut p, Some(&mut g));
        let m = crba(&model, &mut data, &q).unwrap().clone();
        let mv = &m * nalgebra::DVector::from_column_slice(&v);
        let e = p
            .iter()
            .zip(mv.iter())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(e < 1e-12, "M v: {e:e}");
        let eps = 1e-6;
        let mut qe = vec![0.0; model.nq()];
        for k in 0..nv {
            let mut dk = vec![0.0; nv];
            dk[k] = 1.0;
            integrate(&model, &q, &dk, eps, &mut qe).unwrap();
            let kp = kinetic_energy(&model, &mut data, &qe, &v).unwrap();
            integrate(&model, &q, &dk, -eps, &mut qe).unwrap();
            let km = kinetic_energy(&model, &mut data, &qe, &v).unwrap();
            let fd = (kp - km) / (2.0 * eps);
            assert!(
                (fd - g[k]).abs() < 1e-7 * (1.0 + fd.abs()),
                "dof {k}: {fd} vs {}",
                g[k]
            );
        }
        // the free-flyer root: K does not depend on where the robot is
        assert!(g[..6].iter().all(|x| x.abs() < 1e-13));
    }
}
