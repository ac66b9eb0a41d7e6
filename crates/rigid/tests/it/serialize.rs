//! The serialised form of a model (`Model::to_json`, serde): a model read back is the same model
//! (the same JSON, the same results bit for bit) for every built-in model, random trees of every
//! joint type and real robots; a damaged file is an error naming what is wrong.

use crate::common::{every_joint_tree, example_robot_data, models, state};
use rigid::multibody::*;

/// Every algorithm output the tests compare, for one state, as bits.
fn outputs(model: &Model, q: &[f64], v: &[f64], a: &[f64]) -> Vec<u64> {
    let mut d = Data::new(model);
    let mut out: Vec<f64> = rnea(model, &mut d, q, v, a)
        .unwrap()
        .iter()
        .copied()
        .collect();
    out.extend(crba(model, &mut d, q).unwrap().iter());
    out.extend(aba(model, &mut d, q, v, a).unwrap().iter());
    out.extend(compute_minverse(model, &mut d, q).unwrap().iter());
    out.extend(compute_joint_jacobians(model, &mut d, q).unwrap().iter());
    out.push(kinetic_energy(model, &mut d, q, v).unwrap());
    out.push(potential_energy(model, &mut d, q).unwrap());
    out.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn a_model_read_back_is_the_same_model_bit_for_bit() {
    let mut all = models();
    all.extend((0..3).map(|s| every_joint_tree(s, 12)));
    for (file, floating) in [
        ("ur_description/urdf/ur5_robot.urdf", false),
        ("talos_data/robots/talos_reduced.urdf", true),
    ] {
        let opts = rigid::io::urdf::UrdfOptions {
            floating,
            ..Default::default()
        };
        all.push(
            rigid::io::urdf::load_urdf_with(example_robot_data().join(file), &opts)
                .unwrap()
                .0,
        );
    }
    for (k, model) in all.iter().enumerate() {
        let json = model.to_json();
        let back = Model::from_json(&json).unwrap();
        assert_eq!(back.to_json(), json, "{}", model.name());
        assert_eq!(back.joints(), model.joints());
        assert_eq!(back.inertias(), model.inertias());
        assert_eq!(back.frames(), model.frames());
        let mut rng = Rng::new(k as u64);
        let (q, v, a) = state(model, &mut rng);
        assert!(
            outputs(&back, &q, &v, &a) == outputs(model, &q, &v, &a),
            "{}",
            model.name()
        );
        // serde's other formats see the same form
        let value = serde_json::to_value(model).unwrap();
        let again: Model = serde_json::from_value(value).unwrap();
        assert_eq!(again.to_json(), json);
    }
}

#[test]
fn a_damaged_model_file_is_an_error_that_says_what_is_wrong() {
    let model = builtin("double_pendulum").unwrap();
    let json: serde_json::Value = serde_json::from_str(&model.to_json()).unwrap();
    let damage = |path: &[&str], value: serde_json::Value| {
        let mut v = json.clone();
        let mut x = &mut v;
        for p in &path[..path.len() - 1] {
            x = match p.parse::<usize>() {
                Ok(i) => &mut x[i],
                Err(_) => &mut x[*p],
            };
        }
        x[path[path.len() - 1]] = value;
        Model::from_json(&v.to_string()).unwrap_err().to_string()
    };
    use serde_json::json;
    let cases: Vec<(Vec<&str>, serde_json::Value, &str)> = vec![
        (vec!["version"], json!(7), "version 7"),
        (vec!["gravity"], json!([0, 0, "x"]), "malformed"),
        (vec!["joints", "1", "parent"], json!(1), "joint2"),
        (
            vec!["joints", "1", "name"],
            json!("joint1"),
            "duplicate name 'joint1'",
        ),
        (
            vec!["joints", "0", "kind"],
            json!({"type": "revolute", "axis": [0, 0, 0]}),
            "axis is zero",
        ),
        (
            vec!["joints", "0", "kind"],
            json!({"type": "hinge", "axis": [0, 0, 1]}),
            "malformed",
        ),
        (vec!["joints", "1", "idx_q"], json!(0), "wrong indices"),
        (
            vec!["joints", "0", "subtree_end"],
            json!(1),
            "wrong subtree_end",
        ),
        (
            vec!["joints", "0", "placement", "rotation"],
            json!([[2, 0, 0], [0, 1, 0], [0, 0, 1]]),
            "not a finite rigid transform",
        ),
        (vec!["inertias", "0", "mass"], json!(-1), "mass"),
        (vec!["lower"], json!([0.0]), "lower has 1 entries"),
        (vec!["armature"], json!([0.0, -1.0]), "out of range"),
        (vec!["surprise"], json!(1), "unknown field"),
    ];
    for (path, value, expected) in cases {
        let e = damage(&path, value);
        assert!(e.contains(expected), "{path:?}: {e}");
    }
}

/// An axis that a second normalisation moves by an ulp (romeo's LThumb1 in example-robot-data)
/// reads back as it is, bit for bit.
#[test]
fn an_axis_unit_to_round_off_reads_back_bit_for_bit() {
    let urdf = r#"<robot name="thumb">
  <link name="base"/>
  <link name="a"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="LThumb1" type="revolute">
    <origin rpy="-4.76837e-07 1.37881 -2.53073" xyz="0.07115 -0.02465 -0.01233"/>
    <axis xyz="-0.573576 0.819152 1.05097e-07"/>
    <parent link="base"/><child link="a"/>
    <limit effort="0" lower="-1.06" upper="0" velocity="0"/>
  </joint>
</robot>"#;
    let model = rigid::io::urdf::load_urdf_str(urdf, false).unwrap();
    let json = model.to_json();
    let back = Model::from_json(&json).unwrap();
    assert_eq!(back.to_json(), json);
    assert_eq!(back.joints(), model.joints());
}
