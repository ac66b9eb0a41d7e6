//! The world a file describes, in one step: a closed-loop mechanism dropped onto the ground
//! (a box on a parallelogram leg, as URDF with a constraint and as MJCF with `<connect>` and a
//! floor plane), loops, contacts and unilateral limits solved together; and an MJCF scene of
//! free bodies stacked on the file's floor (every pair of geoms colliding, as MuJoCo's).

use super::G;
use rigid::io::collision::{mjcf_file_world, urdf_world, WorldOptions};
use rigid::io::urdf::{load_urdf_str, parse_urdf_str};
use rigid::simulation::{ConstraintOptions, JointLimits, Scenario, SimulationError};

/// The leg of `fixtures/constraints/leg.urdf` (a box on a parallelogram leg, the loop in
/// `leg.json`) and the same as MJCF (`leg.xml`, a floor plane and a `<connect>`).
fn leg(file: &str) -> std::path::PathBuf {
    crate::common::fixtures_dir().join("constraints").join(file)
}

/// The leg of `leg.xml` in its file's world (its floor and `<connect>`, read as MuJoCo reads
/// them), its limits unilateral, set 3 cm above the floor with its hips at 0.05 rad.
pub(super) fn mjcf_leg() -> Scenario {
    let mj = rigid::io::mjcf::load_mjcf(leg("leg.xml")).unwrap();
    let world = mjcf_file_world(&mj, &WorldOptions::default()).unwrap();
    let mut s = Scenario::in_world(mj.model.clone(), world);
    let mut q0 = rigid::multibody::neutral(&mj.model);
    q0[2] = 0.47;
    let at = |name: &str| mj.model.joints()[mj.model.joint_id(name).unwrap().0].idx_q;
    q0[at("hip_a")] = 0.05;
    q0[at("hip_b")] = 0.05;
    q0[at("ankle")] = -0.05;
    s.q0 = Some(q0);
    s.options.limits = JointLimits::Unilateral;
    s
}

/// What a drop of the leg showed.
#[derive(Debug)]
struct Drop {
    /// The largest loop closure error at the end of any step (m).
    violation: f64,
    /// The largest rise of `K + U` above its start (J).
    rise: f64,
    /// `K + U` at the start and at the end (J).
    e0: f64,
    e1: f64,
    /// The mean normal force over the last 0.5 s over the weight.
    support: f64,
    /// The largest speed over the last 0.5 s.
    speed: f64,
}

fn drop(s: &Scenario, seconds: f64) -> Result<Drop, SimulationError> {
    let mut sim = s.build()?;
    let dt = sim.options().dt;
    let weight = s.model.total_mass() * G;
    let e0 = sim.energy()?;
    let (mut violation, mut rise, mut normal, mut n, mut speed) = (0.0f64, 0.0f64, 0.0, 0, 0.0f64);
    let steps = (seconds / dt).round() as u64;
    for k in 1..=steps {
        sim.step()?;
        violation = violation.max(sim.violation()?.position);
        rise = rise.max(sim.energy()? - e0);
        if k as f64 * dt > seconds - 0.5 {
            normal += sim.contact_stats().normal_impulse / dt;
            n += 1;
            speed = sim.v().iter().fold(speed, |a, x| a.max(x.abs()));
        }
    }
    Ok(Drop {
        violation,
        rise,
        e0,
        e1: sim.energy()?,
        support: normal / n as f64 / weight,
        speed,
    })
}

fn check(what: &str, d: &Drop) {
    eprintln!("{what}: {d:?}");
    assert!(d.violation <= 1e-6, "{what}: the loop opened: {d:?}");
    assert!(d.rise <= 5e-3, "{what}: the energy rose: {d:?}");
    // the box was dropped 0.1 m: at least half of m g h taken by the landing and the limit
    assert!(d.e0 - d.e1 > 0.5 * 2.9 * G * 0.1, "{what}: {d:?}");
    assert!((d.support - 1.0).abs() <= 0.03, "{what}: {d:?}");
    assert!(d.speed < 1e-2, "{what}: not at rest: {d:?}");
}

