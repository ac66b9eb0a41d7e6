//! Mimic joints as couplings ([`MimicModel`]): against the full model held by the same couplings
//! as joint constraints (a KKT solve, another algorithm), the identities (`rnea(aba(τ)) = τ`,
//! `½ q̇ᵀ M q̇` = the kinetic energy), finite differences of the derivatives and of a frame's
//! position, on random trees of every one-coordinate joint type; and Pinocchio 4.1's
//! `mimic=True` on Panda (checked-in fixture), Baxter and PR2 (live), with TALOS and Romeo,
//! whose sources come later in the tree than their mimics (Pinocchio refuses them), loading and
//! passing the identities.

use crate::common::reference::{fixture_lines, json_lines, live, rel};
use crate::common::*;
use nalgebra::{DMatrix, DVector};
use rigid::interop::PinocchioLayout;
use rigid::io::urdf::{load_urdf_mimic, SiblingOrder, UrdfOptions};
use rigid::multibody::constraints::{constraint_dynamics, ConstraintData, ProximalSettings};
use rigid::multibody::*;
use std::path::Path;

/// Random couplings between the one-coordinate joints of `model`: about a third of them follow
/// another (sources before or after them in the tree, and one chain).
fn random_mimics(model: &Model, rng: &mut Rng) -> Vec<Mimic> {
    let one: Vec<JointId> = (0..model.njoints())
        .map(JointId)
        .filter(|&j| model.joint(j).nv == 1 && model.joint(j).nq == 1)
        .collect();
    assert!(one.len() >= 4, "{}: too few one-dof joints", model.name());
    let mut out: Vec<Mimic> = Vec::new();
    // a chain: one[1] follows one[3], one[2] follows one[1] (a source later in the tree)
    out.push(Mimic::new(
        one[1],
        one[3],
        rng.uniform(-2.0, 2.0),
        rng.uniform(-0.5, 0.5),
    ));
    out.push(Mimic::new(
        one[2],
        one[1],
        rng.uniform(-2.0, 2.0),
        rng.uniform(-0.5, 0.5),
    ));
    for &j in &one[4..] {
        if rng.next_u64().is_multiple_of(3) {
            let src = one[0];
            out.push(Mimic::new(
                j,
                src,
                rng.uniform(-2.0, 2.0),
                rng.uniform(-0.5, 0.5),
            ));
        }
    }
    out
}

fn coupled_models() -> Vec<MimicModel> {
    let mut rng = Rng::new(53);
    [
        random_tree(1, 8, false),
        random_tree(2, 10, true),
        every_joint_tree(5, 16),
        aligned_forest(),
    ]
    .into_iter()
    .map(|m| {
        let mimics = random_mimics(&m, &mut rng);
        MimicModel::new(m, &mimics).unwrap()
    })
    .collect()
}

fn reduced_state(mm: &MimicModel, rng: &mut Rng) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let q = mm.random_configuration(rng);
    let mut v = || {
        (0..mm.nv())
            .map(|_| rng.uniform(-1.5, 1.5))
            .collect::<Vec<_>>()
    };
    (q, v(), v())
}

#[test]
fn mimic_dynamics_equal_the_full_model_held_by_the_couplings_as_constraints() {
    // q̈_full of the constrained full model (τ on the free dofs, nothing on the mimics) is G q̈
    let mut rng = Rng::new(1);
    for mm in coupled_models() {
        let full = mm.model();
        let (mut md, mut data) = (MimicData::new(&mm), Data::new(full));
        let mut cdata = ConstraintData::new(full, &mm.constraints()).unwrap();
        for _ in 0..3 {
            let (q, v, tau) = reduced_state(&mm, &mut rng);
            let ddq = mm.aba(&mut md, &q, &v, &tau).unwrap().clone();
            let (mut qf, mut vf, mut want) = (
                vec![0.0; full.nq()],
                vec![0.0; full.nv()],
                vec![0.0; full.nv()],
            );
            mm.expand_q(&q, &mut qf);
            mm.expand_v(&v, &mut vf);
            mm.expand_v(ddq.as_slice(), &mut want);
            let mut tf = vec![0.0; full.nv()];
            for (r, &k) in mm.v_full_indices().iter().enumerate() {
                tf[k] = tau[r];
            }
            let got = constraint_dynamics(
                full,
                &mut data,
                &mut cdata,
                &qf,
                &vf,
                &tf,
                &ProximalSettings::default(),
            )
            .unwrap();
            let e = rel(got.as_slice(), &want, 1.0);
            assert!(e < 1e-9, "{}: constrained q̈ vs G q̈: {e:e}", full.name());
            // the constraint force is the torque that drives each mimic: the full model's inverse
            // dynamics at G q̈, projected by Gᵀ, is τ (the Jᵀλ it holds does no virtual work)
            let tau_full = rnea(full, &mut data, &qf, &vf, &want).unwrap().clone();
            let mut back = vec![0.0; mm.nv()];
            mm.reduce_force(tau_full.as_slice(), &mut back);
            assert!(
                rel(&back, &tau, 1.0) < 1e-9,
                "{}: Gᵀ ID(G q̈) vs τ",
                full.name()
            );
        }
    }
}

