//! Log skinning (`super::super::log`) eight vertices at a time with AVX2 and FMA. Each
//! vertex's K twists `(ω, v)` are whole-register loads blended in one register (no
//! signs: twists are blended linearly), eight blends are transposed into lanes, and
//! `exp(ω, v)` is applied lane-parallel without trigonometric calls: its coefficients
//!
//! ```text
//! A = sin θ / θ,  B = (1 − cos θ) / θ²,  C = (θ − sin θ) / θ³
//! ```
//!
//! are even entire functions of θ, summed as their Taylor series in θ² (Horner, FMA) to a
//! truncation error below 2e-8 for θ ≤ π (a blend of twists with θ ≤ π, the logarithm's
//! range, has θ ≤ π). Then `p' = p + v + ω × (A p + B v + ω × (B p + C v))` (= R p + V v) and
//! `n' = n + ω × (A n + B ω × n)`, the library's `exp_twist` regrouped: the lane algebra's
//! `exp_twist` (which the scalar kernel runs), its steps written out here in lanes with the
//! algebra's `cross` and `horner` — the generic `exp_twist` inlined here ran 6–9 % slower
//! (measured side by side with `examples/best_of`), so this kernel keeps its own order.
//!
//! Each turn of the loop blends the next block (its loads, blend and transpose: twelve
//! registers of lanes carried into the next turn) before it moves this one, as DQS's does
//! (`super`'s module docs): the series' three chains of Horner steps, some forty cycles
//! each, run while the next block's loads come in. The job alone, one core, best of 15, the
//! builds in turn three times (2026-12-05), ns a vertex: 3.70–3.71 → 2.92–3.01 at 2·10⁴
//! vertices and 4.01–4.20 → 3.39–3.54 at 2·10⁵; with AVX2's sixteen registers alone
//! 3.74–3.86 → 3.14–3.25 and 4.27–4.31 → 3.77–3.90; with eight influences (5·10⁴
//! vertices, the AVX2 build) 5.60–5.76 → 5.04–5.19.

use super::super::dest::Dest;
use super::super::lane::{cross, horner, EXP_A as A, EXP_B as B, EXP_C as C};
use super::{
    blocks_ahead, by_layout, by_target, eight, joint_rows, load_head, store_rows, transpose8, Store,
};
use crate::fast::Vertex;
use std::arch::x86_64::*;

/// One vertex's blended twist `Σ wₖ (ωₖ, vₖ)` in one register (`[ω, v, 0, 0]`).
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn blend<const K: usize>(vx: &Vertex<K>, tb: *const f32) -> __m256 {
    unsafe {
        // All K loads first: interleaved with the products, this ran 8 % slower.
        let t = joint_rows(&vx.j, tb);
        let mut b = _mm256_mul_ps(_mm256_broadcast_ss(&vx.w[0]), t[0]);
        // By index: zipped iterators over the arrays compiled to slower code (7 %).
        #[allow(clippy::needless_range_loop)]
        for k in 1..K {
            b = _mm256_fmadd_ps(_mm256_broadcast_ss(&vx.w[k]), t[k], b);
        }
        b
    }
}

/// Log skinning for the first `v.len() / 8 * 8` vertices with the joints' twists as
/// `[ω, v, 0, 0]`; returns how many were done.
///
/// # Safety
/// The processor must have AVX2 and FMA, K must be 4 or 8, every joint index in `v` must be below
/// `t.len()`, and `o.len() >= v.len()`; with `stream`, `o` must be packed and
/// 32-byte aligned.
#[target_feature(enable = "avx2,fma")]
pub unsafe fn log<const K: usize>(
    v: &[Vertex<K>],
    t: &[[f32; 8]],
    _: &(),
    o: Dest<'_>,
    stream: bool,
) -> usize {
    unsafe {
        // Eight influences stay on the AVX2 build: with 32 registers that loop ran slower
        // (2.5·10⁴ vertices, one core: 172–182 → 146–162 M vertices/s), four's faster.
        if K == 8 {
            by_layout!(o, S => log_blocks::<K, S>(v, t, o, stream))
        } else {
            by_target!(o, S => log_blocks::<K, S>(v, t, o, stream))
        }
    }
}

