//! DIB skinning (`super::super::dib`) eight vertices at a time with AVX2 and FMA: the DIB
//! algorithm of Kavan et al. 2006 (§4, the box "DIB"), one vertex per lane. Each vertex's
//! K (4 or 8) joint dual quaternions are transposed into lanes (slots of weight 0 in all
//! eight vertices skipped at the end); the start is DLB against the pivot (the first of the
//! heaviest influences); then `b̂ ← b̂ exp(Σ wᵢ log(b̂* q̂ᵢ))`, normalized, in all eight
//! lanes until every lane has stopped by the scalar rule (the update's norm below
//! [`DIB_PRECISION`], or no longer shrinking within 100× of it, or not finite: a lane that
//! stops keeps its blend), at most [`DIB_UPDATES`] times. The last step is DQS's transform.
//!
//! No trigonometric calls. For `r̂ = b̂* q̂ᵢ` taken to `w ≥ 0`, with `r0 = (w, a)`,
//! `rε = (wε, b)`, `n = ‖a‖`, `s = n²` (eq. 2 and the library's `DualQuat::log`):
//!
//! ```text
//! log r̂ = [½ ln‖r0‖², h a] + ε [r0·rε / ‖r0‖², h b + a (2 ∂h/∂s a·b − wε / ‖r0‖²)],
//! h = atan2(n, w) / n
//! ```
//!
//! The angle is reduced to `|t| ≤ tan(π/8)` and summed by the series
//! `Q(z) = atan(√z)/√z = Σ (−1)ᵏ zᵏ/(2k+1)`, z = t² ≤ 0.172, ten terms to 1e-9:
//!
//! ```text
//! n ≤ tan(π/8) w:   t = n/w,             h = Q(t²)/w,  ∂h/∂s = −G(t²)/(2w³)
//! n ≥ w/tan(π/8):   t = w/n,             θ = π/2 − t Q(t²)
//! between:          t = (n − w)/(n + w), θ = π/4 + t Q(t²)
//! ```
//!
//! with `G(z) = Σ (−1)ᵏ 2(k+1)/(2k+3) zᵏ` (the library's series) and, in the last two rows
//! (n > 0.38 ‖r0‖, no cancellation), `h = θ/n`, `∂h/∂s = (w n/‖r0‖² − θ)/(2 n s)`. The
//! exponential's `cos √s`, `sinc √s` and `d sinc √s / ds` are Taylor series in `s = ‖a‖²`
//! for the update's `a`, truncated below 1e-8 at `s = (π/2)²` (a convex blend of
//! half-angles in [0, π/2] stays in it). Two shortcuts, both exact after the normalization
//! that follows, which only the update's norm sees: the exponential's scalar factor `e^ŵ`
//! (a positive dual number, which normalizing removes) is left out, and `½ ln‖r0‖²` is taken
//! as `½ (‖r0‖² − 1)` (r̂ is a product of unit dual quaternions: off by under 1e-14).

use super::super::lane::dqmul;
use super::super::{Out, Vertex};
use super::{
    dot, eight, horner, load_head, store_rows, taylor, transform, transpose4_halves, transpose8,
};
use crate::skinning::{DIB_PRECISION, DIB_UPDATES};
use chasles::blend::STALL_FACTOR;
use std::arch::x86_64::*;

/// A dual quaternion in each lane: w, x, y, z, wε, xε, yε, zε.
type Dq = [__m256; 8];

/// `tan(π/8) = √2 − 1`: where the angle reductions change.
const TAN_PI_8: f32 = 0.414_213_57;
/// `Q(z) = atan(√z)/√z`: `(−1)ᵏ/(2k+1)`; the next term is below 1e-9 at `z = tan²(π/8)`.
const Q: [f32; 10] = series(0);
/// `G(z) = (atan √z − √z/(1+z))/z^{3/2}`: `(−1)ᵏ 2(k+1)/(2k+3)`; next term below 4e-9.
const G: [f32; 11] = series(1);
/// `cos √s = Σ (−1)ᵏ sᵏ/(2k)!`: next term below 7e-9 at `s = (π/2)²`.
const COS: [f32; 7] = taylor(0);
/// `sinc √s = Σ (−1)ᵏ sᵏ/(2k+1)!`: next term below 5e-10 at `s = (π/2)²`.
const SINC: [f32; 7] = taylor(1);
/// `d sinc √s / ds`, the derivative of [`SINC`]'s series term by term (one term fewer).
const D_SINC: [f32; 6] = derivative(SINC);

