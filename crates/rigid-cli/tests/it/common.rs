//! Shared by the command-line tests: the switch of the live cross-checks and the `rigid`
//! crate's checked-in fixtures.

use std::path::PathBuf;

/// `true` when `RIGID_CROSSCHECK=1` turns on the live checks (Python and its packages, a
/// browser); unset (or `0`) they do not, and the tests use the checked-in fixtures. Says so on
/// stderr for `what` when they are off.
///
/// # Panics
/// On any other value, so that a typo does not turn the checks off quietly.
pub fn live(what: &str) -> bool {
    let on = match std::env::var("RIGID_CROSSCHECK").as_deref() {
        Err(_) | Ok("" | "0") => false,
        Ok("1") => true,
        Ok(other) => panic!("RIGID_CROSSCHECK={other}: set it to 1 to turn the live checks on"),
    };
    if !on {
        eprintln!("{what}: not run (RIGID_CROSSCHECK=1 turns the live checks on)");
    }
    on
}

/// The interpreter of the live checks: `RIGID_PYTHON`, or `python3`.
pub fn python() -> String {
    std::env::var("RIGID_PYTHON").unwrap_or_else(|_| "python3".into())
}

/// `crates/rigid/tests/REL`: the `rigid` crate's reference scripts and fixtures.
pub fn rigid_tests(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../rigid/tests")
        .join(rel)
}

/// The checked-in copy of example-robot-data's `robots/` folder (the files the tests load,
/// `crates/rigid/tests/fixtures/robots/`).
pub fn example_robot_data() -> PathBuf {
    rigid_tests("fixtures/robots/example-robot-data/robots")
}