#[test]
fn rnea_inverts_aba_and_the_mass_matrix_is_the_kinetic_energy_s() {
    let mut rng = Rng::new(2);
    for mm in coupled_models() {
        let mut md = MimicData::new(&mm);
        for _ in 0..3 {
            let (q, v, tau) = reduced_state(&mm, &mut rng);
            let ddq = mm.aba(&mut md, &q, &v, &tau).unwrap().clone();
            let back = mm.rnea(&mut md, &q, &v, ddq.as_slice()).unwrap();
            assert!(
                rel(back.as_slice(), &tau, 1.0) < 1e-10,
                "{}",
                mm.model().name()
            );
            let m = mm.crba(&mut md, &q).unwrap().clone();
            assert!((&m - m.transpose()).amax() <= 1e-12 * m.amax());
            assert!(m.clone().cholesky().is_some(), "M not positive definite");
            let vv = DVector::from_column_slice(&v);
            let ke = 0.5 * vv.dot(&(&m * &vv));
            let ke2 = mm.kinetic_energy(&mut md, &q, &v).unwrap();
            assert!(
                (ke - ke2).abs() <= 1e-11 * ke.abs().max(1.0),
                "{ke} vs {ke2}"
            );
            // c + g = rnea at q̈ = 0, and g alone at q̇ = 0
            let nle = mm.nonlinear_effects(&mut md, &q, &v).unwrap().clone();
            let zero = vec![0.0; mm.nv()];
            let r0 = mm.rnea(&mut md, &q, &v, &zero).unwrap();
            assert!(rel(nle.as_slice(), r0.as_slice(), 1.0) < 1e-12);
            let g = mm.gravity_torques(&mut md, &q).unwrap().clone();
            let r0 = mm.rnea(&mut md, &q, &zero, &zero).unwrap();
            assert!(rel(g.as_slice(), r0.as_slice(), 1.0) < 1e-12);
        }
    }
}

/// `∂f/∂q` by central differences along `q ⊕ ±h e_k` (reduced).
fn fd_q(mm: &MimicModel, q: &[f64], mut f: impl FnMut(&[f64]) -> DVector<f64>) -> DMatrix<f64> {
    let h = 1e-6;
    let cols: Vec<DVector<f64>> = (0..mm.nv())
        .map(|k| {
            let mut e = vec![0.0; mm.nv()];
            e[k] = h;
            let (mut qp, mut qm) = (vec![0.0; mm.nq()], vec![0.0; mm.nq()]);
            mm.integrate(q, &e, 1.0, &mut qp).unwrap();
            mm.integrate(q, &e, -1.0, &mut qm).unwrap();
            (f(&qp) - f(&qm)) / (2.0 * h)
        })
        .collect();
    DMatrix::from_columns(&cols)
}

fn fd_x(x: &[f64], mut f: impl FnMut(&[f64]) -> DVector<f64>) -> DMatrix<f64> {
    let h = 1e-6;
    let cols: Vec<DVector<f64>> = (0..x.len())
        .map(|k| {
            let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
            xp[k] += h;
            xm[k] -= h;
            (f(&xp) - f(&xm)) / (2.0 * h)
        })
        .collect();
    DMatrix::from_columns(&cols)
}

fn rel_m(x: &DMatrix<f64>, y: &DMatrix<f64>) -> f64 {
    (x - y).amax() / y.amax().max(1e-3)
}

