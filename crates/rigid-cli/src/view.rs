//! `rigid view MODEL [--q ...] --html FILE`: a robot in one pose, as a self-contained HTML page.

use crate::load::{load_printing_warnings, urdf_path, LoadArgs};
use clap::Args;
use rigid::multibody::Data;
use rigid_replay::{robot_nodes, Recording};
use std::path::PathBuf;

/// Options of `rigid view`.
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// A URDF or MJCF (`.xml`) file, a robot of example-robot-data by name, or a built-in model.
    pub model: String,
    #[command(flatten)]
    pub load: LoadArgs,
    /// The configuration, `nq` comma-separated numbers (default: the neutral one; for MJCF the
    /// pose the file describes, MuJoCo's `qpos0`).
    #[arg(long, value_parser = crate::simulate::parse_list, allow_hyphen_values = true)]
    pub q: Option<crate::simulate::Numbers>,
    /// The page to write.
    #[arg(long)]
    pub html: PathBuf,
}

/// Runs `rigid view`.
pub fn run(args: &ViewArgs) -> Result<(), String> {
    let loaded = load_printing_warnings(&args.model, &args.load)?;
    let q = args.q.clone().map_or_else(|| loaded.home(), |n| n.0);
    let model = loaded.model;
    if q.len() != model.nq() {
        return Err(format!("--q has {} numbers; nq = {}", q.len(), model.nq()));
    }
    let mut scene = robot_nodes(&model, urdf_path(&args.model).as_deref());
    scene.title = model.name().to_string();
    scene.info = format!(
        "nq = {}, nv = {}, {} bodies drawn",
        model.nq(),
        model.nv(),
        scene.nodes.len()
    );
    let mut rec = Recording::default();
    let mut data = Data::new(&model);
    rec.record_model(&scene, &model, &mut data, 0.0, &q, true)?;
    crate::util::write_atomic(&args.html, scene.html(&rec).as_bytes())?;
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    println!(
        "wrote {} ({} bodies drawn)",
        args.html.display(),
        scene.nodes.len()
    );
    Ok(())
}
