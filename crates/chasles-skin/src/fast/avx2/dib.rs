//! DIB skinning (`super::super::dib`) eight vertices at a time with AVX2 and FMA: each
//! vertex's K (4 or 8) joint dual quaternions and weights are transposed into lanes (slots
//! of weight 0 in all eight vertices left out at the end, unused ones replaced by the
//! identity), and the lane algebra's branch-free DIB (`lane::dib`, where the series and the
//! stopping rule and the second-order step are) runs on `__m256`, one vertex per lane. The
//! last step is DQS's transform. Where the processor has AVX-512F and VL the whole blocks of
//! sixteen go through the sixteen-vertex kernel (`fast::avx512`, the same lane algebra on
//! `__m512`, the same bits) and only a last block of eight through this one.
//!
//! The blocks take the vertices side by side. A block costs what its costliest lane needs,
//! so on rigs whose vertices of many influences are strewn along the mesh the job runs
//! DIB on a copy of the vertices grouped by influence count, made once a rig
//! (`fast::grouped`). Sorting each window by count inside the kernel instead, every call,
//! was tried and not kept: a per-call counting sort (the counters in one register),
//! gathers by index and scattered stores cost 12–15 % a vertex on sorted input, and on
//! the rigs in their own order CesiumMan got slower and the Fox at most 5–8 % faster,
//! inside the machine's noise (2026-12-03, best of 30 runs each).

use super::super::dest::Dest;
use super::super::lane::dib::{convex, dib as blend};
use super::super::Vertex;
use super::{
    by_layout, eight, load_head, store_rows, transform, transpose4_halves, transpose8, Store,
};
use std::arch::x86_64::*;

/// DIB for the first `v.len() / 8 * 8` vertices with the joints' dual quaternions as
/// `[w, x, y, z, wε, xε, yε, zε]`; returns how many were done. Influences of weight 0 are
/// left out (their joints may be anything), the others' weights scaled to sum to 1 as the
/// scalar kernel does.
///
/// # Safety
/// The processor must have AVX2 and FMA, K must be 4 or 8, every joint index in `v` must be below
/// `d.len()`, and `o.len() >= v.len()`; with `stream`, `o` must be packed and
/// 32-byte aligned.
#[target_feature(enable = "avx2,fma")]
pub unsafe fn dib<const K: usize>(
    v: &[Vertex<K>],
    d: &[[f32; 8]],
    _: &(),
    o: Dest<'_>,
    stream: bool,
) -> usize {
    // SAFETY: as the caller's; `avx512` is true only where the processor has AVX-512F.
    unsafe { dib_with(v, d, o, stream, super::super::avx512()) }
}

/// [`dib`], the whole blocks of sixteen by the AVX-512F kernel (`avx512::dib_blocks`)
/// where `sixteen`, the rest by eight here: each vertex's numbers are the same either way.
///
/// # Safety
/// As for [`dib`]; with `sixteen`, the processor must have AVX-512F.
#[target_feature(enable = "avx2,fma")]
pub(in crate::fast) unsafe fn dib_with<const K: usize>(
    v: &[Vertex<K>],
    d: &[[f32; 8]],
    o: Dest<'_>,
    stream: bool,
    sixteen: bool,
) -> usize {
    unsafe { by_layout!(scattered o, S => dib_blocks::<K, S>(v, d, o, stream, sixteen)) }
}

