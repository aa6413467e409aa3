//! Writing deformed meshes: Wavefront OBJ and ASCII PLY, with normals. These build the file
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
