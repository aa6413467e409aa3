//! The centres that decomposed blends rotate about (Kavan et al. 2006, §2.2 and §6: Dec and
//! QLB are coordinate dependent, so skinning must choose a centre per vertex).
//!
//! * [`joint_centres`] — each joint's origin in the bind pose; decomposed QLB (Hejl 2004)
//!   rotates a vertex about the weighted mean of its joints' origins.
//! * [`Clusters`] — spherical blend skinning (Kavan & Žára 2005) groups the vertices bound
//!   to the same set of joints and gives each cluster one *rotation centre* per pose: the
//!   point r whose images under the cluster's joint transforms agree best,
//!   `min Σ_{a<b} ‖(R_a − R_b) r + t_a − t_b‖²`. The 3×3 normal equations are solved in f64
//!   with a small Tikhonov term (1e-6 of the trace, at least 1e-12) pulling r towards the
//!   mean of the cluster's joint origins (`prior`), where the problem is rank-deficient
//!   (the paper takes the SVD's pseudo-inverse; along a deficient direction the blend does
//!   not depend on r). A cluster of one joint moves rigidly, about any centre: its prior.
//!
//! The normal equations are summed in O(n) for n joints, not over the n(n−1)/2 pairs:
//! with `S = Σ R_a`, `T = Σ t_a`, `G = Σ R_aᵀR_a` and `U = Σ R_aᵀ t_a`,
//!
//! ```text
//! Σ_{a<b} (R_a − R_b)ᵀ(R_a − R_b) = n G − SᵀS,   Σ_{a<b} (R_a − R_b)ᵀ(t_a − t_b) = n U − SᵀT
//! ```
//!
//! (half the sum over all ordered pairs). `G` is `n I` for rotations. Each joint's `R` is
//! made in f64 from its dual quaternion normalized in f64 ([`Motions`]), so `RᵀR = I` to
//! f64's rounding (the test `motions_are_rigid_to_f64s_rounding`: within 1e-15) and the
//! solve takes `n² I − SᵀS`: the null direction of two joints (their relative rotation's
//! axis) keeps an eigenvalue of f64's rounding (about n²·1e-16), below the Tikhonov term
//! (at least 1e-12). For one joint that rounding is all of A, and A is made exactly 0 (the
//! centre is the prior). Where n ≥ 2 joints turn alike, A is all rounding too, and the
//! centre lands off the prior by about n²·1e-4 (|prior| + |t|) (the old sums of G left a
//! sixth to a half of that, in a review's simulation of two to eight joints): harmless, as
//! the blend of equal rotations does not depend on the centre, nor does it along a free
//! axis.
//! Until 2026-12-05 the motions were the f32 matrices of the dual quaternions, orthogonal
//! only to f32's rounding, where `n² I − SᵀS` would give that direction an eigenvalue of
//! about 1e-7 — as large as the Tikhonov term — so each motion carried its `RᵀR` and the
//! solve summed G as well; with the bind origins that was three 512-bit registers a joint.
//! Now a motion is `R`, `t` and `Rᵀt` (15 f64, two registers), and each cluster's prior is
//! made once, on its first solve (`Clusters::centres_into`: eight clusters' priors side by
//! side in f32, as the lanes load them): the pose's solve on the synthetic rig below
//! 867–945 → 764–824 µs and, on a quieter machine, 845–868 → 746–770 (best of 30, three
//! rounds, the builds in turn three times and twice), SBS's whole pose 1627–1725 →
//! 1532–1592 and 1526–1561 → 1425–1486 µs, DQS 4.31–4.78× → 4.01–4.50× and 4.60–4.86× →
//! 4.24–4.41× SBS (DQS 322–400 µs in those runs). Then the lanes' centres went straight
//! from their registers into the padded table (`Clusters::centres_into`), where they had
//! gone out a float at a time through an array of `Vec3`s and a caller's closure (a fifth
//! of the solve's samples under `perf record`): the solve 771–789 → 697–704 µs, SBS's
//! pose 1478–1524 → 1411–1464, DQS 4.25–4.42× → 4.16–4.34× SBS (best of 30, the builds in
//! turn twice; the old build's first two rounds, still warming up, left out). In `chasles
//! skin --bench`'s interleaved rounds, which start each kernel
//! with others' data in the caches: SBS 59.8–61.1 → 64.0–67.3 M vertices/s at 10⁵ vertices
//! (three runs each in turn), but 69.7–73.9 → 68.0–72.6 at 10⁶ (302 905 clusters, four
//! runs), where the priors' table (3.6 MB) comes from memory each pose and takes back what
//! the arithmetic saves (a warm loop at 10⁶: the solve 3087–3242 → 2569–2580 µs). Each
//! motion sits on whole cache lines (the sums' 64-byte loads straddled two lines wherever
//! the allocator put the vector, and the solve took 1.2 times as long in those runs), and
//! the system is solved by its adjugate with one division — four clusters at once in
//! AVX2's f64 lanes where the
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
//! clusters: 96 adds of the sums, 72 shuffles of the transposes, the rest the solve; 64
//! and 48 since the motions lost G and the origins):
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
//! * The division `1/n` (of the prior, before it was made once) as a multiplication, a
//!   bound with wrong numbers: 864–883 against 870–896 µs a pose (1–2 %, 2026-12-05).
//! * Eight groups of eight a call, every group solved up to its division before the
//!   groups' divisions, choices and stores (a fifth of the solve's samples sat on the
//!   instruction after the division, which ends each group's chain): 697–704 → 835–838 µs
//!   a pose (2026-12-05, the builds in turn twice), and 939–943 while the joints' lists
//!   were made in the AVX-512 function, where the array's `from_fn` stayed a call.
//! * The priors' table in rows aligned to 32 bytes, so that no load of eight priors spans
//!   two lines: 603–628 against 611–629 µs (2026-12-05, five runs each in turn).
//!
//! SBS's pose on that rig is now a little more this solve (about 640 µs) than the skinning
//! job (about 550, since it reads the pose's signed copies of the rows, `fast/antipodes.rs`;
//! DQS about 320), both at QLB's speed or near it (the job blends four floats of quaternion
//! and twelve of matrix a joint where DQS blends eight). A sixth of the solve's samples sit
//! on the instruction after its one division (an f64 division of eight lanes, 23 cycles'
//! latency at the end of each group's chain); a reciprocal by Newton's steps would take as
//! long and give other bits than the scalar solve.
//!
//! **In the bench's rounds** (2026-12-05). `chasles skin --bench` runs a dozen kernels
//! between two of SBS's poses, and there the solve took 1.6 times its back-to-back time,
//! where every other method's pose took its own within 2 % (`examples/pose_rounds`, 2·10⁵
//! synthetic vertices, 148 263 clusters: SBS's palette, nearly all of it the solve,
//! 1.88–1.97 ms in the rounds against 1.12–1.18 back to back). It walks four tables at once, 40 bytes a cluster, and the
//! processor's prefetchers did not bring them in time once the other kernels had pushed
//! them out of the caches. Now each group of eight asks the cache for the tables of the
//! group 16 ahead (`Clusters::ask_ahead`; 8 and 32 ahead measured the same): the solve in
//! the rounds 1.67–1.74 → 1.05–1.07 ms, back to back unchanged (a scratch copy of the
//! rounds, three runs each in turn). And the centres are written once, into a table that
//! may start uninitialized (`Clusters::centres_vec`), where a fresh palette had its
//! 2.4 MB of centres zeroed first: the palette 1.49–1.53 → 1.27–1.31 ms in the rounds and
//! 1.21–1.26 → 1.18–1.19 back to back (one binary, the two ways in turn three times). Both
//! together (`examples/pose_rounds`, the builds in turn three times): SBS's palette in the
//! rounds 1.88–1.97 → 1.29–1.39 ms and its pose 3.05–3.21 → 2.47–2.65; in `chasles skin
//! --bench --bench-vertices 100000,200000 --bench-threads 1 --bench-rounds 31` (four runs
//! each in turn) SBS 59.4–64.9 → 72.1–78.2 M vertices/s at 2·10⁵ and DQS 4.1–4.5× →
//! 3.4–3.5× SBS there, 4.2–4.4× → 3.7–3.9× at 10⁵; at 10⁶ (`--bench-threads 1,2
//! --bench-rounds 11`, one run each) 68.2 → 72.9 on one thread and 138.7 → 152.7 on two;
//! CesiumMan unchanged (`--rig`, 153.0 and 151.2). Tried again the same day, and not kept
//! again (see above): eight groups a call, all their sums before all their solves, 1.1 →
//! 1.6 ms or more back to back; the motions read without bounds checks, 3 %; the centres'
//! slots asked for with the hint to write (`prefetchw`), the palette in the rounds
//! 1.23–1.30 against 1.20–1.27 ms (three runs each in turn).
//!
//! **A group ahead** (2026-12-05). Where AVX-512 runs, one call now solves a batch of up
//! to 16 groups of eight (`wide::eights`; a batch is also a thread's unit of work), each
//! group's system — its sums, transposes and normal equations with the Tikhonov term,
//! twelve registers of lanes — made before the group before it is solved, picked and
//! stored, so that one group's division runs while the next group's loads and sums come
//! in (as the skinning kernels' loops take their next block ahead: `fast::avx2`'s module
//! docs). Unlike the eight groups a call above, one group's system waits at a time. SBS's
//! palette alone at 10⁵ vertices (85 709 clusters; a scratch loop, best of 30, the builds
//! in turn three times, twice): 632–670 → 573–591 µs, with batches of 64 groups (16, for
//! more threads' work on smaller rigs, measured the same: 556–585 against 558–574 µs,
//! three runs each in turn). Made first with arrays' `map` in
//! `system` and a closure for a group's joints, both stayed calls compiled without
//! AVX-512, their lanes' operations calls, and the palette took 1.2 ms; they are written
//! out. Tried and not kept: the adjugate and determinant made ahead as well (13 registers
//! carried), 570–586 against 573–590 µs.
//!
//! The reference and fast paths share this code, so their centres are the same numbers.
//! (Past 500 lines for these docs: what was measured and tried, kept beside the code.)