/// [`dib_with`]'s loop for the layout `S`, a function of its own (each layout's frame its own):
/// the three layouts' loops inlined into [`dib`] ran 2 % slower (best of runs, 10⁵
/// vertices of 4 influences, one core, `examples/dib_influences`: 20.5–20.6 before the
/// layouts, 20.1–20.2 inlined, 20.8 not).
#[inline(never)]
#[target_feature(enable = "avx2,fma")]
unsafe fn dib_blocks<const K: usize, S: Store>(
    v: &[Vertex<K>],
    d: &[[f32; 8]],
    mut o: Dest<'_>,
    stream: bool,
    sixteen: bool,
) -> usize {
    chasles::frame::align_frame();
    unsafe {
        // Sixteen at a time where asked (the same bits), the last eight here.
        // SAFETY: `sixteen` only where the processor has AVX-512F (the caller's contract);
        // the rest is this function's own.
        let first = if sixteen {
            super::super::avx512::dib_blocks::<K, S>(v, d, &mut o, stream) / 8
        } else {
            0
        };
        let db = d.as_ptr() as *const f32;
        let zero = _mm256_setzero_ps();
        let identity = eight(|c| if c == 0 { _mm256_set1_ps(1.0) } else { zero });
        let blocks = v.len() / 8;
        for blk in first..blocks {
            let i = blk * 8;
            let [px, py, pz, nx, ny, nz, _, _] = load_head(v, i);
            // The positive weights scaled to sum to 1, in the scalar kernel's order.
            let (w, used, slots) = convex(weights(v, i));
            // Joints in lanes; unused ones replaced by the identity.
            let mut q = [identity; K];
            for k in 0..slots {
                let t = joints(v, db, i, k);
                q[k] = eight(|c| _mm256_blendv_ps(identity[c], t[c], used[k]));
            }
            let b = blend(&q, &w, slots);
            store_rows::<S>(&mut o, i, transform(b, [px, py, pz], [nx, ny, nz]), stream);
        }
        blocks * 8
    }
}

/// The weights of vertices `i … i + 7` in lanes (vertex l in lane l), slot by slot, four
/// slots at a time by 4×4 transposes within halves.
///
/// # Safety
/// `i + 8 <= v.len()`; the processor must have AVX2.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(in crate::fast) unsafe fn weights<const K: usize>(v: &[Vertex<K>], i: usize) -> [__m256; K] {
    unsafe {
        let mut raw = [_mm256_setzero_ps(); K];
        for g in 0..K / 4 {
            let w = |l: usize| _mm_loadu_ps(v.get_unchecked(i + l).w.as_ptr().add(4 * g));
            let t = transpose4_halves([0, 1, 2, 3].map(|l| _mm256_set_m128(w(l + 4), w(l))));
            raw[4 * g..4 * g + 4].copy_from_slice(&t);
        }
        raw
    }
}

/// The dual quaternions of slot `k`'s joints of vertices `i … i + 7` in lanes (component
/// c in register c, vertex l in lane l): eight whole-register loads from the joints `db`
/// and a transpose.
///
/// # Safety
/// `i + 8 <= v.len()`, `k < K`, every joint index of those vertices is one of `db`'s
/// dual quaternions (8 floats each); the processor must have AVX2.
#[inline]
#[target_feature(enable = "avx2,fma")]
pub(in crate::fast) unsafe fn joints<const K: usize>(
    v: &[Vertex<K>],
    db: *const f32,
    i: usize,
    k: usize,
) -> [__m256; 8] {
    unsafe {
        transpose8(eight(|l| {
            let j = usize::from(v.get_unchecked(i + l).j[k]);
            _mm256_loadu_ps(db.add(j * 8))
        }))
    }
}

#[cfg(test)]
pub(in crate::fast) mod tests {
    use super::*;
    use crate::fast::{simd, Kernel, Out};
    use crate::skinning::DIB_PRECISION;
    use crate::synthetic;
    use chasles::{DualQuat, Quat, Vec3};

    /// Joints of every angle (w < 0 included: the DLB's antipodality and the logarithm's
    /// hemisphere both matter), translations up to 2 (the sixteen-vertex kernel's tests
    /// take them too).
    pub(in crate::fast) fn joints(n: usize) -> Vec<[f32; 8]> {
        (0..n)
            .map(|j| {
                let f = j as f32 / n as f32;
                let axis = Vec3::new(1.0, 3.0 * f - 1.0, (7.0 * f).sin());
                let q = Quat::from_axis_angle(axis, 6.2 * f).unwrap();
                let t = Vec3::new(2.0 * f, 1.0 - f, (3.0 * f).cos());
                DualQuat::from_rotation_translation(q, t).to_array()
            })
            .collect()
    }

