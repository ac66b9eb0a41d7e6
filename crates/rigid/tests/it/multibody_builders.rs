//! Builders: standard and modified DH give the same dynamics for the same robot; the Modern
//! Robotics `(M_i, G_i, S_i)` builder reproduces the product of exponentials and the DH model's
//! dynamics; bad input gives errors naming the joint.
#![allow(non_snake_case)]

use rigid::error::InertiaError;
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::*;
use rigid::spatial::{so3, Transform, Twist, Vec3};

/// A 6-joint standard DH table with a prismatic joint and non-trivial offsets.
fn table() -> Vec<DhLink> {
    let mut rng = Rng::new(9);
    (0..6)
        .map(|i| DhLink {
            a: rng.uniform(-0.5, 0.5),
            alpha: rng.uniform(-3.0, 3.0),
            d: rng.uniform(-0.5, 0.5),
            theta_offset: rng.uniform(-1.0, 1.0),
            joint: if i == 2 {
                DhJoint::Prismatic
            } else {
                DhJoint::Revolute
            },
            mass: rng.uniform(0.5, 3.0),
            com: Vec3::new(
                rng.uniform(-0.2, 0.2),
                rng.uniform(-0.2, 0.2),
                rng.uniform(-0.2, 0.2),
            ),
            inertia: RotationalInertia::new(0.05, 0.06, 0.07, 0.001, -0.002, 0.003),
        })
        .collect()
}

fn state(n: usize, rng: &mut Rng) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut f = || (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect::<Vec<f64>>();
    (f(), f(), f())
}

#[test]
fn standard_and_modified_dh_of_the_same_robot_have_the_same_dynamics() {
    let std_links = table();
    // modified row i holds (a_{i-1}, α_{i-1}); link i's frame {i}_mod = {i}_std Tx(a_i)Rx(α_i)⁻¹
    let mut mod_links = Vec::new();
    let (mut a_prev, mut alpha_prev) = (0.0, 0.0);
    for l in &std_links {
        let t = Transform::new(so3::exp(&(Vec3::x() * l.alpha)), Vec3::new(l.a, 0.0, 0.0)); // {i}_std in {i}_mod
        let inertia = RotationalInertia::from_matrix_unchecked(
            &(t.rotation * l.inertia.matrix() * t.rotation.transpose()),
        );
        mod_links.push(DhLink {
            a: a_prev,
            alpha: alpha_prev,
            com: t.act_point(&l.com),
            inertia,
            ..*l
        });
        (a_prev, alpha_prev) = (l.a, l.alpha);
    }
    let g = Vec3::new(0.0, 0.0, -9.81);
    let ms = from_dh("std", DhConvention::Standard, &std_links, g).unwrap();
    let mm = from_dh("mod", DhConvention::Modified, &mod_links, g).unwrap();
    let (mut ds, mut dm) = (Data::new(&ms), Data::new(&mm));
    let mut rng = Rng::new(1);
    for _ in 0..10 {
        let (q, v, a) = state(6, &mut rng);
        let ts = rnea(&ms, &mut ds, &q, &v, &a).unwrap().clone();
        let tm = rnea(&mm, &mut dm, &q, &v, &a).unwrap().clone();
        assert!((&ts - &tm).amax() < 1e-10 * ts.amax().max(1.0), "{ts} {tm}");
        let Ms = crba(&ms, &mut ds, &q).unwrap().clone();
        let Mm = crba(&mm, &mut dm, &q).unwrap().clone();
        assert!((Ms - Mm).amax() < 1e-10);
        // the last standard frame: {6}_std = {6}_mod Tx(a6) Rx(α6)
        forward_kinematics_q(&ms, &mut ds, &q).unwrap();
        forward_kinematics_q(&mm, &mut dm, &q).unwrap();
        update_frame_placements(&ms, &mut ds);
        update_frame_placements(&mm, &mut dm);
        let l6 = &std_links[5];
        let t = Transform::new(so3::exp(&(Vec3::x() * l6.alpha)), Vec3::new(l6.a, 0.0, 0.0));
        let f6 = ms.frame_id("link6").unwrap().0;
        let d = ds.frame_placements[f6].inverse() * (dm.frame_placements[f6] * t);
        assert!(d.is_identity(1e-12));
    }
}