use chasles::{DualQuat, Mat4, Vec3};
use rayon::prelude::*;
use std::collections::HashMap;
use std::mem::MaybeUninit;
use std::ops::{Add, Div, Mul, Sub};
use std::sync::OnceLock;

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
#[derive(Debug, Clone, Default)]
pub struct Clusters {
    /// The cluster of each vertex.
    of_vertex: Vec<u32>,
    /// The sorted joints of cluster c: `joints[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    joints: Vec<u16>,
    /// One past the highest joint index in `joints` (0 for none; at most 2¹⁶).
    top: u32,
    /// Each cluster's prior (`prior`) for the bind origins of the first solve, made then
    /// (the bind origins of a rig do not change from pose to pose); boxed, so that a
    /// clustering not yet solved stays small.
    priors: OnceLock<Box<PriorTable>>,
}

/// Clusters are equal where they group the vertices alike (`top` follows from the joints,
/// and the priors made are a cache).
impl PartialEq for Clusters {
    fn eq(&self, other: &Self) -> bool {
        (&self.of_vertex, &self.start, &self.joints)
            == (&other.of_vertex, &other.start, &other.joints)
    }
}

/// The bind origins a clustering's priors were made for, and the priors, eight clusters a
/// row.
type PriorTable = (Vec<Vec3<f32>>, Vec<Priors>);