#[test]
fn a_closed_loop_leg_dropped_onto_the_ground_keeps_its_loop_and_comes_to_rest() {
    // URDF + a constraint + --ground
    let text = std::fs::read_to_string(leg("leg.urdf")).unwrap();
    let model = load_urdf_str(&text, true).unwrap();
    let robot = parse_urdf_str(&text).unwrap();
    let options = WorldOptions {
        ground: Some(0.0),
        ..WorldOptions::default()
    };
    let (cm, _) = urdf_world(&robot, &model, &options).unwrap();
    let file = std::fs::read_to_string(leg("leg.json")).unwrap();
    let file = rigid::io::constraints::parse_constraints(&file, &model).unwrap();
    let (foot, thigh_b) = (model.joint_id("ankle"), model.joint_id("hip_b"));
    let mut s = Scenario::new(model.clone());
    let mut q0 = rigid::multibody::neutral(&model);
    q0[2] = 0.47; // the plate 0.1 m above the ground
    let hip_a = model.joints()[model.joint_id("hip_a").unwrap().0].idx_q;
    let (hip_b, ankle) = (
        model.joints()[thigh_b.unwrap().0].idx_q,
        model.joints()[foot.unwrap().0].idx_q,
    );
    // a parallelogram tilted by 0.05 rad: both thighs turn, the foot turns back
    q0[hip_a] = 0.05;
    q0[hip_b] = 0.05;
    q0[ankle] = -0.05;
    s.q0 = Some(q0);
    s.collision = cm;
    s.options.limits = JointLimits::Unilateral;
    s.constraints = file.constraints;
    s.constraint_options = ConstraintOptions {
        settings: file.settings,
        ..ConstraintOptions::default()
    };
    check("URDF leg", &drop(&s, 3.0).unwrap());

    // MJCF: the file's floor and <connect>, no flag
    let s = mjcf_leg();
    assert_eq!(s.constraints.len(), 1);
    assert!(s.collision.as_ref().unwrap().ground.is_some());
    check("MJCF leg", &drop(&s, 3.0).unwrap());
}

/// Three boxes stacked on the file's floor with a capsule across the top: MuJoCo 4.0 holds the
/// boxes (its soft contacts sink them by 0.2-0.7 mm) and lets the capsule creep 4.8 mm sideways
/// in 5 s; rigid holds all four to round-off.
fn stack_xml() -> std::path::PathBuf {
    crate::common::fixtures_dir().join("contact/stack.xml")
}

#[test]
fn free_bodies_stacked_on_the_files_floor_stay_stacked() {
    let mj = rigid::io::mjcf::load_mjcf(stack_xml()).unwrap();
    let world = mjcf_file_world(&mj, &WorldOptions::default()).unwrap();
    let cm = world.collision.clone().unwrap();
    assert!(cm.ground.is_some() && cm.self_collision);
    assert_eq!(world.timestep, Some(0.001));
    let mut s = Scenario::new(mj.model.clone());
    let mut home = rigid::multibody::neutral(&mj.model);
    mj.layout().q_from_mujoco(&mj.qpos0, &mut home).unwrap();
    s.home = Some(home.clone());
    s.collision = world.collision;
    s.options.dt = 0.001;
    let mut sim = s.build().unwrap();
    let mut worst = 0.0f64;
    for _ in 0..5000 {
        sim.step().unwrap();
        for j in mj.model.joints() {
            let p = j.idx_q;
            let d = (0..3)
                .map(|i| (sim.q()[p + i] - home[p + i]).powi(2))
                .sum::<f64>();
            worst = worst.max(d.sqrt());
        }
    }
    eprintln!("stack: largest CoM displacement over 5 s {worst:.2e} m");
    assert!(worst <= 2e-3, "{worst}");
    // MuJoCo on the same file, side by side
    if crate::common::reference::live("the stacked scene in MuJoCo") {
        let xml = stack_xml();
        let out = crate::common::reference::run_script("mujoco/stack.py", &[xml.to_str().unwrap()]);
        let text = String::from_utf8_lossy(&out);
        let n: Vec<f64> = text
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        eprintln!(
            "stack: MuJoCo's largest displacement of each body over 5 s (m): {n:?} (its soft \
             contacts: the boxes sink, the capsule creeps sideways)"
        );
        // MuJoCo holds the boxes too (they sink into each other by less than a millimetre)
        assert!(
            n.len() == 4 && n[..3].iter().all(|x| *x <= 2e-3),
            "MuJoCo: {text}"
        );
    }
}

