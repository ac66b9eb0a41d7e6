//! Shared helpers for the multibody tests: a random kinematic tree and random states.
#![allow(dead_code, non_snake_case)]

pub mod json;
pub mod reference;

use nalgebra::{DMatrix, DVector};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::*;
use rigid::spatial::{so3, Mat3, Transform, Vec3};

/// A random unit vector.
pub fn unit(rng: &mut Rng) -> Vec3 {
    loop {
        let v = Vec3::new(rng.normal(), rng.normal(), rng.normal());
        if v.norm() > 1e-3 {
            return v.normalize();
        }
    }
}

/// A random rigid transform (rotation uniform-ish, translation in [-0.5, 0.5]³).
pub fn transform(rng: &mut Rng) -> Transform {
    let r = so3::exp(&(unit(rng) * rng.uniform(-3.0, 3.0)));
    Transform::new(
        r,
        Vec3::new(
            rng.uniform(-0.5, 0.5),
            rng.uniform(-0.5, 0.5),
            rng.uniform(-0.5, 0.5),
        ),
    )
}

/// A random physical inertia: mass in [0.5, 2], CoM in [-0.3, 0.3]³, principal moments
/// satisfying the triangle inequality, rotated.
pub fn inertia(rng: &mut Rng) -> SpatialInertia {
    let m = rng.uniform(0.5, 2.0);
    let a = rng.uniform(0.01, 0.1);
    let b = rng.uniform(0.01, 0.1);
    let c = rng.uniform((a - b).abs() + 0.001, a + b);
    let r = so3::exp(&(unit(rng) * rng.uniform(-3.0, 3.0)));
    let i = RotationalInertia::diagonal(a, b, c).in_rotated_frame(&r.transpose());
    let com = Vec3::new(
        rng.uniform(-0.3, 0.3),
        rng.uniform(-0.3, 0.3),
        rng.uniform(-0.3, 0.3),
    );
    SpatialInertia::from_com(m, com, i)
}

/// A random tree: a free-flyer root, then `n` joints of random types (revolute, continuous,
/// prismatic with random axes, spherical, planar) with random depth-first parents, random
/// placements and inertias, a welded body and an operational frame; random armature if asked.
pub fn random_tree(seed: u64, n: usize, armature: bool) -> Model {
    let mut rng = Rng::new(seed);
    let mut b = ModelBuilder::new(&format!("random_tree_{seed}"));
    b.set_gravity(Vec3::new(0.3, -0.2, -9.81));
    let root = b
        .add_joint(
            None,
            "root",
            JointType::FreeFlyer,
            transform(&mut rng),
            inertia(&mut rng),
        )
        .unwrap();
    if armature {
        // the free-flyer root too (CRBA writes its 6x6 block on its own path)
        let arm: Vec<f64> = (0..6).map(|_| rng.uniform(0.0, 0.5)).collect();
        b.set_armature(root, &arm).unwrap();
    }
    let mut stack = vec![root];
    for k in 0..n {
        let cut = 1 + (rng.next_u64() as usize) % stack.len();
        stack.truncate(cut.max(1));
        let parent = *stack.last().unwrap();
        let pick = rng.next_u64() % 6;
        let kind = match pick {
            // a coordinate axis ±x, ±y, ±z (the fast path of the joint transform)
            5 => {
                let k = (rng.next_u64() % 3) as usize;
                let sign = if rng.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
                JointType::Revolute {
                    axis: Vec3::ith(k, sign),
                }
            }
            0 => JointType::Revolute {
                axis: unit(&mut rng),
            },
            // a URDF `continuous` joint: revolute, marked below
            1 => JointType::Revolute {
                axis: unit(&mut rng),
            },
            2 => JointType::Prismatic {
                axis: unit(&mut rng),
            },
            3 => JointType::Spherical,
            _ => JointType::Planar,
        };
        // a coordinate-axis revolute joint gets an X_T without rotation every other time (a URDF
        // origin without rpy: the algorithms' unrotated fast paths)
        let mut x_t = transform(&mut rng);
        if pick == 5 && k % 2 == 0 {
            x_t.rotation = Mat3::identity();
        }
        let id = b
            .add_joint(Some(parent), &format!("j{k}"), kind, x_t, inertia(&mut rng))
            .unwrap();
        if pick == 1 {
            b.set_continuous(id).unwrap();
        }
        if armature {
            let arm: Vec<f64> = (0..kind.nv()).map(|_| rng.uniform(0.0, 0.5)).collect();
            b.set_armature(id, &arm).unwrap();
        }
        if k == n / 2 {
            b.add_fixed_body(
                Some(id),
                &format!("welded{k}"),
                transform(&mut rng),
                inertia(&mut rng),
            )
            .unwrap();
            b.add_frame(Some(id), &format!("tool{k}"), transform(&mut rng))
                .unwrap();
        }
        stack.push(id);
    }
    b.build().unwrap()
}

