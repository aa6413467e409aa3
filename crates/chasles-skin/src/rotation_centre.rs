//! The centres that decomposed blends rotate about (Kavan et al. 2006, §2.2 and §6: Dec and
//! QLB are coordinate dependent, so skinning must choose a centre per vertex).
//!
//! * [`joint_centres`] — each joint's origin in the bind pose; decomposed QLB (Hejl 2004)
//!   rotates a vertex about the weighted mean of its joints' origins.
//! * [`Clusters`] — spherical blend skinning (Kavan & Žára 2005) groups the vertices bound
//!   to the same set of joints and gives each cluster one *rotation centre* per pose: the
//!   point r whose images under the cluster's joint transforms agree best,
//!   `min Σ_{a<b} ‖(R_a − R_b) r + t_a − t_b‖²`. The 3×3 normal equations are solved in f64
//!   with a small Tikhonov term (1e-6 of the trace) pulling r towards the mean of the
//!   cluster's joint origins, where the problem is rank-deficient (the paper takes the
//!   SVD's pseudo-inverse; along a deficient direction the blend does not depend on r).
//!   A cluster of one joint moves rigidly, about any centre.
//!
//! The normal equations are summed in O(n) for n joints, not over the n(n−1)/2 pairs:
//! with `S = Σ R_a`, `T = Σ t_a`, `G = Σ R_aᵀR_a` and `U = Σ R_aᵀ t_a`,
//!
//! ```text
//! Σ_{a<b} (R_a − R_b)ᵀ(R_a − R_b) = n G − SᵀS,   Σ_{a<b} (R_a − R_b)ᵀ(t_a − t_b) = n U − SᵀT
//! ```
//!
//! (half the sum over all ordered pairs). `G` is `n I` for exact rotations, but the f32
//! matrices are orthogonal only to rounding, and `n² I − SᵀS` would then give the null
//! direction of two joints (their relative rotation's axis) an eigenvalue of about 1e-7 —
//! as large as the Tikhonov term — and move the centre along it. Each joint's `R`, `t`,
//! `RᵀR` and `Rᵀt` are made once per pose ([`Motions`], each on whole cache lines: the
//! sums' 64-byte loads straddled two lines wherever the allocator put the vector, and the
//! solve took 1.2 times as long in those runs), and the system is solved by its
//! adjugate with one division — four clusters at once in AVX2's f64 lanes where the
//! processor has them (module `wide`: 20 ns a cluster against 35 one by one, on a rig of
//! 3·10⁵ clusters), eight in AVX-512F's, with the same operations in the same order, so
//! the same numbers; the choice of the solution or the prior and the rounding to f32 run
//! in the lanes too. On the synthetic rig of 10⁵ vertices (`synthetic::rig(100000, 54, 5)`:
//! 85 582 clusters; a 2-core Intel Xeon, best of runs of 20 poses): 16.4 ns a cluster with
//! four lanes and that choice made one lane at a time, 14.1–14.6 with eight lanes, 8.7–9.1
//! with eight and the choice in the lanes (13.9–15.1 with four); SBS's whole pose 2213 →
//! 1610–1624 µs. Numbering the clusters by their joint count, so that the loops over the
//! joints of four neighbours run alike, gained 4 % (16.4 → 15.7) and was not kept. The
//! centres are written straight into the caller's table (`Clusters::centres_into`: the
//! fast path's palette).
//!
//! Tried on that rig and not kept (old and new builds in turn, three runs each; the eight
//! lanes are bound by their 512-bit ports, about 300 vector instructions for eight
//! clusters: 96 adds of the sums, 72 shuffles of the transposes, the rest the solve):
//! * Summing each cluster's *pairs* (the definition's `Σ_{a<b}`, with each distinct pair's
//!   `DᵀD`, `−Dᵀe` and origins made once per pose) takes no Gram matrix of S and half the
//!   transposes, but 10.4–10.7 ns a cluster against 9.8: a cluster of four joints reads
//!   six pair records of 13 f64 (two lines each) from a table of 1431 pairs that lives in
//!   the second-level cache, where the joints' 54 motions stay in the first. Records in
//!   f32 (one line) would give the null direction of a two-joint cluster an eigenvalue of
//!   a few per cent of the Tikhonov term, and move its centre along that axis by a few
//!   per cent of its distance from the prior.
//! * The four joints of a cluster unrolled, without bounds checks: 2 %.
//! * Two groups of eight clusters a call, each operation of the solve on both in turn (in
//!   case the solve's chain, ending in its division, left the ports idle): 9.7–10.1 →
//!   13.5–14.1 ns a cluster (2026-12-04, three runs each), its values spilled.
//!
//! The reference and fast paths share this code, so their centres are the same numbers.

