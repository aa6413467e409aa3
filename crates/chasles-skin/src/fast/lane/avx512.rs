//! Sixteen lanes: the lane algebra ([`Lane`]) on AVX-512F's `__m512`, its comparisons as
//! the mask registers' `__mmask16`. Every operation is the eight-lane `__m256` one's on
//! twice the lanes — the same correctly rounded division and square root, the same fused
//! multiply-adds, sign flips by the sign bit alone — so a lane of the sixteen-vertex DIB
//! kernel (`avx512`) gives the eight-vertex kernel's bits (its tests check it).

use super::Lane;
use std::arch::x86_64::*;

/// Sixteen lanes. As for `__m256`'s impl: the methods are safe to call only where AVX-512F
/// runs, and the `__m512` values they take exist only inside the AVX-512 kernels, which
/// run only where `avx512` found the feature.
impl Lane for __m512 {
    type Mask = __mmask16;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        // SAFETY: see the impl's doc: only called from AVX-512F code.
        unsafe { _mm512_set1_ps(x) }
    }
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_add_ps(self, b) }
    }
    #[inline(always)]
    fn sub(self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_sub_ps(self, b) }
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_sqrt_ps(self) }
    }
    #[inline(always)]
    fn lt(self, b: Self) -> __mmask16 {
        // SAFETY: as for splat.
        unsafe { _mm512_cmp_ps_mask::<_CMP_LT_OQ>(self, b) }
    }
    #[inline(always)]
    fn le(self, b: Self) -> __mmask16 {
        // SAFETY: as for splat.
        unsafe { _mm512_cmp_ps_mask::<_CMP_LE_OQ>(self, b) }
    }
    #[inline(always)]
    fn select(m: __mmask16, a: Self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_mask_blend_ps(m, b, a) }
    }
    #[inline(always)]
    fn and(a: __mmask16, b: __mmask16) -> __mmask16 {
        a & b
    }
    #[inline(always)]
    fn and_not(a: __mmask16, b: __mmask16) -> __mmask16 {
        !a & b
    }
    #[inline(always)]
    fn any(m: __mmask16) -> bool {
        m != 0
    }
    #[inline(always)]
    fn neg_where(self, m: __mmask16) -> Self {
        // SAFETY: as for splat.
        unsafe {
            let x = _mm512_castps_si512(self);
            let sign = _mm512_set1_epi32(i32::MIN);
            _mm512_castsi512_ps(_mm512_mask_xor_epi32(x, m, x, sign))
        }
    }
    #[inline(always)]
    fn flip_by_sign_of(self, of: Self) -> Self {
        // SAFETY: as for splat.
        unsafe {
            let sign = _mm512_and_si512(_mm512_castps_si512(of), _mm512_set1_epi32(i32::MIN));
            _mm512_castsi512_ps(_mm512_xor_si512(_mm512_castps_si512(self), sign))
        }
    }
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_mul_ps(self, b) }
    }
    #[inline(always)]
    fn div(self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_div_ps(self, b) }
    }
    #[inline(always)]
    fn madd(self, b: Self, c: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_fmadd_ps(self, b, c) }
    }
    #[inline(always)]
    fn msub(self, b: Self, c: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_fmsub_ps(self, b, c) }
    }
    #[inline(always)]
    fn nmadd(self, b: Self, c: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm512_fnmadd_ps(self, b, c) }
    }
    #[inline(always)]
    fn horner<const N: usize>(c: &[f32; N], s: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { horner16(c, s) }
    }
}

/// [`Lane::horner`] on sixteen lanes, as a `target_feature` function of its own for the
/// reason `horner8` is (the series' constants as broadcasts, not loads in the loop).
///
/// # Safety
/// The processor must have AVX-512F.
#[inline]
#[target_feature(enable = "avx512f")]
unsafe fn horner16<const N: usize>(c: &[f32; N], s: __m512) -> __m512 {
    let mut a = _mm512_set1_ps(c[N - 1]);
    for k in (0..N - 1).rev() {
        a = _mm512_fmadd_ps(a, s, _mm512_set1_ps(c[k]));
    }
    a
}
