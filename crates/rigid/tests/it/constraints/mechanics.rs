//! Closed forms and long runs: the rod on a spherical pivot of the notes 002 (a free body held by
//! a point constraint), a four-bar linkage simulated for 10 s, and a joint-coordinate coupling.

use super::load;
use nalgebra::{DVector, Vector2};
use rigid::body::lagrange::{equations_of_motion, no_force, rk4_step, RodOnPivot};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::constraints::{
    constraint_dynamics, ConstraintData, ConstraintModel, ProximalSettings,
};
use rigid::multibody::{
    crba, integrate, nonlinear_effects, Data, JointId, JointType, Model, ModelBuilder,
    ReferenceFrame,
};
use rigid::simulation::{ConstraintOptions, Controller, Integrator, SimulationOptions, Simulator};
use rigid::spatial::{so3, Mat3, Transform, Vec3};

const M: f64 = 1.5;
const L: f64 = 0.8;
const G: f64 = 9.81;

/// The rod as a free body: a free-flyer whose frame is at the CoM, axis along z, inertia
/// `diag(mL²/12, mL²/12, J)`; its top end `(0, 0, L/2)` held at the world's origin.
fn free_rod(reference: ReferenceFrame) -> (Model, ConstraintModel) {
    let i = M * L * L / 12.0;
    let g = SpatialInertia::from_com(M, Vec3::zeros(), RotationalInertia::diagonal(i, i, 0.01));
    let mut b = ModelBuilder::new("rod");
    b.add_joint(None, "rod", JointType::FreeFlyer, Transform::identity(), g)
        .unwrap();
    let model = b.build().unwrap();
    let top = Transform::from_translation(Vec3::new(0.0, 0.0, 0.5 * L));
    let c = ConstraintModel::point(Some(JointId(0)), top, None, Transform::identity())
        .with_reference(reference);
    (model, c)
}

/// The free body's state at the angles `(φ, θ)` and rates: frame `Rz(φ) Rx(θ)`, CoM at
/// `−(L/2) R e_z`, body twist `ω_b = (θ̇, φ̇ sin θ, 0)` (no spin about the axis, as
/// [`RodOnPivot::state`]), `v_b = ω_b × (0, 0, −L/2)`.
fn free_state(q: &Vector2<f64>, qd: &Vector2<f64>) -> (Vec<f64>, Vec<f64>) {
    let R = RodOnPivot::rotation(q);
    let p = R * Vec3::new(0.0, 0.0, -0.5 * L);
    let quat = so3::to_quaternion(&R);
    let w = Vec3::new(qd[1], qd[0] * q[1].sin(), 0.0);
    let v = w.cross(&Vec3::new(0.0, 0.0, -0.5 * L));
    (
        vec![p.x, p.y, p.z, quat[0], quat[1], quat[2], quat[3]],
        vec![w.x, w.y, w.z, v.x, v.y, v.z],
    )
}

/// The rod's axis `u = R e_z = (sin θ sin φ, −sin θ cos φ, cos θ)` and its second derivative
/// along `(φ, θ)(t)`.
fn axis_acceleration(q: &Vector2<f64>, qd: &Vector2<f64>, qdd: &Vector2<f64>) -> Vec3 {
    let (sp, cp) = q[0].sin_cos();
    let (st, ct) = q[1].sin_cos();
    let u_p = Vec3::new(st * cp, st * sp, 0.0);
    let u_t = Vec3::new(ct * sp, -ct * cp, -st);
    let u_pp = Vec3::new(-st * sp, st * cp, 0.0);
    let u_pt = Vec3::new(ct * cp, ct * sp, 0.0);
    let u_tt = Vec3::new(-st * sp, st * cp, -ct);
    u_p * qdd[0]
        + u_t * qdd[1]
        + u_pp * qd[0] * qd[0]
        + u_pt * 2.0 * qd[0] * qd[1]
        + u_tt * qd[1] * qd[1]
}

