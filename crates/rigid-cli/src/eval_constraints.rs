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
use rigid::multibody::constraints::{
    constraint_dynamics, constraint_dynamics_derivatives, impulse_dynamics,
    impulse_dynamics_derivatives, ConstraintData, ConstraintDynamicsDerivatives,
    ImpulseDynamicsDerivatives,
};
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

/// `constraint_dynamics_derivatives`: `∂q̈` and `∂λ` with respect to `q` (along `q ⊕ δ`), `v`
/// and `τ`, row-major (`nv x nv`, `m x nv`).
#[derive(Serialize)]
pub struct ConstraintDerivatives {
    ddq_dq: Vec<Vec<f64>>,
    ddq_dv: Vec<Vec<f64>>,
    ddq_dtau: Vec<Vec<f64>>,
    dlambda_dq: Vec<Vec<f64>>,
    dlambda_dv: Vec<Vec<f64>>,
    dlambda_dtau: Vec<Vec<f64>>,
}

/// `impulse_dynamics_derivatives`: `∂q̇⁺` and `∂Λ` with respect to `q` and `q̇⁻`, row-major.
#[derive(Serialize)]
pub struct ImpulseDerivatives {
    dvplus_dq: Vec<Vec<f64>>,
    dvplus_dv: Vec<Vec<f64>>,
    dimpulse_dq: Vec<Vec<f64>>,
    dimpulse_dv: Vec<Vec<f64>>,
}

/// One case's constrained results.
pub struct Constrained {
    pub dynamics: ConstraintDynamics,
    pub impulse: ImpulseDynamics,
    pub dynamics_derivatives: Option<ConstraintDerivatives>,
    pub impulse_derivatives: Option<ImpulseDerivatives>,
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

/// Every case's constrained and impulse dynamics (and their derivatives when `derivatives`), in
/// `layout` when given (velocities permuted, wrenches force first); wrenches force first too when
/// `force_first` (MuJoCo's layout, whose velocities the caller converts; the derivatives are
/// asked there only without a free joint, where MuJoCo's velocities are rigid's).
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
    derivatives: bool,
) -> Result<Vec<Constrained>, String> {
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
    // a matrix with nv columns, permuted as velocities; its rows are velocities (`rows_v`) or
    // constraint rows (force first as `w_out`)
    let vi = |k: usize| layout.map_or(k, |l| l.v_index(k));
    let force = layout.is_some() || force_first;
    let m_out = |cd: &ConstraintData, x: &nalgebra::DMatrix<f64>, rows_v: bool| {
        (0..x.nrows())
            .map(|r| {
                let src = if rows_v {
                    vi(r)
                } else {
                    cd.source_row(r, force)
                };
                (0..x.ncols()).map(|c| x[(src, vi(c))]).collect()
            })
            .collect::<Vec<Vec<f64>>>()
    };
    let mut dd = derivatives.then(|| ConstraintDynamicsDerivatives::new(model, &cd));
    let mut id = derivatives.then(|| ImpulseDynamicsDerivatives::new(model, &cd));
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
            let dynamics_derivatives = match &mut dd {
                Some(d) => {
                    constraint_dynamics_derivatives(
                        model, &mut data, &mut cd, &c.q, &c.v, &c.tau, s, d,
                    )
                    .map_err(e("constraint_dynamics_derivatives"))?;
                    for (what, x) in [
                        ("ddq_dq", &d.ddq_dq),
                        ("ddq_dv", &d.ddq_dv),
                        ("ddq_dtau", &d.ddq_dtau),
                        ("dlambda_dq", &d.dlambda_dq),
                        ("dlambda_dv", &d.dlambda_dv),
                        ("dlambda_dtau", &d.dlambda_dtau),
                    ] {
                        finite(what, x.as_slice()).map_err(|m| format!("{name}: case {i}: {m}"))?;
                    }
                    Some(ConstraintDerivatives {
                        ddq_dq: m_out(&cd, &d.ddq_dq, true),
                        ddq_dv: m_out(&cd, &d.ddq_dv, true),
                        ddq_dtau: m_out(&cd, &d.ddq_dtau, true),
                        dlambda_dq: m_out(&cd, &d.dlambda_dq, false),
                        dlambda_dv: m_out(&cd, &d.dlambda_dv, false),
                        dlambda_dtau: m_out(&cd, &d.dlambda_dtau, false),
                    })
                }
                None => None,
            };
            let impulse_derivatives = match &mut id {
                Some(d) => {
                    impulse_dynamics_derivatives(
                        model,
                        &mut data,
                        &mut cd,
                        &c.q,
                        &c.v,
                        file.restitution,
                        s,
                        d,
                    )
                    .map_err(e("impulse_dynamics_derivatives"))?;
                    for (what, x) in [
                        ("dvplus_dq", &d.dvplus_dq),
                        ("dvplus_dv", &d.dvplus_dv),
                        ("dimpulse_dq", &d.dimpulse_dq),
                        ("dimpulse_dv", &d.dimpulse_dv),
                    ] {
                        finite(what, x.as_slice()).map_err(|m| format!("{name}: case {i}: {m}"))?;
                    }
                    Some(ImpulseDerivatives {
                        dvplus_dq: m_out(&cd, &d.dvplus_dq, true),
                        dvplus_dv: m_out(&cd, &d.dvplus_dv, true),
                        dimpulse_dq: m_out(&cd, &d.dimpulse_dq, false),
                        dimpulse_dv: m_out(&cd, &d.dimpulse_dv, false),
                    })
                }
                None => None,
            };
            Ok(Constrained {
                dynamics: ConstraintDynamics {
                    ddq: v_out(&ddq),
                    lambda: w_out(&cd, &lambda),
                },
                impulse: ImpulseDynamics {
                    dq_plus: v_out(&dq_plus),
                    impulse: w_out(&cd, &impulse),
                },
                dynamics_derivatives,
                impulse_derivatives,
            })
        })
        .collect()
}