#[test]
fn mimic_derivatives_equal_finite_differences_on_the_manifold() {
    let mut rng = Rng::new(3);
    // the analytical derivatives assume constant motion subspaces (no universal joint)
    let constant = |mm: &MimicModel| {
        mm.model()
            .joints()
            .iter()
            .all(|j| j.kind.constant_subspace())
    };
    for mm in coupled_models().into_iter().filter(constant) {
        let name = mm.model().name().to_string();
        let mut md = MimicData::new(&mm);
        let (q, v, a) = reduced_state(&mm, &mut rng);
        let d = mm.rnea_derivatives(&mut md, &q, &v, &a).unwrap();
        let (dq, dv, da) = (d.dtau_dq.clone(), d.dtau_dv.clone(), d.dtau_da.clone());
        let mut w = MimicData::new(&mm);
        let mut rnea = |q: &[f64], v: &[f64], a: &[f64]| mm.rnea(&mut w, q, v, a).unwrap().clone();
        assert!(
            rel_m(&dq, &fd_q(&mm, &q, |q| rnea(q, &v, &a))) < 1e-6,
            "{name}: dtau/dq"
        );
        assert!(
            rel_m(&dv, &fd_x(&v, |v| rnea(&q, v, &a))) < 1e-6,
            "{name}: dtau/dv"
        );
        assert!(
            rel_m(&da, &fd_x(&a, |a| rnea(&q, &v, a))) < 1e-6,
            "{name}: dtau/da"
        );
        let tau = a.clone();
        let d = mm.aba_derivatives(&mut md, &q, &v, &tau).unwrap();
        let (dq, dv, dt) = (d.dqdd_dq.clone(), d.dqdd_dv.clone(), d.dqdd_dtau.clone());
        let mut aba = |q: &[f64], v: &[f64], t: &[f64]| mm.aba(&mut w, q, v, t).unwrap().clone();
        assert!(
            rel_m(&dq, &fd_q(&mm, &q, |q| aba(q, &v, &tau))) < 1e-6,
            "{name}: dqdd/dq"
        );
        assert!(
            rel_m(&dv, &fd_x(&v, |v| aba(&q, v, &tau))) < 1e-6,
            "{name}: dqdd/dv"
        );
        assert!(
            rel_m(&dt, &fd_x(&tau, |t| aba(&q, &v, t))) < 1e-6,
            "{name}: dqdd/dtau"
        );
    }
}

#[test]
fn mimic_jacobian_moves_the_frame_as_finite_differences_of_its_position() {
    let mut rng = Rng::new(4);
    for mm in coupled_models() {
        let mut md = MimicData::new(&mm);
        let (q, v, _) = reduced_state(&mm, &mut rng);
        let last = JointId(mm.model().njoints() - 1);
        let j = mm
            .joint_jacobian(&mut md, &q, last, ReferenceFrame::WorldAligned)
            .unwrap()
            .clone();
        let h = 1e-6;
        let mut at = |s: f64| {
            let mut qs = vec![0.0; mm.nq()];
            mm.integrate(&q, &v, s, &mut qs).unwrap();
            mm.forward_kinematics(&mut md, &qs).unwrap();
            md.data.placements[last.0].translation
        };
        let fd = (at(h) - at(-h)) / (2.0 * h);
        let jv = j * DVector::from_column_slice(&v);
        let got = jv.rows(3, 3).into_owned();
        assert!(
            (got - fd).amax() < 1e-6 * fd.amax().max(1.0),
            "{}",
            mm.model().name()
        );
    }
}

#[test]
fn no_couplings_is_the_full_model_bit_for_bit() {
    let model = random_tree(2, 10, true);
    let mm = MimicModel::new(model.clone(), &[]).unwrap();
    let (mut md, mut data) = (MimicData::new(&mm), Data::new(&model));
    let (q, v, a) = state(&model, &mut Rng::new(5));
    assert_eq!(
        mm.rnea(&mut md, &q, &v, &a).unwrap(),
        rnea(&model, &mut data, &q, &v, &a).unwrap()
    );
    assert_eq!(
        mm.crba(&mut md, &q).unwrap(),
        crba(&model, &mut data, &q).unwrap()
    );
}

