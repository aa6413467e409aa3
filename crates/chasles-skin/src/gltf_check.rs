//! A glTF document checked before the `gltf` crate's readers touch it. The crate's own
//! validation catches most out-of-range indices, but its readers assume the rest of the
//! specification holds and panic (or read garbage) when it does not: a JOINTS_0 accessor of
//! FLOATs, WEIGHTS_0 of signed BYTEs, indices of BYTEs, rotations of UNSIGNED_INTs, a
//! POSITION accessor or channel target that does not exist, a byteStride smaller than the
//! element, an unknown animation path. Everything this crate reads is checked here against
//! the glTF 2.0 specification (§3.6 accessors and buffer views, §3.7.2 mesh attributes,
//! §3.8 skins, §3.11 animations, §3.5 the node hierarchy), each failure a typed error
//! naming the accessor, attribute, node or channel:
//!
//! * accessors: a known componentType and type; the element inside its view's stride; a
//!   count of at least 1, a buffer view and no sparse storage where this crate reads them;
//!   `byteOffset + stride · (count − 1) + element` computed with checked arithmetic;
//! * buffer views: an existing buffer, inside its declared length (checked arithmetic), a
//!   byteStride of 4 to 252 bytes in steps of 4;
//! * mesh primitives: existing accessors; POSITION and NORMAL `VEC3` of FLOAT; JOINTS_n
//!   `VEC4` of UNSIGNED_BYTE or UNSIGNED_SHORT; WEIGHTS_n `VEC4` of FLOAT or of normalized
//!   UNSIGNED_BYTE or UNSIGNED_SHORT; indices `SCALAR` of UNSIGNED_BYTE, UNSIGNED_SHORT or
//!   UNSIGNED_INT; a known mode;
//! * skins: inverse bind matrices `MAT4` of FLOAT;
//! * animations: existing samplers, target nodes and accessors, a known path and
//!   interpolation; inputs `SCALAR` FLOAT; translations and scales `VEC3` FLOAT; rotations
//!   `VEC4` of FLOAT or of normalized BYTE, UNSIGNED_BYTE, SHORT or UNSIGNED_SHORT; morph
//!   weights `SCALAR`;
//! * nodes: at most one parent each (the crate's validation does not check it); finite
//!   translation, scale and matrix, and a finite rotation of non-zero length (a zero
//!   quaternion is no rotation: it is an error, not the identity).
//!
//! Cycles in the hierarchy are found by `Rig::new`.

use crate::error::{gltf_content, Result, SkinError};
use gltf::json::accessor::{ComponentType, Type};
use gltf::json::animation::Property;
use gltf::json::mesh::Semantic;
use gltf::json::validation::Checked;
use gltf::json::Root;

/// What an accessor may hold where it is used: its types, component types, and whether
/// integer components must be normalized (`Some(true)`), must not be (`Some(false)`), or
/// may be either (`None`).
struct Expect<'a> {
    what: &'a str,
    types: &'a [Type],
    components: &'a [(ComponentType, Option<bool>)],
}

const FLOAT: (ComponentType, Option<bool>) = (ComponentType::F32, Some(false));

fn component_name(c: ComponentType) -> &'static str {
    match c {
        ComponentType::I8 => "BYTE",
        ComponentType::U8 => "UNSIGNED_BYTE",
        ComponentType::I16 => "SHORT",
        ComponentType::U16 => "UNSIGNED_SHORT",
        ComponentType::U32 => "UNSIGNED_INT",
        ComponentType::F32 => "FLOAT",
    }
}

fn type_name(t: Type) -> &'static str {
    match t {
        Type::Scalar => "SCALAR",
        Type::Vec2 => "VEC2",
        Type::Vec3 => "VEC3",
        Type::Vec4 => "VEC4",
        Type::Mat2 => "MAT2",
        Type::Mat3 => "MAT3",
        Type::Mat4 => "MAT4",
    }
}

/// Bytes of one element: components × component size, each matrix column of 1- or 2-byte
/// components padded to 4 bytes (glTF §3.6.2.4).
fn element_size(t: Type, c: ComponentType) -> usize {
    let size = match c {
        ComponentType::I8 | ComponentType::U8 => 1,
        ComponentType::I16 | ComponentType::U16 => 2,
        ComponentType::U32 | ComponentType::F32 => 4,
    };
    let column = |rows: usize| (rows * size).div_ceil(4) * 4;
    match t {
        Type::Scalar => size,
        Type::Vec2 => 2 * size,
        Type::Vec3 => 3 * size,
        Type::Vec4 => 4 * size,
        Type::Mat2 => 2 * column(2),
        Type::Mat3 => 3 * column(3),
        Type::Mat4 => 4 * column(4),
    }
}

