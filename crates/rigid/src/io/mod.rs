//! Reading models and descriptions from files: URDF robots.

pub mod urdf;
