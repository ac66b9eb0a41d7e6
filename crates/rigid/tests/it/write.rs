//! The writers (`rigid convert`): a model written as MJCF or URDF and read back by rigid's own
//! importers has the same joints, limits, armature, damping and friction, and the same M and
//! bias at random states (to 1e-12: placements pass through a quaternion or roll-pitch-yaw).
//! The cross-checks against MuJoCo and Pinocchio are in crates/rigid-py/tests/test_convert.py.

use crate::common::{inertia, state, transform, unit};
use rigid::collision::{Geometry, Shape};
use rigid::io::mjcf::load_mjcf_str;
use rigid::io::urdf::load_urdf_str;
use rigid::io::write::{mjcf::write_mjcf, urdf::write_urdf, WriteError};
use rigid::multibody::{
    crba, nonlinear_effects as nle, Data, JointId, JointType, Model, ModelBuilder, Rng,
};
use rigid::spatial::{Transform, Vec3};

/// A free-flyer at the world's origin and `n` joints of the `kinds` asked (by index: revolute,
/// prismatic, spherical, universal, continuous, planar), with limits on the scalar joints,
/// armature, damping, friction, a welded body and an operational frame.
fn tree(seed: u64, n: usize, kinds: &[usize]) -> Model {
    let mut rng = Rng::new(seed);
    let mut b = ModelBuilder::new("written");
    b.set_gravity(Vec3::new(0.3, -0.2, -9.81));
    let root = b
        .add_joint(
            None,
            "root",
            JointType::FreeFlyer,
            Transform::identity(),
            inertia(&mut rng),
        )
        .unwrap();
    let mut stack = vec![root];
    for k in 0..n {
        stack.truncate((1 + (rng.next_u64() as usize) % stack.len()).max(1));
        let pick = kinds[k % kinds.len()];
        let kind = match pick {
            0 | 4 => JointType::Revolute {
                axis: unit(&mut rng),
            },
            1 => JointType::Prismatic {
                axis: unit(&mut rng),
            },
            2 => JointType::Spherical,
            3 => JointType::Universal {
                axis1: unit(&mut rng),
                axis2: unit(&mut rng),
            },
            _ => JointType::Planar,
        };
        let parent = Some(*stack.last().unwrap());
        let name = format!("j{k}");
        let id = b
            .add_joint(parent, &name, kind, transform(&mut rng), inertia(&mut rng))
            .unwrap();
        let nv = kind.nv();
        if kind.nq() == 1 && pick != 4 {
            let lo = rng.uniform(-2.0, -0.5);
            b.set_limits(id, &[lo], &[lo + 2.0], &[rng.uniform(1.0, 9.0)], &[3.0])
                .unwrap();
        }
        if pick == 4 {
            b.set_continuous(id).unwrap();
        }
        if kind.nq() == 1 || pick == 3 {
            let arm: Vec<f64> = (0..nv).map(|_| rng.uniform(0.0, 0.2)).collect();
            b.set_armature(id, &arm).unwrap();
        }
        b.set_joint_dynamics(id, &vec![0.25; nv], &vec![0.5; nv])
            .unwrap();
        if k == n / 2 {
            b.add_fixed_body(parent, "welded", transform(&mut rng), inertia(&mut rng))
                .unwrap();
            b.add_frame(Some(id), "tool", transform(&mut rng)).unwrap();
        }
        stack.push(id);
    }
    b.build().unwrap()
}

/// max over random states of the relative differences of M and the bias.
fn dynamics_gap(a: &Model, b: &Model) -> f64 {
    assert_eq!((a.nq(), a.nv()), (b.nq(), b.nv()));
    let (mut da, mut db) = (Data::new(a), Data::new(b));
    let mut rng = Rng::new(3);
    let mut worst: f64 = 0.0;
    for _ in 0..4 {
        let (q, v, _) = state(a, &mut rng);
        let ma = crba(a, &mut da, &q).unwrap().clone();
        let mb = crba(b, &mut db, &q).unwrap().clone();
        let ca = nle(a, &mut da, &q, &v).unwrap().clone();
        let cb = nle(b, &mut db, &q, &v).unwrap().clone();
        worst = worst.max((ma - &mb).amax() / mb.amax().max(1.0));
        worst = worst.max((ca - &cb).amax() / cb.amax().max(1.0));
    }
    worst
}

