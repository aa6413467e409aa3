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
//! Two forms. QLB and SBS read signs (`−0.0` or `+0.0`, applied by an exclusive or) from
//! [`Antipodes::new`]. DQS reads [`Antipodes::copies`]: each joint's dual quaternion and its
//! negation side by side, and for each (pivot, joint) the byte offset of the copy to blend,
//! so that a vertex's blend is one load and one fused multiply-add an influence, with no
//! sign to apply (`w·(−q̂) = (−w)·q̂` exactly, so the bits are those of a negated weight).
//! One core, 54 joints, four influences, the AVX2 build of the DQS kernel alone
//! (`set_avx512(false)`) on the synthetic mesh, the last commit's and this one's in turn (a
//! scratch loop, four runs of 40 passes, medians), 2026-12-04, M vertices/s: 283–286 →
//! 339–352 at 10⁴ and 2.5·10⁴ vertices (in the second-level cache), 266–276 → 327–330 at
//! 10⁵, 249–276 → 289–320 at 2·10⁵. The signs as broadcast weights cost an exclusive or an
//! influence, and the compiler turned each pair of broadcasts from memory (weight, sign)
//! into one broadcast of a register (xor the scalars, then broadcast: on Intel a shuffle,
//! where the loads had cost none of the vector ports); the copies need neither. The loop
//! issues about as many instructions a cycle as the core can take, so each one counts.

// Only the x86-64 SIMD kernels read the table; elsewhere it is made empty and left unread.
#![cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]

use super::real_dot;

/// A pose's antipodality table, row `a` for pivot `a`: signs (QLB, SBS) or signed copies
/// and their offsets (DQS). Empty where a table would not pay.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Antipodes {
    /// [`Antipodes::new`]'s signs: `−0.0` where the weight flips, `+0.0` where it stays.
    pub(super) signs: Vec<f32>,
    /// [`Antipodes::copies`]' joints: joint j's dual quaternion and its negation, one
    /// cache line.
    pub(super) copies: Vec<Signed>,
    /// [`Antipodes::copies`]' byte offsets into `copies`: at `a·joints + b`, that of joint
    /// b's copy to blend when a is the pivot, `64 b` or, where b's weight flips, `64 b + 32`
    /// (below 2¹⁶ for [`MOST_JOINTS`] joints).
    pub(super) at: Vec<u16>,
    /// How many joints the table is for (0: no table).
    pub(super) joints: usize,
}

/// A joint's dual quaternion and its negation, in one 64-byte line, so that no load of a
/// copy spans two lines wherever the allocator puts the table.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(super) struct Signed(pub(super) [[f32; 8]; 2]);

/// Most joints for which a table is made: 128² signs are 64 KiB, about what a core's
/// first-level caches hold beside the joints and the vertex stream (128² offsets, 32 KiB).
const MOST_JOINTS: usize = 128;
// Every offset (below 64 · MOST_JOINTS) fits the table's u16.
const _: () = assert!(64 * MOST_JOINTS <= 1 << 16);

impl Antipodes {
    /// The sign table for joints `d` whose first 4 floats are their rotation quaternions
    /// (QLB rows), when it pays: at most [`MOST_JOINTS`] joints and no more signs than
    /// `vertices` to skin. Otherwise empty, and the kernel takes the dot products itself.
    pub fn new<const N: usize>(d: &[[f32; N]], vertices: usize) -> Self {
        let mut t = Self::default();
        t.refill(d, vertices);
        t
    }

    /// [`Antipodes::new`] in place, keeping the table's capacity (no allocation once a
    /// table of this size has been made).
    pub fn refill<const N: usize>(&mut self, d: &[[f32; N]], vertices: usize) {
        if !self.start(d.len(), vertices) {
            return;
        }
        let joints = d.len();
        self.signs.resize(joints * joints, 0.0);
        each_pair(d, |a, b, flips| {
            let s = if flips { -0.0 } else { 0.0 };
            self.signs[a * joints + b] = s;
            self.signs[b * joints + a] = s;
        });
    }

    /// The signed copies of dual quaternions `d` and their offsets (DQS), when it pays, as
    /// for [`Antipodes::new`].
    pub fn copies(d: &[[f32; 8]], vertices: usize) -> Self {
        let mut t = Self::default();
        t.refill_copies(d, vertices);
        t
    }

