//! MJCF `<equality>` as constraint models (`MjcfModel::constraint_models`): the residuals and
//! their rates equal MuJoCo 4.0's `efc_pos` and `efc_vel` (fixture mjcf_equality.json from
//! gen_mjcf_equality.py, at qpos0 and 4 random states of two files), the four-bar of MJCF
//! has the constrained dynamics of the four-bar of URDF closed by hand, a welded box hangs
//! still with λ its weight, and what cannot be converted is an error or a warning naming the line.

use super::{fixtures, load, rel_err};
use crate::common::reference;
use rigid::io::mjcf::{load_mjcf, load_mjcf_str};
use rigid::multibody::constraints::{
    constraint_dynamics, ConstraintData, ConstraintKind, ConstraintModel, ProximalSettings,
};
use rigid::multibody::{Data, ReferenceFrame};
use rigid::spatial::{Transform, Vec3};

fn exact() -> ProximalSettings {
    ProximalSettings::new(1e-12, 0.0, 1)
}

/// MuJoCo's residual of a connect is `p1 − p2` in world axes, of a joint equality
/// `q1 − p(q2)`: rigid's error and its rate in world-aligned axes are the same numbers. A weld's
/// residual is `p1 − p2` and a quaternion's vector part, where rigid's error is Pinocchio's
/// `−log6(c1Mc2)`: for welds, `p1 − p2` of rigid's two constraint frames and the vector part of
/// the quaternion of their relative rotation `c2Rc1` are compared (their rates are not).
#[test]
fn residuals_and_rates_equal_mujoco() {
    let text = std::fs::read_to_string(fixtures().join("mjcf_equality.json")).unwrap();
    compare_with_mujoco(&serde_json::from_str(&text).unwrap());
}

/// The generator run now (MuJoCo installed, `RIGID_CROSSCHECK=1`): the same comparison on fresh
/// numbers, and the checked-in fixture equal to them.
#[test]
fn residuals_and_rates_equal_live_mujoco() {
    if !reference::live("MJCF equalities against live MuJoCo") {
        return;
    }
    let script = "fixtures/constraints/gen_mjcf_equality.py";
    compare_with_mujoco(
        &serde_json::from_slice(&reference::run_script(script, &["--print"])).unwrap(),
    );
    reference::check_generator(script);
}

fn compare_with_mujoco(fixture: &serde_json::Value) {
    let mut worst: f64 = 0.0;
    for case in fixture["cases"].as_array().unwrap() {
        let file = case["file"].as_str().unwrap();
        let mj = load_mjcf(fixtures().join(file)).unwrap();
        let (constraints, _) = mj.constraint_models().unwrap();
        let layout = mj.layout();
        let (model, mut data) = (&mj.model, Data::new(&mj.model));
        let mut cd = ConstraintData::new(model, &constraints).unwrap();
        let tau = vec![0.0; model.nv()];
        for state in case["states"].as_array().unwrap() {
            let get = |k: &str| -> Vec<f64> {
                state[k]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect()
            };
            let (mut q, mut v) = (vec![0.0; model.nq()], vec![0.0; model.nv()]);
            layout.q_from_mujoco(&get("qpos"), &mut q).unwrap();
            v.copy_from_slice(&get("qvel"));
            layout.v_from_mujoco(&q, &mut v);
            // the site weld repeats the site connect: redundant rows, solved by proximal steps
            let settings = ProximalSettings::new(1e-10, 1e-6, 500);
            constraint_dynamics(model, &mut data, &mut cd, &q, &v, &tau, &settings).unwrap();
            // MuJoCo's rows: the tendon equality's last (one row), left out by rigid
            let (pos, vel) = (get("efc_pos"), get("efc_vel"));
            let mut row = 0;
            for (i, c) in constraints.iter().enumerate() {
                let r = cd.rows_of(i);
                if matches!(c.kind, ConstraintKind::Frame) {
                    let at = |j: Option<rigid::multibody::JointId>, x: &Transform| {
                        j.map_or(*x, |j| data.placements[j.0] * *x)
                    };
                    let (o1, o2) = (at(c.joint1, &c.placement1), at(c.joint2, &c.placement2));
                    // rotation rows: the vector part of the quaternion of c2Rc1 (w > 0)
                    let rel = nalgebra::Rotation3::from_matrix_unchecked(
                        o2.rotation.transpose() * o1.rotation,
                    );
                    let quat = nalgebra::UnitQuaternion::from_rotation_matrix(&rel);
                    let im = quat.imag() * quat.w.signum();
                    let d = o1.translation - o2.translation;
                    for k in 0..6 {
                        let x = if k < 3 { d[k] } else { im[k - 3] };
                        let diff = (x - pos[row + k]).abs();
                        assert!(
                            diff < 1e-12,
                            "{file}: {}: {} vs {}",
                            c.name,
                            d[k],
                            pos[row + k]
                        );
                        worst = worst.max(diff);
                    }
                } else {
                    for k in 0..r.len() {
                        let (e, de) = (cd.error[r.start + k], cd.velocity[r.start + k]);
                        let diff = (e - pos[row + k]).abs().max((de - vel[row + k]).abs());
                        assert!(
                            diff < 1e-12,
                            "{file}: {}: row {k}: rigid ({e}, {de}) MuJoCo ({}, {})",
                            c.name,
                            pos[row + k],
                            vel[row + k]
                        );
                        worst = worst.max(diff);
                    }
                }
                row += r.len();
            }
            // MuJoCo has one row more in equalities.xml: the tendon equality rigid leaves out
            assert_eq!(
                pos.len() - row,
                usize::from(file == "equalities.xml"),
                "{file}"
            );
        }
    }
    eprintln!("MJCF equalities: largest difference to MuJoCo's residuals and rates {worst:.1e}");
}