#[test]
fn mjcf_written_and_read_back_has_the_same_dynamics_and_joint_data() {
    for seed in 0..4 {
        let model = tree(seed, 9, &[0, 1, 2, 3]);
        let written = write_mjcf(&model, &[], &[]).unwrap();
        let mjcf = load_mjcf_str(&written.text, ".".as_ref()).unwrap();
        let back = mjcf.model;
        let gap = dynamics_gap(&model, &back);
        assert!(gap < 1e-12, "seed {seed}: M or bias differ by {gap:e}");
        for (got, want) in [
            (back.armature(), model.armature()),
            (back.damping(), model.damping()),
            (back.friction(), model.friction()),
            (back.lower_limits(), model.lower_limits()),
            (back.upper_limits(), model.upper_limits()),
        ] {
            assert_eq!(got, want, "seed {seed}");
        }
        // MuJoCo has no velocity limit: said, and dropped
        assert!(written.notes.iter().any(|n| n.contains("velocity limits")));
        assert!(back.velocity_limits().iter().all(|x| x.is_infinite()));
        // a universal joint is two hinges named after it
        let universal = model
            .joints()
            .iter()
            .find(|j| matches!(j.kind, JointType::Universal { .. }))
            .unwrap();
        assert!(back.joint_id(&format!("{}_2", universal.name)).is_some());
        // a welded body is a body; an operational frame a site
        assert!(back.frame_id("welded").is_ok());
        assert!(mjcf.sites.iter().any(|s| s.name.as_deref() == Some("tool")));
    }
}

#[test]
fn urdf_written_and_read_back_has_the_same_dynamics_and_joint_data() {
    for seed in 0..4 {
        let model = tree(seed, 9, &[0, 1, 4, 5]);
        let written = write_urdf(&model, &[], &[], "meshes").unwrap();
        // the free-flyer at the origin is left out, as floating robots' URDFs do
        assert!(written.notes.iter().any(|n| n.contains("--floating")));
        // URDF holds no gravity: said; the reader's is the standard one
        assert!(written.notes.iter().any(|n| n.contains("gravity")));
        let back = load_urdf_str(&written.text, true)
            .unwrap()
            .with_gravity(model.gravity());
        // ... and no armature: compared without it
        let mut bare = model.clone();
        bare.set_armature(&vec![0.0; model.nv()]).unwrap();
        let gap = dynamics_gap(&bare, &back);
        assert!(gap < 1e-12, "seed {seed}: M or bias differ by {gap:e}");
        for (got, want) in [
            (back.damping(), model.damping()),
            (back.friction(), model.friction()),
            (back.lower_limits(), model.lower_limits()),
            (back.upper_limits(), model.upper_limits()),
        ] {
            assert_eq!(got, want, "seed {seed}");
        }
        // URDF has no armature: said, and dropped
        assert!(written.notes.iter().any(|n| n.contains("armature")));
        let scalar = |m: &Model| -> Vec<f64> {
            m.joints()
                .iter()
                .filter(|j| j.nv == 1 && !j.continuous)
                .map(|j| m.effort_limits()[j.idx_v])
                .collect()
        };
        assert_eq!(scalar(&back), scalar(&model));
        for j in model.joints().iter().skip(1) {
            let k = back.joint_id(&j.name).unwrap();
            assert_eq!(back.joint(k).continuous, j.continuous, "{}", j.name);
        }
        assert!(back.frame_id("welded").is_ok() && back.frame_id("tool").is_ok());
    }
}

