//! Collision geometry from the files: a URDF's `<collision>` elements ([`urdf_geometries`]),
//! an MJCF model's geoms ([`mjcf_geometries`]), a `rigid mass` spec's parts
//! ([`compound_geometries`]), on a built [`Model`].

use super::mesh_file::read_mesh;
#[cfg(feature = "urdf")]
use super::urdf::{resolve_mesh_path, UrdfRobot, UrdfShape};
use crate::collision::{Geometry, Shape};
use crate::mass::{Compound, Geometry as PartGeometry, Shape as PartShape};
use crate::multibody::JointId;
#[cfg(feature = "urdf")]
use crate::multibody::{FrameKind, Model};
use crate::spatial::{Transform, Vec3};
use std::path::Path;

#[cfg(feature = "urdf")]
/// A URDF shape as a collision shape; a mesh is read (path resolved as for the replay:
/// `package://`, `file://`, relative to the URDF) and becomes the convex hull of its scaled
/// vertices. `Err` says why a mesh could not be used.
pub(crate) fn urdf_shape(shape: &UrdfShape, urdf: Option<&Path>) -> Result<Shape, String> {
    Ok(match shape {
        UrdfShape::Box { size } => Shape::Box { size: *size },
        UrdfShape::Cylinder { radius, length } => Shape::Cylinder {
            radius: *radius,
            length: *length,
        },
        UrdfShape::Sphere { radius } => Shape::Sphere { radius: *radius },
        UrdfShape::Capsule { radius, length } => Shape::Capsule {
            radius: *radius,
            length: *length,
        },
        UrdfShape::Mesh { filename, scale } => {
            let path = resolve_mesh_path(filename, urdf)
                .ok_or_else(|| format!("mesh {filename} not found"))?;
            let mesh = read_mesh(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            Shape::ConvexHull {
                points: mesh
                    .vertices
                    .iter()
                    .map(|v| v.component_mul(scale))
                    .collect(),
            }
        }
    })
}

/// The collision geometry of a URDF robot on its `model` (built from it): every `<collision>`
/// of every link, on the body the link belongs to (a link welded by fixed joints is on its
/// moving ancestor, in the world when welded to it), placed at the link frame times the
/// element's `<origin>`, a mesh as its convex hull. Returns the geometries (named
/// `link/index`) and the warnings: each element that could not be used (a mesh not found or
/// unreadable, a degenerate shape), naming the link and line, which is skipped; and one for the
/// meshes that are not convex, naming them (their hulls fill their dents).
#[cfg(feature = "urdf")]
#[must_use]
pub fn urdf_geometries(robot: &UrdfRobot, model: &Model) -> (Vec<Geometry>, Vec<String>) {
    let (mut out, mut warnings) = (Vec::new(), Vec::new());
    for link in &robot.links {
        if link.collisions.is_empty() {
            continue;
        }
        let Some(frame) = model.frame_id_of_kind(&link.name, FrameKind::Body) else {
            warnings.push(format!(
                "link \"{}\" (line {}): not a body of the model: its collision geometry is skipped",
                link.name, link.line
            ));
            continue;
        };
        let frame = &model.frames()[frame.0];
        for (k, c) in link.collisions.iter().enumerate() {
            match urdf_shape(&c.shape, robot.path.as_deref()) {
                Ok(shape) => {
                    let name = format!("{}/{k}", link.name);
                    if let Err(e) = shape.check() {
                        warnings.push(format!(
                            "link \"{}\" (line {}): collision skipped: {e}",
                            link.name, c.line
                        ));
                        continue;
                    }
                    out.push(Geometry::new(
                        name,
                        frame.parent,
                        frame.placement * c.origin,
                        shape,
                    ));
                }
                Err(e) => warnings.push(format!(
                    "link \"{}\" (line {}): collision skipped: {e}",
                    link.name, c.line
                )),
            }
        }
    }
    warnings.extend(hull_warning(&out));
    (out, warnings)
}

/// A mesh whose deepest vertex lies inside its convex hull by more than this share of the
/// hull's size (the diagonal of its bounding box) is not convex.
const CONCAVE: f64 = 1e-3;

/// The warning for the meshes among `geometries` that are not convex (a vertex deeper inside
/// their hull than [`CONCAVE`] of its size, [`Shape::concavity`]): they collide as their
/// convex hulls, which fill their dents. Names each (at most five, then how many more) with
/// the depth of its deepest vertex.
fn hull_warning(geometries: &[Geometry]) -> Option<String> {
    let concave: Vec<(&str, f64)> = geometries
        .iter()
        .filter_map(|g| {
            let Shape::ConvexHull { points } = &g.shape else {
                return None;
            };
            let (lo, hi) = points.iter().fold(
                (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
                |(lo, hi), p| (lo.inf(p), hi.sup(p)),
            );
            let depth = g.shape.concavity();
            (depth > CONCAVE * (hi - lo).norm()).then_some((g.name.as_str(), depth))
        })
        .collect();
    if concave.is_empty() {
        return None;
    }
    let mut named: Vec<String> = concave
        .iter()
        .take(5)
        .map(|(name, d)| format!("{name} ({:.2} mm)", 1e3 * d))
        .collect();
    if concave.len() > 5 {
        named.push(format!("and {} more", concave.len() - 5));
    }
    let n = concave.len();
    let (meshes, are) = if n == 1 {
        ("mesh", "is")
    } else {
        ("meshes", "are")
    };
    Some(format!(
        "{n} collision {meshes} {are} not convex: each collides as its convex hull, which fills \
         its dents (the deepest given): {}",
        named.join(", ")
    ))
}

/// The collision geometry of a body made of parts (a `rigid mass` spec) moved by `body`, whose
/// joint frame is at `origin` of the spec frame with the spec's axes (the CoM for a free body,
/// the pivot for a pivoted one): one geometry per part with a volume, at its pose. `meshes`
/// holds, per part, the vertices of a mesh part (`None` for the others; see
/// [`spec_mesh_vertices`]); a mesh part without them, points, rods and given inertias do not
/// collide (a warning each), and the meshes that are not convex are named in one warning.
#[must_use]
pub fn compound_geometries(
    compound: &Compound,
    meshes: &[Option<Vec<Vec3>>],
    body: JointId,
    origin: Vec3,
) -> (Vec<Geometry>, Vec<String>) {
    let (mut out, mut warnings) = (Vec::new(), Vec::new());
    let to_joint = Transform::from_translation(-origin);
    for (i, p) in compound.parts.iter().enumerate() {
        let name = p.name.clone().unwrap_or_else(|| format!("part {}", i + 1));
        let shape = match &p.geometry {
            PartGeometry::Shape(s) => match *s {
                PartShape::Box { size } => Some(Shape::Box { size }),
                PartShape::Cylinder { radius, length } => Some(Shape::Cylinder { radius, length }),
                PartShape::Sphere { radius } => Some(Shape::Sphere { radius }),
                PartShape::Ellipsoid { semi_axes } => Some(Shape::Ellipsoid { semi_axes }),
                PartShape::Capsule { radius, length } => Some(Shape::Capsule { radius, length }),
                PartShape::Cone { radius, height } => Some(Shape::Cone { radius, height }),
                PartShape::ThinRod { .. } | PartShape::Point => None,
            },
            PartGeometry::Mesh(_) => meshes
                .get(i)
                .cloned()
                .flatten()
                .map(|points| Shape::ConvexHull { points }),
            PartGeometry::Inertia(_) => None,
        };
        match shape {
            Some(shape) => out.push(Geometry::new(name, Some(body), to_joint * p.pose, shape)),
            None => warnings.push(format!("{name}: has no shape to collide with (skipped)")),
        }
    }
    warnings.extend(hull_warning(&out));
    (out, warnings)
}

/// A body made of parts (a `rigid mass` spec file) as a model of one free-flyer joint `"body"`
/// whose frame is at the centre of mass with the spec's axes (`q = (x, y, z, qx, qy, qz, qw)` is
/// the CoM's position and the spec axes' orientation in the world), and the collision geometry
/// of its parts ([`compound_geometries`]) with their warnings: `rigid simulate SPEC.toml
/// --ground`.
///
/// # Errors
/// The spec or a mesh cannot be read, its mass properties are not physical (the messages of
/// [`read_spec`](super::spec::read_spec) and `Compound::mass_properties`, with the file), or
/// no part has a shape that collides (points and given inertias do not).
#[cfg(feature = "spec")]
pub fn spec_body(
    path: &Path,
) -> Result<(crate::multibody::Model, Vec<Geometry>, Vec<String>), String> {
    use crate::mass::SpatialInertia;
    use crate::multibody::{JointType, ModelBuilder};
    let compound = super::spec::read_spec(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let props = compound
        .mass_properties()
        .map_err(|e| format!("{}: {}", path.display(), compound.error_message(&e)))?;
    let g = SpatialInertia::from_com(props.mass, Vec3::zeros(), props.inertia_com);
    let name = path
        .file_stem()
        .map_or("body".into(), |s| s.to_string_lossy().into_owned());
    let mut b = ModelBuilder::new(&name);
    let joint = b
        .add_joint(None, "body", JointType::FreeFlyer, Transform::identity(), g)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let model = b.build().map_err(|e| format!("{}: {e}", path.display()))?;
    let meshes = spec_mesh_vertices(path)?;
    let (geometries, warnings) = compound_geometries(&compound, &meshes, joint, props.com);
    if geometries.is_empty() {
        return Err(format!(
            "{}: no part has a shape to collide with the ground",
            path.display()
        ));
    }
    Ok((model, geometries, warnings))
}

/// The vertices of each mesh part of a spec file (`None` for the other parts), read again from
/// the files its `[[part]]` tables name (relative to the spec's folder), for
/// [`compound_geometries`].
///
/// # Errors
/// The spec or a mesh cannot be read (the spec parser, [`read_spec`](super::spec::read_spec),
/// reports the same errors with the part and line).
#[cfg(feature = "spec")]
pub fn spec_mesh_vertices(path: &Path) -> Result<Vec<Option<Vec<Vec3>>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let table: toml::Table = text
        .parse()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    let parts = table
        .get("part")
        .and_then(toml::Value::as_array)
        .cloned()
        .unwrap_or_default();
    parts
        .iter()
        .map(|p| {
            let mesh = p.get("shape").and_then(toml::Value::as_str) == Some("mesh");
            match (mesh, p.get("file").and_then(toml::Value::as_str)) {
                (true, Some(file)) => {
                    let f = dir.join(file);
                    read_mesh(&f)
                        .map(|m| Some(m.vertices))
                        .map_err(|e| format!("{}: {e}", f.display()))
                }
                _ => Ok(None),
            }
        })
        .collect()
}

/// The collision geometry of an MJCF model: each geom on the rigid joint it is fixed in, at its
/// placement, with its `contype` and `conaffinity` (MuJoCo's collision filter), a mesh as the
/// convex hull of its vertices (as MuJoCo collides meshes). Returns the geometries (named by the
/// geom, else `geom LINE`) and the warnings. Geoms with `contype = conaffinity = 0` (drawn,
/// never colliding) and planes (the ground of [`mjcf_world`]) are left out; height fields and
/// a mesh that cannot be read are skipped with a warning. Each
/// geometry has its geom's sliding `friction`.
#[cfg(feature = "mjcf")]
#[must_use]
pub fn mjcf_geometries(mjcf: &super::mjcf::MjcfModel) -> (Vec<Geometry>, Vec<String>) {
    let (out, _, warnings) = mjcf_geoms(mjcf);
    (out, warnings)
}

/// A geom's primitive (sphere, capsule, cylinder, ellipsoid, box) as a collision shape, MuJoCo's
/// half-lengths made lengths; `None` for a mesh, plane or height field.
#[cfg(feature = "mjcf")]
pub(crate) fn mjcf_primitive(shape: &super::mjcf::MjcfShape) -> Option<Shape> {
    use super::mjcf::MjcfShape;
    Some(match *shape {
        MjcfShape::Sphere { radius } => Shape::Sphere { radius },
        MjcfShape::Capsule {
            radius,
            half_length,
        } => Shape::Capsule {
            radius,
            length: 2.0 * half_length,
        },
        MjcfShape::Cylinder {
            radius,
            half_length,
        } => Shape::Cylinder {
            radius,
            length: 2.0 * half_length,
        },
        MjcfShape::Ellipsoid { radii } => Shape::Ellipsoid { semi_axes: radii },
        MjcfShape::Box { half } => Shape::Box { size: 2.0 * half },
        MjcfShape::Mesh { .. } | MjcfShape::Plane { .. } | MjcfShape::Hfield { .. } => return None,
    })
}

/// [`mjcf_geometries`], with the index in `mjcf.geoms` of each geometry's geom.
#[cfg(feature = "mjcf")]
fn mjcf_geoms(mjcf: &super::mjcf::MjcfModel) -> (Vec<Geometry>, Vec<usize>, Vec<String>) {
    use super::mjcf::MjcfShape;
    let (mut out, mut from, mut warnings) = (Vec::new(), Vec::new(), Vec::new());
    for (i, g) in mjcf.geoms.iter().enumerate() {
        if g.contype == 0 && g.conaffinity == 0 {
            continue; // a visual geom: it collides with nothing in MuJoCo, the floor included
        }
        if matches!(g.shape, MjcfShape::Plane { .. }) {
            continue; // the ground of `mjcf_world`
        }
        let name = g.name.clone().unwrap_or_else(|| format!("geom {}", g.line));
        let shape = match &g.shape {
            MjcfShape::Sphere { .. }
            | MjcfShape::Capsule { .. }
            | MjcfShape::Cylinder { .. }
            | MjcfShape::Ellipsoid { .. }
            | MjcfShape::Box { .. } => {
                mjcf_primitive(&g.shape).ok_or_else(|| "not a primitive".into())
            }
            MjcfShape::Mesh {
                file,
                inline,
                scale,
                refpos,
                refrot,
                ..
            } => inline
                .clone()
                .map_or_else(|| read_mesh(file), Ok)
                .map(|m| Shape::ConvexHull {
                    points: m
                        .vertices
                        .iter()
                        .map(|v| (refrot.transpose() * (v - refpos)).component_mul(scale))
                        .collect(),
                })
                .map_err(|e| format!("{}: {e}", file.display())),
            MjcfShape::Plane { .. } => Err("a plane is the ground (mjcf_world)".into()),
            MjcfShape::Hfield { .. } => Err("height fields are not read".into()),
        };
        match shape.and_then(|s| s.check().map(|()| s)) {
            Ok(shape) => {
                let mut geometry = Geometry::new(name, g.parent, g.placement, shape);
                geometry.contype = u32::try_from(g.contype).unwrap_or(0);
                geometry.conaffinity = u32::try_from(g.conaffinity).unwrap_or(0);
                geometry.friction = Some(g.friction);
                out.push(geometry);
                from.push(i);
            }
            Err(e) => warnings.push(format!("{name} (line {}): collision skipped: {e}", g.line)),
        }
    }
    (out, from, warnings)
}

/// What a robot file describes beyond its tree, for a simulation: its collision model (with
/// the [`WorldOptions`]), its bilateral constraints (an MJCF file's `<equality>` elements) with
/// the settings that hold them, its time step (MJCF `<option timestep>`), and the warnings of
/// what was left out.
#[derive(Clone, Debug)]
pub struct FileWorld {
    /// The collision model, `None` when nothing can touch.
    pub collision: Option<crate::collision::CollisionModel>,
    /// The bilateral constraints the file declares.
    pub constraints: Vec<crate::multibody::constraints::ConstraintModel>,
    /// Their solver: proximal, `μ = 1e-6` (a loop's redundant rows, as a planar four-bar's in
    /// 3D, need no care).
    pub constraint_settings: crate::multibody::constraints::ProximalSettings,
    /// The file's time step (s), if it gives one.
    pub timestep: Option<f64>,
    /// The configuration the file places the model in (an MJCF file's `qpos0`, in rigid's
    /// layout), if it gives one.
    pub home: Option<Vec<f64>>,
    /// What was left out, each naming its element and line.
    pub warnings: Vec<String>,
}

impl FileWorld {
    /// The world of a model without a file (a built-in model, a body spec's parts): `geometries`
    /// on the ground of `options` when it gives one ([`ground_model`]), else nothing to touch.
    ///
    /// # Errors
    /// As [`ground_model`].
    pub fn without_file(
        options: &WorldOptions,
        geometries: Vec<Geometry>,
    ) -> Result<Self, WorldError> {
        let collision = match options.ground {
            Some(_) => Some(ground_model(
                options.ground,
                options.friction,
                options.restitution,
                geometries,
            )?),
            None => None,
        };
        Ok(Self {
            collision,
            constraints: Vec::new(),
            constraint_settings: crate::multibody::constraints::ProximalSettings::default(),
            timestep: None,
            home: None,
            warnings: Vec::new(),
        })
    }

    /// The time step of a run: `given`, else the file's, else 1 ms.
    #[must_use]
    pub fn time_step(&self, given: Option<f64>) -> f64 {
        given.or(self.timestep).unwrap_or(1e-3)
    }

    /// Refuses a friction or restitution given for a world where nothing can touch.
    ///
    /// # Errors
    /// [`WorldError::NothingToTouch`] naming the option.
    pub fn check_materials(&self, options: &WorldOptions) -> Result<(), WorldError> {
        if self.collision.is_some() {
            return Ok(());
        }
        match (options.friction, options.restitution) {
            (Some(_), _) => Err(WorldError::NothingToTouch { option: "friction" }),
            (None, Some(_)) => Err(WorldError::NothingToTouch {
                option: "restitution",
            }),
            (None, None) => Ok(()),
        }
    }
}

/// The world of an MJCF file ([`mjcf_world`], its active `<equality>` elements, its
/// `timestep`).
///
/// # Errors
/// As [`mjcf_world`]; an `<equality>` naming nothing.
#[cfg(feature = "mjcf")]
pub fn mjcf_file_world(
    mjcf: &super::mjcf::MjcfModel,
    options: &WorldOptions,
) -> Result<FileWorld, WorldError> {
    let (collision, mut warnings) = mjcf_world(mjcf, options)?;
    let (constraints, skipped) = mjcf.constraint_models()?;
    warnings.extend(skipped.iter().map(ToString::to_string));
    let mut home = crate::multibody::neutral(&mjcf.model);
    mjcf.layout()
        .q_from_mujoco(&mjcf.qpos0, &mut home)
        .map_err(|e| WorldError::File {
            path: "qpos0".into(),
            message: e.to_string(),
        })?;
    Ok(FileWorld {
        home: Some(home),
        collision,
        constraints,
        constraint_settings: crate::multibody::constraints::ProximalSettings::redundant(),
        timestep: mjcf.timestep,
        warnings,
    })
}

/// The world of a URDF robot ([`urdf_world`]; a URDF declares no loops, step or placement).
///
/// # Errors
/// As [`urdf_world`].
#[cfg(feature = "urdf")]
pub fn urdf_file_world(
    robot: &UrdfRobot,
    model: &Model,
    options: &WorldOptions,
) -> Result<FileWorld, WorldError> {
    let (collision, warnings) = urdf_world(robot, model, options)?;
    Ok(FileWorld {
        collision,
        warnings,
        ..FileWorld::without_file(&WorldOptions::default(), Vec::new())?
    })
}

/// The world of an SDF model: its collision geometry on the ground and between its bodies as
/// `options` ask (as a URDF's, [`urdf_world`]), its loops as constraints, and its home
/// configuration.
///
/// # Errors
/// As [`ground_model`].
#[cfg(feature = "urdf")]
pub fn sdf_file_world(
    sdf: &super::sdf::SdfModel,
    options: &WorldOptions,
) -> Result<FileWorld, WorldError> {
    let collision = geometries_world(sdf.geometries.clone(), options)?;
    Ok(FileWorld {
        collision,
        constraints: sdf.constraints.clone(),
        constraint_settings: crate::multibody::constraints::ProximalSettings::redundant(),
        timestep: None,
        home: Some(sdf.home.clone()),
        warnings: Vec::new(),
    })
}

/// The world of the robot file at `path` that `model` was built from: an MJCF file's
/// ([`mjcf_file_world`], by the `.xml` extension), an SDF file's ([`sdf_file_world`], `.sdf`),
/// else a URDF's ([`urdf_world`]).
///
/// # Errors
/// The file cannot be read or parsed (the message names it), or as [`mjcf_world`] and
/// [`urdf_world`].
#[cfg(all(feature = "urdf", feature = "mjcf"))]
pub fn file_world(
    path: &Path,
    model: &Model,
    options: &WorldOptions,
) -> Result<FileWorld, WorldError> {
    let unreadable = |e: String| WorldError::File {
        path: path.display().to_string(),
        message: e,
    };
    let ext = |x: &str| path.extension().is_some_and(|e| e.eq_ignore_ascii_case(x));
    if ext("xml") {
        let m = super::mjcf::load_mjcf(path).map_err(|e| unreadable(e.to_string()))?;
        mjcf_file_world(&m, options)
    } else if ext("sdf") {
        let m = super::sdf::load_sdf(path).map_err(|e| unreadable(e.to_string()))?;
        sdf_file_world(&m, options)
    } else {
        let robot = super::urdf::parse_urdf_file(path).map_err(|e| unreadable(e.to_string()))?;
        urdf_file_world(&robot, model, options)
    }
}

/// The collision geometry of the robot file at `path` that `model` was built from, with the
/// warnings of what was skipped: an MJCF file's geoms ([`mjcf_geometries`], by the `.xml`
/// extension), else a URDF's `<collision>` elements ([`urdf_geometries`]).
///
/// # Errors
/// The file cannot be read or parsed (the message names it).
#[cfg(all(feature = "urdf", feature = "mjcf"))]
pub fn file_geometries(
    path: &Path,
    model: &Model,
) -> Result<(Vec<Geometry>, Vec<String>), WorldError> {
    let unreadable = |e: String| WorldError::File {
        path: path.display().to_string(),
        message: e,
    };
    let ext = |x: &str| path.extension().is_some_and(|e| e.eq_ignore_ascii_case(x));
    if ext("xml") {
        let m = super::mjcf::load_mjcf(path).map_err(|e| unreadable(e.to_string()))?;
        Ok(mjcf_geometries(&m))
    } else if ext("sdf") {
        let m = super::sdf::load_sdf(path).map_err(|e| unreadable(e.to_string()))?;
        Ok((m.geometries, Vec::new()))
    } else {
        let robot = super::urdf::parse_urdf_file(path).map_err(|e| unreadable(e.to_string()))?;
        Ok(urdf_geometries(&robot, model))
    }
}

/// What a simulation's world adds to a robot file: `rigid simulate`'s `--ground`, `--friction`,
/// `--restitution` and `--self-collision`, Python's `ground=`, `friction=`, `restitution=`,
/// `self_collision=`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WorldOptions {
    /// A horizontal ground `z = height` under the robot (a file's own floor is read without it).
    pub ground: Option<f64>,
    /// Coulomb friction of every contact (default: the file's, else
    /// [`DEFAULT_FRICTION`](crate::collision::DEFAULT_FRICTION)).
    pub friction: Option<f64>,
    /// Newton restitution of every contact (default 0).
    pub restitution: Option<f64>,
    /// Contacts between the robot's own bodies (a URDF's are off by default; an MJCF file's
    /// follow its masks, always on).
    pub self_collision: bool,
}

/// What is wrong with a world: an option out of range, or an element of the file that names
/// nothing or that the solver cannot handle.
#[derive(Debug, thiserror::Error)]
pub enum WorldError {
    /// A friction that is negative or not finite.
    #[error("friction must be finite and >= 0, got {0}")]
    Friction(f64),
    /// A restitution outside `[0, 1]`.
    #[error("restitution must be in [0, 1], got {0}")]
    Restitution(f64),
    /// A ground height that is not finite.
    #[error("the ground height must be finite, got {0}")]
    Height(f64),
    /// An element of the file (its tag or name, and its line).
    #[error("{element} (line {line}): {message}")]
    Element {
        /// The element.
        element: String,
        /// Its line.
        line: u32,
        /// What is wrong.
        message: String,
    },
    /// A friction or restitution for a world where nothing can touch.
    #[error("{option} applies when something can touch (a ground, or a file with a floor)")]
    NothingToTouch {
        /// `friction` or `restitution`.
        option: &'static str,
    },
    /// A file that cannot be read or parsed.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
    /// An MJCF `<equality>` element that names nothing (its line in the message).
    #[cfg(feature = "mjcf")]
    #[error(transparent)]
    Equality(#[from] super::mjcf::MjcfError),
    /// A bad collision model (a shape, a placement).
    #[error(transparent)]
    Collision(#[from] crate::collision::CollisionError),
}

impl WorldOptions {
    fn check(&self) -> Result<(), WorldError> {
        if let Some(f) = self.friction.filter(|f| !(f.is_finite() && *f >= 0.0)) {
            return Err(WorldError::Friction(f));
        }
        if let Some(e) = self.restitution.filter(|e| !(0.0..=1.0).contains(e)) {
            return Err(WorldError::Restitution(e));
        }
        if let Some(h) = self.ground.filter(|h| !h.is_finite()) {
            return Err(WorldError::Height(h));
        }
        Ok(())
    }
}

/// The world of an MJCF file as MuJoCo collides it: its geoms ([`mjcf_geometries`], each with
/// its friction; the larger of two is a contact's, MuJoCo's rule), its `plane` in the world as
/// the ground (its friction the plane's), every pair of geoms on different bodies that are not
/// parent and child (MuJoCo's bodies welded together, a body with several joints one body)
/// and whose `contype`/`conaffinity` match, less `<contact><exclude>`'s body
/// pairs, plus `<contact><pair>`'s geom pairs. `options.ground` adds a horizontal ground to a
/// file without a floor; `friction` and `restitution` replace every contact's. `None` when
/// nothing can touch (no ground and no pair of geoms on two bodies). Returns the warnings of
/// the geoms left out.
///
/// # Errors
/// A bad option; a plane on a moving body, a second plane, or `--ground` with the file's own
/// floor (rigid's contact model has one ground half-space); an `<exclude>` or `<pair>` naming
/// a body or geom the file does not have (each named with its line).
#[cfg(feature = "mjcf")]
pub fn mjcf_world(
    mjcf: &super::mjcf::MjcfModel,
    options: &WorldOptions,
) -> Result<(Option<crate::collision::CollisionModel>, Vec<String>), WorldError> {
    use super::mjcf::MjcfShape;
    use crate::collision::{CollisionModel, Ground, DEFAULT_FRICTION};
    options.check()?;
    let element = |tag: &str, name: &Option<String>, line: u32, message: String| {
        let element = match name {
            Some(n) => format!("<{tag} name=\"{n}\">"),
            None => format!("<{tag}>"),
        };
        WorldError::Element {
            element,
            line,
            message,
        }
    };
    let mut ground = None;
    for g in &mjcf.geoms {
        if !matches!(g.shape, MjcfShape::Plane { .. }) || (g.contype == 0 && g.conaffinity == 0) {
            continue;
        }
        let why = if g.parent.is_some() {
            "a plane on a moving body: rigid's ground is a half-space fixed in the world"
        } else if ground.is_some() {
            "a second plane: rigid's contact model has one ground half-space"
        } else if options.ground.is_some() {
            "the file has its own floor: --ground (ground=) adds one only to a file without"
        } else {
            let normal = g.placement.rotation * Vec3::z();
            let friction = options.friction.unwrap_or(g.friction);
            ground = Some(Ground {
                height: normal.dot(&g.placement.translation),
                normal,
                friction,
                restitution: options.restitution.unwrap_or(0.0),
            });
            continue;
        };
        return Err(element("geom", &g.name, g.line, why.into()));
    }
    if let Some(h) = options.ground {
        let mut plane = Ground::horizontal(h, options.friction.unwrap_or(DEFAULT_FRICTION));
        plane.restitution = options.restitution.unwrap_or(0.0);
        ground = Some(plane);
    }
    // the geometries and, for each, the geom it came from
    let (mut geometries, from, mut warnings) = mjcf_geoms(mjcf);
    if options.friction.is_some() || options.restitution.is_some() {
        for g in &mut geometries {
            g.friction = options.friction.or(g.friction);
            g.restitution = options.restitution;
        }
    }
    let body_of = |name: &str, line: u32, tag: &str| {
        mjcf.bodies
            .iter()
            .position(|b| b.name == name)
            .ok_or_else(|| WorldError::Element {
                element: format!("<{tag}>"),
                line,
                message: format!("no body named \"{name}\""),
            })
    };
    let mut excluded = Vec::new();
    for x in &mjcf.contact.excludes {
        let (b1, b2) = (
            body_of(&x.body1, x.line, "exclude")?,
            body_of(&x.body2, x.line, "exclude")?,
        );
        if b1 == 0 || b2 == 0 {
            warnings.push(format!(
                "<exclude> (line {}): with the world: rigid's ground touches every geom, and \
                 this exclusion applies only to geoms fixed in the world",
                x.line
            ));
        }
        for (i, gi) in from.iter().enumerate() {
            for (j, gj) in from.iter().enumerate() {
                let (a, b) = (mjcf.geoms[*gi].body, mjcf.geoms[*gj].body);
                if i < j && ((a, b) == (b1, b2) || (a, b) == (b2, b1)) {
                    excluded.push((i, j));
                }
            }
        }
    }
    let mut included = Vec::new();
    let plane = |name: &str| {
        mjcf.geoms
            .iter()
            .any(|g| g.name.as_deref() == Some(name) && matches!(g.shape, MjcfShape::Plane { .. }))
    };
    for p in &mjcf.contact.pairs {
        if plane(&p.geom1) || plane(&p.geom2) {
            warnings.push(format!(
                "<pair> (line {}): with the floor: rigid's ground touches every geom already \
                 (the pair is not needed)",
                p.line
            ));
            continue;
        }
        let find = |name: &str| {
            let geom = mjcf
                .geoms
                .iter()
                .position(|g| g.name.as_deref() == Some(name));
            let Some(geom) = geom else {
                return Err(WorldError::Element {
                    element: "<pair>".into(),
                    line: p.line,
                    message: format!("no geom named \"{name}\""),
                });
            };
            from.iter()
                .position(|&g| g == geom)
                .ok_or_else(|| WorldError::Element {
                    element: "<pair>".into(),
                    line: p.line,
                    message: format!("geom \"{name}\" does not collide (a plane, or skipped)"),
                })
        };
        included.push((find(&p.geom1)?, find(&p.geom2)?));
        if p.friction.is_some() {
            warnings.push(format!(
                "<pair> (line {}): its friction is not used (a contact takes the larger of its \
                 two geoms')",
                p.line
            ));
        }
    }
    // MuJoCo's parent filter is on bodies welded together (a body without joints is welded to
    // its parent): the geoms of a weld and of its parent weld never collide, unless that parent
    // is the world. rigid's own filter (parent and child joints) misses a body with several
    // joints (a hip's three hinges: its geoms against the pelvis's)
    let weld_parent: Vec<Option<crate::multibody::JointId>> = (0..mjcf.model.njoints())
        .map(|j| {
            let j = Some(crate::multibody::JointId(j));
            let mut top = mjcf.bodies.iter().position(|b| b.joint == j)?;
            while let Some(p) = mjcf.bodies[top]
                .parent
                .filter(|&p| mjcf.bodies[p].joint == j)
            {
                top = p;
            }
            mjcf.bodies[top].parent.and_then(|p| mjcf.bodies[p].joint)
        })
        .collect();
    for (i, a) in geometries.iter().enumerate() {
        for (k, b) in geometries.iter().enumerate().skip(i + 1) {
            if let (Some(x), Some(y)) = (a.body, b.body) {
                let family = x != y && (weld_parent[x.0] == Some(y) || weld_parent[y.0] == Some(x));
                if family && !excluded.contains(&(i, k)) {
                    excluded.push((i, k));
                }
            }
        }
    }
    let mut cm = CollisionModel::new(ground);
    cm.self_collision = true;
    cm.friction = options.friction.unwrap_or(DEFAULT_FRICTION);
    cm.restitution = options.restitution.unwrap_or(0.0);
    cm.geometries = geometries;
    cm.excluded = excluded;
    cm.included = included;
    // something can touch: a ground, or a pair the filters let through
    let touches =
        cm.ground.is_some() || crate::collision::CollisionData::new(&mjcf.model, &cm)?.pairs() > 0;
    cm.check(mjcf.model.njoints())?;
    Ok((touches.then_some(cm), warnings))
}

/// The world of a URDF robot: its `<collision>` elements ([`urdf_geometries`]) on a horizontal
/// ground when `options.ground` is given (friction and restitution of every contact from the
/// options, [`DEFAULT_FRICTION`](crate::collision::DEFAULT_FRICTION) and 0 by default), the
/// robot's bodies against each other when `options.self_collision` (not parent and child).
/// `None` without a ground and without self-collision. Returns the warnings of the elements
/// left out.
///
/// # Errors
/// A bad option.
#[cfg(feature = "urdf")]
pub fn urdf_world(
    robot: &UrdfRobot,
    model: &Model,
    options: &WorldOptions,
) -> Result<(Option<crate::collision::CollisionModel>, Vec<String>), WorldError> {
    options.check()?;
    if options.ground.is_none() && !options.self_collision {
        return Ok((None, Vec::new()));
    }
    let (geometries, warnings) = urdf_geometries(robot, model);
    Ok((geometries_world(geometries, options)?, warnings))
}

/// `geometries` on the ground and between the bodies as `options` ask (`None`: neither asked).
///
/// # Errors
/// As [`ground_model`], and options that are not valid.
fn geometries_world(
    geometries: Vec<Geometry>,
    options: &WorldOptions,
) -> Result<Option<crate::collision::CollisionModel>, WorldError> {
    options.check()?;
    if options.ground.is_none() && !options.self_collision {
        return Ok(None);
    }
    let mut cm = ground_model(
        options.ground,
        options.friction,
        options.restitution,
        geometries,
    )?;
    cm.self_collision = options.self_collision;
    Ok(Some(cm))
}

/// Excludes from `cm` the pairs of links an SRDF file disables (`<disable_collisions link1
/// link2>`, MoveIt's and Pinocchio's `removeCollisionPairs`): every pair of geometries of the two
/// links (a URDF geometry is named `link/k`, [`urdf_geometries`]). Returns the number of
/// geometry pairs excluded.
///
/// # Errors
/// The file cannot be read or is not XML; a `<disable_collisions>` without `link1` or `link2`
/// (named with its line).
pub fn exclude_srdf_pairs(
    cm: &mut crate::collision::CollisionModel,
    srdf: &Path,
) -> Result<usize, WorldError> {
    let read = super::srdf::read_srdf(srdf).map_err(|e| match e {
        super::srdf::SrdfError::File { path, message } => WorldError::File { path, message },
        super::srdf::SrdfError::Element {
            element,
            line,
            message,
            ..
        } => WorldError::Element {
            element: format!("<{element}>"),
            line,
            message,
        },
    })?;
    let link_of = |g: &Geometry| {
        g.name
            .rsplit_once('/')
            .map_or(g.name.clone(), |(l, _)| l.into())
    };
    let links: Vec<String> = cm.geometries.iter().map(link_of).collect();
    let mut n = 0;
    for (l1, l2, _) in &read.disabled {
        let (l1, l2) = (l1.as_str(), l2.as_str());
        for i in 0..links.len() {
            for j in i + 1..links.len() {
                let (a, b) = (links[i].as_str(), links[j].as_str());
                if ((a, b) == (l1, l2) || (a, b) == (l2, l1)) && !cm.excluded.contains(&(i, j)) {
                    cm.excluded.push((i, j));
                    n += 1;
                }
            }
        }
    }
    Ok(n)
}

/// The collision model of `rigid simulate --ground HEIGHT --friction MU --restitution E` and of
/// Python's `simulate(ground=, friction=, restitution=)`: the horizontal ground `z = height`,
/// `geometries` (the robot's), `friction` (default [`DEFAULT_FRICTION`](crate::collision::DEFAULT_FRICTION)) and `restitution`
/// (default 0) for every contact, no contact between the robot's own bodies. Without a height,
/// no ground.
///
/// # Errors
/// A friction that is negative or not finite, a restitution outside `[0, 1]`, a height that is
/// not finite.
pub fn ground_model(
    height: Option<f64>,
    friction: Option<f64>,
    restitution: Option<f64>,
    geometries: Vec<Geometry>,
) -> Result<crate::collision::CollisionModel, WorldError> {
    use crate::collision::{CollisionModel, Ground, DEFAULT_FRICTION};
    WorldOptions {
        ground: height,
        friction,
        restitution,
        self_collision: false,
    }
    .check()?;
    let friction = friction.unwrap_or(DEFAULT_FRICTION);
    let restitution = restitution.unwrap_or(0.0);
    let ground = height.map(|h| Ground {
        restitution,
        ..Ground::horizontal(h, friction)
    });
    let mut cm = CollisionModel::new(ground);
    cm.self_collision = false;
    cm.friction = friction;
    cm.restitution = restitution;
    cm.geometries = geometries;
    Ok(cm)
}
