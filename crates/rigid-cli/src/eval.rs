//! `rigid eval MODEL --cases CASES.json [--floating] [--json] [--derivatives]`: the dynamics of a model at given
//! states, for scripts and cross-checks (the contract is in `docs/conventions.md`).

#[path = "eval_mimic.rs"]
mod mimic;
#[path = "eval_mujoco.rs"]
mod mujoco;

use crate::load::load_printing_warnings;
use clap::Args;
use rigid::interop::{Layout, MujocoLayout, PinocchioLayout};
use rigid::io::cases::{parse_cases_with, Case};
use rigid::io::urdf::SiblingOrder;
use rigid::multibody::{
    aba, aba_derivatives, center_of_mass, crba, forward_kinematics_q, gravity_torques,
    kinetic_energy, nonlinear_effects, potential_energy, rnea, rnea_derivatives, Data, Model,
};
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;
use std::path::PathBuf;

/// Arguments of `rigid eval`.
#[derive(Args)]
pub struct EvalArgs {
    /// A URDF file, or a built-in model name (`puma560`, `pendulum`, `double_pendulum`).
    pub model: String,
    /// The states: `{"cases": [{"q": [...], "v": [...], "a": [...], "tau": [...]}]}`; `v`, `a`
    /// and `tau` default to zero.
    #[arg(long)]
    pub cases: PathBuf,
    #[command(flatten)]
    pub load: crate::load::LoadArgs,
    /// Print one JSON object instead of a readable summary.
    #[arg(long)]
    pub json: bool,
    /// `pinocchio`: read and write `q`, `v`, `a`, `τ`, `M` and the derivatives in Pinocchio's
    /// layout (sibling joints sorted by name, `(cos θ, sin θ)` for continuous and planar angles,
    /// free-flyer velocities linear first), so that they pass to and from Pinocchio unchanged.
    /// `mujoco`: MuJoCo's `qpos`, `qvel`, `qacc`, `qfrc` (hinges from `ref`, quaternions `w`
    /// first, free-joint velocity world-linear then body-angular); `mass_matrix` is `mj_fullM`
    /// and `nonlinear_effects` is `qfrc_bias`.
    #[arg(long, default_value = "rigid", value_parser = layout())]
    pub layout: Layout,
    /// Add the analytical derivatives to each result: `rnea_derivatives` (`dtau_dq`, `dtau_dv` at
    /// `(q, v, a)`) and `aba_derivatives` (`dqdd_dq`, `dqdd_dv`, `dqdd_dtau` at `(q, v, tau)`),
    /// nv x nv row-major, derivatives in `q` along the tangent `q ⊕ δ`. With `--constraints`,
    /// also `constraint_dynamics_derivatives` (`ddq_dq`, `ddq_dv`, `ddq_dtau`, `dlambda_dq`,
    /// `dlambda_dv`, `dlambda_dtau`) and `impulse_dynamics_derivatives` (`dvplus_dq`,
    /// `dvplus_dv`, `dimpulse_dq`, `dimpulse_dv`: the full derivatives of v⁺ and of the impulse).
    #[arg(long)]
    pub derivatives: bool,
    /// A constraint file (closed loops, contacts: `{"constraints": [{"type": "point" | "frame",
    /// "joint1", "placement1", "joint2", "placement2", "reference_frame", "baumgarte"}], "mu",
    /// "restitution"}`): adds `constraint_dynamics` (`ddq`, `lambda`) and `impulse_dynamics`
    /// (`dq_plus`, `impulse`) to each result, at `(q, v, tau)`. For an MJCF model, its own
    /// file (`--constraints MODEL.xml`) takes its `<equality>` elements (connect, weld, joint).
    #[arg(long)]
    pub constraints: Option<PathBuf>,
    /// Mimic joints as couplings (a URDF's `<mimic>`, an MJCF `<equality joint>` with a linear
    /// `polycoef`): each follows its source with no coordinate of its own, as Pinocchio's
    /// `mimic=True`; `nq`, `nv` and every vector and matrix leave them out (docs/mimic.md).
    #[arg(long)]
    pub mimic: bool,
}

