//! Dynamics identities over random states of every built-in model and random trees (free-flyer
//! root, spherical, planar, prismatic, revolute joints with random axes).
#![allow(non_snake_case)]

use crate::common;
use common::*;
use nalgebra::{DMatrix, DVector};
use rigid::multibody::*;

const STATES: usize = 8;

#[test]
fn rnea_equals_mass_matrix_times_a_plus_nonlinear_effects() {
    let mut rng = Rng::new(10);
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..STATES {
            let (q, v, a) = state(&model, &mut rng);
            let tau = rnea(&model, &mut data, &q, &v, &a).unwrap().clone();
            let nle = nonlinear_effects(&model, &mut data, &q, &v)
                .unwrap()
                .clone();
            let M = crba(&model, &mut data, &q).unwrap().clone();
            let rhs = &M * DVector::from_column_slice(&a) + nle;
            assert!(
                rel_err_v(&tau, &rhs) < 1e-10,
                "{}: {}",
                model.name(),
                rel_err_v(&tau, &rhs)
            );
        }
    }
}

#[test]
fn aba_inverts_rnea_m_times_ddq_plus_nle_equals_tau() {
    let mut rng = Rng::new(11);
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..STATES {
            let (q, v, tau) = state(&model, &mut rng);
            let ddq = aba(&model, &mut data, &q, &v, &tau).unwrap().clone();
            let nle = nonlinear_effects(&model, &mut data, &q, &v)
                .unwrap()
                .clone();
            let M = crba(&model, &mut data, &q).unwrap().clone();
            let lhs = &M * &ddq + nle;
            let tau = DVector::from_column_slice(&tau);
            assert!(
                rel_err_v(&lhs, &tau) < 1e-9,
                "{}: {}",
                model.name(),
                rel_err_v(&lhs, &tau)
            );
        }
    }
}

#[test]
fn cholesky_forward_dynamics_equals_aba() {
    let mut rng = Rng::new(12);
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..STATES {
            let (q, v, tau) = state(&model, &mut rng);
            let x = aba(&model, &mut data, &q, &v, &tau).unwrap().clone();
            let y = forward_dynamics_cholesky(&model, &mut data, &q, &v, &tau)
                .unwrap()
                .clone();
            assert!(
                rel_err_v(&x, &y) < 1e-9,
                "{}: {}",
                model.name(),
                rel_err_v(&x, &y)
            );
        }
    }
}

#[test]
fn rnea_at_rest_equals_gravity_torques() {
    let mut rng = Rng::new(13);
    for model in models() {
        let mut data = Data::new(&model);
        let z = vec![0.0; model.nv()];
        for _ in 0..STATES {
            let (q, _, _) = state(&model, &mut rng);
            let tau = rnea(&model, &mut data, &q, &z, &z).unwrap().clone();
            let g = gravity_torques(&model, &mut data, &q).unwrap().clone();
            assert!(rel_err_v(&tau, &g) < 1e-12, "{}", model.name());
        }
    }
}

#[test]
fn mass_matrix_is_symmetric_positive_definite() {
    let mut rng = Rng::new(14);
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..STATES {
            let (q, _, _) = state(&model, &mut rng);
            let M = crba(&model, &mut data, &q).unwrap().clone();
            assert!(rel_err_m(&M, &M.transpose()) < 1e-14, "{}", model.name());
            let e = M.symmetric_eigenvalues();
            assert!(
                e.min() > 0.0,
                "{}: min eigenvalue {}",
                model.name(),
                e.min()
            );
        }
    }
}

#[test]
fn half_vt_m_v_equals_kinetic_energy_sum_of_body_and_rotor_energies() {
    let mut rng = Rng::new(15);
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..STATES {
            let (q, v, _) = state(&model, &mut rng);
            let M = crba(&model, &mut data, &q).unwrap().clone();
            let vv = DVector::from_column_slice(&v);
            let k1 = 0.5 * vv.dot(&(&M * &vv));
            let k2 = kinetic_energy(&model, &mut data, &q, &v).unwrap();
            let k3: f64 = model
                .inertias()
                .iter()
                .zip(&data.velocities)
                .map(|(G, V)| 0.5 * V.to_vector().dot(&(G.matrix() * V.to_vector())))
                .sum::<f64>()
                + model
                    .armature()
                    .iter()
                    .zip(&v)
                    .map(|(a, v)| 0.5 * a * v * v)
                    .sum::<f64>();
            assert!(
                (k1 - k2).abs() < 1e-10 * k1.max(1.0),
                "{}: {k1} {k2}",
                model.name()
            );
            assert!((k3 - k2).abs() < 1e-10 * k1.max(1.0), "{}", model.name());
        }
    }
}

