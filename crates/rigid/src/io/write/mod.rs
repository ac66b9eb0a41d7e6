//! Writing robot files: a [`Model`] and its collision [`Geometry`] as MJCF ([`mjcf`]) or URDF
//! ([`urdf`]), for `rigid convert`.
//!
//! Both writers read the same [`Outline`] of the model: each moving joint's body under the name
//! of its link (the [`FrameKind::Body`] frame at the joint frame), the other frames fixed in it
//! (links welded by fixed joints, operational frames), and the world's. What the model holds is
//! written exactly (numbers in their shortest form that reads back to the same `f64`):
//! the tree, joint placements and axes, inertias (mass, centre of mass, the full inertia about
//! it), position, velocity and effort limits, armature, damping, friction, the collision shapes
//! and the link names. What the target format cannot say is either an error naming the joint
//! ([`WriteError`]) or a note in [`Written::notes`], never dropped silently.
//!
//! A collision mesh is written as the convex hull rigid collides it as (inline vertices in MJCF,
//! an OBJ file beside a URDF). The visual geometry ([`Visual`]: a URDF's or SDF file's `<visual>`
//! elements, the geoms an MJCF file draws, [`visuals`]) is written as it is: primitives as primitives, a mesh by its file (its absolute path) in URDF and
//! in MJCF when it is an OBJ file, else as inline vertices and faces; with its colour. It takes no part in the dynamics or the collisions (MJCF: `contype="0"
//! conaffinity="0" group="1"`).

pub mod mjcf;
pub mod urdf;
pub mod visuals;

use crate::collision::Geometry;
use crate::multibody::{FrameKind, JointId, Model};
use crate::spatial::{Transform, Vec3};
use std::collections::HashSet;
use thiserror::Error;

/// A visual element of a robot file: a shape or a mesh file, fixed in a body, with its colour.
#[derive(Clone, Debug, PartialEq)]
pub struct Visual {
    /// Its name (`link/visual/k` for the `k`-th `<visual>` of a URDF link).
    pub name: String,
    /// The link it belongs to (a body's own link, or a link welded to it).
    pub link: String,
    /// The body it moves with (`None`: the world).
    pub body: Option<JointId>,
    /// Its frame in the body's joint frame.
    pub placement: Transform,
    /// What it looks like.
    pub shape: VisualShape,
    /// Its colour `rgba` in `[0, 1]`, if the file gives one.
    pub rgba: Option<[f64; 4]>,
}

/// What a [`Visual`] looks like.
#[derive(Clone, Debug, PartialEq)]
pub enum VisualShape {
    /// A primitive (sphere, box, cylinder, capsule).
    Primitive(crate::collision::Shape),
    /// A mesh file (found on disk), scaled.
    Mesh {
        /// The file.
        file: std::path::PathBuf,
        /// The scale along x, y, z.
        scale: Vec3,
    },
}

/// A written file, with what it could not say.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Written {
    /// The file's text.
    pub text: String,
    /// Files the text refers to, as (path relative to the written file, contents): the OBJ meshes
    /// of a URDF.
    pub files: Vec<(String, String)>,
    /// What the target format cannot express and how it was written instead, one sentence each.
    pub notes: Vec<String>,
}

/// A model the target format cannot express.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum WriteError {
    /// A joint type the format does not have.
    #[error("joint \"{joint}\": {format} has no {kind} joint{hint}")]
    Joint {
        /// The joint's name.
        joint: String,
        /// Its type ([`JointType::name`](crate::multibody::JointType::name)).
        kind: &'static str,
        /// `MJCF` or `URDF`.
        format: &'static str,
        /// What could be done instead (starts with `: ` when present).
        hint: String,
    },
}

