//! `rigid mass SPEC.toml [--json]`: mass properties of a compound body (docs/conventions.md, "The
//! command-line contract").

use clap::Args;
use rigid::io::spec::read_spec;
use rigid::mass::{MassProperties, DEFAULT_INERTIA_TOLERANCE};
use rigid::spatial::{Mat3, Vec3};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Relative tolerance of the validity check (positive semi-definite, triangle inequality).
const VALIDITY_TOLERANCE: f64 = DEFAULT_INERTIA_TOLERANCE;

/// Arguments of `rigid mass`.
#[derive(Args)]
pub struct MassArgs {
    /// The body spec (TOML): `[[part]]` tables with `shape` (box, cylinder, sphere, ellipsoid,
    /// capsule, cone, rod, point, mesh, inertia) and its dimensions, `mass` or `density`,
    /// `position = [x, y, z]`, and optional `rpy = [r, p, y]` or `quaternion = [x, y, z, w]`.
    /// See examples/compound.toml.
    spec: PathBuf,
    /// Print one JSON object instead of the report.
    #[arg(long)]
    json: bool,
}

/// The `--json` output. Keys are a stable contract: add, never rename or remove.
#[derive(Serialize)]
struct MassJson {
    mass: f64,
    com: [f64; 3],
    inertia_com: [[f64; 3]; 3],
    inertia_origin: [[f64; 3]; 3],
    principal_moments: [f64; 3],
    principal_axes: [[f64; 3]; 3],
    spatial_inertia_origin: Vec<[f64; 6]>,
    /// Whether the body is physical (added key).
    valid: bool,
    /// Why not, when `valid` is false (added key).
    #[serde(skip_serializing_if = "Option::is_none")]
    validity_error: Option<String>,
}

/// `x + 0.0` turns `-0.0` into `0.0` and leaves every other number as it is.
fn clean(x: f64) -> f64 {
    x + 0.0
}

fn rows(m: &Mat3) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| clean(m[(r, c)])))
}

fn arr(v: &Vec3) -> [f64; 3] {
    [v.x, v.y, v.z].map(clean)
}

/// Runs the command: exit code 0 on success, 2 on a bad spec (message on stderr).
pub fn run(args: &MassArgs) -> ExitCode {
    match compute(args) {
        Ok((props, out)) => {
            print!("{out}");
            if let Err(e) = props.validity(VALIDITY_TOLERANCE) {
                eprintln!("warning: the body is not physical: {e}");
            }
            ExitCode::SUCCESS
        }
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

/// Reads a body spec and computes its mass properties; the error names the file, the part and
/// the field. Shared with `rigid simulate`.
pub fn load_mass_properties(spec: &Path) -> Result<MassProperties, String> {
    let body = read_spec(spec).map_err(|e| format!("{}: {e}", spec.display()))?;
    body.mass_properties()
        .map_err(|e| format!("{}: {}", spec.display(), body.error_message(&e)))
}

fn compute(args: &MassArgs) -> Result<(MassProperties, String), String> {
    let props = load_mass_properties(&args.spec)?;
    let out = if args.json {
        json(&props)
    } else {
        report(&props)
    };
    Ok((props, out))
}

fn json(p: &MassProperties) -> String {
    let g = p.spatial_inertia_origin.matrix();
    let validity = p.validity(VALIDITY_TOLERANCE);
    let out = MassJson {
        mass: clean(p.mass),
        com: arr(&p.com),
        inertia_com: rows(p.inertia_com.matrix()),
        inertia_origin: rows(p.inertia_origin.matrix()),
        principal_moments: arr(&p.principal_moments),
        principal_axes: rows(&p.principal_axes),
        spatial_inertia_origin: (0..6)
            .map(|r| [0, 1, 2, 3, 4, 5].map(|c| clean(g[(r, c)])))
            .collect(),
        valid: validity.is_ok(),
        validity_error: validity.err().map(|e| e.to_string()),
    };
    // Serialising plain numbers cannot fail.
    serde_json::to_string_pretty(&out).unwrap_or_default() + "\n"
}

fn fmt_vec(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| format!("{:>13.6e}", clean(*x))).collect();
    format!("[{}]", parts.join(" "))
}

fn fmt_mat(m: &Mat3, indent: &str) -> String {
    (0..3)
        .map(|r| format!("{indent}{}\n", fmt_vec(&[m[(r, 0)], m[(r, 1)], m[(r, 2)]])))
        .collect()
}

fn report(p: &MassProperties) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let l = &p.principal_moments;
    let _ = writeln!(s, "mass               {:.6} kg", p.mass);
    let _ = writeln!(s, "centre of mass     {} m", fmt_vec(p.com.as_slice()));
    let _ = writeln!(s, "inertia about the CoM, body axes (kg·m²):");
    s += &fmt_mat(p.inertia_com.matrix(), "    ");
    let _ = writeln!(s, "inertia about the body origin (kg·m²):");
    s += &fmt_mat(p.inertia_origin.matrix(), "    ");
    let _ = writeln!(
        s,
        "principal moments  {} kg·m² (ascending)",
        fmt_vec(l.as_slice())
    );
    let _ = writeln!(s, "principal axes (columns):");
    s += &fmt_mat(&p.principal_axes, "    ");
    let _ = match p.validity(VALIDITY_TOLERANCE) {
        Ok(()) => writeln!(
            s,
            "validity           ok: positive mass, positive semi-definite, λ1 + λ2 = {:.6e} ≥ λ3 = {:.6e}",
            l[0] + l[1],
            l[2]
        ),
        Err(e) => writeln!(s, "validity           NOT PHYSICAL: {e}"),
    };
    s
}
