//! Primitive solids of uniform density: volume and rotational inertia about the centroid, in
//! closed form (the notes 000 for box, cylinder, ellipsoid; the usual tables for the others).
//!
//! Every shape's frame has its origin at the centroid (= CoM for uniform density) and its axes
//! along the shape's symmetry axes, so every inertia here is diagonal.

use super::RotationalInertia;
use crate::spatial::Vec3;
use std::f64::consts::PI;
use thiserror::Error;

/// A primitive solid (or a massive point or rod), in its own frame: origin at the centroid, axes
/// along the symmetry axes. Dimensions in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A rectangular box (parallelepiped) of edge lengths `size = [lx, ly, lz]` along x, y, z.
    Box {
        /// The edge lengths `[lx, ly, lz]`.
        size: Vec3,
    },
    /// A solid circular cylinder, axis along z, from `z = -length/2` to `z = length/2`.
    Cylinder {
        /// The radius `r`.
        radius: f64,
        /// The length `L` along z.
        length: f64,
    },
    /// A solid ball.
    Sphere {
        /// The radius `r`.
        radius: f64,
    },
    /// A solid ellipsoid `(x/a)² + (y/b)² + (z/c)² ≤ 1`.
    Ellipsoid {
        /// The semi-axes `[a, b, c]` along x, y, z.
        semi_axes: Vec3,
    },
    /// A capsule: a cylinder of radius `r` and length `L` along z, capped by two solid
    /// hemispheres of radius `r`; total length `L + 2r`.
    Capsule {
        /// The radius `r` of the cylinder and of the caps.
        radius: f64,
        /// The length `L` of the cylindrical part (without the caps).
        length: f64,
    },
    /// A solid right circular cone, axis along z, **origin at the centroid**: the base (radius
    /// `r`) lies in the plane `z = -h/4` and the apex is at `z = +3h/4`.
    Cone {
        /// The radius `r` of the base.
        radius: f64,
        /// The height `h` from base to apex.
        height: f64,
    },
    /// A thin rod (a segment carrying mass, no thickness) along z from `-length/2` to `length/2`.
    /// It has no volume: give it a mass, not a density.
    ThinRod {
        /// The length `L`.
        length: f64,
    },
    /// A point mass at the origin. It has no volume: give it a mass, not a density.
    Point,
}

/// A shape dimension that is not a positive finite number.
#[derive(Clone, Debug, Error, PartialEq)]
#[error("{field} must be positive and finite, got {value}")]
pub struct ShapeError {
    /// The dimension, as named in a spec file (`radius`, `size[1]`, …).
    pub field: &'static str,
    /// The value found.
    pub value: f64,
}

fn positive(field: &'static str, value: f64) -> Result<(), ShapeError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(ShapeError { field, value })
    }
}

