//! `rigid mass`: the built-in example matches a hand computation, and every kind of bad input
//! gets a message naming the part and the field (or the line), a non-zero exit and no panic.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid")
}

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/compound.toml")
}

type M6 = [[f64; 6]; 6];

fn mul6(a: &M6, b: &M6) -> M6 {
    let mut c = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            c[i][j] = (0..6).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn transpose6(a: &M6) -> M6 {
    let mut t = [[0.0; 6]; 6];
    for i in 0..6 {
        for j in 0..6 {
            t[i][j] = a[j][i];
        }
    }
    t
}

fn mat(v: &Value) -> Vec<Vec<f64>> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect()
}

fn vec(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + b.abs())
}

#[test]
fn compound_example_matches_the_hand_computation_from_textbook_formulas() {
    // examples/compound.toml: a 2 kg cylinder (r = 0.1, L = 0.2, axis z) centred at the origin
    // of {a}, and a 1 kg box 0.3 x 0.1 x 0.1 centred at x = 0.25.
    let (mc, r, l) = (2.0, 0.1, 0.2);
    let (mb, (bx, by, bz), xb) = (1.0, (0.3, 0.1, 0.1), 0.25);
    let m = mc + mb;
    let cx = (mc * 0.0 + mb * xb) / m; // CoM on the x axis
                                       // Notes 000: cylinder I = diag(m(3r²+L²)/12, same, m r²/2); box I = m/12 diag(w²+h², l²+h², l²+w²).
    let cyl = [
        mc * (3.0 * r * r + l * l) / 12.0,
        mc * (3.0 * r * r + l * l) / 12.0,
        mc * r * r / 2.0,
    ];
    let bx_i = [
        mb * (by * by + bz * bz) / 12.0,
        mb * (bx * bx + bz * bz) / 12.0,
        mb * (bx * bx + by * by) / 12.0,
    ];
    // Steiner along x: offsets d from the CoM add m d² to I_yy and I_zz.
    let (dc, db) = (0.0 - cx, xb - cx);
    let i_b = [
        cyl[0] + bx_i[0],
        cyl[1] + mc * dc * dc + bx_i[1] + mb * db * db,
        cyl[2] + mc * dc * dc + bx_i[2] + mb * db * db,
    ];
    let i_a = [i_b[0], i_b[1] + m * cx * cx, i_b[2] + m * cx * cx];

    let out = rigid(&["mass", example().to_str().unwrap(), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "mass",
        "com",
        "inertia_com",
        "inertia_origin",
        "principal_moments",
        "principal_axes",
        "spatial_inertia_origin",
    ] {
        assert!(j.get(key).is_some(), "missing key {key}");
    }
    assert!(close(j["mass"].as_f64().unwrap(), m));
    let com = vec(&j["com"]);
    assert!(
        close(com[0], cx) && close(com[1], 0.0) && close(com[2], 0.0),
        "{com:?}"
    );
    let (ic, io) = (mat(&j["inertia_com"]), mat(&j["inertia_origin"]));
    for a in 0..3 {
        for b in 0..3 {
            let (wc, wo) = if a == b { (i_b[a], i_a[a]) } else { (0.0, 0.0) };
            assert!(
                close(ic[a][b], wc) && close(io[a][b], wo),
                "({a}, {b}): {} vs {wc}",
                ic[a][b]
            );
        }
    }
    let mut sorted = i_b;
    sorted.sort_by(f64::total_cmp);
    let pm = vec(&j["principal_moments"]);
    assert!(
        (0..3).all(|k| close(pm[k], sorted[k])),
        "{pm:?} vs {sorted:?}"
    );
    // The principal axes diagonalise I_b: Rᵀ I_b R = diag(λ).
    let ax = mat(&j["principal_axes"]);
    for a in 0..3 {
        for b in 0..3 {
            let d: f64 = (0..3).map(|k| ax[k][a] * i_b[k] * ax[k][b]).sum();
            assert!(close(d, if a == b { pm[a] } else { 0.0 }));
        }
    }
    // G_a = [Ad_{T_ba}]ᵀ G_b [Ad_{T_ba}], with {b} at the CoM aligned with {a}: T_ba = (1, p),
    // p = -c, and [Ad_T] = [[R, 0], [[p]R, R]].
    let mut g_b = [[0.0; 6]; 6];
    for k in 0..3 {
        g_b[k][k] = i_b[k];
        g_b[k + 3][k + 3] = m;
    }
    let p = [-cx, 0.0, 0.0];
    let skew_p = [[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]];
    let mut ad = [[0.0; 6]; 6];
    for a in 0..3 {
        ad[a][a] = 1.0;
        ad[a + 3][a + 3] = 1.0;
        for b in 0..3 {
            ad[a + 3][b] = skew_p[a][b];
        }
    }
    let g_a = mul6(&transpose6(&ad), &mul6(&g_b, &ad));
    let g = mat(&j["spatial_inertia_origin"]);
    for a in 0..6 {
        for b in 0..6 {
            assert!(
                close(g[a][b], g_a[a][b]),
                "G[{a}][{b}] = {} vs {}",
                g[a][b],
                g_a[a][b]
            );
        }
    }
}

#[test]
fn report_without_json_shows_mass_com_inertia_principal_axes_and_validity() {
    let out = rigid(&["mass", example().to_str().unwrap()]);
    assert!(out.status.success());
    let s = String::from_utf8(out.stdout).unwrap();
    for want in [
        "mass",
        "3.000000 kg",
        "centre of mass",
        "inertia about the CoM",
        "principal moments",
        "principal axes",
        "validity",
        "ok",
    ] {
        assert!(s.contains(want), "missing {want:?} in\n{s}");
    }
}

fn temp_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigid-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `text` to a spec file and runs `rigid mass` on it; returns (exit code, stderr).
fn run_spec(file: &str, text: &str) -> (Option<i32>, String, String) {
    let path = temp_dir().join(file);
    std::fs::write(&path, text).unwrap();
    let out = rigid(&["mass", path.to_str().unwrap(), "--json"]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    (
        out.status.code(),
        err,
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

/// Asserts the spec fails with exit code 2 and a message containing every `want`.
fn assert_rejected(file: &str, text: &str, want: &[&str]) {
    let (code, err, out) = run_spec(file, text);
    assert_eq!(code, Some(2), "{file}: expected exit 2, stderr: {err}");
    assert!(out.is_empty(), "{file}: printed {out}");
    assert!(!err.contains("panicked"), "{file}: {err}");
    for w in want {
        assert!(err.contains(w), "{file}: {w:?} not in {err:?}");
    }
}

const GOOD: &str = "[[part]]\nname = \"base\"\nshape = \"sphere\"\nradius = 0.1\nmass = 1\n\n";

fn second(body: &str) -> String {
    format!("{GOOD}[[part]]\nname = \"arm\"\n{body}\n")
}

const PART2: &str = "part 2 (\"arm\"";

#[test]
fn unknown_shape_is_rejected_naming_part_and_field() {
    assert_rejected(
        "shape.toml",
        &second("shape = \"torus\"\nmass = 1"),
        &[PART2, "`shape`", "unknown shape \"torus\""],
    );
}

#[test]
fn missing_negative_or_zero_dimensions_are_rejected() {
    assert_rejected(
        "missing.toml",
        &second("shape = \"cylinder\"\nradius = 0.1\nmass = 1"),
        &[PART2, "`length`", "missing"],
    );
    assert_rejected(
        "negative.toml",
        &second("shape = \"cone\"\nradius = -0.1\nheight = 1\nmass = 1"),
        &[PART2, "`radius`", "positive"],
    );
    assert_rejected(
        "zero.toml",
        &second("shape = \"box\"\nsize = [1, 0, 1]\nmass = 1"),
        &[PART2, "`size[1]`", "positive"],
    );
    assert_rejected(
        "short.toml",
        &second("shape = \"ellipsoid\"\nsemi_axes = [1, 1]\nmass = 1"),
        &[PART2, "`semi_axes`", "expected 3 numbers"],
    );
    assert_rejected(
        "type.toml",
        &second("shape = \"sphere\"\nradius = \"big\"\nmass = 1"),
        &[PART2, "`radius`", "expected a number"],
    );
    assert_rejected(
        "unused.toml",
        &second("shape = \"sphere\"\nradius = 1\nlength = 2\nmass = 1"),
        &[PART2, "`length`", "not used"],
    );
}

#[test]
fn both_or_neither_mass_and_density_are_rejected() {
    assert_rejected(
        "both.toml",
        &second("shape = \"sphere\"\nradius = 1\nmass = 1\ndensity = 2"),
        &[PART2, "`density`", "not both"],
    );
    assert_rejected(
        "neither.toml",
        &second("shape = \"sphere\"\nradius = 1"),
        &[PART2, "`mass`", "missing"],
    );
    assert_rejected(
        "point_density.toml",
        &second("shape = \"point\"\ndensity = 2"),
        &[PART2, "`density`", "no volume"],
    );
    assert_rejected(
        "rod_nomass.toml",
        &second("shape = \"rod\"\nlength = 1"),
        &[PART2, "`mass`", "missing"],
    );
    assert_rejected(
        "zero_mass.toml",
        &second("shape = \"point\"\nmass = 0"),
        &[PART2, "`mass`", "positive"],
    );
}

#[test]
fn non_finite_numbers_are_rejected() {
    assert_rejected(
        "nan_mass.toml",
        &second("shape = \"point\"\nmass = nan"),
        &[PART2, "`mass`", "finite"],
    );
    assert_rejected(
        "inf_radius.toml",
        &second("shape = \"sphere\"\nradius = inf\nmass = 1"),
        &[PART2, "`radius`", "finite"],
    );
    assert_rejected(
        "nan_pos.toml",
        &second("shape = \"point\"\nmass = 1\nposition = [0, nan, 0]"),
        &[PART2, "`position[1]`", "finite"],
    );
}

#[test]
fn unknown_keys_are_rejected() {
    assert_rejected(
        "unknown.toml",
        &second("shape = \"sphere\"\nradus = 1\nmass = 1"),
        &[PART2, "`radus`", "unknown key"],
    );
    assert_rejected(
        "top.toml",
        &format!("units = \"mm\"\n{GOOD}"),
        &["line 1", "units"],
    );
}

#[test]
fn bad_rotations_are_rejected() {
    assert_rejected(
        "quat.toml",
        &second("shape = \"point\"\nmass = 1\nquaternion = [0, 0, 0, 2]"),
        &[PART2, "`quaternion`", "not a unit quaternion"],
    );
    assert_rejected(
        "quat_len.toml",
        &second("shape = \"point\"\nmass = 1\nquaternion = [0, 0, 1]"),
        &[PART2, "`quaternion`", "expected 4 numbers"],
    );
    assert_rejected(
        "rpy_quat.toml",
        &second("shape = \"point\"\nmass = 1\nrpy = [0, 0, 0]\nquaternion = [0, 0, 0, 1]"),
        &[PART2, "`quaternion`", "not both"],
    );
    assert_rejected(
        "rpy_nan.toml",
        &second("shape = \"point\"\nmass = 1\nrpy = [0, inf, 0]"),
        &[PART2, "`rpy[1]`", "finite"],
    );
}

/// A unit tetrahedron in OBJ, optionally without its last face (then it is open).
fn tetra_obj(open: bool, inward: bool) -> String {
    let mut faces = vec![[1, 3, 2], [1, 2, 4], [1, 4, 3], [2, 3, 4]];
    if open {
        faces.pop();
    }
    let mut s = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
    for f in faces {
        let f = if inward { [f[0], f[2], f[1]] } else { f };
        s += &format!("f {} {} {}\n", f[0], f[1], f[2]);
    }
    s
}

#[test]
fn unreadable_open_or_inward_meshes_are_rejected() {
    let dir = temp_dir();
    std::fs::write(dir.join("open.obj"), tetra_obj(true, false)).unwrap();
    std::fs::write(dir.join("inward.obj"), tetra_obj(false, true)).unwrap();
    assert_rejected(
        "nofile.toml",
        &second("shape = \"mesh\"\nfile = \"nowhere.stl\"\nmass = 1"),
        &[PART2, "`file`", "nowhere.stl"],
    );
    assert_rejected(
        "open.toml",
        &second("shape = \"mesh\"\nfile = \"open.obj\"\nmass = 1"),
        &[PART2, "`file`", "not closed"],
    );
    assert_rejected(
        "inward.toml",
        &second("shape = \"mesh\"\nfile = \"inward.obj\"\ndensity = 1"),
        &[PART2, "`file`", "inward"],
    );
}

#[test]
fn mesh_file_is_found_relative_to_the_spec_folder() {
    let dir = temp_dir().join("sub");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tet.obj"), tetra_obj(false, false)).unwrap();
    let spec = dir.join("tet.toml");
    std::fs::write(
        &spec,
        "[[part]]\nshape = \"mesh\"\nfile = \"tet.obj\"\ndensity = 6\n",
    )
    .unwrap();
    let out = rigid(&["mass", spec.to_str().unwrap(), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: Value = serde_json::from_slice(&out.stdout).unwrap();
    // Density 6 × volume 1/6 = 1 kg, centroid (1/4, 1/4, 1/4), I_xx about the centroid 0.075.
    assert!(close(j["mass"].as_f64().unwrap(), 1.0));
    assert!(vec(&j["com"]).iter().all(|&c| close(c, 0.25)));
    assert!(close(mat(&j["inertia_com"])[0][0], 0.075));
}

#[test]
fn toml_syntax_errors_report_the_line() {
    assert_rejected(
        "syntax.toml",
        "[[part]]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1.2.3\n",
        &["line 4"],
    );
    assert_rejected(
        "syntax2.toml",
        &format!("{GOOD}[[part]]\nshape = = \"box\"\n"),
        &["line 8"],
    );
}

#[test]
fn missing_spec_or_no_parts_is_an_error_not_a_panic() {
    let (code, err, _) = run_spec("empty.toml", "# nothing\n");
    assert_eq!(code, Some(2));
    assert!(err.contains("no [[part]]"), "{err}");
    let out = rigid(&["mass", "/nonexistent/spec.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read"));
}

#[test]
fn nonphysical_hand_given_inertia_is_reported_invalid() {
    // Principal moments 1, 1, 3 violate the triangle inequality λ1 + λ2 ≥ λ3.
    let spec =
        "[[part]]\nname = \"odd\"\nshape = \"inertia\"\ninertia = [1, 1, 3, 0, 0, 0]\nmass = 1\n";
    let (code, err, out) = run_spec("nonphysical.toml", spec);
    assert_eq!(code, Some(0));
    assert!(
        err.contains("not physical") && err.contains("triangle inequality"),
        "{err}"
    );
    let j: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["valid"], Value::Bool(false));
    assert!(j["validity_error"]
        .as_str()
        .unwrap()
        .contains("triangle inequality"));
    let path = temp_dir().join("nonphysical.toml");
    let text = rigid(&["mass", path.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&text.stdout).contains("NOT PHYSICAL"));
}

#[test]
fn a_point_mass_away_from_the_origin_is_valid() {
    // I_c = I_O - m[c]ᵀ[c] cancels to rounding noise; it must not read as a negative moment.
    let spec = "[[part]]\nshape = \"point\"\nmass = 8.6\nposition = [0.3, -0.93, 0.1]\n";
    let (code, err, out) = run_spec("point_offset.toml", spec);
    assert_eq!(code, Some(0), "{err}");
    assert!(err.is_empty(), "{err}");
    let j: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(j["valid"], Value::Bool(true));
}