#[test]
fn a_chain_of_mimics_is_composed_and_bad_couplings_are_named_errors() {
    let model = random_tree(1, 8, false);
    let one: Vec<JointId> = (0..model.njoints())
        .map(JointId)
        .filter(|&j| model.joint(j).nv == 1)
        .collect();
    let (a, b, c) = (one[0], one[1], one[2]);
    // c = 2 b + 1, b = -3 a + 0.5: c = -6 a + 2
    let mm = MimicModel::new(
        model.clone(),
        &[Mimic::new(c, b, 2.0, 1.0), Mimic::new(b, a, -3.0, 0.5)],
    )
    .unwrap();
    let m = mm.mimic_of(c).unwrap();
    assert_eq!((m.source, m.multiplier, m.offset), (a, -6.0, 2.0));
    assert_eq!((mm.nq(), mm.nv()), (model.nq() - 2, model.nv() - 2));
    let q = mm.random_configuration(&mut Rng::new(6));
    let mut qf = vec![0.0; model.nq()];
    mm.expand_q(&q, &mut qf);
    let (ia, ic) = (model.joint(a).idx_q, model.joint(c).idx_q);
    assert!((qf[ic] - (-6.0 * qf[ia] + 2.0)).abs() < 1e-15);
    let err = |m: &[Mimic]| MimicModel::new(model.clone(), m).unwrap_err().to_string();
    let name = |j: JointId| model.joint(j).name.clone();
    assert!(err(&[Mimic::new(a, a, 1.0, 0.0)]).contains(&format!("\"{}\" mimics itself", name(a))));
    let twice = err(&[Mimic::new(c, a, 1.0, 0.0), Mimic::new(c, b, 1.0, 0.0)]);
    assert!(twice.contains("mimics two joints"), "{twice}");
    let cycle = err(&[Mimic::new(a, b, 1.0, 0.0), Mimic::new(b, a, 1.0, 0.0)]);
    assert!(cycle.contains("mimic loop"), "{cycle}");
    assert!(err(&[Mimic::new(a, JointId(99), 1.0, 0.0)]).contains("out of range"));
    assert!(err(&[Mimic::new(a, b, f64::NAN, 0.0)]).contains("must be finite"));
    // the free-flyer root has six coordinates
    let ff = every_joint_tree(5, 16);
    let one = (0..ff.njoints())
        .map(JointId)
        .find(|&j| ff.joint(j).nv == 1)
        .unwrap();
    let e = MimicModel::new(ff.clone(), &[Mimic::new(one, JointId(0), 1.0, 0.0)]).unwrap_err();
    assert!(e.to_string().contains("\"root\" is free_flyer"), "{e}");
    // wrong lengths and NaN in the reduced coordinates are named
    let mut md = MimicData::new(&mm);
    let e = mm.rnea(&mut md, &qf, &[], &[]).unwrap_err();
    assert!(e.to_string().contains('q'), "{e}");
    let mut bad = q.clone();
    bad[0] = f64::NAN;
    let v = vec![0.0; mm.nv()];
    assert!(matches!(
        mm.rnea(&mut md, &bad, &v, &v),
        Err(MultibodyError::NonFinite {
            what: "q",
            index: 0
        })
    ));
}

/// The model of a Pinocchio record, loaded as Pinocchio does (siblings by name, mimic=True).
fn load_pinocchio_order(path: &Path) -> MimicModel {
    let opts = UrdfOptions {
        sibling_order: SiblingOrder::Name,
        ..UrdfOptions::default()
    };
    load_urdf_mimic(path, &opts).unwrap().0
}