/// The priors of eight clusters side by side (x, y, z, each of eight lanes), as the
/// eight-lane solve loads them.
type Priors = [[f32; 8]; 3];

/// How many groups of eight clusters ahead the solve asks the cache for their tables
/// (`Clusters::ask_ahead`; 8 and 32 measured the same).
const AHEAD: usize = 16;

/// A cluster's centre as the solve writes it, padded to four floats (the fourth 0), into a
/// table that may start uninitialized ([`Clusters::centres_vec`]).
type Slot = MaybeUninit<[f32; 4]>;

/// Groups of eight clusters a call of the eight-lane solve (`wide::eights`), and a
/// thread's unit of work: 128 clusters.
const BATCH: usize = 16;

/// Clusters at least this many (two batches) are solved on all threads.
const PARALLEL: usize = 2 * 8 * BATCH;

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
            top: 0,
            priors: OnceLock::new(),
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
        out.top = out.joints.iter().max().map_or(0, |&j| u32::from(j) + 1);
        out
    }

    /// The number of clusters.
    pub fn len(&self) -> usize {
        // `Clusters::default()` has no `start` at all.
        self.start.len().saturating_sub(1)
    }

    /// Whether there are no clusters (no vertices).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// One past the highest joint index any cluster names (0 for none): the joint
    /// transforms a solve needs at least.
    pub fn joint_count(&self) -> usize {
        self.top as usize
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
        let mut out: Vec<[f32; 4]> = Vec::new();
        self.centres_vec(d, bind, parallel, &mut out);
        out.iter().map(|c| Vec3::new(c[0], c[1], c[2])).collect()
    }

    /// [`Clusters::centres_into`] into `v`, emptied and refilled (its capacity kept), one
    /// entry a cluster: entries of any plain type of four floats' size (the palette's
    /// [`crate::fast::RotationCentre`], `[f32; 4]`), each written once, with no zeros
    /// written first (at 2·10⁵ synthetic vertices, 1.5·10⁵ clusters, those zeros cost 30–70
    /// µs a pose back to back and about 220 in `chasles skin --bench`'s rounds: module docs).
    pub(crate) fn centres_vec<T: bytemuck::Pod>(
        &self,
        d: &[DualQuat<f32>],
        bind: &[Vec3<f32>],
        parallel: bool,
        v: &mut Vec<T>,
    ) {
        const {
            assert!(size_of::<T>() == size_of::<[f32; 4]>());
            assert!(align_of::<T>().is_multiple_of(align_of::<[f32; 4]>()));
        };
        let n = self.len();
        v.clear();
        v.reserve(n);
        let spare = &mut v.spare_capacity_mut()[..n];
        // SAFETY: `MaybeUninit<T>` is laid out as `T`, which is as large as `[f32; 4]` and
        // at least as aligned (checked above), so the n slots are n slots of
        // `MaybeUninit<[f32; 4]>`, borrowed from `v` for this call alone.
        let slots = unsafe { std::slice::from_raw_parts_mut(spare.as_mut_ptr().cast::<Slot>(), n) };
        self.centres_into(d, bind, parallel, slots);
        // SAFETY: `centres_into` wrote every one of the n slots (each group of eight, or
        // the last few, in full), and a `T` (`Pod`) is valid for any bytes.
        unsafe { v.set_len(n) };
    }

    /// [`Clusters::centres`] into `out`, one entry a cluster, each centre padded to four
    /// floats (the fourth 0), as the fast path's palette holds them: no vector of centres
    /// made on the way (on a rig of 85 582 clusters that vector and its padded copy were
    /// 2.4 MB a pose), and the lanes' centres stored straight from their registers (module
    /// docs). Every slot is written, once, so `out` may start uninitialized
    /// ([`Clusters::centres_vec`]).
    ///
    /// # Panics
    /// If `out.len()` is not `self.len()` (the callers size it so).
    pub(crate) fn centres_into(
        &self,
        d: &[DualQuat<f32>],
        bind: &[Vec3<f32>],
        parallel: bool,
        out: &mut [Slot],
    ) {
        assert_eq!(out.len(), self.len(), "one centre a cluster");
        let motions = Motions::new(d);
        // The priors made on the first solve, or made again for other bind origins.
        let (made_for, made) = &**self
            .priors
            .get_or_init(|| Box::new((bind.to_vec(), self.prior_table(bind))));
        let other;
        let priors: &[Priors] = if same_bits(made_for, bind) {
            made
        } else {
            other = self.prior_table(bind);
            &other
        };
        // The lanes where the fast path's SIMD kernels run (and not where `fast::set_simd`
        // or `fast::set_avx512` forbid them, so that the fallback is measured whole).
        let lanes = Lanes::allowed(crate::fast::uses_simd(4), crate::fast::uses_avx512(4));
        // Every slot of `out` is written once, straight from the lanes (it may start
        // uninitialized: no table of zeros is written first each pose). A group of eight
        // clusters that `eights` did not take: four at a time in AVX2's lanes, and the last
        // few one by one.
        let group = |g: usize, out: &mut [Slot]| {
            let c = 8 * g;
            self.ask_ahead(g, priors, out.as_ptr().cast());
            let joints = |k: usize| self.joints(c + k);
            let p = &priors[g];
            for (h, out) in out.chunks_mut(4).enumerate() {
                let joints = |k: usize| joints(4 * h + k);
                let p = p.map(|x| [0, 1, 2, 3].map(|k| x[4 * h + k]));
                if let Ok(out) = <&mut [Slot; 4]>::try_from(&mut *out) {
                    four([0, 1, 2, 3].map(joints), &motions, &p, lanes.avx2, out);
                } else {
                    for (k, o) in out.iter_mut().enumerate() {
                        let prior = Vec3::new(p[0][k], p[1][k], p[2][k]);
                        o.write(pad(centre_about(joints(k), &motions, prior)));
                    }
                }
            }
        };
        // A batch's whole groups of eight in one call where AVX-512 may run (`eights`: each
        // group's system made before the group before it is solved), the rest a group at
        // a time.
        let batch = |(k, out): (usize, &mut [Slot])| {
            let g0 = k * BATCH;
            let done = eights(self, g0, &motions, priors, lanes, out);
            for (h, out) in out[done..].chunks_mut(8).enumerate() {
                group(g0 + done / 8 + h, out);
            }
        };
        if parallel && self.len() >= PARALLEL {
            out.par_chunks_mut(8 * BATCH).enumerate().for_each(batch);
        } else {
            out.chunks_mut(8 * BATCH).enumerate().for_each(batch);
        }
    }

    /// Asks the cache for what the solve of group `g + AHEAD` (eight clusters a group) reads
    /// and writes — its priors, its starts in the joint list, its first joints and its
    /// centres' slots (`out` being group g's) — so that the solve finds them there. It
    /// walks four tables at once, 40 bytes a cluster (a start 4, joints 8, a prior 12, a
    /// centre 16), at some 7 ns a cluster, and the processor's own prefetchers did not keep
    /// them coming: with the tables out of the cache (as in `chasles skin --bench`'s rounds,
    /// where a dozen kernels run between two of SBS's poses) the solve took 1.6 times its
    /// time in a warm loop, and with these requests the same time (module docs). Harmless
    /// where the tables are in the cache; nothing on targets without a prefetch here
    /// ([`crate::fast::ask_cache`]).
    #[inline(always)]
    fn ask_ahead(&self, g: usize, priors: &[Priors], out: *const [f32; 4]) {
        use crate::fast::ask_cache;
        // A group's priors (96 bytes) and centres (128) lie on two or three lines (the
        // tables are 4-byte aligned), of which these are two and the next group's requests
        // the rest; its starts (32) and joints (some 64) on one or two.
        let priors = priors.as_ptr().wrapping_add(g + AHEAD).cast::<u8>();
        let out = out.wrapping_add(8 * AHEAD).cast::<u8>();
        for at in [0, 64] {
            ask_cache(priors.wrapping_add(at));
            ask_cache(out.wrapping_add(at));
        }
        let c = 8 * (g + AHEAD);
        ask_cache(self.start.as_ptr().wrapping_add(c));
        if let Some(&j) = self.start.get(c) {
            ask_cache(self.joints.as_ptr().wrapping_add(j as usize));
        }
    }

    /// Every cluster's [`prior`] for the bind origins `bind`, eight clusters a row (the last
    /// row's unused lanes 0).
    ///
    /// # Panics
    /// If a joint index is not below `bind.len()` (the callers check rigs first).
    fn prior_table(&self, bind: &[Vec3<f32>]) -> Vec<Priors> {
        let mut table = vec![[[0f32; 8]; 3]; self.len().div_ceil(8)];
        for c in 0..self.len() {
            let p = prior(self.joints(c), bind);
            for (i, row) in table[c / 8].iter_mut().enumerate() {
                row[c % 8] = p.get(i);
            }
        }
        table
    }
}

