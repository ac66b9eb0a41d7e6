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
fn urdf_shape(shape: &UrdfShape, urdf: Option<&Path>) -> Result<Shape, String> {
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
/// unreadable, a degenerate shape), naming the link and line, which is skipped.
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
    (out, warnings)
}

/// The collision geometry of a body made of parts (a `rigid mass` spec) moved by `body`, whose
/// joint frame is at `origin` of the spec frame with the spec's axes (the CoM for a free body,
/// the pivot for a pivoted one): one geometry per part with a volume, at its pose. `meshes`
/// holds, per part, the vertices of a mesh part (`None` for the others; see
/// [`spec_mesh_vertices`]); a mesh part without them, points, rods and given inertias do not
/// collide (a warning each).
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
/// never colliding) are left out. Planes and height fields are not bodies' shapes
/// (a plane is the ground: `--ground`), a mesh that cannot be read; each is skipped.
#[cfg(feature = "mjcf")]
#[must_use]
pub fn mjcf_geometries(mjcf: &super::mjcf::MjcfModel) -> (Vec<Geometry>, Vec<String>) {
    use super::mjcf::MjcfShape;
    let (mut out, mut warnings) = (Vec::new(), Vec::new());
    for g in &mjcf.geoms {
        if g.contype == 0 && g.conaffinity == 0 {
            continue; // a visual geom: it collides with nothing in MuJoCo, the floor included
        }
        let name = g.name.clone().unwrap_or_else(|| format!("geom {}", g.line));
        let shape = match &g.shape {
            MjcfShape::Sphere { radius } => Ok(Shape::Sphere { radius: *radius }),
            MjcfShape::Capsule {
                radius,
                half_length,
            } => Ok(Shape::Capsule {
                radius: *radius,
                length: 2.0 * half_length,
            }),
            MjcfShape::Cylinder {
                radius,
                half_length,
            } => Ok(Shape::Cylinder {
                radius: *radius,
                length: 2.0 * half_length,
            }),
            MjcfShape::Ellipsoid { radii } => Ok(Shape::Ellipsoid { semi_axes: *radii }),
            MjcfShape::Box { half } => Ok(Shape::Box { size: 2.0 * half }),
            MjcfShape::Mesh {
                file,
                scale,
                refpos,
                refrot,
                ..
            } => read_mesh(file)
                .map(|m| Shape::ConvexHull {
                    points: m
                        .vertices
                        .iter()
                        .map(|v| (refrot.transpose() * (v - refpos)).component_mul(scale))
                        .collect(),
                })
                .map_err(|e| format!("{}: {e}", file.display())),
            MjcfShape::Plane { .. } => {
                Err("a plane is not a body's shape (the ground: --ground)".into())
            }
            MjcfShape::Hfield { .. } => Err("height fields are not read".into()),
        };
        match shape.and_then(|s| s.check().map(|()| s)) {
            Ok(shape) => {
                let mut geometry = Geometry::new(name, g.parent, g.placement, shape);
                geometry.contype = u32::try_from(g.contype).unwrap_or(0);
                geometry.conaffinity = u32::try_from(g.conaffinity).unwrap_or(0);
                out.push(geometry);
            }
            Err(e) => warnings.push(format!("{name} (line {}): collision skipped: {e}", g.line)),
        }
    }
    (out, warnings)
}

/// The collision geometry of the robot file at `path` that `model` was built from: an MJCF
/// file's geoms ([`mjcf_geometries`], by the `.xml` extension), else a URDF's `<collision>`
/// elements ([`urdf_geometries`]). Returns the geometries and the warnings.
///
/// # Errors
/// The file cannot be read or parsed.
#[cfg(all(feature = "urdf", feature = "mjcf"))]
pub fn file_geometries(path: &Path, model: &Model) -> Result<(Vec<Geometry>, Vec<String>), String> {
    let xml = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"));
    if xml {
        let m = super::mjcf::load_mjcf(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(mjcf_geometries(&m))
    } else {
        let robot =
            super::urdf::parse_urdf_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(urdf_geometries(&robot, model))
    }
}

/// The collision model of `rigid simulate --ground HEIGHT --friction MU --restitution E` and of
/// Python's `simulate(ground=, friction=, restitution=)`: the horizontal ground `z = height`,
/// `geometries` (the robot's), `friction` (default [`DEFAULT_FRICTION`](crate::collision::DEFAULT_FRICTION)) and `restitution`
/// (default 0) for every contact, no contact between the robot's own bodies.
///
/// # Errors
/// A friction that is negative or not finite, a restitution outside `[0, 1]`, a height that is
/// not finite; the message names the option.
pub fn ground_model(
    height: f64,
    friction: Option<f64>,
    restitution: Option<f64>,
    geometries: Vec<Geometry>,
) -> Result<crate::collision::CollisionModel, String> {
    use crate::collision::{CollisionModel, Ground, DEFAULT_FRICTION};
    let friction = friction.unwrap_or(DEFAULT_FRICTION);
    let restitution = restitution.unwrap_or(0.0);
    if !(friction.is_finite() && friction >= 0.0) {
        return Err(format!("friction must be finite and >= 0, got {friction}"));
    }
    if !(0.0..=1.0).contains(&restitution) {
        return Err(format!("restitution must be in [0, 1], got {restitution}"));
    }
    if !height.is_finite() {
        return Err(format!("the ground height must be finite, got {height}"));
    }
    let mut ground = Ground::horizontal(height, friction);
    ground.restitution = restitution;
    let mut cm = CollisionModel::new(ground);
    cm.self_collision = false;
    cm.friction = friction;
    cm.restitution = restitution;
    cm.geometries = geometries;
    Ok(cm)
}
