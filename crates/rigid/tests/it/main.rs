//! The integration tests of `rigid`, one test binary (each file a module; `common` and
//! `explicit_support` are shared helpers). The tests that install a counting
//! `#[global_allocator]` are the other binary, `tests/alloc`.
//!
//! The data beside this folder: `fixtures/` (reference values, each with the script that
//! generated it, and the robot files the tests load), `pinocchio/` (the Pinocchio reference
//! scripts and their fixtures), `doctor/` (the fault corpus of `rigid doctor`), `simulation/`
//! (the SciPy reference of the double pendulum), `proptest-regressions/` (proptest's saved
//! failure seeds: for a source file under a folder holding `main.rs` it reads and writes
//! `../proptest-regressions/<file>.txt`, so `it/compound.rs` has
//! `proptest-regressions/compound.txt`).
//!
//! `cargo test` needs nothing but Rust: the comparisons with Pinocchio, SciPy and real robot files
//! read the checked-in fixtures. The checks that need Python (and its packages), a browser, a C
//! compiler, `rustc` or `rustfmt` at test time are live checks, run when `RIGID_CROSSCHECK=1`
//! (`common::reference`; `scripts/test.sh` sets it, in a virtual environment it creates).

mod common;
mod explicit_support;

mod body_lagrange;
mod body_newton_euler;
mod body_simulate;
mod centroidal;
mod collada;
mod compound;
mod consistency;
mod constraints;
mod contact;
mod doctor;
mod doctor_mjcf;
mod explicit_codegen;
mod explicit_derivation;
mod explicit_puma560;
mod fuzz_replay;
mod hostile_numbers;
mod identification;
mod identification_batch;
mod identification_closed_loop;
mod identification_packages;
mod inverse_kinematics;
mod joints_pinocchio;
mod mesh;
mod mimic;
mod mjcf;
mod mjcf_import;
mod mobile;
mod multibody_batch;
mod multibody_builders;
mod multibody_closed_form;
mod multibody_derivatives;
mod multibody_derivatives_kinematics;
mod multibody_identities;
mod multibody_jacobians;
mod multibody_pinocchio;
mod multibody_puma560;
mod pinocchio;
mod pinocchio_packages;
mod reference;
mod sdf;
mod serialize;
mod shapes;
mod simulation;
mod spatial;
mod urdf_errors;
mod write;
