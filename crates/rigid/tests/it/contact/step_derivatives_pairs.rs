//! The derivatives of a step with contacts whose normal turns or whose point slides with the
//! bodies: between two bodies (a face's normal, the common perpendicular of two balls, edges or
//! capsule axes: boxes, balls, capsules, convex hulls) and on the ground at a rim (a cylinder,
//! a cone, a differential drive's wheels), each against central differences of the step
//! (`step_derivatives::check`), inside one mode.

use super::step_derivatives::{check, sim};
use super::{q_of, scene, Free, G};
use rigid::collision::{Ground, Shape};
use rigid::simulation::ContactMode;
use rigid::spatial::{so3, Vec3};

fn ground() -> Option<Ground> {
    Some(Ground::horizontal(0.0, 0.8))
}

fn down() -> Vec3 {
    Vec3::new(0.0, 0.0, -G)
}

/// The pushing contacts between the two bodies (not on the ground) and the held ones.
fn pair_contacts(d: &rigid::simulation::StepDerivatives) -> usize {
    d.contacts
        .iter()
        .zip(&d.modes)
        .filter(|(c, m)| c.body2.is_some() && **m != ContactMode::Separated)
        .count()
}

/// A box (2 kg, 0.4 x 0.4 x 0.1 m) pressed 1 µm into the ground and a smaller one (1 kg,
/// 0.2 x 0.15 x 0.1 m) on its top face turned by `r`, its lowest corner `depth` into that face.
fn two_boxes(
    r: &rigid::spatial::Mat3,
    depth: f64,
) -> (
    rigid::multibody::Model,
    rigid::collision::CollisionModel,
    Vec<f64>,
) {
    let lower = Free::cube(2.0, Vec3::new(0.4, 0.4, 0.1));
    let upper = Free::cube(1.0, Vec3::new(0.2, 0.15, 0.1));
    let (model, cm) = scene(&[lower, upper], down(), ground());
    let mut z = f64::INFINITY;
    for x in [-0.1, 0.1] {
        for y in [-0.075, 0.075] {
            for h in [-0.05, 0.05] {
                z = z.min((r * Vec3::new(x, y, h)).z);
            }
        }
    }
    let mut q = q_of(Vec3::new(0.0, 0.0, 0.05 - 1e-6), &so3::exp(&Vec3::zeros()));
    q.extend(q_of(Vec3::new(0.02, -0.01, 0.1 - 1e-6 - z - depth), r));
    (model, cm, q)
}

#[test]
fn a_box_on_a_box() {
    // tilted 2 mrad, sliding and turning on its lowest corner (the lower box's face turns
    // the normal)
    let (model, cm, q) = two_boxes(&so3::exp(&Vec3::new(0.002, -0.001, 0.3)), 2e-6);
    let v = [
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.1, -0.2, 0.05, 0.01, 0.0, 0.0,
    ];
    let tau = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.02, 0.0, 0.1, 0.0, 0.0];
    let mut s = sim(&model, cm, &q, &v, &tau);
    let (d, kinks) = check("box on a box's corner", &mut s, 1e-7, 1e-5);
    assert_eq!(kinks, 0);
    assert_eq!(pair_contacts(&d), 1, "{:?}", d.modes);
    assert!(d.held_normal.is_empty(), "{:?}", d.held_normal);
    // flat (2 µrad) on its four corners 3 µm in, pushed within the friction cone (sticking;
    // four coplanar points sliding would share the weight as the solver chose: docs/contact.md)
    let (model, cm, q) = two_boxes(&so3::exp(&Vec3::new(2e-6, -1e-6, 0.3)), 3e-6);
    let mut s = sim(&model, cm, &q, &[0.0; 12], &tau);
    let (d, kinks) = check("box on a box's face", &mut s, 1e-7, 1e-5);
    assert_eq!(kinks, 0);
    assert_eq!(pair_contacts(&d), 4, "{:?}", d.modes);
    assert!(d.held_normal.is_empty(), "{:?}", d.held_normal);
}

