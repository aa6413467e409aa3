//! glTF files broken the ways a fuzzer broke them (issue 17): each is a typed error naming
//! the accessor, attribute, node or channel — never a panic, never garbage read as data.
//! The files are SimpleSkin.gltf (built in) with one JSON field changed.

use chasles_skin::gltf_load::load_slice;
use chasles_skin::SkinError;
use serde_json::{json, Value};

/// SimpleSkin with `edit` applied, loaded.
fn load_edited(edit: impl FnOnce(&mut Value)) -> Result<chasles_skin::Rig, SkinError> {
    let mut doc: Value = serde_json::from_slice(chasles_models::SIMPLE_SKIN.bytes).unwrap();
    edit(&mut doc);
    load_slice(&serde_json::to_vec(&doc).unwrap(), "edited.gltf")
}

/// The error's message, which must name `item` and say `words`.
fn fails(edit: impl FnOnce(&mut Value), item: &str, words: &str) {
    let e = load_edited(edit).expect_err("a broken file loaded");
    let msg = e.to_string();
    assert!(msg.contains("edited.gltf"), "{msg}");
    assert!(msg.contains(item) && msg.contains(words), "{msg}");
}

#[test]
fn the_original_loads() {
    let rig = load_edited(|_| {}).unwrap();
    assert_eq!(rig.mesh.positions.len(), 10);
}

#[test]
fn component_types_and_types_are_those_the_spec_allows() {
    fails(
        |d| d["accessors"][2]["componentType"] = json!(5126),
        "JOINTS_0: accessor 2",
        "VEC4 FLOAT",
    );
    fails(
        |d| d["accessors"][3]["componentType"] = json!(5120),
        "WEIGHTS_0: accessor 3",
        "VEC4 BYTE",
    );
    fails(
        |d| d["accessors"][3]["normalized"] = json!(true),
        "WEIGHTS_0",
        "normalized VEC4 FLOAT",
    );
    fails(
        |d| d["accessors"][0]["componentType"] = json!(5120),
        "indices: accessor 0",
        "SCALAR BYTE",
    );
    fails(
        |d| d["accessors"][6]["componentType"] = json!(5125),
        "sampler output (rotation): accessor 6",
        "UNSIGNED_INT",
    );
    fails(
        |d| d["accessors"][2]["type"] = json!("VEC3"),
        "JOINTS_0",
        "VEC3 UNSIGNED_SHORT",
    );
    fails(
        |d| d["accessors"][1]["type"] = json!("VEC2"),
        "POSITION: accessor 1",
        "VEC2 FLOAT",
    );
    fails(
        |d| d["accessors"][4]["type"] = json!("VEC4"),
        "skin 0: inverseBindMatrices",
        "VEC4 FLOAT",
    );
    fails(
        |d| d["accessors"][5]["type"] = json!("VEC2"),
        "sampler input: accessor 5",
        "VEC2",
    );
    fails(
        |d| d["accessors"][1]["componentType"] = json!(7),
        "edited.gltf",
        "componentType",
    );
}

#[test]
fn indices_strides_and_paths_are_checked_before_they_are_used() {
    fails(
        |d| d["animations"][0]["channels"][0]["target"]["node"] = json!(99),
        "animation 0, channel 0",
        "targets node 99, which does not exist",
    );
    fails(
        |d| d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(99),
        "POSITION",
        "accessor 99, which does not exist",
    );
    fails(
        |d| d["meshes"][0]["primitives"][0]["indices"] = json!(42),
        "indices",
        "accessor 42, which does not exist",
    );
    fails(
        |d| d["bufferViews"][2]["byteStride"] = json!(4),
        "accessor 2",
        "8-byte elements but its bufferView 2 has byteStride 4",
    );
    fails(
        |d| d["bufferViews"][2]["byteStride"] = json!(18),
        "bufferView 2",
        "byteStride 18",
    );
    fails(
        |d| d["animations"][0]["channels"][0]["target"]["path"] = json!("wobble"),
        "animation 0, channel 0",
        "unknown path",
    );
    fails(
        |d| d["animations"][0]["channels"][0]["sampler"] = json!(5),
        "animation 0, channel 0",
        "sampler 5, which does not exist",
    );
    fails(
        |d| d["accessors"][1]["bufferView"] = json!(9),
        "accessor 1",
        "bufferView 9, which does not exist",
    );
    fails(
        |d| d["bufferViews"][1]["buffer"] = json!(9),
        "bufferView 1",
        "buffer 9, which does not exist",
    );
    fails(
        |d| d["skins"][0]["joints"] = json!([1, 20]),
        "skin 0",
        "joint node 20",
    );
    fails(
        |d| d["nodes"][1]["children"] = json!([7]),
        "node 1",
        "child 7, which does not exist",
    );
    // A count that overflows any offset arithmetic.
    fails(
        |d| d["accessors"][1]["count"] = json!(u64::MAX / 2),
        "accessor 1",
        "needs",
    );
}

