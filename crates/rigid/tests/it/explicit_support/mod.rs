//! Shared by the `explicit_*` tests (and the `explicit` benchmark): the models (built-ins and
//! example-robot-data URDFs), random states, and running generated code.
#![allow(dead_code)]

use rigid::explicit::lock_joints;
use rigid::io::urdf::load_urdf;
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::{
    builtin, random_configuration, JointId, JointType, Model, ModelBuilder, Rng,
};
use rigid::spatial::{so3, Transform, Vec3};
use std::path::PathBuf;
use std::process::Command;

/// The `robots/` folder of example-robot-data: the copy checked in under
/// `tests/fixtures/robots/` (the files the tests load, copied from the pinned PyPI package by
/// `gen_robots.py` there).
pub fn robots_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/robots/example-robot-data/robots")
}

/// The UR5 of example-robot-data.
pub fn ur5() -> Model {
    load_urdf(
        robots_dir().join("ur_description/urdf/ur5_robot.urdf"),
        false,
    )
    .expect("ur5 loads")
}

/// The Panda of example-robot-data with its two prismatic finger joints locked at 0 (their
/// bodies merged into the 7th link): the 7-joint arm.
pub fn panda_arm() -> Model {
    let panda = load_urdf(
        robots_dir().join("panda_description/urdf/panda.urdf"),
        false,
    )
    .expect("panda loads");
    let locks = [
        ("panda_finger_joint1".to_string(), 0.0),
        ("panda_finger_joint2".to_string(), 0.0),
    ];
    lock_joints(&panda, &locks).expect("fingers lock")
}

/// `(name, model)` of the models every exact-mode test covers.
pub fn models() -> Vec<(&'static str, Model)> {
    vec![
        ("pendulum", builtin("pendulum").unwrap()),
        ("double_pendulum", builtin("double_pendulum").unwrap()),
        ("puma560", builtin("puma560").unwrap()),
        ("ur5", ur5()),
        ("panda", panda_arm()),
    ]
}

/// `count` random states `(q, v)`: `q` within the joint limits, `v` uniform in `[-2, 2]`.
pub fn states(model: &Model, count: usize, seed: u64) -> Vec<(Vec<f64>, Vec<f64>)> {
    let mut rng = Rng::new(seed);
    (0..count)
        .map(|_| {
            let q = random_configuration(model, &mut rng);
            let v = (0..model.nv()).map(|_| rng.uniform(-2.0, 2.0)).collect();
            (q, v)
        })
        .collect()
}

/// `‖x - y‖∞ / ‖y‖∞` (with a floor of 1e-300).
pub fn rel(x: &[f64], y: &[f64]) -> f64 {
    let d = x
        .iter()
        .zip(y)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    d / y.iter().map(|a| a.abs()).fold(1e-300, f64::max)
}

/// A fresh scratch folder under the target directory.
pub fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs a command, panics with its output if it fails; returns its standard output.
pub fn run(cmd: &mut Command, stdin: Option<&str>) -> String {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = cmd
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"));
    let mut input = child.stdin.take().unwrap();
    let text = stdin.unwrap_or("").to_string();
    let writer = std::thread::spawn(move || input.write_all(text.as_bytes()));
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    assert!(
        out.status.success(),
        "{cmd:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

pub fn unit(rng: &mut Rng) -> Vec3 {
    Vec3::new(rng.normal(), rng.normal(), rng.normal()).normalize()
}

/// A random model: `n` joints, revolute or (every third) prismatic on random axes, random
/// placements and inertias (with products of inertia), random armature; `tree`: random
/// depth-first parents.
pub fn random_model(seed: u64, n: usize, tree: bool) -> Model {
    let mut rng = Rng::new(seed);
    let mut b = ModelBuilder::new(&format!("random_{seed}"));
    b.set_gravity(Vec3::new(0.5, -0.3, -9.81));
    let mut stack: Vec<JointId> = Vec::new();
    for k in 0..n {
        let parent = if tree && !stack.is_empty() {
            let cut = 1 + (rng.next_u64() as usize) % stack.len();
            stack.truncate(cut);
            stack.last().copied()
        } else {
            stack.last().copied()
        };
        let axis = unit(&mut rng);
        let kind = if k % 3 == 2 {
            JointType::Prismatic { axis }
        } else {
            JointType::Revolute { axis }
        };
        let placement = Transform::new(
            so3::exp(&(unit(&mut rng) * rng.uniform(-2.0, 2.0))),
            Vec3::new(
                rng.uniform(-0.4, 0.4),
                rng.uniform(-0.4, 0.4),
                rng.uniform(-0.4, 0.4),
            ),
        );
        let (a, bb) = (rng.uniform(0.01, 0.1), rng.uniform(0.01, 0.1));
        let c = rng.uniform((a - bb).abs() + 0.001, a + bb);
        let r = so3::exp(&(unit(&mut rng) * rng.uniform(-3.0, 3.0)));
        let inertia = SpatialInertia::from_com(
            rng.uniform(0.5, 2.0),
            Vec3::new(
                rng.uniform(-0.2, 0.2),
                rng.uniform(-0.2, 0.2),
                rng.uniform(-0.2, 0.2),
            ),
            RotationalInertia::diagonal(a, bb, c).in_rotated_frame(&r),
        );
        let id = b
            .add_joint(parent, &format!("j{k}"), kind, placement, inertia)
            .unwrap();
        b.set_armature(id, &[rng.uniform(0.0, 0.3)]).unwrap();
        if kind.nq() == 1 && matches!(kind, JointType::Prismatic { .. }) {
            b.set_limits(id, &[-0.3], &[0.4], &[1.0], &[10.0]).unwrap();
        }
        stack.push(id);
    }
    b.build().unwrap()
}
