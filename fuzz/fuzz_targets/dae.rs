//! Fuzz target `dae`: see `rigid::fuzzing::dae`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rigid::fuzzing::dae(data));
