//! Raw bytes as a glTF or GLB file (seeded with the five built-in models): the loader must
//! return a rig or a typed error, never panic, hang or exhaust memory.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = chasles_skin::gltf_load::load_slice(data, "fuzz.glb");
});
