//! The integration tests of the `rigid` command-line tool, one test binary (each file a
//! module). They run the binary (`CARGO_BIN_EXE_rigid`); their data is beside this folder:
//! `fixtures/` (small input files) and `corpus/` (the malformed-input corpus and its generator).

mod common;

mod bench_cli;
mod corpus;
mod doctor_cli;
mod eval;
mod eval_parallel;
mod eval_pinocchio;
mod explicit_cli;
mod identify_cli;
mod mass_cli;
mod replay_browser;
mod simulate;
