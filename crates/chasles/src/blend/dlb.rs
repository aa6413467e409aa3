//! *DLB*: dual quaternion linear blending, `Σ wᵢ q̂ᵢ / ‖Σ wᵢ q̂ᵢ‖` (Kavan et al. 2006, §4).
//! Bi-invariant, shortest path, not constant speed (its angle differs from ScLERP's by less
//! than 8.15°, its translation by less than 15 %).
//!
//! The antipodality fix: q̂ and −q̂ are the same transformation, but summing both would
//! cancel. Every q̂ᵢ is first brought into the hemisphere of a pivot — the input with the
//! largest weight — by flipping its sign when `⟨q0,ᵢ, q0,pivot⟩ < 0` (as Kavan's reference
//! `dqsAntipod` does in skinning). The sum is then normalized as a dual quaternion (real
//! part to unit length, dual part made orthogonal to it).
//!
//! [`dlb_batch`] runs [`dlb`] over many blends of the same number of transforms, eight
//! side by side in lanes, with the same operations in the same order and its checks
//! (weights, finiteness, the plain path of the norm) folded into one flag per blend instead
//! of branches, so its results are [`dlb`]'s bit for bit; only blends that fail a check go
//! through [`dlb`] itself, which reports them.

use super::weights::{check_lengths, convex_weights, pivot};
use crate::convert::BatchError;
use crate::{DualQuat, Real, Result};

/// DLB of unit dual quaternions (weights made convex).
pub fn dlb<T: Real>(q: &[DualQuat<T>], w: &[T]) -> Result<DualQuat<T>> {
    dlb_convex(q, &convex_weights(w, q.len())?)
}

/// DLB with weights that are already convex (non-negative, summing to 1; only the lengths
/// are checked) and no allocation: for callers that blend once per vertex.
pub fn dlb_convex<T: Real>(q: &[DualQuat<T>], w: &[T]) -> Result<DualQuat<T>> {
    check_lengths(q.len(), w.len())?;
    let p = q[pivot(w)].real;
    let mut sum = DualQuat::new(crate::Quat::zero(), crate::Quat::zero());
    for (qi, wi) in q.iter().zip(w) {
        let s = if qi.real.dot(p) < T::ZERO { -*wi } else { *wi };
        sum = sum + *qi * s;
    }
    sum.normalize()
}

/// [`dlb`] of every blend `(q[i], w[i])` of `N` dual quaternions into `out[i]`, bit for
/// bit: `q[i][k]` and `out[i]` are dual quaternions as 8 numbers in the order of
/// [`DualQuat::to_array`], so that contiguous arrays of numbers (a numpy array of shape
/// (…, N, 8), say) are read and written where they are. The weights are checked and scaled
/// per blend as [`dlb`] does (no allocation). Eight blends at a time are transposed into
/// lanes (one array per number, one lane per blend) and blended by loops without branches
/// or calls, which the compiler vectorizes across blends (`#[inline(always)]`, so that a
/// caller can compile it for wider vectors inside a `#[target_feature]` function); blends
/// whose weights or sum fail a check go through [`dlb`], which reports them. Errors: the
/// first blend that fails (its index and [`dlb`]'s error — bad weights, a sum that is not
/// finite or has a zero real part; the blends before it are written), or inputs of
/// different lengths.
#[inline(always)]
pub fn dlb_batch<T: Real, const N: usize>(
    q: &[[[T; 8]; N]],
    w: &[[T; N]],
    out: &mut [[T; 8]],
) -> core::result::Result<(), BatchError> {
    crate::convert::same_lengths(
        &[q.len(), w.len(), out.len()],
        &["dlb_batch: q and w", "dlb_batch: q and out"],
    )?;
    let per_item = |index: usize, q: &[[T; 8]; N], w: &[T; N]| {
        let q = q.map(DualQuat::from_array);
        dlb(&q, w)
            .map(DualQuat::to_array)
            .map_err(|error| BatchError { index, error })
    };
    if N == 0 {
        // Nothing to blend: dlb's error for the first item.
        return match (q.first(), w.first()) {
            (Some(q), Some(w)) => per_item(0, q, w).map(|_| ()),
            _ => Ok(()),
        };
    }
    // Whole groups of LANES blends, then the rest padded with copies of its last blend.
    let (qg, qr) = q.as_chunks::<LANES>();
    let (wg, wr) = w.as_chunks::<LANES>();
    let (og, or) = out.as_chunks_mut::<LANES>();
    for (g, ((qs, ws), os)) in qg.iter().zip(wg).zip(og.iter_mut()).enumerate() {
        let ok = dlb_lanes(qs, ws, os);
        redo(g * LANES, &ok, qs, ws, os, &per_item)?;
    }
    if let (Some(ql), Some(wl)) = (qr.last(), wr.last()) {
        let qs = core::array::from_fn(|l| *qr.get(l).unwrap_or(ql));
        let ws = core::array::from_fn(|l| *wr.get(l).unwrap_or(wl));
        let mut os = [[T::ZERO; 8]; LANES];
        let ok = dlb_lanes(&qs, &ws, &mut os);
        let n = or.len();
        or.copy_from_slice(&os[..n]);
        redo(
            qg.len() * LANES,
            &ok[..n],
            &qs[..n],
            &ws[..n],
            or,
            &per_item,
        )?;
    }
    Ok(())
}

