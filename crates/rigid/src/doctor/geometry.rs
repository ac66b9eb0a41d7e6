//! What a link's `<visual>` and `<collision>` shapes say about where its mass can be: the extent
//! of the shapes along a fixed set of directions, and the volume, centroid and second moment of
//! the uniform solid they bound.

use crate::io::mesh_file::read_mesh;
use crate::io::urdf::{resolve_mesh_path, UrdfGeometry, UrdfLink, UrdfShape};
use crate::mass::{Shape, TriMesh};
use crate::spatial::{Mat3, Transform, Vec3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Number of directions of [`directions`]: a Fibonacci half-sphere (a direction and its
/// opposite give the same extent interval).
pub const DIRECTIONS: usize = 48;

/// Unit directions spread over a half-sphere, the three coordinate axes first.
#[must_use]
pub fn directions() -> Vec<Vec3> {
    let mut d = vec![Vec3::x(), Vec3::y(), Vec3::z()];
    let n = DIRECTIONS - 3;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    for k in 0..n {
        let z = (k as f64 + 0.5) / n as f64; // (0, 1): the upper half
        let r = (1.0 - z * z).sqrt();
        let t = golden * k as f64;
        d.push(Vec3::new(r * t.cos(), r * t.sin(), z));
    }
    d
}

/// The solid and the envelope of one link's shapes, in the link frame.
#[derive(Clone, Debug)]
pub struct LinkGeometry {
    /// `(min, max)` of `u·x` over the shapes, for each `u` of [`directions`].
    pub extents: Vec<(f64, f64)>,
    /// Volume of the uniform solid (m³): exact for primitives and closed meshes, an upper bound
    /// (the mesh's bounding box) for open ones.
    pub volume: f64,
    /// Every part's volume is exact.
    pub volume_exact: bool,
    /// Centroid of the uniform solid.
    pub centroid: Vec3,
    /// `∫ r rᵀ dV` about the centroid, unit density (m⁵).
    pub second_moment: Mat3,
    /// Which shapes were used (`"collision"` or `"visual"`), and what could not be read.
    pub notes: Vec<String>,
}

impl LinkGeometry {
    /// The second moment about the CoM of a uniform solid of mass `m` filling this geometry:
    /// `m Σ_g / V`.
    #[must_use]
    pub fn second_moment_of_mass(&self, m: f64) -> Mat3 {
        self.second_moment * (m / self.volume)
    }

    /// The length of the longest extent (m).
    #[must_use]
    pub fn size(&self) -> f64 {
        self.extents.iter().map(|(a, b)| b - a).fold(0.0, f64::max)
    }
}

/// The uniform solid of a closed mesh: `(V, centroid, ∫ r rᵀ dV about the centroid)`.
type Solid = (f64, Vec3, Mat3);

/// A mesh file as read: its triangles and, if it bounds a solid, that solid; or why it could not
/// be read.
type CachedMesh = Result<(TriMesh, Option<Solid>), String>;

/// Meshes read once per file.
#[derive(Default)]
pub struct MeshCache {
    meshes: HashMap<PathBuf, CachedMesh>,
}

impl MeshCache {
    /// The mesh at `path` with its closed-solid moments `(V, centroid, ∫ r rᵀ dV about it)` if it
    /// bounds a solid.
    fn get(&mut self, path: &Path) -> &CachedMesh {
        self.meshes.entry(path.to_path_buf()).or_insert_with(|| {
            let mesh = read_mesh(path).map_err(|e| e.to_string())?;
            let solid = mesh.mass_properties().ok().map(|p| {
                let i = *p.unit_inertia_com.matrix();
                (p.volume, p.com, Mat3::identity() * (0.5 * i.trace()) - i)
            });
            Ok((mesh, solid))
        })
    }
}

/// One shape's contribution: its extents along the directions, and its uniform solid
/// `(V, centroid, Σ about centroid)` in the link frame with whether `V` is exact.
struct Piece {
    extents: Vec<(f64, f64)>,
    solid: Solid,
    exact: bool,
}

fn primitive(shape: Shape, origin: &Transform, dirs: &[Vec3]) -> Option<Piece> {
    let volume = shape.volume();
    if !(volume.is_finite() && volume > 0.0) {
        return None;
    }
    let i = *shape.inertia_com(volume).matrix(); // unit density: mass = volume
    let r = &origin.rotation;
    let sigma = r * (Mat3::identity() * (0.5 * i.trace()) - i) * r.transpose();
    let c = origin.translation;
    let half = |u: &Vec3| -> f64 {
        let l = r.transpose() * u; // the direction in the shape's frame
        match shape {
            Shape::Box { size } => {
                0.5 * (l.x.abs() * size.x + l.y.abs() * size.y + l.z.abs() * size.z)
            }
            Shape::Cylinder { radius, length } => {
                0.5 * length * l.z.abs() + radius * (1.0 - l.z * l.z).max(0.0).sqrt()
            }
            Shape::Capsule { radius, length } => 0.5 * length * l.z.abs() + radius,
            Shape::Sphere { radius } => radius,
            _ => 0.0,
        }
    };
    Some(Piece {
        extents: dirs
            .iter()
            .map(|u| {
                let (m, h) = (u.dot(&c), half(u));
                (m - h, m + h)
            })
            .collect(),
        solid: (volume, c, sigma),
        exact: true,
    })
}

fn mesh_piece(
    cache: &mut MeshCache,
    path: &Path,
    scale: &Vec3,
    origin: &Transform,
    dirs: &[Vec3],
) -> Result<Piece, String> {
    let (mesh, solid) = match cache.get(path) {
        Ok(x) => x,
        Err(e) => return Err(e.clone()),
    };
    if mesh.vertices.is_empty() {
        return Err("the mesh has no vertices".into());
    }
    let s = Mat3::from_diagonal(scale);
    let placed: Vec<Vec3> = mesh
        .vertices
        .iter()
        .map(|v| origin.rotation * (s * v) + origin.translation)
        .collect();
    let extents = dirs
        .iter()
        .map(|u| {
            placed
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    let x = u.dot(p);
                    (a.min(x), b.max(x))
                })
        })
        .collect();
    let det = scale.x * scale.y * scale.z;
    let (solid, exact) = match solid {
        // A closed mesh: scale its moments (S Σ S, |det S| V) and place them.
        Some((v, c, sigma)) if det != 0.0 => {
            let r = &origin.rotation;
            let sigma = r * (s * sigma * s) * det.abs() * r.transpose();
            (
                (
                    v * det.abs(),
                    origin.rotation * (s * c) + origin.translation,
                    sigma,
                ),
                true,
            )
        }
        // Open: the bounding box of the scaled mesh, in the mesh's own axes.
        _ => {
            let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
            for v in &mesh.vertices {
                let w = s * v;
                lo = lo.inf(&w);
                hi = hi.sup(&w);
            }
            let size = (hi - lo).map(|x| x.max(1e-6));
            let centre = Transform::new(
                origin.rotation,
                origin.rotation * ((lo + hi) * 0.5) + origin.translation,
            );
            let b = primitive(Shape::Box { size }, &centre, &[]).ok_or("empty bounding box")?;
            (b.solid, false)
        }
    };
    Ok(Piece {
        extents,
        solid,
        exact,
    })
}

