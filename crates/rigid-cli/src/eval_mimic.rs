//! `rigid eval MODEL --mimic`: the dynamics with each mimic joint following its source
//! (`rigid::multibody::MimicModel`), in the reduced coordinates, as Pinocchio's
//! `buildModelFromUrdf(path, mimic=True)`: `nq`, `nv` and every vector and matrix leave the mimic
//! joints out; the placements, energies and CoM are the full robot's.

use super::{
    case_from_pinocchio, print_summary, result_to_pinocchio, rows, AbaDerivatives, CaseResult,
    EvalArgs, JointInfo, MimicInfo, ModelInfo, Output, Placement, Placements, RneaDerivatives,
};
use rigid::interop::{Layout, PinocchioLayout};
use rigid::io::cases::{parse_cases_with, Case};
use rigid::io::urdf::SiblingOrder;
use rigid::multibody::{JointId, MimicData, MimicModel, MultibodyError};

/// Runs `rigid eval --mimic`.
///
/// # Errors
/// A message naming the model, the case and the field, or the joint.
pub(super) fn run(args: &EvalArgs) -> Result<(), String> {
    if args.layout == Layout::Mujoco {
        return Err(
            "--mimic with --layout mujoco: not available (MuJoCo keeps a coordinate \
                    for every joint and couples them by <equality joint>; use --layout rigid or \
                    pinocchio, or --constraints MODEL.xml)"
                .into(),
        );
    }
    if args.constraints.is_some() {
        return Err(
            "--mimic with --constraints: not available yet (the constraint verbs work \
                    in the full coordinates: drop --mimic, and the couplings can be given as \
                    joint constraints)"
                .into(),
        );
    }
    let mut load = args.load;
    if args.layout == Layout::Pinocchio {
        load.sibling_order = SiblingOrder::Name;
    }
    let mm = crate::load::load_mimic(&args.model, &load)?;
    let layout = (args.layout == Layout::Pinocchio).then(|| PinocchioLayout::of_mimic(&mm));
    let path = args.cases.display();
    let text = std::fs::read_to_string(&args.cases)
        .map_err(|e| format!("cannot read cases file {path}: {e}"))?;
    let nq = layout.as_ref().map_or(mm.nq(), PinocchioLayout::nq);
    let mut cases = parse_cases_with(&text, nq, mm.nv()).map_err(|e| format!("{path}: {e}"))?;
    if let Some(l) = &layout {
        for (i, c) in cases.iter_mut().enumerate() {
            case_from_pinocchio(l, mm.nq(), c).map_err(|e| format!("{path}: case {i}: {e}"))?;
        }
    }
    let mut md = MimicData::new(&mm);
    let mut results = cases
        .iter()
        .enumerate()
        .map(|(i, c)| {
            evaluate(&mm, &mut md, c, args.derivatives)
                .map_err(|e| format!("{path}: case {i}: {e}"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(l) = &layout {
        results.iter_mut().for_each(|r| result_to_pinocchio(l, r));
    }
    let out = Output {
        model: model_info(&mm, layout.as_ref()),
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

/// The joints with their reduced coordinates: a mimic joint has `nq = nv = 0` at its source's
/// indices (Pinocchio's `idx_q`, `idx_v` of a mimic joint) and says what it follows.
fn model_info(mm: &MimicModel, layout: Option<&PinocchioLayout>) -> ModelInfo {
    let model = mm.model();
    // each free joint's position among the free joints (the pinocchio layout's joint index)
    let mut free_index = vec![0; model.njoints()];
    let mut free = 0;
    for (i, f) in free_index.iter_mut().enumerate() {
        *f = free;
        free += usize::from(mm.mimic_of(JointId(i)).is_none());
    }
    let joints = model
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let (idx_q, idx_v) = mm.joint_coordinates(JointId(i));
            let mimic = mm.mimic_of(JointId(i)).map(|m| MimicInfo {
                joint: model.joint(m.source).name.clone(),
                multiplier: m.multiplier,
                offset: m.offset,
            });
            // a mimic joint sits at its source's indices, with nq = nv = 0
            let at = mm.mimic_of(JointId(i)).map_or(i, |m| m.source.0);
            let idx_q = layout.map_or(idx_q, |l| l.joint_q(free_index[at]).0);
            let (nq, nv) = match (&mimic, layout) {
                (Some(_), _) => (0, 0),
                (None, Some(l)) => (l.joint_q(free_index[i]).1, j.nv),
                (None, None) => (j.nq, j.nv),
            };
            JointInfo {
                name: j.name.clone(),
                kind: j.type_name(),
                idx_q,
                nq,
                idx_v,
                nv,
                mimic,
            }
        })
        .collect();
    ModelInfo::of(model, layout, (mm.nq(), mm.nv()), joints)
}

fn evaluate(
    mm: &MimicModel,
    md: &mut MimicData,
    c: &Case,
    derivatives: bool,
) -> Result<CaseResult, String> {
    let e = |what: &'static str| move |e: MultibodyError| format!("{what}: {e}");
    let rnea = mm.rnea(md, &c.q, &c.v, &c.a).map_err(e("rnea"))?;
    let rnea = rnea.as_slice().to_vec();
    let mass_matrix = rows(mm.crba(md, &c.q).map_err(e("mass_matrix"))?);
    let nle = mm
        .nonlinear_effects(md, &c.q, &c.v)
        .map_err(e("nonlinear_effects"))?;
    let nle = nle.as_slice().to_vec();
    let g = mm.gravity_torques(md, &c.q).map_err(e("gravity_torques"))?;
    let g = g.as_slice().to_vec();
    let (aba, aba_error) = super::aba_or_why(mm.aba(md, &c.q, &c.v, &c.tau));
    let kinetic_energy = mm
        .kinetic_energy(md, &c.q, &c.v)
        .map_err(e("kinetic_energy"))?;
    let potential_energy = mm
        .potential_energy(md, &c.q)
        .map_err(e("potential_energy"))?;
    let com = mm.center_of_mass(md, &c.q).map_err(e("com"))?;
    mm.forward_kinematics(md, &c.q).map_err(e("placements"))?;
    let placements = mm
        .model()
        .joints()
        .iter()
        .zip(&md.data.placements)
        .map(|(j, t)| (j.name.clone(), Placement::of(t)))
        .collect();
    let (rnea_derivatives, aba_derivatives) = if derivatives {
        let d = mm
            .rnea_derivatives(md, &c.q, &c.v, &c.a)
            .map_err(e("rnea_derivatives"))?;
        let r = RneaDerivatives::from(d);
        let d = mm
            .aba_derivatives(md, &c.q, &c.v, &c.tau)
            .map_err(e("aba_derivatives"))?;
        (Some(r), Some(AbaDerivatives::from(d)))
    } else {
        (None, None)
    };
    let r = CaseResult {
        rnea,
        mass_matrix,
        nonlinear_effects: nle,
        gravity_torques: g,
        aba,
        aba_error,
        kinetic_energy: kinetic_energy + 0.0,
        potential_energy: potential_energy + 0.0,
        com: [com.x + 0.0, com.y + 0.0, com.z + 0.0],
        total_mass: mm.model().total_mass() + 0.0,
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
