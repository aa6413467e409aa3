//! The viewer's shaders, made once from WGSL: `chasles_skin`'s shared skinning functions
//! ([`chasles_skin::shader::SKINNING_WGSL`], the very code of the GPU compute shaders)
//! followed by `view.wgsl`'s entry points (a vertex shader for LBS, one for DQS, and the
//! surface's fragment shader), parsed and validated by naga and written as GLSL ES 3.00
//! for WebGL2 (`Version::Embedded { version: 300, is_webgl: true }`). No GLSL is written by
//! hand: the page compiles what this module returns.

use crate::ViewError;
use naga::back::glsl;
use naga::valid::{Capabilities, ValidationFlags, Validator};
use serde::Serialize;

/// The viewer's own WGSL: bindings, the vertex entry points `lbs` and `dqs`, the fragment
/// entry point `surface`.
pub const VIEW_WGSL: &str = include_str!("view.wgsl");

/// The whole WGSL module the GLSL is made from.
pub fn wgsl() -> String {
    format!("{}\n{}", chasles_skin::shader::SKINNING_WGSL, VIEW_WGSL)
}

/// The GLSL ES 3.00 programs and the names the page binds them by.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Glsl {
    /// The vertex shader skinning by LBS.
    pub lbs: String,
    /// The vertex shader skinning by DQS.
    pub dqs: String,
    /// The fragment shader.
    pub surface: String,
    /// The sampler uniform of the joint palette in the vertex shaders.
    pub palette: String,
    /// The uniform blocks of the `View` uniform (one per stage that reads it).
    pub blocks: Vec<String>,
    /// The vertex shaders' output holding the skinned position (captured by transform
    /// feedback for the page's read-back).
    pub skinned: String,
    /// The vertex shaders' output holding the blended 3×3's determinant.
    pub det: String,
}

/// Translates the viewer's WGSL into GLSL ES 3.00: an error names the stage and what naga
/// refused (a bug of ours, never of the input).
pub fn glsl() -> Result<Glsl, ViewError> {
    let source = wgsl();
    let module = naga::front::wgsl::parse_str(&source)
        .map_err(|e| ViewError::Shader(e.emit_to_string(&source)))?;
    let info = Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(&module)
        .map_err(|e| ViewError::Shader(e.emit_to_string(&source)))?;
    let options = glsl::Options {
        version: glsl::Version::Embedded {
            version: 300,
            is_webgl: true,
        },
        writer_flags: glsl::WriterFlags::empty(),
        ..Default::default()
    };
    let write = |stage: naga::ShaderStage, entry: &str| {
        let mut out = String::new();
        let pipeline = glsl::PipelineOptions {
            shader_stage: stage,
            entry_point: entry.into(),
            multiview: None,
        };
        let reflection = glsl::Writer::new(
            &mut out,
            &module,
            &info,
            &options,
            &pipeline,
            naga::proc::BoundsCheckPolicies::default(),
        )
        .and_then(|mut w| w.write())
        .map_err(|e| ViewError::Shader(format!("{entry}: {e}")))?;
        Ok::<_, ViewError>((out, reflection))
    };
    let (lbs, vs) = write(naga::ShaderStage::Vertex, "lbs")?;
    let (dqs, _) = write(naga::ShaderStage::Vertex, "dqs")?;
    let (surface, fs) = write(naga::ShaderStage::Fragment, "surface")?;
    let palette = vs
        .texture_mapping
        .keys()
        .next()
        .cloned()
        .ok_or_else(|| ViewError::Shader("no palette sampler in the vertex shader".into()))?;
    let mut blocks: Vec<String> = vs
        .uniforms
        .values()
        .chain(fs.uniforms.values())
        .cloned()
        .collect();
    blocks.sort();
    blocks.dedup();
    // naga names a vertex shader's outputs by location (`Shaded` in view.wgsl: 2 is the
    // skinned position, 3 the determinant); the name is checked in both programs.
    let output = |location: u32| {
        let name = format!("_vs2fs_location{location}");
        let declared = format!(" {name};");
        if lbs.contains(&declared) && dqs.contains(&declared) {
            Ok(name)
        } else {
            Err(ViewError::Shader(format!(
                "no vertex output {name} in the GLSL naga wrote"
            )))
        }
    };
    Ok(Glsl {
        skinned: output(2)?,
        det: output(3)?,
        lbs,
        dqs,
        surface,
        palette,
        blocks,
    })
}