/// rigid's reduced model against one record of tests/pinocchio/mimic.py.
fn compare_with_pinocchio(mm: &MimicModel, rec: &serde_json::Value) {
    let file = rec["file"].as_str().unwrap();
    let layout = PinocchioLayout::of_mimic(mm);
    assert_eq!(
        (layout.nq(), mm.nv()),
        (
            rec["nq"].as_u64().unwrap() as usize,
            rec["nv"].as_u64().unwrap() as usize
        ),
        "{file}: nq, nv"
    );
    // the same joints, the mimics with no coordinate of their own
    let joints = rec["joints"].as_array().unwrap();
    assert_eq!(joints.len(), mm.model().njoints(), "{file}");
    for (i, j) in joints.iter().enumerate() {
        let id = JointId(i);
        assert_eq!(
            j["name"],
            mm.model().joint(id).name.as_str(),
            "{file}: joint {i}"
        );
        assert_eq!(
            j["mimic"].as_bool().unwrap(),
            mm.mimic_of(id).is_some(),
            "{file}: {}",
            j["name"]
        );
        assert_eq!(
            j["idx_v"].as_u64().unwrap() as usize,
            mm.joint_coordinates(id).1,
            "{file}: {} idx_v",
            j["name"]
        );
        // idx_q in Pinocchio's q (continuous joints take two): a mimic at its source's
        let at = mm.mimic_of(id).map_or(id, |m| m.source);
        let free = (0..at.0)
            .filter(|&k| mm.mimic_of(JointId(k)).is_none())
            .count();
        assert_eq!(
            j["idx_q"].as_u64().unwrap() as usize,
            layout.joint_q(free).0,
            "{file}: {} idx_q",
            j["name"]
        );
    }
    let mut md = MimicData::new(mm);
    let v = |c: &serde_json::Value, k: &str| -> Vec<f64> {
        let pin = vec_of(&c[k]);
        let mut out = vec![0.0; pin.len()];
        layout.permute_v(&pin, &mut out);
        out
    };
    let mat = |m: &DMatrix<f64>| {
        let mut out = vec![0.0; m.len()];
        layout.permute_matrix(m.transpose().as_slice(), &mut out);
        out
    };
    let mut worst = 0.0f64;
    for c in rec["cases"].as_array().unwrap() {
        let mut q = vec![0.0; mm.nq()];
        layout.q_from_pinocchio(&vec_of(&c["q"]), &mut q).unwrap();
        let (vel, acc, tau) = (v(c, "v"), v(c, "a"), v(c, "tau"));
        let pin_m = mat_of(&c["M"]);
        let checks = [
            (
                "rnea",
                mm.rnea(&mut md, &q, &vel, &acc)
                    .unwrap()
                    .as_slice()
                    .to_vec(),
                v(c, "rnea"),
            ),
            (
                "nle",
                mm.nonlinear_effects(&mut md, &q, &vel)
                    .unwrap()
                    .as_slice()
                    .to_vec(),
                v(c, "nle"),
            ),
            (
                "aba",
                mm.aba(&mut md, &q, &vel, &tau).unwrap().as_slice().to_vec(),
                v(c, "ddq"),
            ),
            (
                "M",
                mat(&pin_m),
                mm.crba(&mut md, &q)
                    .unwrap()
                    .transpose()
                    .as_slice()
                    .to_vec(),
            ),
        ];
        for (what, got, want) in checks {
            let e = rel(&got, &want, 1.0);
            assert!(e < 1e-9, "{file}: {what} differs from Pinocchio's by {e:e}");
            worst = worst.max(e);
        }
    }
    eprintln!(
        "{file}: nq {} nv {}, largest difference from Pinocchio {worst:.1e}",
        mm.nq(),
        mm.nv()
    );
}

use crate::common::json::{mat_of, vec_of};

#[test]
fn panda_with_mimic_equals_pinocchio_s_mimic_true() {
    let path = example_robot_data().join("panda_description/urdf/panda.urdf");
    let mm = load_pinocchio_order(&path);
    assert_eq!((mm.model().nv(), mm.nv()), (9, 8));
    let rec = &fixture_lines("pinocchio/mimic.json")[0];
    compare_with_pinocchio(&mm, rec);
}

#[test]
fn talos_with_its_sources_later_in_the_tree_loads_and_passes_the_identities() {
    // Pinocchio 4.1 refuses this file with mimic=True
    let path = example_robot_data().join("talos_data/robots/talos_full_v2.urdf");
    identities_of(&path);
}

/// Loads `path` with its mimics and checks, at three random states, `M` symmetric and
/// `rnea(a) = M a + c + g`; then `M` positive definite and `rnea(aba(τ)) = τ`, unless the file
/// has moving bodies that weigh nothing (Romeo's fingers: `M` is singular with or without the
/// couplings, and ABA undefined), where `M` is positive semi-definite.
fn identities_of(path: &Path) {
    let (mm, _) = load_urdf_mimic(path, &UrdfOptions::default()).unwrap();
    assert!(!mm.mimics().is_empty(), "{}", path.display());
    let massless = mm.model().massless_subtrees();
    let mut md = MimicData::new(&mm);
    let mut rng = Rng::new(7);
    for _ in 0..3 {
        let (q, v, tau) = reduced_state(&mm, &mut rng);
        let m = mm.crba(&mut md, &q).unwrap().clone();
        assert!((&m - m.transpose()).amax() <= 1e-12 * m.amax());
        let nle = mm.nonlinear_effects(&mut md, &q, &v).unwrap().clone();
        let r = mm.rnea(&mut md, &q, &v, &tau).unwrap().clone();
        let want = &m * DVector::from_column_slice(&tau) + nle;
        assert!(
            rel(r.as_slice(), want.as_slice(), 1.0) < 1e-10,
            "{}",
            path.display()
        );
        if !massless.is_empty() {
            let low = m.clone().symmetric_eigenvalues().min();
            assert!(
                low >= -1e-12 * m.amax(),
                "{}: M has eigenvalue {low}",
                path.display()
            );
            continue;
        }
        assert!(
            m.cholesky().is_some(),
            "{}: M not positive definite",
            path.display()
        );
        let ddq = mm.aba(&mut md, &q, &v, &tau).unwrap().clone();
        let back = mm.rnea(&mut md, &q, &v, ddq.as_slice()).unwrap();
        assert!(rel(back.as_slice(), &tau, 1.0) < 1e-9, "{}", path.display());
    }
    eprintln!(
        "{}: {} mimic joints, nv {} -> {}, {} joints with a massless subtree",
        path.display(),
        mm.mimics().len(),
        mm.model().nv(),
        mm.nv(),
        massless.len()
    );
}

