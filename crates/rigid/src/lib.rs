//! # rigid: rigid-body dynamics for Rust
//!
//! The crate follows the notation of Lynch & Park, *Modern Robotics*, and Featherstone's spatial
//! algebra. Twists `V = (ω, v)` and wrenches `F = (m, f)` are **angular first**; `T_ab` is frame
//! {b} seen from {a}; SI units throughout.
//!
//! The modules, each using only those above it (docs/architecture.md):
//!
//! | module | what | feature |
//! | --- | --- | --- |
//! | [`spatial`] | SO(3), SE(3), twists, wrenches, `Ad`, `ad`, exp and log; the small dense kernels | core |
//! | [`mass`] | rotational inertia, shapes, meshes, compound bodies, spatial inertia `G`, pseudo-inertia and physical consistency | core |
//! | [`multibody`] | kinematic trees: `Model` (with its compiled plan), `Data`, joints, the textbook [`multibody::reference`] algorithms beside the fast ones (kinematics, Jacobians, RNEA, CRBA, ABA, `M⁻¹`, Coriolis, energies, derivatives), constrained dynamics, builders, built-in robots; no geometry | core (`batch`: `parallel`) |
//! | [`collision`] | collision geometry (URDF `<collision>`, MJCF geoms, body parts, a ground plane) and contact points, on parry3d-f64 | `collision` |
//! | [`simulation`] | the one simulation step: kinematics, collision, one constraint problem (loops, contacts, limits), integration; controllers, trajectories, batches | core (`collision` for contacts) |
//! | [`kinematics`] | inverse kinematics: Newton / Levenberg-Marquardt on the SE(3) log error (`IKinBody`, `IKinSpace`), position or full pose, limits, restarts | core |
//! | [`mobile`] | wheeled mobile robots: omnidirectional and nonholonomic bases, `H(φ)`, `F`, odometry, mobile manipulators, task-space feedback, the *Modern Robotics* capstone | core |
//! | [`body`] | one body in motion: Newton-Euler, Euler, Lagrange by autodiff, and its simulator (the one-joint case of the multibody simulator, plus the Lie-group variational integrator) | core (`lagrange`: `autodiff`) |
//! | [`identification`] | inertial parameters from measured motion: joint-torque regressor, base parameters, least squares, physically consistent estimate (semidefinite program, feature `sdp`), exciting trajectories | core (`regressor_batch`: `parallel`; `sdp`) |
//! | [`io`] | reading files: meshes (STL, OBJ, COLLADA), `rigid mass` specs (TOML), URDF and MJCF robots, case and constraint files, example-robot-data | `mesh`, `spec`, `urdf`, `mjcf`, `serde` |
//! | [`doctor`] | what is wrong with a robot file's inertias, the likely cause, the repair (`rigid doctor`) | `urdf` |
//! | [`interop`] | Pinocchio's and MuJoCo's layouts of the same vectors and matrices | core |
//! | [`explicit`] | the explicit dynamic model of a robot (Armstrong, Khatib & Burdick 1986): `M(q)`, Coriolis, centrifugal and gravity terms as abbreviated expressions, pruned with a proven bound, and generated code | `explicit` |
//! | [`timing`] | how fast the multibody algorithms and their batches run on a model (`rigid bench`) | `parallel` |
//!
//! Every feature is on by default. With `default-features = false` the crate is the dynamics core
//! ("core" above), which depends on nalgebra and thiserror alone; `serde` adds the serialised
//! form of a [`multibody::Model`] (`to_json`, serde).
#![warn(missing_docs)]
#![allow(non_snake_case)]

pub mod body;
#[cfg(feature = "collision")]
pub mod collision;
#[cfg(feature = "urdf")]
pub mod doctor;
pub mod error;
#[cfg(feature = "explicit")]
pub mod explicit;
#[cfg(all(feature = "mjcf", feature = "spec", feature = "serde"))]
#[doc(hidden)]
pub mod fuzzing;
pub mod identification;
pub mod interop;
pub mod io;
pub mod kinematics;
pub mod mass;
pub mod mobile;
pub mod multibody;
pub mod simulation;
pub mod spatial;
#[cfg(feature = "parallel")]
pub mod timing;

// The README's code examples, compiled and run as doctests (`cargo test -p rigid --doc`).
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
