//! Fuzz target `cases`: see `rigid::fuzzing::cases`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rigid::fuzzing::cases(data));