#[test]
fn live_baxter_pr2_panda_equal_pinocchio_and_romeo_talos_pass_the_identities() {
    if !live("mimic joints against Pinocchio's mimic=True") {
        return;
    }
    let root = rigid::io::robots::example_robot_data().expect("example-robot-data");
    let files = [
        "panda_description/urdf/panda.urdf",
        "baxter_description/urdf/baxter.urdf",
        "pr2_description/urdf/pr2.urdf",
    ];
    let paths: Vec<String> = files
        .iter()
        .map(|f| root.join(f).display().to_string())
        .collect();
    let args: Vec<&str> = paths.iter().map(String::as_str).collect();
    let recs = json_lines("pinocchio/mimic.py", &args);
    for (p, rec) in paths.iter().zip(&recs) {
        compare_with_pinocchio(&load_pinocchio_order(Path::new(p)), rec);
    }
    for f in [
        "talos_data/robots/talos_full_v2.urdf",
        "romeo_description/urdf/romeo.urdf",
    ] {
        identities_of(&root.join(f));
    }
    // Alex's eight <mimic>s name joints the file does not have ("index_q1" for
    // "Left_index_q1"), which is why Pinocchio refuses it: each is a warning with its line, and
    // the fingers stay independent joints
    let alex = root.join("alex_description/urdf/alex_psyonic_hands.urdf");
    let (mm, warnings) = load_urdf_mimic(&alex, &UrdfOptions::default()).unwrap();
    let undefined = warnings
        .iter()
        .filter(|w| w.message.contains("which is not defined"))
        .count();
    assert_eq!((undefined, mm.mimics().len()), (8, 0), "{warnings:?}");
}

#[test]
fn simulating_the_full_model_held_by_the_couplings_follows_the_reduced_dynamics() {
    // rk4 on the full model under the joint constraints (what `rigid simulate --mimic` runs)
    // against rk4 on the reduced coordinates with MimicModel::aba, 0.3 s of passive motion
    use rigid::simulation::{ConstraintOptions, Controller, SimulationOptions, Simulator};
    // TALOS's grippers: sources later in the tree, multipliers other than 1; every joint has
    // one coordinate, so the reduced state is a vector
    let mut rng = Rng::new(9);
    let path = example_robot_data().join("talos_data/robots/talos_full_v2.urdf");
    let (mm, _) = load_urdf_mimic(&path, &UrdfOptions::default()).unwrap();
    let model = mm.model().clone();
    let (q0, v0, _) = reduced_state(&mm, &mut rng);
    let (dt, steps) = (1e-3, 300);
    let (mut qf, mut vf) = (vec![0.0; model.nq()], vec![0.0; model.nv()]);
    mm.expand_q(&q0, &mut qf);
    mm.expand_v(&v0, &mut vf);
    let opts = SimulationOptions::conservative(dt, rigid::simulation::Integrator::Rk4);
    let mut sim = Simulator::new(&model, &qf, &vf, opts, Controller::none(&model))
        .unwrap()
        .with_constraints(&mm.constraints(), ConstraintOptions::default())
        .unwrap();
    sim.run(steps, |_| {}).unwrap();
    // the reduced state by classical RK4 (every joint of this tree is a vector space)
    let mut md = MimicData::new(&mm);
    let tau = vec![0.0; mm.nv()];
    let mut f = |q: &[f64], v: &[f64]| mm.aba(&mut md, q, v, &tau).unwrap().as_slice().to_vec();
    let (mut q, mut v) = (q0.clone(), v0.clone());
    let axpy =
        |x: &[f64], a: f64, y: &[f64]| x.iter().zip(y).map(|(x, y)| x + a * y).collect::<Vec<_>>();
    for _ in 0..steps {
        let (k1q, k1v) = (v.clone(), f(&q, &v));
        let (q2, v2) = (axpy(&q, dt / 2.0, &k1q), axpy(&v, dt / 2.0, &k1v));
        let (k2q, k2v) = (v2.clone(), f(&q2, &v2));
        let (q3, v3) = (axpy(&q, dt / 2.0, &k2q), axpy(&v, dt / 2.0, &k2v));
        let (k3q, k3v) = (v3.clone(), f(&q3, &v3));
        let (q4, v4) = (axpy(&q, dt, &k3q), axpy(&v, dt, &k3v));
        let k4v = f(&q4, &v4);
        for i in 0..q.len() {
            q[i] += dt / 6.0 * (k1q[i] + 2.0 * k2q[i] + 2.0 * k3q[i] + v4[i]);
            v[i] += dt / 6.0 * (k1v[i] + 2.0 * k2v[i] + 2.0 * k3v[i] + k4v[i]);
        }
    }
    let mut want = vec![0.0; model.nq()];
    mm.expand_q(&q, &mut want);
    let e = rel(sim.q(), &want, 1.0);
    eprintln!("TALOS grippers, 0.3 s: constrained full model vs reduced RK4 {e:.1e}");
    assert!(
        e < 1e-8,
        "constrained full model vs reduced RK4 after 0.3 s: {e:e}"
    );
}

