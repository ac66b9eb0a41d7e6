//! `rigid simulate ROBOT --ground`: a URDF box falls onto the ground and rests there, a body spec
//! (`.toml`) set down or thrown onto it comes to rest on its parts, Solo-12
//! stands on it under `--controller pd`, the CSV's contact columns, and clean refusals of bad
//! friction and restitution.

use crate::common::example_robot_data;
use std::path::PathBuf;
use std::process::{Command, Output};

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .env("EXAMPLE_ROBOT_DATA", example_robot_data())
        .args(args)
        .output()
        .unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigid-ground-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The last row of a CSV file, by column name.
fn last_row(path: &std::path::Path) -> std::collections::HashMap<String, f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let last = lines.last().unwrap();
    header
        .iter()
        .zip(last.split(','))
        .map(|(h, x)| (h.to_string(), x.parse().unwrap()))
        .collect()
}

/// A 2 kg box 0.4 x 0.3 x 0.1 m with its collision box, one link.
const BOX_URDF: &str = r#"<robot name="crate">
  <link name="crate">
    <inertial><mass value="2"/><inertia ixx="0.0167" iyy="0.0283" izz="0.0417" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
</robot>"#;

#[test]
fn a_urdf_box_falls_onto_the_ground_and_rests_on_it() {
    let dir = scratch("box");
    let urdf = dir.join("crate.urdf");
    std::fs::write(&urdf, BOX_URDF).unwrap();
    let csv = dir.join("box.csv");
    let out = rigid(&[
        "simulate",
        urdf.to_str().unwrap(),
        "--floating",
        "--q0",
        "0,0,0.5,0,0,0,1",
        "--ground",
        "--duration",
        "1",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("ground: z = 0 m, friction 0.8, restitution 0"),
        "{stdout}"
    );
    assert!(stdout.contains("integrator: semi-implicit"), "{stdout}");
    // the solver's record: every step after the landing solved to its tolerance
    let solves = stdout
        .lines()
        .find(|l| l.starts_with("contact solves (pgs): "))
        .unwrap_or_else(|| panic!("no record of the contact solves: {stdout}"));
    assert!(solves.ends_with(" % converged"), "{solves}");
    let converged: f64 = solves.rsplit(", ").next().unwrap()[..5]
        .trim()
        .parse()
        .unwrap();
    assert!(converged > 90.0, "{solves}");
    let row = last_row(&csv);
    // resting on its largest face: the centre half the height above the ground
    assert!((row["q_root_joint_z"] - 0.05).abs() < 1e-4, "{row:?}");
    assert_eq!(row["contacts"], 4.0, "{row:?}");
    // the four corners carry the weight
    assert!(
        (row["normal_force"] - 2.0 * 9.81).abs() < 0.02 * 2.0 * 9.81,
        "{row:?}"
    );
}

/// `--contact-solver admm --residuals`: the box rests the same, the summary names the solver,
/// and each CSV row carries the solve's iterations, whether it converged and its residuals.
/// The sweep's polish is on unless `--no-polish`: gymnasium's ant (checked in) landing in its
/// file's world at 1 ms takes 4 sweeps a step with it and ~32 without (docs/contact.md).
#[test]
fn no_polish_leaves_the_sweep_alone() {
    let ant = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../rigid/tests/mujoco/models/ant.xml"
    );
    let sweeps = |flags: &[&str]| {
        let mut args = vec!["simulate", ant, "--duration", "0.6", "--dt", "0.001"];
        args.extend_from_slice(flags);
        let out = rigid(&args);
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let line = stdout
            .lines()
            .find(|l| l.starts_with("contact solves (pgs): "))
            .unwrap_or_else(|| panic!("{stdout}"))
            .to_string();
        let x: f64 = line
            .split(", ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        (x, line)
    };
    let (with, a) = sweeps(&[]);
    let (without, b) = sweeps(&["--no-polish"]);
    assert!(with <= 6.0 && without >= 20.0, "{a}\n{b}");
}

#[test]
fn the_admm_solver_and_its_residuals_in_the_csv() {
    let dir = scratch("admm");
    let urdf = dir.join("crate.urdf");
    std::fs::write(&urdf, BOX_URDF).unwrap();
    let csv = dir.join("box.csv");
    let out = rigid(&[
        "simulate",
        urdf.to_str().unwrap(),
        "--floating",
        "--q0",
        "0,0,0.5,0,0,0,1",
        "--ground",
        "--duration",
        "1",
        "--contact-solver",
        "admm",
        "--residuals",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("contact solves (admm): "), "{stdout}");
    assert!(
        stdout.contains("contact residuals, largest of a step: Signorini "),
        "{stdout}"
    );
    let row = last_row(&csv);
    assert!((row["q_root_joint_z"] - 0.05).abs() < 1e-4, "{row:?}");
    assert_eq!(row["contacts"], 4.0, "{row:?}");
    assert_eq!(row["converged"], 1.0, "{row:?}");
    assert!(row["iterations"] >= 1.0, "{row:?}");
    // at rest, solved: the residuals at round-off of the 0.02 N·s impulse and 1e-3 m/s speeds
    for k in ["signorini", "dissipation", "coulomb"] {
        assert!(row[k].abs() < 1e-12, "{k}: {row:?}");
    }
    assert!(row["velocity_error"].abs() < 1e-9, "{row:?}");
    // an unknown solver is refused by name
    let bad = rigid(&["simulate", "double_pendulum", "--contact-solver", "newton"]);
    assert!(!bad.status.success());
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("newton"), "{err}");
}

#[test]
fn solo12_stands_on_the_ground_under_pd() {
    let dir = scratch("solo");
    let csv = dir.join("solo.csv");
    let stance = "0,0,0.3,0,0,0,1,0.1,0.8,-1.6,-0.1,0.8,-1.6,0.1,-0.8,1.6,-0.1,-0.8,1.6";
    let out = rigid(&[
        "simulate",
        "solo12",
        "--floating",
        "--ground",
        "--controller",
        "pd",
        "--target",
        stance,
        "--duration",
        "0.5",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let header = text.lines().next().unwrap();
    assert!(header.ends_with(",contacts,normal_force"), "{header}");
    let first: Vec<f64> = text
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let row = last_row(&csv);
    // set down on its four feet at the stance, it stays there
    assert!(
        (row["q_root_joint_z"] - first[3]).abs() < 1e-3,
        "{row:?} from {}",
        first[3]
    );
    assert_eq!(row["contacts"], 4.0);
    let weight = 9.81 * 2.5; // Solo-12 weighs about 2.5 kg
    assert!(
        (row["normal_force"] - weight).abs() < 0.05 * weight,
        "{row:?}"
    );
}

#[test]
fn bad_friction_and_restitution_are_refused_with_the_flag_named() {
    for (args, message) in [
        (
            &["--ground", "--friction", "-0.5"][..],
            "--friction must be finite and >= 0",
        ),
        (
            &["--ground", "--restitution", "1.5"][..],
            "--restitution must be in [0, 1]",
        ),
        (
            &["--friction", "0.5"][..],
            "--friction applies when something can touch",
        ),
    ] {
        let mut all = vec!["simulate", "ur5", "--duration", "0.01"];
        all.extend_from_slice(args);
        let out = rigid(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// The compound of lecture notes 001 (a 2 kg cylinder of radius 0.1 m and length 0.2 m, a 1 kg
/// prism bolted to its side), as `examples/compound.toml`.
fn compound_spec() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/compound.toml")
}

/// `rigid simulate compound.toml --ground FLAGS --csv ...` (`name` names the scratch folder):
/// the last CSV row, after checking that it succeeded.
fn compound_on_ground(name: &str, flags: &[&str]) -> std::collections::HashMap<String, f64> {
    let csv = scratch(name).join("run.csv");
    let spec = compound_spec();
    let mut all = vec!["simulate", spec.to_str().unwrap(), "--ground"];
    all.extend_from_slice(flags);
    all.extend_from_slice(&["--csv", csv.to_str().unwrap()]);
    let out = rigid(&all);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    last_row(&csv)
}

#[test]
fn a_body_spec_set_down_on_the_ground_rests_on_its_parts() {
    // no --q0: the body starts on the ground, spec axes upright; its cylinder (axis vertical,
    // half-length 0.1 m) and the prism (0.1 m thick, centred at the same height) carry it with
    // its CoM at 0.1 m
    let last = compound_on_ground("spec", &["--duration", "1"]);
    // the body columns of a spec, on the ground or not (px, ..., vz)
    assert!((last["pz"] - 0.1).abs() < 1e-4, "{last:?}");
    assert!(
        last["px"].abs() < 1e-3 && last["py"].abs() < 1e-3,
        "{last:?}"
    );
    assert!(
        (last["normal_force"] - 3.0 * 9.81).abs() < 0.01 * 3.0 * 9.81,
        "{last:?}"
    );
}

#[test]
fn a_body_spec_thrown_tumbling_comes_to_rest_on_the_ground() {
    // dropped from 0.5 m tilted, spinning and sliding: at the end it lies still on the ground,
    // its weight on its contacts, having lost energy (never gained it)
    let last = compound_on_ground(
        "throw",
        &[
            "--q0",
            "0,0,0.5,0.199995991,0.099997996,0,0.974680463",
            "--omega",
            "1,2,3",
            "--velocity",
            "0.5,0,0",
            "--duration",
            "3",
        ],
    );
    let speed: f64 = ["wx", "wy", "wz", "vx", "vy", "vz"]
        .iter()
        .map(|k| last[*k].powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(speed < 1e-3, "still moving: {last:?}");
    // the CoM lies between 0.05 m (on the prism's face) and 0.25 m above the ground
    assert!(last["pz"] > 0.05 && last["pz"] < 0.25, "{last:?}");
    assert!(
        (last["normal_force"] - 3.0 * 9.81).abs() < 0.01 * 3.0 * 9.81,
        "{last:?}"
    );
}

#[test]
fn a_body_spec_on_the_ground_refuses_the_flags_that_do_not_apply() {
    let spec = compound_spec();
    for flag in [&["--pivot", "0,0,0"][..], &["--v0", "0,0,0,0,0,0"][..]] {
        let mut all = vec!["simulate", spec.to_str().unwrap(), "--ground"];
        all.extend_from_slice(flag);
        let out = rigid(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flag:?}: {stderr}");
        assert!(
            stderr.contains(&format!(
                "{} does not apply to a body on the ground",
                flag[0]
            )),
            "{stderr}"
        );
    }
}

#[test]
fn the_replay_of_a_body_on_the_ground_draws_the_ground_its_parts_and_the_contacts() {
    let html = scratch("replay").join("replay.html");
    compound_on_ground(
        "replay-csv",
        &["--duration", "0.5", "--html", html.to_str().unwrap()],
    );
    let page = std::fs::read_to_string(&html).unwrap();
    for node in [
        r#""name":"ground""#,
        r#""name":"contact 0""#,
        r#""name":"cylinder""#,
        r#""name":"prism""#,
    ] {
        assert!(page.contains(node), "no {node} in the page");
    }
}

/// The scene JSON of a replay page (the `<script id="scene">` element).
fn page_scene(page: &str) -> serde_json::Value {
    let start = page.find(r#"id="scene">"#).unwrap() + r#"id="scene">"#.len();
    let end = start + page[start..].find("</script>").unwrap();
    serde_json::from_str(&page[start..end].replace("<\\/", "</")).unwrap()
}

/// A base64 array of little-endian `f32` from the scene JSON.
fn floats(scene: &serde_json::Value, key: &str) -> Vec<f64> {
    use base64::Engine;
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(scene[key].as_str().unwrap())
        .unwrap();
    bytes
        .chunks_exact(4)
        .map(|b| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])))
        .collect()
}

#[test]
fn the_replay_draws_the_contact_forces_of_a_resting_body_summing_to_its_weight() {
    let html = scratch("arrows").join("replay.html");
    compound_on_ground(
        "arrows-csv",
        &["--duration", "1", "--html", html.to_str().unwrap()],
    );
    let scene = page_scene(&std::fs::read_to_string(&html).unwrap());
    let slots = scene["force_slots"].as_u64().unwrap() as usize;
    let forces = floats(&scene, "forces");
    let times = floats(&scene, "times");
    assert_eq!(forces.len(), times.len() * slots * 6, "one set per frame");
    // the last frame: the 3 kg compound at rest, its arrows (point, force) carry its weight
    let last = &forces[forces.len() - slots * 6..];
    let arrows: Vec<&[f64]> = last
        .chunks(6)
        .filter(|a| a[3..].iter().any(|x| *x != 0.0))
        .collect();
    assert!(!arrows.is_empty(), "no arrow");
    let weight = 3.0 * 9.81;
    let sum: Vec<f64> = (3..6).map(|k| arrows.iter().map(|a| a[k]).sum()).collect();
    assert!((sum[2] - weight).abs() < 0.01 * weight, "{sum:?}");
    // (the horizontal sum is not asserted: at rest on two contacts the compound rocks about x
    // by ±0.005 rad/s, the sign flipping every step, and its friction forces with it, ±3 N)
    // each arrow starts at its red marker, on the ground
    let nodes = scene["nodes"].as_array().unwrap();
    let poses = floats(&scene, "poses");
    let frame = &poses[poses.len() - nodes.len() * 7..];
    for (k, a) in arrows.iter().enumerate() {
        let i = nodes
            .iter()
            .position(|n| n["name"] == format!("contact {k}"))
            .unwrap();
        let marker = &frame[7 * i..7 * i + 3];
        assert!(
            (0..3).all(|j| (marker[j] - a[j]).abs() < 1e-6),
            "{a:?} {marker:?}"
        );
        assert!(a[2].abs() < 1e-3, "{a:?}");
    }
    // the page states the arrows' scale, the one its arrows are drawn at
    let scale = scene["force_scale"].as_f64().unwrap();
    let info = scene["info"].as_str().unwrap();
    let stated: f64 = info
        .split(" mm per N")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no scale on the page: {info}"));
    assert!(
        (stated / 1e3 - scale).abs() < 1e-3 * scale,
        "{info} vs {scale}"
    );
}

/// `fixtures/constraints/FILE` of the library's tests.
fn constraints_fixture(file: &str) -> PathBuf {
    crate::common::rigid_tests("fixtures/constraints").join(file)
}

/// The start of the leg: the plate 0.1 m above the ground, the parallelogram tilted by 0.05 rad
/// (both hips turned, the ankle back), as `--q0` for a run whose CSV header is `header`.
fn leg_start(header: &[&str]) -> String {
    let q: Vec<&str> = header
        .iter()
        .copied()
        .filter(|h| h.starts_with("q_"))
        .collect();
    q.iter()
        .map(|h| match *h {
            h if h.ends_with("_z") => "0.47",
            h if h.ends_with("_qw") => "1",
            "q_hip_a" | "q_hip_b" => "0.05",
            "q_ankle" => "-0.05",
            _ => "0",
        })
        .collect::<Vec<_>>()
        .join(",")
}

/// Runs `rigid simulate` on the leg (`model` and `flags`), dropped from `leg_start` for 3 s;
/// checks the CSV: the loop closed to 1e-6 m at every step, `K + U` never above its start by
/// more than 5 mJ, the landing taking energy, and at rest the normal force the weight (3 %).
fn drop_leg(name: &str, model: &str, flags: &[&str]) {
    let dir = scratch(name);
    let probe = dir.join("probe.csv");
    let mut all = vec!["simulate", model, "--duration", "0.001", "--csv"];
    all.push(probe.to_str().unwrap());
    all.extend_from_slice(flags);
    let out = rigid(&all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&probe).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let q0 = leg_start(&header);
    let csv = dir.join("leg.csv");
    let mut all = vec!["simulate", model, "--duration", "3", "--q0", &q0, "--csv"];
    all.push(csv.to_str().unwrap());
    all.extend_from_slice(flags);
    let out = rigid(&all);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("constraints: 1"), "{stdout}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let (e, p, f) = (
        col("energy"),
        col("violation_position"),
        col("normal_force"),
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 3001);
    let e0 = rows[0][e];
    for r in &rows {
        assert!(r[p] <= 1e-6, "t = {}: the loop opened by {} m", r[0], r[p]);
        assert!(
            r[e] <= e0 + 5e-3,
            "t = {}: energy {} above {e0}",
            r[0],
            r[e]
        );
    }
    assert!(
        rows[3000][e] < e0 - 0.5 * 2.9 * 9.81 * 0.1,
        "{}",
        rows[3000][e]
    );
    let rest = &rows[2500..];
    let mean = rest.iter().map(|r| r[f]).sum::<f64>() / rest.len() as f64;
    let weight = 2.9 * 9.81;
    assert!((mean - weight).abs() <= 0.03 * weight, "{mean} vs {weight}");
}

#[test]
fn a_closed_loop_leg_lands_on_the_ground_with_its_loop_closed() {
    // URDF + constraint file + --ground: loops and contacts in one step (refused before)
    let urdf = constraints_fixture("leg.urdf");
    let json = constraints_fixture("leg.json");
    drop_leg(
        "leg-urdf",
        urdf.to_str().unwrap(),
        &[
            "--floating",
            "--ground",
            "--limits",
            "unilateral",
            "--constraints",
            json.to_str().unwrap(),
        ],
    );
    // MJCF: the file's floor and <connect>, no flag
    let xml = constraints_fixture("leg.xml");
    drop_leg(
        "leg-mjcf",
        xml.to_str().unwrap(),
        &["--limits", "unilateral"],
    );
}

#[test]
fn an_open_loop_or_a_world_the_solver_cannot_hold_is_refused_by_name() {
    let urdf = constraints_fixture("leg.urdf");
    let json = constraints_fixture("leg.json");
    // thigh A turned, thigh B not: the loop 0.1 m from closing
    let out = rigid(&[
        "simulate",
        urdf.to_str().unwrap(),
        "--floating",
        "--constraints",
        json.to_str().unwrap(),
        "--q0",
        "0,0,1,0,0,0,1,0.3,0,0",
        "--duration",
        "0.01",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("from closing at the start"), "{stderr}");
    let dir = scratch("bad-world");
    for (xml, message) in [
        (
            r#"<mujoco><worldbody><geom type="plane" size="1 1 0.1"/>
  <body name="a"><freejoint/><geom size="0.1"/></body></worldbody>
  <contact><exclude body1="a" body2="nothing"/></contact></mujoco>"#,
            "(line 3): no body named \"nothing\"",
        ),
        (
            r#"<mujoco><worldbody>
  <body name="a"><freejoint/><geom size="0.1"/><geom name="tray" type="plane" size="1 1 0.1"/></body>
  </worldbody></mujoco>"#,
            "line 2: geom \"tray\": a plane is only allowed in a static body",
        ),
        (
            r#"<mujoco><worldbody><geom type="plane" size="1 1 0.1"/>
  <body name="a"><freejoint/><geom size="0.1"/></body></worldbody></mujoco>"#,
            "the file has its own floor",
        ),
    ] {
        let path = dir.join("world.xml");
        std::fs::write(&path, xml).unwrap();
        let mut all = vec!["simulate", path.to_str().unwrap(), "--duration", "0.01"];
        if message.contains("own floor") {
            all.push("--ground");
        }
        let out = rigid(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(message), "{message}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}
