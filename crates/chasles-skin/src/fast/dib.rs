//! The fast path for DIB skinning (Kavan et al. 2006, §4, the DIB algorithm box, per vertex):
//! the DLB start, then `b̂ ← b̂ exp(Σ wᵢ log(b̂* q̂ᵢ))` until the update is below
//! [`DIB_PRECISION`] or [`DIB_UPDATES`] were made, with rayon over chunks of vertices. With
//! AVX2+FMA (4 or 8 influences), eight vertices at a time (`avx2::dib` runs the lane
//! algebra's `lane::dib` on `__m256`; with AVX-512F sixteen, `avx512` on `__m512`, to the
//! same bits: the algorithm branch-free in lanes, the logarithm and
//! exponential by series, and a second-order step to the same fixed point under the same
//! stopping rule, which needs one update where the paper's step needs two, the pass that
//! shows it converged taking the update by one product and no logarithm; the two kernels
//! both end within the stopping rule's reach of the exact blend, the SIMD one nearer
//! it; a vertex of one influence takes no update there, and one of two takes ScLERP in
//! closed form — Lemma 3, as a weighted sum of its two joints — to rounding of the exact
//! blend). Elsewhere, and for the last few
//! vertices, each vertex's influences are gathered on the stack and blended by the library's
//! allocation-free [`dib_convex`]: the same calls in the same order as the reference path
//! ([`crate::skinning`]), so equal numbers (a test checks it on every model and clip). A block
//! pays for the iteration wherever one of its vertices has three influences or more, so on
//! a rig whose vertices of many influences are strewn along the mesh the SIMD kernels run
//! on a copy of the vertices grouped by influence count, made by the first job, to the
//! same bits in the rig's order (`grouped`; a rig reordered once by
//! [`crate::vertex_order`] needs no copy).

use super::{out_of, run, FastRig, Kernel, Out, Vertex};
use crate::error::Result;
use crate::skinning::{dual_quat_vertex, DIB_PRECISION, DIB_UPDATES};
use chasles::blend::dib::dib_convex;
use chasles::{DualQuat, Vec3};

/// A vertex's influences of positive weight, in order, with their weights scaled to sum to 1
/// the way `convex_weights` does (the same sum, the same division: equal bits), on the
/// stack: the inputs of the library's allocation-free [`dib_convex`]. Returns how many.
#[inline(always)]
fn gather<const K: usize>(
    v: &Vertex<K>,
    joints: &[[f32; 8]],
) -> ([DualQuat<f32>; K], [f32; K], usize) {
    let (mut q, mut w, mut n) = ([DualQuat::identity(); K], [0f32; K], 0);
    for k in 0..K {
        if v.w[k] > 0.0 {
            q[n] = DualQuat::from_array(joints[usize::from(v.j[k])]);
            w[n] = v.w[k];
            n += 1;
        }
    }
    let mut sum = 0f32;
    w[..n].iter().for_each(|x| sum += *x);
    w[..n].iter_mut().for_each(|x| *x /= sum);
    (q, w, n)
}

pub(super) struct DibKernel;
impl<const K: usize> Kernel<K> for DibKernel {
    type Joint = [f32; 8];
    type Table = ();
    fn table(_: &[[f32; 8]], _: usize) {}
    #[cfg(target_arch = "x86_64")]
    const AVX2: Option<super::SimdKernel<K, [f32; 8], ()>> = Some(super::avx2::dib::dib::<K>);
    const GROUPED: bool = true;
    #[inline(always)]
    fn vertex(v: &Vertex<K>, joints: &[[f32; 8]]) -> Out {
        let (q, w, n) = gather(v, joints);
        match dib_convex(&q[..n], &w[..n], DIB_PRECISION, DIB_UPDATES) {
            Ok((b, _)) => {
                let (p, n) = dual_quat_vertex(&b, Vec3::from_array(v.p), Vec3::from_array(v.n));
                out_of(p, n)
            }
            // Non-finite joints.
            Err(_) => [f32::NAN; 6],
        }
    }
}