#[derive(Serialize)]
struct Output {
    model: ModelInfo,
    results: Vec<CaseResult>,
}

#[derive(Serialize)]
struct ModelInfo {
    name: String,
    /// `rigid`, `pinocchio` or `mujoco` (added key).
    layout: &'static str,
    /// MuJoCo's `qpos0` (its layout), for an MJCF model in the `mujoco` layout (added key).
    #[serde(skip_serializing_if = "Option::is_none")]
    qpos0: Option<Vec<f64>>,
    nq: usize,
    nv: usize,
    joints: Vec<JointInfo>,
    gravity: [f64; 3],
}

#[derive(Serialize)]
struct JointInfo {
    name: String,
    #[serde(rename = "type")]
    kind: &'static str,
    idx_q: usize,
    nq: usize,
    idx_v: usize,
    nv: usize,
    /// With `--mimic`, what a mimic joint follows (added key).
    #[serde(skip_serializing_if = "Option::is_none")]
    mimic: Option<MimicInfo>,
}

/// `q = multiplier · q_joint + offset`.
#[derive(Serialize)]
struct MimicInfo {
    joint: String,
    multiplier: f64,
    offset: f64,
}

#[derive(Serialize)]
struct CaseResult {
    rnea: Vec<f64>,
    mass_matrix: Vec<Vec<f64>>,
    nonlinear_effects: Vec<f64>,
    gravity_torques: Vec<f64>,
    /// `null` when ABA is undefined for the case (then `aba_error` says why).
    aba: Option<Vec<f64>>,
    /// Why `aba` is `null`: the mass matrix is not positive definite (a non-physical inertia
    /// loaded as written), or ABA failed (added key).
    #[serde(skip_serializing_if = "Option::is_none")]
    aba_error: Option<String>,
    kinetic_energy: f64,
    potential_energy: f64,
    com: [f64; 3],
    total_mass: f64,
    placements: Placements,
    #[serde(skip_serializing_if = "Option::is_none")]
    rnea_derivatives: Option<RneaDerivatives>,
    #[serde(skip_serializing_if = "Option::is_none")]
    aba_derivatives: Option<AbaDerivatives>,
    #[serde(skip_serializing_if = "Option::is_none")]
    constraint_dynamics: Option<crate::eval_constraints::ConstraintDynamics>,
    #[serde(skip_serializing_if = "Option::is_none")]
    impulse_dynamics: Option<crate::eval_constraints::ImpulseDynamics>,
    #[serde(skip_serializing_if = "Option::is_none")]
    constraint_dynamics_derivatives: Option<crate::eval_constraints::ConstraintDerivatives>,
    #[serde(skip_serializing_if = "Option::is_none")]
    impulse_dynamics_derivatives: Option<crate::eval_constraints::ImpulseDerivatives>,
}

/// `∂τ/∂q`, `∂τ/∂v` (row-major).
#[derive(Serialize)]
struct RneaDerivatives {
    dtau_dq: Vec<Vec<f64>>,
    dtau_dv: Vec<Vec<f64>>,
}

/// `∂q̈/∂q`, `∂q̈/∂v`, `∂q̈/∂τ` (row-major).
#[derive(Serialize)]
struct AbaDerivatives {
    dqdd_dq: Vec<Vec<f64>>,
    dqdd_dv: Vec<Vec<f64>>,
    dqdd_dtau: Vec<Vec<f64>>,
}

impl From<rigid::multibody::RneaDerivatives<'_>> for RneaDerivatives {
    fn from(d: rigid::multibody::RneaDerivatives<'_>) -> Self {
        Self {
            dtau_dq: rows(d.dtau_dq),
            dtau_dv: rows(d.dtau_dv),
        }
    }
}

impl From<rigid::multibody::AbaDerivatives<'_>> for AbaDerivatives {
    fn from(d: rigid::multibody::AbaDerivatives<'_>) -> Self {
        Self {
            dqdd_dq: rows(d.dqdd_dq),
            dqdd_dv: rows(d.dqdd_dv),
            dqdd_dtau: rows(d.dqdd_dtau),
        }
    }
}

