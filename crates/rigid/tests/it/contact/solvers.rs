//! The two contact solvers on the same rows (issue 48, item 2): ADMM meets the closed forms PGS
//! meets, the two agree where the impulse is unique, and the ContactBench residuals of a step
//! tell a converged solve from one cut short.

use super::{com, q_of, scene, simulator, Free, G};
use rigid::collision::Ground;
use rigid::simulation::contact::{ContactSettings, Solver};
use rigid::simulation::Simulator;
use rigid::spatial::{Mat3, Vec3};

fn with(sim: Simulator, solver: Solver, max_iterations: usize) -> Simulator {
    sim.with_contact_settings(ContactSettings {
        solver,
        max_iterations,
        ..ContactSettings::default()
    })
    .unwrap()
}

/// A box on a slope with μ = 0.5 under ADMM: it sticks at tan θ = 0.45 (< 1 mm in 2 s) and
/// slides at tan θ = 0.55 with `a = g (sin θ − μ cos θ)` within 1 %, the bars PGS meets
/// (closed_form.rs).
#[test]
fn admm_sticks_and_slides_on_a_slope_at_the_friction_angle() {
    let mu = 0.5;
    for (slope, sticks) in [(0.45f64, true), (0.55, false)] {
        let theta = slope.atan();
        let gravity = Vec3::new(G * theta.sin(), 0.0, -G * theta.cos());
        let (model, cm) = scene(
            &[Free::cube(2.0, Vec3::new(0.2, 0.16, 0.1))],
            gravity,
            Some(Ground::horizontal(0.0, mu)),
        );
        let q0 = q_of(Vec3::new(0.0, 0.0, 0.05), &Mat3::identity());
        let mut sim = with(
            simulator(&model, cm, &q0, &[0.0; 6], 1e-3),
            Solver::Admm,
            200,
        );
        let mut converged = 0;
        for _ in 0..2000 {
            sim.step().unwrap();
            converged += usize::from(sim.contact_stats().converged);
        }
        let (p, v) = com(&sim, 0);
        let expected = G * (theta.sin() - mu * theta.cos());
        let a = v.x / sim.time();
        println!(
            "admm, tan θ = {slope}: moved {:.2e} m, a = {a:.5} (expected {expected:.5}), {converged} of 2000 steps converged, residuals {:?}",
            p.x,
            sim.contact_stats().residuals
        );
        if sticks {
            assert!(p.x.abs() < 1e-3 && v.norm() < 1e-6, "{p} {v}");
        } else {
            assert!((a - expected).abs() < 0.01 * expected, "{a} vs {expected}");
        }
        assert!(converged >= 1990, "{converged} of 2000 steps converged");
        assert!((p.z - 0.05).abs() < 1e-5, "{p}");
    }
}

/// Three boxes stacked under ADMM stand (within 1 mm for 5 s), the velocity solves after the
/// first steps meeting the tolerance (7 of 4990 do not, measured), the residuals of the last
/// step near round-off.
#[test]
fn admm_holds_a_tower_of_three_boxes() {
    let size = Vec3::new(0.3, 0.3, 0.2);
    let boxes = [
        Free::cube(4.0, size),
        Free::cube(2.0, size),
        Free::cube(1.0, size),
    ];
    let (model, cm) = scene(
        &boxes,
        Vec3::new(0.0, 0.0, -G),
        Some(Ground::horizontal(0.0, 0.8)),
    );
    let start: Vec<Vec3> = (0..3)
        .map(|i| Vec3::new(0.0, 0.0, 0.1 + 0.2 * i as f64))
        .collect();
    let q0: Vec<f64> = start
        .iter()
        .flat_map(|p| q_of(*p, &Mat3::identity()))
        .collect();
    let mut sim = with(
        simulator(&model, cm, &q0, &[0.0; 18], 1e-3),
        Solver::Admm,
        200,
    );
    let (mut worst, mut unconverged): (f64, usize) = (0.0, 0);
    for k in 0..5000 {
        sim.step().unwrap();
        for (i, p) in start.iter().enumerate() {
            worst = worst.max((com(&sim, i).0 - p).norm());
        }
        if k >= 10 && !sim.contact_stats().converged {
            unconverged += 1;
        }
    }
    let s = sim.contact_stats();
    println!("admm tower: moved {worst:.2e} m, {unconverged} solves unconverged, last {s:?}");
    assert!(worst < 1e-3, "the tower moved {worst} m");
    assert!(unconverged <= 10, "{unconverged} solves did not converge");
    // the weight of 7 kg over 1 ms is 0.069 N·s: residuals of 1e-12 of that scale
    let r = s.residuals;
    assert!(r.signorini < 1e-12 && r.dissipation < 1e-12, "{r:?}");
    assert!(r.coulomb < 1e-15 && r.velocity_error < 1e-9, "{r:?}");
}

