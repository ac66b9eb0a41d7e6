//! Fuzz target `urdf`: see `rigid::fuzzing::urdf`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rigid::fuzzing::urdf(data));
