//! Compound bodies: rigidly joined parts, each a primitive shape, a closed mesh or a hand-given
//! inertia, with a mass (or density) and a pose in the body frame.
//!
//! The inertia of a compound body is the sum of its parts' inertias expressed in a common frame
//! (notes 001): each part's spatial inertia `G_p` at its own frame {p} is moved to the body frame
//! {b} by `G_b = [Ad_{T_pb}]ᵀ G_p [Ad_{T_pb}]` ([`SpatialInertia::transformed`]) and the results
//! are added.

use super::{MeshMassProperties, RotationalInertia, Shape, SpatialInertia};
use crate::error::InertiaError;
use crate::spatial::{Mat3, Transform, Vec3};
use thiserror::Error;

/// What a part is made of.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A primitive solid, rod or point, centred at the part frame's origin.
    Shape(Shape),
    /// The solid bounded by a closed mesh, in the part frame's coordinates (its centroid need
    /// not be at the origin).
    Mesh(MeshMassProperties),
    /// A hand-given rigid body: CoM at the part frame's origin, inertia about it in the part
    /// frame's axes. It is not checked for physical validity (the compound's validity is
    /// reported by [`MassProperties::validity`]).
    Inertia(RotationalInertia),
}

impl Geometry {
    /// The volume, if the geometry has one (`None` for a rod, a point or a given inertia).
    #[must_use]
    pub fn volume(&self) -> Option<f64> {
        match self {
            Geometry::Shape(s) if s.has_volume() => Some(s.volume()),
            Geometry::Mesh(m) => Some(m.volume),
            _ => None,
        }
    }
}

/// How a part's mass is given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MassOrDensity {
    /// The total mass (kg).
    Mass(f64),
    /// A uniform density (kg/m³); the mass is `ρ V`.
    Density(f64),
}

/// One rigid part of a compound body.
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    /// An optional name, for messages.
    pub name: Option<String>,
    /// The geometry, in the part frame {p}.
    pub geometry: Geometry,
    /// The mass or density.
    pub mass: MassOrDensity,
    /// The pose `T_bp` of the part frame {p} in the body frame {b}.
    pub pose: Transform,
}

/// A part whose mass cannot be worked out.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum PartError {
    /// A density was given for a geometry without volume.
    #[error("a {what} has no volume: give its `mass`, not a `density`")]
    DensityWithoutVolume {
        /// What the geometry is (`point`, `rod`, `inertia`).
        what: &'static str,
    },
    /// The mass, CoM or inertia comes out infinite or NaN (dimensions or density so large that
    /// `f64` overflows).
    #[error("the mass properties overflow (mass {mass}): dimensions or density too large")]
    Overflow {
        /// The mass found.
        mass: f64,
    },
    /// The mass or density is not a positive finite number.
    #[error("{field} must be positive and finite, got {value}")]
    BadMass {
        /// `mass` or `density`.
        field: &'static str,
        /// The value found.
        value: f64,
    },
}

impl Part {
    /// The part's mass `m` (kg): the given mass, or `ρ V`.
    ///
    /// # Errors
    /// [`PartError::BadMass`] for a mass or density that is not positive and finite,
    /// [`PartError::DensityWithoutVolume`] for a density on a rod, point or given inertia.
    pub fn mass(&self) -> Result<f64, PartError> {
        let (field, value) = match self.mass {
            MassOrDensity::Mass(m) => ("mass", m),
            MassOrDensity::Density(rho) => ("density", rho),
        };
        if !(value.is_finite() && value > 0.0) {
            return Err(PartError::BadMass { field, value });
        }
        match self.mass {
            MassOrDensity::Mass(m) => Ok(m),
            MassOrDensity::Density(rho) => match self.geometry.volume() {
                Some(v) => Ok(rho * v),
                None => Err(PartError::DensityWithoutVolume {
                    what: match &self.geometry {
                        Geometry::Shape(s) => s.name(),
                        _ => "inertia",
                    },
                }),
            },
        }
    }

    /// The part's spatial inertia `G_p` in its own frame {p}.
    ///
    /// # Errors
    /// As [`Part::mass`], and [`PartError::Overflow`] when a number is not finite.
    pub fn spatial_inertia_local(&self) -> Result<SpatialInertia, PartError> {
        let m = self.mass()?;
        let g = match &self.geometry {
            Geometry::Shape(s) => SpatialInertia::from_com(m, Vec3::zeros(), s.inertia_com(m)),
            Geometry::Mesh(p) => SpatialInertia::from_com(m, p.com, p.inertia_com(m)),
            Geometry::Inertia(i) => SpatialInertia::from_com(m, Vec3::zeros(), *i),
        };
        if g.matrix().iter().all(|x| x.is_finite()) {
            Ok(g)
        } else {
            Err(PartError::Overflow { mass: m })
        }
    }

    /// The part's spatial inertia in the body frame {b}:
    /// `G_b = [Ad_{T_pb}]ᵀ G_p [Ad_{T_pb}]` with `T_pb = T_bp⁻¹`.
    ///
    /// # Errors
    /// As [`Part::spatial_inertia_local`] (a position so far away that `m |p|²` overflows is
    /// [`PartError::Overflow`] too).
    pub fn spatial_inertia(&self) -> Result<SpatialInertia, PartError> {
        let g = self.spatial_inertia_local()?.transformed(&self.pose);
        if g.matrix().iter().all(|x| x.is_finite()) {
            Ok(g)
        } else {
            Err(PartError::Overflow { mass: g.mass() })
        }
    }
}

