//! # rigid: rigid-body dynamics for Rust
//!
//! The crate follows the notation of Lynch & Park, *Modern Robotics*, and Featherstone's spatial
//! algebra. Twists `V = (ω, v)` and wrenches `F = (m, f)` are **angular first**; `T_ab` is frame
//! {b} seen from {a}; SI units throughout.
//!
//! The modules depend only downward:
//!
//! | module | what |
//! | --- | --- |
//! | [`spatial`] | SO(3), SE(3), twists, wrenches, `Ad`, `ad`, exp and log |
//! | [`mass`] | rotational inertia, shapes, meshes, compound bodies, spatial inertia `G`, pseudo-inertia and physical consistency |
//! | [`io`] | reading files: triangle meshes (STL, OBJ, COLLADA), `rigid mass` body specs (TOML) |
//! | [`multibody`] | kinematic trees: `Model`, `Data`, joints, forward kinematics, Jacobians, RNEA, CRBA, ABA, `M⁻¹`, Coriolis matrix, energies, analytical derivatives of the dynamics, DH and Modern Robotics builders, built-in robots, simulation |
//! | [`collision`] | collision geometry (URDF `<collision>`, body parts, a ground plane) and contact points, on parry3d-f64 (feature `collision`, on by default) |
//! | [`body`] | one body in motion: Newton-Euler, Euler, Lagrange by autodiff, and its simulator (the one-joint case of the multibody simulator, plus the Lie-group variational integrator) |
//! | [`io`] | URDF import into a multibody `Model` (inertia policy, warnings); `rigid doctor` ([`doctor`]) |
//! | [`explicit`] | the explicit dynamic model of a robot (Armstrong, Khatib & Burdick 1986): `M(q)`, Coriolis, centrifugal and gravity terms as abbreviated expressions, pruned with a proven bound, and generated code |
//! | [`identification`] | inertial parameters from measured motion: joint-torque regressor, base parameters, least squares, physically consistent estimate (semidefinite program), exciting trajectories |
//! | [`timing`] | how fast the multibody algorithms and their batches run on a model (`rigid bench`) |
#![warn(missing_docs)]
#![allow(non_snake_case)]

pub mod body;
#[cfg(feature = "collision")]
pub mod collision;
pub mod doctor;
pub mod error;
pub mod explicit;
#[doc(hidden)]
pub mod fuzzing;
pub mod identification;
pub mod interop;
pub mod io;
pub mod mass;
pub mod multibody;
pub mod spatial;
pub mod timing;

// The README's code examples, compiled and run as doctests (`cargo test -p rigid --doc`).
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
