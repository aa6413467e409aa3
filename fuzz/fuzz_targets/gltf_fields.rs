//! Structure-aware glTF fuzzing: one of the five built-in models with a few of its JSON
//! fields replaced — an index, a count, an offset, a stride, a component type, a type, a
//! path, a number, a whole array or object — by values a fuzzer would take long to reach by
//! flipping bytes (the edges of u32 and u64, negative and huge numbers, other fields' values,
//! wrong kinds), then loaded (a GLB is rebuilt around its edited JSON chunk with its binary
//! chunk kept). Byte flips mostly break the JSON syntax; these edits keep it and reach the
//! checks behind it. A rig that loads is posed by its first clip and skinned.
#![no_main]

use arbitrary::{Arbitrary, Unstructured};
use libfuzzer_sys::fuzz_target;
use serde_json::{json, Value};

/// The JSON and (for a GLB) the binary chunk of a model.
fn split(bytes: &[u8]) -> Option<(Value, Option<Vec<u8>>)> {
    if !bytes.starts_with(b"glTF") {
        return Some((serde_json::from_slice(bytes).ok()?, None));
    }
    let word = |at: usize| -> Option<usize> {
        Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?) as usize)
    };
    let json_len = word(12)?;
    let json = serde_json::from_slice(bytes.get(20..20 + json_len)?).ok()?;
    let at = 20 + json_len;
    let bin = if bytes.len() > at + 8 {
        let n = word(at)?;
        Some(bytes.get(at + 8..at + 8 + n)?.to_vec())
    } else {
        None
    };
    Some((json, bin))
}

