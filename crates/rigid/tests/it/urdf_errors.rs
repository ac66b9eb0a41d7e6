//! Bad URDF input gives an error that names the link or joint and the line, never a panic.

use rigid::io::urdf::{
    build_model_with, load_urdf_str, parse_urdf_str, InertiaIssueKind, InertiaPolicy, SiblingOrder,
    UrdfError, UrdfOptions,
};
use rigid::multibody::FrameKind;

/// A valid two-link arm; the tests break one thing at a time.
const GOOD: &str = r#"<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <link name="upper">
    <inertial>
      <origin xyz="0 0 0.5" rpy="0 0 0"/>
      <mass value="2"/>
      <inertia ixx="0.1" iyy="0.1" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <link name="lower">
    <inertial>
      <mass value="1"/>
      <inertia ixx="0.05" iyy="0.05" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/>
    <child link="upper"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="2"/>
  </joint>
  <joint name="elbow" type="continuous">
    <origin xyz="0 0 1"/>
    <parent link="upper"/>
    <child link="lower"/>
    <axis xyz="0 2 0"/>
  </joint>
</robot>
"#;

/// Parses `text` expecting an error; checks that its message contains every `needle` and that it
/// points at `line`.
fn expect_error(text: &str, line: u32, needles: &[&str]) -> UrdfError {
    let err = match parse_urdf_str(text) {
        Ok(_) => panic!("accepted bad URDF:\n{text}"),
        Err(e) => e,
    };
    let msg = err.to_string();
    for n in needles {
        assert!(msg.contains(n), "error {msg:?} does not mention {n:?}");
    }
    assert_eq!(
        err.line(),
        Some(line),
        "error {msg:?} points at the wrong line"
    );
    assert!(
        msg.contains(&format!("line {line}")),
        "{msg:?} has no line number"
    );
    err
}

#[test]
fn good_urdf_parses_with_file_order_and_normalised_axes() {
    let r = parse_urdf_str(GOOD).unwrap();
    assert_eq!(r.name, "arm");
    assert_eq!(r.links[r.root].name, "base");
    assert_eq!(r.joints[1].axis, rigid::spatial::Vec3::y());
    assert_eq!(r.joints[0].line, 17);
    assert!(r.inertia_report().is_empty());
}

#[test]
fn malformed_xml_is_reported_with_its_line() {
    let text = GOOD.replace("<link name=\"lower\">", "<link name=\"lower\"");
    let err = parse_urdf_str(&text).unwrap_err();
    assert!(matches!(err, UrdfError::Xml { .. }), "{err}");
    assert!(err.line().is_some());
    assert!(err.to_string().contains("malformed XML"));
}

#[test]
fn missing_parent_link_names_the_joint() {
    let text = GOOD.replace("<parent link=\"upper\"/>", "<parent link=\"uper\"/>");
    expect_error(&text, 25, &["joint \"elbow\"", "\"uper\"", "not defined"]);
}

#[test]
fn missing_attribute_names_the_element() {
    let text = GOOD.replace(
        "<joint name=\"elbow\" type=\"continuous\">",
        "<joint name=\"elbow\">",
    );
    expect_error(&text, 23, &["joint \"elbow\"", "\"type\""]);
    let text = GOOD.replace("<child link=\"lower\"/>", "");
    expect_error(&text, 23, &["joint \"elbow\"", "<child>"]);
}

#[test]
fn a_cycle_is_found() {
    // elbow: upper -> lower; add lower -> upper by making "upper"'s parent "lower": upper then
    // has two parents, which is the first thing found.
    let two_parents = GOOD.replace(
        "</robot>",
        r#"<joint name="back" type="fixed"><parent link="lower"/><child link="upper"/></joint>
</robot>"#,
    );
    expect_error(
        &two_parents,
        29,
        &["joint \"back\"", "two parents", "\"shoulder\""],
    );
    // A loop detached from the root: base alone, then upper <-> lower.
    let cycle = GOOD.replace("<parent link=\"base\"/>", "<parent link=\"lower\"/>");
    let cycle = cycle.replace(
        "</robot>",
        r#"<link name="tip"/><joint name="tipj" type="fixed"><parent link="base"/><child link="tip"/></joint>
</robot>"#,
    );
    expect_error(&cycle, 17, &["cycle", "joint \"shoulder\""]);
    // A self loop.
    let self_loop = GOOD.replace("<child link=\"lower\"/>", "<child link=\"upper\"/>");
    let self_loop = self_loop.replace("<link name=\"lower\">", "<link name=\"lower2\">");
    expect_error(&self_loop, 23, &["cycle", "joint \"elbow\""]);
}