    /// How far DIB's stopping rule may leave a vertex at `p` from the exact blend: an
    /// update of norm below the precision moves it by at most about `(1 + 2‖p‖) ×` that
    /// (rotation by twice the half-angle about a lever ‖p‖, translation twice the dual
    /// part); twice that again for the rounding and the blend's conditioning.
    fn reach(p: [f32; 3]) -> f64 {
        let lever = Vec3::from_array(p.map(f64::from)).norm();
        2.0 * f64::from(DIB_PRECISION) * (1.0 + 2.0 * lever)
    }

    /// The SIMD kernel on `rig` and `d` against the scalar one and the exact DIB (f64, run
    /// to convergence): per vertex, the distances of the two positions from the exact one,
    /// and how far apart the two outputs are.
    fn compare<const K: usize>(
        rig: &crate::fast::FastRig<K>,
        d: &[[f32; 8]],
    ) -> Vec<(f64, f64, f32)> {
        let n = rig.vertices().len();
        let mut out = vec![[f32::NAN; 6]; n];
        // SAFETY: AVX2 and FMA are present (`simd`), the rig's joint indices are below
        // d.len() (checked by its constructor against the same count), `out` is as long as
        // the vertices.
        let done = unsafe { dib(rig.vertices(), d, &(), Dest::packed(&mut out), false) };
        assert_eq!(done, n / 8 * 8);
        let each = |(v, o): (&Vertex<K>, &Out)| {
            let want = <crate::fast::dib::DibKernel as Kernel<K>>::vertex(v, d);
            let apart = crate::fast::max_diff(o, &want);
            let used = (0..K).filter(|&k| v.w[k] > 0.0);
            let q: Vec<DualQuat<f64>> = used
                .clone()
                .map(|k| DualQuat::from_array(d[usize::from(v.j[k])].map(f64::from)))
                .collect();
            let w: Vec<f64> = used.map(|k| f64::from(v.w[k])).collect();
            let (b, _) = chasles::blend::dib::dib(&q, &w, 1e-12, 200).unwrap();
            let exact = b.transform_point(Vec3::from_array(v.p.map(f64::from)));
            let off =
                |x: &Out| (Vec3::from_array([x[0], x[1], x[2]].map(f64::from)) - exact).norm();
            (off(o), off(&want), apart)
        };
        rig.vertices().iter().zip(&out[..done]).map(each).collect()
    }

    /// The `q`-quantile of `x`.
    fn quantile(x: impl Iterator<Item = f64>, q: f64) -> f64 {
        let mut x: Vec<f64> = x.collect();
        x.sort_by(f64::total_cmp);
        x[((x.len() - 1) as f64 * q) as usize]
    }

