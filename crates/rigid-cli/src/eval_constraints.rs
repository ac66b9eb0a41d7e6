//! `rigid eval ... --constraints K.json`: each case's constrained dynamics and impulse dynamics
//! (the contract is in `docs/conventions.md`; the file format and the semantics are
//! `rigid::io::constraints` and `rigid::multibody::constraints`). `--constraints MODEL.xml`
//! takes the MJCF model's own `<equality>` elements (`MjcfModel::constraint_models`).

use rigid::interop::MujocoLayout;
use rigid::interop::PinocchioLayout;
use rigid::io::cases::Case;
use rigid::io::constraints::{parse_constraints, ConstraintFile};
use rigid::io::mjcf::MjcfModel;
use rigid::multibody::constraints::ProximalSettings;
use rigid::multibody::constraints::{constraint_dynamics, impulse_dynamics, ConstraintData};
use rigid::multibody::{Data, Model};
use serde::Serialize;
use std::path::Path;

/// `constraint_dynamics`: `q̈` and `λ` (3 or 6 numbers per constraint, in file order).
#[derive(Serialize)]
pub struct ConstraintDynamics {
    ddq: Vec<f64>,
    lambda: Vec<f64>,
}

impl ConstraintDynamics {
    /// `q̈` in MuJoCo's layout (`q` in rigid's; `c` what MuJoCo's `qacc` adds, as for ABA).
    pub fn convert_to_mujoco(&mut self, l: &MujocoLayout, q: &[f64], c: &[f64]) {
        self.ddq.iter_mut().zip(c).for_each(|(x, c)| *x -= c);
        l.v_to_mujoco(q, &mut self.ddq);
    }
}

/// `impulse_dynamics`: `q̇⁺` and the impulse (3 or 6 numbers per constraint).
#[derive(Serialize)]
pub struct ImpulseDynamics {
    dq_plus: Vec<f64>,
    impulse: Vec<f64>,
}

impl ImpulseDynamics {
    /// `q̇⁺` in MuJoCo's layout (`q` in rigid's).
    pub fn convert_to_mujoco(&mut self, l: &MujocoLayout, q: &[f64]) {
        l.v_to_mujoco(q, &mut self.dq_plus);
    }
}

/// The constraints of `path`: a constraint file, or the `<equality>` elements of the MJCF file
/// the model was read from (solved by proximal iterations with `μ = 1e-6`, which also holds a
/// loop whose rows are redundant, as a planar four-bar's in 3D).
pub(crate) fn read(
    model: &Model,
    path: &Path,
    mjcf: Option<&MjcfModel>,
) -> Result<ConstraintFile, String> {
    let name = path.display();
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
    {
        let same = mjcf
            .and_then(|m| m.path.as_ref())
            .is_some_and(|p| std::fs::canonicalize(p).ok() == std::fs::canonicalize(path).ok());
        let m = mjcf.filter(|_| same).ok_or_else(|| {
            format!(
                "{name}: the <equality> constraints of an MJCF file apply to the model read from \
                 it: give that file as the model too"
            )
        })?;
        let (constraints, skipped) = m.constraint_models().map_err(|e| format!("{name}: {e}"))?;
        for w in skipped {
            eprintln!("warning: {name}: {w}");
        }
        return Ok(ConstraintFile {
            constraints,
            settings: ProximalSettings::redundant(),
            restitution: 0.0,
        });
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read constraints file {name}: {e}"))?;
    parse_constraints(&text, model).map_err(|e| format!("{name}: {e}"))
}

/// Every case's constrained and impulse dynamics, in `layout` when given (velocities permuted,
/// wrenches force first); wrenches force first too when `force_first` (MuJoCo's layout, whose
/// velocities the caller converts).
///
/// # Errors
/// A message naming the file and the constraint, or the case.
pub fn evaluate(
    model: &Model,
    path: &Path,
    cases: &[Case],
    layout: Option<&PinocchioLayout>,
    mjcf: Option<&MjcfModel>,
    force_first: bool,
) -> Result<Vec<(ConstraintDynamics, ImpulseDynamics)>, String> {
    let name = path.display().to_string();
    let name = name.as_str();
    let file = read(model, path, mjcf)?;
    let mut cd =
        ConstraintData::new(model, &file.constraints).map_err(|e| format!("{name}: {e}"))?;
    let mut data = Data::new(model);
    let v_out = |x: &[f64]| match layout {
        Some(l) => {
            let mut y = vec![0.0; x.len()];
            l.permute_v(x, &mut y);
            y
        }
        None => x.to_vec(),
    };
    // wrenches force first in Pinocchio's layout
    let w_out = |cd: &ConstraintData, x: &[f64]| {
        let mut y = x.to_vec();
        if layout.is_some() || force_first {
            cd.force_first(x, &mut y);
        }
        y
    };
    let finite = |what: &str, x: &[f64]| {
        if x.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(format!("{what} is not finite: the numbers overflow"))
        }
    };
    cases
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let e = |what: &'static str| {
                move |e: rigid::multibody::constraints::ConstraintError| {
                    format!("{name}: case {i}: {what}: {e}")
                }
            };
            let s = &file.settings;
            let ddq = constraint_dynamics(model, &mut data, &mut cd, &c.q, &c.v, &c.tau, s)
                .map_err(e("constraint_dynamics"))?
                .as_slice()
                .to_vec();
            let lambda = cd.lambda.as_slice().to_vec();
            if !cd.stats.converged {
                eprintln!(
                    "warning: {name}: case {i}: the proximal iterations did not converge in {} \
                     (|J ddq + gamma| = {:.3e}): redundant constraints that cannot all hold, or \
                     raise \"max_iter\"",
                    cd.stats.iterations, cd.stats.absolute_residual
                );
            }
            let dq_plus =
                impulse_dynamics(model, &mut data, &mut cd, &c.q, &c.v, file.restitution, s)
                    .map_err(e("impulse_dynamics"))?
                    .as_slice()
                    .to_vec();
            let impulse = cd.impulse.as_slice().to_vec();
            for (what, x) in [
                ("ddq", &ddq),
                ("lambda", &lambda),
                ("dq_plus", &dq_plus),
                ("impulse", &impulse),
            ] {
                finite(what, x).map_err(|m| format!("{name}: case {i}: {m}"))?;
            }
            Ok((
                ConstraintDynamics {
                    ddq: v_out(&ddq),
                    lambda: w_out(&cd, &lambda),
                },
                ImpulseDynamics {
                    dq_plus: v_out(&dq_plus),
                    impulse: w_out(&cd, &impulse),
                },
            ))
        })
        .collect()
}
