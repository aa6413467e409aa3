//! Four clusters solved at once, one in each lane of AVX2's four f64: a cluster's solve
//! is about 270 instructions one at a time (35 ns), the sums over the joints by SSE2's
//! pairs and the rest scalar; the compiler's own vectorization of a four-lane form
//! shuffled more than it computed, so the lanes are written with intrinsics here.

use super::{pick, solve, Motion, Motions, Num};
use chasles::Vec3;
use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Sub};

/// Four clusters' values of one quantity. Private to this module: its operators run AVX2
/// instructions, and only [`four`] (which requires AVX2) makes one.
#[derive(Clone, Copy)]
struct W(__m256d);

macro_rules! op {
    ($trait:ident, $f:ident, $intrinsic:ident) => {
        impl $trait for W {
            type Output = W;
            #[inline(always)]
            fn $f(self, o: W) -> W {
                // SAFETY: `W` is made only inside `four`, which runs with AVX2.
                W(unsafe { $intrinsic(self.0, o.0) })
            }
        }
    };
}
op!(Add, add, _mm256_add_pd);
op!(Sub, sub, _mm256_sub_pd);
op!(Mul, mul, _mm256_mul_pd);
op!(Div, div, _mm256_div_pd);

impl Num for W {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        // SAFETY: as for the operators.
        W(unsafe { _mm256_set1_pd(x) })
    }
    #[inline(always)]
    fn at_least_one(self) -> Self {
        // n ≥ 0, never NaN: the same as `f64::max(n, 1)`.
        W(unsafe { _mm256_max_pd(self.0, _mm256_set1_pd(1.0)) })
    }
}

/// The four lanes of `x`.
#[inline(always)]
fn lanes(x: W) -> [f64; 4] {
    let mut out = [0f64; 4];
    // SAFETY: as for the operators; `out` holds four f64.
    unsafe { _mm256_storeu_pd(out.as_mut_ptr(), x.0) };
    out
}

/// The centres of four clusters: each one's sums over its joints in six registers,
/// transposed into one register per field, then `solve` on the registers.
///
/// # Safety
/// The processor must have AVX2.
#[target_feature(enable = "avx2")]
pub(super) unsafe fn four(joints: [&[u16]; 4], motions: &Motions) -> [Vec3<f32>; 4] {
    chasles::frame::align_frame();
    // Each cluster's sums in six registers, one cluster after the other (all four
    // clusters' 24 accumulators at once spilled to the stack at every joint).
    let mut s = [[_mm256_setzero_pd(); 6]; 4];
    for (s, joints) in s.iter_mut().zip(joints) {
        let mut acc = [_mm256_setzero_pd(); 6];
        for j in joints {
            let m: &Motion = &motions.0[usize::from(*j)];
            for (r, a) in acc.iter_mut().enumerate() {
                // SAFETY: fields 4r … 4r + 3 of the 24.
                *a = _mm256_add_pd(*a, unsafe { _mm256_loadu_pd(m.as_ptr().add(4 * r)) });
            }
        }
        *s = acc;
    }
    let mut f = [W(_mm256_setzero_pd()); 24];
    for r in 0..6 {
        let t0 = _mm256_unpacklo_pd(s[0][r], s[1][r]);
        let t1 = _mm256_unpackhi_pd(s[0][r], s[1][r]);
        let t2 = _mm256_unpacklo_pd(s[2][r], s[3][r]);
        let t3 = _mm256_unpackhi_pd(s[2][r], s[3][r]);
        f[4 * r] = W(_mm256_permute2f128_pd::<0x20>(t0, t2));
        f[4 * r + 1] = W(_mm256_permute2f128_pd::<0x20>(t1, t3));
        f[4 * r + 2] = W(_mm256_permute2f128_pd::<0x31>(t0, t2));
        f[4 * r + 3] = W(_mm256_permute2f128_pd::<0x31>(t1, t3));
    }
    let n = joints.map(|j| j.len() as f64);
    let n = W(_mm256_setr_pd(n[0], n[1], n[2], n[3]));
    let (x, prior, det) = solve(|i| f[i], n);
    let (x, prior, det) = (x.map(lanes), prior.map(lanes), lanes(det));
    let at = |v: &[[f64; 4]; 3], l: usize| [v[0][l], v[1][l], v[2][l]];
    [0, 1, 2, 3].map(|l| pick(at(&x, l), at(&prior, l), det[l]))
}