/// The notes' rod on a spherical pivot, built as a free body with a point constraint at its end:
/// at several states, (1) its axis moves as Lagrange's equations of lecture 002 say
/// (`RodOnPivot`, by automatic differentiation), (2) the reaction `λ` is Newton's
/// `F = m (a_G − g)` with `a_G = −(L/2) ü` from Lagrange's motion (world-aligned `λ`; the local
/// one is `Rᵀ F`), and (3) Euler's equation about the CoM holds with the reaction's moment:
/// `I ω̇ + ω × I ω = r × F` (the free-body diagram).
#[test]
fn rod_on_a_pivot_matches_lagrange_newton_and_euler() {
    let rod = RodOnPivot {
        mass: M,
        length: L,
        gravity: G,
    };
    let states = [
        ([0.3, 0.8], [1.5, 0.3]),
        ([-1.1, 2.2], [-0.7, 1.9]),
        ([2.5, 0.4], [3.0, -2.0]),
    ];
    for (q, qd) in states {
        let (q, qd) = (Vector2::from(q), Vector2::from(qd));
        let qdd = equations_of_motion(&rod, &q, &qd)
            .acceleration(&Vector2::zeros())
            .unwrap();
        let u_dd = axis_acceleration(&q, &qd, &qdd);
        let force = (u_dd * (-0.5 * L) - Vec3::new(0.0, 0.0, -G)) * M;
        for reference in [ReferenceFrame::WorldAligned, ReferenceFrame::Body] {
            let (model, c) = free_rod(reference);
            let (qf, vf) = free_state(&q, &qd);
            let mut data = Data::new(&model);
            let mut cd = ConstraintData::new(&model, &[c]).unwrap();
            let s = ProximalSettings::default();
            constraint_dynamics(&model, &mut data, &mut cd, &qf, &vf, &[0.0; 6], &s).unwrap();
            let R = RodOnPivot::rotation(&q);
            let (w, wd) = (
                Vec3::new(vf[0], vf[1], vf[2]),
                Vec3::new(cd.ddq[0], cd.ddq[1], cd.ddq[2]),
            );
            // (1) ü = R ([ω̇] e_z + [ω]² e_z)
            let ez = Vec3::z();
            let u_dd_free = R * (wd.cross(&ez) + w.cross(&w.cross(&ez)));
            assert!(
                (u_dd_free - u_dd).amax() < 1e-10,
                "axis: {u_dd_free} vs {u_dd}"
            );
            // (2) the reaction
            let lambda = Vec3::new(cd.lambda[0], cd.lambda[1], cd.lambda[2]);
            let expected = match reference {
                ReferenceFrame::Body => R.transpose() * force,
                _ => force,
            };
            assert!(
                (lambda - expected).amax() < 1e-10 * force.amax(),
                "{lambda} vs {expected}"
            );
            // (3) Euler about the CoM, body axes
            let i = M * L * L / 12.0;
            let I = Mat3::from_diagonal(&Vec3::new(i, i, 0.01));
            let lhs = I * wd + w.cross(&(I * w));
            let rhs = Vec3::new(0.0, 0.0, 0.5 * L).cross(&(R.transpose() * force));
            assert!((lhs - rhs).amax() < 1e-10, "Euler: {lhs} vs {rhs}");
        }
    }
}

/// The same rod simulated for 2 s (dt = 1 ms): the constrained free body (RKMK4, projection)
/// and Lagrange's equations in `(φ, θ)` (classical RK4) give the same axis, to 1e-8 (the two
/// integrators' truncation errors; the vector fields agree to 1e-10, test above).
#[test]
fn rod_on_a_pivot_moves_as_lagrange_says() {
    let rod = RodOnPivot {
        mass: M,
        length: L,
        gravity: G,
    };
    let (q0, qd0) = (Vector2::new(0.3, 0.8), Vector2::new(1.5, 0.3));
    let (model, c) = free_rod(ReferenceFrame::WorldAligned);
    let (qf, vf) = free_state(&q0, &qd0);
    let opts = SimulationOptions::conservative(1e-3, Integrator::Rk4);
    let mut sim = Simulator::new(&model, &qf, &vf, opts, Controller::none(&model))
        .unwrap()
        .with_constraints(&[c], ConstraintOptions::default())
        .unwrap();
    let (mut q, mut qd) = (q0, qd0);
    let mut worst: f64 = 0.0;
    for k in 0..2000 {
        sim.step().unwrap();
        let v = sim.violation().unwrap();
        assert!(v.position < 1e-12 && v.velocity < 1e-12, "{v:?}");
        (q, qd) = rk4_step(&rod, k as f64 * 1e-3, &q, &qd, 1e-3, no_force).unwrap();
        let x = sim.q();
        let R = so3::from_quaternion(x[3], x[4], x[5], x[6], 1e-9).unwrap();
        worst = worst.max((R * Vec3::z() - RodOnPivot::rotation(&q) * Vec3::z()).amax());
    }
    eprintln!("rod, 2 s: largest axis difference to Lagrange's motion {worst:.1e}");
    assert!(worst < 1e-8);
}

