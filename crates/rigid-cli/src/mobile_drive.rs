//! `rigid mobile drive MODEL --wheels L,R --speeds uL,uR`: a wheeled robot on the ground with its
//! wheels under velocity control ([`rigid::mobile::WheelDrive`]) in the contact simulator, its
//! motion beside the kinematic model's. This file parses, runs the library's simulator and prints.

use crate::load::{urdf_path, LoadArgs};
use crate::mobile::DriveArgs;
use crate::util::write_atomic;
use rigid::io::collision::{file_world, WorldOptions};
use rigid::io::urdf::{InertiaPolicy, SiblingOrder};
use rigid::mobile::{chassis_motion, wheel_simulator, DriveOptions};
use std::fmt::Write as _;

/// Runs `rigid mobile drive`.
pub fn drive(args: &DriveArgs) -> Result<(), String> {
    if args.wheels.is_empty() {
        return Err("--wheels names no joint".into());
    }
    if args.speeds.0.len() != args.wheels.len() {
        return Err(format!(
            "--speeds has {} numbers for {} wheels",
            args.speeds.0.len(),
            args.wheels.len()
        ));
    }
    for (what, x) in [("--time", args.time), ("--dt", args.dt)] {
        if !(x.is_finite() && x > 0.0) {
            return Err(format!("{what} must be positive, got {x}"));
        }
    }
    let base = args.base.base()?;
    if let Some(b) = &base {
        if b.wheels().len() != args.wheels.len() {
            return Err(format!(
                "the {} base has {} wheels; --wheels names {}",
                b.name(),
                b.wheels().len(),
                args.wheels.len()
            ));
        }
    }
    let load = LoadArgs {
        floating: true,
        inertia: InertiaPolicy::Warn,
        sibling_order: SiblingOrder::default(),
    };
    let model = crate::load::load_printing_warnings(&args.model, &load)?.model;
    let path = urdf_path(&args.model)
        .ok_or_else(|| format!("{}: rigid mobile drive needs a robot file", args.model))?;
    let world_options = WorldOptions {
        ground: Some(0.0),
        friction: Some(args.friction),
        ..WorldOptions::default()
    };
    let world = file_world(&path, &model, &world_options).map_err(|e| e.to_string())?;
    let cm = world
        .collision
        .ok_or("the robot file has no collision geometry")?;
    let options = DriveOptions {
        wheels: args.wheels.clone(),
        speeds: args.speeds.0.clone(),
        gain: args.gain,
        wheel_friction: args.wheel_friction,
        hold: args.hold,
        dt: args.dt,
    };
    let mut sim = wheel_simulator(&model, cm, &options).map_err(|e| e.to_string())?;
    let wheels = sim.control().wheels().to_vec();
    let q0 = sim.q().to_vec();

    // the replay draws the ground and the contact forces that push (the impulse over dt)
    let (mut scene, markers) = if args.html.is_some() {
        let mut s = rigid_replay::robot_nodes(&model, Some(&path));
        let weight = model.total_mass() * model.gravity().norm();
        let first = s.add_ground(0.0, nalgebra::Vector3::new(q0[0], q0[1], 0.0), weight);
        s.title = format!("{}: wheels at {:?} rad/s", model.name(), args.speeds.0);
        (s, first)
    } else {
        (rigid_replay::Scene::default(), 0)
    };
    let mut rec = rigid_replay::Recording::default();
    let mut data = rigid::multibody::Data::new(&model);
    let mut csv = String::from("t,x,y,yaw,v,omega");
    for w in &args.wheels {
        let _ = write!(csv, ",{w}");
    }
    csv.push('\n');
    let steps = (args.time / args.dt).round() as u64;
    // the chassis twist (v forward, ω yaw rate) of the root's body twist (ω_b, v_b), and the
    // kinematic model's F u of the measured wheel speeds
    let (mut worst_v, mut worst_w) = (0.0f64, 0.0f64);
    let (mut v_sum, mut w_sum, mut n_sum) = (0.0, 0.0, 0usize);
    for k in 0..=steps {
        if k > 0 {
            sim.step()
                .map_err(|e| format!("t = {:.3} s: {e}", k as f64 * args.dt))?;
        }
        let t = k as f64 * args.dt;
        let (q, v) = (sim.q(), sim.v());
        let [x, y, yaw, forward, yaw_rate] = chassis_motion(q, v);
        let _ = write!(csv, "{t},{x},{y},{yaw},{forward},{yaw_rate}");
        for &i in &wheels {
            let _ = write!(csv, ",{}", v[i]);
        }
        csv.push('\n');
        if let Some(b) = &base {
            let u: Vec<f64> = wheels.iter().map(|&i| v[i]).collect();
            let [wm, vm, _] = b.body_twist(&u).map_err(|e| e.to_string())?;
            if t >= 0.5 {
                let rim =
                    u.iter().map(|x| x.abs()).sum::<f64>() / u.len() as f64 * b.wheels()[0].radius;
                worst_v = worst_v.max((forward - vm).abs() / vm.abs().max(rim).max(1e-9));
                // a turn in place: the rim speed over the wheels' distance from the centre
                let reach = b
                    .wheels()
                    .iter()
                    .map(|w| w.position[0].hypot(w.position[1]))
                    .fold(0.0, f64::max);
                worst_w = worst_w.max((yaw_rate - wm).abs() / wm.abs().max(rim / reach).max(1e-9));
            }
        }
        if t > args.time - 1.0 {
            v_sum += forward;
            w_sum += yaw_rate;
            n_sum += 1;
        }
        if args.html.is_some() && (k == 0 || rec.due(t)) {
            let pushing: Vec<_> = sim
                .contacts()
                .iter()
                .zip(sim.contact_impulses())
                .filter(|(_, p)| p.norm() > 0.0)
                .map(|(c, p)| (c.point, p / args.dt))
                .collect();
            scene.set_contacts(markers, &pushing, 0.0);
            rec.record_model(&scene, &model, &mut data, t, sim.q(), k == 0)?;
        }
    }
    let q = sim.q();
    println!(
        "{}: {} s at {} s, wheels {:?} at {:?} rad/s (gain {})",
        model.name(),
        args.time,
        args.dt,
        args.wheels,
        args.speeds.0,
        args.gain
    );
    let n = n_sum.max(1) as f64;
    println!(
        "end: x = {:.4} m, y = {:.4} m; over the last second v = {:.4} m/s, ω = {:.4} rad/s",
        q[0],
        q[1],
        v_sum / n,
        w_sum / n
    );
    if let Some(b) = &base {
        let [wc, vc, _] = b.body_twist(&args.speeds.0).map_err(|e| e.to_string())?;
        println!(
            "the {} model at the commanded speeds: v = {vc:.4} m/s, ω = {wc:.4} rad/s; at the \
             wheels' simulated speeds, after 0.5 s, v and ω within {:.2} % and {:.2} % (of the \
             motion's speed)",
            b.name(),
            100.0 * worst_v,
            100.0 * worst_w
        );
    }
    if let Some(p) = &args.csv {
        write_atomic(p, csv.as_bytes())?;
        println!("wrote {}", p.display());
    }
    if let Some(p) = &args.html {
        scene.info = format!("{} s; end at ({:.3}, {:.3}) m", args.time, q[0], q[1]);
        write_atomic(p, scene.html(&rec).as_bytes())?;
        println!("wrote {}", p.display());
    }
    Ok(())
}
