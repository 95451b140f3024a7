#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| meshvol_fuzz::check("m.gltf", data));