/// The alternating coefficients `(−1)ᵏ cₖ` of [`Q`] (`g = 0`: `cₖ = 1/(2k+1)`) and of
/// [`G`] (`g = 1`: `cₖ = 2(k+1)/(2k+3)`).
const fn series<const N: usize>(g: u32) -> [f32; N] {
    let mut out = [0f32; N];
    let mut k = 0;
    while k < N {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        let kf = k as f64;
        let c = if g == 0 {
            1.0 / (2.0 * kf + 1.0)
        } else {
            2.0 * (kf + 1.0) / (2.0 * kf + 3.0)
        };
        out[k] = (sign * c) as f32;
        k += 1;
    }
    out
}

/// The coefficients of the derivative of `Σ cₖ sᵏ`: `(k + 1) cₖ₊₁`.
const fn derivative<const N: usize, const M: usize>(c: [f32; N]) -> [f32; M] {
    let mut out = [0f32; M];
    let mut k = 0;
    while k < M {
        out[k] = (k + 1) as f32 * c[k + 1];
        k += 1;
    }
    out
}

/// `x` in every lane.
#[inline]
#[target_feature(enable = "avx2,fma")]
fn set(x: f32) -> __m256 {
    _mm256_set1_ps(x)
}

/// The unit dual quaternion of `q` (real part to unit length, dual part made orthogonal
/// to it), as `DualQuat::normalize`.
#[inline]
#[target_feature(enable = "avx2,fma")]
fn normalize(q: &Dq) -> Dq {
    let inv = _mm256_div_ps(set(1.0), _mm256_sqrt_ps(dot(&q[..4], &q[..4])));
    let u: Dq = eight(|c| _mm256_mul_ps(q[c], inv));
    let along = dot(&u[..4], &u[4..]);
    eight(|c| {
        if c < 4 {
            u[c]
        } else {
            _mm256_fnmadd_ps(u[c - 4], along, u[c])
        }
    })
}

/// `log r̂` of the module docs, for `r̂` or `−r̂`, whichever has `w ≥ 0`.
#[inline]
#[target_feature(enable = "avx2,fma")]
fn log(r: &Dq) -> Dq {
    let (mul, add, sub, div) = (_mm256_mul_ps, _mm256_add_ps, _mm256_sub_ps, _mm256_div_ps);
    let (fma, fms, blend) = (_mm256_fmadd_ps, _mm256_fmsub_ps, _mm256_blendv_ps);
    let sign = _mm256_and_ps(r[0], set(-0.0));
    let r: Dq = eight(|c| _mm256_xor_ps(r[c], sign));
    let (w, wd) = (r[0], r[4]);
    let s = dot(&r[1..4], &r[1..4]);
    let ab = dot(&r[1..4], &r[5..8]);
    let n2 = fma(w, w, s);
    let inv_n2 = div(set(1.0), n2);
    let n = _mm256_sqrt_ps(s);
    let near = _mm256_cmp_ps::<_CMP_LE_OQ>(n, mul(set(TAN_PI_8), w));
    let far = _mm256_cmp_ps::<_CMP_LT_OQ>(w, mul(set(TAN_PI_8), n));
    let num = blend(blend(sub(n, w), w, far), n, near);
    let den = blend(blend(add(n, w), n, far), w, near);
    let t = div(num, den);
    let z = mul(t, t);
    let q = horner(&Q, z);
    let offset = blend(
        blend(
            set(std::f32::consts::FRAC_PI_4),
            set(std::f32::consts::FRAC_PI_2),
            far,
        ),
        _mm256_setzero_ps(),
        near,
    );
    let theta = fma(_mm256_xor_ps(t, _mm256_and_ps(far, set(-0.0))), q, offset);
    let h = div(blend(theta, q, near), blend(n, w, near));
    let h_s = div(
        blend(
            fms(mul(w, n), inv_n2, theta),
            sub(_mm256_setzero_ps(), horner(&G, z)),
            near,
        ),
        blend(mul(add(n, n), s), mul(add(w, w), mul(w, w)), near),
    );
    // ∂h = ∂h/∂s · 2 a·b − wε / ‖r0‖².
    let h_du = fms(add(h_s, h_s), ab, mul(inv_n2, wd));
    let ln = mul(set(0.5), sub(n2, set(1.0)));
    let ln_du = mul(fma(w, wd, ab), inv_n2);
    eight(|c| match c {
        0 => ln,
        1..=3 => mul(r[c], h),
        4 => ln_du,
        _ => fma(r[c], h, mul(r[c - 4], h_du)),
    })
}