/// The model as both writers walk it: one body per moving joint, named.
pub(crate) struct Outline<'a> {
    pub model: &'a Model,
    /// Each joint's body (link) name.
    pub link: Vec<String>,
    /// The frames fixed in each joint's body other than its own link, indices into
    /// `model.frames()` (welded links and operational frames).
    pub fixed: Vec<Vec<usize>>,
    /// The frames fixed in the world.
    pub world: Vec<usize>,
    /// Each joint's children, in the model's order.
    pub children: Vec<Vec<usize>>,
    /// The joints whose parent is the world.
    pub roots: Vec<usize>,
}

impl<'a> Outline<'a> {
    pub fn new(model: &'a Model) -> Self {
        let n = model.njoints();
        let mut link: Vec<Option<String>> = vec![None; n];
        let (mut fixed, mut world) = (vec![Vec::new(); n], Vec::new());
        for (i, f) in model.frames().iter().enumerate() {
            match f.parent {
                Some(JointId(j)) => {
                    let own = f.kind == FrameKind::Body
                        && link[j].is_none()
                        && f.placement.is_identity(0.0);
                    if own {
                        link[j] = Some(f.name.clone());
                    } else {
                        fixed[j].push(i);
                    }
                }
                None => world.push(i),
            }
        }
        // A body without a link frame (a built-in model) is named after its joint.
        let mut taken: HashSet<String> = model.frames().iter().map(|f| f.name.clone()).collect();
        let link = link
            .into_iter()
            .zip(model.joints())
            .map(|(l, j)| l.unwrap_or_else(|| unique(&mut taken, &format!("{}_link", j.name))))
            .collect();
        let mut children = vec![Vec::new(); n];
        let mut roots = Vec::new();
        for (k, j) in model.joints().iter().enumerate() {
            match j.parent {
                Some(JointId(p)) => children[p].push(k),
                None => roots.push(k),
            }
        }
        Self {
            model,
            link,
            fixed,
            world,
            children,
            roots,
        }
    }
}

/// `name`, or `name_2`, `name_3`, ... the first not in `taken`; taken from then on.
pub(crate) fn unique(taken: &mut HashSet<String>, name: &str) -> String {
    let mut candidate = name.to_string();
    let mut k = 2;
    while taken.contains(&candidate) {
        candidate = format!("{name}_{k}");
        k += 1;
    }
    taken.insert(candidate.clone());
    candidate
}

pub(crate) use super::shortest as num;

/// Numbers separated by spaces.
pub(crate) fn nums(xs: impl IntoIterator<Item = f64>) -> String {
    xs.into_iter().map(num).collect::<Vec<_>>().join(" ")
}

/// A vector as `x y z`.
pub(crate) fn vec3(v: &Vec3) -> String {
    nums(v.iter().copied())
}

/// Text escaped for an XML attribute value.
pub(crate) fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The geometries of body `body` (`None`: the world).
pub(crate) fn geometries_of(
    geometries: &[Geometry],
    body: Option<usize>,
) -> impl Iterator<Item = &Geometry> {
    geometries
        .iter()
        .filter(move |g| g.body.map(|b| b.0) == body)
}

