//! `rigid identify MODEL --data samples.csv [--physical] [--friction] [--out identified.urdf]
//! [--json]`: the inertial parameters of a robot from measured motion (see
//! `rigid::identification`).

use crate::load::{load_model, urdf_path, LoadArgs};
use clap::Args;
use rigid::identification::{
    Estimate, Identification, JointTerms, PhysicalOptions, Samples, Weighting,
};
use rigid::io::urdf::{parse_urdf_file, with_body_inertials};
use rigid::mass::{Consistency, SpatialInertia, Verdict};
use rigid::multibody::Model;
use serde_json::{json, Value};
use std::path::PathBuf;

/// Arguments of `rigid identify`.
#[derive(Args)]
pub struct IdentifyArgs {
    /// A URDF file, a robot of example-robot-data by name, or a built-in model: the kinematics,
    /// and the inertial values the estimate is compared with (and regularised towards).
    pub model: String,
    /// The samples: CSV rows `t, q…, v…, a…, tau…`, `t, q…, v…, tau…` (a by differentiation) or
    /// `t, q…, tau…` (v and a by differentiation), an optional header; columns in the model's
    /// joint order (`rigid excite` writes the layout).
    #[arg(long, value_name = "samples.csv")]
    pub data: PathBuf,
    /// Also the physically consistent estimate: every body's pseudo-inertia positive definite
    /// (a semidefinite program), regularised towards the model's values.
    #[arg(long)]
    pub physical: bool,
    /// Identify viscous and Coulomb friction per joint too.
    #[arg(long)]
    pub friction: bool,
    /// Identify the rotor inertia (armature) per joint too.
    #[arg(long)]
    pub rotor_inertia: bool,
    /// Weighted least squares: each joint's rows weighted by the inverse of its residual's
    /// standard deviation.
    #[arg(long)]
    pub weighted: bool,
    /// λ, the weight of the pull towards the model's values in the physically consistent
    /// estimate (see `rigid::identification::PhysicalOptions`).
    #[arg(long, default_value_t = 1e-4, value_name = "λ")]
    pub regularization: f64,
    /// Bound each body's mass to within this fraction of the model's (0.2: ±20 %), in the
    /// physically consistent estimate.
    #[arg(long, value_name = "FRACTION")]
    pub mass_tolerance: Option<f64>,
    /// The window (s) of the Savitzky–Golay differentiator, when v or a are not in the file.
    #[arg(long, default_value_t = 0.05, value_name = "SECONDS")]
    pub window: f64,
    /// Write a copy of the URDF whose `<inertial>` blocks carry the identified bodies (the
    /// physically consistent estimate with `--physical`, else least squares; each body into its
    /// main link, the links welded to it zeroed, with comments).
    #[arg(long, value_name = "identified.urdf")]
    pub out: Option<PathBuf>,
    /// Print one JSON object instead of the report.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// Runs `rigid identify`.
///
/// # Errors
/// A model or data file that cannot be read, bad samples (the line and column), a motion that
/// does not excite every base parameter, a solver failure, an output that cannot be written.
pub fn run(args: &IdentifyArgs) -> Result<(), String> {
    let model = load_model(&args.model, &args.load)?;
    if args.out.is_some() && crate::load::is_mjcf(&args.model) {
        return Err(format!(
            "--out writes a URDF with the identified <inertial> blocks; \"{}\" is MJCF (the \
             estimate is printed, and --json gives every parameter)",
            args.model
        ));
    }
    let out_urdf = match &args.out {
        Some(_) => Some(urdf_path(&args.model).ok_or_else(|| {
            format!(
                "--out writes a URDF: \"{}\" is a built-in model; give its URDF file instead",
                args.model
            )
        })?),
        None => None,
    };
    if !(args.window.is_finite() && args.window > 0.0) {
        return Err(format!("--window must be positive, got {}", args.window));
    }
    if let Some(f) = args.mass_tolerance {
        if !(f.is_finite() && (0.0..1.0).contains(&f)) {
            return Err(format!("--mass-tolerance must be in [0, 1), got {f}"));
        }
        if !args.physical {
            return Err(
                "--mass-tolerance bounds the physically consistent estimate: add --physical".into(),
            );
        }
    }
    let data = &args.data;
    let text = std::fs::read_to_string(data)
        .map_err(|e| format!("cannot read {}: {e}", data.display()))?;
    let samples = Samples::from_csv(&model, &text, Some(args.window))
        .map_err(|e| format!("{}: {e}", data.display()))?;
    let terms = JointTerms {
        friction: args.friction,
        rotor_inertia: args.rotor_inertia,
    };
    let id = Identification::new(&model, &samples, terms)
        .map_err(|e| format!("{}: {e}", data.display()))?;
    let weighting = if args.weighted {
        Weighting::PerJoint
    } else {
        Weighting::None
    };
    let ls = id.least_squares(weighting).map_err(|e| e.to_string())?;
    let prior = id.evaluate(&id.prior).map_err(|e| e.to_string())?;
    let pc = if args.physical {
        let opts = PhysicalOptions {
            regularization: args.regularization,
            mass_bounds: args
                .mass_tolerance
                .map(|f| PhysicalOptions::mass_bounds_within(&model, f)),
            ..PhysicalOptions::default()
        };
        Some(id.physically_consistent(&opts).map_err(|e| e.to_string())?)
    } else {
        None
    };
    if let (Some(out), Some(path)) = (&args.out, &out_urdf) {
        let est = pc.as_ref().unwrap_or(&ls);
        let robot = parse_urdf_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let urdf_text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let note = if pc.is_some() {
            "rigid identify: physically consistent estimate"
        } else {
            "rigid identify: least-squares estimate (base parameters; the rest from the model)"
        };
        let written = with_body_inertials(&urdf_text, &robot, &model, &bodies(&id, est), note)?;
        crate::util::write_atomic(out, written.as_bytes())?;
    }
    let report = Report {
        model: &model,
        id: &id,
        prior: &prior,
        ls: &ls,
        pc: pc.as_ref(),
        weighted: args.weighted,
    };
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report.json()).map_err(|e| e.to_string())?
        );
    } else {
        report.print();
        if let Some(out) = &args.out {
            println!(
                "\nwrote {} (the {} estimate's bodies)",
                out.display(),
                if pc.is_some() {
                    "physically consistent"
                } else {
                    "least-squares"
                }
            );
        }
    }
    Ok(())
}