fn piece(
    g: &UrdfGeometry,
    urdf: Option<&Path>,
    cache: &mut MeshCache,
    dirs: &[Vec3],
) -> Result<Piece, String> {
    let shape = match &g.shape {
        UrdfShape::Box { size } => Shape::Box {
            size: size.map(|x| x.max(1e-6)),
        },
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
                .ok_or_else(|| format!("mesh \"{filename}\" not found"))?;
            return mesh_piece(cache, &path, scale, &g.origin, dirs)
                .map_err(|e| format!("mesh \"{filename}\": {e}"));
        }
    };
    primitive(shape, &g.origin, dirs).ok_or_else(|| "a shape without volume".into())
}

/// The geometry of `link` (of the URDF file `urdf`, for mesh paths): the envelope of every
/// visual and collision shape that can be read, and the uniform solid of its collision shapes
/// (its visual shapes if it has none). `None` when no shape can be read.
#[must_use]
pub fn link_geometry(
    link: &UrdfLink,
    urdf: Option<&Path>,
    cache: &mut MeshCache,
) -> Option<LinkGeometry> {
    let dirs = directions();
    let mut notes = Vec::new();
    let mut read = |list: &[UrdfGeometry], what: &str, notes: &mut Vec<String>| -> Vec<Piece> {
        list.iter()
            .filter_map(|g| match piece(g, urdf, cache, &dirs) {
                Ok(p) => Some(p),
                Err(e) => {
                    notes.push(format!("{what} at line {}: {e}", g.line));
                    None
                }
            })
            .collect()
    };
    let collision = read(&link.collisions, "collision", &mut notes);
    let visual = read(&link.visuals, "visual", &mut notes);
    let (solid_from, solid) = if collision.is_empty() {
        ("visual", &visual)
    } else {
        ("collision", &collision)
    };
    if solid.is_empty() {
        return None;
    }
    notes.insert(0, format!("solid from the {solid_from} shapes"));
    let mut extents = vec![(f64::INFINITY, f64::NEG_INFINITY); dirs.len()];
    for p in collision.iter().chain(&visual) {
        for (e, q) in extents.iter_mut().zip(&p.extents) {
            *e = (e.0.min(q.0), e.1.max(q.1));
        }
    }
    let volume: f64 = solid.iter().map(|p| p.solid.0).sum();
    if !(volume.is_finite() && volume > 0.0) {
        return None;
    }
    let centroid = solid.iter().map(|p| p.solid.1 * p.solid.0).sum::<Vec3>() / volume;
    let second_moment = solid
        .iter()
        .map(|p| {
            let d = p.solid.1 - centroid;
            p.solid.2 + d * d.transpose() * p.solid.0
        })
        .sum();
    Some(LinkGeometry {
        extents,
        volume,
        volume_exact: solid.iter().all(|p| p.exact),
        centroid,
        second_moment,
        notes,
    })
}