#[test]
fn a_box_overhanging_a_box_s_edge_is_held_where_the_edges_cross() {
    // flat on the lower box's face, hanging over its edge: parry clips the two faces, and the
    // points where their edges cross slide along both edges under the face's normal; those
    // are held (named by held_normal), the upper box's own corners on the face are not
    let (model, cm, mut q) = two_boxes(&so3::exp(&Vec3::new(2e-6, -1e-6, 0.3)), 3e-6);
    q[7] += 0.15;
    let mut s = sim(&model, cm, &q, &[0.0; 12], &[0.0; 12]);
    let d = s.step_derivatives().unwrap();
    let pairs: Vec<usize> = (0..d.contacts.len())
        .filter(|&i| d.contacts[i].body2.is_some() && d.modes[i] != ContactMode::Separated)
        .collect();
    assert!(pairs.len() >= 3, "{:?}", d.modes);
    let held: Vec<&usize> = pairs.iter().filter(|i| d.held_normal.contains(i)).collect();
    assert!(
        !held.is_empty() && held.len() < pairs.len(),
        "{pairs:?} {:?}",
        d.held_normal
    );
    // the lower box's edge is at x = 0.2: the held points lie on it, the others inside
    for i in pairs {
        let on_edge = (d.contacts[i].point.x - 0.2).abs() < 1e-6;
        assert_eq!(
            d.held_normal.contains(&i),
            on_edge,
            "{:?}",
            d.contacts[i].point
        );
    }
}

#[test]
fn a_ball_on_a_box_and_a_ball_on_a_ball() {
    // a ball resting off-centre on a box's top face (the box's normal), and a ball on a ball
    // 4 cm off the vertical (the line of centres), each pressed 2 µm in, sliding and spinning
    let bx = Free::cube(2.0, Vec3::new(0.4, 0.4, 0.1));
    let (model, cm) = scene(&[bx, Free::ball(0.5, 0.05)], down(), ground());
    let r = so3::exp(&Vec3::new(0.01, -0.02, 0.1));
    let centre = Vec3::new(0.0, 0.0, 0.05 - 1e-6);
    let mut q = q_of(centre, &r);
    let top = centre + r * Vec3::new(0.1, -0.05, 0.05);
    let n = r * Vec3::z();
    q.extend(q_of(top + n * (0.05 - 2e-6), &so3::exp(&Vec3::zeros())));
    let v = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, -1.0, 0.5, 0.3, 0.1, 0.0];
    let mut s = sim(&model, cm, &q, &v, &[0.0; 12]);
    let (d, kinks) = check("ball on a box", &mut s, 1e-7, 1e-5);
    assert_eq!(kinks, 0);
    assert_eq!(pair_contacts(&d), 1, "{:?}", d.modes);
    assert!(d.held_normal.is_empty(), "{:?}", d.held_normal);

    let (model, cm) = scene(
        &[Free::ball(1.0, 0.1), Free::ball(0.5, 0.05)],
        down(),
        ground(),
    );
    let mut q = q_of(Vec3::new(0.0, 0.0, 0.1 - 1e-6), &so3::exp(&Vec3::zeros()));
    let dir = Vec3::new(0.04, 0.01, 0.15).normalize();
    q.extend(q_of(
        Vec3::new(0.0, 0.0, 0.1) + dir * (0.15 - 2e-6),
        &so3::exp(&Vec3::zeros()),
    ));
    let v = [
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -2.0, 0.0, 0.1, -0.05,
    ];
    let mut s = sim(&model, cm, &q, &v, &[0.0; 12]);
    let (d, kinks) = check("ball on a ball", &mut s, 1e-7, 1e-5);
    assert_eq!(kinks, 0);
    assert_eq!(pair_contacts(&d), 1, "{:?}", d.modes);
    assert!(d.held_normal.is_empty(), "{:?}", d.held_normal);
}

#[test]
fn a_capsule_across_a_box() {
    // a capsule lying across a box's top face on its two end caps, tilted 3 mrad, 2 µm in
    let bx = Free::cube(2.0, Vec3::new(0.4, 0.4, 0.1));
    let capsule = Free {
        mass: 0.3,
        inertia: rigid::mass::RotationalInertia::diagonal(0.002, 0.002, 0.0003),
        shape: Shape::Capsule {
            radius: 0.03,
            length: 0.2,
        },
    };
    let (model, cm) = scene(&[bx, capsule], down(), ground());
    let mut q = q_of(Vec3::new(0.0, 0.0, 0.05 - 1e-6), &so3::exp(&Vec3::zeros()));
    // the capsule's axis (z in its frame) laid along x, one end 0.3 mm higher
    let r = so3::exp(&Vec3::new(0.0, std::f64::consts::FRAC_PI_2 - 0.003, 0.2));
    let low = (r * Vec3::new(0.0, 0.0, 0.1))
        .z
        .min((r * Vec3::new(0.0, 0.0, -0.1)).z);
    q.extend(q_of(Vec3::new(0.01, 0.02, 0.1 + 0.03 - low - 2e-6), &r));
    let v = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.2, 0.0, -0.1];
    let mut s = sim(&model, cm, &q, &v, &[0.0; 12]);
    let (d, kinks) = check("capsule across a box", &mut s, 1e-7, 1e-5);
    assert_eq!(kinks, 0);
    assert!(pair_contacts(&d) >= 1, "{:?}", d.modes);
    assert!(d.held_normal.is_empty(), "{:?}", d.held_normal);
}

