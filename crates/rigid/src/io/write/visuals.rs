//! The visual geometry of robot files, which the writers draw: a URDF's `<visual>` elements,
//! the geoms MuJoCo draws (groups 0 to 2) of an MJCF model, an SDF link's `<visual>` elements.

use super::{Visual, VisualShape};
#[cfg(feature = "urdf")]
use crate::io::urdf::{resolve_mesh_path, UrdfRobot, UrdfShape};
use crate::multibody::{FrameKind, Model};

/// The visual geometry of a URDF robot on its `model` (built from it): every `<visual>` of every
/// link, on the body the link belongs to, placed at the link frame times the element's
/// `<origin>`, named `link/visual/k`, with its colour; a mesh by the file it resolves to (as for the
/// collisions: `package://`, `file://`, relative to the URDF). Returns the visuals and the
/// warnings: an element whose mesh is not found or whose link is not a body, which is skipped.
#[cfg(feature = "urdf")]
#[must_use]
pub fn urdf_visuals(robot: &UrdfRobot, model: &Model) -> (Vec<Visual>, Vec<String>) {
    let (mut out, mut warnings) = (Vec::new(), Vec::new());
    for link in robot.links.iter().filter(|l| !l.visuals.is_empty()) {
        let Some(frame) = model.frame_id_of_kind(&link.name, FrameKind::Body) else {
            warnings.push(format!(
                "link \"{}\" (line {}): not a body of the model: its visual geometry is skipped",
                link.name, link.line
            ));
            continue;
        };
        let frame = &model.frames()[frame.0];
        for (k, v) in link.visuals.iter().enumerate() {
            let shape = match &v.shape {
                UrdfShape::Mesh { filename, scale } => {
                    match resolve_mesh_path(filename, robot.path.as_deref()) {
                        Some(file) => VisualShape::Mesh {
                            file: std::fs::canonicalize(&file).unwrap_or(file),
                            scale: *scale,
                        },
                        None => {
                            warnings.push(format!(
                                "link \"{}\" (line {}): visual skipped: mesh {filename} not found",
                                link.name, v.line
                            ));
                            continue;
                        }
                    }
                }
                other => match crate::io::collision::urdf_shape(other, None) {
                    Ok(s) => VisualShape::Primitive(s),
                    Err(e) => {
                        warnings.push(format!(
                            "link \"{}\" (line {}): visual skipped: {e}",
                            link.name, v.line
                        ));
                        continue;
                    }
                },
            };
            out.push(Visual {
                name: format!("{}/visual/{k}", link.name),
                link: link.name.clone(),
                body: frame.parent,
                placement: frame.placement * v.origin,
                shape,
                rgba: v.rgba,
            });
        }
    }
    (out, warnings)
}

/// The geoms MuJoCo draws by default (groups 0 to 2) of an MJCF model, on the joints they are
/// fixed in, those that collide too when `colliding` (for URDF, whose `<collision>` elements are
/// not drawn; an MJCF file draws its collision geoms itself): primitives as such, a mesh by its file at the frame MuJoCo puts it
/// in (its `refpos`/`refquat` shift; a mesh given by its vertices, or turned and scaled unevenly,
/// as its convex hull), named by the geom (else `body/geom/k`), with its colour. Planes and
/// height fields are not drawn (a note each). Returns the visuals and the notes.
#[cfg(feature = "mjcf")]
#[must_use]
pub fn mjcf_visuals(m: &crate::io::mjcf::MjcfModel, colliding: bool) -> (Vec<Visual>, Vec<String>) {
    use crate::collision::Shape;
    use crate::io::mjcf::MjcfShape;
    let (mut out, mut notes) = (Vec::new(), Vec::new());
    for (k, g) in m.geoms.iter().enumerate() {
        let collides = g.contype != 0 || g.conaffinity != 0;
        if !(0..3).contains(&g.group) || (collides && !colliding) {
            continue;
        }
        let link = m.bodies[g.body].name.clone();
        let name = g.name.clone().unwrap_or_else(|| format!("{link}/geom/{k}"));
        let mut placement = g.placement;
        let shape = match &g.shape {
            MjcfShape::Sphere { .. }
            | MjcfShape::Box { .. }
            | MjcfShape::Capsule { .. }
            | MjcfShape::Cylinder { .. }
            | MjcfShape::Ellipsoid { .. } => match crate::io::collision::mjcf_primitive(&g.shape) {
                Some(s) => VisualShape::Primitive(s),
                None => continue,
            },
            MjcfShape::Mesh {
                file,
                inline,
                scale,
                refpos,
                refrot,
                ..
            } => {
                // by its file where MuJoCo draws it, else as its hull
                if let Some(frame) = g.shape.mesh_file_frame() {
                    placement = placement * frame;
                    VisualShape::Mesh {
                        // absolute: the written file is read from elsewhere
                        file: std::fs::canonicalize(file).unwrap_or_else(|_| file.clone()),
                        scale: *scale,
                    }
                } else {
                    let mesh = inline
                        .clone()
                        .map_or_else(|| crate::io::mesh_file::read_mesh(file), Ok);
                    match mesh {
                        Ok(mesh) => VisualShape::Primitive(Shape::ConvexHull {
                            points: (mesh.vertices.iter())
                                .map(|v| (refrot.transpose() * (v - refpos)).component_mul(scale))
                                .collect(),
                        }),
                        Err(e) => {
                            notes
                                .push(format!("geom \"{name}\" (line {}): not drawn: {e}", g.line));
                            continue;
                        }
                    }
                }
            }
            MjcfShape::Plane { .. } | MjcfShape::Hfield { .. } => {
                notes.push(format!(
                    "geom \"{name}\" (line {}): planes and height fields are not drawn",
                    g.line
                ));
                continue;
            }
        };
        out.push(Visual {
            name,
            link,
            body: g.parent,
            placement,
            shape,
            rgba: Some(g.rgba),
        });
    }
    (out, notes)
}

/// The `<visual>` elements of an SDF model's links, on the bodies the links belong to (placed at
/// the link frame times the element's pose), named by the element (else `link/visual/k`), with
/// their colours; a mesh by its file. Returns the visuals and the notes: a link that is not a
/// body of the model (which cannot happen for a model `load_sdf` built).
#[cfg(feature = "urdf")]
#[must_use]
pub fn sdf_visuals(m: &crate::io::sdf::SdfModel) -> (Vec<Visual>, Vec<String>) {
    let (mut out, mut notes) = (Vec::new(), Vec::new());
    for link in m.links.iter().filter(|l| !l.visuals.is_empty()) {
        let Some(frame) = m.model.frame_id_of_kind(&link.name, FrameKind::Body) else {
            notes.push(format!(
                "link \"{}\" (line {}): not a body of the model: its visuals are skipped",
                link.name, link.line
            ));
            continue;
        };
        let frame = &m.model.frames()[frame.0];
        for v in &link.visuals {
            out.push(Visual {
                name: v.name.clone(),
                link: link.name.clone(),
                body: frame.parent,
                placement: frame.placement * v.pose,
                shape: v.shape.clone(),
                rgba: v.rgba,
            });
        }
    }
    (out, notes)
}