#[test]
fn the_hierarchy_has_one_parent_per_node_and_no_cycle() {
    fails(
        |d| d["nodes"][0]["children"] = json!([1, 2]),
        "node 2",
        "has two parents, nodes 0 and 1",
    );
    // 1 → 2 → 1: node 1 then has parents 0 and 2.
    fails(
        |d| d["nodes"][2]["children"] = json!([1]),
        "node 1",
        "two parents",
    );
    // A cycle without a second parent: 0 → 1 → 2 → 0 … with the root's own edge gone.
    let e = load_edited(|d| {
        d["nodes"][0]["children"] = json!([]);
        d["nodes"][2]["children"] = json!([1]);
    })
    .expect_err("a cycle loaded");
    assert!(e.to_string().contains("cyclic"), "{e}");
}

#[test]
fn zero_rotations_are_errors_not_the_identity() {
    fails(
        |d| d["nodes"][2]["rotation"] = json!([0, 0, 0, 0]),
        "node 2",
        "not a rotation",
    );
    // A number past f32's range: the JSON reader (serde_json with float_roundtrip, which
    // reads every number exactly) refuses it where it stands, by line and column; the
    // loader's own "node 1: not finite" check stays behind it for other readers.
    fails(
        |d| d["nodes"][1]["translation"] = json!([0, 1e39, 0]),
        "line 1 column",
        "number out of range",
    );
}

/// The first key of the rotation channel (accessor 6) set to zero in the embedded buffer.
#[test]
fn a_zero_rotation_key_is_an_error_naming_it() {
    use base64::Engine;
    let e = load_edited(|d| {
        let acc = d["accessors"][6].clone();
        let view = d["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize].clone();
        let b = view["buffer"].as_u64().unwrap() as usize;
        let uri = d["buffers"][b]["uri"].as_str().unwrap().to_string();
        let (head, payload) = uri.split_once(";base64,").unwrap();
        let mut bytes = base64::engine::general_purpose::STANDARD
            .decode(payload)
            .unwrap();
        let at = (view["byteOffset"].as_u64().unwrap_or(0)
            + acc["byteOffset"].as_u64().unwrap_or(0)) as usize;
        bytes[at..at + 16].fill(0);
        let uri = format!(
            "{head};base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&bytes)
        );
        d["buffers"][b]["uri"] = json!(uri);
    })
    .expect_err("a zero rotation key loaded");
    let msg = e.to_string();
    assert!(
        msg.contains("animation 0, channel 0") && msg.contains("rotation key 0"),
        "{msg}"
    );
}

#[test]
fn counts_of_zero_and_sparse_accessors_are_refused_where_read() {
    fails(
        |d| d["accessors"][1]["count"] = json!(0),
        "POSITION: accessor 1",
        "count 0",
    );
    fails(
        |d| d["accessors"][5]["count"] = json!(0),
        "sampler input: accessor 5",
        "count 0",
    );
    fails(
        |d| d["accessors"][1]["sparse"] = json!({"count": 1, "indices": {"bufferView": 0, "componentType": 5123}, "values": {"bufferView": 1}}),
        "POSITION: accessor 1",
        "sparse",
    );
}

#[test]
fn buffer_views_stay_inside_their_buffer() {
    fails(
        |d| d["bufferViews"][1]["byteOffset"] = json!(u64::MAX - 10),
        "bufferView 1",
        "past the end of buffer 0",
    );
    fails(
        |d| d["bufferViews"][1]["byteLength"] = json!(100_000),
        "bufferView 1",
        "past the end of buffer 0 (168 bytes)",
    );
}
