//! SDFormat (Gazebo's format, read by Drake and Pinocchio 4) import: one `<model>` (at the top or
//! in a `<world>`) read into a [`Model`], its collision geometry and its closed loops as
//! constraint models.
//!
//! # What is read
//!
//! - `<link>`: `<pose>`, `<inertial>` (`<pose>`, `<mass>`, `<inertia>` about the centre of mass
//!   in the inertial frame), `<collision>` (box, sphere, cylinder, capsule, ellipsoid, mesh as its
//!   convex hull; planes and height maps are skipped with a warning).
//! - `<joint>`: `revolute`, `continuous`, `prismatic`, `ball`, `universal` and `revolute2` (both
//!   a rotation about `<axis>` then one about `<axis2>`, which turns with the first: rigid's
//!   universal joint, the axes not necessarily perpendicular), `screw`
//!   (`<screw_thread_pitch>`, m per revolution), `fixed`; `<parent>`, `<child>`, `<pose>`,
//!   `<axis>`/`<axis2>` with `<xyz expressed_in>` (1.7+) or `<use_parent_model_frame>` (1.4–1.6),
//!   `<limit lower upper effort velocity>` (SDFormat's ±1e16 and −1 mean none),
//!   `<dynamics damping friction>`.
//! - `<frame name attached_to>`, and every `<pose relative_to>` (1.7+; `frame` in 1.5–1.6) naming
//!   a link, joint, frame or `__model__`; `degrees="true"` and `rotation_format="quat_xyzw"` (a quaternion off unit length by up to 1e-3 is normalised).
//! - `<model><pose>` places the model in the world; `<static>` welds its root links there; the
//!   `<world>`'s `<gravity>` (without a world, `(0, 0, -9.81)`).
//!
//! - Nested `<model>`s: their links, joints and frames named in their scope (`inner::link`), the
//!   names they refer to read in it, the model placed by its `<pose>` (a frame
//!   `inner::__model__`).
//!
//! - `gearbox` joints: `θ_2 = −ratio · θ_1` as a joint-coordinate constraint between the two
//!   revolute joints that turn its links from the reference body (a mimic under `--mimic`);
//!   another gearbox is left out with a warning saying why.
//!
//! - `<include>` in a model: the one model of the file its `<uri>` names (`model://NAME` in
//!   Gazebo's resource paths, then beside this file; `file://` and paths from this file's folder;
//!   a folder through its `model.config`), read as a nested model named by the include's `<name>`
//!   and placed by its `<pose>` (else the model's own); loops refused.
//!
//! - `<visual>`: pose, primitive or mesh file, colour ([`SdfLink::visuals`], for `rigid convert`).
//!
//! Not read: sensors and plugins; an include's `<placement_frame>` and `<merge>`.
//!
//! # Semantics (as SDFormat and Drake)
//!
//! - Poses: a link's is relative to the model frame by default, a joint's to its child link, a
//!   frame's to what it is attached to (the model by default). `world` is read as the model
//!   frame.
//! - The tree: the joints are walked depth-first from the world, then from every link that is
//!   no joint's child (the canonical link first), in file order. A root link is floating (a
//!   free-flyer named [`ROOT_JOINT_NAME`](crate::io::urdf::ROOT_JOINT_NAME), then
//!   `LINK_root_joint`), unless the model is `<static>`; [`SdfModel::home`] puts it where the
//!   file does.
//! - Each moving joint is one rigid joint whose frame is the SDF joint frame; a fixed joint
//!   welds its child link into the parent body.
//! - A joint whose child is already in the tree closes a loop: a `ball` joint becomes a point
//!   constraint at the joint, a `fixed` joint a weld (frame constraint), a `revolute` joint two
//!   point constraints on its axis 0.1 m apart; any other is left out with a warning.

mod build;
mod include;
mod parse;
mod visual;

