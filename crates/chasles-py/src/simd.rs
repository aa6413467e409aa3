//! The library's batch loops compiled for AVX2 too, the build chosen at run time.
//!
//! The package is built for the x86-64 baseline, so that one wheel runs on every x86-64
//! processor: its vectorized loops use SSE2, two f64 (or four f32) lanes. The library's
//! batch functions (`quats_to_euler`, `quats_to_rotation_matrices`,
//! `quats_from_rotation_matrices`, `dlb_batch`) are `#[inline(always)]`, so each is compiled
//! here a second time inside a `#[target_feature(enable = "avx2")]` function — four f64
//! lanes — and that build runs where `is_x86_feature_detected!("avx2")` finds the feature
//! (cached by std after the first call). The two builds perform the same operations in the
//! same order: Rust never fuses a multiply and an add on its own, and the library's kernels
//! fuse only under the compile-time `fma` target feature, which neither build has — so they
//! give the same bits (`tests/test_convert.py` and `tests/test_blend.py` check it through
//! [`_set_simd`]).
//!
//! For DLB in f64 the AVX2 build goes one step further: the library's `dlb_batch` moves
//! each number of each blend into its lane by itself — over half of its instructions — so
//! here four numbers of four blends move at a time, by a 4×4 transpose in registers, around
//! the library's kernel `dlb_in_lanes` (the same arithmetic, the same bits). At 10⁵ blends
//! of four on one core that took DLB from 5.7 to 3.2 ms (development machine, best of 20).
//!
//! This module holds the crate's only `unsafe`: calling a `#[target_feature]` function is
//! unsafe unless the caller has the feature, and each call here is behind the check; and
//! the unaligned loads and stores of four f64s of the transpose, each on a slice checked
//! to hold them.
#![allow(unsafe_code)]

use chasles::convert::{euler, matrix, BatchError};
use chasles::{blend::dlb, EulerOrder, Mat3, Quat, Real};
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether the AVX2 builds may run (they do where the processor has AVX2).
static ALLOWED: AtomicBool = AtomicBool::new(true);

/// Allows (the default) or forbids the AVX2 builds of the batch loops for this process;
/// returns whether they were allowed. For the tests, which check that both builds give the
/// same bits; not part of the public API.
#[pyfunction]
pub fn _set_simd(allowed: bool) -> bool {
    ALLOWED.swap(allowed, Ordering::Relaxed)
}

/// Whether the AVX2 builds run: an x86-64 processor with AVX2, and allowed.
#[cfg(target_arch = "x86_64")]
#[inline]
fn avx2() -> bool {
    ALLOWED.load(Ordering::Relaxed) && std::is_x86_feature_detected!("avx2")
}

/// `chasles::convert::euler::quats_to_euler`, in the AVX2 build where it runs.
pub fn quats_to_euler<T: Real>(
    q: &[Quat<T>],
    order: EulerOrder,
    out: &mut [[T; 3]],
) -> Result<(), BatchError> {
    #[cfg(target_arch = "x86_64")]
    if avx2() {
        // SAFETY: the processor has AVX2 (avx2() checked it).
        return unsafe { wide::quats_to_euler(q, order, out) };
    }
    euler::quats_to_euler(q, order, out)
}

/// `chasles::convert::matrix::quats_from_rotation_matrices`, in the AVX2 build where it runs.
pub fn quats_from_rotation_matrices<T: Real>(
    m: &[Mat3<T>],
    out: &mut [Quat<T>],
) -> Result<(), BatchError> {
    #[cfg(target_arch = "x86_64")]
    if avx2() {
        // SAFETY: the processor has AVX2 (avx2() checked it).
        return unsafe { wide::quats_from_rotation_matrices(m, out) };
    }
    matrix::quats_from_rotation_matrices(m, out)
}

/// `chasles::convert::matrix::quats_to_rotation_matrices`, in the AVX2 build where it runs.
pub fn quats_to_rotation_matrices<T: Real>(
    q: &[Quat<T>],
    out: &mut [[T; 9]],
) -> Result<(), BatchError> {
    #[cfg(target_arch = "x86_64")]
    if avx2() {
        // SAFETY: the processor has AVX2 (avx2() checked it).
        return unsafe { wide::quats_to_rotation_matrices(q, out) };
    }
    matrix::quats_to_rotation_matrices(q, out)
}

