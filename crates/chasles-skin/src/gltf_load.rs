//! Loading rigs from glTF 2.0 (`.gltf` with embedded or external buffers, and `.glb`),
//! with the `gltf` crate for parsing.
//!
//! What is read: the first node that has both a mesh and a skin (all primitives of that
//! mesh, merged), its POSITION, NORMAL (computed when absent), indices, every
//! JOINTS_n/WEIGHTS_n set; the skin's joints and inverse bind matrices (identity when
//! absent, as the specification says); every node's rest transform and parent; and every
//! animation's translation, rotation and scale channels (morph-target weights are skipped).
//!
//! The document is checked first (`gltf_check`: every accessor inside its buffer view,
//! every view inside its buffer, the types the specification allows where they are read),
//! and every buffer is as long as it declares (`load_buffers`), so a truncated file is a
//! [`SkinError::Truncated`] naming the accessor, never a panic. Joint
//! indices and weights are checked per vertex ([`Influences::from_lists`]).

use crate::animation::{Animation, Channel, Interpolation, Path as ChannelPath};
use crate::error::{gltf_content, same_count, Result, SkinError};
use crate::rig::{compute_normals, Influences, Mesh, Node, Rig, Trs};
use base64::Engine;
use chasles::{Mat4, Quat, Vec3};
use gltf::mesh::Semantic;
use std::path::Path;

fn load_buffers(
    doc: &gltf::Document,
    blob: Option<Vec<u8>>,
    base: Option<&Path>,
    name: &str,
) -> Result<Vec<Vec<u8>>> {
    let mut blob = blob;
    doc.buffers()
        .map(|b| {
            let data = match b.source() {
                gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                    gltf_content(
                        name,
                        format!("buffer {}", b.index()),
                        "refers to a missing GLB binary chunk",
                    )
                })?,
                gltf::buffer::Source::Uri(uri) => {
                    if let Some(rest) = uri.strip_prefix("data:") {
                        let (_, payload) = rest.split_once(";base64,").ok_or_else(|| {
                            gltf_content(
                                name,
                                format!("buffer {}", b.index()),
                                "only base64 data URIs are supported",
                            )
                        })?;
                        base64::engine::general_purpose::STANDARD
                            .decode(payload)
                            .map_err(|e| {
                                gltf_content(
                                    name,
                                    format!("buffer {}", b.index()),
                                    format!("bad base64 data: {e}"),
                                )
                            })?
                    } else if let Some(base) = base {
                        // The declared length (glTF allows a longer file), read no further.
                        crate::bounded::read_prefix(
                            &base.join(uri),
                            b.length() as u64,
                            crate::bounded::MAX_MODEL_BYTES,
                        )
                        .map_err(|e| {
                            gltf_content(
                                name,
                                format!("buffer {}", b.index()),
                                format!("refers to {uri}, which cannot be read: {e}"),
                            )
                        })?
                    } else {
                        return Err(gltf_content(
                            name,
                            format!("buffer {}", b.index()),
                            format!("is in a separate file ({uri}), which bytes in memory cannot refer to"),
                        ));
                    }
                }
            };
            if data.len() < b.length() {
                return Err(gltf_content(
                    name,
                    format!("buffer {}", b.index()),
                    format!(
                        "is truncated: {} bytes, the file declares {}",
                        data.len(),
                        b.length()
                    ),
                ));
            }
            Ok(data)
        })
        .collect()
}

fn trs(node: &gltf::Node) -> Trs {
    let (t, r, s) = node.transform().decomposed();
    Trs {
        translation: Vec3::from_array(t),
        rotation: Quat::new(r[3], r[0], r[1], r[2])
            .normalize()
            .unwrap_or(Quat::identity()),
        scale: Vec3::from_array(s),
    }
}

/// Loads a rig from a `.gltf` or `.glb` file; external buffers are read next to it.
pub fn load(path: &Path) -> Result<Rig> {
    let name = path.display().to_string();
    let bytes = crate::bounded::read_file(path, crate::bounded::MAX_MODEL_BYTES)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let mut rig = parse(&bytes, Some(base), &name)?;
    rig.name = file_name(path);
    Ok(rig)
}

/// The file name of `path`, for a rig's name (titles show no folders).
pub(crate) fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |f| f.to_string_lossy().into_owned(),
    )
}

