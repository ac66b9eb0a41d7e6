//! `rigid mobile capstone`: the Modern Robotics capstone ([`rigid::mobile::Capstone`]): the
//! course's scene CSV, X_err as CSV and a plot, a replay of the youBot carrying the cube. This
//! file parses, draws and prints; the run and the cube's poses are the library's.

use crate::mobile::CapstoneArgs;
use crate::plotting::{color, Panel};
use crate::util::write_atomic;
use rigid::io::urdf::{load_urdf_str, parse_urdf_str};
use rigid::mobile::{Capstone, CapstoneRun};
use rigid::multibody::Data;
use rigid::spatial::{so3, Mat6};
use std::fmt::Write as _;
use std::path::Path;

/// Runs `rigid mobile capstone`.
pub fn run(args: &CapstoneArgs) -> Result<(), String> {
    for p in [&args.plot].into_iter().flatten() {
        crate::plotting::check_format(p)?;
    }
    let mut c = if args.limits {
        Capstone::youbot_with_limits()
    } else {
        Capstone::youbot()
    };
    c.feedback.Kp = Mat6::identity() * args.kp;
    c.feedback.Ki = Mat6::identity() * args.ki;
    if let Some(n) = &args.chassis {
        if n.0.len() != 3 {
            return Err(format!(
                "--chassis has {} numbers; expected φ,x,y",
                n.0.len()
            ));
        }
        c.start.chassis = [n.0[0], n.0[1], n.0[2]];
    }
    c.dt = args.dt;
    c.max_speed = args.max_speed;
    let run = c.run().map_err(|e| e.to_string())?;
    let norms: Vec<f64> = run.errors.iter().map(|e| e.norm()).collect();
    let after = |t: f64| {
        norms[((t / run.dt) as usize).min(norms.len() - 1)..]
            .iter()
            .fold(0.0f64, |a, &b| a.max(b))
    };
    println!(
        "capstone: youBot, {} steps of {} s ({:.2} s), Kp = {} I, Ki = {} I{}",
        run.states.len(),
        run.dt,
        run.dt * (run.states.len() - 1) as f64,
        args.kp,
        args.ki,
        if args.limits {
            ", joints 3 and 4 limited"
        } else {
            ""
        }
    );
    println!(
        "|X_err|: {:.3} at the start, largest after 1 s {:.2e}, after 5 s {:.2e}, at the end {:.2e}",
        norms[0],
        after(1.0),
        after(5.0),
        norms.last().copied().unwrap_or(0.0)
    );
    if let Some(path) = &args.csv {
        let mut s = String::new();
        for k in 0..run.states.len() {
            let row: Vec<String> = run.row(k).iter().map(|x| format!("{x}")).collect();
            let _ = writeln!(s, "{}", row.join(","));
        }
        write_atomic(path, s.as_bytes())?;
        println!(
            "wrote {} (the course's scene CSV, 13 columns)",
            path.display()
        );
    }
    if let Some(path) = &args.errors {
        let mut s = String::from("t,wx,wy,wz,vx,vy,vz\n");
        for (k, e) in run.errors.iter().enumerate() {
            let v = e.to_vector();
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{}",
                k as f64 * run.dt,
                v[0],
                v[1],
                v[2],
                v[3],
                v[4],
                v[5]
            );
        }
        write_atomic(path, s.as_bytes())?;
        println!("wrote {}", path.display());
    }
    if let Some(path) = &args.plot {
        let t: Vec<f64> = (0..run.errors.len()).map(|k| k as f64 * run.dt).collect();
        let names = ["ω_x", "ω_y", "ω_z", "v_x", "v_y", "v_z"];
        let curve = |i: usize| {
            (
                names[i].to_string(),
                run.errors.iter().map(|e| e.to_vector()[i]).collect(),
                color(i),
            )
        };
        let panels = [
            Panel {
                title: "X_err, angular (rad)".into(),
                y_label: "rad".into(),
                curves: (0..3).map(curve).collect(),
            },
            Panel {
                title: "X_err, linear (m)".into(),
                y_label: "m".into(),
                curves: (3..6).map(curve).collect(),
            },
        ];
        crate::plotting::save(path, &t, &panels)?;
        println!("wrote {}", path.display());
    }
    if let Some(path) = &args.html {
        replay(&c, &run, path)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The youBot of `examples/youbot.urdf` (planar base joints, the arm, the wheels, the cube on its
/// own chain), compiled in.
const YOUBOT_URDF: &str = include_str!("../../../examples/youbot.urdf");

/// The replay: the youBot's configuration at each step and the cube where
/// [`Capstone::cube_poses`] puts it.
fn replay(c: &Capstone, run: &CapstoneRun, path: &Path) -> Result<(), String> {
    let model = load_urdf_str(YOUBOT_URDF, false).map_err(|e| e.to_string())?;
    let robot = parse_urdf_str(YOUBOT_URDF).map_err(|e| e.to_string())?;
    let mut scene = rigid_replay::robot_nodes_of_urdf(&model, &robot, Path::new("youbot.urdf"));
    scene.title = "Modern Robotics capstone: the youBot".into();
    scene.info = format!(
        "feedforward + PI, Kp = {} I, Ki = {} I; |X_err| {:.3} at the start, {:.1e} at the end",
        c.feedback.Kp[(0, 0)],
        c.feedback.Ki[(0, 0)],
        run.errors.first().map_or(0.0, |e| e.norm()),
        run.errors.last().map_or(0.0, |e| e.norm())
    );
    let at = |name: &str| -> Result<usize, String> {
        let j = model
            .joint_id(name)
            .ok_or_else(|| format!("examples/youbot.urdf has no joint {name}"))?;
        Ok(model.joints()[j.0].idx_q)
    };
    let base = [at("base_yaw")?, at("base_x")?, at("base_y")?];
    let arm: Vec<usize> = (1..=5)
        .map(|i| at(&format!("arm_joint_{i}")))
        .collect::<Result<_, _>>()?;
    let wheels: Vec<usize> = ["fl", "fr", "rr", "rl"]
        .iter()
        .map(|w| at(&format!("wheel_{w}_joint")))
        .collect::<Result<_, _>>()?;
    let cube: Vec<usize> = [
        "cube_x",
        "cube_y",
        "cube_z",
        "cube_yaw",
        "cube_pitch",
        "cube_roll",
    ]
    .iter()
    .map(|n| at(n))
    .collect::<Result<_, _>>()?;
    let mut rec = rigid_replay::Recording::default();
    let mut data = Data::new(&model);
    let mut q = vec![0.0; model.nq()];
    let cubes = c.cube_poses(run).map_err(|e| e.to_string())?;
    for (k, ((s, _), cube_pose)) in run.states.iter().zip(&cubes).enumerate() {
        let t = k as f64 * run.dt;
        for (i, &j) in base.iter().enumerate() {
            q[j] = s.chassis[i];
        }
        for (&j, &a) in arm.iter().zip(&s.arm) {
            q[j] = a;
        }
        for (&j, &a) in wheels.iter().zip(&s.wheels) {
            q[j] = a;
        }
        let (roll, pitch, yaw) = so3::to_rpy(&cube_pose.rotation);
        for (&j, v) in cube.iter().zip([
            cube_pose.translation.x,
            cube_pose.translation.y,
            cube_pose.translation.z,
            yaw,
            pitch,
            roll,
        ]) {
            q[j] = v;
        }
        rec.record_model(&scene, &model, &mut data, t, &q, k == 0)?;
    }
    write_atomic(path, scene.html(&rec).as_bytes())
}