    /// [`Antipodes::copies`] in place, keeping the table's capacity.
    pub fn refill_copies(&mut self, d: &[[f32; 8]], vertices: usize) {
        if !self.start(d.len(), vertices) {
            return;
        }
        let joints = d.len();
        self.copies
            .extend(d.iter().map(|q| Signed([*q, q.map(|x| -x)])));
        self.at.resize(joints * joints, 0);
        let offset = |j: usize, flips: bool| (64 * j + 32 * usize::from(flips)) as u16;
        each_pair(d, |a, b, flips| {
            self.at[a * joints + b] = offset(b, flips);
            self.at[b * joints + a] = offset(a, flips);
        });
    }

    /// Empties the table and says whether one is to be made for `joints` joints and
    /// `vertices` vertices (then `self.joints` is set).
    fn start(&mut self, joints: usize, vertices: usize) -> bool {
        self.signs.clear();
        self.copies.clear();
        self.at.clear();
        let pays = joints <= MOST_JOINTS && joints * joints <= vertices;
        self.joints = if pays { joints } else { 0 };
        self.joints > 0
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
/// (the pose's, made by [`Antipodes::new`] or [`Antipodes::copies`] for every vertex),
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

    #[test]
    fn the_table_holds_the_signs_of_the_dot_products() {
        let (_, f) = flipped(54);
        let t = Antipodes::new(&f, usize::MAX);
        assert_eq!(t.joints, 54);
        // Unflipped, every pair is within 2 rad of rotation, so ⟨q̂_a, q̂_b⟩ > 0: a weight
        // flips exactly when one of the two joints was negated.
        for a in 0..54 {
            for b in 0..54 {
                let s = t.signs[a * 54 + b];
                assert_eq!(s, 0.0);
                assert_eq!(s.is_sign_negative(), (a + b) % 2 == 1, "{a} {b}");
            }
        }
        // No table where it would not pay: more signs than vertices, or too many joints.
        assert!(Antipodes::new(&f, 54 * 54 - 1).is_empty());
        assert!(Antipodes::new(&vec![f[0]; MOST_JOINTS + 1], usize::MAX).is_empty());
    }

    /// DQS's form: each offset names joint b's copy, negated exactly where the signs flip,
    /// and the copies are the joints and their exact negations; the same rule for when a
    /// table pays; a refill for fewer joints leaves nothing of the last one.
    #[test]
    fn the_copies_are_the_joints_signed_as_the_table_says() {
        let (_, f) = flipped(54);
        let signs = Antipodes::new(&f, usize::MAX);
        let mut t = Antipodes::copies(&f, usize::MAX);
        assert_eq!((t.joints, t.copies.len(), t.at.len()), (54, 54, 54 * 54));
        assert_eq!(t.copies.as_ptr() as usize % 64, 0);
        for (j, q) in f.iter().enumerate() {
            assert_eq!(t.copies[j].0[0], *q);
            assert_eq!(
                t.copies[j].0[1].map(f32::to_bits),
                q.map(|x| (-x).to_bits())
            );
        }
        for a in 0..54 {
            for b in 0..54 {
                let flips = signs.signs[a * 54 + b].is_sign_negative();
                let at = usize::from(t.at[a * 54 + b]);
                assert_eq!(at, 64 * b + if flips { 32 } else { 0 }, "{a} {b}");
                assert_eq!((at % 32, at / 32), (0, 2 * b + usize::from(flips)));
            }
        }
        // The largest table's offsets fit their u16 (the last joint flipped for pivot 0).
        let alternate: Vec<[f32; 8]> = (0..MOST_JOINTS).map(|j| f[j % 2]).collect();
        let most = Antipodes::copies(&alternate, usize::MAX);
        assert_eq!(most.at[MOST_JOINTS - 1], (64 * MOST_JOINTS - 32) as u16);
        assert!(Antipodes::copies(&f, 54 * 54 - 1).is_empty());
        assert!(Antipodes::copies(&vec![f[0]; MOST_JOINTS + 1], usize::MAX).is_empty());
        t.refill_copies(&f[..3], usize::MAX);
        assert_eq!((t.joints, t.copies.len(), t.at.len()), (3, 3, 9));
        t.refill_copies(&f, 10);
        assert!(t.is_empty() && t.copies.is_empty() && t.at.is_empty());
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
