//! Writing a rig with animation clips as binary glTF 2.0 (`.glb`): what `chasles clip
//! blend` and `chasles clip compress` write, so that a made clip is loaded back like any
//! other (`chasles skin --anim NAME`, `chasles view --clip NAME`, any glTF viewer).
//!
//! What is written, from the [`Rig`] (so a JSON rig can be written too): every node with
//! its name, rest translation, rotation and scale, and children; one more node at the end
//! holding the mesh and the skin (glTF ignores the transform of a skinned mesh's node, and
//! [`crate::gltf_load`] reads only the skin's joints); the mesh as one triangle primitive
//! (POSITION with its min/max, NORMAL, u32 indices, the influences as `JOINTS_n`/`WEIGHTS_n`
//! sets of four, u16 and f32, zero-padded); the skin's joints and inverse bind matrices; and
//! the given clips, each channel with its own input accessor (with the min/max the
//! specification asks of animation inputs) and its interpolation as stored (LINEAR, STEP
//! or CUBICSPLINE with in-tangent, value, out-tangent per key). Quaternions go out as glTF
//! stores them, `[x, y, z, w]`. Materials, textures and morph targets of the file a rig
//! came from are not carried: the rig model does not hold them.
//!
//! Why by hand (serde_json plus a byte buffer, as [`crate::writers::glb`] does) rather than
//! `gltf-json`'s typed document: the document is a dozen small objects, every field written
//! is one the loader checks on the way back (`gltf_check` and the `gltf` crate's
//! validation), and the tests load every written file back; `gltf-json`'s structures would
//! need every optional field and `Checked` wrapper spelled out for the same bytes.

use crate::animation::{Animation, Interpolation, Path};
use crate::error::{Result, SkinError};
use crate::rig::Rig;
use serde_json::{json, Value};

/// The byte buffer and the JSON arrays of buffer views and accessors being built.
#[derive(Default)]
struct Builder {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Builder {
    /// Appends `bytes` as a new buffer view (4-byte aligned) and returns its index.
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut v = json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    /// An accessor of f32 elements of `width` numbers (`kind`: SCALAR, VEC3, VEC4, MAT4),
    /// with min/max when `bounds`.
    fn floats(&mut self, data: &[f32], width: usize, kind: &str, bounds: bool) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
        let target = matches!(kind, "VEC3").then_some(34962);
        let view = self.view(&bytes, target);
        let count = data.len() / width;
        let mut a =
            json!({"bufferView": view, "componentType": 5126, "count": count, "type": kind});
        if bounds {
            let (mut lo, mut hi) = (vec![f32::INFINITY; width], vec![f32::NEG_INFINITY; width]);
            for e in data.chunks(width) {
                for (k, v) in e.iter().enumerate() {
                    lo[k] = lo[k].min(*v);
                    hi[k] = hi[k].max(*v);
                }
            }
            a["min"] = json!(lo);
            a["max"] = json!(hi);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// An accessor of integers: u16 (`5123`) or u32 (`5125`) components.
    fn ints(&mut self, data: &[u32], width: usize, kind: &str, u16s: bool) -> usize {
        let bytes: Vec<u8> = if u16s {
            data.iter()
                .flat_map(|v| (*v as u16).to_le_bytes())
                .collect()
        } else {
            data.iter().flat_map(|v| v.to_le_bytes()).collect()
        };
        let target = if kind == "SCALAR" { 34963 } else { 34962 };
        let view = self.view(&bytes, Some(target));
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": if u16s { 5123 } else { 5125 },
            "count": data.len() / width,
            "type": kind
        }));
        self.accessors.len() - 1
    }
}

