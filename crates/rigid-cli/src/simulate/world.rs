//! `rigid simulate`'s flags as a [`Scenario`]: the model file, the world it describes (an MJCF
//! file's floor, geoms, `<contact>` and `<equality>`; a URDF's `<collision>` on `--ground`,
//! `--self-collision`), `--constraints`, the start, the controller and the step's options. The
//! rules are the library's (`rigid::simulation::Scenario`, `rigid::io::collision`); this only
//! reads the flags and names them in errors.

use super::SimulateArgs;
use crate::load::{is_mjcf, is_sdf, load_printing_warnings, urdf_path, Loaded};
use rigid::io::collision::{
    mjcf_file_world, sdf_file_world, spec_body, urdf_file_world, FileWorld, WorldError,
    WorldOptions,
};
use rigid::io::urdf::parse_urdf_file;
use rigid::simulation::{ConstraintOptions, Scenario, SimulationError, SimulationOptions};

/// What `rigid simulate` runs: the scenario, whether the model is a body spec, and the MJCF
/// import (for the replay's geometry).
pub struct World {
    pub scenario: Scenario,
    pub spec: bool,
    /// The time step: `--dt`, else the MJCF file's `<option timestep>`, else 1 ms.
    pub dt: f64,
}

/// A world error with the flag it comes from named.
fn flag_error(e: WorldError) -> String {
    match e {
        WorldError::Friction(_) => format!("--{e}"),
        WorldError::Restitution(_) => format!("--{e}"),
        WorldError::Height(h) => format!("--ground must be finite, got {h}"),
        WorldError::NothingToTouch { option } => {
            format!(
                "--{option} applies when something can touch (--ground, or a file with a floor)"
            )
        }
        e => e.to_string(),
    }
}

/// A scenario error with the flag it comes from named.
pub fn simulation_error(e: SimulationError) -> String {
    match e {
        SimulationError::MissingTarget { controller, nq } => {
            format!("--controller {controller} needs --target (nq = {nq} numbers)")
        }
        SimulationError::Length {
            what,
            got,
            expected,
            joints,
        } => format!("--{what} has {got} numbers; the model has {expected} ({joints})"),
        SimulationError::Constraint(rigid::multibody::constraints::ConstraintError::Singular) => {
            "--constraints: the constraints are redundant (a planar loop held by a 3D point, \
             say): give the file \"mu\": 1e-6 (proximal iterations)"
                .into()
        }
        e => e.to_string(),
    }
}

/// The world of `args` (files read, warnings printed on stderr).
pub fn world(args: &SimulateArgs) -> Result<World, String> {
    let options = WorldOptions {
        ground: args.ground,
        friction: args.friction,
        restitution: args.restitution,
        self_collision: args.self_collision,
    };
    let warn = |ws: &[String]| {
        for w in ws {
            eprintln!("warning: {}: {w}", args.model);
        }
    };
    let spec = super::is_body_spec(&args.model);
    // a body spec on the ground is a one-body model: its pose is --q0 (the CoM and the spec
    // axes), its twist --omega and --velocity
    let (loaded, world) = if spec {
        let (model, geometries, warnings) = spec_body(std::path::Path::new(&args.model))?;
        warn(&warnings);
        let world = FileWorld::without_file(&options, geometries).map_err(flag_error)?;
        let loaded = Loaded {
            model,
            warnings: Vec::new(),
            mjcf: None,
            sdf: None,
        };
        (loaded, world)
    } else {
        let loaded = load_printing_warnings(&args.model, &args.load)?;
        let mut world = file_world(args, &loaded, &options)?;
        warn(&world.warnings);
        if let (Some(srdf), Some(cm)) = (&args.srdf, world.collision.as_mut()) {
            let n = rigid::io::collision::exclude_srdf_pairs(cm, srdf).map_err(flag_error)?;
            eprintln!("{}: {n} pairs of geometries never collide", srdf.display());
        }
        world.check_materials(&options).map_err(flag_error)?;
        (loaded, world)
    };
    let mut s = Scenario::new(loaded.model.clone());
    if let Some(g) = args.gravity {
        s.model = s.model.with_gravity(g);
    }
    s.home = world.home.clone();
    s.q0 = args.q0.clone().map(|n| n.0);
    s.v0 = if spec {
        let (w, v) = (args.omega, args.velocity);
        Some(vec![w.x, w.y, w.z, v.x, v.y, v.z])
    } else {
        args.v0.clone().map(|n| n.0)
    };
    s.controller = args.controller;
    s.target = args.target.clone().map(|n| n.0);
    s.profile = args.profile;
    let dt = world.time_step(args.dt);
    s.move_time = args.move_time.unwrap_or(0.5 * args.duration);
    s.options = SimulationOptions {
        dt,
        integrator: args.integrator,
        limits: args.limits,
        joint_dynamics: !args.no_joint_dynamics,
        ..SimulationOptions::default()
    };
    s.collision = world.collision;
    // the loops: --constraints FILE, else the file's own (an MJCF file's <equality> elements)
    let (constraints, settings) = match &args.constraints {
        Some(path) => {
            let f = crate::eval_constraints::read(&s.model, path, loaded.mjcf.as_ref())?;
            (f.constraints, f.settings)
        }
        None => (world.constraints, world.constraint_settings),
    };
    s.constraints = constraints;
    if args.mimic {
        couple(args, &mut s)?;
    }
    s.constraint_options = ConstraintOptions {
        settings,
        ..ConstraintOptions::default()
    };
    s.contact.solver = args.contact_solver;
    s.contact.polish = !args.no_polish;
    Ok(World {
        scenario: s,
        spec,
        dt,
    })
}