/// `chasles::blend::dlb::dlb_batch`, in the AVX2 build where it runs; for f64 there,
/// with the blends moved into the library's lanes by AVX2 shuffles ([`Dlb`]).
pub fn dlb_batch<T: Dlb, const N: usize>(
    q: &[[[T; 8]; N]],
    w: &[[T; N]],
    out: &mut [[T; 8]],
) -> Result<(), BatchError> {
    T::dlb_batch(q, w, out)
}

/// How a precision runs `dlb_batch`. The library's `dlb_batch` moves each number into its
/// lane by itself — about 110 of the 190 instructions a blend of four takes; for f64 in the
/// AVX2 build, [`wide::dlb_batch_f64`] moves four numbers at a time (a 4×4 transpose in
/// registers) around the library's kernel `dlb_in_lanes`, for the same bits.
pub trait Dlb: Real {
    /// `chasles::blend::dlb::dlb_batch` (AVX2 build where it runs).
    fn dlb_batch<const N: usize>(
        q: &[[[Self; 8]; N]],
        w: &[[Self; N]],
        out: &mut [[Self; 8]],
    ) -> Result<(), BatchError> {
        #[cfg(target_arch = "x86_64")]
        if avx2() {
            // SAFETY: the processor has AVX2 (avx2() checked it).
            return unsafe { wide::dlb_batch(q, w, out) };
        }
        dlb::dlb_batch(q, w, out)
    }
}

impl Dlb for f32 {}

impl Dlb for f64 {
    fn dlb_batch<const N: usize>(
        q: &[[[f64; 8]; N]],
        w: &[[f64; N]],
        out: &mut [[f64; 8]],
    ) -> Result<(), BatchError> {
        #[cfg(target_arch = "x86_64")]
        if avx2() {
            // SAFETY: the processor has AVX2 (avx2() checked it).
            return unsafe { wide::dlb_batch_f64(q, w, out) };
        }
        dlb::dlb_batch(q, w, out)
    }
}

/// The AVX2 builds: the library's `#[inline(always)]` batch functions inlined into
/// functions compiled with the feature.
#[cfg(target_arch = "x86_64")]
mod wide {
    use super::*;
    use std::arch::x86_64::{
        __m256d, _mm256_loadu_pd, _mm256_permute2f128_pd, _mm256_storeu_pd, _mm256_unpackhi_pd,
        _mm256_unpacklo_pd,
    };

    #[target_feature(enable = "avx2")]
    pub fn quats_to_euler<T: Real>(
        q: &[Quat<T>],
        order: EulerOrder,
        out: &mut [[T; 3]],
    ) -> Result<(), BatchError> {
        chasles::frame::align_frame();
        euler::quats_to_euler(q, order, out)
    }

    #[target_feature(enable = "avx2")]
    pub fn quats_from_rotation_matrices<T: Real>(
        m: &[Mat3<T>],
        out: &mut [Quat<T>],
    ) -> Result<(), BatchError> {
        chasles::frame::align_frame();
        matrix::quats_from_rotation_matrices(m, out)
    }

    #[target_feature(enable = "avx2")]
    pub fn quats_to_rotation_matrices<T: Real>(
        q: &[Quat<T>],
        out: &mut [[T; 9]],
    ) -> Result<(), BatchError> {
        chasles::frame::align_frame();
        matrix::quats_to_rotation_matrices(q, out)
    }

    #[target_feature(enable = "avx2")]
    pub fn dlb_batch<T: Real, const N: usize>(
        q: &[[[T; 8]; N]],
        w: &[[T; N]],
        out: &mut [[T; 8]],
    ) -> Result<(), BatchError> {
        chasles::frame::align_frame();
        dlb::dlb_batch(q, w, out)
    }

