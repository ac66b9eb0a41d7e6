//! `rigid mobile drive MODEL --wheels L,R --speeds uL,uR`: a wheeled robot on the ground with its
//! wheels under velocity control ([`rigid::mobile::drive`]), its motion beside the kinematic
//! model's ([`rigid::mobile::DriveRecord::agreement`]). This file parses, draws and prints.

use crate::load::{urdf_path, LoadArgs};
use crate::mobile::DriveArgs;
use crate::util::write_atomic;
use rigid::io::collision::{file_world, WorldOptions};
use rigid::io::urdf::{InertiaPolicy, SiblingOrder};
use rigid::mobile::DriveOptions;
use std::fmt::Write as _;

/// Runs `rigid mobile drive`.
pub fn run(args: &DriveArgs) -> Result<(), String> {
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
    let base = args.base.optional()?;
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
    // the replay draws the ground and the contact forces that push (the impulse over dt)
    let mut replay = args.html.as_ref().map(|_| {
        let mut s = rigid_replay::robot_nodes(&model, Some(&path));
        let weight = model.total_mass() * model.gravity().norm();
        let first = s.add_ground(0.0, nalgebra::Vector3::zeros(), weight);
        s.title = format!("{}: wheels at {:?} rad/s", model.name(), args.speeds.0);
        (
            s,
            first,
            rigid_replay::Recording::default(),
            rigid::multibody::Data::new(&model),
        )
    });
    let record = rigid::mobile::drive(&model, cm, &options, args.time, |t, sim| {
        let Some((scene, markers, rec, data)) = replay.as_mut() else {
            return Ok(());
        };
        if t == 0.0 || rec.due(t) {
            let pushing: Vec<_> = sim
                .contacts()
                .iter()
                .zip(sim.contact_impulses())
                .filter(|(_, p)| p.norm() > 0.0)
                .map(|(c, p)| (c.point, p / args.dt))
                .collect();
            scene.set_contacts(*markers, &pushing, 0.0);
            rec.record_model(scene, &model, data, t, sim.q(), t == 0.0)?;
        }
        Ok(())
    })
    .map_err(|e| e.to_string())?;
    let last = record.motion.last().copied().unwrap_or_default();
    println!(
        "{}: {} s at {} s, wheels {:?} at {:?} rad/s (gain {})",
        model.name(),
        args.time,
        args.dt,
        args.wheels,
        args.speeds.0,
        args.gain
    );
    let tail: Vec<&[f64; 5]> = record
        .motion
        .iter()
        .enumerate()
        .filter(|(k, _)| *k as f64 * args.dt > args.time - 1.0)
        .map(|(_, m)| m)
        .collect();
    let n = tail.len().max(1) as f64;
    println!(
        "end: x = {:.4} m, y = {:.4} m; over the last second v = {:.4} m/s, ω = {:.4} rad/s",
        last[0],
        last[1],
        tail.iter().map(|m| m[3]).sum::<f64>() / n,
        tail.iter().map(|m| m[4]).sum::<f64>() / n
    );
    if let Some(b) = &base {
        let [wc, vc, _] = b.body_twist(&args.speeds.0).map_err(|e| e.to_string())?;
        let (dv, dw) = record.agreement(b, 0.5).map_err(|e| e.to_string())?;
        println!(
            "the {} model at the commanded speeds: v = {vc:.4} m/s, ω = {wc:.4} rad/s; at the \
             wheels' simulated speeds, after 0.5 s, v and ω within {:.2} % and {:.2} % (of the \
             motion's speed)",
            b.name(),
            100.0 * dv,
            100.0 * dw
        );
    }
    if let Some(p) = &args.csv {
        let mut csv = String::from("t,x,y,yaw,v,omega");
        for w in &args.wheels {
            let _ = write!(csv, ",{w}");
        }
        csv.push('\n');
        for (k, (m, u)) in record.motion.iter().zip(&record.wheel_speeds).enumerate() {
            let _ = write!(csv, "{}", k as f64 * args.dt);
            for x in m.iter().chain(u) {
                let _ = write!(csv, ",{x}");
            }
            csv.push('\n');
        }
        write_atomic(p, csv.as_bytes())?;
        println!("wrote {}", p.display());
    }
    if let (Some(p), Some((mut scene, _, rec, _))) = (&args.html, replay) {
        scene.info = format!("{} s; end at ({:.3}, {:.3}) m", args.time, last[0], last[1]);
        write_atomic(p, scene.html(&rec).as_bytes())?;
        println!("wrote {}", p.display());
    }
    Ok(())
}
