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
//! This module holds the crate's only `unsafe`: calling a `#[target_feature]` function is
//! unsafe unless the caller has the feature, and each call here is behind the check.
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
#[inline]
fn avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        ALLOWED.load(Ordering::Relaxed) && std::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
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

/// `chasles::blend::dlb::dlb_batch`, in the AVX2 build where it runs.
pub fn dlb_batch<T: Real, const N: usize>(
    q: &[[[T; 8]; N]],
    w: &[[T; N]],
    out: &mut [[T; 8]],
) -> Result<(), BatchError> {
    #[cfg(target_arch = "x86_64")]
    if avx2() {
        // SAFETY: the processor has AVX2 (avx2() checked it).
        return unsafe { wide::dlb_batch(q, w, out) };
    }
    dlb::dlb_batch(q, w, out)
}

/// The AVX2 builds: the library's `#[inline(always)]` batch functions inlined into
/// functions compiled with the feature.
#[cfg(target_arch = "x86_64")]
mod wide {
    use super::*;

    #[target_feature(enable = "avx2")]
    pub fn quats_to_euler<T: Real>(
        q: &[Quat<T>],
        order: EulerOrder,
        out: &mut [[T; 3]],
    ) -> Result<(), BatchError> {
        euler::quats_to_euler(q, order, out)
    }

    #[target_feature(enable = "avx2")]
    pub fn quats_from_rotation_matrices<T: Real>(
        m: &[Mat3<T>],
        out: &mut [Quat<T>],
    ) -> Result<(), BatchError> {
        matrix::quats_from_rotation_matrices(m, out)
    }

    #[target_feature(enable = "avx2")]
    pub fn quats_to_rotation_matrices<T: Real>(
        q: &[Quat<T>],
        out: &mut [[T; 9]],
    ) -> Result<(), BatchError> {
        matrix::quats_to_rotation_matrices(q, out)
    }

    #[target_feature(enable = "avx2")]
    pub fn dlb_batch<T: Real, const N: usize>(
        q: &[[[T; 8]; N]],
        w: &[[T; N]],
        out: &mut [[T; 8]],
    ) -> Result<(), BatchError> {
        dlb::dlb_batch(q, w, out)
    }
}
