//! DQS's antipodality fix (Kavan et al. 2006, §3 and Kavan's `dqsAntipod`) as a table made
//! once per pose: for a pivot joint a and a joint b, whether `⟨q̂_b, q̂_a⟩ < 0` (real parts),
//! i.e. whether b's weight is negated when a is a vertex's heaviest influence. A vertex then
//! looks its signs up instead of taking three dot products. The dot products are the scalar
//! kernel's (`real_dot`), so the signs are the same bit for bit. The table is made once a
//! pair (the dot product is symmetric bit for bit) by plain loops: for RiggedFigure's 19
//! joints the DQS palette went 1.51 → 0.59 µs a pose and `skin_pose` 3.49 → 2.56 µs, 1.36×
//! on its 370 vertices (`examples/pose_cost`, the two builds in turn; the table was an
//! iterator of closures before, every pair twice).
//!
//! The table holds signed copies: each joint beside its copy with the rotation negated, and
//! for each (pivot, joint) the byte offset of the copy to blend, so that a vertex's blend is
//! a load and a fused multiply-add a register of the joint, with no sign to apply
//! (`w·(−q̂) = (−w)·q̂` exactly, so the bits are those of a negated weight). DQS's copies
//! ([`Antipodes::copies`]) are whole dual quaternions, all 8 floats negated; QLB's and SBS's
//! ([`Antipodes::rows`]) are their rows of 24 floats (rotation, `[R | t]`, bind origin), the
//! rotation alone negated, as the matrices and origins blend with the plain weights.
//!
//! DQS: one core, 54 joints, four influences, the AVX2 build of the DQS kernel alone
//! (`set_avx512(false)`) on the synthetic mesh, the last commit's and this one's in turn (a
//! scratch loop, four runs of 40 passes, medians), 2026-12-04, M vertices/s: 283–286 →
//! 339–352 at 10⁴ and 2.5·10⁴ vertices (in the second-level cache), 266–276 → 327–330 at
//! 10⁵, 249–276 → 289–320 at 2·10⁵. The signs as broadcast weights cost an exclusive or an
//! influence, and the compiler turned each pair of broadcasts from memory (weight, sign)
//! into one broadcast of a register (xor the scalars, then broadcast: on Intel a shuffle,
//! where the loads had cost none of the vector ports); the copies need neither. The loop
//! issues about as many instructions a cycle as the core can take, so each one counts.
//!
//! QLB and SBS read signs (`−0.0` or `+0.0`, applied by an exclusive or and a mask to the
//! rotation's lanes) until 2026-12-05; now their rows' copies. Where no pair of the pose
//! flips (`flips` false: no two joints' quaternions have a negative dot product) they
//! read each joint's unnegated copy without an offset, a load an influence fewer. That is
//! most poses of a character — all but 6 of the built-in characters' 126 poses at 21 times
//! of each clip, those 6 in the Fox's third clip — and every pose of the synthetic rig's
//! default joints (within 60° of the identity). The copies are
//! 32-byte aligned where the palette's rows (`Vec<QlbJoint>`) may lie anywhere: SBS's job
//! reading the palette's rows in place with no signs at all ran 560–581 µs where the
//! aligned copies ran 533–542 (the setting below, a first pair of builds in turn three
//! times). The SBS job alone on the synthetic rig of 10⁵ vertices (a scratch loop of
//! `SkinningJob::run`, best of 30, one core, the builds in turn three times):
//! 646–650 → 550–558 µs; with every odd joint negated (antipodal pairs everywhere, the
//! offsets read) 644–648 → 588–594; QLB 602–667 → 549–552, and with the negated joints
//! 662–669 → 556–559. DQS reads its offsets even where none flips: its copies at `64 j`
//! instead measured the same (313–324 against 315–320 µs a pose).

// Only the x86-64 SIMD kernels read the table; elsewhere it is made empty and left unread.
#![cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]

use super::real_dot;

/// A pose's antipodality table, row `a` for pivot `a`: each joint beside its copy with the
/// rotation negated, and for each (pivot, joint) the offset of the copy to blend. Empty where
/// a table would not pay.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Antipodes {
    /// The joints' copies, 64-byte aligned: joint j's N floats, then the same with the
    /// rotation negated (all 8 for DQS's dual quaternion, the first 4 of QLB's row), at
    /// `8 N j` bytes: every 32-byte register's load lies within one line.
    pub(super) copies: Vec<Line>,
    /// Byte offsets into `copies`: at `a·joints + b`, that of joint b's copy to blend when a
    /// is the pivot, `8 N b` or, where b's weight flips, `8 N b + 4 N` (below 2¹⁶ for
    /// [`MOST_JOINTS`] joints).
    pub(super) at: Vec<u16>,
    /// How many joints the table is for (0: no table).
    pub(super) joints: usize,
    /// Whether any pair's weight flips. Where none does QLB's and SBS's kernels read the
    /// unnegated copies at `8 N j` and not the offsets: a load an influence fewer.
    pub(super) flips: bool,
}