/// fourbar.xml is fourbar.urdf assembled at crank angle 0.5 with its loop in a `<connect>`:
/// rigid's `q` of the MJCF model is the URDF's less the assembly angles, and the constrained
/// accelerations and pin forces of the two agree.
#[test]
fn fourbar_of_mjcf_is_fourbar_of_urdf() {
    let mj = load_mjcf(fixtures().join("fourbar.xml")).unwrap();
    let (from_mjcf, skipped) = mj.constraint_models().unwrap();
    assert!(skipped.is_empty());
    // MuJoCo's anchor on the rocker is where the coupler's tip is at qpos0: the rocker's tip
    let on_rocker = from_mjcf[0].placement2.translation;
    assert!(
        (on_rocker - Vec3::new(0.6, 0.0, 0.0)).amax() < 1e-12,
        "{on_rocker}"
    );
    let urdf = load("fourbar.urdf", false);
    let tip = |x: f64| Transform::from_translation(Vec3::new(x, 0.0, 0.0));
    let by_hand = ConstraintModel::point(
        urdf.joint_id("coupler_joint"),
        tip(0.8),
        urdf.joint_id("rocker_joint"),
        tip(0.6),
    )
    .with_reference(ReferenceFrame::WorldAligned);
    let assembly = [0.5, 0.02116623166979137, 1.1280269456729848];
    let settings = ProximalSettings::new(1e-12, 1e-6, 200); // the planar loop is redundant in 3D
    let (mut d1, mut d2) = (Data::new(&mj.model), Data::new(&urdf));
    let mut c1 = ConstraintData::new(&mj.model, &from_mjcf).unwrap();
    let mut c2 = ConstraintData::new(&urdf, &[by_hand]).unwrap();
    for (k, q) in [[0.0, 0.0, 0.0], [0.1, -0.2, 0.05], [-0.3, 0.2, 0.4]]
        .iter()
        .enumerate()
    {
        let q_urdf: Vec<f64> = q.iter().zip(assembly).map(|(a, b)| a + b).collect();
        let (v, tau) = ([0.5, -1.0, 0.3], [0.2, 0.0, -0.1]);
        let a = constraint_dynamics(&mj.model, &mut d1, &mut c1, q, &v, &tau, &settings)
            .unwrap()
            .clone();
        let b = constraint_dynamics(&urdf, &mut d2, &mut c2, &q_urdf, &v, &tau, &settings)
            .unwrap()
            .clone();
        let (ea, el) = (
            rel_err(a.as_slice(), b.as_slice()),
            rel_err(c1.lambda.as_slice(), c2.lambda.as_slice()),
        );
        assert!(ea < 1e-9 && el < 1e-9, "state {k}: q̈ {ea:.1e}, λ {el:.1e}");
    }
}

