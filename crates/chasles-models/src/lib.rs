//! # chasles-models — the real rigged characters, built in
//!
//! The five glTF 2.0 models that Kavan et al. 2006, §6 (skinning on real characters) is
//! reproduced on in the tests, the benchmarks and `chasles tour`: Khronos glTF samples,
//! byte for byte as published, compiled in with `include_bytes!` so that nothing outside
//! the repository is read. Each [`Model`] carries its licence and credit, which every
//! picture of it must show (see this crate's README).
//!
//! Load one with `chasles_skin::gltf_load::load_slice(model.bytes, model.file)`; the files
//! also lie on disk under [`dir`] for tests of the command line, which takes paths.

#![forbid(unsafe_code)]

use std::path::{Path, PathBuf};

/// One built-in model: its file name, what it is, its size and its licence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Model {
    /// The file name (`CesiumMan.glb`); also its name in [`dir`].
    pub file: &'static str,
    /// What the model is, in a few words.
    pub what: &'static str,
    /// Vertices of the skinned mesh (all primitives merged).
    pub vertices: usize,
    /// Joints of its skin.
    pub joints: usize,
    /// Animation clips.
    pub clips: usize,
    /// Licence and attribution, to be shown with every picture of it.
    pub credit: &'static str,
    /// The file's bytes (`.glb`, or `.gltf` with its buffers embedded).
    pub bytes: &'static [u8],
}

impl Model {
    /// The file name without its extension (`CesiumMan`).
    pub fn stem(&self) -> &'static str {
        self.file.rsplit_once('.').map_or(self.file, |(s, _)| s)
    }

    /// The file on disk in this crate's `gltf/` folder (for tools that take a path).
    pub fn path(&self) -> PathBuf {
        dir().join(self.file)
    }
}

/// CesiumMan: a walking man, up to 4 influences per vertex.
pub const CESIUM_MAN: Model = Model {
    file: "CesiumMan.glb",
    what: "Khronos glTF sample: walking man, up to 4 influences",
    vertices: 3273,
    joints: 19,
    clips: 1,
    credit: "CesiumMan, CC-BY 4.0 with trademark limitations, © 2017 Cesium (Khronos glTF-Sample-Models)",
    bytes: include_bytes!("../gltf/CesiumMan.glb"),
};

/// RiggedFigure: a simple figure.
pub const RIGGED_FIGURE: Model = Model {
    file: "RiggedFigure.glb",
    what: "Khronos glTF sample: simple figure",
    vertices: 370,
    joints: 19,
    clips: 1,
    credit: "RiggedFigure, CC-BY 4.0 (Khronos glTF-Sample-Models)",
    bytes: include_bytes!("../gltf/RiggedFigure.glb"),
};

/// RiggedSimple: a two-bone cylinder (the older 160-vertex export).
pub const RIGGED_SIMPLE: Model = Model {
    file: "RiggedSimple.glb",
    what: "Khronos glTF sample: two-bone cylinder (older 160-vertex export)",
    vertices: 160,
    joints: 2,
    clips: 1,
    credit: "RiggedSimple, CC-BY 4.0 (Khronos glTF-Sample-Models)",
    bytes: include_bytes!("../gltf/RiggedSimple.glb"),
};

/// Fox: a fox with Survey, Walk and Run clips.
pub const FOX: Model = Model {
    file: "Fox.glb",
    what: "Khronos glTF sample: fox with Survey, Walk, Run clips",
    vertices: 1728,
    joints: 24,
    clips: 3,
    credit: "Fox: mesh CC0 1.0 (PixelMannen), rigging and animation CC-BY 4.0 (@tomkranis)",
    bytes: include_bytes!("../gltf/Fox.glb"),
};

/// SimpleSkin: the glTF tutorial's 10-vertex skin, buffers embedded as base64.
pub const SIMPLE_SKIN: Model = Model {
    file: "SimpleSkin.gltf",
    what: "Khronos glTF tutorial SimpleSkin, embedded buffers",
    vertices: 10,
    joints: 2,
    clips: 1,
    credit: "SimpleSkin, CC0 1.0 (Khronos glTF tutorial)",
    bytes: include_bytes!("../gltf/SimpleSkin.gltf"),
};

/// Every built-in model, in the README's order.
pub const ALL: [Model; 5] = [CESIUM_MAN, RIGGED_FIGURE, RIGGED_SIMPLE, FOX, SIMPLE_SKIN];

/// The model with this file name (`"Fox.glb"`), if built in.
pub fn by_file(file: &str) -> Option<&'static Model> {
    ALL.iter().find(|m| m.file == file)
}

/// The folder the model files lie in, inside this crate (`crates/chasles-models/gltf`).
pub fn dir() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/gltf"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_bytes_are_the_files_on_disk() {
        for m in ALL {
            let disk = std::fs::read(m.path()).unwrap();
            assert_eq!(disk.len(), m.bytes.len(), "{}", m.file);
            assert!(disk == m.bytes, "{}", m.file);
        }
    }

    #[test]
    fn each_model_is_glb_or_embedded_gltf() {
        for m in ALL {
            if m.file.ends_with(".glb") {
                assert_eq!(&m.bytes[..4], b"glTF", "{}", m.file);
                let len = u32::from_le_bytes(m.bytes[8..12].try_into().unwrap()) as usize;
                assert_eq!(len, m.bytes.len(), "{}: GLB header length", m.file);
            } else {
                let text = std::str::from_utf8(m.bytes).unwrap();
                assert!(text.contains("\"asset\""), "{}", m.file);
                assert!(
                    text.contains("data:application/octet-stream;base64,")
                        || text.contains("data:application/gltf-buffer;base64,"),
                    "{}: buffers embedded",
                    m.file
                );
            }
        }
        assert_eq!(by_file("Fox.glb").map(|m| m.stem()), Some("Fox"));
        assert!(by_file("nope.glb").is_none());
    }
}