/// `exp x̂` of a dual quaternion's vector parts (`a + ε b`), its scalar factor `e^ŵ` left out
/// (see the module docs): `[cos √s, k a] + ε [−k a·b, k b + 2 ∂k/∂s a·b a]`, `k = sinc √s`.
#[inline]
#[target_feature(enable = "avx2,fma")]
fn exp(x: &Dq) -> Dq {
    let s = dot(&x[1..4], &x[1..4]);
    let ab = dot(&x[1..4], &x[5..8]);
    let (k, cos) = (horner(&SINC, s), horner(&COS, s));
    let k_du = _mm256_mul_ps(_mm256_add_ps(ab, ab), horner(&D_SINC, s));
    eight(|c| match c {
        0 => cos,
        1..=3 => _mm256_mul_ps(k, x[c]),
        4 => _mm256_sub_ps(_mm256_setzero_ps(), _mm256_mul_ps(k, ab)),
        _ => _mm256_fmadd_ps(k, x[c], _mm256_mul_ps(k_du, x[c - 4])),
    })
}

/// Whether each lane's iteration goes on (`keep_going` of the library): the update's
/// `norm` is finite, not below the precision, and not stuck (no smaller than the `last`
/// while within `STALL_FACTOR` × the precision).
#[inline]
#[target_feature(enable = "avx2,fma")]
fn keep_going(norm: __m256, last: __m256) -> __m256 {
    let above = _mm256_cmp_ps::<_CMP_GE_OQ>(norm, set(DIB_PRECISION));
    let finite = _mm256_cmp_ps::<_CMP_LT_OQ>(norm, set(f32::INFINITY));
    let stuck = _mm256_and_ps(
        _mm256_cmp_ps::<_CMP_GE_OQ>(norm, last),
        _mm256_cmp_ps::<_CMP_LT_OQ>(norm, set(DIB_PRECISION * STALL_FACTOR as f32)),
    );
    _mm256_andnot_ps(stuck, _mm256_and_ps(above, finite))
}

