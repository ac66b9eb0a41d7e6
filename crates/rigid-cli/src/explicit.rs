//! `rigid explicit MODEL [--tolerance T] [--lang text|latex|rust|c|python] [--out FILE]`: the
//! explicit dynamic model of a robot (see `rigid::explicit`): its kinetic-energy matrix,
//! Coriolis, centrifugal and gravity terms as tables in abbreviated constants, optionally pruned
//! with a proven error bound per entry, or as code.

use crate::load::{is_file, load_model};
use clap::{Args, ValueEnum};
use rigid::explicit::{lock_joints, ExplicitModel, Lang, TableOptions};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Tables as text, laid out like Armstrong, Khatib & Burdick (1986).
    Text,
    /// Tables as a LaTeX document.
    Latex,
    /// A Rust module: `mass_matrix`, `coriolis_centrifugal`, `gravity`, the constants.
    Rust,
    /// C99 functions of the same names.
    C,
    /// A Python module (only `math`), with a `constants` dict.
    Python,
}

/// Arguments of `rigid explicit`.
#[derive(Args)]
pub struct ExplicitArgs {
    /// A URDF file, a built-in model (`puma560`, `pendulum`, `double_pendulum`, …) or a robot
    /// of example-robot-data by name (`ur5`, `panda`).
    model: String,
    #[command(flatten)]
    load: crate::load::LoadArgs,
    /// Drop each term whose largest magnitude over the joint ranges is below T times the largest
    /// term of its entry, and print the proven bound on each entry's error (0: exact).
    #[arg(long, default_value_t = 0.0)]
    tolerance: f64,
    /// Output format.
    #[arg(long, value_enum, default_value = "text")]
    lang: Format,
    /// Write to this file instead of standard output.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Lock joints: NAME or NAME=VALUE (default 0), comma separated; their bodies are merged into
    /// their parents' (e.g. the Panda's fingers: --lock panda_finger_joint1,panda_finger_joint2).
    #[arg(long, value_delimiter = ',')]
    lock: Vec<String>,
    /// Write the tables in the angles θ_j = q_j + ANGLE: JOINT=ANGLE, where JOINT is a joint
    /// number counted from one or a joint name, and ANGLE a number or a multiple of pi (`pi`,
    /// `-pi/2`), comma separated. The 1986 PUMA 560 tables' angles: --offset 2=pi,3=pi. The code
    /// still takes q.
    #[arg(long, value_delimiter = ',')]
    offset: Vec<String>,
    /// Print the derivation's time and size on standard error.
    #[arg(long)]
    stats: bool,
}

/// `pi`, `-pi/2`, `3pi/4`, `0.5`.
fn parse_angle(s: &str) -> Result<f64, String> {
    let t = s.trim().replace(' ', "");
    if let Some(i) = t.find("pi") {
        let (coef, rest) = (&t[..i], &t[i + 2..]);
        let c = match coef.trim_end_matches('*') {
            "" | "+" => 1.0,
            "-" => -1.0,
            x => x.parse::<f64>().map_err(|_| format!("bad angle '{s}'"))?,
        };
        let d = match rest {
            "" => 1.0,
            r => r
                .strip_prefix('/')
                .and_then(|d| d.parse::<f64>().ok())
                .ok_or_else(|| format!("bad angle '{s}'"))?,
        };
        return Ok(c * std::f64::consts::PI / d);
    }
    t.parse::<f64>().map_err(|_| format!("bad angle '{s}'"))
}

/// The command line quoted in generated code: the model as its file name, the options.
fn command_line(args: &ExplicitArgs) -> String {
    let model = if is_file(&args.model) {
        Path::new(&args.model)
            .file_name()
            .map_or(args.model.clone(), |f| f.to_string_lossy().into_owned())
    } else {
        args.model.clone()
    };
    let mut c = format!("rigid explicit {model}");
    if args.tolerance != 0.0 {
        c += &format!(" --tolerance {}", args.tolerance);
    }
    if !args.lock.is_empty() {
        c += &format!(" --lock {}", args.lock.join(","));
    }
    if !args.offset.is_empty() {
        c += &format!(" --offset {}", args.offset.join(","));
    }
    let lang = format!("{:?}", args.lang).to_lowercase();
    c + &format!(" --lang {lang}")
}

/// Runs `rigid explicit`.
///
/// # Errors
/// The model cannot be loaded or has joints the explicit model does not cover, bad options, or
/// the output cannot be written.
pub fn run(args: &ExplicitArgs) -> Result<(), String> {
    if !(args.tolerance >= 0.0 && args.tolerance < 1.0) {
        return Err(format!("--tolerance {} must be in [0, 1)", args.tolerance));
    }
    let mut model = load_model(&args.model, &args.load)?;
    if !args.lock.is_empty() {
        let mut locks = Vec::new();
        for l in &args.lock {
            let (name, value) = match l.split_once('=') {
                Some((n, v)) => (n.trim(), parse_angle(v)?),
                None => (l.trim(), 0.0),
            };
            locks.push((name.to_string(), value));
        }
        model = lock_joints(&model, &locks).map_err(|e| e.to_string())?;
    }
    let t0 = Instant::now();
    let explicit = ExplicitModel::derive(&model).map_err(|e| format!("{}: {e}", args.model))?;
    let derived = t0.elapsed();
    let n = explicit.n();
    let mut offsets = vec![0.0; n];
    for o in &args.offset {
        let (joint, angle) = o
            .split_once('=')
            .ok_or_else(|| format!("--offset {o}: expected JOINT=ANGLE"))?;
        let j = match joint.trim().parse::<usize>() {
            Ok(k) if (1..=n).contains(&k) => k - 1,
            Ok(k) => return Err(format!("--offset {o}: joint {k} is not in 1..={n}")),
            Err(_) => {
                model
                    .joint_id(joint.trim())
                    .ok_or_else(|| format!("--offset {o}: no joint named '{joint}'"))?
                    .0
            }
        };
        if explicit.is_prismatic(j) {
            return Err(format!(
                "--offset {o}: joint {} is prismatic (offsets are for angles)",
                j + 1
            ));
        }
        offsets[j] = parse_angle(angle)?;
    }
    let t1 = Instant::now();
    let tables = explicit.tables(&TableOptions {
        tolerance: args.tolerance,
        offsets,
    });
    let tabulated = t1.elapsed();
    let command = command_line(args);
    let out = match args.lang {
        Format::Text => tables.to_text(),
        Format::Latex => tables.to_latex(),
        Format::Rust => tables.to_code(Lang::Rust, &command),
        Format::C => tables.to_code(Lang::C, &command),
        Format::Python => tables.to_code(Lang::Python, &command),
    };
    if args.stats {
        let terms: usize = tables.entries.iter().map(|e| e.terms.len()).sum();
        eprintln!(
            "{}: {n} joints, {} parameters; derivation {:.3} s, tables {:.3} s; {} constants, {terms} terms kept",
            model.name(),
            explicit.parameters().len(),
            derived.as_secs_f64(),
            tabulated.as_secs_f64(),
            tables.constants.len(),
        );
    }
    match &args.out {
        Some(path) => {
            std::fs::write(path, out).map_err(|e| format!("cannot write {}: {e}", path.display()))
        }
        None => {
            print!("{out}");
            Ok(())
        }
    }
}