fn positive3(fields: [&'static str; 3], v: &Vec3) -> Result<(), ShapeError> {
    for (f, x) in fields.iter().zip(v.iter()) {
        positive(f, *x)?;
    }
    Ok(())
}

impl Shape {
    /// The shape's name as written in a spec file (`box`, `cylinder`, …, `rod`, `point`).
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Box { .. } => "box",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Ellipsoid { .. } => "ellipsoid",
            Shape::Capsule { .. } => "capsule",
            Shape::Cone { .. } => "cone",
            Shape::ThinRod { .. } => "rod",
            Shape::Point => "point",
        }
    }

    /// Checks that every dimension is positive and finite.
    ///
    /// # Errors
    /// A [`ShapeError`] naming the first bad dimension (`size[0]`, `radius`, …).
    pub fn validate(&self) -> Result<(), ShapeError> {
        match self {
            Shape::Box { size } => positive3(["size[0]", "size[1]", "size[2]"], size),
            Shape::Cylinder { radius, length } | Shape::Capsule { radius, length } => {
                positive("radius", *radius)?;
                positive("length", *length)
            }
            Shape::Sphere { radius } => positive("radius", *radius),
            Shape::Ellipsoid { semi_axes } => {
                positive3(["semi_axes[0]", "semi_axes[1]", "semi_axes[2]"], semi_axes)
            }
            Shape::Cone { radius, height } => {
                positive("radius", *radius)?;
                positive("height", *height)
            }
            Shape::ThinRod { length } => positive("length", *length),
            Shape::Point => Ok(()),
        }
    }

    /// Whether the shape has a volume (so a density makes sense); false for a rod and a point.
    #[must_use]
    pub fn has_volume(&self) -> bool {
        !matches!(self, Shape::ThinRod { .. } | Shape::Point)
    }

    /// The volume (m³):
    ///
    /// | shape | volume |
    /// | --- | --- |
    /// | box | `lx ly lz` |
    /// | cylinder | `π r² L` |
    /// | sphere | `4/3 π r³` |
    /// | ellipsoid | `4/3 π a b c` |
    /// | capsule | `π r² L + 4/3 π r³` |
    /// | cone | `π r² h / 3` |
    /// | rod, point | `0` |
    #[must_use]
    pub fn volume(&self) -> f64 {
        match *self {
            Shape::Box { size } => size.x * size.y * size.z,
            Shape::Cylinder { radius, length } => PI * radius * radius * length,
            Shape::Sphere { radius } => 4.0 / 3.0 * PI * radius.powi(3),
            Shape::Ellipsoid { semi_axes: a } => 4.0 / 3.0 * PI * a.x * a.y * a.z,
            Shape::Capsule { radius, length } => {
                PI * radius * radius * length + 4.0 / 3.0 * PI * radius.powi(3)
            }
            Shape::Cone { radius, height } => PI * radius * radius * height / 3.0,
            Shape::ThinRod { .. } | Shape::Point => 0.0,
        }
    }

    /// The rotational inertia about the centroid in the shape's frame, for a uniform body of mass
    /// `m` (kg). All are diagonal, `diag(I_xx, I_yy, I_zz)`:
    ///
    /// | shape | `I_xx` | `I_yy` | `I_zz` | source |
    /// | --- | --- | --- | --- | --- |
    /// | box | `m(ly²+lz²)/12` | `m(lx²+lz²)/12` | `m(lx²+ly²)/12` | notes 000 |
    /// | cylinder | `m(3r²+L²)/12` | same | `m r²/2` | notes 000 |
    /// | sphere | `2/5 m r²` | same | same | notes 000 (ellipsoid, a=b=c) |
    /// | ellipsoid | `m(b²+c²)/5` | `m(a²+c²)/5` | `m(a²+b²)/5` | notes 000 |
    /// | cone | `3/20 m r² + 3/80 m h²` | same | `3/10 m r²` | Meriam & Kraige, Table D/4, moved from the apex to the centroid by Steiner (`3/5 h² - (3h/4)² = 3/80 h²`) |
    /// | rod | `m L²/12` | same | `0` | Meriam & Kraige, Table D/4 |
    /// | point | `0` | `0` | `0` | |
    ///
    /// Capsule (derived here): the cylinder has mass `m_c = m V_c / V` with `V_c = π r² L`, the
    /// two hemispheres together `m_s = m - m_c`. A solid hemisphere of mass `μ` has, about the
    /// centre of its flat face, the ball's `2/5 μ r²` about every axis, and its CoM is `3r/8` from
    /// that face; so about its own CoM, across the axis, `(2/5 - 9/64) μ r² = 83/320 μ r²`. Its CoM
    /// is `d = L/2 + 3r/8` from the capsule's centre, and Steiner gives
    /// `μ (83/320 r² + d²) = μ (2/5 r² + L²/4 + 3 L r / 8)`. Summing:
    ///
    /// `I_xx = I_yy = m_c (r²/4 + L²/12) + m_s (2/5 r² + L²/4 + 3 L r / 8)`,
    /// `I_zz = m_c r²/2 + 2/5 m_s r²`.
    ///
    /// ```
    /// use rigid::mass::Shape;
    /// let i = Shape::Cylinder { radius: 0.1, length: 0.2 }.inertia_com(2.0);
    /// assert!((i.matrix()[(0, 0)] - 2.0 * (3.0 * 0.01 + 0.04) / 12.0).abs() < 1e-15);
    /// assert!((i.matrix()[(2, 2)] - 0.01).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn inertia_com(&self, m: f64) -> RotationalInertia {
        match *self {
            Shape::Box { size: s } => {
                let (x2, y2, z2) = (s.x * s.x, s.y * s.y, s.z * s.z);
                RotationalInertia::diagonal(
                    m * (y2 + z2) / 12.0,
                    m * (x2 + z2) / 12.0,
                    m * (x2 + y2) / 12.0,
                )
            }
            Shape::Cylinder {
                radius: r,
                length: l,
            } => {
                let across = m * (3.0 * r * r + l * l) / 12.0;
                RotationalInertia::diagonal(across, across, m * r * r / 2.0)
            }
            Shape::Sphere { radius: r } => {
                let i = 0.4 * m * r * r;
                RotationalInertia::diagonal(i, i, i)
            }
            Shape::Ellipsoid { semi_axes: a } => {
                let (a2, b2, c2) = (a.x * a.x, a.y * a.y, a.z * a.z);
                RotationalInertia::diagonal(
                    m * (b2 + c2) / 5.0,
                    m * (a2 + c2) / 5.0,
                    m * (a2 + b2) / 5.0,
                )
            }
            Shape::Capsule {
                radius: r,
                length: l,
            } => {
                let v_c = PI * r * r * l;
                let v_s = 4.0 / 3.0 * PI * r.powi(3);
                let m_c = m * v_c / (v_c + v_s);
                let m_s = m - m_c;
                let across = m_c * (r * r / 4.0 + l * l / 12.0)
                    + m_s * (0.4 * r * r + l * l / 4.0 + 3.0 * l * r / 8.0);
                RotationalInertia::diagonal(across, across, 0.5 * m_c * r * r + 0.4 * m_s * r * r)
            }
            Shape::Cone {
                radius: r,
                height: h,
            } => {
                let across = m * (3.0 / 20.0 * r * r + 3.0 / 80.0 * h * h);
                RotationalInertia::diagonal(across, across, 0.3 * m * r * r)
            }
            Shape::ThinRod { length: l } => {
                let across = m * l * l / 12.0;
                RotationalInertia::diagonal(across, across, 0.0)
            }
            Shape::Point => RotationalInertia::zero(),
        }
    }
}
