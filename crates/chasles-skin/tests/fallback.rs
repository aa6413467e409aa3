//! The portable scalar kernels, forced on this machine (`fast::set_simd(false)`): every
//! method through the job agrees with the reference path to 1e-5 as the SIMD kernels do, and
//! LBS with the SIMD kernel to rounding. One test in its own binary, since the
//! switch is process-wide.

use chasles_skin::fast::{set_simd, skin_pose, uses_simd, FastRig};
use chasles_skin::{gltf_load, joint_transforms, skin, Method, Pose};

#[test]
fn the_scalar_fallback_skins_every_method_as_the_reference_does() {
    let m = chasles_models::CESIUM_MAN;
    let rig = gltf_load::load_slice(m.bytes, m.file).unwrap();
    let pose = Pose::animated(&rig, 0, 0.4).unwrap();
    let jt = joint_transforms(&rig, &pose).unwrap();
    let f4 = FastRig::<4>::new(&rig).unwrap();
    let f8 = FastRig::<8>::new(&rig).unwrap();
    let n = f4.vertices().len();
    let size = rig.mesh.positions.iter().fold(1f32, |s, p| s.max(p.norm()));
    let had_simd = uses_simd(4);
    for method in Method::ALL {
        let want = skin(&rig, &pose, method).unwrap();
        let mut simd = vec![[0f32; 6]; n];
        set_simd(true);
        skin_pose(&f4, &jt, method, &mut simd, true).unwrap();
        set_simd(false);
        assert!(!uses_simd(4) && !uses_simd(8));
        let (mut scalar, mut scalar8) = (vec![[0f32; 6]; n], vec![[0f32; 6]; n]);
        skin_pose(&f4, &jt, method, &mut scalar, true).unwrap();
        skin_pose(&f8, &jt, method, &mut scalar8, false).unwrap();
        set_simd(true);
        let pn = want.positions.iter().zip(&want.normals);
        for (v, ((s, s8), (p, nr))) in scalar.iter().zip(&scalar8).zip(pn).enumerate() {
            let (p, nr) = (p.to_array(), nr.to_array());
            for k in 0..3 {
                for (got, what) in [(s, "K = 4"), (s8, "K = 8")] {
                    let m = method.name();
                    assert!(
                        (got[k] - p[k]).abs() <= 1e-5 * size,
                        "{m} {what} vertex {v}"
                    );
                    assert!((got[3 + k] - nr[k]).abs() <= 1e-4, "{m} {what} normal {v}");
                }
            }
        }
        if method == Method::Lbs {
            // The SIMD kernel is the scalar one to rounding (fused multiply-adds).
            for (v, (s, d)) in scalar.iter().zip(&simd).enumerate() {
                for k in 0..6 {
                    let tol = if k < 3 { 2e-6 * size } else { 4e-6 };
                    assert!((s[k] - d[k]).abs() <= tol, "LBS vertex {v}: {s:?} vs {d:?}");
                }
            }
        }
        if !had_simd {
            eprintln!("no AVX2+FMA here: the 'SIMD' run was the scalar kernel too");
        }
    }
    assert_eq!(uses_simd(4), had_simd, "the switch is back");
}
