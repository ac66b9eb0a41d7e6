//! The integration tests of the `rigid` command-line tool, one test binary (each file a
//! module). They run the binary (`CARGO_BIN_EXE_rigid`); their data is beside this folder:
//! `fixtures/` (small input files) and `corpus/` (the malformed-input corpus and its generator);
//! the robot files and Pinocchio fixtures are the `rigid` crate's (`crates/rigid/tests/`).
//!
//! `cargo test` needs nothing but Rust. The checks that need Python or a browser at test time are
//! live checks, run when `RIGID_CROSSCHECK=1` (`common::live`; `scripts/test.sh` sets it).

mod common;

mod bench_cli;
mod convert_cli;
mod corpus;
mod doctor_cli;
mod eval;
mod eval_constraints;
mod eval_mimic;
mod eval_mujoco;
mod eval_parallel;
mod eval_pinocchio;
mod explicit_cli;
mod identify_cli;
mod ik_cli;
mod mass_cli;
mod mobile_cli;
mod replay_browser;
mod simulate;
mod simulate_ground;
mod step_cli;
