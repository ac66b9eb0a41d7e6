//! Per-call time of the constrained dynamics in Rust alone (no Python): Solo-12 and ANYmal with
//! four point contacts at the feet, TALOS with its two soles held (frame constraints), all local,
//! `μ = 0`. Fastest of 21 batches of 2000 calls at one state; the same constraints as
//! `bench/constraints.py`, which compares with Pinocchio through both Python bindings.
//! Run with `cargo run --release -p rigid --example constraints_timing`.

use rigid::io::urdf::{load_urdf_with, SiblingOrder, UrdfOptions};
use rigid::multibody::constraints::{
    constraint_dynamics, impulse_dynamics, ConstraintData, ConstraintKind, ConstraintModel,
    ProximalSettings,
};
use rigid::multibody::{forward_kinematics_q, neutral, update_frame_placements, Data};
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let erd = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/robots/example-robot-data/robots/"
    );
    let cases = [
        (
            "Solo-12, 4 points",
            "solo_description/robots/solo12.urdf",
            ConstraintKind::Point,
            &["FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"][..],
        ),
        (
            "ANYmal, 4 points",
            "anymal_b_simple_description/robots/anymal.urdf",
            ConstraintKind::Point,
            &["LF_FOOT", "RF_FOOT", "LH_FOOT", "RH_FOOT"][..],
        ),
        (
            "TALOS, 2 frames",
            "talos_data/robots/talos_reduced.urdf",
            ConstraintKind::Frame,
            &["left_sole_link", "right_sole_link"][..],
        ),
    ];
    for (name, path, kind, feet) in cases {
        let opts = UrdfOptions {
            floating: true,
            sibling_order: SiblingOrder::Name,
            ..UrdfOptions::default()
        };
        let model = load_urdf_with(format!("{erd}{path}"), &opts)
            .expect("fixture")
            .0;
        let mut data = Data::new(&model);
        let q0 = neutral(&model);
        forward_kinematics_q(&model, &mut data, &q0).expect("q");
        update_frame_placements(&model, &mut data);
        let constraints: Vec<ConstraintModel> = feet
            .iter()
            .map(|f| {
                let mut c = ConstraintModel::on_frames(&model, kind, f, "universe").expect("frame");
                c.placement2 = data.frame_placements[model.frame_id(f).expect("frame").0];
                c
            })
            .collect();
        let mut cd = ConstraintData::new(&model, &constraints).expect("valid");
        let nv = model.nv();
        let mut q = q0.clone();
        for (k, x) in q.iter_mut().enumerate().skip(7) {
            *x += 0.3 * ((k as f64) * 1.7).sin();
        }
        let v: Vec<f64> = (0..nv).map(|k| ((k as f64) * 0.9).cos()).collect();
        let tau: Vec<f64> = (0..nv).map(|k| ((k as f64) * 1.3).sin()).collect();
        let s = ProximalSettings::default();
        let time = |f: &mut dyn FnMut()| {
            (0..21)
                .map(|_| {
                    let t = Instant::now();
                    for _ in 0..2000 {
                        f();
                    }
                    t.elapsed().as_secs_f64() / 2000.0
                })
                .fold(f64::INFINITY, f64::min)
        };
        let fwd = time(&mut || {
            black_box(
                constraint_dynamics(&model, &mut data, &mut cd, &q, &v, &tau, &s).expect("solves"),
            );
        });
        let imp = time(&mut || {
            black_box(
                impulse_dynamics(&model, &mut data, &mut cd, &q, &v, 0.0, &s).expect("solves"),
            );
        });
        println!(
            "{name} (nv = {nv}): constraint_dynamics {:.2} µs, impulse_dynamics {:.2} µs",
            fwd * 1e6,
            imp * 1e6
        );
    }
}