/// Whether `a` and `b` hold the same points bit for bit (a NaN origin is its own, and
/// −0 is not +0: each gives its own priors' bits).
fn same_bits(a: &[Vec3<f32>], b: &[Vec3<f32>]) -> bool {
    let bits = |v: &Vec3<f32>| v.to_array().map(f32::to_bits);
    a.len() == b.len() && a.iter().zip(b).all(|(a, b)| bits(a) == bits(b))
}

/// The point a cluster's centre is pulled towards along the directions its joints leave
/// free: the mean of its joints' bind origins (in f64, in the joints' order, then rounded
/// to f32); the origin for no joints.
///
/// # Panics
/// If a joint index is not below `bind.len()` (the callers check rigs first).
pub(crate) fn prior(joints: &[u16], bind: &[Vec3<f32>]) -> Vec3<f32> {
    let sum = joints
        .iter()
        .fold(Vec3::<f64>::zero(), |s, &j| s + bind[usize::from(j)].cast());
    (sum * (1.0 / (joints.len() as f64).max(1.0))).cast()
}

/// One joint of a pose as the centre solve sums it, in f64: its rotation R (rows, 0–8),
/// its translation t (9–11) and `Rᵀt` (12–14); 15 is 0. One flat array of two cache lines,
/// so a cluster's sum over its joints is a vector loop of two 512-bit additions a joint.
/// R is made in f64 from the joint's dual quaternion, normalized in f64, so `RᵀR = I` to
/// f64's rounding (module docs).
type Motion = [f64; FIELDS];

