//! `gltf_write::rig_glb`: a rig written with clips and read back by `gltf_load` is the same
//! rig (plus the node holding the mesh) with the same clips, bit for bit where nothing is
//! computed on the way (the loader normalizes weights and rest rotations: an ulp or two):
//! the built-in characters with their own clips, and a JSON rig with six influences on a
//! vertex (two JOINTS/WEIGHTS sets) and STEP and CUBICSPLINE channels.

use chasles_skin::animation::{Animation, Channel, Interpolation, Path};
use chasles_skin::gltf_write::rig_glb;
use chasles_skin::{gltf_load, json_rig, Rig};

fn same_rig(rig: &Rig, back: &Rig, clips: &[Animation]) {
    assert_eq!(back.mesh.positions, rig.mesh.positions);
    assert_eq!(back.mesh.normals, rig.mesh.normals);
    assert_eq!(back.mesh.triangles, rig.mesh.triangles);
    assert_eq!(back.nodes.len(), rig.nodes.len() + 1);
    for (i, (a, b)) in back.nodes.iter().zip(&rig.nodes).enumerate() {
        assert_eq!((&a.name, a.parent), (&b.name, b.parent), "node {i}");
        assert_eq!(a.rest.translation, b.rest.translation, "node {i}");
        assert_eq!(a.rest.scale, b.rest.scale, "node {i}");
        // The loader normalizes rotations: an ulp or two where the file's was not unit.
        let d = (a.rest.rotation - b.rest.rotation).norm();
        assert!(d <= 2.5e-7, "node {i}: {d}");
    }
    assert_eq!(back.nodes.last().unwrap().name, "skinned mesh");
    assert_eq!(back.joints, rig.joints);
    assert_eq!(back.inverse_bind, rig.inverse_bind);
    assert_eq!(back.influences.start, rig.influences.start);
    assert_eq!(back.influences.joints, rig.influences.joints);
    for (a, b) in back.influences.weights.iter().zip(&rig.influences.weights) {
        // Renormalized on loading: at most a unit in the last place or two.
        assert!((a - b).abs() <= 2.5e-7, "{a} vs {b}");
    }
    assert_eq!(back.animations, clips);
}

#[test]
fn the_characters_come_back_with_their_clips() {
    for m in [chasles_models::CESIUM_MAN, chasles_models::FOX] {
        let rig = gltf_load::load_slice(m.bytes, m.file).unwrap();
        let bytes = rig_glb(&rig, &rig.animations, "round trip").unwrap();
        let back = gltf_load::load_slice(&bytes, "back.glb").unwrap();
        same_rig(&rig, &back, &rig.animations);
        // Without clips: none.
        let bare = gltf_load::load_slice(&rig_glb(&rig, &[], "").unwrap(), "bare.glb").unwrap();
        assert!(bare.animations.is_empty());
    }
}

#[test]
fn six_influences_and_every_interpolation_come_back() {
    let text = r#"{
        "positions": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]],
        "triangles": [[0,1,2],[1,3,2]],
        "joints": [
            {"name": "a", "parent": null},
            {"name": "b", "parent": 0, "translation": [0, 1, 0]},
            {"name": "c", "parent": 1, "translation": [0, 1, 0], "rotation": [0.9238795, 0, 0, 0.3826834]},
            {"name": "d", "parent": 0, "translation": [1, 0, 0], "scale": [1, 2, 1]},
            {"name": "e", "parent": 3},
            {"name": "f", "parent": 4, "translation": [0, 0, 1]}
        ],
        "influences": [
            [[0, 0.3], [1, 0.25], [2, 0.15], [3, 0.12], [4, 0.1], [5, 0.08]],
            [[1, 1]], [[2, 0.5], [3, 0.5]], [[5, 1]]
        ]
    }"#;
    let rig = json_rig::parse_rig(text, "six.json").unwrap();
    assert_eq!(rig.influences.max_per_vertex(), 6);
    let clip = Animation {
        name: "mixed".into(),
        channels: vec![
            Channel {
                node: 1,
                path: Path::Rotation,
                interpolation: Interpolation::CubicSpline,
                times: vec![0.0, 0.5],
                values: vec![
                    [0.0, 0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0, 0.0],
                    [0.0, 0.5, 0.0, 0.0],
                    [0.0, 0.1, 0.0, 0.0],
                    [0.8, 0.6, 0.0, 0.0],
                    [0.0, 0.0, 0.0, 0.0],
                ],
            },
            Channel {
                node: 3,
                path: Path::Translation,
                interpolation: Interpolation::Step,
                times: vec![0.0, 0.25, 1.0],
                values: vec![
                    [1.0, 0.0, 0.0, 0.0],
                    [1.0, 2.0, 3.0, 0.0],
                    [0.0, -1.0, 0.5, 0.0],
                ],
            },
            Channel {
                node: 5,
                path: Path::Scale,
                interpolation: Interpolation::Linear,
                times: vec![0.1, 0.9],
                values: vec![[1.0, 1.0, 1.0, 0.0], [2.0, 0.5, 1.0, 0.0]],
            },
        ],
    };
    let bytes = rig_glb(&rig, std::slice::from_ref(&clip), "six").unwrap();
    let back = gltf_load::load_slice(&bytes, "six.glb").unwrap();
    same_rig(&rig, &back, std::slice::from_ref(&clip));
    // A clip naming a node the rig lacks is refused before anything is written.
    let mut bad = clip.clone();
    bad.channels[0].node = 99;
    let e = rig_glb(&rig, &[bad], "bad").unwrap_err().to_string();
    assert!(e.contains("99"), "{e}");
}
