#![no_main]
//! The 3MF model XML, wrapped in a valid package (a fuzzer seldom gets a zip right).
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| meshvol_fuzz::check("m.3mf", &meshvol_fuzz::three_mf(data)));