use chasles::{DualQuat, Mat4, Vec3};
use rayon::prelude::*;
use std::collections::HashMap;
use std::ops::{Add, Div, Mul, Sub};

/// The origin of each joint's frame in bind space: the translation of the inverse of its
/// inverse bind matrix (the origin where that matrix is singular).
pub fn joint_centres(inverse_bind: &[Mat4<f32>]) -> Vec<Vec3<f32>> {
    inverse_bind
        .iter()
        .map(|ib| match ib.linear_part().inverse() {
            Some(inv) => -inv.mul_vec(ib.translation()),
            None => Vec3::zero(),
        })
        .collect()
}

/// Vertices grouped by the set of joints that move them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Clusters {
    /// The cluster of each vertex.
    of_vertex: Vec<u32>,
    /// The sorted joints of cluster c: `joints[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    joints: Vec<u16>,
}

/// Clusters at least this many are solved on all threads.
const PARALLEL: usize = 256;

impl Clusters {
    /// Groups `vertices` vertices by their joint sets; `joints_of(v)` lists vertex v's
    /// joints (any order, repeats allowed).
    pub fn new<I: IntoIterator<Item = u16>>(
        vertices: usize,
        joints_of: impl Fn(usize) -> I,
    ) -> Self {
        let mut index: HashMap<Vec<u16>, u32> = HashMap::new();
        let mut out = Clusters {
            of_vertex: Vec::with_capacity(vertices),
            start: vec![0],
            joints: Vec::new(),
        };
        for v in 0..vertices {
            let mut key: Vec<u16> = joints_of(v).into_iter().collect();
            key.sort_unstable();
            key.dedup();
            let next = index.len() as u32;
            let c = *index.entry(key).or_insert_with_key(|key| {
                out.joints.extend_from_slice(key);
                out.start.push(out.joints.len() as u32);
                next
            });
            out.of_vertex.push(c);
        }
        out
    }

    /// The number of clusters.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// Whether there are no clusters (no vertices).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The cluster of each vertex.
    pub fn of_vertex(&self) -> &[u32] {
        &self.of_vertex
    }