#[test]
fn several_roots_are_refused() {
    let text = GOOD.replace("</robot>", "<link name=\"stray\"/>\n</robot>");
    expect_error(&text, 29, &["no unique root", "\"stray\"", "\"base\""]);
}

#[test]
fn unknown_joint_type_names_the_joint() {
    let text = GOOD.replace("type=\"continuous\"", "type=\"ball\"");
    expect_error(
        &text,
        23,
        &["joint \"elbow\"", "unknown joint type \"ball\""],
    );
}

#[test]
fn negative_mass_names_the_link_under_every_policy() {
    let text = GOOD.replace("<mass value=\"1\"/>", "<mass value=\"-1\"/>");
    let robot = parse_urdf_str(&text).unwrap();
    for inertia in [
        InertiaPolicy::Strict,
        InertiaPolicy::Warn,
        InertiaPolicy::Repair,
    ] {
        let opts = UrdfOptions {
            inertia,
            ..UrdfOptions::default()
        };
        let err = build_model_with(&robot, &opts).unwrap_err();
        let msg = err.to_string();
        assert_eq!(err.line(), Some(12), "{msg}");
        assert!(
            msg.contains("link \"lower\"") && msg.contains("mass"),
            "{msg}"
        );
    }
}

#[test]
fn non_finite_values_are_refused() {
    let text = GOOD.replace("<origin xyz=\"0 0 1\"/>", "<origin xyz=\"0 nan 1\"/>");
    expect_error(&text, 24, &["joint \"elbow\"", "non-finite"]);
    let text = GOOD.replace("izz=\"0.01\" ixy", "izz=\"inf\" ixy");
    expect_error(&text, 8, &["link \"upper\"", "non-finite"]);
    let text = GOOD.replace("<mass value=\"2\"/>", "<mass value=\"two\"/>");
    expect_error(&text, 7, &["link \"upper\"", "not a number"]);
}

#[test]
fn zero_axis_is_refused() {
    let text = GOOD.replace("<axis xyz=\"0 2 0\"/>", "<axis xyz=\"0 0 0\"/>");
    expect_error(&text, 27, &["joint \"elbow\"", "zero joint axis"]);
}

#[test]
fn duplicate_names_are_refused() {
    let text = GOOD.replace("<link name=\"lower\">", "<link name=\"upper\">");
    expect_error(&text, 11, &["link \"upper\"", "duplicate", "line 4"]);
}