/// `--self-collision` on a URDF: the box and the foot plate of the leg are a candidate pair
/// (not parent and child); an SRDF's `<disable_collisions>` takes it out, and an element
/// without `link2` is refused with its line.
#[test]
fn an_srdf_disables_the_pairs_it_names() {
    use rigid::collision::CollisionData;
    use rigid::io::collision::exclude_srdf_pairs;
    let text = std::fs::read_to_string(leg("leg.urdf")).unwrap();
    let model = load_urdf_str(&text, true).unwrap();
    let robot = parse_urdf_str(&text).unwrap();
    let options = WorldOptions {
        self_collision: true,
        ..WorldOptions::default()
    };
    let (cm, _) = urdf_world(&robot, &model, &options).unwrap();
    let mut cm = cm.unwrap();
    assert!(cm.ground.is_none());
    assert_eq!(CollisionData::new(&model, &cm).unwrap().pairs(), 1);
    let dir = std::env::temp_dir().join(format!("rigid-srdf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let srdf = dir.join("leg.srdf");
    std::fs::write(
        &srdf,
        r#"<robot name="leg"><disable_collisions link1="foot" link2="box" reason="Never"/>
<disable_collisions link1="thigh_a" link2="thigh_b"/></robot>"#,
    )
    .unwrap();
    assert_eq!(exclude_srdf_pairs(&mut cm, &srdf).unwrap(), 1);
    assert_eq!(CollisionData::new(&model, &cm).unwrap().pairs(), 0);
    std::fs::write(
        &srdf,
        "<robot>\n<disable_collisions link1=\"foot\"/></robot>",
    )
    .unwrap();
    let e = exclude_srdf_pairs(&mut cm, &srdf).unwrap_err().to_string();
    assert_eq!(e, "<disable_collisions> (line 2): needs \"link2\"");
}

/// MuJoCo's parent filter is on bodies, and a body with two hinges is one body: a thigh hinged
/// twice under a pelvis, their capsules overlapping (as gymnasium's humanoid's butt and thighs),
/// never collide, while the thigh and a second pelvis-level body that it does not hang from do.
#[test]
fn a_body_with_several_joints_is_one_body_for_the_parent_filter() {
    use rigid::collision::CollisionData;
    let mj = rigid::io::mjcf::load_mjcf_str(
        r#"<mujoco><worldbody>
  <body name="pelvis" pos="0 0 1"><freejoint/><geom type="capsule" fromto="0 -0.1 0 0 0.1 0" size="0.09"/>
    <body name="thigh" pos="0 0.1 -0.04">
      <joint name="hip_x" axis="1 0 0"/><joint name="hip_y" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.3" size="0.06"/>
    </body>
    <body name="tail" pos="0 -0.1 -0.04"><joint name="wag" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0.1 -0.3" size="0.05"/></body>
  </body></worldbody></mujoco>"#,
        std::path::Path::new("."),
    )
    .unwrap();
    let world = mjcf_file_world(&mj, &WorldOptions::default()).unwrap();
    let cm = world.collision.unwrap();
    // pelvis-thigh and pelvis-tail are parent and child; thigh-tail collide
    assert_eq!(cm.excluded, vec![(0, 1), (0, 2)]);
    assert_eq!(CollisionData::new(&mj.model, &cm).unwrap().pairs(), 1);
}

/// A mesh that is not convex collides as its convex hull, and the loader says so, naming it
/// with the depth of its dent: a 10 cm cube whose top face is pushed 2 cm in at its centre
/// (the hull is the cube: the dent's vertex lies 20 mm under its top face); the plain cube
/// beside it is convex and not named.
#[test]
fn a_mesh_that_is_not_convex_is_named_in_a_warning() {
    use rigid::io::collision::urdf_geometries;
    use rigid::io::urdf::{load_urdf, parse_urdf_file};
    let dir = std::env::temp_dir().join(format!("rigid-concave-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let corners =
        "v -0.05 -0.05 -0.05\nv 0.05 -0.05 -0.05\nv 0.05 0.05 -0.05\nv -0.05 0.05 -0.05\n\
                   v -0.05 -0.05 0.05\nv 0.05 -0.05 0.05\nv 0.05 0.05 0.05\nv -0.05 0.05 0.05\n";
    let sides = "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n\
                 f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
    let cube = format!("{corners}{sides}f 5 6 7\nf 5 7 8\n");
    let dented = format!("{corners}v 0 0 0.03\n{sides}f 5 6 9\nf 6 7 9\nf 7 8 9\nf 8 5 9\n");
    std::fs::write(dir.join("cube.obj"), cube).unwrap();
    std::fs::write(dir.join("dented.obj"), dented).unwrap();
    let inertial = r#"<inertial><mass value="1"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>"#;
    let urdf = dir.join("two.urdf");
    std::fs::write(
        &urdf,
        format!(
            r#"<robot name="two">
  <link name="base">{inertial}<collision><geometry><mesh filename="cube.obj"/></geometry></collision></link>
  <link name="dented">{inertial}<collision><geometry><mesh filename="dented.obj"/></geometry></collision></link>
  <joint name="j" type="continuous"><parent link="base"/><child link="dented"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/></joint>
</robot>"#
        ),
    )
    .unwrap();
    let model = load_urdf(&urdf, false).unwrap();
    let robot = parse_urdf_file(&urdf).unwrap();
    let (geometries, warnings) = urdf_geometries(&robot, &model);
    assert_eq!(geometries.len(), 2);
    assert_eq!(
        warnings,
        [
            "1 collision mesh is not convex: each collides as its convex hull, which fills its \
          dents (the deepest given): dented/0 (20.00 mm)"
        ]
    );
}