/// A matrix as row-major nested arrays.
fn rows(m: &nalgebra::DMatrix<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|r| (0..m.ncols()).map(|k| m[(r, k)]).collect())
        .collect()
}

#[derive(Serialize)]
struct Placement {
    translation: [f64; 3],
    rotation: [[f64; 3]; 3],
}

impl Placement {
    fn of(t: &rigid::spatial::Transform) -> Self {
        let r = &t.rotation;
        Self {
            translation: [t.translation.x, t.translation.y, t.translation.z],
            rotation: [0, 1, 2].map(|i| [r[(i, 0)], r[(i, 1)], r[(i, 2)]]),
        }
    }
}

/// Joint name → placement, serialised as a JSON object in joint order.
struct Placements(Vec<(String, Placement)>);

impl Serialize for Placements {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (name, p) in &self.0 {
            map.serialize_entry(name, p)?;
        }
        map.end()
    }
}

/// Runs `rigid eval`.
///
/// # Errors
/// A message naming the model, the case and the field, or the joint.
pub fn run(args: &EvalArgs) -> Result<(), String> {
    if args.mimic {
        return mimic::run(args);
    }
    let mut load = args.load;
    if args.layout == Layout::Pinocchio {
        load.sibling_order = SiblingOrder::Name;
    }
    let loaded = load_printing_warnings(&args.model, &load)?;
    let model = loaded.model;
    let layout = (args.layout == Layout::Pinocchio).then(|| PinocchioLayout::new(&model));
    let mujoco = (args.layout == Layout::Mujoco).then(|| {
        loaded
            .mjcf
            .as_ref()
            .map_or_else(|| MujocoLayout::new(&model), |m| m.layout())
    });
    if let (Some(l), true) = (&mujoco, args.derivatives) {
        if l.has_free_joint() {
            return Err(
                "--derivatives with --layout mujoco: not available for a model with a free joint \
                 (MuJoCo's free-joint velocity depends on the orientation; use --layout rigid)"
                    .into(),
            );
        }
    }
    let path = args.cases.display();
    let text = std::fs::read_to_string(&args.cases)
        .map_err(|e| format!("cannot read cases file {path}: {e}"))?;
    let nq = layout.as_ref().map_or(model.nq(), PinocchioLayout::nq);
    let mut cases = parse_cases_with(&text, nq, model.nv()).map_err(|e| format!("{path}: {e}"))?;
    if let Some(l) = &layout {
        for (i, c) in cases.iter_mut().enumerate() {
            case_from_pinocchio(l, model.nq(), c).map_err(|e| format!("{path}: case {i}: {e}"))?;
        }
    }
    let mut offsets = Vec::new();
    if let Some(l) = &mujoco {
        for (i, c) in cases.iter_mut().enumerate() {
            let off = mujoco::case_from_mujoco(l, &model, c)
                .map_err(|e| format!("{path}: case {i}: {e}"))?;
            offsets.push(off);
        }
    }
    let mut results = evaluate_all(&model, &cases, args.derivatives)
        .into_iter()
        .enumerate()
        .map(|(i, r)| r.map_err(|e| format!("{path}: case {i}: {e}")))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(path) = &args.constraints {
        let more = crate::eval_constraints::evaluate(
            &model,
            path,
            &cases,
            layout.as_ref(),
            loaded.mjcf.as_ref(),
            mujoco.is_some(),
            args.derivatives,
        )?;
        for (r, c) in results.iter_mut().zip(more) {
            (r.constraint_dynamics, r.impulse_dynamics) = (Some(c.dynamics), Some(c.impulse));
            r.constraint_dynamics_derivatives = c.dynamics_derivatives;
            r.impulse_dynamics_derivatives = c.impulse_derivatives;
        }
    }
    if let Some(l) = &layout {
        results.iter_mut().for_each(|r| result_to_pinocchio(l, r));
    }
    if let Some(l) = &mujoco {
        for ((r, c), off) in results.iter_mut().zip(&cases).zip(&offsets) {
            mujoco::result_to_mujoco(l, &model, c, off, r);
        }
    }
    let mut info = model_info(&model, layout.as_ref());
    if mujoco.is_some() {
        info.layout = "mujoco";
        info.qpos0 = loaded.mjcf.as_ref().map(|m| m.qpos0.clone());
    }
    let out = Output {
        model: info,
        results,
    };
    if args.json {
        let text = serde_json::to_string(&out).map_err(|e| format!("writing JSON: {e}"))?;
        println!("{text}");
    } else {
        print_summary(&out);
    }
    Ok(())
}

