//! The body spec of `rigid mass SPEC.toml` (see docs/conventions.md, "The command-line contract"):
//! a list of `[[part]]` tables, read into a [`Compound`].
//!
//! ```toml
//! [[part]]
//! name = "drum"            # optional, used in messages
//! shape = "cylinder"       # box, cylinder, sphere, ellipsoid, capsule, cone, rod, point, mesh, inertia
//! radius = 0.1             # the shape's dimensions (m)
//! length = 0.2
//! mass = 2.0               # kg; or `density` (kg/m³), never both
//! position = [0, 0, 0]     # the part frame's origin in the body frame (default: the origin)
//! rpy = [0, 0, 0]          # optional: fixed-axis roll, pitch, yaw (rad), as in URDF
//! # quaternion = [x, y, z, w]  # or a unit quaternion, never both
//! ```
//!
//! Dimensions per shape: `box`: `size = [lx, ly, lz]`; `cylinder`, `capsule`: `radius`,
//! `length` (axis z; the capsule's `length` excludes the caps); `sphere`: `radius`;
//! `ellipsoid`: `semi_axes = [a, b, c]`; `cone`: `radius`, `height` (axis z, origin at the
//! centroid); `rod`: `length` (along z, mass only); `point`: none (mass only); `mesh`:
//! `file = "part.stl"` (`.stl` or `.obj`, relative to the spec file's folder; the mesh's
//! coordinates are the part frame); `inertia`: `inertia = [ixx, iyy, izz, ixy, ixz, iyz]`
//! about the part frame's origin, which is the part's CoM (mass only, not checked for physical
//! validity, as in URDF).
//!
//! Everything else is rejected with an error naming the part (its number from 1, its name, its
//! line) and the field: unknown keys, keys the shape does not use, missing or non-positive
//! dimensions, non-finite numbers, both or neither of `mass` and `density`, a quaternion whose
//! norm differs from 1 by more than `1e-6` (it is normalised otherwise), both `rpy` and
//! `quaternion`, a mesh file that cannot be read or is not a closed, outward-oriented surface.

use super::mesh_file::read_mesh;
use crate::mass::{Compound, Geometry, MassOrDensity, Part, RotationalInertia, Shape};
use crate::spatial::{so3, Mat3, Transform, Vec3};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use thiserror::Error;
use toml::{Spanned, Table, Value};

/// Largest accepted `| |q| - 1 |` for a `quaternion`.
pub const QUATERNION_TOLERANCE: f64 = 1e-6;