/// A free-flyer root and `n` joints drawn from every joint type, helical and universal
/// included, with random axes, pitches, placements, inertias and armature.
pub fn every_joint_tree(seed: u64, n: usize) -> Model {
    let mut rng = Rng::new(seed);
    let mut b = ModelBuilder::new(&format!("every_joint_{seed}"));
    b.set_gravity(Vec3::new(0.3, -0.2, -9.81));
    let root = b
        .add_joint(
            None,
            "root",
            JointType::FreeFlyer,
            transform(&mut rng),
            inertia(&mut rng),
        )
        .unwrap();
    let mut stack = vec![root];
    for k in 0..n {
        stack.truncate((1 + (rng.next_u64() as usize) % stack.len()).max(1));
        let kind = match k % 7 {
            0 => JointType::Helical {
                axis: unit(&mut rng),
                pitch: rng.uniform(-0.3, 0.3),
            },
            1 => JointType::Universal {
                axis1: unit(&mut rng),
                axis2: unit(&mut rng),
            },
            2 => JointType::Revolute {
                axis: unit(&mut rng),
            },
            3 => JointType::Prismatic {
                axis: unit(&mut rng),
            },
            4 => JointType::Spherical,
            5 => JointType::Planar,
            _ => JointType::Universal {
                axis1: Vec3::x(),
                axis2: Vec3::z(),
            },
        };
        let id = b
            .add_joint(
                Some(*stack.last().unwrap()),
                &format!("j{k}"),
                kind,
                transform(&mut rng),
                inertia(&mut rng),
            )
            .unwrap();
        let arm: Vec<f64> = (0..kind.nv()).map(|_| rng.uniform(0.0, 0.2)).collect();
        b.set_armature(id, &arm).unwrap();
        stack.push(id);
    }
    b.build().unwrap()
}

/// Every built-in model and a few random trees.
pub fn models() -> Vec<Model> {
    let mut v: Vec<Model> = builtin_names()
        .iter()
        .map(|n| builtin(n).unwrap())
        .collect();
    v.push(random_tree(1, 8, false));
    v.push(random_tree(2, 10, true));
    v.push(random_tree(3, 6, true));
    v.push(random_tree(4, 12, false));
    v.push(aligned_forest());
    v
}

/// Two trees from the world, neither with a free-flyer root (a revolute about z and a planar
/// joint), whose chains are revolute joints about ±x, ±y, ±z with X_T translations only (as in
/// most URDFs), with armature: the root-frame CRBA and the unrotated fast paths of ABA.
pub fn aligned_forest() -> Model {
    let mut rng = Rng::new(77);
    let mut b = ModelBuilder::new("aligned_forest");
    let shift = |rng: &mut Rng| {
        Transform::from_translation(Vec3::new(
            rng.uniform(-0.5, 0.5),
            rng.uniform(-0.5, 0.5),
            rng.uniform(-0.5, 0.5),
        ))
    };
    for (t, root_kind) in [JointType::Revolute { axis: Vec3::z() }, JointType::Planar]
        .into_iter()
        .enumerate()
    {
        let mut parent = b
            .add_joint(
                None,
                &format!("root{t}"),
                root_kind,
                transform(&mut rng),
                inertia(&mut rng),
            )
            .unwrap();
        for k in 0..4 {
            let axis = Vec3::ith(k % 3, if k % 2 == 0 { 1.0 } else { -1.0 });
            parent = b
                .add_joint(
                    Some(parent),
                    &format!("t{t}j{k}"),
                    JointType::Revolute { axis },
                    shift(&mut rng),
                    inertia(&mut rng),
                )
                .unwrap();
            b.set_armature(parent, &[0.05 * k as f64]).unwrap();
        }
    }
    b.build().unwrap()
}

/// A random state (q, v, a) of the model.
pub fn state(model: &Model, rng: &mut Rng) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let q = random_configuration(model, rng);
    let v = (0..model.nv()).map(|_| rng.uniform(-2.0, 2.0)).collect();
    let a = (0..model.nv()).map(|_| rng.uniform(-2.0, 2.0)).collect();
    (q, v, a)
}

/// `|x - y|_∞ / max(1, |y|_∞)`.
pub fn rel_err_v(x: &DVector<f64>, y: &DVector<f64>) -> f64 {
    (x - y).amax() / y.amax().max(1.0)
}

/// `|x - y|_∞ / max(1, |y|_∞)`.
pub fn rel_err_m(x: &DMatrix<f64>, y: &DMatrix<f64>) -> f64 {
    (x - y).amax() / y.amax().max(1.0)
}

/// `q ⊕ v dt` allocating (for tests).
pub fn step(model: &Model, q: &[f64], v: &[f64], dt: f64) -> Vec<f64> {
    let mut out = vec![0.0; model.nq()];
    integrate(model, q, v, dt, &mut out).unwrap();
    out
}

/// The folder of the checked-in fixtures, `tests/fixtures`.
pub fn fixtures_dir() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
}

/// The checked-in copy of a description package's folder (`tests/fixtures/robots/PACKAGE`, copied
/// from the pinned PyPI package by `gen_robots.py` there): for `example-robot-data` its `robots/`
/// folder. It holds only the files the tests load (its `README.md` lists them and their
/// licences); the live cross-checks (`RIGID_CROSSCHECK=1`) walk the installed packages.
pub fn robots(package: &str) -> std::path::PathBuf {
    let dir = fixtures_dir().join("robots").join(package);
    if package == "example-robot-data" {
        dir.join("robots")
    } else {
        dir
    }
}

/// The checked-in copy of example-robot-data's `robots/` folder ([`robots`]).
pub fn example_robot_data() -> std::path::PathBuf {
    robots("example-robot-data")
}

/// The `*.urdf` files under `dir`, recursively, sorted.
pub fn urdfs_under(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "urdf") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}