/// DIB for the first `v.len() / 8 * 8` vertices with the joints' dual quaternions as
/// `[w, x, y, z, wε, xε, yε, zε]`; returns how many were done. Influences of weight 0 are
/// left out (their joints may be anything), the others' weights scaled to sum to 1 as the
/// scalar kernel does.
///
/// # Safety
/// The processor must have AVX2 and FMA, K must be 4 or 8, every joint index in `v` must be below
/// `d.len()`, and `o.len() >= v.len()`.
#[target_feature(enable = "avx2,fma")]
pub unsafe fn dib<const K: usize>(v: &[Vertex<K>], d: &[[f32; 8]], _: &(), o: &mut [Out]) -> usize {
    unsafe {
        let db = d.as_ptr() as *const f32;
        let zero = _mm256_setzero_ps();
        let identity: Dq = eight(|c| if c == 0 { set(1.0) } else { zero });
        let blocks = v.len() / 8;
        for blk in 0..blocks {
            let i = blk * 8;
            let [px, py, pz, nx, ny, nz, _, _] = load_head(v, i);
            let vs = eight(|l| v.get_unchecked(i + l));
            // Weights in lanes (vertex l in lane l), four slots at a time; the positive ones
            // scaled to sum to 1, in the scalar kernel's order.
            let mut raw = [zero; K];
            for g in 0..K / 4 {
                let w = |l: usize| _mm_loadu_ps(vs[l].w.as_ptr().add(4 * g));
                let t = transpose4_halves([0, 1, 2, 3].map(|l| _mm256_set_m128(w(l + 4), w(l))));
                raw[4 * g..4 * g + 4].copy_from_slice(&t);
            }
            let used = raw.map(|w| _mm256_cmp_ps::<_CMP_GT_OQ>(w, zero));
            let mut wp = [zero; K];
            let mut sum = zero;
            for k in 0..K {
                wp[k] = _mm256_and_ps(raw[k], used[k]);
                sum = _mm256_add_ps(sum, wp[k]);
            }
            let w = wp.map(|x| _mm256_div_ps(x, sum));
            // Trailing slots of weight 0 in all eight vertices (neighbours in a mesh tend to
            // have as many influences) are skipped: their terms would be exact zeros.
            let slots = (0..K)
                .rev()
                .find(|&k| _mm256_movemask_ps(used[k]) != 0)
                .map_or(0, |k| k + 1);
            // Joints in lanes; unused ones replaced by the identity.
            let mut q = [identity; K];
            for k in 0..slots {
                let t = transpose8(eight(|l| {
                    _mm256_loadu_ps(db.add(usize::from(vs[l].j[k]) * 8))
                }));
                q[k] = eight(|c| _mm256_blendv_ps(identity[c], t[c], used[k]));
            }
            // DLB against the pivot: the first of the heaviest (slot 0 in a `FastRig::new`).
            let (mut pivot, mut heaviest) = (q[0], w[0]);
            for k in 1..slots {
                let more = _mm256_cmp_ps::<_CMP_GT_OQ>(w[k], heaviest);
                pivot = eight(|c| _mm256_blendv_ps(pivot[c], q[k][c], more));
                heaviest = _mm256_blendv_ps(heaviest, w[k], more);
            }
            let mut sum = [zero; 8];
            for k in 0..slots {
                let flip = _mm256_cmp_ps::<_CMP_LT_OQ>(dot(&q[k][..4], &pivot[..4]), zero);
                let wk = _mm256_xor_ps(w[k], _mm256_and_ps(flip, set(-0.0)));
                sum = eight(|c| _mm256_fmadd_ps(wk, q[k][c], sum[c]));
            }
            let mut b = normalize(&sum);
            let mut last = set(f32::INFINITY);
            let mut active = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
            for _ in 0..DIB_UPDATES {
                let conj: Dq = eight(|c| match c {
                    0 | 4 => b[c],
                    _ => _mm256_xor_ps(b[c], set(-0.0)),
                });
                let mut x = [zero; 8];
                for k in 0..slots {
                    let l = log(&dqmul(&conj, &q[k]));
                    x = eight(|c| _mm256_fmadd_ps(w[k], l[c], x[c]));
                }
                let norm = _mm256_sqrt_ps(dot(&x, &x));
                active = _mm256_and_ps(active, keep_going(norm, last));
                if _mm256_movemask_ps(active) == 0 {
                    break;
                }
                last = norm;
                let next = normalize(&dqmul(&b, &exp(&x)));
                b = eight(|c| _mm256_blendv_ps(b[c], next[c], active));
            }
            store_rows(o, i, transform(b, [px, py, pz], [nx, ny, nz]));
        }
        blocks * 8
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::{simd, Kernel};
    use crate::synthetic;
    use chasles::{DualQuat, Quat, Vec3};

    #[test]
    fn the_series_are_the_closed_forms() {
        let sum = super::super::sum64;
        for i in 0..=1000 {
            let f = f64::from(i) / 1000.0;
            // Q and G up to tan²(π/8).
            let z = f * (2f64.sqrt() - 1.0).powi(2);
            let r = z.sqrt();
            let (q, g) = if z == 0.0 {
                (1.0, 2.0 / 3.0)
            } else {
                (r.atan() / r, (r.atan() - r / (1.0 + z)) / (z * r))
            };
            assert!((sum(&Q, z) - q).abs() < 2e-8, "Q({z})");
            // G's closed form loses digits to cancellation near 0.
            let tol = if z < 0.01 { 1e-5 } else { 5e-8 };
            assert!(
                (sum(&G, z) - g).abs() < tol,
                "G({z}): {} vs {g}",
                sum(&G, z)
            );
            // cos √s, sinc √s and its derivative up to s = (π/2)².
            let x = f * std::f64::consts::FRAC_PI_2;
            let s = x * x;
            assert!((sum(&COS, s) - x.cos()).abs() < 5e-8, "cos {x}");
            if x > 0.1 {
                assert!((sum(&SINC, s) - x.sin() / x).abs() < 5e-8, "sinc {x}");
                let d = (x.cos() - x.sin() / x) / (2.0 * s);
                assert!((sum(&D_SINC, s) - d).abs() < 5e-8, "d sinc {x}");
            }
        }
    }

    /// Joints of every angle (w < 0 included: the DLB's antipodality and the logarithm's
    /// hemisphere both matter), translations up to 2.
    fn joints(n: usize) -> Vec<[f32; 8]> {
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
    fn compare(rig: &crate::fast::FastRig<4>, d: &[[f32; 8]]) -> Vec<(f64, f64, f32)> {
        let n = rig.vertices().len();
        let mut out = vec![[f32::NAN; 6]; n];
        // SAFETY: AVX2 and FMA are present (`simd`), the rig's joint indices are below
        // d.len() (checked by its constructor against the same count), `out` is as long as
        // the vertices.
        let done = unsafe { dib(rig.vertices(), d, &(), &mut out) };
        assert_eq!(done, n / 8 * 8);
        let each = |(v, o): (&Vertex<4>, &Out)| {
            let want = <crate::fast::dib::DibKernel as Kernel<4>>::vertex(v, d);
            let apart = crate::fast::max_diff(o, &want);
            let used = (0..4).filter(|&k| v.w[k] > 0.0);
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

    #[test]
    fn the_simd_kernel_is_the_scalar_one_at_every_angle() {
        if !simd(4) {
            eprintln!("no AVX2+FMA here: nothing to compare");
            return;
        }
        let rig = synthetic::rig(4000, 54, 9);
        let reach: Vec<f64> = rig.vertices().iter().map(|v| reach(v.p)).collect();
        // Joints within 60° of the identity, as in a pose: both kernels end within the
        // stopping rule's reach of the exact blend, and mostly agree to rounding (they
        // part where an update's norm falls on either side of the precision).
        let r = compare(&rig, &crate::fast::dual_quats8(&synthetic::joints(54, 3)));
        for (k, (simd, scalar, _)) in r.iter().enumerate() {
            assert!(
                *simd <= reach[k] && *scalar <= reach[k],
                "{k}: {r:?}",
                r = r[k]
            );
        }
        let close = r.iter().filter(|x| x.2 <= 2e-6).count();
        eprintln!("{close} {}", r.len());
        assert!(close * 100 >= r.len() * 99, "{close} of {}", r.len());
        // Every angle: blends so ill-conditioned that f32 DIB can end 1e-4 from the exact
        // one on either path; the SIMD kernel is no farther than the scalar one and reach.
        let r = compare(&rig, &joints(54));
        let close = r.iter().filter(|x| x.2 <= 2e-6).count();
        eprintln!("{close} {}", r.len());
        for (k, (simd, scalar, _)) in r.iter().enumerate() {
            assert!(*simd <= scalar + reach[k], "{k}: {r:?}", r = r[k]);
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
            unsafe { dib(rig.vertices(), d, &(), &mut out) };
            out
        };
        let want = run(&d);
        // Slot 3 is skipped in every block: the same numbers as the scalar kernel.
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