/// A GLB of `json` and `bin` (chunks padded to 4 bytes, as the format asks).
fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| n.div_ceil(4) * 4;
    let (jl, bl) = (pad(json.len()), pad(bin.len()));
    let total = 12 + 8 + jl + 8 + bl;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(jl as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(json);
    out.resize(20 + jl, b' ');
    out.extend_from_slice(&(bl as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out.resize(total, 0);
    out
}

/// Every path to a value in `v` (object keys and array indices).
fn paths(v: &Value, at: &mut Vec<Value>, out: &mut Vec<Vec<Value>>) {
    out.push(at.clone());
    match v {
        Value::Object(o) => {
            for (k, x) in o {
                at.push(json!(k));
                paths(x, at, out);
                at.pop();
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                at.push(json!(i));
                paths(x, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn get<'a>(v: &'a Value, path: &[Value]) -> Option<&'a Value> {
    path.iter().try_fold(v, |v, k| match k {
        Value::String(s) => v.get(s.as_str()),
        Value::Number(n) => v.get(n.as_u64()? as usize),
        _ => None,
    })
}

fn get_mut<'a>(v: &'a mut Value, path: &[Value]) -> Option<&'a mut Value> {
    path.iter().try_fold(v, |v, k| match k {
        Value::String(s) => v.get_mut(s.as_str()),
        Value::Number(n) => v.get_mut(n.as_u64()? as usize),
        _ => None,
    })
}

/// A replacement value.
#[derive(Arbitrary, Debug)]
enum Replacement {
    Small(i8),
    U32Edge(u8),
    U64Edge(u8),
    Float(f64),
    Huge(bool),
    ComponentType(u8),
    Type(u8),
    Path(u8),
    Interpolation(u8),
    EmptyArray,
    EmptyObject,
    Null,
    Text(String),
    Drop,
    CopyOf(u16),
}

fn value_of(r: &Replacement, doc: &Value, all: &[Vec<Value>]) -> Option<Value> {
    Some(match r {
        Replacement::Small(n) => json!(n),
        Replacement::U32Edge(k) => json!(u32::MAX as u64 - u64::from(*k % 4) + u64::from(*k & 4)),
        Replacement::U64Edge(k) => json!(u64::MAX - u64::from(*k % 8)),
        Replacement::Float(x) if x.is_finite() => json!(x),
        Replacement::Float(_) => json!(1e308),
        Replacement::Huge(neg) => json!(if *neg { -1e300 } else { 1e300 }),
        Replacement::ComponentType(k) => {
            json!([5120, 5121, 5122, 5123, 5125, 5126, 5124, 0][*k as usize % 8])
        }
        Replacement::Type(k) => json!(
            ["SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4", "VEC5"][*k as usize % 8]
        ),
        Replacement::Path(k) => {
            json!(["translation", "rotation", "scale", "weights", "wobble"][*k as usize % 5])
        }
        Replacement::Interpolation(k) => {
            json!(["LINEAR", "STEP", "CUBICSPLINE", "SMOOTH"][*k as usize % 4])
        }
        Replacement::EmptyArray => json!([]),
        Replacement::EmptyObject => json!({}),
        Replacement::Null => Value::Null,
        Replacement::Text(s) => json!(s),
        Replacement::Drop => return None,
        Replacement::CopyOf(i) => {
            let p = &all[*i as usize % all.len()];
            get(doc, p)?.clone()
        }
    })
}

/// A model split once: its JSON, binary chunk and the paths into its JSON.
struct Parsed {
    file: &'static str,
    doc: Value,
    bin: Option<Vec<u8>>,
    all: Vec<Vec<Value>>,
}

fn parsed() -> &'static [Parsed] {
    static MODELS: std::sync::OnceLock<Vec<Parsed>> = std::sync::OnceLock::new();
    MODELS.get_or_init(|| {
        chasles_models::ALL
            .iter()
            .filter_map(|m| {
                let (doc, bin) = split(m.bytes)?;
                let mut all = Vec::new();
                paths(&doc, &mut Vec::new(), &mut all);
                // Leave the base64 buffers alone: editing their text finds nothing new.
                all.retain(|p| p.first() != Some(&json!("buffers")) || p.len() < 3);
                Some(Parsed {
                    file: m.file,
                    doc,
                    bin,
                    all,
                })
            })
            .collect()
    })
}

fn edit(u: &mut Unstructured) -> arbitrary::Result<()> {
    let models = parsed();
    let model = &models[u.choose_index(models.len())?];
    let (mut doc, bin, all) = (model.doc.clone(), model.bin.clone(), &model.all);
    for _ in 0..u.int_in_range(1..=4)? {
        let p = all[u.choose_index(all.len())?].clone();
        if p.is_empty() {
            continue;
        }
        let r = Replacement::arbitrary(u)?;
        let new = value_of(&r, &model.doc, all);
        let (last, parent) = p.split_last().expect("not empty");
        let Some(parent) = get_mut(&mut doc, parent) else {
            continue;
        };
        match (parent, last, new) {
            (Value::Object(o), Value::String(k), Some(v)) => {
                o.insert(k.clone(), v);
            }
            (Value::Object(o), Value::String(k), None) => {
                o.remove(k);
            }
            (Value::Array(a), Value::Number(n), v) => {
                let i = n.as_u64().unwrap_or(0) as usize;
                if i < a.len() {
                    match v {
                        Some(v) => a[i] = v,
                        None => {
                            a.remove(i);
                        }
                    }
                }
            }
            _ => {}
        }
    }
    let text = serde_json::to_vec(&doc).expect("serializes");
    let bytes = match bin {
        Some(bin) => glb(&text, &bin),
        None => text,
    };
    if let Ok(rig) = chasles_skin::gltf_load::load_slice(&bytes, model.file) {
        // Skinning every large model each time would cost the fuzzer most of its runs.
        if rig.mesh.positions.len() <= 2_000 {
            let pose = if rig.animations.is_empty() {
                Ok(chasles_skin::Pose::rest(&rig))
            } else {
                chasles_skin::Pose::animated(&rig, 0, 0.37)
            };
            if let Ok(pose) = pose {
                for m in [chasles_skin::Method::Lbs, chasles_skin::Method::Dqs] {
                    let _ = chasles_skin::skin(&rig, &pose, m);
                }
            }
        }
    }
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let _ = edit(&mut Unstructured::new(data));
});
