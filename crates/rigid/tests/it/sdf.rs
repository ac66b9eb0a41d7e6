//! SDF import: poses resolved through `relative_to`, frames, degrees and quaternions against the
//! same model built by hand; loops as constraints; floating, static and world-jointed roots; every
//! refusal naming its element and line. The cross-check against Drake's MultibodyPlant and the
//! Cassie files are in crates/rigid-py/tests/test_sdf.py.

use crate::common::state;
use rigid::io::sdf::{load_sdf_str, SdfError};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::constraints::ConstraintKind;
use rigid::multibody::{crba, nonlinear_effects, Data, JointType, Model, ModelBuilder, Rng};
use rigid::spatial::{so3, Transform, Vec3};
use std::f64::consts::FRAC_1_SQRT_2;

fn sdf(body: &str) -> String {
    format!(r#"<?xml version="1.0"?><sdf version="1.9"><model name="m">{body}</model></sdf>"#)
}

fn load(body: &str) -> rigid::io::sdf::SdfModel {
    load_sdf_str(&sdf(body), ".".as_ref()).unwrap()
}

fn error(body: &str) -> String {
    load_sdf_str(&sdf(body), ".".as_ref())
        .unwrap_err()
        .to_string()
}

fn gap(a: &Model, b: &Model) -> f64 {
    let (mut da, mut db) = (Data::new(a), Data::new(b));
    let mut rng = Rng::new(4);
    let mut worst: f64 = 0.0;
    for _ in 0..3 {
        let (q, v, _) = state(a, &mut rng);
        let (ma, mb) = (
            crba(a, &mut da, &q).unwrap().clone(),
            crba(b, &mut db, &q).unwrap().clone(),
        );
        let ca = nonlinear_effects(a, &mut da, &q, &v).unwrap().clone();
        let cb = nonlinear_effects(b, &mut db, &q, &v).unwrap().clone();
        worst = worst.max((ma - mb).amax()).max((ca - cb).amax());
    }
    worst
}

const LINK: &str = r#"<inertial><pose>0.1 0 -0.4 0 0 0</pose><mass>2</mass>
    <inertia><ixx>0.3</ixx><iyy>0.2</iyy><izz>0.1</izz><ixy>0.01</ixy><ixz>0</ixz><iyz>0.02</iyz></inertia></inertial>"#;

fn g() -> SpatialInertia {
    let i = RotationalInertia::new(0.3, 0.2, 0.1, 0.01, 0.0, 0.02);
    SpatialInertia::from_com(2.0, Vec3::new(0.1, 0.0, -0.4), i)
}

#[test]
fn poses_relative_to_frames_in_degrees_and_quaternions_give_the_hand_built_model() {
    // upper link at 1 m up, turned 90° about x (degrees); a frame on it; the elbow's pose
    // relative to that frame (a quaternion); its axis expressed in the model frame
    let m = load(&format!(
        r#"<link name="base"/>
        <joint name="weld" type="fixed"><parent>world</parent><child>base</child></joint>
        <link name="upper"><pose degrees="true">0 0 1 90 0 0</pose>{LINK}</link>
        <frame name="tip" attached_to="upper"><pose>0 0 -0.8 0 0 0</pose></frame>
        <joint name="shoulder" type="revolute"><parent>base</parent><child>upper</child>
          <axis><xyz>1 0 0</xyz></axis></joint>
        <link name="lower"><pose relative_to="tip" rotation_format="quat_xyzw">0 0.1 0 0 0 0.7071067811865476 0.7071067811865476</pose>{LINK}</link>
        <joint name="elbow" type="prismatic"><parent>upper</parent><child>lower</child>
          <pose>0 0 0.05 0 0 0</pose>
          <axis><xyz expressed_in="__model__">0 0 1</xyz>
            <limit><lower>-0.2</lower><upper>0.3</upper><effort>40</effort><velocity>2</velocity></limit>
            <dynamics><damping>0.5</damping><friction>0.25</friction></dynamics></axis></joint>"#
    ));
    let r_upper = so3::from_rpy(std::f64::consts::FRAC_PI_2, 0.0, 0.0);
    let upper = Transform::new(r_upper, Vec3::new(0.0, 0.0, 1.0));
    let tip = upper * Transform::from_translation(Vec3::new(0.0, 0.0, -0.8));
    let r_lower = so3::from_quaternion(0.0, 0.0, FRAC_1_SQRT_2, FRAC_1_SQRT_2, 1e-9).unwrap();
    let lower = tip * Transform::new(r_lower, Vec3::new(0.0, 0.1, 0.0));
    let elbow = lower * Transform::from_translation(Vec3::new(0.0, 0.0, 0.05));
    let mut b = ModelBuilder::new("m");
    let s = b
        .add_joint(
            None,
            "shoulder",
            JointType::Revolute { axis: Vec3::x() },
            upper,
            g(),
        )
        .unwrap();
    b.set_continuous(s).unwrap();
    let axis = elbow.rotation.transpose() * Vec3::z();
    let e = b
        .add_joint(
            Some(s),
            "elbow",
            JointType::Prismatic { axis },
            upper.inverse() * elbow,
            g().transformed(&(elbow.inverse() * lower)),
        )
        .unwrap();
    b.set_limits(e, &[-0.2], &[0.3], &[2.0], &[40.0]).unwrap();
    let want = b.build().unwrap();
    assert!(gap(&m.model, &want) < 1e-12, "{:e}", gap(&m.model, &want));
    let got = &m.model;
    assert_eq!(got.lower_limits(), &[f64::NEG_INFINITY, -0.2]);
    assert_eq!(
        (got.damping(), got.friction()),
        (&[0.0, 0.5][..], &[0.0, 0.25][..])
    );
    assert!(got.joints()[0].continuous);
    assert!(got.frame_id("lower").is_ok() && got.frame_id("base").is_ok());
    assert!(m.constraints.is_empty() && m.warnings.is_empty());
}

/// `revolute2`: a rotation about `<axis>`, then one about `<axis2>` turned by the first (here 53°
/// apart, not perpendicular), is two revolute joints in series through a massless frame.
#[test]
fn a_revolute2_joint_is_two_rotations_in_series() {
    let m = load(&format!(
        r#"<link name="arm"><pose>0.2 0 1 0.3 0 0</pose>{LINK}</link>
        <joint name="hip" type="revolute2"><parent>world</parent><child>arm</child>
          <axis><xyz>1 0 0</xyz></axis>
          <axis2><xyz>0.6 0.8 0</xyz><limit><lower>-0.5</lower><upper>0.7</upper></limit></axis2>
        </joint>"#
    ));
    let at = Transform::new(so3::from_rpy(0.3, 0.0, 0.0), Vec3::new(0.2, 0.0, 1.0));
    let mut b = ModelBuilder::new("m");
    let first = b
        .add_joint(
            None,
            "first",
            JointType::Revolute { axis: Vec3::x() },
            at,
            SpatialInertia::zero(),
        )
        .unwrap();
    b.add_joint(
        Some(first),
        "second",
        JointType::Revolute {
            axis: Vec3::new(0.6, 0.8, 0.0),
        },
        Transform::identity(),
        g(),
    )
    .unwrap();
    let want = b.build().unwrap();
    let got = &m.model;
    assert_eq!((got.nq(), got.nv()), (2, 2));
    assert!(matches!(got.joints()[0].kind, JointType::Universal { .. }));
    let g = gap(got, &want);
    assert!(g < 1e-12, "{g:e}");
    assert_eq!(got.lower_limits(), &[f64::NEG_INFINITY, -0.5]);
    assert_eq!(got.upper_limits(), &[f64::INFINITY, 0.7]);
}

#[test]
fn a_root_no_joint_holds_floats_where_the_file_puts_it_unless_the_model_is_static() {
    let body = format!(
        r#"<pose>1 2 3 0 0 0</pose><link name="torso"><pose>0 0 0.5 0 0 0</pose>{LINK}</link>"#
    );
    let m = load(&body);
    assert_eq!(m.model.joints()[0].kind, JointType::FreeFlyer);
    assert_eq!(m.model.joints()[0].name, "root_joint");
    assert_eq!(&m.home[..7], &[1.0, 2.0, 3.5, 0.0, 0.0, 0.0, 1.0]);
    let fixed = load(&format!("<static>true</static>{body}"));
    assert_eq!(fixed.model.nv(), 0);
}

#[test]
fn loops_become_constraints_at_the_closing_joint() {
    // a four-bar: crank and rocker on the ground, a coupler closed by a ball joint, a revolute
    // joint, a fixed joint and a prismatic joint (which cannot be closed: a warning)
    let link =
        |name: &str, pose: &str| format!(r#"<link name="{name}"><pose>{pose}</pose>{LINK}</link>"#);
    let joint = |name: &str, kind: &str, p: &str, c: &str| {
        format!(
            r#"<joint name="{name}" type="{kind}"><parent>{p}</parent><child>{c}</child><axis><xyz>0 1 0</xyz></axis></joint>"#
        )
    };
    let body = [
        link("crank", "0 0 0 0 0 0"),
        link("rocker", "1 0 0 0 0 0"),
        link("coupler", "0 0 -1 0 0 0"),
        joint("a", "revolute", "world", "crank"),
        joint("b", "revolute", "world", "rocker"),
        joint("c", "revolute", "crank", "coupler"),
        joint("ball", "ball", "rocker", "coupler"),
        joint("hinge", "revolute", "rocker", "coupler"),
        joint("weld", "fixed", "rocker", "coupler"),
        joint("slide", "prismatic", "rocker", "coupler"),
    ]
    .concat();
    let m = load(&body);
    assert_eq!(m.model.nv(), 3);
    let names: Vec<(&str, ConstraintKind)> = m
        .constraints
        .iter()
        .map(|c| (c.name.as_str(), c.kind))
        .collect();
    assert_eq!(
        names,
        [
            ("ball", ConstraintKind::Point),
            ("hinge", ConstraintKind::Point),
            ("hinge", ConstraintKind::Point),
            ("weld", ConstraintKind::Frame),
        ]
    );
    // each closure's two anchors coincide at the file's configuration
    let mut data = Data::new(&m.model);
    let q = vec![0.0; m.model.nq()];
    rigid::multibody::forward_kinematics_q(&m.model, &mut data, &q).unwrap();
    for c in &m.constraints {
        let at = |j: Option<rigid::multibody::JointId>, x: &Transform| {
            j.map_or(Transform::identity(), |j| data.placements[j.0]) * *x
        };
        let (w1, w2) = (at(c.joint1, &c.placement1), at(c.joint2, &c.placement2));
        assert!(
            (w1.translation - w2.translation).norm() < 1e-15,
            "{}",
            c.name
        );
    }
    let hinge: Vec<_> = m.constraints.iter().filter(|c| c.name == "hinge").collect();
    let span = hinge[1].placement2.translation - hinge[0].placement2.translation;
    assert!((span - Vec3::new(0.0, 0.1, 0.0)).norm() < 1e-15);
    assert_eq!(m.warnings.len(), 1);
    assert!(m.warnings[0]
        .to_string()
        .contains("joint \"slide\": closes a loop"));
}

#[test]
fn bad_files_are_refused_naming_the_element_and_line() {
    let cases = [
        (
            r#"<link name="a"/>
<joint name="j" type="revolute"><parent>nowhere</parent><child>a</child></joint>"#,
            "line 2: joint \"j\": its parent \"nowhere\" is not a link of the model",
        ),
        (
            r#"<link name="a"><pose relative_to="ghost">0 0 0 0 0 0</pose></link>"#,
            "line 1: \"a\": its pose is relative to \"ghost\", which is not defined",
        ),
        (
            r#"<link name="a"><pose relative_to="b">0 0 0 0 0 0</pose></link>
<link name="b"><pose relative_to="a">0 0 0 0 0 0</pose></link>"#,
            "its pose is relative to itself through",
        ),
        (
            r#"<link name="a"/><joint name="j" type="hinge"><parent>world</parent><child>a</child></joint>"#,
            "joint \"j\": joint type \"hinge\" is not supported",
        ),
        (
            r#"<link name="a"><pose>0 0 x 0 0 0</pose></link>"#,
            "link \"a\" <pose>: \"0 0 x 0 0 0\" is not numbers",
        ),
        (
            r#"<link name="a"><pose>0 0 0 0 0</pose></link>"#,
            "expected 6 numbers, got 5",
        ),
        (
            r#"<link name="a"><inertial><mass>-1</mass></inertial></link>"#,
            "link \"a\": negative mass -1",
        ),
        (
            r#"<include><uri>model://no_such_model</uri></include>"#,
            "line 1: <include>: \"model://no_such_model\" not found",
        ),
        (
            r#"<link name="a"/><joint name="j" type="screw"><parent>world</parent><child>a</child><axis><xyz>0 0 1</xyz></axis></joint>"#,
            "a screw joint needs <screw_thread_pitch>",
        ),
        (
            r#"<link name="a"/><joint name="j" type="revolute"><parent>world</parent><child>a</child><axis><xyz>0 0 0</xyz></axis></joint>"#,
            "the axis is zero",
        ),
        (
            r#"<link name="a"><collision name="c"><geometry><cylinder><radius>0.1</radius></cylinder></geometry></collision></link>"#,
            "length must be positive and finite",
        ),
    ];
    for (body, want) in cases {
        let e = error(body);
        assert!(e.contains(want), "{e}\n  wanted: {want}");
    }
    assert!(matches!(
        load_sdf_str("<robot/>", ".".as_ref()),
        Err(SdfError::Invalid { .. })
    ));
    assert!(matches!(
        load_sdf_str("<sdf><model", ".".as_ref()),
        Err(SdfError::Xml(_))
    ));
}

#[test]
fn the_worlds_gravity_is_the_models() {
    let text = format!(
        r#"<sdf version="1.6"><world name="moon"><gravity>0 0 -1.62</gravity>
        <model name="m"><link name="torso">{LINK}</link></model></world></sdf>"#
    );
    let m = load_sdf_str(&text, ".".as_ref()).unwrap();
    assert_eq!(m.model.gravity(), Vec3::new(0.0, 0.0, -1.62));
    assert_eq!(
        load(&format!(r#"<link name="t">{LINK}</link>"#))
            .model
            .gravity()
            .z,
        -9.81
    );
}

#[test]
fn a_nested_model_is_its_links_and_joints_in_its_scope_placed_by_its_pose() {
    // the same arm written flat and with its forearm as a nested model (its pose, its own
    // __model__, a joint inside it, and the parent joining `fore::upper`)
    let flat = load(&format!(
        r#"<link name="base"/>
        <joint name="weld" type="fixed"><parent>world</parent><child>base</child></joint>
        <link name="upper"><pose>0.5 0 1 0 0.3 0</pose>{LINK}</link>
        <joint name="shoulder" type="revolute"><parent>base</parent><child>upper</child>
          <axis><xyz>0 1 0</xyz></axis></joint>
        <link name="lower"><pose>0.5 0.2 0.4 0.1 0.3 0</pose>{LINK}</link>
        <joint name="elbow" type="revolute"><parent>upper</parent><child>lower</child>
          <axis><xyz expressed_in="__model__">1 0 0</xyz></axis></joint>"#
    ));
    let nested = load(&format!(
        r#"<link name="base"/>
        <joint name="weld" type="fixed"><parent>world</parent><child>base</child></joint>
        <model name="fore"><pose>0.5 0 1 0 0 0</pose>
          <link name="upper"><pose>0 0 0 0 0.3 0</pose>{LINK}</link>
          <link name="lower"><pose relative_to="__model__">0 0.2 -0.6 0.1 0.3 0</pose>{LINK}</link>
          <joint name="elbow" type="revolute"><parent>upper</parent><child>lower</child>
            <axis><xyz expressed_in="__model__">1 0 0</xyz></axis></joint>
        </model>
        <joint name="shoulder" type="revolute"><parent>base</parent><child>fore::upper</child>
          <axis><xyz>0 1 0</xyz></axis></joint>"#
    ));
    let names: Vec<&str> = nested
        .model
        .joints()
        .iter()
        .map(|j| j.name.as_str())
        .collect();
    assert_eq!(names, ["shoulder", "fore::elbow"]);
    assert!(nested.model.frame_id("fore::lower").is_ok());
    let g = gap(&flat.model, &nested.model);
    assert!(g < 1e-12, "{g:e}");
}

/// `<include>`: the forearm of the nested-model test in its own folder (`model.config` naming
/// the file of the highest version), found by `model://`, renamed and placed by the include; a
/// model that includes itself; a missing `<uri>`.
#[test]
fn an_included_model_is_a_nested_model_named_and_placed_by_the_include() {
    let root = std::env::temp_dir().join(format!("rigid-sdf-include-{}", std::process::id()));
    let (robot, fore, looped) = (root.join("robot"), root.join("fore"), root.join("looped"));
    for d in [&robot, &fore, &looped] {
        std::fs::create_dir_all(d).unwrap();
    }
    std::fs::write(
        fore.join("model.config"),
        r#"<?xml version="1.0"?><model><name>fore</name>
        <sdf version="1.6">missing.sdf</sdf><sdf version="1.10">forearm.sdf</sdf></model>"#,
    )
    .unwrap();
    // its own name and pose, which the include replaces
    std::fs::write(
        fore.join("forearm.sdf"),
        format!(
            r#"<?xml version="1.0"?><sdf version="1.10"><model name="forearm">
            <pose>9 9 9 0 0 0</pose>
            <link name="upper"><pose>0 0 0 0 0.3 0</pose>{LINK}</link>
            <link name="lower"><pose relative_to="__model__">0 0.2 -0.6 0.1 0.3 0</pose>{LINK}</link>
            <joint name="elbow" type="revolute"><parent>upper</parent><child>lower</child>
              <axis><xyz expressed_in="__model__">1 0 0</xyz></axis></joint>
            </model></sdf>"#
        ),
    )
    .unwrap();
    let main = robot.join("model.sdf");
    std::fs::write(
        &main,
        sdf(r#"<link name="base"/>
        <joint name="weld" type="fixed"><parent>world</parent><child>base</child></joint>
        <include><uri>model://fore</uri><name>fore</name><pose>0.5 0 1 0 0 0</pose></include>
        <joint name="shoulder" type="revolute"><parent>base</parent><child>fore::upper</child>
          <axis><xyz>0 1 0</xyz></axis></joint>"#),
    )
    .unwrap();
    let flat = load(&format!(
        r#"<link name="base"/>
        <joint name="weld" type="fixed"><parent>world</parent><child>base</child></joint>
        <link name="upper"><pose>0.5 0 1 0 0.3 0</pose>{LINK}</link>
        <joint name="shoulder" type="revolute"><parent>base</parent><child>upper</child>
          <axis><xyz>0 1 0</xyz></axis></joint>
        <link name="lower"><pose>0.5 0.2 0.4 0.1 0.3 0</pose>{LINK}</link>
        <joint name="elbow" type="revolute"><parent>upper</parent><child>lower</child>
          <axis><xyz expressed_in="__model__">1 0 0</xyz></axis></joint>"#
    ));
    let got = rigid::io::sdf::load_sdf(&main).unwrap();
    let names: Vec<&str> = got.model.joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["shoulder", "fore::elbow"]);
    assert!(got.model.frame_id("fore::lower").is_ok());
    let g = gap(&flat.model, &got.model);
    assert!(g < 1e-12, "{g:e}");
    // a model that includes itself, and an include without a uri
    std::fs::write(
        looped.join("model.sdf"),
        sdf(r#"<link name="a"/><include><uri>model://looped</uri></include>"#),
    )
    .unwrap();
    let e = rigid::io::sdf::load_sdf(looped.join("model.sdf"))
        .unwrap_err()
        .to_string();
    let file = looped.join("model.sdf").canonicalize().unwrap();
    let file = file.display();
    assert!(
        e.ends_with(&format!(
            "line 1: <include>: include loop: {file} -> {file}"
        )),
        "{e}"
    );
    let e = error(r#"<include><name>x</name></include>"#);
    assert!(e.contains("line 1: <include>: no <uri>"), "{e}");
    // an error the build finds in an included file names that file (its line is the file's)
    std::fs::write(
        fore.join("forearm.sdf"),
        r#"<?xml version="1.0"?><sdf version="1.10"><model name="forearm">
            <link name="upper"><inertial><mass>-2</mass></inertial></link></model></sdf>"#,
    )
    .unwrap();
    let e = rigid::io::sdf::load_sdf(&main).unwrap_err().to_string();
    let file = fore.join("forearm.sdf").canonicalize().unwrap();
    assert!(
        e.contains(&format!("link \"fore::upper\" in {}", file.display()))
            && e.contains("negative mass"),
        "{e}"
    );
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn bodies_below_a_floating_root_are_where_the_file_puts_them_at_home() {
    let m = load(&format!(
        r#"<pose>0 0 0.5 0 0 0.3</pose>
        <link name="torso">{LINK}</link>
        <link name="leg"><pose>0.1 0 -0.3 0.2 0 0</pose>{LINK}</link>
        <joint name="hip" type="revolute"><parent>torso</parent><child>leg</child>
          <axis><xyz>0 1 0</xyz></axis></joint>
        <link name="foot"><pose>0.1 0 -0.6 0 0 0</pose>{LINK}</link>
        <joint name="ankle" type="ball"><parent>leg</parent><child>foot</child></joint>"#
    ));
    let mut data = Data::new(&m.model);
    rigid::multibody::forward_kinematics_q(&m.model, &mut data, &m.home).unwrap();
    let model_pose = Transform::new(so3::from_rpy(0.0, 0.0, 0.3), Vec3::new(0.0, 0.0, 0.5));
    for (name, pose) in [
        (
            "leg",
            Transform::new(so3::from_rpy(0.2, 0.0, 0.0), Vec3::new(0.1, 0.0, -0.3)),
        ),
        (
            "foot",
            Transform::from_translation(Vec3::new(0.1, 0.0, -0.6)),
        ),
    ] {
        let f = &m.model.frames()[m.model.frame_id(name).unwrap().0];
        let at = data.placements[f.parent.unwrap().0] * f.placement;
        let want = model_pose * pose;
        assert!((at.translation - want.translation).norm() < 1e-15, "{name}");
        assert!((at.rotation - want.rotation).amax() < 1e-15, "{name}");
        // the link is its joint's own frame, exactly
        assert!(f.placement.is_identity(0.0), "{name}");
    }
}

#[test]
fn a_gearbox_is_a_coupling_of_the_two_joints_that_turn_its_links() {
    // θ_out = −0.25 θ_rotor about +x; the output joint turns about −x, so q_out = +0.25 q_rotor
    let link = |name: &str| format!(r#"<link name="{name}"><pose>0 0 0 0 0 0</pose>{LINK}</link>"#);
    let joint = |name: &str, child: &str, axis: &str| {
        format!(
            r#"<joint name="{name}" type="revolute"><parent>world</parent><child>{child}</child><axis><xyz>{axis}</xyz></axis></joint>"#
        )
    };
    let gearbox = |reference: &str| {
        format!(
            r#"<joint name="gear" type="gearbox"><parent>rotor</parent><child>out</child>
            <gearbox_reference_body>{reference}</gearbox_reference_body><gearbox_ratio>0.25</gearbox_ratio>
            <axis><xyz>1 0 0</xyz></axis><axis2><xyz>1 0 0</xyz></axis2></joint>"#
        )
    };
    let body = [
        link("rotor"),
        link("out"),
        joint("ip", "rotor", "1 0 0"),
        joint("op", "out", "-1 0 0"),
    ]
    .concat();
    let m = load(&(body.clone() + &gearbox("world")));
    assert!(m.warnings.is_empty(), "{:?}", m.warnings);
    let [c] = &m.constraints[..] else {
        panic!("{:?}", m.constraints)
    };
    assert_eq!(
        (c.name.as_str(), c.joint1, c.joint2),
        ("gear", m.model.joint_id("op"), m.model.joint_id("ip"))
    );
    let ConstraintKind::JointCoordinate { polycoef } = c.kind else {
        panic!("{:?}", c.kind)
    };
    assert_eq!(polycoef, [0.0, 0.25, 0.0, 0.0, 0.0]);
    // as a mimic: one degree of freedom, the rotor's
    let mm = rigid::multibody::MimicModel::new(
        m.model.clone(),
        &[rigid::multibody::Mimic::from_constraint(c).unwrap()],
    )
    .unwrap();
    assert_eq!(mm.nv(), 1);
    // a reference body the links are not turned from: left out, saying why
    let m = load(&(body + &link("base") + &gearbox("base")));
    assert!(m.constraints.is_empty());
    let w = m.warnings[0].to_string();
    assert!(
        w.contains("joint \"gear\"")
            && w.contains("\"rotor\" is not turned by a revolute joint from \"base\""),
        "{w}"
    );
}