/// Points on the surface of a capsule, cylinder, cone or ellipsoid (for a format without the
/// shape: their convex hull stands for it), `n` around and `n / 2` from pole to pole.
pub(crate) fn surface_points(shape: &crate::collision::Shape, n: usize) -> Vec<Vec3> {
    use crate::collision::Shape;
    use std::f64::consts::{PI, TAU};
    let ring = |r: f64, z: f64| -> Vec<Vec3> {
        (0..n)
            .map(|k| {
                let a = TAU * k as f64 / n as f64;
                Vec3::new(r * a.cos(), r * a.sin(), z)
            })
            .collect()
    };
    let half = n / 2;
    match shape {
        Shape::Capsule { radius, length } => {
            let mut p = Vec::new();
            for s in [-1.0, 1.0] {
                p.push(Vec3::new(0.0, 0.0, s * (length / 2.0 + radius)));
                for i in 0..half {
                    let t = PI / 2.0 * i as f64 / half as f64;
                    p.extend(ring(
                        radius * t.cos(),
                        s * (length / 2.0 + radius * t.sin()),
                    ));
                }
            }
            p
        }
        Shape::Cylinder { radius, length } => {
            let mut p = ring(*radius, -length / 2.0);
            p.extend(ring(*radius, length / 2.0));
            p
        }
        Shape::Cone { radius, height } => {
            let mut p = ring(*radius, -height / 4.0);
            p.push(Vec3::new(0.0, 0.0, 0.75 * height));
            p
        }
        Shape::Ellipsoid { semi_axes } => {
            let mut p = vec![
                Vec3::new(0.0, 0.0, -semi_axes.z),
                Vec3::new(0.0, 0.0, semi_axes.z),
            ];
            for i in 1..half {
                let t = PI * i as f64 / half as f64 - PI / 2.0;
                p.extend(
                    ring(t.cos(), t.sin())
                        .into_iter()
                        .map(|v| v.component_mul(semi_axes)),
                );
            }
            p
        }
        Shape::ConvexHull { points } => points.clone(),
        Shape::Sphere { radius } => surface_points(
            &Shape::Ellipsoid {
                semi_axes: Vec3::repeat(*radius),
            },
            n,
        ),
        Shape::Box { size } => {
            let h = size / 2.0;
            (0..8)
                .map(|k| {
                    let s = |b: usize| if k & b == 0 { -1.0 } else { 1.0 };
                    Vec3::new(s(1) * h.x, s(2) * h.y, s(4) * h.z)
                })
                .collect()
        }
    }
}

/// The convex hull of `points` (vertices and triangles), `None` when it encloses no volume (all
/// points on a plane or a line: MuJoCo refuses such a mesh, and nothing can rest on it).
pub(crate) fn solid_hull(points: &[Vec3]) -> Option<(Vec<Vec3>, Vec<[usize; 3]>)> {
    let (v, t) = crate::collision::hull_triangles(points)?;
    let volume: f64 = t
        .iter()
        .map(|f| v[f[0]].dot(&v[f[1]].cross(&v[f[2]])) / 6.0)
        .sum();
    let size = v
        .iter()
        .flat_map(|a| v.iter().map(move |b| (a - b).norm()))
        .fold(0.0, f64::max);
    (volume.abs() > 1e-9 * size.powi(3)).then_some((v, t))
}

/// The rotation of `t` as MuJoCo's `w x y z`, `None` for the identity.
pub(crate) fn quat_wxyz(t: &Transform) -> Option<[f64; 4]> {
    if t.rotation == crate::spatial::Mat3::identity() {
        return None;
    }
    let [x, y, z, w] = crate::spatial::so3::to_quaternion(&t.rotation);
    Some([w, x, y, z])
}

/// A format rigid writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// MuJoCo's MJCF (`.xml`).
    Mjcf,
    /// URDF (`.urdf`).
    Urdf,
}

impl Format {
    /// The format of a file name's extension (`.xml`, `.urdf`, any case), `None` otherwise.
    #[must_use]
    pub fn of_path(path: &std::path::Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "xml" | "mjcf" => Some(Self::Mjcf),
            "urdf" => Some(Self::Urdf),
            _ => None,
        }
    }

    /// `MJCF` or `URDF`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Mjcf => "MJCF",
            Self::Urdf => "URDF",
        }
    }

    /// `model`, its collision `geometries` and its `visuals` in this format
    /// ([`mjcf::write_mjcf`], [`urdf::write_urdf`] with its collision hulls in `mesh_dir`).
    ///
    /// # Errors
    /// [`WriteError::Joint`] for a joint the format cannot express.
    pub fn write(
        self,
        model: &Model,
        geometries: &[Geometry],
        visuals: &[Visual],
        mesh_dir: &str,
    ) -> Result<Written, WriteError> {
        match self {
            Self::Mjcf => mjcf::write_mjcf(model, geometries, visuals),
            Self::Urdf => urdf::write_urdf(model, geometries, visuals, mesh_dir),
        }
    }
}