/// The crank-rocker of fourbar.urdf assembled at crank angle `a` (the coupler-rocker pin found
/// by intersecting two circles in the x-z plane), as `q = (crank, coupler, rocker)`.
fn fourbar_assembled(a: f64) -> Vec<f64> {
    let (l1, l2, l3, d) = (0.3, 0.8, 0.6, 0.7);
    // a turn by θ about y maps x to (cos θ, 0, −sin θ): work with (x, −z) as a plane
    let A = nalgebra::Vector2::new(l1 * a.cos(), l1 * a.sin());
    let D = nalgebra::Vector2::new(d, 0.0);
    let e = D - A;
    let dist = e.norm();
    let along = (l2 * l2 - l3 * l3 + dist * dist) / (2.0 * dist);
    let h = (l2 * l2 - along * along).sqrt();
    let n = nalgebra::Vector2::new(-e.y, e.x) / dist;
    let B = A + e * (along / dist) + n * h;
    let ang = |p: nalgebra::Vector2<f64>| p.y.atan2(p.x);
    vec![a, ang(B - A) - a, ang(B - D)]
}

/// A four-bar linkage (a loop closed by a redundant 3D point constraint, solved by proximal
/// iterations), 10 s under gravity: with the projection the constraint violation stays below
/// 1e-9 while Baumgarte alone, or nothing, lets the loop open; the energy drifts no more than the
/// unconstrained RK4's on the same mechanism with the loop cut (same start, same step), both when
/// the crank rocks (2 rad/s at the start) and when it turns round (8 rad/s), and the drift is the
/// integrator's own (fourth order: ÷16 or so when the step is halved).
#[test]
fn fourbar_runs_ten_seconds_on_its_manifold() {
    let model = load("fourbar.urdf", false);
    let tip = |x: f64| Transform::from_translation(Vec3::new(x, 0.0, 0.0));
    let (coupler, rocker) = (
        model.joint_id("coupler_joint"),
        model.joint_id("rocker_joint"),
    );
    let closure = ConstraintModel::point(coupler, tip(0.8), rocker, tip(0.6));
    let q0 = fourbar_assembled(0.5);
    let settings = ProximalSettings::new(1e-12, 1e-6, 100);
    // (largest violation, largest relative energy change, final crank angle, q̇ at the start)
    let run = |c: &ConstraintModel, project: bool, rate: f64, dt: f64| {
        let opts = ConstraintOptions {
            settings,
            project,
            ..ConstraintOptions::default()
        };
        let conservative = SimulationOptions::conservative(dt, Integrator::Rk4);
        let mut sim = Simulator::new(
            &model,
            &q0,
            &[rate, 0.0, 0.0],
            conservative,
            Controller::none(&model),
        )
        .unwrap()
        .with_constraints(std::slice::from_ref(c), opts)
        .unwrap();
        sim.project_constraints().unwrap(); // start on the manifold, q̇ tangent to it
        let v0 = sim.v().to_vec();
        let e0 = sim.energy().unwrap();
        let (mut violation, mut drift): (f64, f64) = (0.0, 0.0);
        for _ in 0..(10.0 / dt).round() as usize {
            sim.step().unwrap();
            let v = sim.violation().unwrap();
            violation = violation.max(v.position);
            drift = drift.max((sim.energy().unwrap() - e0).abs());
        }
        (violation, drift / e0.abs(), sim.q()[0], v0)
    };
    // the unconstrained RK4 on the open chain
    let open = |v0: &[f64], dt: f64| {
        let opts = SimulationOptions {
            dt,
            ..SimulationOptions::default()
        };
        let mut sim = Simulator::new(&model, &q0, v0, opts, Controller::none(&model)).unwrap();
        let e0 = sim.energy().unwrap();
        let mut drift: f64 = 0.0;
        for _ in 0..(10.0 / dt).round() as usize {
            sim.run(1, |_| {}).unwrap();
            drift = drift.max((sim.energy().unwrap() - e0).abs());
        }
        drift / e0.abs()
    };
    for rate in [2.0, 8.0] {
        let (violation, drift, crank, v0) = run(&closure, true, rate, 1e-3);
        let (baumgarte, ..) = run(
            &closure.clone().with_baumgarte(100.0, 20.0),
            false,
            rate,
            1e-3,
        );
        let (bare, ..) = run(&closure, false, rate, 1e-3);
        let open_drift = open(&v0, 1e-3);
        let (_, half, ..) = run(&closure, true, rate, 5e-4);
        eprintln!(
            "four-bar, crank at {rate} rad/s, 10 s at 1 ms: violation {violation:.1e} m with \
             projection, {baumgarte:.1e} m with Baumgarte (100, 20) alone, {bare:.1e} m with \
             neither; relative energy drift {drift:.1e} (at 0.5 ms {half:.1e}), open chain with \
             the unconstrained RK4 {open_drift:.1e}; crank at {crank:.2} rad"
        );
        assert!(violation < 1e-9);
        assert!(bare > 1e3 * violation && baumgarte > 10.0 * violation);
        assert!(drift <= 10.0 * open_drift, "{drift:e} vs {open_drift:e}");
        assert!(half < drift / 8.0, "fourth order: {drift:e} then {half:e}");
    }
}

