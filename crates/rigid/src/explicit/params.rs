//! The model's parameters as symbols: the inertial parameters of every body (Khalil's standard
//! parameters, linear in the dynamics), the joints' offsets, the armature and gravity.
//!
//! | name | meaning | unit |
//! | --- | --- | --- |
//! | `Mj` | mass of body j | kg |
//! | `MXj`, `MYj`, `MZj` | first moment `m c` of body j, in joint j's frame | kg·m |
//! | `XXj`, `XYj`, `XZj`, `YYj`, `YZj`, `ZZj` | rotational inertia of body j about joint j's origin, in its frame (`XY = -∫xy dm`, the matrix entry) | kg·m² |
//! | `pxj`, `pyj`, `pzj` | origin of joint j's frame in its parent's frame (the URDF `<origin xyz>`, DH `a`, `d`) | m |
//! | `IAj` | armature (rotor inertia) of joint j | kg·m² or kg |
//! | `g` | magnitude of gravity (its direction is a number) | m/s² |
//!
//! Bodies and joints are numbered from 1, as in the tables. A parameter whose value is zero in
//! the model (to 1e-14 in SI units, which covers the round-off of a DH `cos(π/2)`) is not a
//! symbol: the expressions are specific to the model's zero pattern, as the 1986 tables were.

use std::fmt;

/// What a parameter stands for (indices 0-based).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamKind {
    /// The mass of a body.
    Mass {
        /// The body (= its joint).
        body: usize,
    },
    /// A component (0 = x) of a body's first moment `m c`.
    FirstMoment {
        /// The body.
        body: usize,
        /// The component.
        axis: usize,
    },
    /// An entry (row ≤ column) of a body's rotational inertia about its joint origin.
    Inertia {
        /// The body.
        body: usize,
        /// Row.
        row: usize,
        /// Column.
        col: usize,
    },
    /// A component of a joint frame's origin in its parent's frame.
    Offset {
        /// The joint.
        joint: usize,
        /// The component.
        axis: usize,
    },
    /// A joint's armature.
    Armature {
        /// The joint.
        joint: usize,
    },
    /// The magnitude of gravity.
    Gravity,
}

/// One symbol with its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Parameter {
    /// Its name in the tables (`MX3`, `pz4`, `g`).
    pub name: String,
    /// Its value in the model (SI).
    pub value: f64,
    /// What it stands for.
    pub kind: ParamKind,
}

impl Parameter {
    /// The SI unit of the value.
    #[must_use]
    pub fn unit(&self) -> &'static str {
        match self.kind {
            ParamKind::Mass { .. } => "kg",
            ParamKind::FirstMoment { .. } => "kg·m",
            ParamKind::Inertia { .. } | ParamKind::Armature { .. } => "kg·m²",
            ParamKind::Offset { .. } => "m",
            ParamKind::Gravity => "m/s²",
        }
    }
}

/// The symbols of a model, indexed as in the parameter monomials of an
/// [`Expr`](super::Expr).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Parameters {
    list: Vec<Parameter>,
}

/// Values this close to zero (SI units) are taken as zero.
pub(crate) const ZERO: f64 = 1e-14;

impl Parameters {
    /// Adds a symbol unless its value is (numerically) zero; returns its index.
    pub(crate) fn add(&mut self, name: String, value: f64, kind: ParamKind) -> Option<usize> {
        if value.abs() <= ZERO {
            return None;
        }
        self.list.push(Parameter { name, value, kind });
        Some(self.list.len() - 1)
    }

    /// All symbols, in order.
    #[must_use]
    pub fn list(&self) -> &[Parameter] {
        &self.list
    }

    /// Their values, in order.
    #[must_use]
    pub fn values(&self) -> Vec<f64> {
        self.list.iter().map(|p| p.value).collect()
    }

    /// Number of symbols.
    #[must_use]
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Whether there are none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The symbol `p`.
    #[must_use]
    pub fn get(&self, p: usize) -> &Parameter {
        &self.list[p]
    }
}

impl fmt::Display for Parameter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {} {}", self.name, self.value, self.unit())
    }
}