#[test]
fn unphysical_inertias_follow_the_policy() {
    // Not positive semi-definite: refused by `strict`, loaded as written by `warn` (the default),
    // replaced by a consistent inertia by `repair`; each says which link and line.
    let text = GOOD.replace("ixx=\"0.05\" iyy=\"0.05\"", "ixx=\"-0.05\" iyy=\"0.05\"");
    let r = parse_urdf_str(&text).unwrap();
    let report = r.inertia_report();
    assert_eq!(report.len(), 1);
    assert!(matches!(report[0].kind, InertiaIssueKind::Invalid(_)));
    let strict = UrdfOptions {
        inertia: InertiaPolicy::Strict,
        ..UrdfOptions::default()
    };
    let err = build_model_with(&r, &strict).unwrap_err().to_string();
    assert!(err.contains("link \"lower\""), "{err}");
    assert!(err.contains("line 12"), "{err}");
    assert!(err.contains("positive semi-definite"), "{err}");
    let (model, warnings) = build_model_with(&r, &UrdfOptions::default()).unwrap();
    assert_eq!(warnings.len(), 1);
    let w = warnings[0].to_string();
    assert!(
        w.contains("line 12") && w.contains("\"lower\"") && w.contains("as written"),
        "{w}"
    );
    let as_written = r.link_inertia(r.link_index("lower").unwrap());
    assert_eq!(model.inertias()[1], as_written);
    let repair = UrdfOptions {
        inertia: InertiaPolicy::Repair,
        ..UrdfOptions::default()
    };
    let (model, warnings) = build_model_with(&r, &repair).unwrap();
    assert!(warnings[0].to_string().contains("repaired"), "{warnings:?}");
    assert!(model.inertia_issues().is_empty());
    assert_eq!(model.inertias()[1].mass(), 1.0);
    // Triangle inequality: 0.01 + 0.01 < 0.05: a warning, the model is built (as Pinocchio does).
    let text = GOOD.replace("ixx=\"0.05\" iyy=\"0.05\"", "ixx=\"0.01\" iyy=\"0.05\"");
    let report = parse_urdf_str(&text).unwrap().inertia_report();
    assert!(report.len() == 1 && !report[0].is_error(), "{report:?}");
    let msg = report[0].to_string();
    assert!(msg.contains("link \"lower\"") && msg.contains("line 12") && msg.contains("triangle"));
    let model = load_urdf_str(&text, false).unwrap();
    assert_eq!(model.inertia_issues().len(), 1);
    // A dummy inertia on one link is fine when the body it is welded into is physical (ANYmal).
    let dummy = GOOD.replace(
        "</robot>",
        r#"<link name="dummy"><inertial><mass value="1e-6"/>
  <inertia ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"/></inertial></link>
<joint name="weld" type="fixed"><parent link="lower"/><child link="dummy"/></joint>
</robot>"#,
    );
    let report = parse_urdf_str(&dummy).unwrap().inertia_report();
    assert!(report.len() == 1 && !report[0].is_error(), "{report:?}");
    let model = load_urdf_str(&dummy, false).unwrap();
    assert!((model.total_mass() - 3.000001).abs() < 1e-12);
    assert!(
        model.inertia_issues().is_empty(),
        "the composite body is physical"
    );
}

#[test]
fn round_off_is_not_a_defect() {
    // iCub's head: zeros but ixz = 2.4e-35 (eigenvalue -2.4e-35), CoM 0.11 m from the origin.
    let text = GOOD.replace(
        r#"<mass value="1"/>
      <inertia ixx="0.05" iyy="0.05" izz="0.01" ixy="0" ixz="0" iyz="0"/>"#,
        r#"<mass value="1.33687"/><origin xyz="0.0185 -0.1108 6.78454e-18"/>
      <inertia ixx="0" ixy="0" ixz="2.40741e-35" iyy="0" iyz="0" izz="0"/>"#,
    );
    let r = parse_urdf_str(&text).unwrap();
    assert!(r.inertia_report().is_empty(), "{:?}", r.inertia_report());
    let strict = UrdfOptions {
        inertia: InertiaPolicy::Strict,
        ..UrdfOptions::default()
    };
    let (_, warnings) = build_model_with(&r, &strict).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    // The same matrix 1e30 times larger is not round-off.
    let big = text.replace("2.40741e-35", "2.40741e-5");
    assert!(build_model_with(&parse_urdf_str(&big).unwrap(), &strict).is_err());
}

#[test]
fn zero_mass_moving_leaf_is_a_warning() {
    let text = GOOD.replace("<mass value=\"1\"/>", "<mass value=\"0\"/>");
    let text = text.replace(
        "ixx=\"0.05\" iyy=\"0.05\" izz=\"0.01\"",
        "ixx=\"0\" iyy=\"0\" izz=\"0\"",
    );
    let r = parse_urdf_str(&text).unwrap();
    let report = r.inertia_report();
    assert_eq!(report.len(), 1, "{report:?}");
    assert!(!report[0].is_error());
    let msg = report[0].to_string();
    assert!(msg.contains("\"lower\"") && msg.contains("\"elbow\"") && msg.contains("zero mass"));
    // Loaded all the same, as Pinocchio does.
    assert!(load_urdf_str(&text, false).is_ok());
}

#[test]
fn not_a_robot_and_empty_robot_are_refused() {
    expect_error("<model name=\"x\"/>", 1, &["expected <robot>"]);
    expect_error("<robot name=\"x\">\n</robot>", 1, &["no <link>"]);
    let err = parse_urdf_str("").unwrap_err();
    assert!(matches!(err, UrdfError::Xml { .. }));
}

#[test]
fn unreadable_file_is_an_io_error() {
    let err = rigid::io::urdf::load_urdf("/nonexistent/robot.urdf", false).unwrap_err();
    assert!(matches!(err, UrdfError::Io { .. }));
    assert!(err.to_string().contains("/nonexistent/robot.urdf"));
}