/// DIB skinning into `out` with the joints' unit dual quaternions (one off unit length is
/// normalized first), on all threads when `parallel`. A vertex whose blend fails
/// (non-finite joints) gets NaN; joints a vertex gives weight 0 do not touch it.
pub fn dib<const K: usize>(
    rig: &FastRig<K>,
    d: &[DualQuat<f32>],
    out: &mut [Out],
    parallel: bool,
) -> Result<()> {
    let joints = super::arrays8(d, super::palette::dib_unit);
    run::<K, DibKernel>(rig, &joints, out.into(), parallel)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cylinder::{pose, twisted_cylinder, Motion};
    use crate::{joint_transforms, skin_joints, JointTransforms, Method};
    use chasles::DualQuat;

    /// Joints off unit length (a `JointTransforms` or a palette made by hand) skin as the
    /// unit ones do, on every path into the kernels: the SIMD kernels' logarithm takes
    /// `‖b̂* q̂ᵢ‖` as 1 (`lane::dib`), so they are normalized first; unit joints are taken
    /// bit for bit as they are.
    #[test]
    fn joints_off_unit_length_skin_as_unit_ones() {
        use crate::fast::{Joints, Output, Palette, SkinningJob};
        let rig = crate::synthetic::rig(1000, 54, 7);
        let jt = crate::synthetic::joints(54, 7);
        let n = rig.vertices().len();
        let skin = |d: &[DualQuat<f32>]| {
            let mut out = vec![[0f32; 6]; n];
            dib(&rig, d, &mut out, false).unwrap();
            out
        };
        let job = |palette: Palette| {
            let mut out = vec![[0f32; 6]; n];
            SkinningJob {
                rig: &rig,
                palette: &palette,
                output: Output::Packed(&mut out),
                parallel: false,
            }
            .run()
            .unwrap();
            out
        };
        let by_palette = |d: &[DualQuat<f32>]| {
            let joints = d.iter().map(super::super::palette::unit).collect();
            job(Palette::from_joints(&rig, Joints::Dib(joints)).unwrap())
        };
        let by_transforms = |d: &[DualQuat<f32>]| {
            let jt = JointTransforms {
                dual_quats: d.to_vec(),
                ..jt.clone()
            };
            job(Palette::from_joint_transforms(Method::Dib, &rig, &jt, false).unwrap())
        };
        let want = skin(&jt.dual_quats);
        assert_eq!(by_palette(&jt.dual_quats), want, "unit joints as they are");
        assert_eq!(
            by_transforms(&jt.dual_quats),
            want,
            "unit joints as they are"
        );
        for scale in [2.0f32, 0.5, 1.01] {
            let d: Vec<DualQuat<f32>> = jt.dual_quats.iter().map(|d| *d * scale).collect();
            for (path, got) in [
                ("fast::dib", skin(&d)),
                ("Palette::from_joints", by_palette(&d)),
                ("Palette::from_joint_transforms", by_transforms(&d)),
            ] {
                for (v, (g, w)) in got.iter().zip(&want).enumerate() {
                    for c in 0..6 {
                        let tol = 1e-4 * (1.0 + w[c].abs());
                        assert!(
                            (g[c] - w[c]).abs() <= tol,
                            "{path}, scale {scale}, vertex {v}: {g:?} against {w:?}"
                        );
                    }
                }
            }
        }
    }

    /// The scalar kernel (the fast path without AVX2, and the last few vertices of a chunk)
    /// is the reference path bit for bit: the same calls on the same numbers in order.
    #[test]
    fn the_scalar_kernel_is_the_reference_bit_for_bit() {
        let rig = twisted_cylinder();
        let (four, eight) = (
            super::super::FastRig::<4>::new(&rig).unwrap(),
            super::super::FastRig::<8>::new(&rig).unwrap(),
        );
        for (motion, angle) in [
            (Motion::Twist, 0.0),
            (Motion::Twist, 3.0),
            (Motion::Bend, 2.1),
        ] {
            let jt = joint_transforms(&rig, &pose(&rig, motion, angle)).unwrap();
            let want = skin_joints(&rig, &jt, Method::Dib).unwrap();
            let d = super::super::dual_quats8(&jt);
            for v in 0..want.positions.len() {
                let (p, n) = (want.positions[v], want.normals[v]);
                let want = [p.x, p.y, p.z, n.x, n.y, n.z];
                assert_eq!(DibKernel::vertex(&four.vertices()[v], &d), want, "{v}");
                assert_eq!(DibKernel::vertex(&eight.vertices()[v], &d), want, "{v}");
            }
        }
    }
}