#[test]
fn geometry_is_written_as_each_format_can_hold_it() {
    let model = tree(7, 3, &[0]);
    let body = Some(JointId(1));
    let at = Transform::from_translation(Vec3::new(0.1, 0.0, 0.0));
    let hull: Vec<Vec3> = (0..8)
        .map(|k| Vec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, (k >> 2) as f64))
        .chain([Vec3::repeat(0.5)]) // inside: not a hull vertex
        .collect();
    let geometries = vec![
        Geometry::new("ball", body, at, Shape::Sphere { radius: 0.1 }),
        Geometry::new(
            "brick",
            body,
            at,
            Shape::Box {
                size: Vec3::new(0.1, 0.2, 0.3),
            },
        ),
        Geometry::new(
            "pill",
            body,
            at,
            Shape::Capsule {
                radius: 0.05,
                length: 0.2,
            },
        ),
        Geometry::new("cube", body, at, Shape::ConvexHull { points: hull }),
    ];
    let mjcf = write_mjcf(&model, &geometries, &[]).unwrap();
    assert!(mjcf.text.contains(r#"type="box" size="0.05 0.1 0.15""#));
    assert!(mjcf.text.contains(r#"type="capsule" size="0.05 0.1""#));
    let back = load_mjcf_str(&mjcf.text, ".".as_ref()).unwrap();
    assert_eq!(back.geoms.len(), 4);
    // the inline mesh holds the hull's 8 vertices, not the inner point
    let mesh = mjcf.text.lines().find(|l| l.contains("<mesh")).unwrap();
    let numbers = mesh.split('"').nth(3).unwrap().split(' ').count();
    assert_eq!(numbers, 24, "{mesh}");

    let urdf = write_urdf(&model, &geometries, &[], "m").unwrap();
    assert!(urdf.text.contains(r#"<box size="0.1 0.2 0.3"/>"#));
    assert!(urdf.text.contains(r#"<sphere radius="0.1"/>"#));
    // the capsule and the hull as OBJ files; the capsule noted
    let files: Vec<&str> = urdf.files.iter().map(|f| f.0.as_str()).collect();
    assert_eq!(files, ["m/pill.obj", "m/cube.obj"]);
    assert!(urdf.notes.iter().any(|n| n.contains("\"pill\"")));
    let cube = &urdf.files[1].1;
    assert_eq!(cube.lines().filter(|l| l.starts_with("v ")).count(), 8);
    assert_eq!(cube.lines().filter(|l| l.starts_with("f ")).count(), 12);
}

#[test]
fn what_a_format_cannot_express_is_an_error_naming_the_joint() {
    let planar = tree(1, 2, &[5]);
    let e = write_mjcf(&planar, &[], &[]).unwrap_err();
    assert_eq!(e.to_string(), "joint \"j0\": MJCF has no planar joint");
    let ball = tree(1, 2, &[2]);
    let e = write_urdf(&ball, &[], &[], "m").unwrap_err();
    assert!(matches!(&e, WriteError::Joint { joint, kind: "spherical", .. } if joint == "j0"));
    assert_eq!(
        e.to_string(),
        "joint \"j0\": URDF has no spherical joint: MJCF has one (rigid convert to .xml)"
    );
    // a free-flyer below the root: MuJoCo's free joint moves top-level bodies only
    let mut b = ModelBuilder::new("nested");
    let g = rigid::mass::SpatialInertia::from_com(
        1.0,
        Vec3::zeros(),
        rigid::mass::RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    let r = b
        .add_joint(
            None,
            "hinge",
            JointType::Revolute { axis: Vec3::z() },
            Transform::identity(),
            g,
        )
        .unwrap();
    b.add_joint(
        Some(r),
        "free",
        JointType::FreeFlyer,
        Transform::identity(),
        g,
    )
    .unwrap();
    let e = write_mjcf(&b.build().unwrap(), &[], &[]).unwrap_err();
    assert!(e.to_string().contains("top-level body"), "{e}");
}

#[test]
fn a_massless_moving_body_goes_into_its_child_for_mujoco() {
    // MuJoCo refuses massless moving bodies: a hip of three hinges on two massless links is one
    // body with three joints (each at its place in it), as MuJoCo's own files write hips
    let mut rng = Rng::new(5);
    let mut b = ModelBuilder::new("hip");
    let zero = rigid::mass::SpatialInertia::zero();
    let x = b
        .add_joint(
            None,
            "hip_x",
            JointType::Revolute { axis: Vec3::x() },
            transform(&mut rng),
            zero,
        )
        .unwrap();
    let z = b
        .add_joint(
            Some(x),
            "hip_z",
            JointType::Revolute {
                axis: unit(&mut rng),
            },
            transform(&mut rng),
            zero,
        )
        .unwrap();
    b.add_joint(
        Some(z),
        "hip_y",
        JointType::Prismatic { axis: Vec3::y() },
        transform(&mut rng),
        inertia(&mut rng),
    )
    .unwrap();
    let model = b.build().unwrap();
    let written = write_mjcf(&model, &[], &[]).unwrap();
    assert_eq!(
        written.text.matches("<body ").count(),
        1,
        "{}",
        written.text
    );
    assert_eq!(written.text.matches("<joint ").count(), 3);
    assert_eq!(
        written
            .notes
            .iter()
            .filter(|n| n.contains("massless body"))
            .count(),
        2
    );
    let back = load_mjcf_str(&written.text, ".".as_ref()).unwrap().model;
    let gap = dynamics_gap(&model, &back);
    assert!(gap < 1e-12, "M or bias differ by {gap:e}");
}

#[test]
fn what_mujoco_or_urdf_would_refuse_is_said_and_names_stay_unique() {
    let mut rng = Rng::new(9);
    let mut b = ModelBuilder::new("edge");
    let j = b
        .add_joint(
            None,
            "j",
            JointType::Revolute { axis: Vec3::z() },
            transform(&mut rng),
            inertia(&mut rng),
        )
        .unwrap();
    b.set_limits(
        j,
        &[-1.0],
        &[f64::INFINITY],
        &[f64::INFINITY],
        &[f64::INFINITY],
    )
    .unwrap();
    // a body and a tool frame of one name (two namespaces in rigid, one in URDF)
    b.add_frame_of_kind(
        Some(j),
        "hand",
        Transform::identity(),
        rigid::multibody::FrameKind::Body,
    )
    .unwrap();
    b.add_frame(Some(j), "hand", transform(&mut rng)).unwrap();
    // a massless moving leaf
    b.add_joint(
        Some(j),
        "k",
        JointType::Prismatic { axis: Vec3::x() },
        transform(&mut rng),
        rigid::mass::SpatialInertia::zero(),
    )
    .unwrap();
    let model = b.build().unwrap();
    let flat = Geometry::new(
        "flat",
        Some(JointId(0)),
        Transform::identity(),
        Shape::ConvexHull {
            points: vec![
                Vec3::zeros(),
                Vec3::x(),
                Vec3::y(),
                Vec3::new(1.0, 1.0, 0.0),
            ],
        },
    );
    let mjcf = write_mjcf(&model, &[flat], &[]).unwrap();
    for said in [
        "one-sided limit",
        "hull is flat",
        "\"k_link\" moves and has no mass",
    ] {
        assert!(
            mjcf.notes.iter().any(|n| n.contains(said)),
            "{said}: {:?}",
            mjcf.notes
        );
    }
    assert!(!mjcf.text.contains("<mesh"), "{}", mjcf.text);
    let urdf = write_urdf(&model, &[], &[], "m").unwrap();
    assert_eq!(
        urdf.text.matches("<link name=\"hand\"").count(),
        1,
        "{}",
        urdf.text
    );
    assert_eq!(urdf.text.matches("<link name=\"hand_2\"").count(), 1);
    load_urdf_str(&urdf.text, false).unwrap();
}

/// A URDF's visual elements go through `rigid convert` both ways: into URDF as `<visual>`s on
/// their links (a welded link's on that link) with their origins, primitives, the mesh by its
/// file and scale, and colours; into MJCF as geoms that neither collide nor weigh (`contype` and
/// `conaffinity` 0, `inertiafromgeom` false), an OBJ mesh by its file.
#[test]
fn visual_geometry_is_written_both_ways() {
    use rigid::io::write::save;
    let dir = std::env::temp_dir().join(format!("rigid_visuals_{}", std::process::id()));
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::write(
        dir.join("meshes/tet.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let urdf = dir.join("arm.urdf");
    std::fs::write(
        &urdf,
        r#"<robot name="arm">
  <material name="Blue"><color rgba="0 0 1 1"/></material>
  <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry>
    <material name="Blue"/></visual></link>
  <link name="upper">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0 0 0.25" rpy="0.1 0 0"/>
      <geometry><cylinder radius="0.03" length="0.5"/></geometry>
      <material name="Red"><color rgba="1 0 0 1"/></material></visual>
    <collision><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="2"/></joint>
  <link name="tool"><visual><origin xyz="0.01 0 0"/>
    <geometry><mesh filename="meshes/tet.obj" scale="0.1 0.1 0.2"/></geometry></visual></link>
  <joint name="weld" type="fixed"><parent link="upper"/><child link="tool"/>
    <origin xyz="0 0 0.5"/></joint>
</robot>"#,
    )
    .unwrap();
    let model = rigid::io::urdf::load_urdf(&urdf, false).unwrap();
    // URDF: read back, the visuals are where they were
    let out = dir.join("out.urdf");
    save(&model, Some(&urdf), &out).unwrap();
    let back = rigid::io::urdf::parse_urdf_file(&out).unwrap();
    let link = |n: &str| back.links.iter().find(|l| l.name == n).unwrap();
    assert_eq!(link("base").visuals.len(), 1);
    assert_eq!(link("base").visuals[0].rgba, Some([0.0, 0.0, 1.0, 1.0]));
    let upper = &link("upper").visuals;
    assert_eq!(
        upper.len(),
        1,
        "the cylinder (the welded tool's mesh is on the tool's link)"
    );
    let cylinder = &upper[0];
    assert!(matches!(
        cylinder.shape,
        rigid::io::urdf::UrdfShape::Cylinder { .. }
    ));
    assert_eq!(cylinder.rgba, Some([1.0, 0.0, 0.0, 1.0]));
    assert!((cylinder.origin.translation - Vec3::new(0.0, 0.0, 0.25)).norm() < 1e-15);
    let tool = &link("tool").visuals;
    assert_eq!(tool.len(), 1);
    let mesh = &tool[0];
    assert!((mesh.origin.translation - Vec3::new(0.01, 0.0, 0.0)).norm() < 1e-15);
    let rigid::io::urdf::UrdfShape::Mesh { filename, scale } = &mesh.shape else {
        unreachable!()
    };
    assert!(std::path::Path::new(filename).is_absolute() && filename.ends_with("tet.obj"));
    assert_eq!(*scale, Vec3::new(0.1, 0.1, 0.2));
    // MJCF: the visuals are geoms that do not collide, the dynamics unchanged
    let out = dir.join("out.xml");
    save(&model, Some(&urdf), &out).unwrap();
    let m = rigid::io::mjcf::load_mjcf(&out).unwrap();
    let visual: Vec<_> = m
        .geoms
        .iter()
        .filter(|g| g.contype == 0 && g.conaffinity == 0)
        .collect();
    assert_eq!(visual.len(), 3, "{:?}", m.geoms);
    assert!(dynamics_gap(&model, &m.model) < 1e-12);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.contains("tet.obj") && text.contains("rgba=\"1 0 0 1\""),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// What MuJoCo would refuse among visuals is left out with a note, and a massless body with a
/// visual is still merged into its child (its visual left out, noted): a zero-size box, and a
/// massless yaw link between two joints.
#[test]
fn visuals_mujoco_would_refuse_are_noted_and_left_out() {
    use rigid::io::write::save;
    let dir = std::env::temp_dir().join(format!("rigid_visuals_refused_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let urdf = dir.join("h.urdf");
    std::fs::write(
        &urdf,
        r#"<robot name="h">
  <link name="base"/>
  <link name="yaw"><visual><geometry><cylinder radius="0.05" length="0.1"/></geometry></visual></link>
  <joint name="j1" type="continuous"><parent link="base"/><child link="yaw"/><axis xyz="0 0 1"/></joint>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.1 0.15 0"/></geometry></visual>
    <visual><geometry><sphere radius="0.02"/></geometry></visual>
  </link>
  <joint name="j2" type="continuous"><parent link="yaw"/><child link="arm"/><axis xyz="0 1 0"/></joint>
</robot>"#,
    )
    .unwrap();
    let model = rigid::io::urdf::load_urdf(&urdf, false).unwrap();
    let out = dir.join("h.xml");
    let notes = save(&model, Some(&urdf), &out).unwrap();
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(!text.contains("<body name=\"yaw\""), "{text}");
    assert!(
        notes
            .iter()
            .any(|n| n.contains("visuals of the merged body \"yaw\"")),
        "{notes:?}"
    );
    assert!(
        notes.iter().any(|n| n.contains("visual \"arm/visual/0\"")),
        "{notes:?}"
    );
    assert!(text.contains("type=\"sphere\" size=\"0.02\""), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An MJCF model's drawn geoms (groups 0 to 2) go through `rigid convert` to URDF as `<visual>`s,
/// the colliding ones too (a URDF's `<collision>` elements are not drawn), and to MJCF without
/// doubling the colliding ones: a mesh where MuJoCo draws it (its file's vertices moved by the
/// asset's `refpos` and `refquat`, then scaled), a visual-only box with its colour, a hidden
/// group-3 geom left out.
#[test]
fn an_mjcf_models_drawn_geoms_are_written_as_visuals() {
    use rigid::io::write::save;
    let dir = std::env::temp_dir().join(format!("rigid_mjcf_visuals_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("tet.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let xml = dir.join("arm.xml");
    std::fs::write(
        &xml,
        r#"<mujoco><asset><mesh name="tet" file="tet.obj" scale="0.1 0.1 0.1"
    refpos="0.5 0 0" refquat="0.9238795325112867 0 0 0.3826834323650898"/></asset>
<worldbody><body name="arm" pos="0 0 1"><joint name="hinge" axis="0 1 0"/>
  <geom name="rod" type="capsule" size="0.02 0.2" pos="0 0 -0.2" rgba="1 0 0 1"/>
  <geom name="label" type="box" size="0.05 0.05 0.01" pos="0.1 0 0" contype="0" conaffinity="0"
        group="1" rgba="0 0 1 1"/>
  <geom name="hidden" type="sphere" size="0.03" group="3"/>
  <geom name="tip" type="mesh" mesh="tet" pos="0 0 -0.4" euler="0 0 30"/>
</body></worldbody></mujoco>"#,
    )
    .unwrap();
    let m = rigid::io::mjcf::load_mjcf(&xml).unwrap();
    // URDF: rod, label and tip drawn
    let out = dir.join("out.urdf");
    save(&m.model, Some(&xml), &out).unwrap();
    let back = rigid::io::urdf::parse_urdf_file(&out).unwrap();
    let arm = back.links.iter().find(|l| l.name == "arm").unwrap();
    assert_eq!(arm.visuals.len(), 3, "{:?}", arm.visuals);
    let label = arm
        .visuals
        .iter()
        .find(|v| matches!(v.shape, rigid::io::urdf::UrdfShape::Box { .. }))
        .unwrap();
    assert_eq!(label.rgba, Some([0.0, 0.0, 1.0, 1.0]));
    assert!((label.origin.translation - Vec3::new(0.1, 0.0, 0.0)).norm() < 1e-15);
    // the mesh's vertices where rigid collides the same geom (the hull of its drawn vertices)
    // (the capsule is drawn as an OBJ of its hull, the mesh by its own file)
    let tip = arm
        .visuals
        .iter()
        .find_map(|v| match &v.shape {
            rigid::io::urdf::UrdfShape::Mesh { filename, scale }
                if filename.ends_with("tet.obj") =>
            {
                Some((v.origin, *scale))
            }
            _ => None,
        })
        .unwrap();
    let (geometries, _) = rigid::io::collision::mjcf_geometries(&m);
    let hull = geometries.iter().find(|g| g.name == "tip").unwrap();
    let Shape::ConvexHull { points } = &hull.shape else {
        unreachable!()
    };
    let raw = [Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()];
    assert_eq!(points.len(), raw.len());
    for v in raw {
        let drawn = tip.0.act_point(&v.component_mul(&tip.1));
        let nearest = (points.iter())
            .map(|p| (hull.placement.act_point(p) - drawn).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < 1e-12, "{drawn}: {nearest:e}");
    }
    // MJCF: the label is the one geom that does not collide; nothing doubled
    let out = dir.join("out.xml");
    save(&m.model, Some(&xml), &out).unwrap();
    let again = rigid::io::mjcf::load_mjcf(&out).unwrap();
    let drawn_only = again
        .geoms
        .iter()
        .filter(|g| g.contype == 0 && g.conaffinity == 0)
        .count();
    assert_eq!((again.geoms.len(), drawn_only), (4, 1), "{:?}", again.geoms);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An SDF link's `<visual>` elements go through `rigid convert`: as `<visual>`s on the link in
/// URDF (pose, primitive, a mesh by its file, the material's diffuse colour), as geoms that do not
/// collide in MJCF.
#[test]
fn an_sdf_links_visuals_are_written() {
    use rigid::io::write::save;
    let dir = std::env::temp_dir().join(format!("rigid_sdf_visuals_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("tet.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let sdf = dir.join("arm.sdf");
    std::fs::write(
        &sdf,
        r#"<?xml version="1.0"?><sdf version="1.9"><model name="m">
  <link name="arm"><pose>0 0 1 0 0 0</pose>
    <inertial><mass>1</mass></inertial>
    <collision name="c"><geometry><sphere><radius>0.1</radius></sphere></geometry></collision>
    <visual name="body"><pose>0 0 -0.2 0.3 0 0</pose>
      <geometry><box><size>0.1 0.2 0.3</size></box></geometry>
      <material><diffuse>0 1 0 1</diffuse></material></visual>
    <visual name="tip"><pose>0.1 0 0 0 0 0</pose>
      <geometry><mesh><uri>tet.obj</uri><scale>0.1 0.1 0.2</scale></mesh></geometry></visual>
    <visual name="nothing"><geometry><empty/></geometry></visual>
    <visual name="flat"><geometry><box><size>0 0.1 0.1</size></box></geometry>
      <material><diffuse>green</diffuse></material></visual>
  </link>
  <joint name="hinge" type="revolute"><parent>world</parent><child>arm</child>
    <axis><xyz>0 1 0</xyz></axis></joint>
</model></sdf>"#,
    )
    .unwrap();
    // visuals that cannot be drawn are skipped with a warning each; the model loads
    let m = rigid::io::sdf::load_sdf(&sdf).unwrap();
    let skipped = (m.warnings.iter())
        .filter(|w| w.message.contains("the visual is skipped"))
        .count();
    assert_eq!(skipped, 2, "{:?}", m.warnings);
    let out = dir.join("out.urdf");
    save(&m.model, Some(&sdf), &out).unwrap();
    let back = rigid::io::urdf::parse_urdf_file(&out).unwrap();
    let arm = back.links.iter().find(|l| l.name == "arm").unwrap();
    assert_eq!(arm.visuals.len(), 2, "{:?}", arm.visuals);
    let body = &arm.visuals[0];
    assert_eq!(body.rgba, Some([0.0, 1.0, 0.0, 1.0]));
    assert!(matches!(
        body.shape,
        rigid::io::urdf::UrdfShape::Box { size } if size == Vec3::new(0.1, 0.2, 0.3)
    ));
    let want = Transform::new(
        rigid::spatial::so3::from_rpy(0.3, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -0.2),
    );
    assert!((body.origin.to_homogeneous() - want.to_homogeneous()).amax() < 1e-15);
    let rigid::io::urdf::UrdfShape::Mesh { filename, scale } = &arm.visuals[1].shape else {
        unreachable!("{:?}", arm.visuals[1])
    };
    assert!(std::path::Path::new(filename).is_absolute() && filename.ends_with("tet.obj"));
    assert_eq!(*scale, Vec3::new(0.1, 0.1, 0.2));
    // MJCF: two geoms that do not collide beside the sphere that does
    let out = dir.join("out.xml");
    save(&m.model, Some(&sdf), &out).unwrap();
    let again = rigid::io::mjcf::load_mjcf(&out).unwrap();
    let drawn_only = (again.geoms.iter())
        .filter(|g| g.contype == 0 && g.conaffinity == 0)
        .count();
    assert_eq!((again.geoms.len(), drawn_only), (3, 2), "{:?}", again.geoms);
    std::fs::remove_dir_all(&dir).unwrap();
}