fn mass_matrix_at(model: &Model, data: &mut Data, q: &[f64]) -> DMatrix<f64> {
    crba(model, data, q).unwrap().clone()
}

#[test]
fn mdot_minus_2c_is_skew_and_c_v_equals_nle_minus_g() {
    let mut rng = Rng::new(16);
    let eps = 1e-6;
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..STATES {
            let (q, v, _) = state(&model, &mut rng);
            let C = coriolis_matrix(&model, &mut data, &q, &v).unwrap().clone();
            let Mp = mass_matrix_at(&model, &mut data, &step(&model, &q, &v, eps));
            let Mm = mass_matrix_at(&model, &mut data, &step(&model, &q, &v, -eps));
            let Mdot = (Mp - Mm) / (2.0 * eps);
            let S = &Mdot - &C * 2.0;
            let skew = (&S + S.transpose()).amax() / Mdot.amax().max(1.0);
            assert!(skew < 1e-6, "{}: {skew}", model.name());
            let nle = nonlinear_effects(&model, &mut data, &q, &v)
                .unwrap()
                .clone();
            let g = gravity_torques(&model, &mut data, &q).unwrap().clone();
            let cv = &C * DVector::from_column_slice(&v);
            assert!(rel_err_v(&cv, &(nle - g)) < 1e-10, "{}", model.name());
        }
    }
}

#[test]
fn total_energy_rate_equals_power_of_joint_forces() {
    let mut rng = Rng::new(17);
    let eps = 1e-3;
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..STATES {
            let (q, v, tau) = state(&model, &mut rng);
            let a = aba(&model, &mut data, &q, &v, &tau).unwrap().clone();
            let mut energy = |t: f64| {
                let w: Vec<f64> = (0..model.nv())
                    .map(|k| t * v[k] + 0.5 * t * t * a[k])
                    .collect();
                let qt = step(&model, &q, &w, 1.0);
                let vt: Vec<f64> = (0..model.nv()).map(|k| v[k] + t * a[k]).collect();
                kinetic_energy(&model, &mut data, &qt, &vt).unwrap()
                    + potential_energy(&model, &mut data, &qt).unwrap()
            };
            // central differences with Richardson extrapolation: O(eps⁴)
            let d1 = (energy(eps) - energy(-eps)) / (2.0 * eps);
            let d2 = (energy(eps / 2.0) - energy(-eps / 2.0)) / eps;
            let rate = (4.0 * d2 - d1) / 3.0;
            let power: f64 = tau.iter().zip(&v).map(|(t, v)| t * v).sum();
            assert!(
                (rate - power).abs() < 1e-6 * power.abs().max(1.0),
                "{}: {rate} {power}",
                model.name()
            );
        }
    }
}

#[test]
fn difference_inverts_integrate() {
    let mut rng = Rng::new(18);
    for model in models() {
        for _ in 0..STATES {
            let (q, v, _) = state(&model, &mut rng);
            let q1 = step(&model, &q, &v, 0.3);
            let mut d = vec![0.0; model.nv()];
            difference(&model, &q, &q1, &mut d).unwrap();
            for k in 0..model.nv() {
                assert!((d[k] - 0.3 * v[k]).abs() < 1e-9, "{}", model.name());
            }
        }
    }
}

#[test]
fn neutral_configuration_has_identity_quaternions_and_normalize_restores_unit_norm() {
    let model = random_tree(5, 8, false);
    let q = neutral(&model);
    let mut data = Data::new(&model);
    forward_kinematics_q(&model, &mut data, &q).unwrap();
    let mut bad = q.clone();
    for x in bad.iter_mut() {
        *x *= 1.5;
    }
    assert!(matches!(
        forward_kinematics_q(&model, &mut data, &bad),
        Err(MultibodyError::NotUnitQuaternion { .. })
    ));
    normalize(&model, &mut bad).unwrap();
    forward_kinematics_q(&model, &mut data, &bad).unwrap();
}