/// `--mimic`: a URDF's `<mimic>` joints held as joint constraints of the full model (the
/// constrained dynamics are those of the reduced model, `rigid::multibody::MimicModel`), the
/// start and the target made consistent with them (each mimic coordinate from its source's; a
/// `--q0`, `--v0` or `--target` may also be given in the reduced coordinates). An MJCF file's
/// `<equality joint>` elements are held without the flag.
fn couple(args: &SimulateArgs, s: &mut Scenario) -> Result<(), String> {
    let Some(path) =
        urdf_path(&args.model).filter(|_| !is_mjcf(&args.model) && !is_sdf(&args.model))
    else {
        let what = if is_mjcf(&args.model) {
            "an MJCF file's <equality joint> elements are held without it"
        } else if is_sdf(&args.model) {
            "an SDF file's gearboxes are held without it"
        } else {
            "the model has no mimic joints"
        };
        eprintln!("warning: {}: --mimic: {what}", args.model);
        return Ok(());
    };
    let robot = parse_urdf_file(&path).map_err(|e| format!("{}: {e}", args.model))?;
    let mm = rigid::io::urdf::mimic_model(&robot, s.model.clone())
        .map_err(|e| format!("{}: {e}", args.model))?;
    if mm.mimics().is_empty() {
        eprintln!(
            "warning: {}: --mimic: the file has no mimic joints",
            args.model
        );
    }
    let (nq, nv) = (s.model.nq(), s.model.nv());
    let consistent = |q: &[f64], what: &str| {
        mm.consistent_q(q).ok_or_else(|| {
            format!(
                "--{what} has {} numbers; with --mimic give the reduced coordinates ({}) or \
                 every joint's ({nq})",
                q.len(),
                mm.nq()
            )
        })
    };
    // without --q0, the start is the file's home made consistent, or the neutral configuration,
    // which the scenario closes under the couplings and sets down on a ground
    if let Some(q0) = &s.q0 {
        s.q0 = Some(consistent(q0, "q0")?);
    } else if let Some(home) = &s.home {
        s.home = Some(consistent(home, "q0")?);
    }
    if let Some(v0) = &s.v0 {
        s.v0 = Some(mm.consistent_v(v0).ok_or_else(|| {
            format!(
                "--v0 has {} numbers; with --mimic give the reduced velocities ({}) or every \
                 joint's ({nv})",
                v0.len(),
                mm.nv()
            )
        })?);
    }
    if let Some(t) = &s.target {
        s.target = Some(consistent(t, "target")?);
    }
    s.constraints.extend(mm.constraints());
    Ok(())
}

/// The world of a robot file: an MJCF file's own (floor, geoms, `<contact>`, `<equality>`,
/// timestep), a URDF's `<collision>` on `--ground` (and between its bodies with
/// `--self-collision`), a built-in model's ground (it has no geometry).
fn file_world(
    args: &SimulateArgs,
    loaded: &Loaded,
    options: &WorldOptions,
) -> Result<FileWorld, String> {
    let world = if let Some(m) = &loaded.mjcf {
        mjcf_file_world(m, options).map_err(|e| format!("{}: {}", args.model, flag_error(e)))?
    } else if let Some(s) = &loaded.sdf {
        sdf_file_world(s, options).map_err(flag_error)?
    } else if let Some(path) = urdf_path(&args.model) {
        let robot = parse_urdf_file(&path).map_err(|e| format!("{}: {e}", args.model))?;
        urdf_file_world(&robot, &loaded.model, options).map_err(flag_error)?
    } else {
        FileWorld::without_file(options, Vec::new()).map_err(flag_error)?
    };
    if world
        .collision
        .as_ref()
        .is_some_and(|c| c.geometries.is_empty())
    {
        eprintln!(
            "warning: {}: no collision geometry: nothing touches the ground",
            args.model
        );
    }
    Ok(world)
}