/// 64 bytes of the copies, so that the table starts a cache line.
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(64))]
pub(super) struct Line([f32; 16]);

/// Most joints for which a table is made: 128² offsets are 32 KiB, about what a core's
/// first-level cache holds beside the joints and the vertex stream (and the copies, 16 KiB
/// of dual quaternions or 24 KiB of QLB's rows).
const MOST_JOINTS: usize = 128;

impl Antipodes {
    /// The signed copies of dual quaternions `d` and their offsets (DQS), when it pays: at
    /// most [`MOST_JOINTS`] joints and no more offsets than `vertices` to skin. Otherwise
    /// empty, and the kernel takes the dot products itself.
    pub fn copies(d: &[[f32; 8]], vertices: usize) -> Self {
        let mut t = Self::default();
        t.refill_copies(d, vertices);
        t
    }

    /// [`Antipodes::copies`] in place, keeping the table's capacity (no allocation once a
    /// table of this size has been made).
    pub fn refill_copies(&mut self, d: &[[f32; 8]], vertices: usize) {
        self.fill(d, 8, vertices);
    }

    /// The signed copies of QLB's and SBS's rows (`fast::qlb::Row`: rotation quaternion,
    /// `[R | t]`, bind origin) and their offsets, when it pays, as for
    /// [`Antipodes::copies`]: a copy has its rotation negated and the rest as it is, since
    /// the matrices and origins blend with the plain weights.
    pub fn rows(rows: &[[f32; 24]], vertices: usize) -> Self {
        let mut t = Self::default();
        t.refill_rows(rows, vertices);
        t
    }

    /// [`Antipodes::rows`] in place, keeping the table's capacity.
    pub fn refill_rows(&mut self, rows: &[[f32; 24]], vertices: usize) {
        self.fill(rows, 4, vertices);
    }

    /// The table of joints `d` of N floats (a multiple of 8, so that the copies fill whole
    /// lines), each followed by its copy with the first `negate` floats negated, and the
    /// offsets of the copies to blend.
    fn fill<const N: usize>(&mut self, d: &[[f32; N]], negate: usize, vertices: usize) {
        // Whole lines, and every offset (below 8 N MOST_JOINTS) in the table's u16.
        const { assert!(N.is_multiple_of(8) && 8 * N * MOST_JOINTS <= 1 << 16) };
        if !self.start(d.len(), vertices) {
            return;
        }
        let joints = d.len();
        self.copies.resize(joints * N / 8, Line([0.0; 16]));
        let floats: &mut [f32] = bytemuck::cast_slice_mut(&mut self.copies);
        for (q, two) in d.iter().zip(floats.chunks_exact_mut(2 * N)) {
            let (plain, flipped) = two.split_at_mut(N);
            plain.copy_from_slice(q);
            for (c, (f, x)) in flipped.iter_mut().zip(q).enumerate() {
                *f = if c < negate { -x } else { *x };
            }
        }
        self.at.resize(joints * joints, 0);
        let offset = |j: usize, flips: bool| (8 * N * j + 4 * N * usize::from(flips)) as u16;
        let mut any = false;
        each_pair(d, |a, b, flips| {
            any |= flips;
            self.at[a * joints + b] = offset(b, flips);
            self.at[b * joints + a] = offset(a, flips);
        });
        self.flips = any;
    }

    /// Empties the table and says whether one is to be made for `joints` joints and
    /// `vertices` vertices (then `self.joints` is set).
    fn start(&mut self, joints: usize, vertices: usize) -> bool {
        self.copies.clear();
        self.at.clear();
        self.flips = false;
        let pays = joints <= MOST_JOINTS && joints * joints <= vertices;
        self.joints = if pays { joints } else { 0 };
        self.joints > 0
    }

    /// How many floats a joint of the table has (8 for DQS's copies, 24 for QLB's rows;
    /// 0 without a table): the kernels check that a table is of the form they read.
    pub(super) fn floats(&self) -> usize {
        if self.joints == 0 {
            0
        } else {
            self.copies.len() * 16 / (2 * self.joints)
        }
    }