#[test]
fn model_level_errors_name_the_joint_or_link() {
    // lower > upper: Bullet's "no limit", loaded as urdfdom does, with a warning naming the line
    let text = GOOD.replace("lower=\"-1\" upper=\"1\"", "lower=\"1\" upper=\"-1\"");
    let robot = rigid::io::urdf::parse_urdf_str(&text).unwrap();
    let w = robot
        .warnings
        .iter()
        .find(|w| w.message.contains("above upper"))
        .unwrap();
    assert!(w.element.contains("shoulder") && w.line == 21, "{w}");
    let model = load_urdf_str(&text, false).unwrap();
    assert_eq!(model.lower_limits()[0], f64::NEG_INFINITY);
    // A link named like a moving joint: two namespaces, as in URDF and Pinocchio.
    let text = GOOD.replace("\"lower\"", "\"elbow\"");
    let model = load_urdf_str(&text, false).unwrap();
    assert_eq!(model.joint_id("elbow").unwrap().0, 1);
    let f = model.frame_id("elbow").unwrap();
    assert_eq!(model.frames()[f.0].kind, FrameKind::Body);
    // The free-flyer's name is taken.
    let text = GOOD.replace("\"shoulder\"", "\"root_joint\"");
    assert!(load_urdf_str(&text, false).is_ok());
    let err = load_urdf_str(&text, true).unwrap_err().to_string();
    assert!(err.contains("root_joint"), "{err}");
}

#[test]
fn planar_axis_and_mimic_target_are_checked() {
    let text = GOOD.replace("type=\"continuous\"", "type=\"planar\"");
    expect_error(&text, 23, &["joint \"elbow\"", "planar", "0 0 1"]);
    let text = text.replace("<axis xyz=\"0 2 0\"/>", "<axis xyz=\"0 0 3\"/>");
    let model = load_urdf_str(&text, false).unwrap();
    assert_eq!(model.joints()[1].kind, rigid::multibody::JointType::Planar);
    let text = GOOD.replace(
        "<axis xyz=\"0 2 0\"/>",
        "<axis xyz=\"0 2 0\"/><mimic joint=\"knee\" multiplier=\"2\"/>",
    );
    // A mimic of a joint that is not defined: a warning, the mimic dropped (alex_psyonic_hands).
    let robot = parse_urdf_str(&text).unwrap();
    let w = robot.warnings[0].to_string();
    assert!(w.contains("line 23") && w.contains("joint \"elbow\"") && w.contains("\"knee\""));
    assert!(robot.joint("elbow").unwrap().mimic.is_none());
    let text = text.replace("joint=\"knee\"", "joint=\"shoulder\"");
    let robot = parse_urdf_str(&text).unwrap();
    let mimic = robot.joint("elbow").unwrap().mimic.clone().unwrap();
    assert_eq!(
        (mimic.joint.as_str(), mimic.multiplier, mimic.offset),
        ("shoulder", 2.0, 0.0)
    );
    // Imported as an independent joint, as Pinocchio's default.
    assert_eq!(load_urdf_str(&text, false).unwrap().nv(), 2);
}

#[test]
fn truncated_or_corrupted_files_never_panic() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/pinocchio/all_joints.urdf"
    ))
    .unwrap();
    let mut cuts = 0;
    for end in (0..text.len())
        .step_by(13)
        .filter(|&e| text.is_char_boundary(e))
    {
        // Every prefix is rejected (or, rarely, a smaller valid robot), never a panic.
        if load_urdf_str(&text[..end], true).is_err() {
            cuts += 1;
        }
    }
    assert!(cuts > 100);
    // One word replaced at a time by junk.
    for (k, word) in text.split_whitespace().enumerate().step_by(5) {
        for junk in ["\"\"", "\"-1\"", "\"1e999\"", "<", "\"0 0\""] {
            let corrupted = text.replacen(word, junk, 1);
            let _ = load_urdf_str(&corrupted, k % 2 == 0);
        }
    }
}

