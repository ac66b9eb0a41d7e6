//! Centres of mass of the subtrees (position, velocity, acceleration), the centre-of-mass
//! Jacobian and the centroidal momentum (and its matrix) against Pinocchio 4.1 on UR5, Panda,
//! Solo-12 and TALOS (free-flyer roots for the last two), to 1e-9 relative.
//!
//! The fixture `tests/pinocchio/centroidal.json` is written by `tests/pinocchio/gen_centroidal.py`
//! (Pinocchio's `centerOfMass(q, v, a)`, `jacobianCenterOfMass`, `ccrba`,
//! `computeCentroidalMomentum`, in Pinocchio's raw layout); the robots are read from the
//! checked-in copies of their URDF files with sibling joints sorted by name (Pinocchio's order)
//! and the vectors go through [`PinocchioLayout`]. `RIGID_CROSSCHECK=1` also re-runs the generator
//! and checks that the committed fixture is what it writes.
#![allow(non_snake_case)]

use crate::common;
use common::json::{mat_of, vec_of};
use common::reference;
use nalgebra::DMatrix;
use rigid::interop::PinocchioLayout;
use rigid::io::urdf::{load_urdf_with, SiblingOrder, UrdfOptions};
use rigid::multibody::*;
use rigid::spatial::Vec3;
use serde_json::Value;

const TOLERANCE: f64 = 1e-9;

/// `‖a - b‖∞ / max(‖b‖∞, 1)`.
fn rel(a: &[f64], b: &[f64]) -> f64 {
    reference::rel(a, b, 1.0)
}

fn v3(x: &Vec3) -> Vec<f64> {
    vec![x.x, x.y, x.z]
}

struct Robot {
    model: Model,
    layout: PinocchioLayout,
}

impl Robot {
    fn load(r: &Value) -> Self {
        let path = common::example_robot_data().join(r["urdf"].as_str().unwrap());
        let opts = UrdfOptions {
            floating: r["floating"].as_bool().unwrap(),
            sibling_order: SiblingOrder::Name,
            ..UrdfOptions::default()
        };
        let model = load_urdf_with(&path, &opts).unwrap().0;
        let layout = PinocchioLayout::new(&model);
        assert_eq!(layout.nq(), r["nq"].as_u64().unwrap() as usize);
        Self { model, layout }
    }

    fn q(&self, s: &Value) -> Vec<f64> {
        let mut q = vec![0.0; self.model.nq()];
        self.layout
            .q_from_pinocchio(&vec_of(&s["q"]), &mut q)
            .unwrap();
        q
    }

    /// A velocity-space vector of Pinocchio's layout in rigid's (the map is an involution).
    fn v(&self, x: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; x.len()];
        self.layout.permute_v(x, &mut out);
        out
    }

    /// A 6 x nv matrix of rigid's (rows angular first) in Pinocchio's layout, row-major.
    fn six_by_nv(&self, m: &DMatrix<f64>) -> Vec<f64> {
        (0..6)
            .flat_map(|r| (0..m.ncols()).map(move |c| (r, c)))
            .map(|(r, c)| m[((r + 3) % 6, self.layout.v_index(c))])
            .collect()
    }

    /// A 3 x nv matrix of rigid's in Pinocchio's layout, row-major.
    fn three_by_nv(&self, m: &DMatrix<f64>) -> Vec<f64> {
        (0..3)
            .flat_map(|r| (0..m.ncols()).map(move |c| (r, c)))
            .map(|(r, c)| m[(r, self.layout.v_index(c))])
            .collect()
    }
}