/// A spec that cannot be read.
#[derive(Debug, Error)]
pub enum SpecError {
    /// The spec file cannot be read.
    #[error("cannot read {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The TOML is malformed, or the top level has a key other than `part`.
    #[error("TOML error at line {line}, column {column}: {message}")]
    Syntax {
        /// The line, from 1.
        line: usize,
        /// The column, from 1.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// The spec has no `[[part]]`.
    #[error("the spec has no [[part]] table")]
    NoParts,
    /// A part is wrong.
    #[error("{}, field `{field}`: {message}", part_label(*number, name.as_deref(), *line))]
    Part {
        /// The part's number, counting from 1 in file order.
        number: usize,
        /// The part's `name`, if it has one.
        name: Option<String>,
        /// The line of the wrong key, from 1; the line of the part's `[[part]]` header when the
        /// key is missing.
        line: usize,
        /// The key that is wrong.
        field: String,
        /// What is wrong with it.
        message: String,
    },
}

fn part_label(number: usize, name: Option<&str>, line: usize) -> String {
    match name {
        Some(n) => format!("part {number} (\"{n}\", line {line})"),
        None => format!("part {number} (line {line})"),
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SpecFile {
    #[serde(default)]
    part: Vec<Spanned<Table>>,
}

/// The 1-based line of `key = ...` in the part whose `[[part]]` header is on line `header`
/// (scanning until the next table header), or `header` when the key is not written there.
fn key_line(text: &str, header: usize, key: &str) -> usize {
    let key = key.split('[').next().unwrap_or(key);
    for (k, l) in text.lines().enumerate().skip(header) {
        let l = l.trim_start();
        if l.starts_with('[') {
            break;
        }
        let quoted = format!("\"{key}\"");
        if let Some(rest) = l
            .strip_prefix(key)
            .or_else(|| l.strip_prefix(quoted.as_str()))
        {
            if rest.trim_start().starts_with('=') {
                return k + 1;
            }
        }
    }
    header
}

/// The 1-based (line, column) of a byte offset.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.chars().rev().take_while(|&c| c != '\n').count() + 1;
    (line, column)
}

/// Reads the spec file at `path`; mesh files are looked up relative to its folder.
///
/// # Errors
/// A [`SpecError`] naming the part and field, or the line of a TOML syntax error.
pub fn read_spec(path: &Path) -> Result<Compound, SpecError> {
    let text = std::fs::read_to_string(path).map_err(|source| SpecError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    parse_spec(&text, dir)
}

/// Parses a spec; mesh `file`s are relative to `base_dir`.
///
/// ```
/// let spec = r#"
/// [[part]]
/// shape = "point"
/// mass = 2.0
/// position = [1, 0, 0]
/// "#;
/// let body = rigid::io::spec::parse_spec(spec, std::path::Path::new(".")).unwrap();
/// let props = body.mass_properties().unwrap();
/// assert_eq!(props.mass, 2.0);
/// assert_eq!(props.com.x, 1.0);
/// ```
///
/// # Errors
/// A [`SpecError`] naming the part and field, or the line of a TOML syntax error.
pub fn parse_spec(text: &str, base_dir: &Path) -> Result<Compound, SpecError> {
    let file: SpecFile = toml::from_str(text).map_err(|e| {
        let (line, column) = line_col(text, e.span().map_or(0, |s| s.start));
        SpecError::Syntax {
            line,
            column,
            message: e.message().trim().to_string(),
        }
    })?;
    if file.part.is_empty() {
        return Err(SpecError::NoParts);
    }
    let mut parts = Vec::with_capacity(file.part.len());
    for (i, spanned) in file.part.iter().enumerate() {
        let (header, _) = line_col(text, spanned.span().start);
        let table = spanned.get_ref();
        let name = match table.get("name") {
            Some(Value::String(s)) => Some(s.clone()),
            _ => None,
        };
        let fail = |field: &str, message: String| SpecError::Part {
            number: i + 1,
            name: name.clone(),
            line: key_line(text, header, field),
            field: field.to_string(),
            message,
        };
        parts.push(parse_part(table, name.clone(), base_dir).map_err(|(f, m)| fail(&f, m))?);
    }
    Ok(Compound::new(parts))
}

/// A field error: (key, message).
type FieldError = (String, String);

fn err<T>(field: &str, message: impl Into<String>) -> Result<T, FieldError> {
    Err((field.to_string(), message.into()))
}

const KEYS: [&str; 14] = [
    "name",
    "shape",
    "size",
    "radius",
    "length",
    "height",
    "semi_axes",
    "file",
    "inertia",
    "mass",
    "density",
    "position",
    "rpy",
    "quaternion",
];

/// The dimension keys each shape takes.
fn dimension_keys(shape: &str) -> Option<&'static [&'static str]> {
    Some(match shape {
        "box" => &["size"],
        "cylinder" | "capsule" => &["radius", "length"],
        "sphere" => &["radius"],
        "ellipsoid" => &["semi_axes"],
        "cone" => &["radius", "height"],
        "rod" => &["length"],
        "point" => &[],
        "mesh" => &["file"],
        "inertia" => &["inertia"],
        _ => return None,
    })
}

const DIMENSION_KEYS: [&str; 7] = [
    "size",
    "radius",
    "length",
    "height",
    "semi_axes",
    "file",
    "inertia",
];

fn number(key: &str, v: &Value) -> Result<f64, FieldError> {
    let x = match v {
        Value::Float(x) => *x,
        Value::Integer(i) => *i as f64,
        other => return err(key, format!("expected a number, got {}", other.type_str())),
    };
    if x.is_finite() {
        Ok(x)
    } else {
        err(key, format!("must be a finite number, got {x}"))
    }
}

fn numbers<const N: usize>(key: &str, v: &Value) -> Result<[f64; N], FieldError> {
    let Value::Array(a) = v else {
        return err(
            key,
            format!("expected an array of {N} numbers, got {}", v.type_str()),
        );
    };
    if a.len() != N {
        return err(key, format!("expected {N} numbers, got {}", a.len()));
    }
    let mut out = [0.0; N];
    for (k, x) in a.iter().enumerate() {
        out[k] = number(&format!("{key}[{k}]"), x)?;
    }
    Ok(out)
}

fn string<'a>(key: &str, v: &'a Value) -> Result<&'a str, FieldError> {
    match v {
        Value::String(s) => Ok(s),
        other => err(key, format!("expected a string, got {}", other.type_str())),
    }
}

fn positive(key: &str, x: f64) -> Result<f64, FieldError> {
    if x > 0.0 {
        Ok(x)
    } else {
        err(key, format!("must be positive, got {x}"))
    }
}