/// The fields of a [`Motion`].
const FIELDS: usize = 16;
/// Where the parts of a [`Motion`] start.
const R: usize = 0;
const T: usize = 9;
const U: usize = 12;

/// The lower triangle of `MᵀM` and `Mᵀt` for a 3×3 matrix M given by its rows, by one
/// order of operations (so a cluster of one joint gets `b = SᵀT − n U` exactly 0).
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
    /// `min(self, 1)`.
    fn at_most_one(self) -> Self;
}

impl Num for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn at_most_one(self) -> Self {
        self.min(1.0)
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
    /// quaternion, normalized in f64). A dual quaternion that cannot be normalized
    /// (non-finite, or a zero real part) gives a motion of NaN, whose clusters take their
    /// prior.
    pub fn new(d: &[DualQuat<f32>]) -> Self {
        let lines = d
            .iter()
            .map(|d| {
                let Ok(unit) = d.cast::<f64>().normalize() else {
                    return Lines([f64::NAN; FIELDS]);
                };
                let m = unit.to_matrix4();
                let mut x = [0f64; FIELDS];
                for i in 0..3 {
                    for k in 0..3 {
                        x[R + 3 * i + k] = m.m[i][k];
                    }
                    x[T + i] = m.m[i][3];
                }
                let (_, u) = gram(
                    core::array::from_fn(|i| x[R + i]),
                    core::array::from_fn(|i| x[T + i]),
                );
                x[U..U + 3].copy_from_slice(&u);
                Lines(x)
            })
            .collect();
        Motions(lines)
    }