    /// The sorted joints of cluster `c`.
    #[inline]
    pub fn joints(&self, c: usize) -> &[u16] {
        &self.joints[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// The rotation centre of every cluster for joint transforms `d` (one per joint) and the
    /// joints' bind origins `bind` ([`joint_centres`]); on all threads when `parallel` and
    /// there are many clusters. The same bits on every processor and in every lane width,
    /// but for the payload of a NaN (a centre from non-finite input, which the fast path's
    /// palette refuses).
    pub fn centres(
        &self,
        d: &[DualQuat<f32>],
        bind: &[Vec3<f32>],
        parallel: bool,
    ) -> Vec<Vec3<f32>> {
        let mut out = vec![Vec3::zero(); self.len()];
        self.centres_into(d, bind, parallel, &mut out, |c| c);
        out
    }

    /// [`Clusters::centres`] into `out`, one entry a cluster, each centre as `put`
    /// makes it: the fast path's palette takes them padded to four floats with no vector of
    /// centres made on the way (on a rig of 85 582 clusters that vector and its padded copy
    /// were 2.4 MB a pose).
    ///
    /// # Panics
    /// If `out.len()` is not `self.len()` (the callers size it so).
    pub(crate) fn centres_into<O: Send>(
        &self,
        d: &[DualQuat<f32>],
        bind: &[Vec3<f32>],
        parallel: bool,
        out: &mut [O],
        put: impl Fn(Vec3<f32>) -> O + Sync,
    ) {
        assert_eq!(out.len(), self.len(), "one centre a cluster");
        let motions = Motions::new(d, bind);
        // The lanes where the fast path's SIMD kernels run (and not where `fast::set_simd`
        // or `fast::set_avx512` forbid them, so that the fallback is measured whole).
        let lanes = Lanes::allowed(crate::fast::uses_simd(4), crate::fast::uses_avx512(4));
        let write = |out: &mut [O], centres: &[Vec3<f32>]| {
            for (o, c) in out.iter_mut().zip(centres) {
                *o = put(*c);
            }
        };
        // Eight clusters at a time where AVX-512 may run, else (and the last few) four at a
        // time, and the last few of those one by one.
        let solve = |(g, out): (usize, &mut [O])| {
            let c = 8 * g;
            let joints = |k: usize| self.joints(c + k);
            if out.len() == 8 {
                if let Some(centres) = eight(core::array::from_fn(joints), &motions, lanes) {
                    write(out, &centres);
                    return;
                }
            }
            for (h, out) in out.chunks_mut(4).enumerate() {
                let joints = |k: usize| joints(4 * h + k);
                if out.len() == 4 {
                    write(out, &four([0, 1, 2, 3].map(joints), &motions, lanes.avx2));
                } else {
                    for (k, o) in out.iter_mut().enumerate() {
                        *o = put(rotation_centre(joints(k), &motions));
                    }
                }
            }
        };
        if parallel && self.len() >= PARALLEL {
            out.par_chunks_mut(8).enumerate().for_each(solve);
        } else {
            out.chunks_mut(8).enumerate().for_each(solve);
        }
    }
}

/// One joint of a pose as the centre solve sums it, in f64: its rotation R (rows, 0–8),
/// the lower triangle of `RᵀR` (00, 10, 11, 20, 21, 22; 9–14), its translation t (15–17),
/// `Rᵀt` (18–20) and its bind origin (21–23). One flat array, so a cluster's sum over its
/// joints is a vector loop.
type Motion = [f64; 24];

/// Where the parts of a [`Motion`] start.
const R: usize = 0;
const G: usize = 9;
const T: usize = 15;
const U: usize = 18;
const ORIGIN: usize = 21;

/// The lower triangle of `MᵀM` and `Mᵀt` for a 3×3 matrix M given by its rows, by one
/// order of operations (so a cluster of one joint sums to exactly zero).
#[inline(always)]
fn gram<X: Num>(m: [X; 9], t: [X; 3]) -> ([X; 6], [X; 3]) {
    let dot = |i: usize, x: [X; 3]| m[i] * x[0] + m[3 + i] * x[1] + m[6 + i] * x[2];
    let column = |k: usize| [m[k], m[3 + k], m[6 + k]];
    let g = |i: usize, k: usize| dot(i, column(k));
    (
        [g(0, 0), g(1, 0), g(1, 1), g(2, 0), g(2, 1), g(2, 2)],
        [dot(0, t), dot(1, t), dot(2, t)],
    )
}

/// The arithmetic of the solve: `f64` for one cluster, and four clusters' numbers in one
/// AVX2 register or eight in one AVX-512 register, lane by lane the same operations in the
/// same order (so equal bits: no fused multiply-adds).
trait Num:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    fn splat(x: f64) -> Self;
    /// `max(self, 1)`.
    fn at_least_one(self) -> Self;
}

impl Num for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn at_least_one(self) -> Self {
        self.max(1.0)
    }
}

/// A [`Motion`] on whole cache lines of its own, so the eight-lane sums' 64-byte loads
/// never straddle two (from an 8- or 16-byte aligned vector, the pose's centre solve took
/// 1.2 times as long in some runs as in others).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
struct Lines(Motion);

/// The joints of one pose as the centre solve sums them.
#[derive(Debug, Clone, PartialEq)]
pub struct Motions(Vec<Lines>);

impl Motions {
    /// The motions of joint transforms `d` (one per joint: `[R | t]` of each dual
    /// quaternion) with the joints' bind origins `bind`, in f64; as many as the shorter of
    /// the two has (the callers pass one per joint in both).
    pub fn new(d: &[DualQuat<f32>], bind: &[Vec3<f32>]) -> Self {
        Motions(
            d.iter()
                .zip(bind)
                .map(|(d, o)| {
                    let m = d.to_matrix4();
                    let mut x = [0f64; 24];
                    for i in 0..3 {
                        for k in 0..3 {
                            x[R + 3 * i + k] = f64::from(m.m[i][k]);
                        }
                        x[T + i] = f64::from(m.m[i][3]);
                        x[ORIGIN + i] = f64::from(o.get(i));
                    }
                    let (g, u) = gram(
                        core::array::from_fn(|i| x[R + i]),
                        core::array::from_fn(|i| x[T + i]),
                    );
                    x[G..T].copy_from_slice(&g);
                    x[U..ORIGIN].copy_from_slice(&u);
                    Lines(x)
                })
                .collect(),
        )
    }
}