/// The body inertias of an estimate ([`rigid::identification::ParameterLayout::body_inertias`]).
fn bodies(id: &Identification, est: &Estimate) -> Vec<SpatialInertia> {
    id.layout.body_inertias(est.parameters.as_slice())
}

struct Report<'a> {
    model: &'a Model,
    id: &'a Identification,
    prior: &'a Estimate,
    ls: &'a Estimate,
    pc: Option<&'a Estimate>,
    weighted: bool,
}

fn verdict(g: &SpatialInertia) -> &'static str {
    match Consistency::of(g).verdict() {
        Verdict::Consistent | Verdict::RoundOff => "consistent",
        Verdict::Massless => "massless",
        Verdict::Degenerate => "degenerate",
        Verdict::TriangleInequality => "triangle inequality violated",
        Verdict::NotPositiveSemiDefinite => "inertia not positive semi-definite",
        Verdict::BadMass => "bad mass",
        Verdict::NonFinite => "not finite",
    }
}

fn body_json(g: &SpatialInertia) -> Value {
    let i = g.inertia_com().to_rows();
    json!({
        "mass": g.mass(),
        "com": if g.mass() != 0.0 { g.com().as_slice().to_vec() } else { vec![0.0; 3] },
        "inertia_com": i,
        "parameters": g.to_parameters(),
        "verdict": verdict(g),
        "consistent": Consistency::of(g).is_consistent(),
    })
}

fn estimate_json(id: &Identification, e: &Estimate) -> Value {
    json!({
        "base": e.base.as_slice(),
        "base_std": e.base_std.as_slice(),
        "parameters": e.parameters.as_slice(),
        "residual_rms": e.residual_rms,
        "residual_rms_per_dof": e.residual_rms_per_dof,
        "relative_residual": e.relative_residual,
        "condition_number": e.condition_number,
        "bodies": bodies(id, e).iter().map(body_json).collect::<Vec<_>>(),
    })
}

