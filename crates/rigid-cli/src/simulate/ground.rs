//! `rigid simulate ROBOT --ground`: the robot's collision geometry from its file, the ground
//! plane, and the floating base set down on it (the logic in `rigid::collision` and
//! `rigid::io::collision`).

use super::SimulateArgs;
use crate::load::{urdf_path, Loaded};
use rigid::collision::{place_on_ground, CollisionModel, Ground, DEFAULT_FRICTION};
use rigid::io::collision::{mjcf_geometries, urdf_geometries};
use rigid::io::urdf::parse_urdf_file;
use rigid::multibody::Model;

/// The collision model of `--ground` (`None` without it): the ground `z = HEIGHT` with
/// `--friction` and `--restitution`, the geometry of the URDF's `<collision>` elements or the
/// MJCF's geoms, no contact between the robot's own bodies. Prints the geometry's warnings.
pub fn collision_model(
    args: &SimulateArgs,
    loaded: &Loaded,
) -> Result<Option<CollisionModel>, String> {
    let Some(height) = args.ground else {
        return Ok(None);
    };
    let friction = args.friction.unwrap_or(DEFAULT_FRICTION);
    let restitution = args.restitution.unwrap_or(0.0);
    if !(friction.is_finite() && friction >= 0.0) {
        return Err(format!(
            "--friction must be finite and >= 0, got {friction}"
        ));
    }
    if !(0.0..=1.0).contains(&restitution) {
        return Err(format!(
            "--restitution must be in [0, 1], got {restitution}"
        ));
    }
    let mut ground = Ground::horizontal(height, friction);
    ground.restitution = restitution;
    let mut cm = CollisionModel::new(ground);
    cm.self_collision = false;
    cm.friction = friction;
    cm.restitution = restitution;
    let (geometries, warnings) = if let Some(m) = &loaded.mjcf {
        mjcf_geometries(m)
    } else if let Some(path) = urdf_path(&args.model) {
        let robot = parse_urdf_file(&path).map_err(|e| format!("{}: {e}", args.model))?;
        urdf_geometries(&robot, &loaded.model)
    } else {
        (Vec::new(), Vec::new())
    };
    for w in &warnings {
        eprintln!("warning: {}: {w}", args.model);
    }
    if geometries.is_empty() {
        eprintln!(
            "warning: {}: no collision geometry: nothing touches the ground",
            args.model
        );
    }
    cm.geometries = geometries;
    Ok(Some(cm))
}

/// Sets `q` of a floating robot down on the ground (see [`place_on_ground`]).
pub fn set_down(model: &Model, cm: &CollisionModel, q: &mut [f64]) -> Result<(), String> {
    place_on_ground(model, cm, q)
        .map(|_| ())
        .map_err(|e| e.to_string())
}
