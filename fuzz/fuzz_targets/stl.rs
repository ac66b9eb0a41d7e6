//! Fuzz target `stl`: see `rigid::fuzzing::stl`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rigid::fuzzing::stl(data));