#[test]
fn an_mjcf_linear_joint_equality_is_a_mimic_and_a_polynomial_one_is_not() {
    // jb = 0.3 − 2 ja (MuJoCo's polycoef "0.3 -2 0 0 0"); a quadratic stays a constraint
    let xml = |poly: &str| {
        format!(
            r#"<mujoco><worldbody>
              <body name="a"><joint name="ja" axis="0 1 0"/><geom size="0.1" pos="0 0 -1"/>
                <body name="b" pos="0 0 -1"><joint name="jb" axis="0 1 0"/>
                  <geom size="0.1" pos="1 0 0"/></body></body></worldbody>
              <equality><joint joint1="jb" joint2="ja" polycoef="{poly}"/></equality></mujoco>"#
        )
    };
    let dir = std::path::Path::new(".");
    let mj = rigid::io::mjcf::load_mjcf_str(&xml("0.3 -2 0 0 0"), dir).unwrap();
    let (constraints, _) = mj.constraint_models().unwrap();
    let m = Mimic::from_constraint(&constraints[0]).unwrap();
    assert_eq!(
        (m.joint, m.source, m.multiplier, m.offset),
        (JointId(1), JointId(0), -2.0, 0.3)
    );
    let mm = MimicModel::new(mj.model.clone(), &[m]).unwrap();
    assert_eq!(mm.nv(), 1);
    // the reduced acceleration is the constrained full model's
    let (mut md, mut data) = (MimicData::new(&mm), Data::new(mm.model()));
    let mut cdata = ConstraintData::new(mm.model(), &constraints).unwrap();
    let ddq = mm.aba(&mut md, &[0.4], &[1.0], &[0.5]).unwrap()[0];
    let mut qf = [0.0; 2];
    mm.expand_q(&[0.4], &mut qf);
    let got = constraint_dynamics(
        mm.model(),
        &mut data,
        &mut cdata,
        &qf,
        &[1.0, -2.0],
        &[0.5, 0.0],
        &ProximalSettings::default(),
    )
    .unwrap();
    assert!(
        (got[0] - ddq).abs() < 1e-10 && (got[1] + 2.0 * ddq).abs() < 1e-10,
        "{got} vs {ddq}"
    );
    let quad = rigid::io::mjcf::load_mjcf_str(&xml("0 0 1 0 0"), dir).unwrap();
    assert!(Mimic::from_constraint(&quad.constraint_models().unwrap().0[0]).is_none());
}

