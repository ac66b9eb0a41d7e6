//! Fuzz target `mjcf`: see `rigid::fuzzing::mjcf`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rigid::fuzzing::mjcf(data));
