//! Fuzz target `sdf`: see `rigid::fuzzing::sdf`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rigid::fuzzing::sdf(data));