use crate::collision::{Geometry, Shape};
use crate::mass::RotationalInertia;
use crate::multibody::constraints::ConstraintModel;
use crate::multibody::Model;
use crate::spatial::Transform;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// An SDF model read and built.
#[derive(Clone, Debug)]
pub struct SdfModel {
    /// The kinematic tree.
    pub model: Model,
    /// The joints that close loops, as constraint models named after them.
    pub constraints: Vec<ConstraintModel>,
    /// The collision geometry, on the model's bodies.
    pub geometries: Vec<Geometry>,
    /// The configuration the file places the model in (floating roots where their links are;
    /// every joint at zero).
    pub home: Vec<f64>,
    /// `<sdf version>`.
    pub version: String,
    /// What was tolerated, each with its line.
    pub warnings: Vec<SdfWarning>,
    /// The file it was read from (`None` for text).
    pub path: Option<PathBuf>,
    /// Every link as the file writes it, for the inertia doctor.
    pub links: Vec<SdfLink>,
}

/// A link as its file writes it: the `<inertial>` and the collision shapes in the link frame
/// (`rigid::doctor::examine_sdf` checks one against the other).
#[derive(Clone, Debug)]
pub struct SdfLink {
    /// Its name in the model's scope (`inner::link` in a nested or included model).
    pub name: String,
    /// Line of the `<link>`.
    pub line: u32,
    /// The file it is written in when it came from an `<include>` (`None`: the file read).
    pub file: Option<PathBuf>,
    /// Its `<inertial>`.
    pub inertial: Option<SdfInertial>,
    /// Each `<collision>`'s pose in the link frame and shape (a mesh as its hull's points).
    pub collisions: Vec<(Transform, Shape)>,
    /// Its `<visual>` elements.
    pub visuals: Vec<SdfVisual>,
}

/// A `<visual>`: what `rigid convert` draws.
#[derive(Clone, Debug)]
pub struct SdfVisual {
    /// `name` (else `link/visual/k`).
    pub name: String,
    /// Its pose in the link frame.
    pub pose: Transform,
    /// A primitive, or a mesh by its file.
    pub shape: crate::io::write::VisualShape,
    /// `<material><diffuse>` (else `<ambient>`), `rgba` in `[0, 1]`.
    pub rgba: Option<[f64; 4]>,
}

/// An `<inertial>` as written.
#[derive(Clone, Debug)]
pub struct SdfInertial {
    /// Its `<pose>` in the link frame: the centre of mass and the axes of `inertia`.
    pub pose: Transform,
    /// `<mass>` (kg; SDFormat's default 1).
    pub mass: f64,
    /// `<inertia>` about the centre of mass in the pose's axes (kg·m²; SDFormat's default the
    /// identity).
    pub inertia: RotationalInertia,
    /// Line of the `<inertial>`.
    pub line: u32,
    /// The numbers as written: `mass`, then `ixx, iyy, izz, ixy, ixz, iyz` (empty where absent).
    pub text: [String; 7],
    /// Its byte range in the file it is written in (for `rigid doctor --fix`).
    pub span: std::ops::Range<usize>,
}

impl SdfModel {
    /// The gearboxes among the [`constraints`](Self::constraints) (a joint coordinate tied
    /// linearly to another's) as [`Mimic`] couplings: `MimicModel::new(model, &mimics)` has no
    /// coordinate for the driven joint (`rigid ... --mimic`, Python's `Model.from_sdf(path,
    /// mimic=True)`).
    #[must_use]
    pub fn mimics(&self) -> Vec<crate::multibody::Mimic> {
        self.constraints
            .iter()
            .filter_map(crate::multibody::Mimic::from_constraint)
            .collect()
    }
}

/// Something in an SDF file that was left out or tolerated.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SdfWarning {
    /// Line (1-based).
    pub line: u32,
    /// The element, with its name.
    pub element: String,
    /// What was done.
    pub message: String,
}

impl std::fmt::Display for SdfWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}: {}: {}", self.line, self.element, self.message)
    }
}