    /// The motion of joint `j`.
    ///
    /// # Panics
    /// If `j` is not below the number of motions.
    #[inline(always)]
    fn of(&self, j: u16) -> &Motion {
        &self.0[usize::from(j)].0
    }
}

/// The rotation centre of one cluster of a pose's `motions`:
/// `min Σ_{a<b} ‖(R_a − R_b) r + t_a − t_b‖²`, with a Tikhonov pull (1e-6 of the trace, at
/// least 1e-12) towards the prior, the mean of the joints' origins in `bind` rounded to
/// f32, for the rank-deficient directions; that prior where the system cannot be solved
/// (non-finite motions).
///
/// # Panics
/// If a joint index is not below the number of motions and of bind origins (the callers
/// check rigs first).
pub fn rotation_centre(joints: &[u16], motions: &Motions, bind: &[Vec3<f32>]) -> Vec3<f32> {
    centre_about(joints, motions, prior(joints, bind))
}

/// [`rotation_centre`] with its prior given.
fn centre_about(joints: &[u16], motions: &Motions, prior: Vec3<f32>) -> Vec3<f32> {
    let mut sum = [0f64; FIELDS];
    for &j in joints {
        for (s, m) in sum.iter_mut().zip(motions.of(j)) {
            *s += m;
        }
    }
    let prior = prior.cast::<f64>().to_array();
    let (x, det) = solve(|i| sum[i], joints.len() as f64, prior);
    pick(x, prior, det)
}

/// The solution where the determinant is positive and finite, else the prior.
#[inline(always)]
fn pick(x: [f64; 3], prior: [f64; 3], det: f64) -> Vec3<f32> {
    let ok = det > 0.0 && det.is_finite();
    Vec3::from_array(if ok { x } else { prior }).cast()
}

/// The normal equations of a cluster from the sums `f(i)` of its joints' motions (the
/// fields of a [`Motion`]) over its `n` joints, with the Tikhonov term towards `prior`,
/// solved: the solution and the determinant.
#[inline(always)]
fn solve<X: Num>(f: impl Fn(usize) -> X, n: X, prior: [X; 3]) -> ([X; 3], X) {
    let (a, b) = system(f, n, prior);
    solve_symmetric(a, b)
}

