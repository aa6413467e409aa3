//! The AVX-512 code against the AVX2 code alone (`fast::set_avx512(false)`), through the
//! public job: DIB's sixteen-vertex kernel against its eight-vertex one, and every other
//! method's kernels built with AVX-512F and VL's 32 registers (`avx2::registers`) against
//! their AVX2 build, and SBS's centres solved eight clusters at a time against four. The
//! same bits for every vertex, on the built-in characters (four and eight influences, one
//! thread and all, packed, interleaved and split outputs), on a rig too small for a sign
//! table, and on a mesh big enough to stream its output (which build ran is counted by a
//! unit test, `avx2::registers`). One test in its own binary, since the switch is
//! process-wide.

use chasles_skin::fast::{
    set_avx512, uses_avx512, uses_simd, FastRig, Out, Output, Palette, SkinningJob,
};
use chasles_skin::{gltf_load, joint_transforms, synthetic, JointTransforms, Method, Pose};

/// `rig` skinned by `method` into `layout` (0 packed, 1 interleaved of stride 8, 2 split),
/// read back as packed outputs; NaN where nothing was written.
fn skin<const K: usize>(
    rig: &FastRig<K>,
    jt: &JointTransforms,
    method: Method,
    layout: usize,
    parallel: bool,
) -> Vec<Out> {
    let n = rig.vertices().len();
    let palette = Palette::from_joint_transforms(method, rig, jt, parallel).unwrap();
    let job = |output| SkinningJob {
        rig,
        palette: &palette,
        output,
        parallel,
    };
    match layout {
        0 => {
            let mut out = vec![[f32::NAN; 6]; n];
            job(Output::Packed(&mut out)).run().unwrap();
            out
        }
        1 => {
            let mut data = vec![f32::NAN; n * 8];
            job(Output::Interleaved {
                data: &mut data,
                stride: 8,
            })
            .run()
            .unwrap();
            data.chunks(8)
                .map(|v| core::array::from_fn(|k| v[k]))
                .collect()
        }
        _ => {
            let (mut p, mut q) = (vec![[f32::NAN; 3]; n], vec![[f32::NAN; 3]; n]);
            job(Output::Split {
                positions: &mut p,
                normals: &mut q,
            })
            .run()
            .unwrap();
            p.iter()
                .zip(&q)
                .map(|(p, q)| [p[0], p[1], p[2], q[0], q[1], q[2]])
                .collect()
        }
    }
}

/// `rig` skinned by the AVX2 code alone and, switched back on, by the AVX-512 code where it
/// runs: the two outputs' bits, vertex by vertex.
fn same<const K: usize>(what: &str, rig: &FastRig<K>, jt: &JointTransforms, parallel: bool) {
    let layouts = if rig.vertices().len() > 100_000 {
        0..1
    } else {
        0..3
    };
    for method in Method::ALL {
        for layout in layouts.clone() {
            set_avx512(false);
            assert!(!uses_avx512(K));
            let narrow = skin(rig, jt, method, layout, parallel);
            set_avx512(true);
            let wide = skin(rig, jt, method, layout, parallel);
            for (v, (a, b)) in narrow.iter().zip(&wide).enumerate() {
                assert_eq!(
                    a.map(f32::to_bits),
                    b.map(f32::to_bits),
                    "{what}, {} into layout {layout}, vertex {v}: {a:?} by AVX2, {b:?} by \
                     AVX-512",
                    method.name()
                );
            }
        }
    }
}

#[test]
fn the_avx512_code_skins_every_vertex_to_the_bits_of_avx2() {
    let wide = uses_avx512(4);
    assert_eq!(
        wide,
        uses_simd(4)
            && std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512vl"),
        "the AVX-512 code runs where AVX-512F and VL do, unless switched off"
    );
    if !wide {
        eprintln!("no AVX-512F and VL here: both runs are the AVX2 (or scalar) kernels");
    }
    for m in [chasles_models::CESIUM_MAN, chasles_models::FOX] {
        let rig = gltf_load::load_slice(m.bytes, m.file).unwrap();
        let clip = &rig.animations[0];
        for t in [0.1, 0.5, 0.9].map(|f| f * clip.duration()) {
            let pose = Pose::animated(&rig, 0, t).unwrap();
            let jt = joint_transforms(&rig, &pose).unwrap();
            for parallel in [false, true] {
                let what = format!("{} at {t} s, parallel {parallel}", rig.name);
                same(&what, &FastRig::<4>::new(&rig).unwrap(), &jt, parallel);
                same(&what, &FastRig::<8>::new(&rig).unwrap(), &jt, parallel);
            }
        }
    }
    // No table (54² signs are more than 1003 vertices): the antipodality signs from dot
    // products, the blends' other path; four and eight influences.
    let jt = synthetic::joints(54, 3);
    same("no table", &synthetic::rig(1003, 54, 5), &jt, false);
    same(
        "no table",
        &synthetic::rig_with::<8>(1003, 54, 5),
        &jt,
        true,
    );
    // Streamed (packed output, non-temporal stores) past 2^18 vertices; 60° poses, and a
    // table (the synthetic rig's 54 joints, far fewer than its vertices).
    let big = synthetic::rig((1 << 18) + 13, 54, 3);
    same("the big mesh", &big, &jt, true);
    assert_eq!(uses_avx512(4), wide, "the switch is back");
}
