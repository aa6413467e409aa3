//! The fast path's SIMD kernels against the scalar ones (x86-64 with AVX2 and FMA; elsewhere
//! there is nothing to compare).

use super::*;
use crate::synthetic;

/// A SIMD kernel's output on the whole blocks of `rig` (checked to be all of them but
/// the last few vertices), and the scalar kernel's on the same vertices.
fn both<const K: usize, F: Kernel<K>>(
    rig: &FastRig<K>,
    joints: &[F::Joint],
    kernel: SimdKernel<K, F::Joint, F::Table>,
) -> [Vec<Out>; 2] {
    let n = rig.vertices.len();
    let mut simd = vec![[f32::NAN; 6]; n];
    // SAFETY: the callers check `simd(K)`; the rig's joint indices are below its joint
    // count, which is `joints.len()`; the table is made from `joints`; `simd` is as
    // long as the vertices.
    let done = unsafe { kernel(&rig.vertices, joints, &F::table(joints, n), &mut simd) };
    assert_eq!(done, n / 8 * 8, "the SIMD kernel did every whole block");
    simd.truncate(done);
    let scalar = rig.vertices[..done]
        .iter()
        .map(|v| F::vertex(v, joints))
        .collect();
    [simd, scalar]
}

/// The largest difference of two outputs, and the share of vertices within `tol`.
fn apart(a: &[Out], b: &[Out], tol: f32) -> (f32, f64) {
    let d: Vec<f32> = a.iter().zip(b).map(|(a, b)| max_diff(a, b)).collect();
    let within = d.iter().filter(|x| **x <= tol).count() as f64 / d.len() as f64;
    (d.iter().copied().fold(0f32, f32::max), within)
}

/// 8 influences: the SIMD kernels are the scalar ones (LBS bit for bit, the others to
/// rounding; DIB apart only where an update's norm falls on either side of the
/// precision), SBS included.
#[test]
fn the_simd_kernels_take_8_influences() {
    if !simd(8) {
        eprintln!("no AVX2+FMA here: nothing to compare");
        return;
    }
    let rig = synthetic::rig_with::<8>(1003, 54, 7);
    let jt = synthetic::joints(54, 7);
    let d8 = dual_quats8(&jt);
    let [a, b] = both::<8, LbsKernel>(&rig, &matrices12(&jt), avx2::lbs);
    assert_eq!(a, b);
    let [a, b] = both::<8, DqsKernel>(&rig, &d8, avx2::dqs);
    assert!(
        apart(&a, &b, 2e-6).1 == 1.0,
        "DQS {:?}",
        apart(&a, &b, 2e-6)
    );
    let t = log::rows(&twists(&jt).unwrap());
    let [a, b] = both::<8, log::LogKernel>(&rig, &t, avx2::log::log);
    assert!(
        apart(&a, &b, 2e-6).1 == 1.0,
        "Log {:?}",
        apart(&a, &b, 2e-6)
    );
    let rows = qlb::rows(&jt.dual_quats, rig.centres());
    let [a, b] = both::<8, qlb::QlbKernel>(&rig, &rows, avx2::qlb::qlb);
    assert!(
        apart(&a, &b, 4e-6).1 == 1.0,
        "QLB {:?}",
        apart(&a, &b, 4e-6)
    );
    let [a, b] = both::<8, dib::DibKernel>(&rig, &d8, avx2::dib::dib);
    let (most, within) = apart(&a, &b, 2e-6);
    assert!(within >= 0.99 && most < 1e-4, "DIB {most} {within}");
    // SBS: the SIMD kernel against the scalar one about the same cluster centres.
    let cl = clusters(&rig);
    let centres = cl.centres(&jt.dual_quats, rig.centres(), false);
    let padded = qlb::padded(&centres);
    let mut o = vec![[f32::NAN; 6]; 1003];
    let table = Antipodes::new(&rows, 1003);
    // SAFETY: as in `both`, and every cluster index is below `padded.len()`.
    let done = unsafe {
        avx2::qlb::sbs(
            &rig.vertices,
            &rows,
            &table,
            cl.of_vertex(),
            &padded,
            &mut o,
        )
    };
    assert_eq!(done, 1000);
    let want: Vec<Out> = rig.vertices[..done]
        .iter()
        .zip(cl.of_vertex())
        .map(|(v, c)| {
            let c = centres[*c as usize];
            qlb::about(v, &qlb::blend(v, &rows), [c.x, c.y, c.z])
        })
        .collect();
    let (most, within) = apart(&o[..done], &want, 4e-6);
    assert!(within == 1.0, "SBS {most}");
}