/// [`log`]'s loop for the layout `S`.
///
/// # Safety
/// Only from AVX2+FMA code (`by_target!`'s builds, each its own copy, or `by_layout!` in
/// an AVX2 function), with the preconditions of the kernel that calls it.
#[inline(always)]
unsafe fn log_blocks<const K: usize, S: Store>(
    v: &[Vertex<K>],
    t: &[[f32; 8]],
    mut o: Dest<'_>,
    stream: bool,
) -> usize {
    chasles::frame::align_frame();
    unsafe {
        let tb = t.as_ptr() as *const f32;
        // The next block blended before this one is moved (the series' chains of Horner
        // steps run while its loads come in). Its first steps are DQS's; a helper shared
        // with DQS, which carried the transpose's two unused lanes into the next turn, ran
        // Log 3.48–3.53 → 3.52–3.64 ns a vertex at 2·10⁵ (four runs each in turn), so each
        // keeps its own.
        blocks_ahead(
            v.len() / 8,
            true,
            #[inline(always)]
            |i| {
                let [px, py, pz, nx, ny, nz, _, _] = load_head(v, i);
                let [wx, wy, wz, vx_, vy, vz, _, _] =
                    transpose8(eight(|l| blend(v.get_unchecked(i + l), tb)));
                ([wx, wy, wz, vx_, vy, vz], [px, py, pz, nx, ny, nz])
            },
            #[inline(always)]
            |i, ([wx, wy, wz, vx_, vy, vz], [px, py, pz, nx, ny, nz])| {
                let mul = |a, b| _mm256_mul_ps(a, b);
                let add = |a, b| _mm256_add_ps(a, b);
                let fma = |a, b, c| _mm256_fmadd_ps(a, b, c);
                let s = fma(wz, wz, fma(wy, wy, mul(wx, wx)));
                let (ca, cb, cc) = (horner(&A, s), horner(&B, s), horner(&C, s));
                let w = [wx, wy, wz];
                // Component c of ω × x.
                let cross = |x: [__m256; 3], c: usize| cross(w, x, c);
                let (p, n, t) = ([px, py, pz], [nx, ny, nz], [vx_, vy, vz]);
                // u = B p + C v; e = A p + B v + ω × u; p' = p + v + ω × e (each written out: no
                // array maps, which can stay calls).
                let u = |c: usize| fma(cb, p[c], mul(cc, t[c]));
                let u = [u(0), u(1), u(2)];
                let e = |c: usize| add(fma(ca, p[c], mul(cb, t[c])), cross(u, c));
                let e = [e(0), e(1), e(2)];
                let q = |c: usize| add(add(p[c], t[c]), cross(e, c));
                let q = [q(0), q(1), q(2)];
                // n' = n + ω × (A n + B ω × n).
                let f = |c: usize| fma(ca, n[c], mul(cb, cross(n, c)));
                let f = [f(0), f(1), f(2)];
                let m = |c: usize| add(n[c], cross(f, c));
                let m = [m(0), m(1), m(2)];
                store_rows::<S>(&mut o, i, [q[0], q[1], q[2], m[0], m[1], m[2]], stream);
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic;

    #[test]
    fn the_series_are_the_closed_forms_up_to_the_half_turn() {
        let sum = super::super::sum64;
        for i in 0..=1000 {
            let t = std::f64::consts::PI * f64::from(i) / 1000.0;
            let s = t * t;
            let (sn, cs) = t.sin_cos();
            let want = if t == 0.0 {
                [1.0, 0.5, 1.0 / 6.0]
            } else {
                [sn / t, (1.0 - cs) / s, (t - sn) / (s * t)]
            };
            let got = [sum(&A, s), sum(&B, s), sum(&C, s)];
            for k in 0..3 {
                // Closed forms lose digits near 0 (cancellation), the series nowhere.
                let tol = if t < 0.1 { 1e-6 } else { 5e-8 };
                assert!(
                    (got[k] - want[k]).abs() < tol,
                    "θ = {t}: {got:?} vs {want:?}"
                );
            }
        }
    }

    #[test]
    fn the_simd_kernel_is_the_scalar_one_up_to_the_half_turn() {
        if !crate::fast::simd(4) {
            eprintln!("no AVX2+FMA here: nothing to compare");
            return;
        }
        let rig = synthetic::rig(1000, 54, 3);
        // Twists of every angle up to π (joint j turns by π j / 53 about a varying axis).
        let t: Vec<[f32; 8]> = (0..54)
            .map(|j| {
                let a = std::f32::consts::PI * j as f32 / 53.0;
                let axis = chasles::Vec3::new(1.0, j as f32 * 0.3 - 5.0, 2.0)
                    .normalize()
                    .unwrap();
                let w = axis * a;
                [w.x, w.y, w.z, 0.5, -1.0, 0.25 * j as f32 / 53.0, 0.0, 0.0]
            })
            .collect();
        let mut out = vec![[f32::NAN; 6]; 1000];
        // SAFETY: AVX2 and FMA are present (`simd`), the synthetic rig's joint indices are
        // below 54 = t.len(), `out` is as long as the vertices.
        let done = unsafe { log(rig.vertices(), &t, &(), Dest::packed(&mut out), false) };
        assert_eq!(done, 1000);
        for (v, o) in rig.vertices().iter().zip(&out) {
            let want = <crate::fast::log::LogKernel as crate::fast::Kernel<4>>::vertex(v, &t);
            for k in 0..6 {
                assert!((o[k] - want[k]).abs() < 2e-6, "{o:?} vs {want:?}");
            }
        }
    }
}