/// A GLB's 12-byte header: its declared length at least the header itself and at most the
/// bytes there are (the `gltf` crate's reader would subtract the header from a shorter one
/// without a check). Text (a `.gltf`) passes untouched.
pub(crate) fn check_glb_header(bytes: &[u8], name: &str) -> Result<()> {
    if !bytes.starts_with(b"glTF") {
        return Ok(());
    }
    let Some(length) = bytes.get(8..12) else {
        return Err(gltf_content(
            name,
            "GLB header",
            format!("is {} bytes of 12", bytes.len()),
        ));
    };
    let length = u32::from_le_bytes([length[0], length[1], length[2], length[3]]) as usize;
    if length < 12 || length > bytes.len() {
        return Err(gltf_content(
            name,
            "GLB header",
            format!(
                "declares {length} bytes; the file has {} (and the header alone is 12)",
                bytes.len()
            ),
        ));
    }
    Ok(())
}

/// Checks the whole document; `name` names the file in errors.
pub(crate) fn check(root: &Root, name: &str) -> Result<()> {
    for (i, v) in root.buffer_views.iter().enumerate() {
        let item = || format!("bufferView {i}");
        if v.buffer.value() >= root.buffers.len() {
            return Err(gltf_content(
                name,
                item(),
                format!(
                    "refers to buffer {}, which does not exist",
                    v.buffer.value()
                ),
            ));
        }
        let declared = root.buffers[v.buffer.value()].byte_length.0;
        let end = v
            .byte_offset
            .map_or(0, |o| o.0)
            .checked_add(v.byte_length.0);
        if end.is_none_or(|e| e > declared) {
            return Err(gltf_content(
                name,
                item(),
                format!(
                    "runs from byte {} for {} bytes, past the end of buffer {} ({declared} bytes)",
                    v.byte_offset.map_or(0, |o| o.0),
                    v.byte_length.0,
                    v.buffer.value()
                ),
            ));
        }
        if let Some(s) = v.byte_stride {
            if !(4..=252).contains(&s.0) || s.0 % 4 != 0 {
                return Err(gltf_content(
                    name,
                    item(),
                    format!("has byteStride {}: it must be 4 to 252 in steps of 4", s.0),
                ));
            }
        }
    }
    for (i, a) in root.accessors.iter().enumerate() {
        let item = || format!("accessor {i}");
        let (Checked::Valid(t), Checked::Valid(c)) = (a.type_, a.component_type) else {
            return Err(gltf_content(
                name,
                item(),
                "has an unknown type or componentType",
            ));
        };
        let elem = element_size(t, c.0);
        let Some(view) = a.buffer_view else { continue };
        let Some(v) = root.buffer_views.get(view.value()) else {
            return Err(gltf_content(
                name,
                item(),
                format!(
                    "refers to bufferView {}, which does not exist",
                    view.value()
                ),
            ));
        };
        let stride = v.byte_stride.map_or(elem, |s| s.0);
        if stride < elem {
            return Err(gltf_content(
                name,
                item(),
                format!(
                    "has {}-byte elements but its bufferView {} has byteStride {stride}",
                    elem,
                    view.value()
                ),
            ));
        }
        let offset = a.byte_offset.map_or(0, |o| o.0);
        let count = a.count.0;
        let needed = if count == 0 {
            Some(0)
        } else {
            (count - 1)
                .checked_mul(stride as u64)
                .and_then(|x| x.checked_add(offset))
                .and_then(|x| x.checked_add(elem as u64))
        };
        let available = v.byte_length.0;
        let what = || format!("{count} {} of {}", type_name(t), component_name(c.0));
        match needed {
            Some(n) if n <= available => {}
            Some(n) => {
                return Err(SkinError::Truncated {
                    file: name.to_string(),
                    accessor: i,
                    what: what(),
                    needed: usize::try_from(n).unwrap_or(usize::MAX),
                    available: usize::try_from(available).unwrap_or(usize::MAX),
                })
            }
            None => {
                return Err(gltf_content(
                    name,
                    item(),
                    format!(
                        "({}) needs more than 2^64 bytes: its count cannot be right",
                        what()
                    ),
                ))
            }
        }
    }
    let accessor = |index: usize, e: &Expect, at: &dyn Fn() -> String| -> Result<()> {
        let Some(a) = root.accessors.get(index) else {
            return Err(gltf_content(
                name,
                at(),
                format!(
                    "{} refers to accessor {index}, which does not exist",
                    e.what
                ),
            ));
        };
        let (Checked::Valid(t), Checked::Valid(c)) = (a.type_, a.component_type) else {
            return Err(gltf_content(
                name,
                at(),
                format!("{}: accessor {index} has an unknown type", e.what),
            ));
        };
        // The spec's minimum (and the crate's readers subtract 1 from it unchecked).
        if a.count.0 == 0 {
            return Err(gltf_content(
                name,
                at(),
                format!(
                    "{}: accessor {index} has count 0 (glTF asks for at least 1)",
                    e.what
                ),
            ));
        }
        if a.buffer_view.is_none() {
            return Err(gltf_content(
                name,
                at(),
                format!("{}: accessor {index} has no buffer view", e.what),
            ));
        }
        if a.sparse.is_some() {
            return Err(gltf_content(
                name,
                at(),
                format!(
                    "{}: accessor {index} is sparse, which is not supported here",
                    e.what
                ),
            ));
        }
        let component_ok = e
            .components
            .iter()
            .any(|(ct, norm)| *ct == c.0 && norm.is_none_or(|n| n == a.normalized));
        if !e.types.contains(&t) || !component_ok {
            let allowed: Vec<String> = e
                .components
                .iter()
                .map(|(ct, n)| match n {
                    Some(true) => format!("normalized {}", component_name(*ct)),
                    _ => component_name(*ct).to_string(),
                })
                .collect();
            let types: Vec<&str> = e.types.iter().map(|t| type_name(*t)).collect();
            return Err(gltf_content(
                name,
                at(),
                format!(
                    "{}: accessor {index} holds {}{} {}, where glTF allows {} of {}",
                    e.what,
                    if a.normalized { "normalized " } else { "" },
                    type_name(t),
                    component_name(c.0),
                    types.join(" or "),
                    allowed.join(", ")
                ),
            ));
        }
        Ok(())
    };
    for (mi, m) in root.meshes.iter().enumerate() {
        for (pi, p) in m.primitives.iter().enumerate() {
            let at = || format!("mesh {mi}, primitive {pi}");
            if !matches!(p.mode, Checked::Valid(_)) {
                return Err(gltf_content(name, at(), "has an unknown mode"));
            }
            for (semantic, index) in &p.attributes {
                let (what, e) = match semantic {
                    Checked::Valid(Semantic::Positions) => ("POSITION".to_string(), vec3_float()),
                    Checked::Valid(Semantic::Normals) => ("NORMAL".to_string(), vec3_float()),
                    Checked::Valid(Semantic::Joints(n)) => (format!("JOINTS_{n}"), joints()),
                    Checked::Valid(Semantic::Weights(n)) => (format!("WEIGHTS_{n}"), weights()),
                    _ => {
                        if index.value() >= root.accessors.len() {
                            return Err(gltf_content(
                                name,
                                at(),
                                format!(
                                    "an attribute refers to accessor {}, which does not exist",
                                    index.value()
                                ),
                            ));
                        }
                        continue;
                    }
                };
                let e = Expect { what: &what, ..e };
                accessor(index.value(), &e, &at)?;
            }
            if let Some(ix) = p.indices {
                let e = Expect {
                    what: "indices",
                    types: &[Type::Scalar],
                    components: &[
                        (ComponentType::U8, Some(false)),
                        (ComponentType::U16, Some(false)),
                        (ComponentType::U32, Some(false)),
                    ],
                };
                accessor(ix.value(), &e, &at)?;
            }
        }
    }
    for (si, s) in root.skins.iter().enumerate() {
        if let Some(ibm) = s.inverse_bind_matrices {
            let e = Expect {
                what: "inverseBindMatrices",
                types: &[Type::Mat4],
                components: &[FLOAT],
            };
            accessor(ibm.value(), &e, &|| format!("skin {si}"))?;
        }
        if let Some(j) = s.joints.iter().find(|j| j.value() >= root.nodes.len()) {
            return Err(gltf_content(
                name,
                format!("skin {si}"),
                format!("has joint node {}, which does not exist", j.value()),
            ));
        }
    }
    for (ai, anim) in root.animations.iter().enumerate() {
        for (ci, c) in anim.channels.iter().enumerate() {
            let at = || format!("animation {ai}, channel {ci}");
            let Some(s) = anim.samplers.get(c.sampler.value()) else {
                return Err(gltf_content(
                    name,
                    at(),
                    format!("uses sampler {}, which does not exist", c.sampler.value()),
                ));
            };
            if c.target.node.value() >= root.nodes.len() {
                return Err(gltf_content(
                    name,
                    at(),
                    format!(
                        "targets node {}, which does not exist",
                        c.target.node.value()
                    ),
                ));
            }
            let Checked::Valid(path) = c.target.path else {
                return Err(gltf_content(
                    name,
                    at(),
                    "targets an unknown path (glTF has translation, rotation, scale and weights)",
                ));
            };
            if !matches!(s.interpolation, Checked::Valid(_)) {
                return Err(gltf_content(name, at(), "has an unknown interpolation"));
            }
            let input = Expect {
                what: "sampler input",
                types: &[Type::Scalar],
                components: &[FLOAT],
            };
            accessor(s.input.value(), &input, &at)?;
            let normalized_ints = [
                FLOAT,
                (ComponentType::I8, Some(true)),
                (ComponentType::U8, Some(true)),
                (ComponentType::I16, Some(true)),
                (ComponentType::U16, Some(true)),
            ];
            let output = match path {
                Property::Translation | Property::Scale => Expect {
                    what: "sampler output",
                    types: &[Type::Vec3],
                    components: &[FLOAT],
                },
                Property::Rotation => Expect {
                    what: "sampler output (rotation)",
                    types: &[Type::Vec4],
                    components: &normalized_ints,
                },
                Property::MorphTargetWeights => Expect {
                    what: "sampler output (weights)",
                    types: &[Type::Scalar],
                    components: &normalized_ints,
                },
            };
            accessor(s.output.value(), &output, &at)?;
        }
    }
    let mut parent = vec![None; root.nodes.len()];
    for (ni, n) in root.nodes.iter().enumerate() {
        let at = || format!("node {ni}");
        for c in n.children.iter().flatten() {
            let Some(slot) = parent.get_mut(c.value()) else {
                return Err(gltf_content(
                    name,
                    at(),
                    format!("has child {}, which does not exist", c.value()),
                ));
            };
            if let Some(p) = *slot {
                return Err(gltf_content(
                    name,
                    format!("node {}", c.value()),
                    format!("has two parents, nodes {p} and {ni}"),
                ));
            }
            *slot = Some(ni);
        }
        let finite = |v: &[f32]| v.iter().all(|x| x.is_finite());
        if !n.translation.is_none_or(|t| finite(&t))
            || !n.scale.is_none_or(|s| finite(&s))
            || !n.matrix.is_none_or(|m| finite(&m))
        {
            return Err(gltf_content(
                name,
                at(),
                "has a translation, scale or matrix that is not finite",
            ));
        }
        if let Some(r) = n.rotation {
            let norm2: f32 = r.0.iter().map(|x| x * x).sum();
            if !finite(&r.0) || norm2 == 0.0 || !norm2.is_normal() {
                return Err(gltf_content(
                    name,
                    at(),
                    format!(
                        "has rotation {:?}, which is not a rotation (zero or not finite)",
                        r.0
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The `gltf` crate's own validation (index ranges, required fields), run after
/// [`check`] has made its indexing safe; its first findings become one error.
pub(crate) fn crate_validation(root: &Root, name: &str) -> Result<()> {
    use gltf::json::validation::Validate;
    let mut errors = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |path, error| {
        errors.push(format!("{}: {error}", path()))
    });
    if errors.is_empty() {
        return Ok(());
    }
    let shown: Vec<&str> = errors.iter().take(3).map(String::as_str).collect();
    let more = errors.len().saturating_sub(3);
    Err(SkinError::Gltf {
        path: name.to_string(),
        reason: format!(
            "invalid glTF: {}{}",
            shown.join("; "),
            if more > 0 {
                format!(" (and {more} more)")
            } else {
                String::new()
            }
        ),
    })
}

fn vec3_float() -> Expect<'static> {
    Expect {
        what: "",
        types: &[Type::Vec3],
        components: &[FLOAT],
    }
}

fn joints() -> Expect<'static> {
    Expect {
        what: "",
        types: &[Type::Vec4],
        components: &[
            (ComponentType::U8, Some(false)),
            (ComponentType::U16, Some(false)),
        ],
    }
}

fn weights() -> Expect<'static> {
    Expect {
        what: "",
        types: &[Type::Vec4],
        components: &[
            FLOAT,
            (ComponentType::U8, Some(true)),
            (ComponentType::U16, Some(true)),
        ],
    }
}