#[test]
fn tolerated_oddities_are_warnings_with_lines() {
    // No robot name (ur3.urdf's header), an unknown element, an undeclared XML prefix (Drake).
    let text = GOOD
        .replace("<robot name=\"arm\">", "<robot>")
        .replace(
            "<link name=\"base\"/>",
            "<link name=\"base\"><sparkle/></link>",
        )
        .replace(
            "</robot>",
            "<drake:collision_filter_group name=\"g\"/>\n</robot>",
        );
    let robot = parse_urdf_str(&text).unwrap();
    let w: Vec<String> = robot.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(robot.name, "");
    assert!(
        w.iter()
            .any(|w| w.contains("line 1") && w.contains("drake")),
        "{w:?}"
    );
    assert!(
        w.iter().any(|w| w.contains("line 2") && w.contains("name")),
        "{w:?}"
    );
    assert!(
        w.iter()
            .any(|w| w.contains("line 3") && w.contains("<sparkle>")),
        "{w:?}"
    );
    let model = load_urdf_str(&text, false).unwrap();
    assert_eq!((model.name(), model.nv()), ("robot", 2));
    // The inertial spans point into the text as given, whatever was declared.
    let span = robot
        .link("upper")
        .unwrap()
        .inertial
        .as_ref()
        .unwrap()
        .span
        .clone();
    assert!(text[span].starts_with("<inertial>"));
}

#[test]
fn siblings_in_file_order_or_by_name() {
    // Two children of the base listed "zeta" then "alpha": file order keeps zeta first,
    // name order (urdfdom's, Pinocchio's) puts alpha first.
    let text = r#"<robot name="t"><link name="base"/>
      <link name="a"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="zeta" type="continuous"><parent link="base"/><child link="a"/></joint>
      <joint name="alpha" type="continuous"><parent link="base"/><child link="b"/></joint>
    </robot>"#;
    let robot = parse_urdf_str(text).unwrap();
    let names = |order| {
        let opts = UrdfOptions {
            sibling_order: order,
            ..UrdfOptions::default()
        };
        let (m, _) = build_model_with(&robot, &opts).unwrap();
        m.joints()
            .iter()
            .map(|j| j.name.clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(names(SiblingOrder::File), ["zeta", "alpha"]);
    assert_eq!(names(SiblingOrder::Name), ["alpha", "zeta"]);
}

#[test]
fn a_fixed_joint_named_like_its_child_link_is_ambiguous_by_name_only() {
    let text = GOOD.replace(
        "</robot>",
        r#"<link name="tool"/><joint name="tool" type="fixed"><parent link="lower"/><child link="tool"/></joint>
</robot>"#,
    );
    let model = load_urdf_str(&text, false).unwrap();
    let err = model.frame_id("tool").unwrap_err().to_string();
    assert!(err.contains("ambiguous") && err.contains("body") && err.contains("fixed joint"));
    assert!(model.frame_id_of_kind("tool", FrameKind::Body).is_some());
    assert!(model
        .frame_id_of_kind("tool", FrameKind::FixedJoint)
        .is_some());
}

/// A visual's colour as urdfdom (and so Pinocchio) reads it: a known material name wins over the
/// element's own `<color>`, and an element that first names a material defines it for the later
/// ones (TALOS's `DarkGrey`).
#[test]
fn material_colours_follow_urdfdoms_first_definition() {
    let robot = rigid::io::urdf::parse_urdf_str(
        r#"<robot name="r">
  <material name="Top"><color rgba="0.1 0.1 0.1 1"/></material>
  <link name="a">
    <visual><geometry><box size="1 1 1"/></geometry>
      <material name="Dark"><color rgba="0.2 0.2 0.2 1"/></material></visual>
    <visual><geometry><box size="1 1 1"/></geometry>
      <material name="Top"><color rgba="0.9 0.9 0.9 1"/></material></visual>
  </link>
  <link name="b">
    <visual><geometry><box size="1 1 1"/></geometry>
      <material name="Dark"><color rgba="0.5 0.5 0.5 1"/></material></visual>
    <visual><geometry><box size="1 1 1"/></geometry>
      <material><color rgba="0.3 0.4 0.5 1"/></material></visual>
  </link>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
</robot>"#,
    )
    .unwrap();
    let colour = |l: usize, k: usize| robot.links[l].visuals[k].rgba.unwrap()[0];
    assert_eq!(colour(0, 0), 0.2);
    assert_eq!(colour(0, 1), 0.1);
    assert_eq!(colour(1, 0), 0.2);
    assert_eq!(colour(1, 1), 0.3);
}
