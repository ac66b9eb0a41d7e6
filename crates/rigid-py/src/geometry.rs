//! Geometry for Python: a URDF's `<visual>` and `<collision>` elements as written
//! (`urdf_link_geometries`, read by the Pinocchio layer's `buildGeomFromUrdf`), the inertia its
//! fixed-base model welds to the world (`_urdf_welded_inertia`), an SRDF file (`read_srdf`), and
//! the signed
//! distance of two shapes at their world poses (`Collider`, `proximity`: its
//! `computeCollisions` and `computeDistances`).

use crate::convert::{array1, array2, io_error, pose, value_error, vector};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rigid::collision::Shape;
use rigid::io::urdf::{parse_urdf_file, resolve_mesh_path, UrdfError, UrdfShape};
use rigid::spatial::Vec3;
use std::path::PathBuf;

/// The `<collision>` (`kind="collision"`) or `<visual>` (`kind="visual"`) elements of every link
/// of a URDF file, links in file order and each link's elements in order: one dict each with
/// `link`, `index` (within the link), `origin` (4 x 4, in the link frame), `shape` (`"box"`,
/// `"cylinder"`, `"sphere"`, `"capsule"`, `"mesh"`), `size` (a box's edges; `[radius, length]`;
/// `[radius]`; none for a mesh), `filename` (a mesh's, as written), `mesh_path` (the file it
/// resolves to, or None), `scale`, `rgba` (or None).
#[pyfunction]
#[pyo3(signature = (path, kind = "collision"))]
pub fn urdf_link_geometries<'py>(
    py: Python<'py>,
    path: PathBuf,
    kind: &str,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    const F: &str = "urdf_link_geometries";
    let visual = match kind {
        "visual" => true,
        "collision" => false,
        _ => {
            return Err(value_error(
                F,
                format!("kind is \"visual\" or \"collision\", not \"{kind}\""),
            ))
        }
    };
    let robot = parse_urdf_file(&path).map_err(|e| match &e {
        UrdfError::Io { source, .. } => io_error(source, format!("{F}: {e}")),
        _ => value_error(F, format!("{}: {e}", path.display())),
    })?;
    let mut out = Vec::new();
    for link in &robot.links {
        let elements = if visual {
            &link.visuals
        } else {
            &link.collisions
        };
        for (index, g) in elements.iter().enumerate() {
            let d = PyDict::new(py);
            d.set_item("link", &link.name)?;
            d.set_item("index", index)?;
            let h = g.origin.to_homogeneous();
            d.set_item("origin", array2(py, 4, 4, |r, c| h[(r, c)]))?;
            let (shape, size, scale): (&str, Vec<f64>, Vec3) = match &g.shape {
                UrdfShape::Box { size } => ("box", size.as_slice().to_vec(), Vec3::repeat(1.0)),
                UrdfShape::Cylinder { radius, length } => {
                    ("cylinder", vec![*radius, *length], Vec3::repeat(1.0))
                }
                UrdfShape::Sphere { radius } => ("sphere", vec![*radius], Vec3::repeat(1.0)),
                UrdfShape::Capsule { radius, length } => {
                    ("capsule", vec![*radius, *length], Vec3::repeat(1.0))
                }
                UrdfShape::Mesh { filename, scale } => {
                    d.set_item("filename", filename)?;
                    let found = resolve_mesh_path(filename, Some(&path));
                    d.set_item("mesh_path", found.map(|p| p.display().to_string()))?;
                    ("mesh", Vec::new(), *scale)
                }
            };
            d.set_item("shape", shape)?;
            d.set_item("size", array1(py, &size))?;
            d.set_item("scale", array1(py, scale.as_slice()))?;
            d.set_item("rgba", g.rgba.map(|c| array1(py, &c)))?;
            out.push(d);
        }
    }
    Ok(out)
}

/// A collision shape made ready for `proximity` (`rigid::collision::Collider`): `kind` is
/// `"sphere"` (`size = [radius]`), `"box"` (`[x, y, z]` edges), `"cylinder"` and `"capsule"`
/// (`[radius, length]`, along z, centred), `"cone"` (`[radius, height]`, origin at the centroid),
/// `"ellipsoid"` (`[a, b, c]` semi-axes), or `"mesh"` (`path` a mesh file, STL, OBJ or DAE, its
/// vertices times `scale`; its convex hull collides).
#[pyclass(module = "rigid", frozen)]
pub struct Collider {
    inner: rigid::collision::Collider,
}

