//! Every input the fuzzers (`fuzz/`, `scripts/fuzz.sh`) crashed the loader with, kept in
//! `tests/fuzz-cases/`: each now loads or fails with a typed error — no panic. The files are
//! named by what broke (`glb-header-length-2.glb`: a GLB header declaring 2 bytes).

use chasles_skin::gltf_load::load_slice;

#[test]
fn every_kept_fuzz_case_is_a_typed_error() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-cases");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let e = load_slice(&bytes, &name).expect_err(&name);
        assert!(e.to_string().contains(&name), "{name}: {e}");
        n += 1;
    }
    assert!(n >= 1);
}
