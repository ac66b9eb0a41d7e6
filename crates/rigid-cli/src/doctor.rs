//! `rigid doctor MODEL.urdf [--json] [--fix OUT.urdf]`: the inertial data of every link checked,
//! the likely cause of each problem, and a repair (see `rigid::doctor`); for an MJCF file
//! (`.xml`) every body's `<inertial>` against its geoms, `--fix` writing MJCF; for an SDF file
//! (`.sdf`) every link's against its collision shapes, `--fix` writing SDF.

use clap::Args;
use rigid::doctor::{examine_file, BodyReport, FileReport, Status};
use std::path::PathBuf;

/// Arguments of `rigid doctor`.
#[derive(Args)]
pub struct DoctorArgs {
    /// A URDF file, an MJCF file (`.xml`) or an SDF file (`.sdf`).
    pub model: PathBuf,
    /// Print one JSON object: `{"robot", "bodies": [{"name", "line", "status", "findings":
    /// [{"code", "message"}], "likely_cause", "explanation", "repair"}]}`.
    #[arg(long)]
    pub json: bool,
    /// Write a copy of the file, in its own format, in which only the `<inertial>` elements that
    /// needed a repair are replaced, each with a comment saying what was done and why.
    #[arg(long, value_name = "OUT")]
    pub fix: Option<PathBuf>,
}

/// Runs `rigid doctor`.
///
/// # Errors
/// A file that cannot be read or parsed, or an output that cannot be written.
pub fn run(args: &DoctorArgs) -> Result<(), String> {
    let path = &args.model;
    let shown = path.display();
    let examined = examine_file(path).map_err(|e| format!("{shown}: {e}"))?;
    let FileReport { report, robot, .. } = &examined;
    if let Some(out) = &args.fix {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{shown}: {e}"))?;
        let (fixed, notes) = examined.fixed(&text).map_err(|e| format!("{shown}: {e}"))?;
        for n in notes {
            eprintln!("note: {shown}: {n}");
        }
        crate::util::write_atomic(out, fixed.as_bytes())?;
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    let count = |s| report.bodies.iter().filter(|b| b.status == s).count();
    println!(
        "robot \"{}\": {} links, {} with <inertial>: {} ok, {} warning, {} invalid",
        report.robot,
        robot.links.len(),
        report.bodies.len(),
        count(Status::Ok),
        count(Status::Warning),
        count(Status::Invalid)
    );
    for b in report.bodies.iter().filter(|b| b.status != Status::Ok) {
        print_body(b);
    }
    if let Some(out) = &args.fix {
        let n = report
            .bodies
            .iter()
            .filter(|b| b.repaired.is_some())
            .count();
        println!("wrote {} ({n} <inertial> block(s) replaced)", out.display());
    }
    Ok(())
}

fn print_body(b: &BodyReport) {
    let status = match b.status {
        Status::Ok => "ok",
        Status::Warning => "warning",
        Status::Invalid => "invalid",
    };
    let cause = b.likely_cause.map_or("-", |c| c.code());
    println!(
        "\nlink \"{}\" (line {}): {status}, likely cause {cause}",
        b.name, b.line
    );
    for f in &b.findings {
        println!("  - {}: {}", f.code, f.message);
    }
    if !b.explanation.is_empty() {
        println!("  why: {}", b.explanation);
    }
    match &b.repair {
        Some(r) => {
            let i = r.inertia;
            println!(
                "  repair: mass {} kg, CoM ({}, {}, {}) m, inertia about the CoM (link axes) \
                 ixx {:.6e} iyy {:.6e} izz {:.6e} ixy {:.6e} ixz {:.6e} iyz {:.6e} kg·m²",
                r.mass,
                r.com[0],
                r.com[1],
                r.com[2],
                i[0][0],
                i[1][1],
                i[2][2],
                i[0][1],
                i[0][2],
                i[1][2]
            );
        }
        None => println!("  repair: none"),
    }
}
