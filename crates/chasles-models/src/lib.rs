//! # chasles-models — the real rigged characters, built in
//!
//! The five glTF 2.0 models that Kavan et al. 2006, §6 (skinning on real characters) is
//! reproduced on in the tests, the benchmarks and `chasles tour`: Khronos glTF samples,
//! byte for byte as published, compiled in with `include_bytes!` so that nothing outside
//! the repository is read. Each [`Model`] carries its licence and credit, which every
//! picture of it must show (see this crate's README).
//!
//! Load one with `chasles_skin::gltf_load::load_slice(model.bytes, model.file)`; a tool that
//! takes paths gets a file with [`Model::write_to`] or all of them with [`on_disk`] (tests of
//! the command line do). No path
//! is compiled in: the bytes are all there is, wherever the build was made or moved.

#![forbid(unsafe_code)]

use std::path::{Path, PathBuf};

/// One built-in model: its file name, what it is, its size and its licence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Model {
    /// The file name (`CesiumMan.glb`); also its name in [`on_disk`].
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

    /// Writes the model into `dir` under its file name and returns that path (for tools
    /// that take a path).
    pub fn write_to(&self, dir: &Path) -> std::io::Result<PathBuf> {
        let p = dir.join(self.file);
        std::fs::write(&p, self.bytes)?;
        Ok(p)
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

/// Every model as a file, in one folder of the system's temporary directory
/// (`chasles-models-VERSION`), for tools and tests that take paths: written on the first call
/// of a process where missing or different (each file whole, by a rename), then reused.
pub fn on_disk() -> std::io::Result<&'static Path> {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    if let Some(d) = DIR.get() {
        return Ok(d);
    }
    // One thread writes at a time: two threads of one process would share the temporary
    // file's name below (it has the process id), and the second rename would find it gone.
    static WRITING: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _one = WRITING.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(d) = DIR.get() {
        return Ok(d);
    }
    let dir = std::env::temp_dir().join(concat!("chasles-models-", env!("CARGO_PKG_VERSION")));
    std::fs::create_dir_all(&dir)?;
    for m in ALL {
        let p = dir.join(m.file);
        if std::fs::read(&p).ok().as_deref() != Some(m.bytes) {
            let tmp = dir.join(format!(".{}.{}", m.file, std::process::id()));
            std::fs::write(&tmp, m.bytes)?;
            std::fs::rename(&tmp, &p)?;
        }
    }
    Ok(DIR.get_or_init(|| dir))
}

/// The model with this file name (`"Fox.glb"`), if built in.
pub fn by_file(file: &str) -> Option<&'static Model> {
    ALL.iter().find(|m| m.file == file)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_bytes_are_the_files_of_gltf_and_write_back() {
        // At test time cargo names this crate's folder: the sources beside the bytes.
        let here = Path::new(&std::env::var_os("CARGO_MANIFEST_DIR").unwrap()).join("gltf");
        let out = std::env::temp_dir().join(format!("chasles-models-{}", std::process::id()));
        std::fs::create_dir_all(&out).unwrap();
        for m in ALL {
            let disk = std::fs::read(here.join(m.file)).unwrap();
            assert!(disk == m.bytes, "{}", m.file);
            let written = m.write_to(&out).unwrap();
            assert_eq!(written.file_name().unwrap(), m.file);
            assert!(std::fs::read(&written).unwrap() == m.bytes, "{}", m.file);
            let shared = on_disk().unwrap().join(m.file);
            assert!(std::fs::read(&shared).unwrap() == m.bytes, "{}", m.file);
        }
        std::fs::remove_dir_all(&out).unwrap();
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