#[test]
fn random_trees_cover_every_joint_type_and_coordinate_axes() {
    let mut names = std::collections::BTreeSet::new();
    let mut coordinate_axis = false;
    for model in models() {
        for j in model.joints() {
            names.insert(j.type_name());
            if let JointType::Revolute { axis } = j.kind {
                coordinate_axis |= axis.iter().filter(|x| **x == 0.0).count() == 2;
            }
        }
    }
    assert_eq!(names.len(), 6, "{names:?}");
    assert!(coordinate_axis);
}

#[test]
fn coriolis_matrix_is_the_christoffel_symbol_matrix_for_vector_space_joints() {
    // C_ij = Σ_k ½ (∂M_ij/∂q_k + ∂M_ik/∂q_j - ∂M_jk/∂q_i) v_k, derivatives by central differences
    let mut rng = Rng::new(19);
    let eps = 1e-6;
    for model in [
        puma560(Puma560Options { armature: true }),
        double_pendulum(),
        pendulum(),
    ] {
        let mut data = Data::new(&model);
        let n = model.nv();
        for _ in 0..3 {
            let (q, v, _) = state(&model, &mut rng);
            let dM: Vec<DMatrix<f64>> = (0..n)
                .map(|k| {
                    let (mut qp, mut qm) = (q.clone(), q.clone());
                    qp[k] += eps;
                    qm[k] -= eps;
                    (mass_matrix_at(&model, &mut data, &qp)
                        - mass_matrix_at(&model, &mut data, &qm))
                        / (2.0 * eps)
                })
                .collect();
            let C = coriolis_matrix(&model, &mut data, &q, &v).unwrap().clone();
            let Cc = DMatrix::from_fn(n, n, |i, j| {
                (0..n)
                    .map(|k| 0.5 * (dM[k][(i, j)] + dM[j][(i, k)] - dM[i][(j, k)]) * v[k])
                    .sum::<f64>()
            });
            assert!(
                rel_err_m(&C, &Cc) < 1e-6,
                "{}: {}",
                model.name(),
                rel_err_m(&C, &Cc)
            );
        }
    }
}

/// Every built-in model, the random trees, and a model with two root joints (so that `M⁻¹` has
/// zero blocks between the two trees).
fn minverse_models() -> Vec<Model> {
    let mut v = models();
    let mut b = ModelBuilder::new("two_roots");
    let mut rng = Rng::new(40);
    let a = b
        .add_joint(
            None,
            "a0",
            JointType::Revolute {
                axis: unit(&mut rng),
            },
            transform(&mut rng),
            inertia(&mut rng),
        )
        .unwrap();
    b.add_joint(
        Some(a),
        "a1",
        JointType::Spherical,
        transform(&mut rng),
        inertia(&mut rng),
    )
    .unwrap();
    let c = b
        .add_joint(
            None,
            "b0",
            JointType::FreeFlyer,
            transform(&mut rng),
            inertia(&mut rng),
        )
        .unwrap();
    b.add_joint(
        Some(c),
        "b1",
        JointType::Prismatic {
            axis: unit(&mut rng),
        },
        transform(&mut rng),
        inertia(&mut rng),
    )
    .unwrap();
    b.set_armature(JointId(3), &[0.2]).unwrap();
    v.push(b.build().unwrap());
    v
}

#[test]
fn minverse_times_mass_matrix_is_the_identity_and_solves_forward_dynamics() {
    let mut rng = Rng::new(20);
    let (mut worst_eye, mut worst_aba) = (0.0f64, 0.0f64);
    for model in minverse_models() {
        let mut data = Data::new(&model);
        let n = model.nv();
        for _ in 0..STATES {
            let (q, v, tau) = state(&model, &mut rng);
            let M = crba(&model, &mut data, &q).unwrap().clone();
            let Minv = compute_minverse(&model, &mut data, &q).unwrap().clone();
            assert_eq!(Minv, Minv.transpose(), "{}: not symmetric", model.name());
            let eye = DMatrix::<f64>::identity(n, n);
            let e1 = rel_err_m(&(&M * &Minv), &eye);
            let e2 = rel_err_m(&(&Minv * &M), &eye);
            worst_eye = worst_eye.max(e1).max(e2);
            assert!(e1 < 1e-9 && e2 < 1e-9, "{}: {e1} {e2}", model.name());
            let ddq = aba(&model, &mut data, &q, &v, &tau).unwrap().clone();
            let nle = nonlinear_effects(&model, &mut data, &q, &v)
                .unwrap()
                .clone();
            let x = &Minv * (DVector::from_column_slice(&tau) - nle);
            let e = rel_err_v(&x, &ddq);
            worst_aba = worst_aba.max(e);
            assert!(e < 1e-9, "{}: {e}", model.name());
        }
    }
    eprintln!("max |M M⁻¹ - 1|: {worst_eye:.1e}, max M⁻¹(τ - nle) vs aba: {worst_aba:.1e}");
}

