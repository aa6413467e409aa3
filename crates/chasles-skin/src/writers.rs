//! Writing deformed meshes: Wavefront OBJ, ASCII PLY and binary glTF (`.glb`), with normals. These build the file
//! text; writing it whole or not at all is the caller's job (the CLI writes through a
//! temporary file and a rename).

use crate::rig::Mesh;
use crate::skinning::Skinned;
use std::fmt::Write;

/// OBJ text: `v`, `vn`, and `f a//a b//b c//c` (1-based).
pub fn obj(mesh: &Mesh, s: &Skinned, comment: &str) -> String {
    let mut out = String::with_capacity(s.positions.len() * 64);
    for line in comment.lines() {
        let _ = writeln!(out, "# {line}");
    }
    for p in &s.positions {
        let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
    }
    for n in &s.normals {
        let _ = writeln!(out, "vn {} {} {}", n.x, n.y, n.z);
    }
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| i + 1);
        let _ = writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}");
    }
    out
}

/// ASCII PLY text with positions, normals and triangles.
pub fn ply(mesh: &Mesh, s: &Skinned, comment: &str) -> String {
    let mut out = String::with_capacity(s.positions.len() * 64);
    out.push_str("ply\nformat ascii 1.0\n");
    for line in comment.lines() {
        let _ = writeln!(out, "comment {line}");
    }
    let _ = writeln!(out, "element vertex {}", s.positions.len());
    out.push_str("property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n");
    let _ = writeln!(out, "element face {}", mesh.triangles.len());
    out.push_str("property list uchar int vertex_indices\nend_header\n");
    for (p, n) in s.positions.iter().zip(&s.normals) {
        let _ = writeln!(out, "{} {} {} {} {} {}", p.x, p.y, p.z, n.x, n.y, n.z);
    }
    for t in &mesh.triangles {
        let _ = writeln!(out, "3 {} {} {}", t[0], t[1], t[2]);
    }
    out
}

/// A binary glTF 2.0 (`.glb`) of the deformed mesh: one node, one mesh, POSITION (with
/// the min/max the specification requires), NORMAL and u32 indices in one buffer.
pub fn glb(mesh: &Mesh, s: &Skinned, comment: &str) -> Vec<u8> {
    let n = s.positions.len();
    let mut bin: Vec<u8> = Vec::with_capacity(n * 24 + mesh.triangles.len() * 12);
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &s.positions {
        for (k, v) in p.to_array().iter().enumerate() {
            lo[k] = lo[k].min(*v);
            hi[k] = hi[k].max(*v);
            bin.extend_from_slice(&v.to_le_bytes());
        }
    }
    if n == 0 {
        (lo, hi) = ([0.0; 3], [0.0; 3]);
    }
    for v in s.normals.iter().flat_map(|p| p.to_array()) {
        bin.extend_from_slice(&v.to_le_bytes());
    }
    for i in mesh.triangles.iter().flatten() {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let (pos_len, idx_len) = (n * 12, mesh.triangles.len() * 12);
    let json = serde_json::json!({
        "asset": {"version": "2.0", "generator": "chasles", "extras": {"comment": comment}},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": pos_len, "target": 34962},
            {"buffer": 0, "byteOffset": pos_len, "byteLength": pos_len, "target": 34962},
            {"buffer": 0, "byteOffset": 2 * pos_len, "byteLength": idx_len, "target": 34963}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": mesh.triangles.len() * 3, "type": "SCALAR"}
        ]
    });
    let mut j = json.to_string().into_bytes();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}