    /// Whether there is a table (the kernels look at the part they read).
    #[cfg(test)]
    pub fn is_empty(&self) -> bool {
        self.joints == 0
    }
}

/// `f(a, b, ⟨q̂_b, q̂_a⟩ < 0)` for every pair `a ≤ b` of `d`, once: the dot product is
/// symmetric bit for bit (the same four products, summed in the same order), so each pair's
/// sign serves both of its places, half the work of a pose's table (for a character of a
/// few hundred vertices a good part of its pose's cost).
fn each_pair<const N: usize>(d: &[[f32; N]], mut f: impl FnMut(usize, usize, bool)) {
    for (a, pivot) in d.iter().enumerate() {
        for (b, q) in d.iter().enumerate().skip(a) {
            f(a, b, real_dot(q, pivot) < 0.0);
        }
    }
}

/// Runs a SIMD kernel over 1003 vertices with no table (dot products) and with `table`
/// (the pose's, made by [`Antipodes::copies`] or [`Antipodes::rows`] for every vertex),
/// checks that it did the 1000 in whole blocks and that the two ways to the signs gave the
/// same numbers bit for bit, and returns those 1000 results.
#[cfg(all(test, target_arch = "x86_64"))]
pub(super) fn both_ways(
    table: Antipodes,
    run: impl Fn(&Antipodes, &mut [super::Out]) -> usize,
) -> Vec<super::Out> {
    assert!(!table.is_empty());
    let go = |table: &Antipodes| {
        let mut out = vec![[f32::NAN; 6]; 1003];
        assert_eq!(run(table, &mut out), 1000);
        out.truncate(1000);
        out
    };
    let dots = go(&Antipodes::default());
    let looked_up = go(&table);
    let bits = |o: &[super::Out]| o.iter().map(|v| v.map(f32::to_bits)).collect::<Vec<_>>();
    assert_eq!(
        bits(&dots),
        bits(&looked_up),
        "the table and the dot products disagree"
    );
    looked_up
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::{dqs_vertex, dual_quats8, Out};
    use crate::synthetic;

    /// Joints 60° or less from the identity, every odd one negated: the same rigid
    /// transforms, with antipodal pairs everywhere.
    fn flipped(joints: usize) -> (Vec<[f32; 8]>, Vec<[f32; 8]>) {
        let d = dual_quats8(&synthetic::joints(joints, 5));
        let f = d
            .iter()
            .enumerate()
            .map(|(j, q)| if j % 2 == 1 { q.map(|x| -x) } else { *q })
            .collect();
        (d, f)
    }

    /// QLB's rows of joints `d` (bind origins 0.25 j, 0, 1) with their dual quaternions.
    fn rows_of(d: &[[f32; 8]]) -> Vec<[f32; 24]> {
        let d: Vec<chasles::DualQuat<f32>> = d
            .iter()
            .map(|q| chasles::DualQuat::from_array(*q))
            .collect();
        let origins: Vec<chasles::Vec3<f32>> = (0..d.len())
            .map(|j| chasles::Vec3::new(0.25 * j as f32, 0.0, 1.0))
            .collect();
        crate::fast::qlb::rows(&d, &origins)
    }

    /// The floats of joint j's two copies in `t` (N floats each).
    fn copies_of<const N: usize>(t: &Antipodes, j: usize) -> (&[f32], &[f32]) {
        let floats: &[f32] = bytemuck::cast_slice(&t.copies);
        floats[2 * N * j..2 * N * (j + 1)].split_at(N)
    }

    /// Both forms, DQS's dual quaternions (all 8 floats negated in a copy) and QLB's rows
    /// (the rotation alone): each joint is followed by its copy, negated exactly there; each
    /// offset names joint b's copy, negated exactly where `⟨q̂_b, q̂_a⟩ < 0`; `flips` says
    /// whether any pair does; the same rule for when a table pays; a refill for fewer joints
    /// leaves nothing of the last one; the largest table's offsets fit their u16.
    #[test]
    fn the_copies_are_the_joints_signed_as_the_dot_products_say() {
        fn check<const N: usize>(
            make: fn(&[[f32; N]], usize) -> Antipodes,
            refill: fn(&mut Antipodes, &[[f32; N]], usize),
            of: fn(&[[f32; 8]]) -> Vec<[f32; N]>,
            negate: usize,
        ) {
            let (d, f) = flipped(54);
            let (plain, signed) = (of(&d), of(&f));
            for (joints, flips) in [(&plain, false), (&signed, true)] {
                let mut t = make(joints, usize::MAX);
                assert_eq!((t.joints, t.at.len(), t.flips), (54, 54 * 54, flips));
                assert_eq!(t.copies.len() * 16, 54 * 2 * N);
                assert_eq!(t.copies.as_ptr() as usize % 64, 0);
                for (j, q) in joints.iter().enumerate() {
                    let (as_is, copy) = copies_of::<N>(&t, j);
                    let bits = |x: &[f32]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(as_is), bits(q), "joint {j}");
                    for c in 0..N {
                        let want = if c < negate { -q[c] } else { q[c] };
                        assert_eq!(copy[c].to_bits(), want.to_bits(), "joint {j}, float {c}");
                    }
                }
                // Unflipped, every pair is within 2 rad of rotation, so ⟨q̂_a, q̂_b⟩ > 0: a
                // weight flips exactly when one of the two joints was negated.
                for a in 0..54 {
                    for b in 0..54 {
                        let flips = flips && (a + b) % 2 == 1;
                        let at = usize::from(t.at[a * 54 + b]);
                        assert_eq!(at, 8 * N * b + if flips { 4 * N } else { 0 }, "{a} {b}");
                    }
                }
                // No table where it would not pay: more offsets than vertices, or too many
                // joints.
                assert!(make(joints, 54 * 54 - 1).is_empty());
                assert!(make(&[joints[0]; MOST_JOINTS + 1], usize::MAX).is_empty());
                refill(&mut t, &joints[..3], usize::MAX);
                assert_eq!(
                    (t.joints, t.copies.len() * 16, t.at.len()),
                    (3, 3 * 2 * N, 9)
                );
                // Joints 1 and 2 of the negated ones flip against each other.
                assert_eq!((t.flips, t.floats()), (flips, N));
                refill(&mut t, joints, 10);
                assert!(t.is_empty() && t.copies.is_empty() && t.at.is_empty() && !t.flips);
            }
            // A table remade for joints with no antipodal pair after one with them.
            let mut t = make(&signed, usize::MAX);
            refill(&mut t, &plain, usize::MAX);
            assert!(!t.flips && t.at.iter().all(|&at| usize::from(at) % (8 * N) == 0));
            // The last joint flipped for pivot 0 in the largest table.
            let alternate: Vec<[f32; N]> = (0..MOST_JOINTS).map(|j| signed[j % 2]).collect();
            let most = make(&alternate, usize::MAX);
            assert_eq!(
                usize::from(most.at[MOST_JOINTS - 1]),
                8 * N * MOST_JOINTS - 4 * N
            );
        }
        check::<8>(
            Antipodes::copies,
            Antipodes::refill_copies,
            |d| d.to_vec(),
            8,
        );
        check::<24>(Antipodes::rows, Antipodes::refill_rows, rows_of, 4);
    }

    #[test]
    fn negated_joints_skin_the_same_with_and_without_the_table() {
        let rig = synthetic::rig(1003, 54, 5);
        let (d, f) = flipped(54);
        let want: Vec<Out> = rig.vertices().iter().map(|v| dqs_vertex(v, &d)).collect();
        let scalar: Vec<Out> = rig.vertices().iter().map(|v| dqs_vertex(v, &f)).collect();
        for (a, b) in want.iter().zip(&scalar) {
            for k in 0..6 {
                assert!((a[k] - b[k]).abs() < 1e-5, "{a:?} {b:?}");
            }
        }
        #[cfg(target_arch = "x86_64")]
        if crate::fast::simd(4) {
            // SAFETY: the processor has AVX2 and FMA (`simd`), the synthetic rig's joint
            // indices are below 54, the table is empty or made from `f`.
            let looked_up = both_ways(Antipodes::copies(&f, usize::MAX), |table, out| unsafe {
                crate::fast::avx2::dqs(
                    rig.vertices(),
                    &f,
                    table,
                    crate::fast::dest::Dest::packed(out),
                    false,
                )
            });
            // The two ways to the signs gave the same blends, bit for bit (`both_ways`), and
            // the SIMD kernel (fused multiply-adds) is the scalar one to rounding.
            for (a, b) in looked_up.iter().zip(&scalar) {
                for k in 0..6 {
                    assert!((a[k] - b[k]).abs() < 2e-6, "{a:?} {b:?}");
                }
            }
        } else {
            eprintln!("no AVX2+FMA here: only the scalar kernel is checked");
        }
    }
}