/// A solid body of `shape` with a rough inertia (the derivatives do not care how round).
fn body(mass: f64, shape: Shape) -> Free {
    let i = 0.002 * mass;
    Free {
        mass,
        inertia: rigid::mass::RotationalInertia::diagonal(i, 1.2 * i, 0.8 * i),
        shape,
    }
}

/// One step's derivatives of a pair of free bodies 2 µm into each other without ground or
/// gravity: body 0 at the origin turned by `r0`, body 1 at `c1` turned by `r1`, with the
/// velocities `v`, against central differences; the pair must push, its normal followed.
fn pair(what: &str, shapes: [Free; 2], (r0, r1): (Vec3, Vec3), c1: Vec3, v: &[f64; 12]) {
    let (model, cm) = scene(&shapes, Vec3::zeros(), None);
    let mut q = q_of(Vec3::zeros(), &so3::exp(&r0));
    q.extend(q_of(c1, &so3::exp(&r1)));
    let mut s = sim(&model, cm, &q, v, &[0.0; 12]);
    let (d, kinks) = check(what, &mut s, 1e-7, 1e-5);
    assert_eq!(kinks, 0, "{what}");
    assert_eq!(pair_contacts(&d), 1, "{what}: {:?}", d.modes);
    assert!(d.held_normal.is_empty(), "{what}: {:?}", d.held_normal);
}

fn capsule(radius: f64, length: f64) -> Shape {
    Shape::Capsule { radius, length }
}

#[test]
fn edges_and_axes_across_each_other() {
    let v = [
        0.3, -0.2, 0.1, 0.05, 0.1, 0.2, -0.2, 0.4, 0.3, -0.1, 0.05, -0.3,
    ];
    // two capsules crossing at 1.2 rad (their axes' common perpendicular), both lying along
    // the horizontal plane
    let flat = |yaw: f64| {
        so3::log(&(so3::exp(&Vec3::new(0.0, 0.0, yaw)) * so3::exp(&Vec3::new(1.5, 0.0, 0.0))))
    };
    pair(
        "capsule across a capsule",
        [body(1.0, capsule(0.05, 0.4)), body(0.5, capsule(0.03, 0.3))],
        (flat(0.0), flat(1.2)),
        Vec3::new(0.02, -0.01, 0.08 - 2e-6),
        &v,
    );
    // a box's edge across another box's edge: each turned 45° about a horizontal axis, the
    // upper one also 1 rad about z
    let edge = std::f64::consts::FRAC_PI_4;
    let cube = |m: f64, a: f64| Free::cube(m, Vec3::new(a, a, a));
    let r1 =
        so3::log(&(so3::exp(&Vec3::new(0.0, 0.0, 1.0)) * so3::exp(&Vec3::new(edge, 0.0, 0.0))));
    let h = 0.1 * std::f64::consts::SQRT_2 / 2.0;
    pair(
        "edge across an edge",
        [cube(1.0, 0.1), cube(0.7, 0.1)],
        (Vec3::new(0.0, edge, 0.0), r1),
        Vec3::new(0.003, -0.002, 2.0 * h - 2e-6),
        &v,
    );
    // a ball on a box's edge, and a capsule's side on a ball
    pair(
        "ball on an edge",
        [cube(1.0, 0.1), Free::ball(0.3, 0.04)],
        (Vec3::new(0.0, edge, 0.0), Vec3::zeros()),
        Vec3::new(0.0, 0.01, h + 0.04 - 2e-6),
        &v,
    );
    pair(
        "capsule's side on a ball",
        [Free::ball(1.0, 0.05), body(0.4, capsule(0.03, 0.3))],
        (Vec3::zeros(), Vec3::new(0.0, 1.5, 0.2)),
        Vec3::new(0.02, 0.01, 0.08 - 2e-6),
        &v,
    );
}