/// A case read in Pinocchio's layout, in rigid's.
fn case_from_pinocchio(l: &PinocchioLayout, nq: usize, c: &mut Case) -> Result<(), String> {
    let mut q = vec![0.0; nq];
    l.q_from_pinocchio(&c.q, &mut q)
        .map_err(|e| format!("\"q\": {e}"))?;
    c.q = q;
    for x in [&mut c.v, &mut c.a, &mut c.tau] {
        let mut y = vec![0.0; x.len()];
        l.permute_v(x, &mut y);
        *x = y;
    }
    Ok(())
}

/// A result in Pinocchio's layout (placements, energies and the CoM are the same in both): the
/// vectors and the rows and columns of `M` and of the derivatives (Pinocchio's tangent `q ⊕ δ`
/// is linear first for a free-flyer, as its velocity) permuted.
fn result_to_pinocchio(l: &PinocchioLayout, r: &mut CaseResult) {
    for x in [
        Some(&mut r.rnea),
        Some(&mut r.nonlinear_effects),
        Some(&mut r.gravity_torques),
        r.aba.as_mut(),
    ]
    .into_iter()
    .flatten()
    {
        let mut y = vec![0.0; x.len()];
        l.permute_v(x, &mut y);
        *x = y;
    }
    let permute = |m: &mut Vec<Vec<f64>>| {
        let (n, rigid) = (m.len(), m.concat());
        let mut pin = vec![0.0; rigid.len()];
        l.permute_matrix(&rigid, &mut pin);
        *m = pin.chunks_exact(n.max(1)).map(<[f64]>::to_vec).collect();
    };
    permute(&mut r.mass_matrix);
    if let Some(d) = &mut r.rnea_derivatives {
        permute(&mut d.dtau_dq);
        permute(&mut d.dtau_dv);
    }
    if let Some(f) = &mut r.aba_derivatives {
        permute(&mut f.dqdd_dq);
        permute(&mut f.dqdd_dv);
        permute(&mut f.dqdd_dtau);
    }
}

impl ModelInfo {
    /// The header of `model` with these joints, `nq` and `nv` (in the layout asked for).
    fn of(
        model: &Model,
        layout: Option<&PinocchioLayout>,
        (nq, nv): (usize, usize),
        joints: Vec<JointInfo>,
    ) -> Self {
        let g = model.gravity();
        Self {
            name: model.name().to_string(),
            layout: if layout.is_some() {
                "pinocchio"
            } else {
                "rigid"
            },
            qpos0: None,
            nq: layout.map_or(nq, PinocchioLayout::nq),
            nv,
            joints,
            gravity: [g.x, g.y, g.z],
        }
    }
}

fn model_info(model: &Model, layout: Option<&PinocchioLayout>) -> ModelInfo {
    let joints = model
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let (idx_q, nq) = layout.map_or((j.idx_q, j.nq), |l| l.joint_q(i));
            JointInfo {
                name: j.name.clone(),
                kind: j.type_name(),
                idx_q,
                nq,
                idx_v: j.idx_v,
                nv: j.nv,
                mimic: None,
            }
        })
        .collect();
    ModelInfo::of(model, layout, (model.nq(), model.nv()), joints)
}

/// Case files of at least this many cases are evaluated on every core.
const PARALLEL_CASES: usize = 64;