/// Where the impulse is unique (one ball, one contact, sliding then rolling), the two solvers
/// give the same steps: the velocities after 200 steps agree to 1e-8 (measured 1.2e-9: each
/// solve stops within its tolerance, 1e-10 of the impulse).
#[test]
fn pgs_and_admm_agree_where_the_impulse_is_unique() {
    let run = |solver| {
        let (model, cm) = scene(
            &[Free::ball(1.0, 0.1)],
            Vec3::new(0.0, 0.0, -G),
            Some(Ground::horizontal(0.0, 0.3)),
        );
        let q0 = q_of(Vec3::new(0.0, 0.0, 0.1), &Mat3::identity());
        let v0 = [0.0, 0.0, 0.0, 2.0, 0.0, 0.0];
        let mut sim = with(simulator(&model, cm, &q0, &v0, 1e-3), solver, 200);
        sim.run(200, |_| {}).unwrap();
        (sim.v().to_vec(), sim.contact_stats())
    };
    let ((a, sa), (b, sb)) = (run(Solver::Pgs), run(Solver::Admm));
    let d = a
        .iter()
        .zip(&b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    println!("ball: PGS {a:?} ({sa:?}), ADMM {b:?} ({sb:?}), largest difference {d:.2e}");
    assert!(sa.converged && sb.converged);
    assert!(d < 1e-8, "the solvers differ by {d}");
}

/// The residuals tell a solve cut short from a converged one: the tower's first steps under
/// one sweep of PGS leave residuals 1e4 times those of the converged solve, and say
/// `converged: false`.
#[test]
fn the_residuals_name_a_solve_cut_short() {
    let size = Vec3::new(0.3, 0.3, 0.2);
    let boxes = [Free::cube(4.0, size), Free::cube(2.0, size)];
    let (model, cm) = scene(
        &boxes,
        Vec3::new(0.0, 0.0, -G),
        Some(Ground::horizontal(0.0, 0.8)),
    );
    let q0: Vec<f64> = (0..2)
        .flat_map(|i| {
            q_of(
                Vec3::new(0.01 * i as f64, 0.0, 0.1 + 0.2 * i as f64),
                &Mat3::identity(),
            )
        })
        .collect();
    let last = |iterations| {
        let sim = simulator(&model, cm.clone(), &q0, &[0.0; 12], 1e-3);
        let mut sim = with(sim, Solver::Pgs, iterations);
        sim.run(20, |_| {}).unwrap();
        sim.contact_stats()
    };
    let (short, full) = (last(1), last(200));
    println!("one sweep: {short:?}\nconverged: {full:?}");
    assert!(!short.converged && full.converged);
    let (a, b) = (short.residuals, full.residuals);
    assert!(
        a.velocity_error > 1e4 * b.velocity_error.max(1e-16),
        "{a:?} vs {b:?}"
    );
    assert!(a.signorini.max(a.dissipation) > 1e4 * b.signorini.max(b.dissipation).max(1e-20));
}

/// The sweep's active-set polish (`contact/polish.rs`) ends a solve only at a solution:
/// gymnasium's ant (a free torso on four two-hinge legs with limits) in its file's world for
/// 1 s, every solve that converged (by the sweep's test or by an accepted polish) has the
/// ContactBench residuals of a solution.
#[test]
fn every_converged_solve_of_the_ant_is_a_solution() {
    use rigid::io::collision::{mjcf_file_world, WorldOptions};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mujoco/models/ant.xml");
    let mj = rigid::io::mjcf::load_mjcf(&path).unwrap();
    let world = mjcf_file_world(&mj, &WorldOptions::default()).unwrap();
    let sim = rigid::simulation::Scenario::in_world(mj.model.clone(), world)
        .build()
        .unwrap();
    let mut sim = sim
        .with_contact_settings(ContactSettings {
            polish: true,
            ..ContactSettings::default()
        })
        .unwrap();
    let (mut solves, mut sweeps, mut converged, mut worst) = (0usize, 0usize, 0usize, 0.0f64);
    for _ in 0..1000 {
        sim.step().unwrap();
        let s = sim.contact_stats();
        if s.iterations > 0 {
            solves += 1;
            sweeps += s.iterations;
            if s.converged {
                converged += 1;
                let r = s.residuals;
                worst = worst
                    .max(r.signorini)
                    .max(r.dissipation)
                    .max(r.velocity_error);
            }
        }
    }
    let mean = sweeps as f64 / solves as f64;
    eprintln!("{solves} solves, {converged} converged, {mean:.1} sweeps on average, largest residual {worst:.1e}");
    assert!(solves > 500, "the ant did not land: {solves} solves");
    assert!(converged > solves / 2, "{converged} of {solves} converged");
    assert!(worst <= 1e-9, "largest residual {worst:e}");
}

/// The polish gives the sweep's own step, only sooner: with the tolerance at round-off, a ball
/// 5 cm deep in a tilted box resting on two of its corners (the position correction then holds
/// four coplanar corners to targets no rigid motion meets: a singular, inconsistent system whose
/// regularised step, 8e11 along the null direction, once left 1e-4 of round-off in σ) steps to
/// the same state with the polish on and off, the polish ending the solve after 4 sweeps; a box
/// resting on a box's face (eight corners, four redundant on each face: the polish's split of
/// the weight leaves a corner outside its cone, and it is refused) steps to the same state,
/// the refused polishes leaving the sweep as it was.
#[test]
fn the_polish_gives_the_sweeps_step() {
    use rigid::spatial::so3;
    let down = Vec3::new(0.0, 0.0, -G);
    let r = so3::exp(&Vec3::new(0.01, -0.02, 0.1));
    let mut deep = q_of(Vec3::new(0.0, 0.0, 0.05 - 1e-6), &r);
    deep.extend(q_of(
        r * Vec3::new(0.1, -0.05, 0.05) + r * Vec3::z() * (0.05 - 2e-6),
        &Mat3::identity(),
    ));
    let r2 = so3::exp(&Vec3::new(2e-6, -1e-6, 0.3));
    let mut stacked = q_of(Vec3::new(0.0, 0.0, 0.05 - 1e-6), &Mat3::identity());
    stacked.extend(q_of(Vec3::new(0.02, -0.01, 0.15 - 4e-6), &r2));
    let scenes = [
        (
            "a ball deep in a box",
            vec![
                Free::cube(2.0, Vec3::new(0.4, 0.4, 0.1)),
                Free::ball(0.5, 0.05),
            ],
            deep,
            [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0, -1.0, 0.5, 0.3, 0.1, 0.0],
        ),
        (
            "a box on a box",
            vec![
                Free::cube(2.0, Vec3::new(0.4, 0.4, 0.1)),
                Free::cube(1.0, Vec3::new(0.2, 0.15, 0.1)),
            ],
            stacked,
            [0.0; 12],
        ),
    ];
    for (k, (what, bodies, q0, v0)) in scenes.into_iter().enumerate() {
        let (model, cm) = scene(&bodies, down, Some(Ground::horizontal(0.0, 0.8)));
        let step = |polish: bool| {
            let mut sim = simulator(&model, cm.clone(), &q0, &v0, 1e-3)
                .with_contact_settings(ContactSettings {
                    polish,
                    max_iterations: 5000,
                    tolerance: 1e-15,
                    ..ContactSettings::default()
                })
                .unwrap();
            sim.step().unwrap();
            let s = sim.contact_stats();
            assert!(s.converged, "{what}: {s:?}");
            (sim.q().to_vec(), sim.v().to_vec(), s.iterations)
        };
        let (q1, v1, sweeps) = step(false);
        let (q2, v2, polished) = step(true);
        let dq = q1
            .iter()
            .zip(&q2)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        let dv = v1
            .iter()
            .zip(&v2)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        let scale = v1.iter().fold(1.0f64, |a, x| a.max(x.abs()));
        eprintln!(
            "{what}: {sweeps} sweeps, {polished} with the polish; |Δq⁺| {dq:.1e} m, |Δv⁺| {dv:.1e}"
        );
        if k == 0 {
            assert!(
                polished < sweeps,
                "{what}: the polish did not end the solve"
            );
        }
        assert!(dq <= 1e-12 && dv <= 1e-11 * scale, "{what}: {dq:e} {dv:e}");
    }
}
