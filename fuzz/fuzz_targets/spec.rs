//! Fuzz target `spec`: see `rigid::fuzzing::spec`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rigid::fuzzing::spec(data));