/// The rotation centre of one cluster: `min Σ_{a<b} ‖(R_a − R_b) r + t_a − t_b‖²`, with a
/// Tikhonov pull (1e-6 of the trace) towards the mean of the joints' bind origins for the
/// rank-deficient directions; that mean where the system cannot be solved (non-finite
/// motions).
///
/// # Panics
/// If a joint index is not below the number of motions (the callers check rigs first).
pub fn rotation_centre(joints: &[u16], motions: &Motions) -> Vec3<f32> {
    let mut sum = [0f64; 24];
    for j in joints {
        let m = &motions.0[usize::from(*j)].0;
        for i in 0..24 {
            sum[i] += m[i];
        }
    }
    let (x, prior, det) = solve(|i| sum[i], joints.len() as f64);
    pick(x, prior, det)
}

/// The solution where the determinant is positive and finite, else the prior.
#[inline(always)]
fn pick(x: [f64; 3], prior: [f64; 3], det: f64) -> Vec3<f32> {
    let ok = det > 0.0 && det.is_finite();
    Vec3::from_array(if ok { x } else { prior }).cast()
}

/// The normal equations of a cluster from the sums `f(i)` of its joints' motions (the
/// fields of a [`Motion`]) over its `n` joints, with the Tikhonov term, solved: the solution,
/// the prior (the mean bind origin) and the determinant.
#[inline(always)]
fn solve<X: Num>(f: impl Fn(usize) -> X, n: X) -> ([X; 3], [X; 3], X) {
    let inv_n = X::splat(1.0) / n.at_least_one();
    let prior = [0, 1, 2].map(|i| f(ORIGIN + i) * inv_n);
    // A = n G − SᵀS and b = −(n U − SᵀT).
    let (sts, stt) = gram(
        [0, 1, 2, 3, 4, 5, 6, 7, 8].map(|i| f(R + i)),
        [0, 1, 2].map(|i| f(T + i)),
    );
    let mut a = [0, 1, 2, 3, 4, 5].map(|i| n * f(G + i) - sts[i]);
    let mut b = [0, 1, 2].map(|i| stt[i] - n * f(U + i));
    let lambda = X::splat(1e-6) * (a[0] + a[2] + a[5]) + X::splat(1e-12);
    for (i, d) in [0, 2, 5].into_iter().enumerate() {
        a[d] = a[d] + lambda;
        b[i] = b[i] + lambda * prior[i];
    }
    let (x, det) = solve_symmetric(a, b);
    (x, prior, det)
}

/// Four clusters' centres: in AVX2 registers where the processor has them (`avx2`, checked
/// once by the caller: [`wide::four`]), else one by one; the same numbers either way.
fn four(joints: [&[u16]; 4], motions: &Motions, avx2: bool) -> [Vec3<f32>; 4] {
    #[cfg(target_arch = "x86_64")]
    if avx2 {
        // SAFETY: the caller found AVX2 on this processor.
        return unsafe { wide::four(joints, motions) };
    }
    let _ = avx2;
    joints.map(|j| rotation_centre(j, motions))
}

/// Which lanes the centre solve may use, checked once a pose. Made only by
/// [`Lanes::allowed`], which asks the processor, so a `true` is always a feature it has.
#[derive(Clone, Copy)]
struct Lanes {
    /// AVX2's four f64.
    avx2: bool,
    /// AVX-512F's eight.
    avx512: bool,
}

impl Lanes {
    /// The lanes among those allowed that this processor has.
    fn allowed(avx2: bool, avx512: bool) -> Self {
        #[cfg(target_arch = "x86_64")]
        return Lanes {
            avx2: avx2 && std::arch::is_x86_feature_detected!("avx2"),
            avx512: avx512 && std::arch::is_x86_feature_detected!("avx512f"),
        };
        #[cfg(not(target_arch = "x86_64"))]
        {
            let _ = (avx2, avx512);
            Lanes {
                avx2: false,
                avx512: false,
            }
        }
    }
}

