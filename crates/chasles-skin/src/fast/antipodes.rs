//! DQS's antipodality fix (Kavan et al. 2006, §3 and Kavan's `dqsAntipod`) as a table made
//! once per pose: for a pivot joint a and a joint b, whether `⟨q̂_b, q̂_a⟩ < 0` (real parts),
//! i.e. whether b's weight is negated when a is a vertex's heaviest influence. A vertex then
//! looks its signs up instead of taking three dot products, and the SIMD kernel applies them
//! to broadcast weights with no shuffles. The dot products are the scalar kernel's
//! (`real_dot`), so the signs are the same bit for bit. The table is made once a pair (the
//! dot product is symmetric bit for bit) by plain loops: for RiggedFigure's 19 joints the
//! DQS palette went 1.51 → 0.59 µs a pose and `skin_pose` 3.49 → 2.56 µs, 1.36× on its 370
//! vertices (`examples/pose_cost`, the two builds in turn; the table was an iterator of
//! closures before, every pair twice).

// Only the x86-64 SIMD kernel reads the table; elsewhere it is made empty and left unread.
#![cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]

use super::real_dot;

/// The sign table: `−0.0` where the weight flips, `+0.0` where it stays (so a sign is
/// applied by an exclusive or), row `a` for pivot `a`. Empty where a table would not pay.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Antipodes {
    pub(super) signs: Vec<f32>,
    pub(super) joints: usize,
}

/// Most joints for which a table is made: 128² signs are 64 KiB, about what a core's
/// first-level caches hold beside the joints and the vertex stream.
const MOST_JOINTS: usize = 128;

impl Antipodes {
    /// The table for joints `d` whose first 4 floats are their rotation quaternions (dual
    /// quaternions, real part first, or QLB rows), when it pays: at most [`MOST_JOINTS`]
    /// joints and no more signs than `vertices` to skin. Otherwise empty, and the kernel
    /// takes the dot products itself.
    pub fn new<const N: usize>(d: &[[f32; N]], vertices: usize) -> Self {
        let mut t = Self::default();
        t.refill(d, vertices);
        t
    }

    /// [`Antipodes::new`] in place, keeping the table's capacity (no allocation once a
    /// table of this size has been made).
    pub fn refill<const N: usize>(&mut self, d: &[[f32; N]], vertices: usize) {
        let joints = d.len();
        self.signs.clear();
        if joints > MOST_JOINTS || joints * joints > vertices {
            self.joints = 0;
            return;
        }
        self.joints = joints;
        self.signs.resize(joints * joints, 0.0);
        // The dot product is symmetric bit for bit (the same four products, summed in the
        // same order), so each pair is taken once and written to both of its places: half
        // the work of a pose's table, which for a character of a few hundred vertices is a
        // good part of its pose's cost.
        for (a, pivot) in d.iter().enumerate() {
            for (b, q) in d.iter().enumerate().skip(a) {
                let s = if real_dot(q, pivot) < 0.0 { -0.0 } else { 0.0 };
                self.signs[a * joints + b] = s;
                self.signs[b * joints + a] = s;
            }
        }
    }

    /// Whether there is a table.
    pub fn is_empty(&self) -> bool {
        self.signs.is_empty()
    }
}

/// Runs a SIMD kernel over 1003 vertices with no sign table (dot products) and with the
/// table of `joints`, checks that it did the 1000 in whole blocks and that the two ways to
/// the signs gave the same numbers bit for bit, and returns those 1000 results.
#[cfg(all(test, target_arch = "x86_64"))]
pub(super) fn both_ways<const N: usize>(
    joints: &[[f32; N]],
    run: impl Fn(&Antipodes, &mut [super::Out]) -> usize,
) -> Vec<super::Out> {
    let go = |table: &Antipodes| {
        let mut out = vec![[f32::NAN; 6]; 1003];
        assert_eq!(run(table, &mut out), 1000);
        out.truncate(1000);
        out
    };
    let dots = go(&Antipodes::default());
    let looked_up = go(&Antipodes::new(joints, usize::MAX));
    assert_eq!(
        dots, looked_up,
        "the sign table and the dot products disagree"
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
            let looked_up = both_ways(&f, |table, out| unsafe {
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
