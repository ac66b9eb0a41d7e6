//! Error types shared by several modules. Each error says what is wrong with numbers, so that the
//! caller (the importer, the CLI) can add which body, joint or line it came from.

use thiserror::Error;

/// A matrix or quaternion that should be a rotation and is not.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum RotationError {
    /// A quaternion whose norm is not 1 (within the tolerance).
    #[error("quaternion is not a unit quaternion (norm {norm})")]
    NotUnitQuaternion {
        /// The norm found.
        norm: f64,
    },
    /// `RᵀR` differs from the identity.
    #[error("matrix is not orthonormal (max |RᵀR - I| = {error:.3e})")]
    NotOrthonormal {
        /// The largest entry of `|RᵀR - I|`.
        error: f64,
    },
    /// `det R = -1`.
    #[error("matrix is a reflection (det = -1), not a rotation")]
    Reflection,
    /// An axis of zero length.
    #[error("rotation axis has zero or non-finite length, or the angle is not finite")]
    ZeroAxis,
    /// A NaN or infinite entry.
    #[error("rotation has a non-finite entry")]
    NonFinite,
}

/// A rotational or spatial inertia that is not physical.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum InertiaError {
    /// A NaN or infinite entry.
    #[error("inertia has a non-finite entry")]
    NonFinite,
    /// Mass not finite or negative (or zero where a positive mass is needed).
    #[error("mass must be positive and finite, got {mass}")]
    BadMass {
        /// The mass found.
        mass: f64,
    },
    /// `I ≠ Iᵀ`.
    #[error("inertia matrix is not symmetric (max |I - Iᵀ| = {asymmetry:.3e})")]
    NotSymmetric {
        /// The largest entry of `|I - Iᵀ|`.
        asymmetry: f64,
    },
    /// A negative principal moment.
    #[error("inertia is not positive semi-definite: principal moment {moment:.6e} < 0")]
    NotPositiveSemiDefinite {
        /// The smallest principal moment.
        moment: f64,
    },
    /// `λi + λj < λk`: no mass distribution has these principal moments.
    #[error(
        "principal moments violate the triangle inequality: {small_sum:.6e} = λ1 + λ2 < λ3 = {largest:.6e}"
    )]
    TriangleInequality {
        /// The sum of the two smaller principal moments.
        small_sum: f64,
        /// The largest principal moment.
        largest: f64,
    },
}

/// An input vector of the wrong length.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("{what}: expected length {expected}, got {got}")]
pub struct DimensionError {
    /// Which argument.
    pub what: &'static str,
    /// The length needed.
    pub expected: usize,
    /// The length given.
    pub got: usize,
}

impl DimensionError {
    /// `Ok(())` if `got == expected`, else the error.
    ///
    /// # Errors
    /// A [`DimensionError`] naming `what`.
    #[inline]
    pub fn check(what: &'static str, expected: usize, got: usize) -> Result<(), DimensionError> {
        if expected == got {
            Ok(())
        } else {
            Err(DimensionError {
                what,
                expected,
                got,
            })
        }
    }
}