/// [`solve`]'s normal equations with the Tikhonov term: A's lower triangle and b. Apart, so
/// that the eight-lane solve can make a group's system before it ends the group before
/// (`wide::eights`).
#[inline(always)]
fn system<X: Num>(f: impl Fn(usize) -> X, n: X, prior: [X; 3]) -> ([X; 6], [X; 3]) {
    // A = n G − SᵀS with G = Σ RᵀR = n I (the rotations are exact to f64's rounding), and
    // b = −(n U − SᵀT).
    // Written out, without arrays' `map`: in the eight-lane solve of several groups a
    // call (`wide::eights`) the maps stayed calls, and the lanes' operations in them.
    let r = |i: usize| f(R + i);
    let (sts, stt) = gram(
        [r(0), r(1), r(2), r(3), r(4), r(5), r(6), r(7), r(8)],
        [f(T), f(T + 1), f(T + 2)],
    );
    let (nn, zero) = (n * n, X::splat(0.0));
    // One joint: A = I − RᵀR is rounding alone (about 1e-16, against the Tikhonov term's
    // floor of 1e-12), so it is made 0 (n − 1 is 0 there and at least 1 from two joints
    // on): the centre is the prior. No joints (n − 1 = −1): A is 0 already, and the centre
    // the prior, the origin.
    let many = (n - X::splat(1.0)).at_most_one();
    let mut a = [
        (nn - sts[0]) * many,
        (zero - sts[1]) * many,
        (nn - sts[2]) * many,
        (zero - sts[3]) * many,
        (zero - sts[4]) * many,
        (nn - sts[5]) * many,
    ];
    let bi = |i: usize| stt[i] - n * f(U + i);
    let mut b = [bi(0), bi(1), bi(2)];
    let lambda = X::splat(1e-6) * (a[0] + a[2] + a[5]) + X::splat(1e-12);
    for (i, d) in [0, 2, 5].into_iter().enumerate() {
        a[d] = a[d] + lambda;
        b[i] = b[i] + lambda * prior[i];
    }
    (a, b)
}

/// A centre padded to four floats, the fourth 0.
#[inline(always)]
fn pad(c: Vec3<f32>) -> [f32; 4] {
    [c.x, c.y, c.z, 0.0]
}

/// Four clusters' centres about their priors (x, y, z, four lanes each) into `out`, padded:
/// in AVX2 registers where the processor has them (`avx2`, checked once by the caller:
/// [`wide::four`]), else one by one; the same numbers either way.
fn four(
    joints: [&[u16]; 4],
    motions: &Motions,
    priors: &[[f32; 4]; 3],
    avx2: bool,
    out: &mut [Slot; 4],
) {
    #[cfg(target_arch = "x86_64")]
    if avx2 {
        // SAFETY: the caller found AVX2 on this processor.
        return unsafe { wide::four(joints, motions, priors, out) };
    }
    let _ = avx2;
    for (k, o) in out.iter_mut().enumerate() {
        let p = Vec3::new(priors[0][k], priors[1][k], priors[2][k]);
        o.write(pad(centre_about(joints[k], motions, p)));
    }
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

/// The whole groups of eight clusters in `out` (groups `g0` on) solved by
/// [`wide::eights`] where AVX-512 is allowed; returns how many slots it wrote (none
/// elsewhere: the caller solves them a group at a time, to the same numbers).
fn eights(
    clusters: &Clusters,
    g0: usize,
    motions: &Motions,
    priors: &[Priors],
    lanes: Lanes,
    out: &mut [Slot],
) -> usize {
    #[cfg(target_arch = "x86_64")]
    if lanes.avx512 {
        let whole = out.len() / 8 * 8;
        // SAFETY: `Lanes::allowed` found AVX-512F on this processor; `whole` is a multiple
        // of 8, and its groups are whole groups of `clusters` (the caller's `out` starts at
        // group `g0` and holds one slot a cluster).
        unsafe { wide::eights(clusters, g0, motions, priors, &mut out[..whole]) };
        return whole;
    }
    let _ = (clusters, g0, motions, priors, lanes.avx512, out);
    0
}

#[cfg(target_arch = "x86_64")]
mod wide;

/// Slots holding centres of NaN, for the tests to have written over.
#[cfg(test)]
fn nan_slots<const N: usize>() -> [Slot; N] {
    [Slot::new([f32::NAN; 4]); N]
}

/// The centres in `slots`.
///
/// # Safety
/// Every slot must hold a value (as those of [`nan_slots`] do, written over or not).
#[cfg(test)]
unsafe fn read_slots<const N: usize>(slots: [Slot; N]) -> [[f32; 4]; N] {
    // SAFETY: the caller's.
    slots.map(|s| unsafe { s.assume_init() })
}

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
mod tests;