/// `q_0 = p(q_1)` on the double pendulum: with the linear `p(x) = c_0 + c_1 x` the constrained
/// `q̈` is the one-dof reduced dynamics `(Tᵀ M T) s̈ = Tᵀ (τ − c − g)`, `q = T s + o`,
/// `T = (c_1, 1)`; with a quadratic `p`, `γ` is the derivative of `J q̇` (central differences).
#[test]
fn joint_coordinate_constraint_is_the_reduced_dynamics() {
    let model = rigid::multibody::double_pendulum();
    let (c0, c1) = (0.1, 0.5);
    let gear =
        ConstraintModel::joint_coordinate(JointId(0), Some(JointId(1)), [c0, c1, 0.0, 0.0, 0.0]);
    let mut cd = ConstraintData::new(&model, &[gear]).unwrap();
    let mut data = Data::new(&model);
    let s = 0.7;
    let sd = -1.3;
    let (q, v) = ([c0 + c1 * s, s], [c1 * sd, sd]);
    let tau = [0.4, -0.2];
    let set = ProximalSettings::default();
    constraint_dynamics(&model, &mut data, &mut cd, &q, &v, &tau, &set).unwrap();
    let ddq = cd.ddq.clone();
    let Mq = crba(&model, &mut data, &q).unwrap().clone();
    let nle = nonlinear_effects(&model, &mut data, &q, &v)
        .unwrap()
        .clone();
    let T = DVector::from_column_slice(&[c1, 1.0]);
    let sdd = T.dot(&(DVector::from_column_slice(&tau) - nle)) / (T.transpose() * &Mq * &T)[0];
    assert!((&ddq - &T * sdd).amax() < 1e-12, "{ddq} vs {}", &T * sdd);
    assert!(cd.violation() < 1e-15);
    // quadratic: γ = −p''(q_1) q̇_1² is d/dt (J q̇) along q ⊕ t q̇
    let quad =
        ConstraintModel::joint_coordinate(JointId(0), Some(JointId(1)), [0.1, 0.5, -0.8, 0.0, 0.0]);
    let mut cd = ConstraintData::new(&model, &[quad]).unwrap();
    let jv = |cd: &mut ConstraintData, q: &[f64]| {
        constraint_dynamics(&model, &mut Data::new(&model), cd, q, &v, &tau, &set).unwrap();
        cd.velocity[0]
    };
    jv(&mut cd, &q);
    let gamma = cd.gamma[0];
    let h = 1e-6;
    let (mut qp, mut qm) = ([0.0; 2], [0.0; 2]);
    integrate(&model, &q, &v, h, &mut qp).unwrap();
    integrate(&model, &q, &v, -h, &mut qm).unwrap();
    let fd = (jv(&mut cd, &qp) - jv(&mut cd, &qm)) / (2.0 * h);
    assert!((gamma - fd).abs() < 1e-7, "{gamma} vs {fd}");
}
