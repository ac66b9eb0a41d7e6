//! `rigid model MODEL [--floating] [--inertia strict|warn|repair]`: a readable summary of a model
//! (bodies, joints, sizes, total mass), the warnings of its file and a validity report of every
//! inertia.

#[path = "model_mjcf.rs"]
mod mjcf;

use crate::load::{is_file, is_mjcf, is_sdf, load_any, load_model, LoadArgs};
use clap::Args;
use rigid::io::urdf::{self, build_model_with};
use rigid::multibody::{FrameKind, Model};

/// Arguments of `rigid model`.
#[derive(Args)]
pub struct ModelArgs {
    /// A URDF file, an MJCF file (`.xml`), an SDF file (`.sdf`), or a built-in model name (`puma560`, `pendulum`, `double_pendulum`).
    pub model: String,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// Runs `rigid model`.
///
/// # Errors
/// A model that cannot be read or built (after printing what was found, if the file could be
/// parsed).
pub fn run(args: &ModelArgs) -> Result<(), String> {
    if is_mjcf(&args.model) {
        return mjcf::run(args);
    }
    if is_sdf(&args.model) {
        let loaded = load_any(&args.model, &args.load)?;
        let sdf = loaded.sdf.as_ref().expect("an SDF file");
        println!(
            "SDF {} (version {}): {} loop-closing constraints ({}), {} collision geometries",
            args.model,
            sdf.version,
            sdf.constraints.len(),
            sdf.constraints
                .iter()
                .map(|c| format!("{} ({} rows)", c.name, c.dim()))
                .collect::<Vec<_>>()
                .join(", "),
            sdf.geometries.len()
        );
        print_model(&loaded.model);
        println!("{} warning(s)", loaded.warnings.len());
        for w in &loaded.warnings {
            println!("  warning: {w}");
        }
        let mut issues = body_report(&loaded.model);
        issues.extend(massless_subtrees(&loaded.model));
        print_report(&issues, loaded.model.joints().len(), "bodies");
        return Ok(());
    }
    if !is_file(&args.model) {
        let model = load_model(&args.model, &args.load)?;
        print_model(&model);
        let mut issues = body_report(&model);
        issues.extend(massless_subtrees(&model));
        print_report(&issues, model.joints().len(), "bodies");
        return Ok(());
    }
    let spec = &args.model;
    let robot = urdf::parse_urdf_file(spec).map_err(|e| format!("{spec}: {e}"))?;
    println!(
        "URDF {spec}: robot \"{}\", {} links, {} joints ({} fixed)",
        robot.name,
        robot.links.len(),
        robot.joints.len(),
        robot
            .joints
            .iter()
            .filter(|j| j.kind == urdf::UrdfJointKind::Fixed)
            .count()
    );
    match build_model_with(&robot, &args.load.urdf_options()) {
        Ok((model, warnings)) => {
            print_model(&model);
            let warnings: Vec<String> = warnings.iter().map(|w| format!("warning: {w}")).collect();
            println!(
                "inertia policy: {}; {} warning(s){}",
                args.load.inertia.as_str(),
                warnings.len(),
                if warnings.is_empty() { "" } else { ":" }
            );
            for w in &warnings {
                println!("  {w}");
            }
            print_report(&body_report(&model), model.joints().len(), "moving bodies");
            Ok(())
        }
        Err(e) => {
            for w in &robot.warnings {
                println!("  warning: {w}");
            }
            Err(format!("{spec}: {e}"))
        }
    }
}

fn print_model(model: &Model) {
    let g = model.gravity();
    println!("model \"{}\"", model.name());
    println!(
        "nq = {}, nv = {}, {} moving joints, total mass {:.6} kg (moving bodies), gravity [{}, {}, {}]",
        model.nq(),
        model.nv(),
        model.joints().len(),
        model.total_mass() + 0.0,
        g.x,
        g.y,
        g.z
    );
    println!("joints (depth-first; each carries one body):");
    println!(
        "  {:>3}  {:<32} {:<11} {:<32} {:>5} {:>3} {:>5} {:>3} {:>12}",
        "#", "name", "type", "parent", "idx_q", "nq", "idx_v", "nv", "body mass"
    );
    let joints = model.joints();
    for (i, (j, g)) in joints.iter().zip(model.inertias()).enumerate() {
        let parent = j.parent.map_or("(world)", |p| joints[p.0].name.as_str());
        println!(
            "  {:>3}  {:<32} {:<11} {:<32} {:>5} {:>3} {:>5} {:>3} {:>12.6}",
            i,
            j.name,
            j.type_name(),
            parent,
            j.idx_q,
            j.nq,
            j.idx_v,
            j.nv,
            g.mass()
        );
    }
    let frames = model.frames();
    if !frames.is_empty() {
        println!("frames (links, fixed joints, named frames):");
        for f in frames {
            let on = f.parent.map_or("(world)", |p| joints[p.0].name.as_str());
            let kind = match f.kind {
                FrameKind::Body => "link",
                FrameKind::FixedJoint => "fixed joint",
                FrameKind::Operational => "frame",
            };
            println!("  {:<10} {:<40} on {}", kind, f.name, on);
        }
    }
}

fn print_report(issues: &[String], checked: usize, what: &str) {
    if issues.is_empty() {
        println!("inertias of the {checked} {what}: all physical, none massless where it moves");
    } else {
        println!(
            "inertias of the {checked} {what}: {} finding(s):",
            issues.len()
        );
        for i in issues {
            println!("  {i}");
        }
    }
}

/// Each moving body's inertia (a link with everything welded to it) that is not physical: zero
/// mass, or principal moments violating the triangle inequality (warnings: the model is built;
/// the builder refuses the rest).
fn body_report(model: &Model) -> Vec<String> {
    let joints = model.joints();
    model
        .inertia_issues()
        .into_iter()
        .map(|(j, e)| format!("warning: body of joint \"{}\": {e}", joints[j.0].name))
        .collect()
}

/// Moving joints whose whole subtree is massless ([`Model::massless_subtrees`]).
fn massless_subtrees(model: &Model) -> Vec<String> {
    let joints = model.joints();
    model
        .massless_subtrees()
        .into_iter()
        .map(|j| {
            format!(
                "warning: joint \"{}\" moves bodies of zero total mass (singular mass matrix, ABA \
                 undefined)",
                joints[j.0].name
            )
        })
        .collect()
}