/// A body made of rigidly joined [`Part`]s, all posed in the body frame {b}.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Compound {
    /// The parts.
    pub parts: Vec<Part>,
}

/// A compound whose mass properties cannot be computed.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CompoundError {
    /// One part is bad; `index` counts from 0.
    #[error("part {index}: {source}")]
    Part {
        /// The index of the part (from 0).
        index: usize,
        /// What is wrong.
        source: PartError,
    },
    /// No part at all, or a total mass of zero.
    #[error("the body has no mass (no parts)")]
    NoMass,
}

/// The mass properties of a rigid body, in its body frame {b}.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProperties {
    /// The total mass `m` (kg).
    pub mass: f64,
    /// The centre of mass `c` in {b} (m).
    pub com: Vec3,
    /// The rotational inertia about the CoM, in the axes of {b}.
    pub inertia_com: RotationalInertia,
    /// The rotational inertia about the origin of {b}: `I_c + m[c]ᵀ[c]`.
    pub inertia_origin: RotationalInertia,
    /// The principal moments about the CoM, ascending.
    pub principal_moments: Vec3,
    /// The principal axes (columns, in {b}) of a right-handed rotation: `I_c = R diag(λ) Rᵀ`.
    pub principal_axes: Mat3,
    /// The spatial inertia `G` about the origin of {b}, angular first.
    pub spatial_inertia_origin: SpatialInertia,
}

impl MassProperties {
    /// The mass properties of the body whose spatial inertia in {b} is `g`.
    #[must_use]
    pub fn from_spatial_inertia(g: &SpatialInertia) -> Self {
        let inertia_com = g.inertia_com();
        let (principal_moments, principal_axes) = inertia_com.principal();
        Self {
            mass: g.mass(),
            com: g.com(),
            inertia_com,
            inertia_origin: g.inertia_origin(),
            principal_moments,
            principal_axes,
            spatial_inertia_origin: *g,
        }
    }

    /// Whether the body is physical: positive mass and an inertia about the CoM that is positive
    /// semi-definite and satisfies the triangle inequality, with relative tolerance `tol`.
    ///
    /// # Errors
    /// The first test that fails, as an [`InertiaError`].
    pub fn validity(&self, tol: f64) -> Result<(), InertiaError> {
        self.spatial_inertia_origin.validate(tol)
    }
}

impl Compound {
    /// What is wrong, naming a bad part by its number from 1 and its name:
    /// `part 2 ("prism"): ...`.
    ///
    /// ```
    /// use rigid::mass::{Compound, CompoundError};
    /// assert_eq!(Compound::new(vec![]).error_message(&CompoundError::NoMass), "the body has no mass (no parts)");
    /// ```
    #[must_use]
    pub fn error_message(&self, e: &CompoundError) -> String {
        match e {
            CompoundError::Part { index, source } => {
                let name = self
                    .parts
                    .get(*index)
                    .and_then(|p| p.name.as_deref())
                    .map(|n| format!(" (\"{n}\")"))
                    .unwrap_or_default();
                format!("part {}{name}: {source}", index + 1)
            }
            other => other.to_string(),
        }
    }

    /// A compound of the given parts.
    #[must_use]
    pub fn new(parts: Vec<Part>) -> Self {
        Self { parts }
    }

    /// The spatial inertia about the origin of {b}: `Σ_p [Ad_{T_pb}]ᵀ G_p [Ad_{T_pb}]`.
    ///
    /// # Errors
    /// The first bad part, as [`CompoundError::Part`].
    pub fn spatial_inertia(&self) -> Result<SpatialInertia, CompoundError> {
        let mut g = SpatialInertia::zero();
        for (index, p) in self.parts.iter().enumerate() {
            g += p
                .spatial_inertia()
                .map_err(|source| CompoundError::Part { index, source })?;
        }
        Ok(g)
    }

    /// Total mass, CoM, inertia about the CoM and about the origin, principal moments and axes,
    /// and spatial inertia about the origin.
    ///
    /// ```
    /// use rigid::mass::{Compound, Geometry, MassOrDensity, Part, Shape};
    /// use rigid::spatial::{Transform, Vec3};
    /// let point = |x: f64| Part {
    ///     name: None,
    ///     geometry: Geometry::Shape(Shape::Point),
    ///     mass: MassOrDensity::Mass(1.0),
    ///     pose: Transform::from_translation(Vec3::new(x, 0.0, 0.0)),
    /// };
    /// let props = Compound::new(vec![point(1.0), point(3.0)]).mass_properties().unwrap();
    /// assert_eq!(props.mass, 2.0);
    /// assert!((props.com - Vec3::new(2.0, 0.0, 0.0)).norm() < 1e-15);
    /// assert!((props.inertia_com.matrix()[(1, 1)] - 2.0).abs() < 1e-12);
    /// ```
    ///
    /// # Errors
    /// A bad part, or [`CompoundError::NoMass`] when there is no part.
    pub fn mass_properties(&self) -> Result<MassProperties, CompoundError> {
        let g = self.spatial_inertia()?;
        if g.mass() <= 0.0 {
            return Err(CompoundError::NoMass);
        }
        Ok(MassProperties::from_spatial_inertia(&g))
    }
}