    /// The SIMD kernel takes the second-order step (`lane::dib`), the scalar one the
    /// paper's: both end within the stopping rule's reach of the exact blend, and the SIMD
    /// kernel nearer it — its last update leaves less behind — at the median and the 90th
    /// percentile, with 4 and with 8 influences.
    #[test]
    fn the_simd_kernel_ends_as_near_the_exact_blend_as_the_scalar_one_at_every_angle() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: nothing to compare");
            return;
        }
        let four = synthetic::rig(4000, 54, 9);
        let eight = synthetic::rig_with::<8>(2000, 54, 9);
        let poses = crate::fast::dual_quats8(&synthetic::joints(54, 3));
        // Joints within 60° of the identity, as in a pose.
        for (r, p) in [
            (
                compare(&four, &poses),
                four.vertices().iter().map(|v| v.p).collect::<Vec<_>>(),
            ),
            (
                compare(&eight, &poses),
                eight.vertices().iter().map(|v| v.p).collect(),
            ),
        ] {
            for (k, (simd, scalar, _)) in r.iter().enumerate() {
                let reach = reach(p[k]);
                assert!(*simd <= reach && *scalar <= reach, "{k}: {:?}", r[k]);
            }
            for q in [0.5, 0.9] {
                let (simd, scalar) = (
                    quantile(r.iter().map(|x| x.0), q),
                    quantile(r.iter().map(|x| x.1), q),
                );
                assert!(simd <= scalar, "quantile {q}: {simd:e} against {scalar:e}");
            }
        }
        // Every angle: blends so ill-conditioned that f32 DIB can end 1e-4 from the exact
        // one on either path; the SIMD kernel is no farther than the scalar one and reach.
        let r = compare(&four, &joints(54));
        for (k, (simd, scalar, _)) in r.iter().enumerate() {
            let reach = reach(four.vertices()[k].p);
            assert!(*simd <= scalar + reach, "{k}: {r:?}", r = r[k]);
        }
    }

    /// The SIMD kernel on `v` with the joints `d` (whose count bounds `v`'s joint
    /// indices): the outputs of the whole blocks of eight. AVX2 and FMA must be present.
    fn run(v: &[Vertex<4>], d: &[[f32; 8]]) -> Vec<Out> {
        assert!(simd(4), "the SIMD kernel needs AVX2 and FMA");
        assert!(v
            .iter()
            .all(|v| v.j.iter().all(|j| usize::from(*j) < d.len())));
        let mut out = vec![[f32::NAN; 6]; v.len()];
        // SAFETY: AVX2 and FMA are present, the joint indices are below d.len() (both
        // checked above), `out` is as long as the vertices.
        let done = unsafe { dib(v, d, &(), Dest::packed(&mut out), false) };
        out.truncate(done);
        out
    }

    /// `rig` with `count(i)` influences on vertex i (its first slots, the weights scaled
    /// to sum to 1).
    pub(in crate::fast) fn with_counts<const K: usize>(
        rig: &crate::fast::FastRig<K>,
        count: impl Fn(usize) -> usize,
    ) -> crate::fast::FastRig<K> {
        synthetic::with_influences(rig, |i, k| k < count(i))
    }

    /// A vertex's own influence count decides its path (one: DLB's start; two: ScLERP in
    /// closed form, Lemma 3; three or more: the iteration), so it keeps its numbers whatever
    /// its block-mates need: the kernel on the mesh and on the
    /// mesh without its first 1–7 vertices (every block made of other vertices) gives each
    /// vertex the same bits. Influence counts 1–4 mixed in blocks, runs of blocks of one
    /// and two only, and runs of two alone (whose blocks take their ScLERP's two joints from
    /// the first two slots as they are, `lane::dib::sclerp`).
    #[test]
    fn a_vertex_is_skinned_alike_whatever_its_block_mates() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: nothing to compare");
            return;
        }
        let rig = with_counts(&synthetic::rig(1200, 54, 5), |i| {
            let h = (i * 7919) % 13;
            match (i / 40) % 3 {
                0 => 1 + h % 2,
                1 => 1 + h % 4,
                _ => 2,
            }
        });
        let d = crate::fast::dual_quats8(&synthetic::joints(54, 3));
        let whole = run(rig.vertices(), &d);
        for shift in 1..8 {
            let part = run(&rig.vertices()[shift..], &d);
            for (k, o) in part
                .iter()
                .enumerate()
                .filter(|(k, _)| shift + k < whole.len())
            {
                assert_eq!(
                    *o,
                    whole[shift + k],
                    "vertex {}, shifted by {shift}",
                    shift + k
                );
            }
        }
    }

    /// A vertex's influences may sit in any slots, weights of 0 between them (a layout
    /// built by hand need not put them first): it is skinned to the same bits as with them
    /// in the first slots — its counts of one and two (no update; ScLERP in closed form)
    /// are its positive weights' wherever they are.
    #[test]
    fn influences_in_any_slots_are_skinned_as_in_the_first() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: nothing to compare");
            return;
        }
        let compact = with_counts(&synthetic::rig(1200, 54, 5), |i| 1 + (i * 7919) % 3);
        let places: [&[&[usize]]; 3] = [
            &[&[1], &[3], &[2]],
            &[&[0, 2], &[1, 3], &[2, 3], &[0, 3]],
            &[&[0, 2, 3], &[1, 2, 3], &[0, 1, 3]],
        ];
        let scattered: Vec<Vertex<4>> = compact
            .vertices()
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let count = v.w.iter().filter(|w| **w > 0.0).count();
                let at = places[count - 1][(i / 3) % places[count - 1].len()];
                let mut u = Vertex {
                    j: [0; 4],
                    w: [0.0; 4],
                    ..*v
                };
                for (s, &p) in at.iter().enumerate() {
                    (u.j[p], u.w[p]) = (v.j[s], v.w[s]);
                }
                u
            })
            .collect();
        let d = crate::fast::dual_quats8(&synthetic::joints(54, 3));
        let (want, got) = (run(compact.vertices(), &d), run(&scattered, &d));
        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
            assert_eq!(
                g,
                w,
                "vertex {k}: {:?} against {:?}",
                scattered[k],
                compact.vertices()[k]
            );
        }
    }

    /// A vertex of one influence is its joint, and one of two ScLERP in closed form (Lemma
    /// 3): the exact blend to f32's rounding, where the scalar kernel (the library's f32
    /// DIB, the paper's update and the pass that shows it converged) stops within its
    /// rule's reach — at 60° poses and at every angle.
    #[test]
    fn one_or_two_influences_end_at_the_exact_blend_to_rounding() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: nothing to compare");
            return;
        }
        let rig = with_counts(&synthetic::rig(2000, 54, 9), |i| 1 + (i * 31) % 2);
        for d in [
            crate::fast::dual_quats8(&synthetic::joints(54, 3)),
            joints(54),
        ] {
            for (k, (simd, scalar, _)) in compare(&rig, &d).into_iter().enumerate() {
                // f32's rounding at the vertex's lever (2.9e-7 at most when written, where
                // the scalar kernel was up to 1.0e-5 away).
                let lever = 1.0 + Vec3::from_array(rig.vertices()[k].p.map(f64::from)).norm();
                assert!(
                    simd <= 1e-6 * lever,
                    "{k}: {simd:e} (the scalar kernel {scalar:e})"
                );
            }
        }
    }

    #[test]
    fn unused_joints_may_be_anything_and_used_nan_joints_give_nan() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: nothing to check");
            return;
        }
        // Every vertex's last slot: weight 0 on joint 54, which is NaN.
        let rig = synthetic::rig(800, 54, 4);
        let vertices = rig
            .vertices()
            .iter()
            .map(|v| {
                let mut v = *v;
                let s = v.w[0] + v.w[1] + v.w[2];
                v.w = [v.w[0] / s, v.w[1] / s, v.w[2] / s, 0.0];
                v.j[3] = 54;
                v
            })
            .collect();
        let mut centres = rig.centres().to_vec();
        centres.push(Vec3::zero());
        let rig = crate::fast::FastRig::from_vertices(vertices, centres).unwrap();
        let mut d = crate::fast::dual_quats8(&synthetic::joints(55, 2));
        let run = |d: &[[f32; 8]]| {
            let mut out = vec![[f32::NAN; 6]; 800];
            // SAFETY: AVX2 and FMA are present, joint indices are below 55 = d.len(),
            // `out` is as long as the vertices.
            unsafe { dib(rig.vertices(), d, &(), Dest::packed(&mut out), false) };
            out
        };
        let want = run(&d);
        // Slot 3 is left out of every block (a NaN joint there changes nothing, below), and
        // both kernels end within reach of the exact blend.
        for (k, (simd, scalar, _)) in compare(&rig, &d).into_iter().enumerate() {
            let reach = reach(rig.vertices()[k].p);
            assert!(simd <= reach && scalar <= reach, "{k}: {simd} {scalar}");
        }
        d[54] = [f32::NAN; 8];
        assert_eq!(run(&d), want);
        assert!(want.iter().flatten().all(|x| x.is_finite()));
        // A used joint that is NaN: NaN out for the vertices it moves, the others unchanged.
        let j = usize::from(rig.vertices()[0].j[0]);
        d[j][0] = f32::NAN;
        let got = run(&d);
        for (k, v) in rig.vertices().iter().enumerate() {
            if v.j[..3].contains(&(j as u16)) {
                assert!(got[k].iter().all(|x| x.is_nan()), "{k}");
            } else {
                assert_eq!(got[k], want[k], "{k}");
            }
        }
    }
}
