//! Text as a JSON rig, and as a pose for the built-in SimpleSkin rig: a rig or a typed
//! error, never a panic; a rig that loads is skinned by every method without panicking.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

fn simple_skin() -> &'static chasles_skin::Rig {
    static RIG: OnceLock<chasles_skin::Rig> = OnceLock::new();
    RIG.get_or_init(|| {
        let m = chasles_models::SIMPLE_SKIN;
        chasles_skin::gltf_load::load_slice(m.bytes, m.file).expect("the built-in model loads")
    })
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(rig) = chasles_skin::json_rig::parse_rig(text, "fuzz.json") {
        if rig.mesh.positions.len() <= 10_000 {
            let pose = chasles_skin::Pose::rest(&rig);
            for m in chasles_skin::Method::ALL {
                let _ = chasles_skin::skin(&rig, &pose, m);
            }
        }
    }
    let rig = simple_skin();
    if let Ok(pose) = chasles_skin::json_rig::parse_pose(text, rig, "fuzz-pose.json") {
        for m in chasles_skin::Method::ALL {
            let _ = chasles_skin::skin(rig, &pose, m);
        }
    }
});