/// Why an SDF file could not be read. Every variant says where.
#[derive(Debug, Error)]
pub enum SdfError {
    /// The file cannot be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// Not well-formed XML.
    #[error("malformed XML: {0}")]
    Xml(#[from] roxmltree::Error),
    /// An element that cannot be read.
    #[error("line {line}: {element}: {message}")]
    Invalid {
        /// Line (1-based).
        line: u32,
        /// The element.
        element: String,
        /// What is wrong.
        message: String,
    },
    /// The model the file describes cannot be built.
    #[error("{0}")]
    Model(String),
}

/// Reads the SDF file at `path` (meshes resolved beside it).
///
/// # Errors
/// [`SdfError`], naming the file, or the element and line.
pub fn load_sdf(path: impl AsRef<Path>) -> Result<SdfModel, SdfError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| SdfError::Io {
        path: path.display().to_string(),
        source,
    })?;
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut m = read(&text, dir, Some(path))?;
    m.path = Some(path.to_path_buf());
    Ok(m)
}

/// Reads SDF text, meshes resolved in `dir`.
///
/// ```
/// let m = rigid::io::sdf::load_sdf_str(r#"<sdf version="1.9"><model name="arm">
///   <link name="base"/>
///   <joint name="weld" type="fixed"><parent>world</parent><child>base</child></joint>
///   <link name="upper"><pose>0 0 1 0 0 0</pose>
///     <inertial><mass>2</mass><pose>0 0 -0.5 0 0 0</pose></inertial></link>
///   <joint name="shoulder" type="revolute"><parent>base</parent><child>upper</child>
///     <axis><xyz>0 1 0</xyz><limit><lower>-1</lower><upper>1</upper></limit></axis></joint>
/// </model></sdf>"#, ".".as_ref()).unwrap();
/// assert_eq!((m.model.nq(), m.model.joints()[0].name.as_str()), (1, "shoulder"));
/// assert_eq!(m.model.lower_limits(), &[-1.0]);
/// ```
///
/// # Errors
/// [`SdfError`], naming the element and line.
pub fn load_sdf_str(text: &str, dir: &Path) -> Result<SdfModel, SdfError> {
    read(text, dir, None)
}

/// Reads SDF text from `file` (if it is one: an include of it is a loop).
fn read(text: &str, dir: &Path, file: Option<&Path>) -> Result<SdfModel, SdfError> {
    let doc = roxmltree::Document::parse(text)?;
    let mut reader = parse::Reader {
        doc: &doc,
        dir,
        warnings: Vec::new(),
        chain: file.into_iter().map(include::canonical).collect(),
        included: std::collections::HashMap::new(),
    };
    let raw = reader.model()?;
    let poses = parse::Poses::resolve(&raw).map_err(|e| in_file(&raw, e))?;
    let mut m = build::build(&raw, &poses, reader.warnings, None).map_err(|e| in_file(&raw, e))?;
    for w in &mut m.warnings {
        if let Some(file) = included_file(&raw, &w.element) {
            w.element = format!("{} in {file}", w.element);
        }
    }
    Ok(m)
}

/// An error about an element written in an `<include>`d file, its element named with the file
/// (the line is that file's).
fn in_file(raw: &parse::Raw, e: SdfError) -> SdfError {
    match e {
        SdfError::Invalid {
            line,
            element,
            message,
        } => match included_file(raw, &element) {
            Some(file) => SdfError::Invalid {
                line,
                element: format!("{element} in {file}"),
                message,
            },
            None => SdfError::Invalid {
                line,
                element,
                message,
            },
        },
        other => other,
    }
}

/// The included file of the element `element` names (`link "fore::upper"`: the quoted name).
fn included_file(raw: &parse::Raw, element: &str) -> Option<String> {
    let name = element.split('"').nth(1)?;
    raw.included.get(name).map(|p| p.display().to_string())
}