#[test]
fn a_hull_on_a_hull() {
    // an octahedron's vertex on a tetrahedron's face (convex hulls: the face's normal)
    let octahedron = Shape::ConvexHull {
        points: vec![
            Vec3::new(0.05, 0.0, 0.0),
            Vec3::new(-0.05, 0.0, 0.0),
            Vec3::new(0.0, 0.05, 0.0),
            Vec3::new(0.0, -0.05, 0.0),
            Vec3::new(0.0, 0.0, 0.05),
            Vec3::new(0.0, 0.0, -0.05),
        ],
    };
    let slab = Shape::ConvexHull {
        points: vec![
            Vec3::new(-0.2, -0.2, -0.05),
            Vec3::new(0.2, -0.2, -0.05),
            Vec3::new(-0.2, 0.2, -0.05),
            Vec3::new(0.2, 0.2, -0.05),
            Vec3::new(-0.15, -0.15, 0.05),
            Vec3::new(0.15, -0.15, 0.05),
            Vec3::new(-0.15, 0.15, 0.05),
            Vec3::new(0.15, 0.15, 0.05),
        ],
    };
    let v = [
        0.3, -0.2, 0.1, 0.05, 0.1, 0.2, -0.2, 0.4, 0.3, -0.1, 0.05, -0.3,
    ];
    pair(
        "octahedron's vertex on a slab's face",
        [body(2.0, slab), body(0.5, octahedron)],
        (Vec3::new(0.01, -0.02, 0.1), Vec3::new(0.05, 0.02, 0.3)),
        Vec3::new(0.02, 0.01, 0.1 - 2e-6),
        &v,
    );
}

#[test]
fn rims_rolling_on_the_ground() {
    // a cylinder on its side and a cone on its side, 2 µm into the ground, rolling and turning:
    // their points slide along the rims
    let cylinder = body(
        1.0,
        Shape::Cylinder {
            radius: 0.1,
            length: 0.2,
        },
    );
    let (model, cm) = scene(&[cylinder], down(), ground());
    // its axis (z) along the ground, turned 0.3 rad about the vertical
    let r = so3::exp(&Vec3::new(0.0, 0.0, 0.3))
        * so3::exp(&Vec3::new(std::f64::consts::FRAC_PI_2, 0.0, 0.0));
    let q = q_of(Vec3::new(0.0, 0.0, 0.1 - 2e-6), &r);
    // spinning about its axis, rolling forward, turning about the vertical
    let w = r.transpose() * Vec3::new(0.0, 0.0, 0.5);
    let v = [w.x, w.y, w.z + 5.0, 0.5, 0.0, 0.0];
    let mut s = sim(&model, cm, &q, &v, &[0.0; 6]);
    let (d, kinks) = check("cylinder rolling", &mut s, 1e-7, 1e-5);
    assert_eq!(kinks, 0);
    assert!(
        d.modes
            .iter()
            .filter(|m| **m != ContactMode::Separated)
            .count()
            >= 2,
        "{:?}",
        d.modes
    );

    let cone = body(
        1.0,
        Shape::Cone {
            radius: 0.1,
            height: 0.3,
        },
    );
    let (model, cm) = scene(&[cone], down(), ground());
    // on its side (base at z = −h/4, apex at 3h/4 in its frame): the axis tilted by the
    // half-angle atan(r/h) from the ground
    let tilt = (0.1_f64 / 0.3).atan();
    let r = so3::exp(&Vec3::new(0.0, 0.0, 0.4))
        * so3::exp(&Vec3::new(std::f64::consts::FRAC_PI_2 - tilt, 0.0, 0.0));
    let mut low = f64::INFINITY;
    for k in 0..720 {
        let t = k as f64 / 720.0 * std::f64::consts::TAU;
        low = low.min((r * Vec3::new(0.1 * t.cos(), 0.1 * t.sin(), -0.075)).z);
    }
    low = low.min((r * Vec3::new(0.0, 0.0, 0.225)).z);
    let q = q_of(Vec3::new(0.0, 0.0, -low - 2e-6), &r);
    // turning about the vertical and spinning about its axis
    let w = r.transpose() * Vec3::new(0.0, 0.0, 1.5) + Vec3::new(0.0, 0.0, 2.0);
    let v = [w.x, w.y, w.z, 0.0, 0.0, 0.0];
    let mut s = sim(&model, cm, &q, &v, &[0.0; 6]);
    let (d, kinks) = check("cone rolling", &mut s, 1e-7, 1e-5);
    assert_eq!(kinks, 0);
    assert!(
        d.modes.iter().any(|m| *m != ContactMode::Separated),
        "{:?}",
        d.modes
    );
}

