//! Fuzz target `obj`: see `rigid::fuzzing::obj`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rigid::fuzzing::obj(data));
