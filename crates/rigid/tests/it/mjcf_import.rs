//! The MJCF importer's semantics without MuJoCo: the tree it builds, what it keeps, what it warns
//! about and what it refuses, each with its line.

use rigid::io::mjcf::{load_mjcf_str, MjcfEqualityKind, MjcfError, MjcfJointKind, MjcfShape};
use rigid::multibody::{crba, Data, JointType};
use std::path::Path;

fn load(text: &str) -> Result<rigid::io::mjcf::MjcfModel, MjcfError> {
    load_mjcf_str(text, Path::new("."))
}

#[test]
fn joints_of_one_body_become_a_chain_in_file_order_with_the_body_on_the_last() {
    let m = load(
        r#"<mujoco><worldbody><body name="b" pos="1 0 0">
             <joint name="x" axis="1 0 0" pos="0 0.1 0"/>
             <joint name="s" type="slide" axis="0 0 1"/>
             <joint name="y" axis="0 1 0" pos="0.2 0 0"/>
             <geom size="0.1" mass="2"/>
           </body></worldbody></mujoco>"#,
    )
    .unwrap();
    let names: Vec<&str> = m.model.joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["x", "s", "y"]);
    let masses: Vec<f64> = m.model.inertias().iter().map(|g| g.mass()).collect();
    assert_eq!(masses, [0.0, 0.0, 2.0]);
    // joint frames at the anchors: x at the body origin + (0, .1, 0), y at +(.2, 0, 0)
    let j = m.model.joints();
    assert!((j[0].placement.translation - rigid::spatial::Vec3::new(1.0, 0.1, 0.0)).norm() < 1e-15);
    assert!((j[2].placement.translation - rigid::spatial::Vec3::new(0.2, 0.0, 0.0)).norm() < 1e-15);
    assert!(matches!(j[1].kind, JointType::Prismatic { .. }));
    // the body frame sits at -(.2, 0, 0) in the last joint's frame; the sphere's centre with it
    assert_eq!(m.bodies[1].joint, Some(rigid::multibody::JointId(2)));
    let c = m.model.inertias()[2].com();
    assert!((c + rigid::spatial::Vec3::new(0.2, 0.0, 0.0)).norm() < 1e-15);
}

#[test]
fn bodies_without_joints_are_welded_and_the_world_ones_leave_the_dynamics() {
    let m = load(
        r#"<mujoco><worldbody>
             <body name="table" pos="0 0 1"><geom size="1" mass="50"/></body>
             <body name="arm"><joint/><geom size="0.1" mass="1"/>
               <body name="tool" pos="0 0 1"><geom size="0.1" mass="0.5"/></body>
             </body>
           </worldbody></mujoco>"#,
    )
    .unwrap();
    assert_eq!(m.model.njoints(), 1);
    assert!((m.model.total_mass() - 1.5).abs() < 1e-15);
    // every body is kept, with its mass; the table is fixed in the world
    let names: Vec<&str> = m.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["world", "table", "arm", "tool"]);
    assert_eq!((m.bodies[1].joint, m.bodies[1].mass), (None, 50.0));
    let tool = m.model.frames().iter().find(|f| f.name == "tool").unwrap();
    assert_eq!(tool.parent, Some(rigid::multibody::JointId(0)));
}

#[test]
fn classes_nest_and_childclass_reaches_into_frames() {
    let m = load(
        r#"<mujoco>
             <default>
               <joint axis="1 0 0" armature="0.1"/>
               <default class="a"><joint damping="2"/>
                 <default class="b"><joint axis="0 0 1"/><geom type="box" size="0.1 0.2 0.3"/></default>
               </default>
             </default>
             <worldbody><body childclass="a"><joint name="j1"/><geom size="0.1"/>
               <frame childclass="b"><body><joint name="j2"/><geom/></body></frame>
             </body></worldbody>
           </mujoco>"#,
    )
    .unwrap();
    let j = &m.joints;
    assert_eq!((j[0].armature, j[0].damping), (0.1, 2.0));
    assert_eq!((j[1].armature, j[1].damping), (0.1, 2.0));
    assert_eq!(
        m.model.joints()[1].kind,
        JointType::Revolute {
            axis: rigid::spatial::Vec3::z()
        }
    );
    assert_eq!(m.model.damping(), &[2.0, 2.0]);
    assert!(matches!(m.geoms[1].shape, MjcfShape::Box { .. }));
}

