//! Finding a model from the command line: a URDF file, an MJCF file (`.xml`, chosen by the
//! extension here and nowhere else) or a built-in model name, with the loading options every
//! model command shares (`--floating`, `--inertia`).

use clap::Args;
use rigid::io::mjcf::{self, MjcfModel};
use rigid::io::robots;
use rigid::io::sdf::{self, SdfModel};
use rigid::io::urdf::{self, InertiaPolicy, SiblingOrder, UrdfOptions};
use rigid::multibody::{builtin, builtin_names, MimicModel, Model};
use std::path::Path;

/// How to load a URDF: shared by the commands that take a model.
#[derive(Args, Clone, Copy, Debug)]
pub struct LoadArgs {
    /// Add a free-flyer root joint carrying the URDF's root link.
    #[arg(long)]
    pub floating: bool,
    /// Non-physical inertias in a URDF: `strict` refuses them, `warn` loads them as written
    /// with a warning, `repair` loads the doctor's repair (see `rigid doctor`).
    #[arg(long, default_value = "warn", value_name = "strict|warn|repair")]
    pub inertia: InertiaPolicy,
    /// The order of sibling joints (not a flag: `rigid eval --layout pinocchio` sets it).
    #[arg(skip)]
    pub sibling_order: SiblingOrder,
}

impl LoadArgs {
    /// The URDF options these arguments ask for.
    pub fn urdf_options(&self) -> UrdfOptions {
        UrdfOptions {
            floating: self.floating,
            inertia: self.inertia,
            sibling_order: self.sibling_order,
        }
    }
}

/// True when `spec` names a file (or looks like a URDF path) rather than a built-in model.
pub fn is_file(spec: &str) -> bool {
    let p = Path::new(spec);
    p.exists()
        || spec.ends_with(".urdf")
        || spec.ends_with(".xml")
        || spec.ends_with(".sdf")
        || spec.contains('/')
}

/// Warnings printed on stderr by the commands that are not about the model itself.
const SHOWN_WARNINGS: usize = 5;

/// The model named by `spec`: a URDF file loaded under `args`, or a built-in model. The URDF's
/// warnings go to stderr (the first few, then a count).
///
/// # Errors
/// The URDF error (with its file, link or joint and line), an unknown built-in name, or
/// `--floating` asked of a built-in model.
pub fn load_model(spec: &str, args: &LoadArgs) -> Result<Model, String> {
    Ok(load_printing_warnings(spec, args)?.model)
}

/// As [`load_model`], with the MJCF import when there is one.
///
/// # Errors
/// As [`load_model`].
pub fn load_printing_warnings(spec: &str, args: &LoadArgs) -> Result<Loaded, String> {
    let loaded = load_any(spec, args)?;
    print_warnings(spec, &loaded.warnings);
    Ok(loaded)
}

/// The first few warnings on stderr, then a count.
fn print_warnings(spec: &str, warnings: &[String]) {
    for w in warnings.iter().take(SHOWN_WARNINGS) {
        eprintln!("warning: {spec}: {w}");
    }
    if warnings.len() > SHOWN_WARNINGS {
        eprintln!(
            "warning: {spec}: {} more warnings (`rigid model {spec}` lists them all)",
            warnings.len() - SHOWN_WARNINGS
        );
    }
}

/// The model named by `spec` with its mimic joints as couplings (`--mimic`): a URDF's
/// `<mimic>` elements, an MJCF file's `<equality joint>` elements whose polynomial is linear,
/// an SDF file's gearboxes;
/// a model with neither has no couplings. Warnings as [`load_printing_warnings`].
///
/// # Errors
/// As [`load_model`], and a coupling rigid cannot hold (naming the joint and its line).
pub fn load_mimic(spec: &str, args: &LoadArgs) -> Result<MimicModel, String> {
    if !is_mjcf(spec) && !is_sdf(spec) {
        if let Some(path) = urdf_path(spec) {
            let (mm, warnings) = urdf::load_urdf_mimic(&path, &args.urdf_options())
                .map_err(|e| format!("{spec}: {e}"))?;
            let warnings: Vec<String> = warnings.iter().map(ToString::to_string).collect();
            print_warnings(spec, &warnings);
            return Ok(mm);
        }
    }
    let loaded = load_printing_warnings(spec, args)?;
    let mut mimics = Vec::new();
    if let Some(m) = &loaded.mjcf {
        mimics = m.mimics().map_err(|e| format!("{spec}: {e}"))?;
    }
    if let Some(s) = &loaded.sdf {
        mimics = s.mimics();
    }
    if mimics.is_empty() {
        eprintln!("warning: {spec}: --mimic: the model has no mimic joints");
    }
    MimicModel::new(loaded.model, &mimics).map_err(|e| format!("{spec}: {e}"))
}