    /// `dlb::dlb_batch` for f64 with AVX2 shuffles moving the numbers into and out of the
    /// library's lanes (`dlb::dlb_in_lanes`, eight blends): four numbers of four blends at a
    /// time by a 4×4 transpose in registers. The blends whose flag is false, and the last
    /// blends short of a group of eight, go through `dlb::dlb_batch` (and so `dlb`).
    #[target_feature(enable = "avx2")]
    pub fn dlb_batch_f64<const N: usize>(
        q: &[[[f64; 8]; N]],
        w: &[[f64; N]],
        out: &mut [[f64; 8]],
    ) -> Result<(), BatchError> {
        chasles::frame::align_frame();
        const L: usize = dlb::LANES;
        const { assert!(L.is_multiple_of(4), "whole 4x4 transposes") };
        if N == 0 || q.len() != w.len() || q.len() != out.len() {
            // dlb_batch's errors.
            return dlb::dlb_batch(q, w, out);
        }
        let (qg, qr) = q.as_chunks::<L>();
        let (wg, wr) = w.as_chunks::<L>();
        let (og, or) = out.as_chunks_mut::<L>();
        let at = |start: usize, e: BatchError| BatchError {
            index: start + e.index,
            error: e.error,
        };
        for (g, ((qs, ws), os)) in qg.iter().zip(wg).zip(og.iter_mut()).enumerate() {
            let mut x = [[[0.0; L]; 8]; N];
            let mut wk = [[0.0; L]; N];
            for (k, xk) in x.iter_mut().enumerate() {
                for h in 0..2 {
                    for b in 0..L / 4 {
                        // Numbers 4h..4h+4 of dual quaternion k of blends 4b..4b+4.
                        let rows = std::array::from_fn(|l| load4(&qs[4 * b + l][k][4 * h..]));
                        for (j, col) in transpose4(rows).into_iter().enumerate() {
                            store4(&mut xk[4 * h + j][4 * b..], col);
                        }
                    }
                }
            }
            if N.is_multiple_of(4) {
                for c in 0..N / 4 {
                    for b in 0..L / 4 {
                        // Weights 4c..4c+4 of blends 4b..4b+4.
                        let rows = std::array::from_fn(|l| load4(&ws[4 * b + l][4 * c..]));
                        for (k, col) in transpose4(rows).into_iter().enumerate() {
                            store4(&mut wk[4 * c + k][4 * b..], col);
                        }
                    }
                }
            } else {
                for (l, wl) in ws.iter().enumerate() {
                    for (k, v) in wl.iter().enumerate() {
                        wk[k][l] = *v;
                    }
                }
            }
            let (res, ok) = dlb::dlb_in_lanes(&x, &wk);
            for h in 0..2 {
                for b in 0..L / 4 {
                    let rows = std::array::from_fn(|j| load4(&res[4 * h + j][4 * b..]));
                    for (l, col) in transpose4(rows).into_iter().enumerate() {
                        store4(&mut os[4 * b + l][4 * h..], col);
                    }
                }
            }
            if ok.iter().any(|g| !g) {
                for (l, ((qi, wi), o)) in qs.iter().zip(ws).zip(os.iter_mut()).enumerate() {
                    if !ok[l] {
                        let one = std::slice::from_mut(o);
                        dlb::dlb_batch(std::slice::from_ref(qi), std::slice::from_ref(wi), one)
                            .map_err(|e| at(g * L + l, e))?;
                    }
                }
            }
        }
        dlb::dlb_batch(qr, wr, or).map_err(|e| at(qg.len() * L, e))
    }

    /// The first four numbers of `s` in a register.
    #[inline]
    #[target_feature(enable = "avx2")]
    fn load4(s: &[f64]) -> __m256d {
        assert!(s.len() >= 4);
        // SAFETY: four f64s are readable at s (checked above); loadu takes any alignment.
        unsafe { _mm256_loadu_pd(s.as_ptr()) }
    }

    /// A register into the first four numbers of `s`.
    #[inline]
    #[target_feature(enable = "avx2")]
    fn store4(s: &mut [f64], v: __m256d) {
        assert!(s.len() >= 4);
        // SAFETY: four f64s are writable at s (checked above); storeu takes any alignment.
        unsafe { _mm256_storeu_pd(s.as_mut_ptr(), v) }
    }

    /// The 4×4 transpose of four registers (rows in, columns out).
    #[inline]
    #[target_feature(enable = "avx2")]
    fn transpose4(r: [__m256d; 4]) -> [__m256d; 4] {
        let t0 = _mm256_unpacklo_pd(r[0], r[1]);
        let t1 = _mm256_unpackhi_pd(r[0], r[1]);
        let t2 = _mm256_unpacklo_pd(r[2], r[3]);
        let t3 = _mm256_unpackhi_pd(r[2], r[3]);
        [
            _mm256_permute2f128_pd::<0x20>(t0, t2),
            _mm256_permute2f128_pd::<0x20>(t1, t3),
            _mm256_permute2f128_pd::<0x31>(t0, t2),
            _mm256_permute2f128_pd::<0x31>(t1, t3),
        ]
    }
}