#[test]
fn minverse_keeps_no_state_from_a_previous_call() {
    let mut rng = Rng::new(21);
    for model in minverse_models() {
        let mut data = Data::new(&model);
        let (q1, v1, a1) = state(&model, &mut rng);
        let (q2, _, _) = state(&model, &mut rng);
        compute_minverse(&model, &mut data, &q1).unwrap();
        // other algorithms share workspaces (`ia`, the joint columns)
        aba(&model, &mut data, &q1, &v1, &a1).unwrap();
        crba(&model, &mut data, &q1).unwrap();
        // every entry is written by every call
        data.minv.fill(f64::NAN);
        let again = compute_minverse(&model, &mut data, &q2).unwrap().clone();
        let fresh = compute_minverse(&model, &mut Data::new(&model), &q2)
            .unwrap()
            .clone();
        assert_eq!(again, fresh, "{}", model.name());
    }
}

/// A chain built to take every shortcut of CRBA's first pass, each checked against RNEA: column
/// `k` of `M` is `rnea(q, 0, e_k) − rnea(q, 0, 0)` with gravity off; `M⁻¹` (the same first pass)
/// times `M` is the identity. The shortcuts: placements whose rotation is a signed permutation
/// (`rpy` in multiples of π/2, as URDF files write them) or a turn about one coordinate axis,
/// unrotated ones, offsets and centres of mass on one axis, diagonal inertias (coordinate
/// principal axes), prismatic joints along ±axes, behind a fixed root and behind a free flyer.
#[test]
fn crba_shortcuts_equal_rnea_columns() {
    use rigid::mass::{RotationalInertia, SpatialInertia};
    use rigid::spatial::{so3, Transform, Vec3};
    let half_pi = std::f64::consts::FRAC_PI_2;
    let rpy = |r: f64, p: f64, y: f64| {
        so3::exp(&Vec3::new(0.0, 0.0, y))
            * so3::exp(&Vec3::new(0.0, p, 0.0))
            * so3::exp(&Vec3::new(r, 0.0, 0.0))
    };
    let mut rng = Rng::new(77);
    for floating in [false, true] {
        let mut b = ModelBuilder::new("shortcuts");
        b.set_gravity(Vec3::zeros());
        let body = |k: usize| {
            let mut com = Vec3::zeros();
            com[k % 3] = 0.1 + 0.05 * k as f64;
            SpatialInertia::from_com(
                1.0 + 0.1 * k as f64,
                com,
                RotationalInertia::diagonal(0.02, 0.03, 0.04),
            )
        };
        let mut parent = if floating {
            Some(
                b.add_joint(
                    None,
                    "root",
                    JointType::FreeFlyer,
                    Transform::identity(),
                    body(0),
                )
                .unwrap(),
            )
        } else {
            None
        };
        let kinds = [
            (
                JointType::Revolute { axis: Vec3::z() },
                rpy(0.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 0.3),
            ),
            (
                JointType::Revolute { axis: Vec3::z() },
                rpy(half_pi, 0.0, 0.0),
                Vec3::new(0.0, 0.12, 0.0),
            ),
            (
                JointType::Prismatic { axis: -Vec3::y() },
                rpy(0.0, 0.0, 0.0),
                Vec3::new(0.2, 0.0, 0.0),
            ),
            (
                JointType::Revolute { axis: -Vec3::x() },
                rpy(-half_pi, 0.0, std::f64::consts::PI),
                Vec3::new(0.1, -0.2, 0.05),
            ),
            (
                JointType::Prismatic { axis: Vec3::z() },
                rpy(0.0, half_pi, 0.0),
                Vec3::new(0.0, 0.0, 0.15),
            ),
            (
                JointType::Revolute { axis: Vec3::y() },
                rpy(0.0, 0.0, 0.0),
                Vec3::zeros(),
            ),
            (
                JointType::Revolute {
                    axis: Vec3::new(0.0, 0.6, 0.8),
                },
                rpy(half_pi, 0.0, half_pi),
                Vec3::new(0.0, 0.0, 0.1),
            ),
            // X_T turns about one coordinate axis (UR5's `rpy="0 1.570796325 0"`, Panda's hand)
            (
                JointType::Revolute { axis: Vec3::z() },
                rpy(0.0, 1.570796325, 0.0),
                Vec3::new(0.0, 0.1, 0.0),
            ),
            (
                JointType::Prismatic { axis: Vec3::y() },
                rpy(0.0, 0.0, -std::f64::consts::FRAC_PI_4),
                Vec3::new(0.0, 0.0, 0.06),
            ),
            (
                JointType::Revolute { axis: -Vec3::x() },
                rpy(0.3, 0.0, 0.0),
                Vec3::new(0.05, 0.0, 0.0),
            ),
        ];
        for (k, (kind, r, t)) in kinds.into_iter().enumerate() {
            let id = b
                .add_joint(
                    parent,
                    &format!("j{k}"),
                    kind,
                    Transform::new(r, t),
                    body(k + 1),
                )
                .unwrap();
            parent = Some(id);
        }
        let model = b.build().unwrap();
        let nv = model.nv();
        let mut data = Data::new(&model);
        for _ in 0..4 {
            let (q, _, _) = state(&model, &mut rng);
            let M = crba(&model, &mut data, &q).unwrap().clone();
            let zero = vec![0.0; nv];
            let bias = rnea(&model, &mut data, &q, &zero, &zero).unwrap().clone();
            for k in 0..nv {
                let mut e = vec![0.0; nv];
                e[k] = 1.0;
                let col = rnea(&model, &mut data, &q, &zero, &e).unwrap() - &bias;
                let d = (M.column(k) - col).amax();
                assert!(d < 1e-12, "floating {floating}, column {k}: {d:e}");
            }
            let Minv = compute_minverse(&model, &mut data, &q).unwrap().clone();
            let d = (Minv * &M - nalgebra::DMatrix::<f64>::identity(nv, nv)).amax();
            assert!(d < 1e-10, "floating {floating}: M⁻¹ M − 1 = {d:e}");
        }
    }
}

