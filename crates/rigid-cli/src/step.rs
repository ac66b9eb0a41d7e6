//! `rigid step MODEL --cases CASES.json [--ground H] [--friction μ] [--restitution e] [--dt h]
//! [--derivatives] [--json]`: one step of the time-stepping simulation with contacts from each
//! case's `(q, v, tau)`, and its analytical derivatives `∂(q⁺, v⁺)/∂(q, v, τ)`
//! (`rigid::simulation::Simulator::step_derivatives`). The world is `rigid simulate`'s: an MJCF
//! file's floor, geoms and `<equality>` loops, a URDF's `<collision>` on `--ground`. Parses, calls
//! the library, prints.

use crate::load::{is_file, load_printing_warnings, LoadArgs};
use clap::Args;
use nalgebra::DMatrix;
use rigid::io::cases::parse_cases;
use rigid::io::collision::{file_world, FileWorld, WorldOptions};
use rigid::simulation::{OpenLoop, Scenario, StepDerivatives};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Arguments of `rigid step`.
#[derive(Args)]
pub struct StepArgs {
    /// A URDF or MJCF file, or a built-in model name.
    pub model: String,
    /// The states: `{"cases": [{"q": [...], "v": [...], "tau": [...]}]}` (rigid's layout; `v`
    /// and `tau` default to zero, `a` is ignored).
    #[arg(long)]
    pub cases: PathBuf,
    #[command(flatten)]
    pub load: LoadArgs,
    /// The ground plane's height (m) under a URDF's `<collision>` geometry (an MJCF file brings
    /// its own floor).
    #[arg(long, allow_hyphen_values = true)]
    pub ground: Option<f64>,
    /// Coulomb friction of the ground (default: the file's, else 0.8).
    #[arg(long)]
    pub friction: Option<f64>,
    /// Newton's restitution of the ground (default 0).
    #[arg(long)]
    pub restitution: Option<f64>,
    /// Collisions between the robot's own bodies (not parent and child).
    #[arg(long)]
    pub self_collision: bool,
    /// The step (s); default: an MJCF file's `timestep`, else 1 ms.
    #[arg(long)]
    pub dt: Option<f64>,
    /// Add `step_derivatives` to each result: `dq_dq`, `dq_dv`, `dq_dtau`, `dv_dq`, `dv_dv`,
    /// `dv_dtau` (nv x nv, row-major; q along `q ⊕ δ`, q⁺ by `⊖`), `modes`, `at_switch`,
    /// `held_normal`, `scaled`.
    #[arg(long)]
    pub derivatives: bool,
    /// Print one JSON object instead of a readable summary.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Output {
    model: String,
    nq: usize,
    nv: usize,
    dt: f64,
    results: Vec<CaseResult>,
}

#[derive(Serialize)]
struct CaseResult {
    q_next: Vec<f64>,
    v_next: Vec<f64>,
    /// The active contacts and limits after the step.
    contacts: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    step_derivatives: Option<Derivatives>,
}

#[derive(Serialize)]
struct Derivatives {
    dq_dq: Vec<Vec<f64>>,
    dq_dv: Vec<Vec<f64>>,
    dq_dtau: Vec<Vec<f64>>,
    dv_dq: Vec<Vec<f64>>,
    dv_dv: Vec<Vec<f64>>,
    dv_dtau: Vec<Vec<f64>>,
    modes: Vec<&'static str>,
    at_switch: Vec<usize>,
    held_normal: Vec<usize>,
    scaled: bool,
}

fn rows(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    m.row_iter().map(|r| r.iter().copied().collect()).collect()
}

impl From<StepDerivatives> for Derivatives {
    fn from(d: StepDerivatives) -> Self {
        Self {
            dq_dq: rows(&d.dq_dq),
            dq_dv: rows(&d.dq_dv),
            dq_dtau: rows(&d.dq_dtau),
            dv_dq: rows(&d.dv_dq),
            dv_dv: rows(&d.dv_dv),
            dv_dtau: rows(&d.dv_dtau),
            modes: d.modes.iter().map(|m| m.name()).collect(),
            at_switch: d.at_switch,
            held_normal: d.held_normal,
            scaled: d.scaled,
        }
    }
}

