//! `rigid simulate MODEL --constraints K.json` (or the MJCF model's own file, for its
//! `<equality>` elements): a closed loop in motion without torques, by the library's
//! `ConstrainedSimulator` (RKMK4 on the constrained dynamics, projected back onto the constraints
//! every step), with the constraint violation over time.

use super::{robot, SimulateArgs};
use crate::load::load_printing_warnings;
use rigid::multibody::column_names;
use rigid::multibody::constraints::{ConstrainedSimulator, ConstrainedStepOptions};
use std::io::Write;
use std::path::Path;

/// Runs the closed-loop simulation of `args` with the constraints of `path`.
///
/// # Errors
/// A message naming the file, the flag or the step.
pub fn run(args: &SimulateArgs, path: &Path) -> Result<(), String> {
    let steps = super::step_count(args)?;
    let loaded = load_printing_warnings(&args.model, &args.load)?;
    let home = loaded.home();
    let file = crate::eval_constraints::read(&loaded.model, path, loaded.mjcf.as_ref())?;
    let mut model = loaded.model;
    if let Some(g) = args.gravity {
        model = model.with_gravity(g);
    }
    let q0 = match &args.q0 {
        None => home, // an MJCF model starts where the file puts it (MuJoCo's qpos0)
        Some(_) => robot::configuration(&model, "q0", &args.q0)?,
    };
    let v0 = robot::velocity(&model, &args.v0)?;
    let options = ConstrainedStepOptions {
        dt: args.dt,
        settings: file.settings,
        ..ConstrainedStepOptions::default()
    };
    let name = path.display();
    let err = |e: rigid::multibody::constraints::ConstraintError| format!("{name}: {e}");
    let mut sim =
        ConstrainedSimulator::new(&model, &file.constraints, &q0, &v0, options).map_err(err)?;
    sim.project().map_err(err)?; // start on the constraints, q̇ tangent to them
    let mut csv = match &args.csv {
        Some(p) => {
            let f = std::fs::File::create(p)
                .map_err(|e| format!("cannot write {}: {e}", p.display()))?;
            let mut w = std::io::BufWriter::new(f);
            let mut cols = vec!["t".to_string()];
            cols.extend(column_names(&model, &["q", "v"]));
            cols.extend(["energy", "violation_position", "violation_velocity"].map(String::from));
            writeln!(w, "{}", cols.join(",")).map_err(|e| e.to_string())?;
            Some(w)
        }
        None => None,
    };
    let tau = vec![0.0; model.nv()];
    let e0 = sim.energy().map_err(err)?;
    let (mut worst, mut drift) = (sim.violation().map_err(err)?, 0.0f64);
    for k in 0..=steps {
        let v = if k == 0 {
            worst
        } else {
            sim.step(&tau).map_err(|e| format!("step {k}: {e}"))?
        };
        let e = sim.energy().map_err(err)?;
        drift = drift.max((e - e0).abs());
        worst.position = worst.position.max(v.position);
        worst.velocity = worst.velocity.max(v.velocity);
        if let Some(w) = csv.as_mut() {
            let mut row = format!("{}", sim.time());
            for x in sim.q().iter().chain(sim.v()) {
                row += &format!(",{x}");
            }
            writeln!(w, "{row},{e},{},{}", v.position, v.velocity).map_err(|e| e.to_string())?;
        }
    }
    if let Some(mut w) = csv {
        w.flush().map_err(|e| e.to_string())?;
    }
    println!(
        "{} constraint(s), {steps} steps of {} s to t = {:.3} s: largest violation {:.2e} (position), \
         {:.2e} (velocity); energy {e0:.6} J at the start, largest change {drift:.2e} J",
        file.constraints.len(),
        args.dt,
        sim.time(),
        worst.position,
        worst.velocity,
    );
    Ok(())
}