/// Every case's result, in order: one loop for small files; for large ones a rayon parallel
/// iterator with one [`Data`] per worker (`map_init`), as `rigid::multibody::batch` does. Each
/// case is evaluated alone, so the results are the same bit for bit either way.
fn evaluate_all(
    model: &Model,
    cases: &[Case],
    derivatives: bool,
) -> Vec<Result<CaseResult, String>> {
    use rayon::prelude::*;
    if cases.len() < PARALLEL_CASES {
        let mut data = Data::new(model);
        return cases
            .iter()
            .map(|c| evaluate(model, &mut data, c, derivatives))
            .collect();
    }
    cases
        .par_iter()
        .map_init(
            || Data::new(model),
            |data, c| evaluate(model, data, c, derivatives),
        )
        .collect()
}

fn evaluate(
    model: &Model,
    data: &mut Data,
    c: &Case,
    derivatives: bool,
) -> Result<CaseResult, String> {
    use rigid::multibody::MultibodyError;
    let e = |what: &'static str| move |e: MultibodyError| format!("{what}: {e}");
    let rnea = rnea(model, data, &c.q, &c.v, &c.a).map_err(e("rnea"))?;
    let rnea = rnea.as_slice().to_vec();
    let mass_matrix = rows(crba(model, data, &c.q).map_err(e("mass_matrix"))?);
    let nle = nonlinear_effects(model, data, &c.q, &c.v).map_err(e("nonlinear_effects"))?;
    let nle = nle.as_slice().to_vec();
    let g = gravity_torques(model, data, &c.q).map_err(e("gravity_torques"))?;
    let g = g.as_slice().to_vec();
    let (ddq, aba_error) = aba_or_why(aba(model, data, &c.q, &c.v, &c.tau));
    let kinetic_energy = kinetic_energy(model, data, &c.q, &c.v).map_err(e("kinetic_energy"))?;
    let potential_energy = potential_energy(model, data, &c.q).map_err(e("potential_energy"))?;
    let com = center_of_mass(model, data, &c.q).map_err(e("com"))?;
    forward_kinematics_q(model, data, &c.q).map_err(e("placements"))?;
    let placements = model
        .joints()
        .iter()
        .zip(&data.placements)
        .map(|(j, t)| (j.name.clone(), Placement::of(t)))
        .collect();
    let (rnea_derivatives, aba_derivatives) = if derivatives {
        let d = rnea_derivatives(model, data, &c.q, &c.v, &c.a).map_err(e("rnea_derivatives"))?;
        let r = RneaDerivatives::from(d);
        let d = aba_derivatives(model, data, &c.q, &c.v, &c.tau).map_err(e("aba_derivatives"))?;
        (Some(r), Some(AbaDerivatives::from(d)))
    } else {
        (None, None)
    };
    // `+ 0.0` turns an empty sum's `-0.0` into `0.0`.
    let r = CaseResult {
        rnea,
        mass_matrix,
        nonlinear_effects: nle,
        gravity_torques: g,
        aba: ddq,
        aba_error,
        kinetic_energy: kinetic_energy + 0.0,
        potential_energy: potential_energy + 0.0,
        com: [com.x + 0.0, com.y + 0.0, com.z + 0.0],
        total_mass: model.total_mass() + 0.0,
        placements: Placements(placements),
        rnea_derivatives,
        aba_derivatives,
        constraint_dynamics: None,
        impulse_dynamics: None,
        constraint_dynamics_derivatives: None,
        impulse_dynamics_derivatives: None,
    };
    r.check_finite()?;
    Ok(r)
}

/// ABA's result, or why it is undefined: ABA is defined when M is positive definite (the
/// library's `aba` says when it is not): a non-physical inertia loaded as written can make it
/// indefinite, and then the case still gets every other output.
fn aba_or_why(
    r: Result<&nalgebra::DVector<f64>, rigid::multibody::MultibodyError>,
) -> (Option<Vec<f64>>, Option<String>) {
    use rigid::multibody::MultibodyError;
    match r {
        Ok(a) if a.iter().all(|x| x.is_finite()) => (Some(a.as_slice().to_vec()), None),
        Ok(_) => (
            None,
            Some("aba is not finite: the numbers overflow".to_string()),
        ),
        Err(MultibodyError::NotPositiveDefinite) => (
            None,
            Some(
                "mass matrix is not positive definite (a non-physical inertia): ABA is undefined"
                    .to_string(),
            ),
        ),
        Err(err) => (None, Some(format!("aba: {err}"))),
    }
}