/// A `Data` made for a model with the same numbers of joints and dofs but another `nq` (a planar
/// root, nq = 3, against a spherical one, nq = 4, both nv = 3) is refused with `DataMismatch`,
/// not a panic in the buffers sized by `nq`.
#[test]
fn data_of_another_nq_is_a_data_mismatch() {
    use rigid::mass::SpatialInertia;
    use rigid::spatial::{Transform, Vec3};
    let tree = |root: JointType| {
        let mut b = ModelBuilder::new("two");
        let body = SpatialInertia::from_com(
            1.0,
            Vec3::new(0.1, 0.0, 0.0),
            rigid::mass::RotationalInertia::diagonal(0.01, 0.02, 0.03),
        );
        let r = b
            .add_joint(None, "root", root, Transform::identity(), body)
            .unwrap();
        b.add_joint(
            Some(r),
            "elbow",
            JointType::Revolute { axis: Vec3::z() },
            Transform::new(rigid::spatial::Mat3::identity(), Vec3::new(0.3, 0.0, 0.0)),
            body,
        )
        .unwrap();
        b.build().unwrap()
    };
    let (planar, spherical) = (tree(JointType::Planar), tree(JointType::Spherical));
    assert_eq!((planar.nv(), spherical.nv()), (4, 4));
    assert_ne!(planar.nq(), spherical.nq());
    let mut data = Data::new(&planar);
    let q = neutral(&spherical);
    assert!(matches!(
        crba(&spherical, &mut data, q.as_slice()),
        Err(MultibodyError::DataMismatch { .. })
    ));
    assert!(matches!(
        compute_minverse(&spherical, &mut data, q.as_slice()),
        Err(MultibodyError::DataMismatch { .. })
    ));
}