/// Blends of a group, starting at index `start`, that did not stand, through `per_item`
/// (that is, [`dlb`]): the first error stops.
#[inline(always)]
fn redo<T: Real, const N: usize>(
    start: usize,
    ok: &[bool],
    q: &[[[T; 8]; N]],
    w: &[[T; N]],
    out: &mut [[T; 8]],
    per_item: &impl Fn(usize, &[[T; 8]; N], &[T; N]) -> core::result::Result<[T; 8], BatchError>,
) -> core::result::Result<(), BatchError> {
    if ok.iter().all(|g| *g) {
        return Ok(());
    }
    for (l, (((qi, wi), o), good)) in q.iter().zip(w).zip(out).zip(ok).enumerate() {
        if !good {
            *o = per_item(start + l, qi, wi)?;
        }
    }
    Ok(())
}

/// How many blends [`dlb_in_lanes`] blends side by side (and [`dlb_batch`] at a time).
pub const LANES: usize = crate::convert::LANES;

/// [`dlb`] of [`LANES`] blends side by side, with its checks as one flag a blend: the
/// numbers transposed into lanes, blended by [`dlb_in_lanes`], the results transposed
/// back into `out`. Whether each blend stands.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // the lane loops are the point: each one vectorizes
fn dlb_lanes<T: Real, const N: usize>(
    q: &[[[T; 8]; N]; LANES],
    w: &[[T; N]; LANES],
    out: &mut [[T; 8]; LANES],
) -> [bool; LANES] {
    // x[k][j][l] is number j of dual quaternion k of blend l; wk[k][l] its weight.
    let mut x = [[[T::ZERO; LANES]; 8]; N];
    let mut wk = [[T::ZERO; LANES]; N];
    for l in 0..LANES {
        for k in 0..N {
            for j in 0..8 {
                x[k][j][l] = q[l][k][j];
            }
            wk[k][l] = w[l][k];
        }
    }
    let (res, good) = dlb_in_lanes(&x, &wk);
    for (l, o) in out.iter_mut().enumerate() {
        *o = core::array::from_fn(|j| res[j][l]);
    }
    good
}

/// The kernel of [`dlb_batch`]: [`dlb`] of [`LANES`] blends held in lanes — `x[k][j][l]` is
/// number j (in [`DualQuat::to_array`]'s order) of dual quaternion k of blend l, `w[k][l]`
/// its weight; number j of blend l's result is returned in `[j][l]` — with `dlb`'s
/// operations (`convex_weights`, `dlb_convex`, `DualQuat::normalize`) in their order, in
/// one loop over the lanes that the compiler vectorizes, every choice a select. The flag of
/// a lane says whether its blend stands (good weights, a finite sum whose real part's
/// squared norm is a normal number — the norm's plain path): then it is `dlb`'s bit for
/// bit; a blend whose flag is false must go through [`dlb`] (which reports what is wrong
/// with it). For callers that hold their blends in lanes already, or put them there with
/// shuffles the compiler does not find (the Python package's AVX2 build does; [`dlb_batch`]
/// moves numbers one by one). `#[inline(always)]`, like [`dlb_batch`].
#[inline(always)]
#[allow(clippy::needless_range_loop)] // the lane loop is the point: it vectorizes
pub fn dlb_in_lanes<T: Real, const N: usize>(
    x: &[[[T; LANES]; 8]; N],
    w: &[[T; LANES]; N],
) -> ([[T; LANES]; 8], [bool; LANES]) {
    let mut res = [[T::ZERO; LANES]; 8];
    let mut good = [true; LANES];
    for l in 0..LANES {
        // The weights, checked and scaled (convex_weights).
        let mut total = T::ZERO;
        let mut ok = true;
        for k in 0..N {
            let v = w[k][l];
            ok &= v.is_finite() & (v >= T::ZERO);
            total += v;
        }
        ok &= (total > T::ZERO) & total.is_finite();
        let c: [T; N] = core::array::from_fn(|k| w[k][l] / total);
        // Every real part, loaded once (a load under the pivot's condition below would be
        // compiled as a masked load, slow on AMD's Zen).
        let r: [[T; 4]; N] = core::array::from_fn(|k| core::array::from_fn(|j| x[k][j][l]));
        // The pivot: the real part of the first heaviest.
        let mut best = c[0];
        let mut p = r[0];
        for k in 1..N {
            let heavier = c[k] > best;
            best = if heavier { c[k] } else { best };
            for j in 0..4 {
                p[j] = if heavier { r[k][j] } else { p[j] };
            }
        }
        // The sum from zero, each term flipped into the pivot's hemisphere.
        let mut sum = [T::ZERO; 8];
        for k in 0..N {
            let dot = r[k][0] * p[0] + r[k][1] * p[1] + r[k][2] * p[2] + r[k][3] * p[3];
            let s = if dot < T::ZERO { -c[k] } else { c[k] };
            for j in 0..8 {
                sum[j] += x[k][j][l] * s;
            }
        }
        // DualQuat::normalize on its plain path.
        let finite = sum.iter().fold(true, |a, v| a & v.is_finite());
        let n2 = sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2] + sum[3] * sum[3];
        ok &= finite & n2.is_finite() & (n2 >= T::MIN_POSITIVE);
        let n = n2.sqrt();
        let real = [sum[0] / n, sum[1] / n, sum[2] / n, sum[3] / n];
        let dual = [sum[4] / n, sum[5] / n, sum[6] / n, sum[7] / n];
        let d = real[0] * dual[0] + real[1] * dual[1] + real[2] * dual[2] + real[3] * dual[3];
        for j in 0..4 {
            res[j][l] = real[j];
            res[4 + j][l] = dual[j] - real[j] * d;
        }
        good[l] = ok;
    }
    (res, good)
}