/// Eight clusters' centres in one AVX-512 register a field ([`wide::eight`]), where
/// allowed; `None` elsewhere (the caller takes them four at a time: the same numbers).
fn eight(joints: [&[u16]; 8], motions: &Motions, lanes: Lanes) -> Option<[Vec3<f32>; 8]> {
    #[cfg(target_arch = "x86_64")]
    if lanes.avx512 {
        // SAFETY: `Lanes::allowed` found AVX-512F on this processor.
        return Some(unsafe { wide::eight(joints, motions) });
    }
    let _ = (joints, motions, lanes.avx512);
    None
}

#[cfg(target_arch = "x86_64")]
mod wide;

/// x with `A x = b` for a symmetric 3×3 A given by its lower triangle (00, 10, 11, 20, 21,
/// 22), by the adjugate and one division, and the determinant (x is of use only where it
/// is positive and finite).
#[inline(always)]
fn solve_symmetric<X: Num>(a: [X; 6], b: [X; 3]) -> ([X; 3], X) {
    let [a00, a10, a11, a20, a21, a22] = a;
    let c00 = a11 * a22 - a21 * a21;
    let c10 = a20 * a21 - a10 * a22;
    let c20 = a10 * a21 - a20 * a11;
    let c11 = a00 * a22 - a20 * a20;
    let c21 = a10 * a20 - a00 * a21;
    let c22 = a00 * a11 - a10 * a10;
    let det = a00 * c00 + a10 * c10 + a20 * c20;
    let inv = X::splat(1.0) / det;
    (
        [
            (c00 * b[0] + c10 * b[1] + c20 * b[2]) * inv,
            (c10 * b[0] + c11 * b[1] + c21 * b[2]) * inv,
            (c20 * b[0] + c21 * b[1] + c22 * b[2]) * inv,
        ],
        det,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use chasles::Quat;

    #[test]
    fn clusters_group_equal_joint_sets() {
        let sets: [&[u16]; 5] = [&[3, 1], &[1, 3], &[2], &[1, 3, 3], &[0, 2]];
        let c = Clusters::new(sets.len(), |v| sets[v].iter().copied());
        assert_eq!(c.len(), 3);
        assert_eq!(c.of_vertex(), &[0, 0, 1, 0, 2]);
        assert_eq!(c.joints(0), &[1, 3]);
        assert_eq!(c.joints(2), &[0, 2]);
    }

    /// Sixteen joints, each turned and moved its own way, and their bind origins.
    fn sixteen_joints() -> (Vec<DualQuat<f32>>, Vec<Vec3<f32>>) {
        let d = (0..16)
            .map(|j| {
                let q = Quat::from_axis_angle(Vec3::new(1.0, j as f32, 2.0), 0.3 * j as f32);
                DualQuat::from_rotation_translation(q.unwrap(), Vec3::new(j as f32, 1.0, 0.5))
            })
            .collect();
        let bind = (0..16).map(|j| Vec3::new(0.0, j as f32, 1.0)).collect();
        (d, bind)
    }

    /// Asserts that `got` is the centre of `joints` solved alone, bit for bit (`what` says
    /// where it came from).
    fn assert_alone(got: Vec3<f32>, joints: &[u16], m: &Motions, what: &str) {
        let want = rotation_centre(joints, m);
        assert_eq!(
            got.to_array().map(f32::to_bits),
            want.to_array().map(f32::to_bits),
            "{joints:?} {what}"
        );
    }

    /// Every motion starts a cache line, wherever the allocator puts the vector, so no
    /// 64-byte load of the eight-lane sums straddles two.
    #[test]
    fn motions_sit_on_whole_cache_lines() {
        let (d, bind) = sixteen_joints();
        for _ in 0..4 {
            let m = Motions::new(&d, &bind);
            assert_eq!(m.0.len(), 16);
            for x in &m.0 {
                assert_eq!(std::ptr::from_ref(x) as usize % 64, 0);
            }
            assert_eq!(size_of::<Lines>(), size_of::<Motion>(), "no padding");
            assert_eq!(align_of::<Lines>(), 64);
            // Another allocation between poses, so the next vector may start elsewhere.
            std::hint::black_box(vec![0u8; 24]);
        }
    }

    #[test]
    fn many_clusters_solve_alike_on_all_threads() {
        // The 560 sets of 3 of 16 joints: over the threshold for threads.
        let (d, bind) = sixteen_joints();
        let sets: Vec<[u16; 3]> = (0..16u16)
            .flat_map(|a| (a + 1..16).flat_map(move |b| (b + 1..16).map(move |c| [a, b, c])))
            .collect();
        let c = Clusters::new(sets.len(), |v| sets[v]);
        assert!(c.len() >= PARALLEL, "{}", c.len());
        assert_eq!(c.centres(&d, &bind, true), c.centres(&d, &bind, false));
    }

    /// Every cluster's centre is its own, solved alone, bit for bit, whatever the count
    /// (the eights, fours and last few of `centres_into`'s chunks) and on all threads or
    /// one (in the widest lanes here: `fast::set_avx512` is the process's, which tests
    /// running beside this one count on; the widths are compared in the test below).
    #[test]
    fn every_cluster_gets_its_own_centre() {
        let (d, bind) = sixteen_joints();
        let m = Motions::new(&d, &bind);
        // Sets of 1 to 5 joints in a mixed order (equal sets make one cluster).
        let sets: Vec<Vec<u16>> = (0..PARALLEL as u16 + 13)
            .map(|i| (0..1 + i % 5).map(|k| (i * 7 + k * 3) % 16).collect())
            .collect();
        for n in (1..=20).chain([PARALLEL + 13]) {
            let c = Clusters::new(n, |v| sets[v].iter().copied());
            for parallel in [false, true] {
                let got = c.centres(&d, &bind, parallel);
                for (i, got) in got.iter().enumerate() {
                    let what = format!("n {n} cluster {i} parallel {parallel}");
                    assert_alone(*got, c.joints(i), &m, &what);
                }
            }
        }
    }

    /// Four clusters at once (AVX2 lanes, where the processor has them) give each one's
    /// centre bit for bit: clusters of 1 to 4 joints side by side, one
    /// with a non-finite joint (the prior), equal rotations (the prior by the determinant).
    #[test]
    fn four_at_once_are_each_alone_bit_for_bit() {
        let mut d: Vec<DualQuat<f32>> = (0..12)
            .map(|j| {
                let q = Quat::from_axis_angle(Vec3::new(1.0, j as f32, -2.0), 0.37 * j as f32);
                DualQuat::from_rotation_translation(q.unwrap(), Vec3::new(0.5, j as f32, -1.0))
            })
            .collect();
        d[11].real.w = f32::NAN;
        d[10] = d[9];
        let bind: Vec<Vec3<f32>> = (0..12).map(|j| Vec3::new(j as f32, 1.0, -0.5)).collect();
        let m = Motions::new(&d, &bind);
        let sets: [&[u16]; 8] = [
            &[0, 3, 5, 7],
            &[2],
            &[1, 4, 6],
            &[8, 9],
            &[0, 11],
            &[9, 10],
            &[3, 4, 5, 6],
            &[7],
        ];
        let avx2 = Lanes::allowed(true, false).avx2;
        for g in sets.chunks(4) {
            let got = four([g[0], g[1], g[2], g[3]], &m, avx2);
            for (set, got) in g.iter().zip(got) {
                assert_alone(got, set, &m, "");
            }
        }
        if !avx2 {
            eprintln!("no AVX2 here: four at once ran one by one");
        }
    }

    /// Eight clusters at once (AVX-512F's lanes, where the processor has them and they are
    /// allowed; nothing elsewhere) give each cluster's centre alone bit for bit: clusters of
    /// 1 to 8 joints side by side, with a non-finite joint (the prior) and equal rotations
    /// (the prior by the determinant) among them, every set in every lane.
    #[test]
    fn eight_at_once_are_each_alone_bit_for_bit() {
        let mut d: Vec<DualQuat<f32>> = (0..20)
            .map(|j| {
                let axis = Vec3::new(1.0, j as f32, -2.0 + 0.1 * j as f32);
                let q = Quat::from_axis_angle(axis, 0.29 * j as f32).unwrap();
                DualQuat::from_rotation_translation(q, Vec3::new(0.5, j as f32, -1.0))
            })
            .collect();
        d[19].real.w = f32::INFINITY;
        d[18] = d[17];
        let bind: Vec<Vec3<f32>> = (0..20).map(|j| Vec3::new(j as f32, 1.0, -0.5)).collect();
        let m = Motions::new(&d, &bind);
        let sets: [&[u16]; 11] = [
            &[0, 3, 5, 7, 9, 11, 13, 15],
            &[2],
            &[1, 4, 6],
            &[8, 9],
            &[0, 19],
            &[17, 18],
            &[3, 4, 5, 6, 12],
            &[7, 8, 10, 14, 16, 2, 1],
            &[10, 11, 12, 13, 14, 15],
            &[16, 17, 18, 19],
            &[5, 6],
        ];
        // Each width allowed in turn (`Lanes::allowed` keeps those this processor has).
        for widths in [(false, false), (true, false), (true, true)] {
            let lanes = Lanes::allowed(widths.0, widths.1);
            for shift in 0..sets.len() {
                let group: [&[u16]; 8] = core::array::from_fn(|k| sets[(k + shift) % sets.len()]);
                let Some(got) = eight(group, &m, lanes) else {
                    assert!(!lanes.avx512, "eight at once where AVX-512 is allowed");
                    continue;
                };
                assert!(lanes.avx512);
                for (set, got) in group.iter().zip(got) {
                    let what = format!("shift {shift} lanes ({}, {})", lanes.avx2, lanes.avx512);
                    assert_alone(got, set, &m, &what);
                }
            }
        }
        if !Lanes::allowed(true, true).avx512 {
            eprintln!("no AVX-512F here: eight at once did not run (fours do)");
        }
    }

    #[test]
    fn the_centre_is_the_common_fixed_point() {
        // Joints rotating about different axes through the point x (and then all moved by
        // one offset): x is the point they all map to the same place.
        let x = Vec3::new(0.3f32, -1.2, 2.0);
        let q = [
            Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.7).unwrap(),
            Quat::from_axis_angle(Vec3::new(0.0, 1.0, 1.0), -1.1).unwrap(),
            Quat::from_axis_angle(Vec3::new(1.0, -2.0, 0.5), 0.4).unwrap(),
        ];
        let d = q.map(|q| {
            DualQuat::from_rotation_translation(q, x - q.rotate(x) + Vec3::new(0.5, 0.0, 0.1))
        });
        let bind = [
            Vec3::zero(),
            Vec3::new(5.0, 5.0, 5.0),
            Vec3::new(1.0, 0.0, 4.0),
        ];
        // Three joints: x, and only x.
        let r = Clusters::new(1, |_| [0u16, 1, 2]).centres(&d, &bind, false)[0];
        assert!((r - x).norm() < 1e-4, "{r:?}");
        // Two joints agree on the whole line through x along the axis u of their relative
        // rotation; the Tikhonov term picks its point nearest the prior (the mean of the
        // bind origins).
        let two = Clusters::new(1, |_| [0u16, 1]);
        let r = two.centres(&d, &bind, false)[0];
        let u = (q[1].conjugate() * q[0]).vector().normalize().unwrap();
        let prior = Vec3::new(2.5, 2.5, 2.5);
        let want = x + u * (prior - x).dot(u);
        assert!((r - want).norm() < 1e-3, "{r:?} vs {want:?}");
        // Equal rotations (rank 0): the prior itself.
        let r = two.centres(&[d[0], d[0], d[0]], &bind, false)[0];
        assert!((r - prior).norm() < 1e-4, "{r:?}");
        // One joint: the prior, its own origin.
        let one = Clusters::new(1, |_| [2u16]);
        assert!((one.centres(&d, &bind, false)[0] - bind[2]).norm() < 1e-6);
    }

    /// The normal equations summed over the pairs, as defined: `Σ_{a<b} DᵀD` and `−Σ DᵀE`
    /// with `D = R_a − R_b`, `E = t_a − t_b` (before the Tikhonov term).
    fn pairwise(joints: &[u16], d: &[DualQuat<f32>]) -> ([[f64; 3]; 3], [f64; 3]) {
        let m: Vec<Mat4<f32>> = d.iter().map(|d| d.to_matrix4()).collect();
        let (mut a, mut b) = ([[0f64; 3]; 3], [0f64; 3]);
        for (i, ja) in joints.iter().enumerate() {
            for jb in &joints[i + 1..] {
                let (ma, mb) = (&m[usize::from(*ja)], &m[usize::from(*jb)]);
                let dd = |r: usize, c: usize| f64::from(ma.m[r][c] - mb.m[r][c]);
                for (r, (ar, br)) in a.iter_mut().zip(&mut b).enumerate() {
                    for (c, arc) in ar.iter_mut().enumerate() {
                        *arc += (0..3).map(|k| dd(k, r) * dd(k, c)).sum::<f64>();
                    }
                    *br -= (0..3).map(|k| dd(k, r) * dd(k, 3)).sum::<f64>();
                }
            }
        }
        (a, b)
    }

    proptest::proptest! {
        /// The O(n) sums give the pairs' normal equations, and so their solution: the
        /// centre's residual gradient `A r − b` (with the Tikhonov term) vanishes, for 1 to 8
        /// joints of any rotations, some nearly equal.
        #[test]
        fn the_centre_solves_the_pairwise_normal_equations(
            n in 1usize..=8,
            seed in proptest::prelude::any::<u64>(),
            spread in proptest::prop_oneof![proptest::prelude::Just(1e-3f32), 0.01f32..3.0],
        ) {
            use rand::{Rng, SeedableRng};
            let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
            let mut v = || Vec3::new(rng.random_range(-1.0f32..1.0), rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
            let base = Quat::from_axis_angle(v() + Vec3::new(0.0, 0.0, 2.0), 0.8).unwrap();
            let d: Vec<DualQuat<f32>> = (0..n)
                .map(|_| {
                    let axis = v() + Vec3::new(2.0, 0.0, 0.0);
                    let q = base * Quat::from_axis_angle(axis, spread * v().x).unwrap();
                    DualQuat::from_rotation_translation(q, v() * 3.0)
                })
                .collect();
            let joints: Vec<u16> = (0..n as u16).collect();
            let bind: Vec<Vec3<f32>> = (0..n).map(|_| v()).collect();
            let r = rotation_centre(&joints, &Motions::new(&d, &bind)).cast::<f64>().to_array();
            let (a, b) = pairwise(&joints, &d);
            let lambda = 1e-6 * (a[0][0] + a[1][1] + a[2][2]) + 1e-12;
            let mean = bind.iter().fold(Vec3::zero(), |s, o| s + o.cast::<f64>()) * (1.0 / n as f64);
            let p = mean.to_array();
            let scale = a.iter().flatten().fold(lambda, |m, x| m.max(x.abs()));
            for i in 0..3 {
                let g: f64 = (0..3).map(|k| a[i][k] * r[k]).sum::<f64>() + lambda * (r[i] - p[i]) - b[i];
                // f32 centre, f32 inputs: the gradient is small against A's size times |r|;
                // and the O(n) sums `n G − SᵀS`, `n U − SᵀT` cancel terms of the size of G
                // (about n, RᵀR ≈ I) and U (n |t|, |t| < 6) to A's and b's in f64: for joints
                // within 1e-6 rad of each other (A ~ 1e-12) that rounding is what is left.
                let far = 1.0 + r.iter().fold(0f64, |m, x| m.max(x.abs()));
                let size = scale * far;
                let sums = 16.0 * n as f64 * f64::EPSILON * far * 7.0;
                proptest::prop_assert!(g.abs() <= 1e-5 * size + sums, "row {i}: {g} vs {size}, {sums}");
            }
        }
    }

    #[test]
    fn joint_centres_invert_the_bind_matrices() {
        let origin = Vec3::new(1.0f32, 2.0, -3.0);
        let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.4).unwrap();
        let bind = DualQuat::from_rotation_translation(q, origin).to_matrix4();
        let ib = chasles::blend::log::inverse_rigid(&bind);
        let c = joint_centres(&[ib, Mat4::from_rows([[0.0; 4]; 4])]);
        assert!((c[0] - origin).norm() < 1e-5, "{:?}", c[0]);
        assert_eq!(c[1], Vec3::zero(), "a singular matrix gives the origin");
    }
}