/// Runs `rigid step`.
///
/// # Errors
/// A message for a bad model, world, cases file or state.
pub fn run(args: &StepArgs) -> Result<(), String> {
    let loaded = load_printing_warnings(&args.model, &args.load)?;
    let model = loaded.model;
    let options = WorldOptions {
        ground: args.ground,
        friction: args.friction,
        restitution: args.restitution,
        self_collision: args.self_collision,
    };
    let world = if is_file(&args.model) {
        file_world(Path::new(&args.model), &model, &options)
    } else {
        FileWorld::without_file(&options, Vec::new())
    }
    .map_err(|e| e.to_string())?;
    for w in &world.warnings {
        eprintln!("warning: {}: {w}", args.model);
    }
    world.check_materials(&options).map_err(|e| e.to_string())?;
    if world.collision.is_none() {
        return Err(format!(
            "{}: nothing can touch: give --ground (and <collision> geometry in the file), or a \
             file with a floor",
            args.model
        ));
    }
    let path = args.cases.display();
    let text = std::fs::read_to_string(&args.cases)
        .map_err(|e| format!("cannot read cases file {path}: {e}"))?;
    let cases = parse_cases(&text, &model).map_err(|e| format!("{path}: {e}"))?;
    let nv = model.nv();
    let mut scenario = Scenario::in_world(model, world);
    if let Some(dt) = args.dt {
        scenario.options.dt = dt;
    }
    let dt = scenario.options.dt;
    let err = |e: rigid::simulation::SimulationError| e.to_string();
    let mut sim = scenario.build_with(OpenLoop(vec![0.0; nv])).map_err(err)?;
    let mut results = Vec::with_capacity(cases.len());
    for (i, c) in cases.iter().enumerate() {
        let at = |e: rigid::simulation::SimulationError| format!("{path}: case {i}: {e}");
        // a case that does not continue the last one's result starts its contacts cold
        if c.q != sim.q() || c.v != sim.v() {
            sim.forget_contacts();
        }
        sim.set_state(&c.q, &c.v).map_err(at)?;
        sim.control_mut().0.clone_from(&c.tau);
        let derivatives = if args.derivatives {
            Some(Derivatives::from(sim.step_derivatives().map_err(at)?))
        } else {
            None
        };
        sim.step().map_err(at)?;
        results.push(CaseResult {
            q_next: sim.q().to_vec(),
            v_next: sim.v().to_vec(),
            contacts: sim.contact_stats().active,
            step_derivatives: derivatives,
        });
    }
    let out = Output {
        model: sim.model().name().to_string(),
        nq: sim.model().nq(),
        nv,
        dt,
        results,
    };
    if args.json {
        let text = serde_json::to_string(&out).map_err(|e| e.to_string())?;
        println!("{text}");
        return Ok(());
    }
    println!(
        "{}: nq = {}, nv = {}, dt = {} s",
        out.model, out.nq, out.nv, out.dt
    );
    for (i, r) in out.results.iter().enumerate() {
        println!("case {i}: {} contacts pushing", r.contacts);
        println!("  q_next = {:?}", r.q_next);
        println!("  v_next = {:?}", r.v_next);
        if let Some(d) = &r.step_derivatives {
            println!("  modes = {:?}", d.modes);
            let largest =
                |m: &Vec<Vec<f64>>| m.iter().flatten().fold(0.0_f64, |a, x| a.max(x.abs()));
            println!(
                "  |dq_dq|max = {:.4}, |dv_dq|max = {:.4}, |dv_dv|max = {:.4}, |dv_dtau|max = {:.4} \
                 (--json for the matrices)",
                largest(&d.dq_dq),
                largest(&d.dv_dq),
                largest(&d.dv_dv),
                largest(&d.dv_dtau)
            );
        }
    }
    Ok(())
}