fn compare(name: &str, r: &Value) {
    let robot = Robot::load(r);
    let model = &robot.model;
    let mut d = Data::new(model);
    let mut worst: Vec<(&str, f64)> = Vec::new();
    let mut record = |what: &'static str, e: f64| {
        let e = if e.is_nan() { f64::INFINITY } else { e };
        match worst.iter_mut().find(|(w, _)| *w == what) {
            Some((_, m)) => *m = m.max(e),
            None => worst.push((what, e)),
        }
    };
    for s in r["states"].as_array().unwrap() {
        let q = robot.q(s);
        let v = robot.v(&vec_of(&s["v"]));
        let a = robot.v(&vec_of(&s["a"]));

        let c = subtree_centers_of_mass(
            model,
            &mut d,
            &q,
            KinematicLevel::Acceleration { v: &v, a: &a },
        )
        .unwrap();
        record("com", rel(&v3(&c), &vec_of(&s["com"])));
        record("vcom", rel(&v3(&d.com_velocity), &vec_of(&s["vcom"])));
        record("acom", rel(&v3(&d.com_acceleration), &vec_of(&s["acom"])));
        record("mass", rel(&[d.mass], &[s["mass"].as_f64().unwrap()]));
        let per_joint = |key: &str| -> Vec<f64> { mat_of(&s[key]).transpose().as_slice().to_vec() };
        let flat = |x: &[Vec3]| -> Vec<f64> { x.iter().flat_map(v3).collect() };
        record(
            "subtree com",
            rel(&flat(&d.subtree_coms), &per_joint("subtree_com")),
        );
        record(
            "subtree vcom",
            rel(&flat(&d.subtree_com_velocities), &per_joint("subtree_vcom")),
        );
        record(
            "subtree acom",
            rel(
                &flat(&d.subtree_com_accelerations),
                &per_joint("subtree_acom"),
            ),
        );
        record(
            "subtree mass",
            rel(&d.subtree_masses, &vec_of(&s["subtree_mass"])),
        );

        let J = jacobian_center_of_mass(model, &mut d, &q).unwrap().clone();
        record(
            "Jcom",
            rel(
                &robot.three_by_nv(&J),
                mat_of(&s["Jcom"]).transpose().as_slice(),
            ),
        );

        let Ag = centroidal_momentum_matrix(model, &mut d, &q, &v)
            .unwrap()
            .clone();
        record(
            "Ag",
            rel(
                &robot.six_by_nv(&Ag),
                mat_of(&s["Ag"]).transpose().as_slice(),
            ),
        );
        let h = d.centroidal_momentum;
        let hg_pin = [v3(&h.f), v3(&h.m)].concat();
        record("hg (ccrba)", rel(&hg_pin, &vec_of(&s["hg"])));
        let Ig = &d.centroidal_inertia;
        record(
            "Ig mass",
            rel(&[Ig.mass()], &[s["Ig_mass"].as_f64().unwrap()]),
        );
        record(
            "Ig inertia",
            rel(
                Ig.inertia_com().matrix().transpose().as_slice(),
                mat_of(&s["Ig_inertia"]).transpose().as_slice(),
            ),
        );
        assert!(
            Ig.com().norm() < 1e-12,
            "{name}: Ig is about the centre of mass"
        );

        let h = centroidal_momentum(model, &mut d, &q, &v).unwrap();
        record(
            "hg",
            rel(&[v3(&h.f), v3(&h.m)].concat(), &vec_of(&s["hg_direct"])),
        );
        record(
            "vcom (momentum)",
            rel(&v3(&d.com_velocity), &vec_of(&s["vcom_direct"])),
        );
    }
    let line: Vec<String> = worst.iter().map(|(w, e)| format!("{w} {e:.1e}")).collect();
    eprintln!("{name}: max relative error: {}", line.join(", "));
    for (what, e) in &worst {
        assert!(
            *e <= TOLERANCE,
            "{name}: {what} differs from Pinocchio by {e:.3e} relative"
        );
    }
}

#[test]
fn centres_of_mass_and_centroidal_momentum_equal_pinocchio_on_four_robots() {
    let fx = reference::fixture("pinocchio/centroidal.json");
    let robots = fx["robots"].as_object().unwrap();
    assert_eq!(robots.len(), 4);
    for (name, r) in robots {
        compare(name, r);
    }
    if reference::live("centroidal fixture regenerated from Pinocchio") {
        reference::check_generator("pinocchio/gen_centroidal.py");
    }
}

/// `h_G = A_G v`, `p = m ċ`, and the centre-of-mass Jacobian is the linear rows of `A_G / m`:
/// three identities between the verbs, on a random state of the floating TALOS.
#[test]
fn centroidal_identities_hold_on_talos() {
    let path = common::example_robot_data().join("talos_data/robots/talos_full_v2.urdf");
    let model = rigid::io::urdf::load_urdf(&path, true).unwrap();
    let mut d = Data::new(&model);
    let mut rng = Rng::new(5);
    let q = random_configuration(&model, &mut rng);
    let v: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
    let Ag = centroidal_momentum_matrix(&model, &mut d, &q, &v)
        .unwrap()
        .clone();
    let h1 = d.centroidal_momentum;
    let h2 = centroidal_momentum(&model, &mut d, &q, &v).unwrap();
    assert!((h1.m - h2.m).norm() + (h1.f - h2.f).norm() < 1e-10);
    let cdot = d.com_velocity;
    let m = d.mass;
    let J = jacobian_center_of_mass(&model, &mut d, &q).unwrap().clone();
    let Jv = &J * nalgebra::DVector::from_column_slice(&v);
    assert!((Vec3::new(Jv[0], Jv[1], Jv[2]) - cdot).norm() < 1e-10);
    let lin = Ag.rows(3, 3) / m;
    assert!((lin - J).amax() < 1e-10);
}
