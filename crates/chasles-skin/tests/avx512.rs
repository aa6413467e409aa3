//! DIB's sixteen-vertex AVX-512F kernel against the eight-vertex AVX2 kernel alone
//! (`fast::set_avx512(false)`), through the public job: the same bits for every vertex, on
//! the built-in characters (four and eight influences, one thread and all) and on a mesh big
//! enough to stream its output. One test in its own binary, since the switch is
//! process-wide.

use chasles_skin::fast::{dib, set_avx512, uses_avx512, uses_simd, FastRig, Out};
use chasles_skin::{gltf_load, joint_transforms, synthetic, Pose};

/// `rig`'s DIB by eight alone and, switched back on, with sixteen where it runs.
fn both<const K: usize>(
    rig: &FastRig<K>,
    d: &[chasles::DualQuat<f32>],
    parallel: bool,
) -> [Vec<Out>; 2] {
    let n = rig.vertices().len();
    let (mut eight, mut sixteen) = (vec![[f32::NAN; 6]; n], vec![[f32::NAN; 6]; n]);
    set_avx512(false);
    assert!(!uses_avx512(K));
    dib(rig, d, &mut eight, parallel).unwrap();
    set_avx512(true);
    dib(rig, d, &mut sixteen, parallel).unwrap();
    [eight, sixteen]
}

/// The two outputs' bits, vertex by vertex.
fn same(what: &str, [eight, sixteen]: &[Vec<Out>; 2]) {
    for (v, (a, b)) in eight.iter().zip(sixteen).enumerate() {
        assert_eq!(
            a.map(f32::to_bits),
            b.map(f32::to_bits),
            "{what}, vertex {v}: {a:?} by eight, {b:?} by sixteen"
        );
    }
}

#[test]
fn sixteen_lanes_skin_every_vertex_to_the_bits_of_eight() {
    let wide = uses_avx512(4);
    assert_eq!(
        wide,
        uses_simd(4) && std::is_x86_feature_detected!("avx512f"),
        "the sixteen-vertex kernel runs where AVX-512F does, unless switched off"
    );
    if !wide {
        eprintln!("no AVX-512F here: both runs are the eight-vertex (or scalar) kernel");
    }
    for m in [chasles_models::CESIUM_MAN, chasles_models::FOX] {
        let rig = gltf_load::load_slice(m.bytes, m.file).unwrap();
        let clip = &rig.animations[0];
        for t in [0.1, 0.5, 0.9].map(|f| f * clip.duration()) {
            let pose = Pose::animated(&rig, 0, t).unwrap();
            let jt = joint_transforms(&rig, &pose).unwrap();
            for parallel in [false, true] {
                let what = format!("{} at {t} s, parallel {parallel}", rig.name);
                same(
                    &what,
                    &both(&FastRig::<4>::new(&rig).unwrap(), &jt.dual_quats, parallel),
                );
                same(
                    &what,
                    &both(&FastRig::<8>::new(&rig).unwrap(), &jt.dual_quats, parallel),
                );
            }
        }
    }
    // Streamed (packed output, non-temporal stores) past 2^18 vertices; 60° poses.
    let big = synthetic::rig((1 << 18) + 13, 54, 3);
    let jt = synthetic::joints(54, 3);
    same("the big mesh", &both(&big, &jt.dual_quats, true));
    assert_eq!(uses_avx512(4), wide, "the switch is back");
}
