//! Entry points of the fuzz targets (`fuzz/`, run by `cargo fuzz`) and of their replay in the test
//! suite (`tests/fuzz_replay.rs`): each takes arbitrary bytes, runs one reader of the library on
//! them and returns, whatever the bytes. A panic, a hang or an abort is a bug. Not part of the
//! public API.

use crate::io::{cases, collada, mesh_file, spec, urdf};
use crate::multibody::{aba, crba, rnea, Data};
use std::path::Path;

fn text(data: &[u8]) -> Option<&str> {
    std::str::from_utf8(data).ok()
}

/// The state the bytes make from `q0` (each coordinate moved by a byte, normalised), and a
/// velocity; RNEA, CRBA and ABA run there. Returns `(q, v)`.
fn dynamics_at(
    model: &crate::multibody::Model,
    d: &mut Data,
    q0: &[f64],
    data: &[u8],
) -> (Vec<f64>, Vec<f64>) {
    let mut q = q0.to_vec();
    for (x, b) in q.iter_mut().zip(data) {
        *x += f64::from(*b) * 1e-3;
    }
    let _ = crate::multibody::normalize(model, &mut q);
    let v: Vec<f64> = (0..model.nv()).map(|i| (i as f64).sin()).collect();
    let _ = rnea(model, d, &q, &v, &v);
    let _ = crba(model, d, &q);
    let _ = aba(model, d, &q, &v, &v);
    (q, v)
}

/// URDF text through the parser, the model builder (all three inertia policies, fixed and
/// floating) and one `rnea`, `crba` and `aba` call at a state made from the bytes.
pub fn urdf(data: &[u8]) {
    let Some(t) = text(data) else { return };
    let Ok(robot) = urdf::parse_urdf_str(t) else {
        return;
    };
    for (k, inertia) in [
        urdf::InertiaPolicy::Strict,
        urdf::InertiaPolicy::Warn,
        urdf::InertiaPolicy::Repair,
    ]
    .into_iter()
    .enumerate()
    {
        let opts = urdf::UrdfOptions {
            floating: k == 1,
            inertia,
            sibling_order: urdf::SiblingOrder::Name,
        };
        let Ok((model, _)) = urdf::build_model_with(&robot, &opts) else {
            continue;
        };
        let mut d = Data::new(&model);
        dynamics_at(&model, &mut d, &crate::multibody::neutral(&model), data);
    }
    let _ = crate::doctor::Doctor::new().examine(&robot);
}

/// MJCF text through the importer (included files and meshes are looked up in a folder that
/// does not exist), then RNEA, CRBA and ABA at a state made from the bytes, in rigid's layout and
/// in MuJoCo's.
pub fn mjcf(data: &[u8]) {
    let Some(t) = text(data) else { return };
    let Ok(m) = crate::io::mjcf::load_mjcf_str(t, Path::new("/nonexistent-rigid-fuzz")) else {
        return;
    };
    let model = &m.model;
    let mut d = Data::new(model);
    let (q, v) = dynamics_at(model, &mut d, &crate::multibody::neutral(model), data);
    let layout = m.layout();
    let _ = layout.rnea(model, &mut d, &q, &v, &v);
    let _ = layout.mass_matrix(model, &mut d, &q);
    let _ = layout.aba(model, &mut d, &q, &v, &v);
}

/// SDF text through the importer (meshes are looked up in a folder that does not exist), then
/// RNEA, CRBA and ABA at a state made from the bytes, and the loops' constrained dynamics.
#[cfg(feature = "collision")]
pub fn sdf(data: &[u8]) {
    let Some(t) = text(data) else { return };
    let Ok(m) = crate::io::sdf::load_sdf_str(t, Path::new("/nonexistent-rigid-fuzz")) else {
        return;
    };
    let model = &m.model;
    let mut d = Data::new(model);
    let (q, v) = dynamics_at(model, &mut d, &m.home, data);
    if let Ok(mut cd) = crate::multibody::constraints::ConstraintData::new(model, &m.constraints) {
        let settings = crate::multibody::constraints::ProximalSettings::redundant();
        let _ = crate::multibody::constraints::constraint_dynamics(
            model, &mut d, &mut cd, &q, &v, &v, &settings,
        );
    }
}

/// A `rigid mass` body spec (meshes are looked up in a folder that does not exist).
pub fn spec(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Ok(body) = spec::parse_spec(t, Path::new("/nonexistent-rigid-fuzz")) {
        let _ = body.mass_properties();
    }
}

/// STL bytes (binary or ASCII), then the solid's mass properties.
pub fn stl(data: &[u8]) {
    if let Ok(m) = mesh_file::parse_stl(data.to_vec()) {
        let _ = m.mass_properties();
    }
}

/// OBJ text, then the solid's mass properties.
pub fn obj(data: &[u8]) {
    if let Ok(m) = mesh_file::parse_obj(&mut std::io::Cursor::new(data)) {
        let _ = m.mass_properties();
    }
}

/// COLLADA text, then the solid's mass properties.
pub fn dae(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Ok(m) = collada::parse_dae(t) {
        let _ = m.mass_properties();
    }
}

/// A `rigid eval` case file against the built-in PUMA 560 and a free-flyer model, then the
/// algorithms at each case.
pub fn cases(data: &[u8]) {
    let Some(t) = text(data) else { return };
    let models = [
        crate::multibody::builtin("puma560"),
        urdf::load_urdf_str(FREE_FLYER, true).ok(),
    ];
    for model in models.into_iter().flatten() {
        let Ok(cs) = cases::parse_cases(t, &model) else {
            continue;
        };
        let mut d = Data::new(&model);
        for c in cs.iter().take(16) {
            let _ = rnea(&model, &mut d, &c.q, &c.v, &c.a);
            let _ = aba(&model, &mut d, &c.q, &c.v, &c.tau);
        }
    }
}

const FREE_FLYER: &str = r#"<robot name="b"><link name="a"><inertial><mass value="1"/>
<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>"#;