impl Report<'_> {
    fn json(&self) -> Value {
        let base = &self.id.base;
        json!({
            "model": self.model.name(),
            "samples": self.id.samples(),
            "rows": self.id.rows(),
            "joints": self.model.joints().iter().map(|j| j.name.clone()).collect::<Vec<_>>(),
            "parameter_names": base.names,
            "base_parameters": (0..base.len()).map(|i| base.expression(i)).collect::<Vec<_>>(),
            "weighted": self.weighted,
            "model_values": estimate_json(self.id, self.prior),
            "least_squares": estimate_json(self.id, self.ls),
            "physical": self.pc.map(|e| estimate_json(self.id, e)),
        })
    }

    fn print(&self) {
        let (id, base) = (self.id, &self.id.base);
        println!(
            "{}: {} samples, {} equations, {} parameters, {} base parameters; condition number \
             of the base regressor {:.4e}",
            self.model.name(),
            id.samples(),
            id.rows(),
            base.names.len(),
            base.len(),
            self.ls.condition_number
        );
        println!(
            "body k is the body moved by joint k: {}",
            self.model
                .joints()
                .iter()
                .enumerate()
                .map(|(k, j)| format!("{} = {}", k + 1, j.name))
                .collect::<Vec<_>>()
                .join(", ")
        );
        let width = (0..base.len())
            .map(|i| base.expression(i).chars().count())
            .max()
            .unwrap_or(4)
            .clamp(4, 60);
        print!(
            "\n{:>4}  {:<width$}  {:>12}  {:>12}  {:>10}  {:>7}",
            "", "base parameter", "model", "least sq.", "std", "std %"
        );
        println!(
            "{}",
            if self.pc.is_some() {
                "    physical"
            } else {
                ""
            }
        );
        for i in 0..base.len() {
            let (b, s) = (self.ls.base[i], self.ls.base_std[i]);
            let pct = if b != 0.0 {
                100.0 * s / b.abs()
            } else {
                f64::INFINITY
            };
            let mut e = base.expression(i);
            if e.chars().count() > width {
                e = e.chars().take(width - 1).collect::<String>() + "…";
            }
            print!(
                "{:>4}  {e:<width$}  {:>12.5e}  {:>12.5e}  {:>10.3e}  {:>7.2}",
                format!("β{}", i + 1),
                self.prior.base[i],
                b,
                s,
                pct
            );
            match self.pc {
                Some(p) => println!("  {:>12.5e}", p.base[i]),
                None => println!(),
            }
        }
        println!("\ntorque residual RMS per joint (N·m or N):");
        let mut rows = vec![("model", self.prior), ("least squares", self.ls)];
        if let Some(p) = self.pc {
            rows.push(("physical", p));
        }
        for (name, e) in &rows {
            println!(
                "  {name:<14} total {:.4e} ({:.2} % of ‖τ‖): {}",
                e.residual_rms,
                100.0 * e.relative_residual,
                e.residual_rms_per_dof
                    .iter()
                    .map(|x| format!("{x:.3e}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            );
        }
        println!("\nbodies (least squares: base parameters, the rest from the model):");
        let (lsb, pcb) = (bodies(id, self.ls), self.pc.map(|e| bodies(id, e)));
        for (k, j) in self.model.joints().iter().enumerate() {
            let g = &lsb[k];
            print!(
                "  {:>3} {:<20} least squares: mass {:.4} kg, {}",
                k + 1,
                j.name,
                g.mass(),
                verdict(g)
            );
            match &pcb {
                Some(p) => println!("; physical: mass {:.4} kg, {}", p[k].mass(), verdict(&p[k])),
                None => println!(),
            }
        }
        let n = lsb
            .iter()
            .filter(|g| !Consistency::of(g).is_consistent())
            .count();
        if n > 0 && self.pc.is_none() {
            println!(
                "\n{n} least-squares bod{} not physically consistent (ABA may fail on them): \
                 add --physical",
                if n == 1 { "y is" } else { "ies are" }
            );
        }
    }
}