#[test]
fn a_coin_rolling_on_a_box() {
    // a cylinder leaning 0.1 rad, sliding and spinning on its rim on a tilted, turning box's
    // top face (the face's normal turns with the box, the rim's point slides), 2 µm in, no
    // ground: the box falls with it. Checked to 1e-3 (it agrees to 2.2e-5; with the normal held
    // 2.8e-3): parry's cylinder–box contact moves with the box's position along its own face
    // (a static box moved 1 mm along its face changes the coin's spin after one step by 5e-7
    // rad/s, where the coin cannot tell), which the differences see and the derivatives do not
    let bx = Free::cube(2.0, Vec3::new(0.4, 0.4, 0.1));
    let coin = body(
        1.0,
        Shape::Cylinder {
            radius: 0.1,
            length: 0.02,
        },
    );
    let (model, cm) = scene(&[bx, coin], down(), None);
    let rb = so3::exp(&Vec3::new(0.02, -0.01, 0.1));
    let mut q = q_of(Vec3::zeros(), &rb);
    // the coin's axis (z) along the face, leaning 0.1 rad about its rolling direction
    let r = rb
        * so3::exp(&Vec3::new(0.0, 0.0, 0.3))
        * so3::exp(&Vec3::new(std::f64::consts::FRAC_PI_2 - 0.1, 0.0, 0.0));
    let mut low = f64::INFINITY;
    for k in 0..3600 {
        let t = k as f64 / 3600.0 * std::f64::consts::TAU;
        for h in [-0.01, 0.01] {
            let x = rb.transpose() * (r * Vec3::new(0.1 * t.cos(), 0.1 * t.sin(), h));
            low = low.min(x.z);
        }
    }
    let n = rb * Vec3::z();
    q.extend(q_of(
        rb * Vec3::new(0.03, -0.02, 0.05) + n * (-low - 2e-6),
        &r,
    ));
    let w = r.transpose() * (n * 0.5);
    let v = [
        0.1,
        0.0,
        -0.2,
        0.0,
        0.1,
        0.0,
        w.x,
        w.y,
        w.z + 5.0,
        0.5,
        0.0,
        -0.1,
    ];
    let mut s = sim(&model, cm, &q, &v, &[0.0; 12]);
    let (d, kinks) = check("coin on a box", &mut s, 1e-7, 1e-3);
    assert_eq!(kinks, 0);
    assert_eq!(pair_contacts(&d), 1, "{:?}", d.modes);
    assert!(d.held_normal.is_empty(), "{:?}", d.held_normal);
}

#[test]
fn a_differential_drive_rolling_on_its_wheels() {
    // examples/diff_drive.urdf with 4 cm treads (its own 4 mm treads' two points 4 mm apart
    // leave projected Gauss–Seidel unconverged after 100,000 sweeps, so that differences of
    // the step are its noise) and a ball caster (its 2 cm caster wheel's two points part the
    // forward and backward differences by 3e-2: docs/contact.md), driven straight for 0.3 s,
    // then pressed 3 µm into the ground (inside one mode: the resting gap is g h²). The wheels
    // meet the ground at their rims' lowest points, which slide along the rims as they turn
    use rigid::io::collision::{urdf_world, WorldOptions};
    use rigid::io::urdf::{load_urdf_str, parse_urdf_str};
    use rigid::simulation::{OpenLoop, Scenario};
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/diff_drive.urdf");
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace(
            r#"<cylinder radius="0.03" length="0.02"/>"#,
            r#"<sphere radius="0.03"/>"#,
        )
        .replace(
            r#"<cylinder radius="0.08" length="0.004"/>"#,
            r#"<cylinder radius="0.08" length="0.04"/>"#,
        );
    let model = load_urdf_str(&text, true).unwrap();
    let options = WorldOptions {
        ground: Some(0.0),
        friction: Some(1.0),
        ..WorldOptions::default()
    };
    let (cm, _) = urdf_world(&parse_urdf_str(&text).unwrap(), &model, &options).unwrap();
    let v_of = |name: &str| model.joints()[model.joint_id(name).unwrap().0].idx_v;
    let mut tau = vec![0.0; model.nv()];
    tau[v_of("left_wheel_joint")] = 0.2;
    tau[v_of("right_wheel_joint")] = 0.2;
    let mut s = Scenario::new(model.clone());
    s.collision = cm;
    s.options = super::options(1e-3);
    let mut sim = s
        .build_with(OpenLoop(tau))
        .unwrap()
        .with_contact_settings(super::step_derivatives::settings())
        .unwrap();
    for _ in 0..300 {
        sim.step().unwrap();
    }
    let (mut q, v) = (sim.q().to_vec(), sim.v().to_vec());
    assert!(v[3] > 0.05, "{v:?}");
    q[2] -= 3e-6;
    sim.set_state(&q, &v).unwrap();
    let (d, kinks) = check("differential drive", &mut sim, 1e-7, 1e-5);
    assert_eq!(kinks, 0);
    assert_eq!(d.modes, [ContactMode::Sticking; 5]);
}
