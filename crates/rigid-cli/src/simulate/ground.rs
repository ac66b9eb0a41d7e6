//! `rigid simulate ROBOT --ground`: the robot's collision geometry from its file, the ground
//! plane, and the floating base set down on it (the logic in `rigid::collision` and
//! `rigid::io::collision`).

use super::SimulateArgs;
use crate::load::{urdf_path, Loaded};
use rigid::collision::{place_on_ground, CollisionModel};
use rigid::io::collision::{ground_model, mjcf_geometries, spec_body, urdf_geometries};
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
    on_ground(args, height, geometries).map(Some)
}

/// The ground `z = height` with `--friction` and `--restitution` under `geometries` (a bad value
/// named by its flag).
fn on_ground(
    args: &SimulateArgs,
    height: f64,
    geometries: Vec<rigid::collision::Geometry>,
) -> Result<CollisionModel, String> {
    ground_model(height, args.friction, args.restitution, geometries).map_err(|e| {
        if e.starts_with("the ") {
            e
        } else {
            format!("--{e}")
        }
    })
}

/// `rigid simulate SPEC.toml --ground`: the body of the spec as a model of one free-flyer at
/// its CoM ([`spec_body`]) and the collision model of its parts on the ground.
pub fn body_on_ground(args: &SimulateArgs) -> Result<(Loaded, CollisionModel), String> {
    let height = args.ground.unwrap_or_default();
    let (model, geometries, warnings) = spec_body(std::path::Path::new(&args.model))?;
    for w in &warnings {
        eprintln!("warning: {}: {w}", args.model);
    }
    let cm = on_ground(args, height, geometries)?;
    let loaded = Loaded {
        model,
        warnings: Vec::new(),
        mjcf: None,
    };
    Ok((loaded, cm))
}

/// Sets `q` of a floating robot down on the ground (see [`place_on_ground`]).
pub fn set_down(model: &Model, cm: &CollisionModel, q: &mut [f64]) -> Result<(), String> {
    place_on_ground(model, cm, q)
        .map(|_| ())
        .map_err(|e| e.to_string())
}