#[test]
fn standard_dh_frames_follow_rz_tz_tx_rx() {
    let links = table();
    let model = from_dh("std", DhConvention::Standard, &links, Vec3::zeros()).unwrap();
    let mut data = Data::new(&model);
    let q = [0.3, -0.2, 0.1, 0.5, -0.7, 0.9];
    forward_kinematics_q(&model, &mut data, &q).unwrap();
    update_frame_placements(&model, &mut data);
    let mut T = Transform::identity();
    for (i, l) in links.iter().enumerate() {
        let (theta, d) = match l.joint {
            DhJoint::Revolute => (q[i] + l.theta_offset, l.d),
            DhJoint::Prismatic => (l.theta_offset, l.d + q[i]),
        };
        T = T
            * Transform::from_rotation(so3::exp(&(Vec3::z() * theta)))
            * Transform::from_translation(Vec3::new(0.0, 0.0, d))
            * Transform::from_translation(Vec3::new(l.a, 0.0, 0.0))
            * Transform::from_rotation(so3::exp(&(Vec3::x() * l.alpha)));
        let f = model.frame_id(&format!("link{}", i + 1)).unwrap().0;
        assert!(
            (data.frame_placements[f].inverse() * T).is_identity(1e-12),
            "frame {}",
            i + 1
        );
    }
}

#[test]
fn modern_robotics_lists_reproduce_product_of_exponentials_and_dh_dynamics() {
    // the lists of the DH robot: home link frames, screw axes in the space frame, link inertias
    let links = table();
    let g = Vec3::new(0.0, 0.0, -9.81);
    let dh = from_dh("dh", DhConvention::Standard, &links, g).unwrap();
    let mut dd = Data::new(&dh);
    let q0 = vec![0.0; 6];
    forward_kinematics_q(&dh, &mut dd, &q0).unwrap();
    update_frame_placements(&dh, &mut dd);
    let mut m_list = Vec::new();
    let mut s_list = Vec::new();
    let mut g_list = Vec::new();
    let mut prev = Transform::identity();
    for (i, l) in links.iter().enumerate() {
        let link = dd.frame_placements[dh.frame_id(&format!("link{}", i + 1)).unwrap().0];
        m_list.push(prev.inverse() * link);
        prev = link;
        let joint = dd.placements[i]; // joint frame at home, axis z
        let axis = joint.rotation * Vec3::z();
        s_list.push(match l.joint {
            DhJoint::Revolute => Twist::new(axis, -axis.cross(&joint.translation)),
            DhJoint::Prismatic => Twist::new(Vec3::zeros(), axis),
        });
        g_list.push(SpatialInertia::from_com(l.mass, l.com, l.inertia));
    }
    let ee = Transform::from_translation(Vec3::new(0.0, 0.0, 0.1));
    m_list.push(ee);
    let mr = from_modern_robotics("mr", &m_list, &g_list, &s_list, g).unwrap();
    let mut dm = Data::new(&mr);
    let mut rng = Rng::new(5);
    for _ in 0..10 {
        let (q, v, a) = state(6, &mut rng);
        // T_0n(θ) = e^{[S1]θ1} ... e^{[Sn]θn} M_0n
        let mut T = Transform::identity();
        for (S, th) in s_list.iter().zip(&q) {
            T = T * Transform::exp(&(*S * *th));
        }
        let home: Transform = m_list.iter().fold(Transform::identity(), |acc, m| acc * *m);
        let poe = T * home;
        forward_kinematics_q(&mr, &mut dm, &q).unwrap();
        update_frame_placements(&mr, &mut dm);
        let f = mr.frame_id("ee").unwrap().0;
        assert!((dm.frame_placements[f].inverse() * poe).is_identity(1e-12));
        let t1 = rnea(&dh, &mut dd, &q, &v, &a).unwrap().clone();
        let t2 = rnea(&mr, &mut dm, &q, &v, &a).unwrap().clone();
        assert!((&t1 - &t2).amax() < 1e-10 * t1.amax().max(1.0));
    }
}

