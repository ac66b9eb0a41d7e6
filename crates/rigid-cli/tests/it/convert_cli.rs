//! `rigid convert`: an MJCF model with meshes written as URDF and back, the summary line, the
//! notes, the OBJ files beside the URDF, the same model on re-reading (`rigid model`), and the
//! errors (an unknown extension, a joint the format has no type for) that write nothing. The
//! cross-checks against MuJoCo and Pinocchio are crates/rigid-py/tests/test_convert.py.

use crate::common::rigid_tests;
use std::process::{Command, Output};

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn mjcf_to_urdf_and_back_keeps_the_model() {
    let dir = std::env::temp_dir().join(format!("rigid-convert-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ant = rigid_tests("mujoco/models/ant.xml");
    let urdf = dir.join("ant.urdf");
    let out = rigid(&["convert", ant.to_str().unwrap(), urdf.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_eq!(
        text(&out.stdout).trim(),
        format!("wrote {} (URDF): 9 joints, nq 15, nv 14", urdf.display())
    );
    let notes = text(&out.stderr);
    assert!(
        notes.contains("note: the free-flyer \"root\" is left out"),
        "{notes}"
    );
    assert!(notes.contains("armatures are not written"), "{notes}");
    // the ant's 12 capsules, collided and drawn, as OBJ hulls beside the URDF (its sphere is a
    // URDF sphere): one file per distinct hull, its legs' two lengths
    let meshes = std::fs::read_dir(dir.join("ant_meshes")).unwrap().count();
    assert_eq!(meshes, 2);
    let written = std::fs::read_to_string(&urdf).unwrap();
    assert_eq!(written.matches("<mesh filename=\"ant_meshes/").count(), 24);
    assert_eq!(written.matches("<visual").count(), 13);
    // read back with a free-flyer root: the same sizes and mass
    let summary = |path: &str, floating: bool| {
        let mut args = vec!["model", path];
        if floating {
            args.push("--floating");
        }
        let out = rigid(&args);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let s = text(&out.stdout);
        s.lines()
            .find(|l| l.contains("nq"))
            .unwrap_or_default()
            .to_string()
    };
    let back = summary(urdf.to_str().unwrap(), true);
    let orig = summary(ant.to_str().unwrap(), false);
    // "nq = 15, nv = 14, 9 moving joints, total mass 0.910880 kg (moving bodies), ..."
    let sizes = |s: &str| s.split(", gravity").next().unwrap().to_string();
    assert_eq!(sizes(&back), sizes(&orig));
    assert!(
        back.starts_with("nq = 15, nv = 14, 9 moving joints"),
        "{back}"
    );
    // and to MJCF again: MuJoCo's multi-joint bodies come back as such
    let xml = dir.join("ant.xml");
    let out = rigid(&[
        "convert",
        urdf.to_str().unwrap(),
        xml.to_str().unwrap(),
        "--floating",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let written = std::fs::read_to_string(&xml).unwrap();
    assert_eq!(written.matches("type=\"free\"").count(), 1);
    // the 12 capsules' hulls as collision meshes, and as the URDF's visual meshes (OBJ files)
    assert_eq!(written.matches("<mesh ").count(), 24);
    assert_eq!(
        written.matches("contype=\"0\" conaffinity=\"0\"").count(),
        13
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn what_cannot_be_written_is_an_error_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("rigid-convert-err-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let balls = rigid_tests("mujoco/models/ball_joints.xml");
    let urdf = dir.join("b.urdf");
    let out = rigid(&["convert", balls.to_str().unwrap(), urdf.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = text(&out.stderr);
    assert!(
        err.contains("URDF has no spherical joint: MJCF has one"),
        "{err}"
    );
    assert!(!urdf.exists());
    let out = rigid(&["convert", "puma560", dir.join("p.sdf").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("unknown output format"));
    std::fs::remove_dir_all(&dir).unwrap();
}