/// Why [`save`] wrote nothing.
#[derive(Debug, Error)]
pub enum SaveError {
    /// The output's extension names no format.
    #[error("{0}: unknown output format: the extension must be .xml (MJCF) or .urdf (URDF)")]
    Format(String),
    /// The source file's geometry cannot be read.
    #[error(transparent)]
    Source(#[from] super::collision::WorldError),
    /// The model holds what the format cannot express.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// A file cannot be written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
}

/// Writes `model` to `out` in the format of its extension ([`Format::of_path`]) with the
/// collision geometry of the file it was loaded from (`source`, a URDF, MJCF or SDF file:
/// [`file_geometries`](super::collision::file_geometries); `None`: no geometry) and its visual
/// geometry ([`visuals`]: a URDF's or SDF file's `<visual>` elements, the geoms MuJoCo draws), a
/// URDF's collision hulls as OBJ files in the folder `OUT_meshes` beside it. Returns what was not
/// written: the source's skipped geometry, what the source holds that is not written (an MJCF
/// file's actuators and tendons, an SDF file's loops), and the writer's [`Written::notes`].
///
/// # Errors
/// [`SaveError`]: an unknown extension, an unreadable source, a joint the format cannot express
/// (nothing is written then), a file that cannot be written.
#[cfg(all(feature = "urdf", feature = "mjcf"))]
pub fn save(
    model: &Model,
    source: Option<&std::path::Path>,
    out: &std::path::Path,
) -> Result<Vec<String>, SaveError> {
    let format =
        Format::of_path(out).ok_or_else(|| SaveError::Format(out.display().to_string()))?;
    let (geometries, mut notes) = match source {
        Some(path) => super::collision::file_geometries(path, model)?,
        None => (Vec::new(), Vec::new()),
    };
    let mut visuals = Vec::new();
    if let Some(path) = source {
        let ext = |x: &str| path.extension().is_some_and(|e| e.eq_ignore_ascii_case(x));
        if ext("xml") {
            notes.push(
                "the source's planes, height fields, actuators, tendons and <equality> \
                 constraints are not written"
                    .into(),
            );
            let m =
                super::mjcf::load_mjcf(path).map_err(|e| super::collision::WorldError::File {
                    path: path.display().to_string(),
                    message: e.to_string(),
                })?;
            let (v, skipped) = visuals::mjcf_visuals(&m, format == Format::Urdf);
            visuals = v;
            notes.extend(skipped);
        } else if ext("sdf") {
            notes.push("the source's plugins and sensors are not written".into());
            let m = super::sdf::load_sdf(path).map_err(|e| super::collision::WorldError::File {
                path: path.display().to_string(),
                message: e.to_string(),
            })?;
            let (v, skipped) = visuals::sdf_visuals(&m);
            visuals = v;
            notes.extend(skipped);
            let loops = m.constraints.len();
            if loops > 0 {
                notes.push(format!(
                    "the source's {loops} loop-closing constraints are not written: the file \
                     holds the tree only"
                ));
            }
        } else {
            let robot = super::urdf::parse_urdf_file(path).map_err(|e| {
                super::collision::WorldError::File {
                    path: path.display().to_string(),
                    message: e.to_string(),
                }
            })?;
            let (v, skipped) = visuals::urdf_visuals(&robot, model);
            visuals = v;
            notes.extend(skipped);
        }
    }
    let stem = out.file_stem().and_then(|s| s.to_str()).unwrap_or("robot");
    let written = format.write(model, &geometries, &visuals, &format!("{stem}_meshes"))?;
    let io = |path: &std::path::Path| {
        let path = path.display().to_string();
        move |source| SaveError::Io { path, source }
    };
    let dir = out.parent().unwrap_or(std::path::Path::new(""));
    for (rel, text) in &written.files {
        let path = dir.join(rel);
        if let Some(p) = path.parent() {
            std::fs::create_dir_all(p).map_err(io(p))?;
        }
        std::fs::write(&path, text).map_err(io(&path))?;
    }
    std::fs::write(out, &written.text).map_err(io(out))?;
    notes.extend(written.notes);
    Ok(notes)
}