/// A model as loaded, with what its file says besides the dynamics.
pub struct Loaded {
    /// The model.
    pub model: Model,
    /// The loader's warnings.
    pub warnings: Vec<String>,
    /// The MJCF import, for an `.xml` file (geoms, MuJoCo's layout, ...).
    pub mjcf: Option<MjcfModel>,
    /// The SDF import, for an `.sdf` file (geometry, loops, home configuration).
    pub sdf: Option<SdfModel>,
}

impl Loaded {
    /// The configuration the file describes: MuJoCo's `qpos0` for MJCF (each body where the
    /// file puts it), rigid's neutral configuration otherwise.
    pub fn home(&self) -> Vec<f64> {
        if let Some(s) = &self.sdf {
            return s.home.clone();
        }
        let mut q = rigid::multibody::neutral(&self.model);
        if let Some(m) = &self.mjcf {
            // qpos0 has the model's length and finite entries: the conversion cannot fail
            let _ = m.layout().q_from_mujoco(&m.qpos0, &mut q);
        }
        q
    }
}

/// True when `spec` names an SDF file: its extension is `.sdf` (any case).
pub fn is_sdf(spec: &str) -> bool {
    Path::new(spec)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("sdf"))
}

/// True when `spec` names an MJCF file: its extension is `.xml` (any case).
pub fn is_mjcf(spec: &str) -> bool {
    Path::new(spec)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
}

/// The model named by `spec` (an MJCF file, a URDF file, a built-in model), its warnings and, for
/// MJCF, the import. `--floating` is refused for MJCF, whose free joints are in the file.
///
/// # Errors
/// As [`load_model`].
pub fn load_any(spec: &str, args: &LoadArgs) -> Result<Loaded, String> {
    if is_mjcf(spec) {
        if args.floating {
            return Err(format!(
                "--floating applies to URDF models; the MJCF file \"{spec}\" declares its free \
                 joints itself"
            ));
        }
        let m = mjcf::load_mjcf(spec).map_err(|e| format!("{spec}: {e}"))?;
        return Ok(Loaded {
            model: m.model.clone(),
            warnings: m.warnings.iter().map(ToString::to_string).collect(),
            mjcf: Some(m),
            sdf: None,
        });
    }
    if is_sdf(spec) {
        if args.floating {
            return Err(format!(
                "--floating applies to URDF models; the SDF file \"{spec}\" floats every link \
                 that no joint holds (and welds them in a <static> model)"
            ));
        }
        let m = sdf::load_sdf(spec).map_err(|e| format!("{spec}: {e}"))?;
        return Ok(Loaded {
            model: m.model.clone(),
            warnings: m.warnings.iter().map(ToString::to_string).collect(),
            mjcf: None,
            sdf: Some(m),
        });
    }
    let (model, warnings) = load_urdf_or_builtin(spec, args)?;
    Ok(Loaded {
        model,
        warnings,
        mjcf: None,
        sdf: None,
    })
}

fn load_urdf_or_builtin(spec: &str, args: &LoadArgs) -> Result<(Model, Vec<String>), String> {
    if let Some(path) = urdf_path(spec) {
        let (model, warnings) = urdf::load_urdf_with(&path, &args.urdf_options())
            .map_err(|e| format!("{spec}: {e}"))?;
        return Ok((model, warnings.iter().map(ToString::to_string).collect()));
    }
    let model = builtin(spec).ok_or_else(|| {
        let erd = if robots::robot(spec).is_some() {
            " (it is a robot of example-robot-data, which was not found: `pip install \
             example-robot-data`, or set EXAMPLE_ROBOT_DATA to its robots/ folder)"
        } else {
            ""
        };
        format!(
            "unknown model \"{spec}\": not a file, and not a built-in model ({}, or {} with \
             example-robot-data){erd}",
            builtin_names().join(", "),
            robots::ROBOTS
                .iter()
                .map(|r| r.name)
                .collect::<Vec<_>>()
                .join(", ")
        )
    })?;
    if args.floating {
        return Err(format!(
            "--floating applies to URDF models; the built-in model \"{spec}\" has a fixed base"
        ));
    }
    Ok((model, Vec::new()))
}

/// The URDF file `spec` names: itself if it is a file (or looks like a path), the file of a
/// robot of example-robot-data known by name ([`robots::ROBOTS`]), else `None` (a built-in
/// model).
pub fn urdf_path(spec: &str) -> Option<std::path::PathBuf> {
    if is_file(spec) {
        return Some(spec.into());
    }
    if builtin(spec).is_some() {
        return None;
    }
    robots::robot(spec)?.urdf()
}
