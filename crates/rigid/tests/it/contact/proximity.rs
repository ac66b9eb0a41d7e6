//! `collision::proximity` (Pinocchio's `computeDistance`) against the closed forms of two balls,
//! a ball and a box, two parallel capsules, and a box's convex hull against the box itself.

use rigid::collision::{proximity, Collider, Shape};
use rigid::spatial::{so3, Transform, Vec3};

fn at(x: f64, y: f64, z: f64) -> Transform {
    Transform::from_translation(Vec3::new(x, y, z))
}

#[test]
fn two_balls_are_their_centres_distance_less_the_radii_apart() {
    let a = Collider::new("a", &Shape::Sphere { radius: 0.1 }).unwrap();
    let b = Collider::new("b", &Shape::Sphere { radius: 0.2 }).unwrap();
    for (d, pen) in [(1.0, false), (0.3, true), (0.25, true)] {
        let p = proximity(&a, &at(0.0, 0.0, 0.0), &b, &at(0.0, d * 0.6, d * 0.8)).unwrap();
        assert!(
            (p.distance - (d - 0.3)).abs() < 1e-12,
            "{d}: {}",
            p.distance
        );
        assert_eq!(p.collides(), pen || d <= 0.3);
        assert!((p.normal - Vec3::new(0.0, 0.6, 0.8)).norm() < 1e-12);
        assert!((p.point_a - p.normal * 0.1).norm() < 1e-12);
    }
}

#[test]
fn a_ball_meets_a_turned_box_on_its_face_and_its_corner() {
    let ball = Collider::new("ball", &Shape::Sphere { radius: 0.05 }).unwrap();
    let cube = Collider::new(
        "cube",
        &Shape::Box {
            size: Vec3::new(0.2, 0.4, 0.6),
        },
    )
    .unwrap();
    let turn = Transform::new(
        so3::exp(&Vec3::new(0.0, 0.0, 0.7)),
        Vec3::new(1.0, 2.0, 3.0),
    );
    // beyond the +x face: the gap is the distance to the face less the radius
    let p = proximity(&cube, &turn, &ball, &(turn * at(0.3, 0.05, -0.1))).unwrap();
    assert!((p.distance - (0.2 - 0.05)).abs() < 1e-9, "{}", p.distance);
    assert!((p.normal - turn.rotation * Vec3::x()).norm() < 1e-9);
    // beyond the corner (0.1, 0.2, 0.3): the distance to the corner less the radius
    let off = Vec3::new(0.03, 0.04, 0.12);
    let p = proximity(&cube, &turn, &ball, &(turn * at(0.13, 0.24, 0.42))).unwrap();
    assert!(
        (p.distance - (off.norm() - 0.05)).abs() < 1e-9,
        "{}",
        p.distance
    );
    // 1 cm into the face: penetration
    let p = proximity(&cube, &turn, &ball, &(turn * at(0.14, 0.0, 0.0))).unwrap();
    assert!(
        (p.distance + 0.01).abs() < 1e-9 && p.collides(),
        "{}",
        p.distance
    );
}

#[test]
fn parallel_capsules_are_their_axes_distance_less_the_radii_apart() {
    let c = Collider::new(
        "capsule",
        &Shape::Capsule {
            radius: 0.05,
            length: 0.4,
        },
    )
    .unwrap();
    let p = proximity(&c, &at(0.0, 0.0, 0.0), &c, &at(0.3, 0.0, 0.1)).unwrap();
    assert!((p.distance - 0.2).abs() < 1e-9, "{}", p.distance);
}

#[test]
fn a_boxs_hull_is_the_box() {
    let h = Vec3::new(0.1, 0.2, 0.3);
    let corners: Vec<Vec3> = (0..8)
        .map(|i| {
            let s = |b: usize| if i & (1 << b) == 0 { -1.0 } else { 1.0 };
            Vec3::new(s(0) * h.x, s(1) * h.y, s(2) * h.z)
        })
        .collect();
    let hull = Collider::new("hull", &Shape::ConvexHull { points: corners }).unwrap();
    let cube = Collider::new("cube", &Shape::Box { size: h * 2.0 }).unwrap();
    let ball = Collider::new("ball", &Shape::Sphere { radius: 0.01 }).unwrap();
    let turn = Transform::new(so3::exp(&Vec3::new(0.3, -0.2, 0.5)), Vec3::zeros());
    for x in [at(0.5, 0.1, 0.0), at(0.12, 0.25, 0.33), at(0.0, 0.0, 0.5)] {
        let a = proximity(&hull, &turn, &ball, &(turn * x)).unwrap();
        let b = proximity(&cube, &turn, &ball, &(turn * x)).unwrap();
        assert!(
            (a.distance - b.distance).abs() < 1e-9,
            "{} {}",
            a.distance,
            b.distance
        );
    }
}

#[test]
fn a_shape_with_a_bad_dimension_is_refused_by_name() {
    let e = Collider::new("wheel", &Shape::Sphere { radius: -1.0 }).unwrap_err();
    assert!(e.to_string().contains("wheel"), "{e}");
    let segment = vec![Vec3::zeros(), Vec3::x()];
    let e = Collider::new("sole", &Shape::ConvexHull { points: segment }).unwrap_err();
    assert!(e.to_string().contains("sole"), "{e}");
}