/// A `Data` made for a model of the same shape (joints, nq, nv) but other joints is refused
/// with `DataMismatch`: the same elbow about another axis, and the same joints on another tree.
/// It holds the constant motion subspaces and the derivatives' tree of the model it was made
/// for, which would otherwise give the new model's calls the old model's axes.
#[test]
fn data_of_other_joints_of_the_same_shape_is_a_data_mismatch() {
    use rigid::mass::SpatialInertia;
    use rigid::spatial::{Mat3, Transform, Vec3};
    let model = |axes: [Vec3; 3], chain: bool| {
        let mut b = ModelBuilder::new("three");
        let body = SpatialInertia::from_com(
            1.0,
            Vec3::new(0.1, 0.0, 0.0),
            rigid::mass::RotationalInertia::diagonal(0.01, 0.02, 0.03),
        );
        let at = Transform::new(Mat3::identity(), Vec3::new(0.3, 0.0, 0.0));
        let root = b
            .add_joint(
                None,
                "root",
                JointType::Revolute { axis: axes[0] },
                at,
                body,
            )
            .unwrap();
        let one = b
            .add_joint(
                Some(root),
                "one",
                JointType::Revolute { axis: axes[1] },
                at,
                body,
            )
            .unwrap();
        let parent = if chain { one } else { root };
        b.add_joint(
            Some(parent),
            "two",
            JointType::Revolute { axis: axes[2] },
            at,
            body,
        )
        .unwrap();
        b.build().unwrap()
    };
    let chain = model([Vec3::z(), Vec3::y(), Vec3::y()], true);
    let other_axis = model([Vec3::z(), Vec3::x(), Vec3::y()], true);
    let star = model([Vec3::z(), Vec3::y(), Vec3::y()], false);
    let mut data = Data::new(&chain);
    let (q, v) = (vec![0.3; 3], vec![0.2; 3]);
    // the same model, rebuilt, is the same joints
    let again = model([Vec3::z(), Vec3::y(), Vec3::y()], true);
    assert!(aba(&again, &mut data, &q, &v, &v).is_ok());
    for other in [&other_axis, &star] {
        assert!(matches!(
            aba(other, &mut data, &q, &v, &v),
            Err(MultibodyError::DataMismatch { .. })
        ));
        assert!(matches!(
            rnea_derivatives(other, &mut data, &q, &v, &v),
            Err(MultibodyError::DataMismatch { .. })
        ));
        // a data of its own gives its numbers
        assert!(aba(other, &mut Data::new(other), &q, &v, &v).is_ok());
    }
}

/// What ABA leaves in `Data` besides `q̈` (the joint poses in their parents, the body twists and
/// the body accelerations with gravity as the base acceleration) is what RNEA computes at
/// `(q, v, q̈)`: every built-in model and a random tree of every joint type.
#[test]
fn aba_leaves_the_kinematics_rnea_computes() {
    let mut rng = Rng::new(12);
    let mut all = models();
    all.push(every_joint_tree(5, 12));
    for model in all {
        let (mut d_aba, mut d_rnea) = (Data::new(&model), Data::new(&model));
        for _ in 0..STATES {
            let (q, v, tau) = state(&model, &mut rng);
            let Ok(ddq) = aba(&model, &mut d_aba, &q, &v, &tau) else {
                continue;
            };
            let ddq = ddq.clone();
            rnea(&model, &mut d_rnea, &q, &v, ddq.as_slice()).unwrap();
            for i in 0..model.njoints() {
                let (x, y) = (&d_aba.parent_placements[i], &d_rnea.parent_placements[i]);
                let e = (x.rotation - y.rotation).amax() + (x.translation - y.translation).amax();
                assert!(
                    e < 1e-14,
                    "{}: joint {i}: liMi differs by {e:e}",
                    model.name()
                );
                for (what, x, y) in [
                    ("V", &d_aba.velocities[i], &d_rnea.velocities[i]),
                    (
                        "A",
                        &d_aba.accelerations_gravity[i],
                        &d_rnea.accelerations_gravity[i],
                    ),
                ] {
                    let e = (x.to_vector() - y.to_vector()).amax() / (1.0 + y.to_vector().amax());
                    assert!(
                        e < 1e-9,
                        "{}: joint {i}: {what} differs by {e:e}",
                        model.name()
                    );
                }
            }
        }
    }
}