#[pymethods]
impl Collider {
    #[new]
    #[pyo3(signature = (kind, size = None, path = None, scale = None))]
    fn new(
        kind: &str,
        size: Option<&Bound<'_, PyAny>>,
        path: Option<PathBuf>,
        scale: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        const F: &str = "Collider";
        let n = match kind {
            "sphere" => 1,
            "cylinder" | "capsule" | "cone" => 2,
            "box" | "ellipsoid" => 3,
            "mesh" => 0,
            _ => {
                return Err(value_error(
                    F,
                    format!(
                        "unknown shape \"{kind}\": sphere, box, cylinder, capsule, cone, \
                         ellipsoid or mesh"
                    ),
                ))
            }
        };
        let s: Vec<f64> = match (n, size) {
            (0, _) => Vec::new(),
            (_, Some(x)) => vector(x, F, "size", &n.to_string(), n)?.as_slice().to_vec(),
            (_, None) => return Err(value_error(F, format!("a {kind} needs its size"))),
        };
        let shape = match kind {
            "sphere" => Shape::Sphere { radius: s[0] },
            "box" => Shape::Box {
                size: Vec3::new(s[0], s[1], s[2]),
            },
            "cylinder" => Shape::Cylinder {
                radius: s[0],
                length: s[1],
            },
            "capsule" => Shape::Capsule {
                radius: s[0],
                length: s[1],
            },
            "cone" => Shape::Cone {
                radius: s[0],
                height: s[1],
            },
            "ellipsoid" => Shape::Ellipsoid {
                semi_axes: Vec3::new(s[0], s[1], s[2]),
            },
            _ => {
                let path =
                    path.ok_or_else(|| value_error(F, "a mesh needs the path of its file"))?;
                let scale = match scale {
                    Some(x) => crate::convert::vec3(x, F, "scale")?,
                    None => Vec3::repeat(1.0),
                };
                let mesh = rigid::io::mesh_file::read_mesh(&path)
                    .map_err(|e| value_error(F, format!("{}: {e}", path.display())))?;
                Shape::ConvexHull {
                    points: mesh
                        .vertices
                        .iter()
                        .map(|v| v.component_mul(&scale))
                        .collect(),
                }
            }
        };
        let inner = rigid::collision::Collider::new(kind, &shape).map_err(|e| value_error(F, e))?;
        Ok(Self { inner })
    }
}

/// The signed distance between collider `a` at the world pose `pose_a` (4 x 4) and `b` at
/// `pose_b`: `(distance, point_a, point_b, normal)`, the distance negative for a penetration
/// (its depth), the nearest points in the world, the unit normal out of `a` towards `b`.
#[pyfunction]
pub fn proximity<'py>(
    py: Python<'py>,
    a: &Collider,
    pose_a: &Bound<'py, PyAny>,
    b: &Collider,
    pose_b: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    const F: &str = "proximity";
    let (pa, pb) = (pose(pose_a, F, "pose_a")?, pose(pose_b, F, "pose_b")?);
    let p = rigid::collision::proximity(&a.inner, &pa, &b.inner, &pb)
        .ok_or_else(|| value_error(F, "parry has no query for this pair of shapes"))?;
    let v = |x: Vec3| array1(py, x.as_slice());
    Ok((p.distance, v(p.point_a), v(p.point_b), v(p.normal))
        .into_pyobject(py)?
        .into_any())
}

/// An SRDF file (`rigid::io::srdf`): `{"disabled": [(link1, link2), ...], "group_states":
/// [{"name", "group", "joints": [(joint, values), ...]}, ...]}`.
#[pyfunction]
pub fn read_srdf<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let s = rigid::io::srdf::read_srdf(&path).map_err(|e| {
        if path.is_file() {
            value_error("read_srdf", e)
        } else {
            pyo3::exceptions::PyFileNotFoundError::new_err(format!("read_srdf: {e}"))
        }
    })?;
    let d = PyDict::new(py);
    let disabled: Vec<(String, String)> = s.disabled.into_iter().map(|(a, b, _)| (a, b)).collect();
    d.set_item("disabled", disabled)?;
    let mut states = Vec::new();
    for g in s.group_states {
        let e = PyDict::new(py);
        e.set_item("name", g.name)?;
        e.set_item("group", g.group)?;
        e.set_item("joints", g.joints)?;
        states.push(e);
    }
    d.set_item("group_states", states)?;
    Ok(d)
}

/// The inertia of a URDF's links welded to its root link, in the root's frame
/// (`UrdfRobot::welded_to_root_inertia`): `(mass, centre of mass (3,), inertia about it (3, 3))`,
/// Pinocchio's `model.inertias[0]` of the fixed-base model.
#[pyfunction]
pub fn _urdf_welded_inertia<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyAny>> {
    const F: &str = "_urdf_welded_inertia";
    let robot = parse_urdf_file(&path).map_err(|e| match &e {
        UrdfError::Io { source, .. } => io_error(source, format!("{F}: {e}")),
        _ => value_error(F, format!("{}: {e}", path.display())),
    })?;
    let g = robot.welded_to_root_inertia();
    let i = g.inertia_com();
    let i = i.matrix();
    Ok((
        g.mass(),
        array1(py, g.com().as_slice()),
        array2(py, 3, 3, |r, c| i[(r, c)]),
    )
        .into_pyobject(py)?
        .into_any())
}
