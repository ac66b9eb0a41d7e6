//! `rigid doctor --fix` on MJCF: the repaired `<inertial>` replaces the original in place (the
//! rest of the file byte for byte), MuJoCo's rules hold (`fullinertia` in the body frame, no
//! `quat` beside it), and the compiled inertia is the original's with the fault undone, whatever
//! the axes the original was written in.

use rigid::doctor::{examine_mjcf, fixed_mjcf, Status};
use rigid::io::mjcf::load_mjcf_str;
use rigid::spatial::Mat3;

/// A 10 kg box body whose inertia is written in kg·mm² and its CoM in mm, in axes turned by
/// `quat`; a clean body beside it.
const FILE: &str = r#"<mujoco model="m">
  <worldbody>
    <body name="turned" pos="0 0 1">
      <joint name="a" axis="0 1 0"/>
      <inertial pos="10 0 -5" quat="0.9 0.3 0.2 0.1" mass="10" diaginertia="70000 80000 90000"/>
      <geom type="box" size="0.1 0.12 0.14"/>
    </body>
    <body name="clean" pos="1 0 1">
      <joint name="b" axis="0 1 0"/>
      <inertial pos="0 0 0" mass="10" diaginertia="0.1133 0.0987 0.0813"/>
      <geom type="box" size="0.1 0.12 0.14"/>
    </body>
  </worldbody>
</mujoco>
"#;

/// The compiled inertia about the CoM in the body frame, and the CoM, of body `name`.
fn compiled(text: &str, name: &str) -> (Mat3, rigid::spatial::Vec3) {
    let m = load_mjcf_str(text, ".".as_ref()).unwrap();
    let b = m.bodies.iter().find(|b| b.name == name).unwrap();
    let (frame, moments) = &b.inertial;
    let r = frame.rotation;
    (
        r * Mat3::from_diagonal(moments) * r.transpose(),
        frame.translation,
    )
}

#[test]
fn the_repair_replaces_the_inertial_in_place_and_undoes_the_units() {
    let m = load_mjcf_str(FILE, ".".as_ref()).unwrap();
    let report = examine_mjcf(&m);
    let turned = report.bodies.iter().find(|b| b.name == "turned").unwrap();
    assert_ne!(turned.status, Status::Ok);
    let (fixed, notes) = fixed_mjcf(FILE, &report).unwrap();
    assert!(notes.is_empty(), "{notes:?}");
    // only the faulted element changed, with its comments
    let (before, after) = FILE.split_once("      <inertial pos=\"10").unwrap();
    assert!(fixed.starts_with(before));
    assert!(fixed.ends_with(&after[after.find('\n').unwrap()..]));
    assert!(fixed.contains("<!-- rigid doctor: units_millimetres:"));
    assert!(fixed.contains("<!-- was: <inertial pos=\"10 0 -5\" quat=\"0.9 0.3 0.2 0.1\""));
    let element = fixed
        .lines()
        .find(|l| l.contains("<inertial pos=\"0.01"))
        .unwrap();
    assert!(!element.contains("quat"), "{element}");
    // the compiled inertia is the original's over 10⁶, the CoM over 10³, in the same axes
    let (i0, c0) = compiled(FILE, "turned");
    let (i1, c1) = compiled(&fixed, "turned");
    assert!((i0 * 1e-6 - i1).amax() < 1e-13, "{i0} {i1}"); // eigen-decomposed twice
    assert!((c0 * 1e-3 - c1).amax() < 1e-15);
    // and the doctor finds the repaired file clean
    let again = examine_mjcf(&load_mjcf_str(&fixed, ".".as_ref()).unwrap());
    assert!(
        again.bodies.iter().all(|b| b.status == Status::Ok),
        "{again:?}"
    );
}

#[test]
fn a_file_that_computes_inertias_from_geoms_is_said_to_ignore_the_repair() {
    let text = FILE.replace(
        "<mujoco model=\"m\">",
        "<mujoco model=\"m\">\n  <compiler inertiafromgeom=\"true\"/>",
    );
    let m = load_mjcf_str(FILE, ".".as_ref()).unwrap();
    let (_, notes) = fixed_mjcf(&text, &examine_mjcf(&m)).unwrap();
    assert!(notes[0].contains("inertiafromgeom"), "{notes:?}");
}