#[test]
fn live_cassie_s_gearboxes_are_mimics_and_pass_the_identities() {
    if !live("Cassie's gearboxes as mimic joints") {
        return;
    }
    let root = rigid::io::robots::example_robot_data().expect("example-robot-data");
    let s = rigid::io::sdf::load_sdf(root.join("cassie_description/robots/cassie.sdf")).unwrap();
    let mimics: Vec<Mimic> = s.mimics();
    // 10 gearboxes: 8 couple two joints from their reference body; the feet's output hinges
    // close loops, so those 2 are left out with a warning
    assert_eq!(mimics.len(), 8);
    let left_out = s
        .warnings
        .iter()
        .filter(|w| w.message.contains("a gearbox rigid cannot hold"))
        .count();
    assert_eq!(left_out, 2);
    let ratios: Vec<f64> = mimics.iter().map(|m| m.multiplier.abs()).collect();
    for r in &ratios {
        assert!(
            [0.04, 0.0625, 0.02].iter().any(|x| (x - r).abs() < 1e-15),
            "{ratios:?}"
        );
    }
    let mm = MimicModel::new(s.model.clone(), &mimics).unwrap();
    assert_eq!((s.model.nv(), mm.nv()), (48, 40));
    let mut md = MimicData::new(&mm);
    let mut rng = Rng::new(11);
    for _ in 0..3 {
        let (q, v, tau) = reduced_state(&mm, &mut rng);
        let m = mm.crba(&mut md, &q).unwrap().clone();
        assert!(m.clone().cholesky().is_some());
        let ddq = mm.aba(&mut md, &q, &v, &tau).unwrap().clone();
        let back = mm.rnea(&mut md, &q, &v, ddq.as_slice()).unwrap();
        assert!(rel(back.as_slice(), &tau, 1.0) < 1e-9);
    }
}

#[test]
fn energy_rate_equals_power_for_talos_with_its_mimics() {
    // constant torques on the reduced coordinates: E(T) − E(0) = ∫ τ · q̇ dt (RK4 at 1 ms, the
    // power integrated by Simpson's rule over the same steps), and without torque E is constant
    let path = example_robot_data().join("talos_data/robots/talos_full_v2.urdf");
    let (mm, _) = load_urdf_mimic(&path, &UrdfOptions::default()).unwrap();
    let mut rng = Rng::new(12);
    let (q0, v0, tau) = reduced_state(&mm, &mut rng);
    let tau: Vec<f64> = tau.iter().map(|t| 0.2 * t).collect();
    let mut md = MimicData::new(&mm);
    let dt = 1e-3;
    for torque in [false, true] {
        let t: Vec<f64> = if torque {
            tau.clone()
        } else {
            vec![0.0; mm.nv()]
        };
        let energy = |md: &mut MimicData, q: &[f64], v: &[f64]| {
            mm.kinetic_energy(md, q, v).unwrap() + mm.potential_energy(md, q).unwrap()
        };
        let power = |v: &[f64]| v.iter().zip(&t).map(|(a, b)| a * b).sum::<f64>();
        let (mut q, mut v) = (q0.clone(), v0.clone());
        let e0 = energy(&mut md, &q, &v);
        let mut work = 0.0;
        let axpy = |x: &[f64], a: f64, y: &[f64]| -> Vec<f64> {
            x.iter().zip(y).map(|(x, y)| x + a * y).collect()
        };
        for _ in 0..200 {
            let mut f =
                |q: &[f64], v: &[f64]| mm.aba(&mut md, q, v, &t).unwrap().as_slice().to_vec();
            let k1 = f(&q, &v);
            let (q2, v2) = (axpy(&q, dt / 2.0, &v), axpy(&v, dt / 2.0, &k1));
            let k2 = f(&q2, &v2);
            let (q3, v3) = (axpy(&q, dt / 2.0, &v2), axpy(&v, dt / 2.0, &k2));
            let k3 = f(&q3, &v3);
            let (q4, v4) = (axpy(&q, dt, &v3), axpy(&v, dt, &k3));
            let k4 = f(&q4, &v4);
            // Simpson on the RK4 stages: P(v), P(v2), P(v3), P(v4)
            work += dt / 6.0 * (power(&v) + 2.0 * power(&v2) + 2.0 * power(&v3) + power(&v4));
            for i in 0..q.len() {
                q[i] += dt / 6.0 * (v[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
                v[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        let gained = energy(&mut md, &q, &v) - e0;
        let e = (gained - work).abs() / e0.abs().max(1.0);
        eprintln!("TALOS with mimics, 0.2 s, torque {torque}: ΔE {gained:.6e} J, work {work:.6e} J, gap {e:.1e} of E");
        assert!(e < 1e-8, "energy rate vs power: {e:e}");
        if torque {
            assert!(work.abs() > 1e-3, "the torques did work");
        }
    }
}