impl CaseResult {
    /// A result that overflowed (huge masses, huge velocities) is an error, not a JSON `null`.
    fn check_finite(&self) -> Result<(), String> {
        let finite = |what: &'static str, x: &[f64]| {
            if x.iter().all(|v| v.is_finite()) {
                Ok(())
            } else {
                Err(format!(
                    "{what} is not finite: the numbers overflow (check the masses and the state)"
                ))
            }
        };
        finite("rnea", &self.rnea)?;
        finite("mass_matrix", &self.mass_matrix.concat())?;
        finite("nonlinear_effects", &self.nonlinear_effects)?;
        finite("gravity_torques", &self.gravity_torques)?;
        let energies = [self.kinetic_energy, self.potential_energy];
        finite("kinetic_energy", &energies)?;
        finite("com", &self.com)?;
        if let Some(r) = &self.rnea_derivatives {
            let all = [r.dtau_dq.concat(), r.dtau_dv.concat()].concat();
            finite("rnea_derivatives", &all)?;
        }
        if let Some(f) = &self.aba_derivatives {
            let all = [f.dqdd_dq.concat(), f.dqdd_dv.concat(), f.dqdd_dtau.concat()].concat();
            finite("aba_derivatives", &all)?;
        }
        Ok(())
    }
}

fn fmt_vec(x: &[f64]) -> String {
    let items: Vec<String> = x.iter().map(|v| format!("{v:.6}")).collect();
    format!("[{}]", items.join(", "))
}

fn print_summary(out: &Output) {
    let m = &out.model;
    println!(
        "model {}: nq = {}, nv = {}, {} joints",
        m.name,
        m.nq,
        m.nv,
        m.joints.len()
    );
    println!("gravity {}", fmt_vec(&m.gravity));
    for (i, r) in out.results.iter().enumerate() {
        println!("case {i}:");
        println!("  rnea              {}", fmt_vec(&r.rnea));
        match (&r.aba, &r.aba_error) {
            (Some(a), _) => println!("  aba               {}", fmt_vec(a)),
            (None, e) => println!(
                "  aba               undefined: {}",
                e.as_deref().unwrap_or("")
            ),
        }
        println!("  nonlinear effects {}", fmt_vec(&r.nonlinear_effects));
        println!("  gravity torques   {}", fmt_vec(&r.gravity_torques));
        println!("  kinetic energy    {:.6} J", r.kinetic_energy);
        println!("  potential energy  {:.6} J", r.potential_energy);
        println!(
            "  com               {} m (total mass {:.6} kg)",
            fmt_vec(&r.com),
            r.total_mass
        );
        let mut matrices = vec![("mass matrix", &r.mass_matrix)];
        if let (Some(d), Some(f)) = (&r.rnea_derivatives, &r.aba_derivatives) {
            matrices.extend([
                ("rnea derivatives dtau/dq", &d.dtau_dq),
                ("rnea derivatives dtau/dv", &d.dtau_dv),
                ("aba derivatives dqdd/dq", &f.dqdd_dq),
                ("aba derivatives dqdd/dv", &f.dqdd_dv),
                ("aba derivatives dqdd/dtau", &f.dqdd_dtau),
            ]);
        }
        for (name, m) in matrices {
            println!("  {name}");
            for row in m {
                println!("    {}", fmt_vec(row));
            }
        }
    }
}

/// `--layout`: rigid's names, listed by clap (`[possible values: rigid, pinocchio, mujoco]`),
/// read by the library's `Layout`.
fn layout() -> impl clap::builder::TypedValueParser<Value = Layout> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(Layout::ALL.map(Layout::name))
        .try_map(|name| name.parse::<Layout>())
}