/// Loads a rig from the bytes of a `.glb`, or of a `.gltf` whose buffers are embedded
/// (base64 data URIs); `name` names it in errors. A buffer in a separate file is an
/// error here, since there is no folder to read it from: use [`load`] for those.
pub fn load_slice(bytes: &[u8], name: &str) -> Result<Rig> {
    parse(bytes, None, name)
}

fn parse(bytes: &[u8], base: Option<&Path>, name: &str) -> Result<Rig> {
    // Our checks first: the crate's own validation indexes arrays it has not checked
    // (an attribute's accessor, say) and can panic, and its GLB reader subtracts the
    // 12-byte header from the declared length unchecked.
    crate::gltf_check::check_glb_header(bytes, name)?;
    let g = gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| SkinError::Gltf {
        path: name.to_string(),
        reason: e.to_string(),
    })?;
    crate::gltf_check::check(g.document.as_json(), name)?;
    crate::gltf_check::crate_validation(g.document.as_json(), name)?;
    let buffers = load_buffers(&g.document, g.blob.clone(), base, name)?;
    from_document(&g.document, &buffers, name)
}

fn from_document(doc: &gltf::Document, buffers: &[Vec<u8>], name: &str) -> Result<Rig> {
    let get = |b: gltf::Buffer| Some(&buffers[b.index()][..]);
    let skinned = doc
        .nodes()
        .find(|n| n.mesh().is_some() && n.skin().is_some())
        .ok_or_else(|| {
            gltf_content(
                name,
                "nodes",
                "no node has both a mesh and a skin: nothing to skin",
            )
        })?;
    let (mesh, skin) = (
        skinned.mesh().unwrap_or_else(|| unreachable!()),
        skinned.skin().unwrap_or_else(|| unreachable!()),
    );
    let joint_nodes: Vec<usize> = skin.joints().map(|j| j.index()).collect();
    let nj = joint_nodes.len();
    let mut positions = Vec::new();
    let mut normals: Vec<Vec3<f32>> = Vec::new();
    let mut have_normals = true;
    let mut triangles = Vec::new();
    let mut lists: Vec<Vec<(usize, f32)>> = Vec::new();
    for prim in mesh.primitives() {
        if prim.mode() != gltf::mesh::Mode::Triangles {
            return Err(gltf_content(
                name,
                format!("mesh primitive {}", prim.index()),
                "is not made of triangles",
            ));
        }
        let base = positions.len() as u32;
        let item = || format!("primitive {}", prim.index());
        prim.get(&Semantic::Positions)
            .ok_or_else(|| gltf_content(name, item(), "has no POSITION"))?;
        let reader = prim.reader(get);
        let p: Vec<Vec3<f32>> = reader
            .read_positions()
            .ok_or_else(|| gltf_content(name, item(), "POSITION unreadable"))?
            .map(Vec3::from_array)
            .collect();
        let count = p.len();
        match reader.read_normals() {
            Some(n) => normals.extend(n.map(Vec3::from_array)),
            None => have_normals = false,
        }
        let idx: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..count as u32).collect(),
        };
        if !idx.len().is_multiple_of(3) {
            return Err(gltf_content(
                name,
                item(),
                format!("{} indices is not a whole number of triangles", idx.len()),
            ));
        }
        if let Some(bad) = idx.iter().find(|i| **i as usize >= count) {
            return Err(gltf_content(
                name,
                item(),
                format!("index {bad} out of range ({count} vertices)"),
            ));
        }
        triangles.extend(
            idx.chunks(3)
                .map(|c| [c[0] + base, c[1] + base, c[2] + base]),
        );
        let mut per_vertex: Vec<Vec<(usize, f32)>> = vec![Vec::new(); count];
        let mut set = 0;
        while let (Some(j), Some(w)) = (reader.read_joints(set), reader.read_weights(set)) {
            let j: Vec<[u16; 4]> = j.into_u16().collect();
            let w: Vec<[f32; 4]> = w.into_f32().collect();
            if j.len() != count || w.len() != count {
                return Err(gltf_content(
                    name,
                    item(),
                    format!(
                        "JOINTS_{set}/WEIGHTS_{set} have {}/{} entries for {count} vertices",
                        j.len(),
                        w.len()
                    ),
                ));
            }
            for (v, (jv, wv)) in j.iter().zip(&w).enumerate() {
                for k in 0..4 {
                    per_vertex[v].push((usize::from(jv[k]), wv[k]));
                }
            }
            set += 1;
        }
        if set == 0 {
            return Err(gltf_content(
                name,
                item(),
                "has no JOINTS_0/WEIGHTS_0: it is not skinned",
            ));
        }
        lists.extend(per_vertex);
        positions.extend(p);
    }
    // Weight errors keep their type (BadWeights, JointOutOfRange: they name the vertex).
    let influences = Influences::from_lists(&lists, nj)?;
    if !have_normals || normals.len() != positions.len() {
        normals = compute_normals(&positions, &triangles);
    }
    let inverse_bind = match skin.inverse_bind_matrices() {
        Some(_) => {
            let m: Vec<Mat4<f32>> = skin
                .reader(get)
                .read_inverse_bind_matrices()
                .ok_or_else(|| gltf_content(name, "skin", "inverse bind matrices unreadable"))?
                // glTF matrices are column-major: cols[c][r].
                .map(|cols| Mat4::from_rows(cols).transpose())
                .collect();
            same_count(name, "inverse bind matrices", nj, m.len())?;
            m
        }
        None => vec![Mat4::identity(); nj],
    };
    let mut nodes: Vec<Node> = doc
        .nodes()
        .map(|n| Node {
            name: n.name().unwrap_or("").to_string(),
            parent: None,
            rest: trs(&n),
        })
        .collect();
    for n in doc.nodes() {
        for c in n.children() {
            nodes[c.index()].parent = Some(n.index());
        }
    }
    let mut animations = Vec::new();
    for a in doc.animations() {
        let mut channels = Vec::new();
        for c in a.channels() {
            use gltf::animation::util::ReadOutputs;
            let s = c.sampler();
            let r = c.reader(get);
            let times: Vec<f32> = r
                .read_inputs()
                .ok_or_else(|| {
                    gltf_content(name, format!("animation {}", a.index()), "input unreadable")
                })?
                .collect();
            let (path, values): (ChannelPath, Vec<[f32; 4]>) = match r.read_outputs() {
                Some(ReadOutputs::Translations(t)) => (
                    ChannelPath::Translation,
                    t.map(|v| [v[0], v[1], v[2], 0.0]).collect(),
                ),
                Some(ReadOutputs::Scales(t)) => (
                    ChannelPath::Scale,
                    t.map(|v| [v[0], v[1], v[2], 0.0]).collect(),
                ),
                Some(ReadOutputs::Rotations(q)) => (
                    ChannelPath::Rotation,
                    q.into_f32().map(|v| [v[3], v[0], v[1], v[2]]).collect(),
                ),
                _ => continue, // morph target weights
            };
            // A rotation key of zero length (or not finite) is no rotation: an error naming
            // it, not the identity it would silently become.
            // (CUBICSPLINE stores in-tangent, value, out-tangent per key: only the values.)
            if path == ChannelPath::Rotation {
                let cubic = s.interpolation() == gltf::animation::Interpolation::CubicSpline;
                let is_value = |i: usize| !cubic || i % 3 == 1;
                if let Some(k) = values.iter().enumerate().position(|(i, v)| {
                    let n2: f32 = v.iter().map(|x| x * x).sum();
                    is_value(i) && !n2.is_normal()
                }) {
                    return Err(gltf_content(
                        name,
                        format!("animation {}, channel {}", a.index(), c.index()),
                        format!(
                            "rotation key {} is {:?}, which is not a rotation (zero or not finite)",
                            if cubic { k / 3 } else { k },
                            values[k]
                        ),
                    ));
                }
            }
            let interpolation = match s.interpolation() {
                gltf::animation::Interpolation::Linear => Interpolation::Linear,
                gltf::animation::Interpolation::Step => Interpolation::Step,
                gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
            };
            let ch = Channel {
                node: c.target().node().index(),
                path,
                interpolation,
                times,
                values,
            };
            channels.push(ch);
        }
        animations.push(Animation {
            name: a.name().unwrap_or("").to_string(),
            channels,
        });
    }
    Rig::new(
        name.to_string(),
        Mesh {
            positions,
            normals,
            triangles,
        },
        nodes,
        joint_nodes,
        inverse_bind,
        influences,
        animations,
    )
}