#[test]
fn bad_inputs_give_errors_naming_the_joint() {
    let model = puma560(Puma560Options::default());
    let mut data = Data::new(&model);
    let z = [0.0; 6];
    assert!(matches!(
        rnea(&model, &mut data, &z[..5], &z, &z),
        Err(MultibodyError::Dimension(e)) if e.what == "q" && e.expected == 6 && e.got == 5
    ));
    let mut q = z;
    q[3] = f64::NAN;
    assert!(matches!(
        rnea(&model, &mut data, &q, &z, &z),
        Err(MultibodyError::NonFinite {
            what: "q",
            index: 3
        })
    ));
    assert!(matches!(
        aba(&model, &mut data, &z, &z, &z[..2]),
        Err(MultibodyError::Dimension(_))
    ));
    // M⁻¹ checks q exactly as CRBA does
    for q in [&z[..5], &q[..]] {
        assert_eq!(
            compute_minverse(&model, &mut data, q).unwrap_err(),
            crba(&model, &mut data, q).unwrap_err()
        );
    }
    assert!(matches!(
        compute_minverse(&model, &mut data, &q),
        Err(MultibodyError::NonFinite {
            what: "q",
            index: 3
        })
    ));
    let other = double_pendulum();
    assert!(matches!(
        compute_minverse(&other, &mut data, &[0.0; 2]),
        Err(MultibodyError::DataMismatch { .. })
    ));

    let mut b = ModelBuilder::new("bad");
    let root = b
        .add_joint(
            None,
            "base",
            JointType::FreeFlyer,
            Transform::identity(),
            SpatialInertia::from_com(
                1.0,
                Vec3::zeros(),
                RotationalInertia::diagonal(1.0, 1.0, 1.0),
            ),
        )
        .unwrap();
    b.add_joint(
        Some(root),
        "ball",
        JointType::Spherical,
        Transform::identity(),
        SpatialInertia::zero(),
    )
    .unwrap();
    let m = b.build().unwrap();
    let mut d = Data::new(&m);
    let mut q = neutral(&m);
    q[10] = 1.1; // the ball's qw
    let e = forward_kinematics_q(&m, &mut d, &q).unwrap_err();
    assert!(matches!(&e, MultibodyError::NotUnitQuaternion { joint, .. } if joint == "ball"));
    assert!(e.to_string().contains("ball"));
    assert_eq!(
        compute_minverse(&m, &mut d, &q).unwrap_err(),
        crba(&m, &mut d, &q).unwrap_err()
    );
    // the ball moves no mass: M is singular, and M⁻¹ says so (as ABA does)
    let q = neutral(&m);
    assert_eq!(
        compute_minverse(&m, &mut d, &q).unwrap_err(),
        MultibodyError::NotPositiveDefinite
    );
    assert_eq!(
        aba(&m, &mut d, &q, &[0.0; 9], &[0.0; 9]).unwrap_err(),
        MultibodyError::NotPositiveDefinite
    );
    // the same for a massless revolute leaf (ABA's one-dof path): an error, not NaN
    let mut b = ModelBuilder::new("massless leaf");
    let root = b
        .add_joint(
            None,
            "shoulder",
            JointType::Revolute { axis: Vec3::z() },
            Transform::identity(),
            SpatialInertia::from_com(
                1.0,
                Vec3::new(0.5, 0.0, 0.0),
                RotationalInertia::diagonal(0.1, 0.1, 0.1),
            ),
        )
        .unwrap();
    b.add_joint(
        Some(root),
        "wrist",
        JointType::Revolute { axis: Vec3::x() },
        Transform::from_translation(Vec3::new(1.0, 0.0, 0.0)),
        SpatialInertia::zero(),
    )
    .unwrap();
    let m = b.build().unwrap();
    let mut d = Data::new(&m);
    assert_eq!(
        aba(&m, &mut d, &[0.3, 0.2], &[0.0; 2], &[1.0, 0.0]).unwrap_err(),
        MultibodyError::NotPositiveDefinite
    );

    let unit = SpatialInertia::from_com(
        1.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    let mut b = ModelBuilder::new("bad");
    let j = b
        .add_joint(
            None,
            "a",
            JointType::Revolute { axis: Vec3::z() },
            Transform::identity(),
            unit,
        )
        .unwrap();
    let e = b.add_joint(
        None,
        "a",
        JointType::Revolute { axis: Vec3::z() },
        Transform::identity(),
        unit,
    );
    assert!(matches!(e, Err(ModelError::DuplicateName { .. })));
    let e = b.add_joint(
        Some(j),
        "b",
        JointType::Revolute {
            axis: Vec3::zeros(),
        },
        Transform::identity(),
        unit,
    );
    assert!(matches!(e, Err(ModelError::BadAxis { name }) if name == "b"));
    let neg = SpatialInertia::from_com(
        -1.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    let e = b.add_joint(
        Some(j),
        "c",
        JointType::Prismatic { axis: Vec3::x() },
        Transform::identity(),
        neg,
    );
    assert!(
        matches!(e, Err(ModelError::BadInertia { name, source: InertiaError::BadMass { .. } }) if name == "c")
    );
    let npd = SpatialInertia::from_com(
        1.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 1.0, -0.5),
    );
    let e = b.add_joint(
        Some(j),
        "d",
        JointType::Prismatic { axis: Vec3::x() },
        Transform::identity(),
        npd,
    );
    assert!(matches!(
        e,
        Err(ModelError::BadInertia {
            source: InertiaError::NotPositiveSemiDefinite { .. },
            ..
        })
    ));
    let e = b.add_joint(
        Some(JointId(7)),
        "e",
        JointType::Spherical,
        Transform::identity(),
        unit,
    );
    assert!(matches!(e, Err(ModelError::UnknownParent { .. })));
    // depth-first: after a second root, the first root's subtree is closed
    b.add_joint(
        None,
        "r2",
        JointType::Spherical,
        Transform::identity(),
        unit,
    )
    .unwrap();
    let e = b.add_joint(
        Some(j),
        "late",
        JointType::Spherical,
        Transform::identity(),
        unit,
    );
    assert!(matches!(e, Err(ModelError::NotDepthFirst { .. })));
    let e = b.set_limits(j, &[1.0], &[0.0], &[1.0], &[1.0]);
    assert!(matches!(e, Err(ModelError::BadLimits { .. })));
    let e = b.set_armature(j, &[1.0, 2.0]);
    assert!(matches!(e, Err(ModelError::Dimension { .. })));
}

#[test]
fn welded_bodies_merge_into_the_parent_and_welded_to_world_bodies_are_dropped() {
    let body = SpatialInertia::from_com(
        2.0,
        Vec3::new(0.1, 0.0, 0.0),
        RotationalInertia::diagonal(0.1, 0.2, 0.25),
    );
    let at = Transform::new(
        so3::exp(&Vec3::new(0.3, 0.2, 0.1)),
        Vec3::new(0.0, 0.5, 0.0),
    );
    let mut b = ModelBuilder::new("weld");
    b.add_fixed_body(None, "base_link", Transform::identity(), body)
        .unwrap();
    let j = b
        .add_joint(
            None,
            "j",
            JointType::Revolute { axis: Vec3::z() },
            Transform::identity(),
            body,
        )
        .unwrap();
    b.add_fixed_body(Some(j), "tool", at, body).unwrap();
    let m = b.build().unwrap();
    assert_eq!(m.total_mass(), 4.0);
    assert_eq!(m.frames().len(), 2);
    let expect = body + body.transformed(&at);
    assert!((m.inertia(j).matrix() - expect.matrix()).amax() < 1e-15);
    // the PUMA's link 3 violates the triangle inequality: reported, not rejected
    let issues = puma560(Puma560Options::default()).inertia_issues();
    assert!(issues
        .iter()
        .any(|(j, e)| j.0 == 2 && matches!(e, InertiaError::TriangleInequality { .. })));
}