/// The `.glb` bytes of `rig` with `clips` as its animations (the rig's own clips are not
/// written unless they are among `clips`); `comment` goes into `asset.extras`. Errors: a
/// rig or clip that does not validate (a clip's channel naming a node the rig lacks, say),
/// or one too big for a GLB (4 GiB).
pub fn rig_glb(rig: &Rig, clips: &[Animation], comment: &str) -> Result<Vec<u8>> {
    let mut check = rig.clone();
    check.animations = clips.to_vec();
    check.validate()?;
    let mut b = Builder::default();
    let mesh = &rig.mesh;
    let positions: Vec<f32> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let normals: Vec<f32> = mesh.normals.iter().flat_map(|p| p.to_array()).collect();
    let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let mut attributes = serde_json::Map::new();
    attributes.insert(
        "POSITION".into(),
        json!(b.floats(&positions, 3, "VEC3", true)),
    );
    attributes.insert("NORMAL".into(), json!(b.floats(&normals, 3, "VEC3", false)));
    let sets = rig.influences.max_per_vertex().div_ceil(4).max(1);
    let n = mesh.positions.len();
    for set in 0..sets {
        let mut joints = vec![0u32; n * 4];
        let mut weights = vec![0f32; n * 4];
        for v in 0..n {
            for (k, (j, w)) in rig.influences.of(v).skip(4 * set).take(4).enumerate() {
                joints[4 * v + k] = j as u32;
                weights[4 * v + k] = w;
            }
        }
        attributes.insert(
            format!("JOINTS_{set}"),
            json!(b.ints(&joints, 4, "VEC4", true)),
        );
        attributes.insert(
            format!("WEIGHTS_{set}"),
            json!(b.floats(&weights, 4, "VEC4", false)),
        );
    }
    let idx = b.ints(&indices, 1, "SCALAR", false);
    // glTF matrices are column-major.
    let ibm: Vec<f32> = rig
        .inverse_bind
        .iter()
        .flat_map(|m| {
            let t = m.transpose();
            t.m.into_iter().flatten()
        })
        .collect();
    let ibm = b.floats(&ibm, 16, "MAT4", false);
    let mesh_node = rig.nodes.len();
    let mut nodes: Vec<Value> = rig
        .nodes
        .iter()
        .map(|node| {
            let r = node.rest.rotation.to_array();
            json!({
                "name": node.name,
                "translation": node.rest.translation.to_array(),
                "rotation": [r[1], r[2], r[3], r[0]],
                "scale": node.rest.scale.to_array(),
            })
        })
        .collect();
    for (i, node) in rig.nodes.iter().enumerate() {
        if let Some(p) = node.parent {
            let children = nodes[p]
                .as_object_mut()
                .map(|o| o.entry("children").or_insert_with(|| json!([])));
            if let Some(Value::Array(c)) = children {
                c.push(json!(i));
            }
        }
    }
    nodes.push(json!({"name": "skinned mesh", "mesh": 0, "skin": 0}));
    let mut roots: Vec<usize> = (0..rig.nodes.len())
        .filter(|i| rig.nodes[*i].parent.is_none())
        .collect();
    roots.push(mesh_node);
    let animations: Vec<Value> = clips
        .iter()
        .map(|clip| {
            let mut samplers = Vec::new();
            let mut channels = Vec::new();
            for (c, ch) in clip.channels.iter().enumerate() {
                let input = b.floats(&ch.times, 1, "SCALAR", true);
                let (width, kind) = match ch.path {
                    Path::Rotation => (4, "VEC4"),
                    _ => (3, "VEC3"),
                };
                let out: Vec<f32> = ch
                    .values
                    .iter()
                    .flat_map(|v| match ch.path {
                        Path::Rotation => vec![v[1], v[2], v[3], v[0]],
                        _ => v[..3].to_vec(),
                    })
                    .collect();
                let output = b.floats(&out, width, kind, false);
                let interpolation = match ch.interpolation {
                    Interpolation::Linear => "LINEAR",
                    Interpolation::Step => "STEP",
                    Interpolation::CubicSpline => "CUBICSPLINE",
                };
                samplers.push(
                    json!({"input": input, "output": output, "interpolation": interpolation}),
                );
                let path = match ch.path {
                    Path::Translation => "translation",
                    Path::Rotation => "rotation",
                    Path::Scale => "scale",
                };
                channels.push(json!({"sampler": c, "target": {"node": ch.node, "path": path}}));
            }
            json!({"name": clip.name, "samplers": samplers, "channels": channels})
        })
        .collect();
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": "chasles", "extras": {"comment": comment}},
        "scene": 0,
        "scenes": [{"nodes": roots}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": attributes, "indices": idx}]}],
        "skins": [{"joints": rig.joints, "inverseBindMatrices": ibm}],
    });
    if !animations.is_empty() {
        doc["animations"] = json!(animations);
    }
    while !b.bin.len().is_multiple_of(4) {
        b.bin.push(0);
    }
    doc["buffers"] = json!([{"byteLength": b.bin.len()}]);
    doc["bufferViews"] = json!(b.views);
    doc["accessors"] = json!(b.accessors);
    let mut j = doc.to_string().into_bytes();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let total = 12 + 8 + j.len() + 8 + b.bin.len();
    let total32 = u32::try_from(total).map_err(|_| SkinError::TooLarge {
        path: format!("{} as .glb", rig.name),
        size: total as u64,
        limit: u64::from(u32::MAX),
    })?;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total32.to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b.bin);
    Ok(out)
}