fn parse_part(t: &Table, name: Option<String>, base_dir: &Path) -> Result<Part, FieldError> {
    for (key, value) in t {
        if !KEYS.contains(&key.as_str()) {
            return err(
                key,
                format!("unknown key (known keys: {})", KEYS.join(", ")),
            );
        }
        if key == "name" {
            string(key, value)?;
        }
    }
    let Some(shape_value) = t.get("shape") else {
        return err("shape", "missing (box, cylinder, sphere, ellipsoid, capsule, cone, rod, point, mesh or inertia)");
    };
    let shape = string("shape", shape_value)?;
    let Some(keys) = dimension_keys(shape) else {
        return err(
            "shape",
            format!("unknown shape {shape:?} (expected box, cylinder, sphere, ellipsoid, capsule, cone, rod, point, mesh or inertia)"),
        );
    };
    for key in DIMENSION_KEYS {
        if t.contains_key(key) && !keys.contains(&key) {
            let takes = if keys.is_empty() {
                "no dimension".to_string()
            } else {
                keys.join(", ")
            };
            return err(
                key,
                format!("not used by shape {shape:?} (it takes: {takes})"),
            );
        }
    }
    let get = |key: &str| -> Result<&Value, FieldError> {
        t.get(key).ok_or_else(|| {
            (
                key.to_string(),
                format!("missing (shape {shape:?} needs it)"),
            )
        })
    };
    let scalar = |key: &str| -> Result<f64, FieldError> { positive(key, number(key, get(key)?)?) };
    let vec3 = |key: &str| -> Result<Vec3, FieldError> {
        let a = numbers::<3>(key, get(key)?)?;
        for (k, x) in a.iter().enumerate() {
            positive(&format!("{key}[{k}]"), *x)?;
        }
        Ok(Vec3::from(a))
    };
    let geometry = match shape {
        "box" => Geometry::Shape(Shape::Box {
            size: vec3("size")?,
        }),
        "cylinder" => Geometry::Shape(Shape::Cylinder {
            radius: scalar("radius")?,
            length: scalar("length")?,
        }),
        "capsule" => Geometry::Shape(Shape::Capsule {
            radius: scalar("radius")?,
            length: scalar("length")?,
        }),
        "sphere" => Geometry::Shape(Shape::Sphere {
            radius: scalar("radius")?,
        }),
        "ellipsoid" => Geometry::Shape(Shape::Ellipsoid {
            semi_axes: vec3("semi_axes")?,
        }),
        "cone" => Geometry::Shape(Shape::Cone {
            radius: scalar("radius")?,
            height: scalar("height")?,
        }),
        "rod" => Geometry::Shape(Shape::ThinRod {
            length: scalar("length")?,
        }),
        "point" => Geometry::Shape(Shape::Point),
        "mesh" => {
            let file = string("file", get("file")?)?;
            let path = base_dir.join(file);
            let mesh = read_mesh(&path)
                .map_err(|e| ("file".to_string(), format!("{}: {e}", path.display())))?;
            let props = mesh
                .mass_properties()
                .map_err(|e| ("file".to_string(), format!("{}: {e}", path.display())))?;
            Geometry::Mesh(props)
        }
        _ => {
            let [ixx, iyy, izz, ixy, ixz, iyz] = numbers::<6>("inertia", get("inertia")?)?;
            Geometry::Inertia(RotationalInertia::new(ixx, iyy, izz, ixy, ixz, iyz))
        }
    };
    let has_volume = geometry.volume().is_some();
    let mass = match (t.get("mass"), t.get("density")) {
        (Some(_), Some(_)) => return err("density", "give either `mass` or `density`, not both"),
        (None, None) if has_volume => {
            return err("mass", "missing: give `mass` (kg) or `density` (kg/m³)")
        }
        (None, None) => {
            return err(
                "mass",
                format!("missing (shape {shape:?} has no volume: give its `mass` in kg)"),
            )
        }
        (Some(m), None) => MassOrDensity::Mass(positive("mass", number("mass", m)?)?),
        (None, Some(_)) if !has_volume => {
            return err(
                "density",
                format!("shape {shape:?} has no volume: give its `mass` instead"),
            )
        }
        (None, Some(d)) => MassOrDensity::Density(positive("density", number("density", d)?)?),
    };
    let position = match t.get("position") {
        Some(v) => Vec3::from(numbers::<3>("position", v)?),
        None => Vec3::zeros(),
    };
    let rotation = match (t.get("rpy"), t.get("quaternion")) {
        (Some(_), Some(_)) => {
            return err("quaternion", "give either `rpy` or `quaternion`, not both")
        }
        (Some(v), None) => {
            let [r, p, y] = numbers::<3>("rpy", v)?;
            so3::from_rpy(r, p, y)
        }
        (None, Some(v)) => {
            let [x, y, z, w] = numbers::<4>("quaternion", v)?;
            so3::from_quaternion(x, y, z, w, QUATERNION_TOLERANCE).map_err(|e| {
                (
                    "quaternion".to_string(),
                    format!("{e} (tolerance {QUATERNION_TOLERANCE:e})"),
                )
            })?
        }
        (None, None) => Mat3::identity(),
    };
    Ok(Part {
        name,
        geometry,
        mass,
        pose: Transform::new(rotation, position),
    })
}