#[test]
fn hinge_ref_and_range_are_in_degrees_and_mujocos_coordinates() {
    let m = load(
        r#"<mujoco><worldbody><body><joint name="h" ref="30" range="-45 90"/>
             <geom size="0.1"/></body></worldbody></mujoco>"#,
    )
    .unwrap();
    let j = &m.joints[0];
    assert!((j.reference - 30f64.to_radians()).abs() < 1e-15);
    // rigid's limits are in rigid's coordinates, q = qpos - ref
    let lo = m.model.lower_limits()[0];
    assert!((lo - (-45f64 - 30.0).to_radians()).abs() < 1e-15, "{lo}");
    assert_eq!(m.qpos0, [j.reference]);
}

#[test]
fn gravity_follows_the_option_and_its_flag() {
    let g = load(r#"<mujoco><option gravity="0 0 -1.62"/><worldbody/></mujoco>"#).unwrap();
    assert_eq!(g.model.gravity().z, -1.62);
    let off =
        load(r#"<mujoco><option><flag gravity="disable"/></option><worldbody/></mujoco>"#).unwrap();
    assert_eq!(off.model.gravity().norm(), 0.0);
}

#[test]
fn sites_equalities_and_tendons_are_kept() {
    let m = load(
        r#"<mujoco><worldbody>
             <body name="a"><joint name="ja"/><geom size="0.1"/><site name="s1" pos="0 0 1"/></body>
             <body name="b"><joint name="jb"/><geom size="0.1"/></body>
           </worldbody>
           <equality><connect body1="a" body2="b" anchor="0 0 1"/><joint joint1="ja" joint2="jb"/></equality>
           <tendon><fixed name="t"><joint joint="ja" coef="1"/><joint joint="jb" coef="-1"/></fixed></tendon>
           </mujoco>"#,
    )
    .unwrap();
    assert_eq!(m.sites[0].name.as_deref(), Some("s1"));
    assert!(
        matches!(&m.equalities[0].kind, MjcfEqualityKind::Connect { targets, .. }
        if targets[0].as_deref() == Some("a"))
    );
    assert!(
        matches!(&m.equalities[1].kind, MjcfEqualityKind::Joint { polycoef, .. }
        if polycoef[1] == 1.0)
    );
    assert_eq!(m.tendons[0].name.as_deref(), Some("t"));
}

#[test]
fn what_rigid_does_not_model_is_a_warning_with_its_line() {
    let m = load(
        "<mujoco>\n<worldbody><body gravcomp=\"1\"><joint/><geom size=\"0.1\"/></body></worldbody>\n\
         <actuator><motor joint=\"j\"/></actuator>\n<sensor><jointpos joint=\"j\"/></sensor>\n</mujoco>",
    )
    .unwrap();
    let text: Vec<String> = m.warnings.iter().map(ToString::to_string).collect();
    assert!(
        text.iter().any(|w| w.starts_with("line 3: <actuator>")),
        "{text:?}"
    );
    assert!(
        text.iter().any(|w| w.starts_with("line 4: <sensor>")),
        "{text:?}"
    );
    assert!(text.iter().any(|w| w.contains("gravcomp")), "{text:?}");
}

#[test]
fn a_free_joint_is_the_world_pose_of_its_body() {
    let m = load(
        r#"<mujoco><worldbody><frame pos="1 0 0"><body pos="0 2 0" euler="0 0 90">
             <freejoint/><geom size="0.1"/></body></frame></worldbody></mujoco>"#,
    )
    .unwrap();
    assert_eq!(m.joints[0].kind, MjcfJointKind::Free);
    assert_eq!(
        m.model.joints()[0].placement,
        rigid::spatial::Transform::identity()
    );
    let q0 = &m.qpos0;
    assert!((q0[0] - 1.0).abs() < 1e-15 && (q0[1] - 2.0).abs() < 1e-15);
    assert!((q0[3] - 0.5f64.sqrt()).abs() < 1e-15 && (q0[6] - 0.5f64.sqrt()).abs() < 1e-15);
}

#[test]
fn errors_name_the_element_and_line() {
    let cases = [
        ("<mujoco><worldbody><body>", "malformed XML"),
        (
            "<mujoco>\n<worldbody>\n<body><joint/><geom class=\"x\" size=\"1\"/></body></worldbody></mujoco>",
            "line 3: <geom>: unknown default class \"x\"",
        ),
        (
            "<mujoco>\n<worldbody>\n<body><joint/><geom type=\"capsule\" fromto=\"0 0 0 0 0 0\" size=\"1\"/></body></worldbody></mujoco>",
            "line 3: <geom>: fromto has zero length",
        ),
        (
            "<mujoco><asset>\n<mesh name=\"m\" file=\"none.stl\"/></asset><worldbody/></mujoco>",
            "line 2: mesh \"m\": mesh file",
        ),
        (
            "<mujoco>\n<worldbody>\n<body><joint/><geom size=\"1\" mass=\"-1\"/></body></worldbody></mujoco>",
            "line 3: <geom>: a negative mass",
        ),
        (
            "<mujoco>\n<worldbody>\n<body><joint/><geom size=\"1\" pos=\"0 NaN 0\"/></body></worldbody></mujoco>",
            "line 3: <geom>: attribute \"pos\" is not finite",
        ),
        // meshes given in the XML
        (
            "<mujoco><asset>\n<mesh name=\"m\" vertex=\"0 0 0 1 0 0 0 1 0 0 0\"/></asset></mujoco>",
            "line 2: mesh \"m\": attribute \"vertex\" has 11 numbers: 3 per vertex, at least 4",
        ),
        (
            "<mujoco><asset>\n<mesh name=\"m\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\" face=\"0 1 4\"/></asset></mujoco>",
            "line 2: mesh \"m\": attribute \"face\": 3 vertex indices (0 to 3) per triangle",
        ),
        (
            "<mujoco><asset>\n<mesh name=\"m\" vertex=\"0 0 0 1 0 0 0 1 0 2 2 0\"/></asset></mujoco>",
            "line 2: mesh \"m\": the mesh volume is too small",
        ),
        (
            "<mujoco><asset>\n<mesh name=\"m\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1e39\"/></asset></mujoco>",
            "line 2: mesh \"m\": attribute \"vertex\": a number beyond float32's range",
        ),
        (
            "<mujoco><asset>\n<mesh file=\"a.stl\" vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/></asset></mujoco>",
            "line 2: <mesh>: a mesh has a file or vertices, not both",
        ),
        (
            "<mujoco><asset>\n<mesh vertex=\"0 0 0 1 0 0 0 1 0 0 0 1\"/></asset></mujoco>",
            "line 2: <mesh>: a mesh given by vertices needs a name",
        ),
    ];
    for (text, want) in cases {
        let e = load(text).unwrap_err().to_string();
        assert!(e.contains(want), "{e:?} lacks {want:?}");
    }
}

#[test]
fn deep_nesting_is_refused_without_overflowing_the_stack() {
    let n = 100_000;
    let text = format!(
        "<mujoco><worldbody>{}{}</worldbody></mujoco>",
        "<body>".repeat(n),
        "</body>".repeat(n)
    );
    let e = load(&text).unwrap_err().to_string();
    assert!(e.contains("nested"), "{e}");
}

#[test]
fn armature_is_on_the_diagonal_of_the_mass_matrix() {
    let m = load(
        r#"<mujoco><worldbody><body><joint armature="0.25"/><geom size="0.1" mass="1"/></body></worldbody></mujoco>"#,
    )
    .unwrap();
    let mut d = Data::new(&m.model);
    let mm = crba(&m.model, &mut d, &[0.0]).unwrap()[(0, 0)];
    assert!((mm - (0.4 * 0.01 + 0.25)).abs() < 1e-15, "{mm}");
}
