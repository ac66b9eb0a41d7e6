//! Constrained dynamics (closed loops and rigid contacts): against Pinocchio 4.1 (checked-in
//! fixture, live with `RIGID_CROSSCHECK=1`), the identities `M q̈ + c + g = τ + Jᵀ λ` and
//! `J q̈ + γ = 0`, `γ` by finite differences, closed forms (the rod on a spherical pivot of the
//! notes 002), a four-bar linkage simulated for 10 s, and the errors.

#![allow(non_snake_case)]

mod derivatives;
mod identities;
mod mechanics;
mod mjcf;
mod pinocchio;
mod pinocchio_derivatives;

use rigid::io::urdf::{load_urdf_with, SiblingOrder, UrdfOptions};
use rigid::multibody::Model;
use std::path::PathBuf;

/// `tests/fixtures/constraints/`.
pub fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/constraints")
}

/// A URDF of the fixtures, sibling joints sorted by name (Pinocchio's order).
pub fn load(rel: &str, floating: bool) -> Model {
    let opts = UrdfOptions {
        floating,
        sibling_order: SiblingOrder::Name,
        ..UrdfOptions::default()
    };
    load_urdf_with(fixtures().join(rel), &opts)
        .unwrap_or_else(|e| panic!("{rel}: {e}"))
        .0
}

/// `max |x − y| / max(1, ‖y‖∞)`.
pub fn rel_err(x: &[f64], y: &[f64]) -> f64 {
    assert_eq!(x.len(), y.len());
    let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(y)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale
}