/// A free box welded to the world where it starts (`<weld body1="box"/>`): it hangs still, and
/// the weld carries its weight. The weld's frame is body2's (the world's) origin moved by
/// `anchor` (0), so `λ` (angular first, world axes) is the weight's wrench about the world
/// origin: `(p × m g e_z, m g e_z)` with `p` the box's centre.
#[test]
fn welded_box_hangs_with_its_weight() {
    let mj = load_mjcf(fixtures().join("equalities.xml")).unwrap();
    let (all, skipped) = mj.constraint_models().unwrap();
    let hold: Vec<_> = all.into_iter().filter(|c| c.name == "hold").collect();
    let mut cd = ConstraintData::new(&mj.model, &hold).unwrap();
    let mut data = Data::new(&mj.model);
    let mut q = vec![0.0; mj.model.nq()];
    mj.layout().q_from_mujoco(&mj.qpos0, &mut q).unwrap();
    let (v, tau) = (vec![0.0; mj.model.nv()], vec![0.0; mj.model.nv()]);
    let ddq = constraint_dynamics(&mj.model, &mut data, &mut cd, &q, &v, &tau, &exact()).unwrap();
    let box_dofs = 0..6;
    assert!(ddq.rows(box_dofs.start, 6).amax() < 1e-12, "{ddq}");
    let m = mj.bodies.iter().find(|b| b.name == "box").unwrap().mass;
    assert!((m - 500.0 * 0.2 * 0.4 * 0.6).abs() < 1e-12);
    let (p, w) = (Vec3::new(0.2, -0.1, 1.5), m * 9.81);
    let expected = [p.y * w, -p.x * w, 0.0, 0.0, 0.0, w];
    let lambda: Vec<f64> = cd.lambda.iter().copied().collect();
    assert!(
        rel_err(&lambda, &expected) < 1e-12,
        "{lambda:?} vs {expected:?}"
    );
    // what was left out, with its line
    let said: Vec<String> = skipped.iter().map(ToString::to_string).collect();
    assert_eq!(said.len(), 2, "{said:?}");
    assert!(
        said[0].starts_with("line 34: tendon \"tie\": tendon equalities"),
        "{}",
        said[0]
    );
    assert!(
        said[1].starts_with("line 35: weld \"off\": active=\"false\""),
        "{}",
        said[1]
    );
}

#[test]
fn bad_equalities_are_errors_naming_the_line() {
    let model = |eq: &str| {
        load_mjcf_str(
            &format!(
                r#"<mujoco><worldbody><body name="b"><joint name="j" type="ball"/>
                <geom size="0.1"/></body><body name="c" pos="1 0 0"><joint name="h"/>
                <geom size="0.1"/></body></worldbody>
                <equality>{eq}</equality></mujoco>"#
            ),
            std::path::Path::new("."),
        )
        .unwrap()
    };
    let err = |eq: &str| model(eq).constraint_models().unwrap_err().to_string();
    assert_eq!(
        err(r#"<connect body1="nobody" anchor="0 0 0"/>"#),
        "line 4: <connect>: body1: no body named \"nobody\""
    );
    assert_eq!(
        err(r#"<joint name="bad" joint1="j"/>"#),
        "line 4: joint \"bad\": joint \"j\" is a ball joint: a joint equality ties hinges and slides"
    );
    assert_eq!(
        err(r#"<weld site1="s" site2="t"/>"#),
        "line 4: <weld>: site1: no site named \"s\""
    );
    // MuJoCo's default `torquescale` is 1; another is said, and the weld kept
    let (c, said) = model(r#"<weld body1="c" torquescale="0.5"/>"#)
        .constraint_models()
        .unwrap();
    assert_eq!((c.len(), said.len()), (1, 1));
    assert!(
        said[0].message.contains("torquescale=\"0.5\""),
        "{}",
        said[0]
    );
}
