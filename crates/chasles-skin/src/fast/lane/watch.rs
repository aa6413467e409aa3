//! A lane type for tests that watches for subnormal numbers: sixteen `f32` lanes, as the
//! sixteen-vertex kernels' (`__m512`), with their fused multiply-adds (`a·b ± c` rounded
//! once), which note each lane's operations whose operands or result are subnormal, or
//! whose exact result was nonzero and below the normal range (it underflowed; counted
//! before rounding, so a result that rounds up to the smallest normal counts too), with
//! the line that called the operation (for the helpers without `#[track_caller]` —
//! `dot`, `cross`, Horner's rule — their own line). An x86 core may take a microcode
//! assist for such an operation unless the flush-to-zero and denormals-are-zero modes are
//! on, which Rust assumes are off, so the kernels cannot switch them on. DIB met thousands
//! of them on the Fox: it ran 2.5× faster with both modes on in a scratch run, and 2.9×
//! faster over its clips once a lane of one influence no longer made them (`lane::dib`).
//! Every operation is applied lane by lane, so run on a block's vertices the algebra
//! takes the kernel's steps: the same passes for all sixteen lanes, and the same numbers.

use super::Lane;
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::panic::Location;

/// Sixteen `f32` lanes whose operations are watched (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::fast) struct Watch(pub [f32; LANES]);

/// The lanes of a [`Watch`]: the sixteen-vertex kernel's.
pub(in crate::fast) const LANES: usize = 16;

thread_local! {
    /// The lines at which each lane's operations met a subnormal number or underflowed,
    /// with how many operations each.
    static SEEN: RefCell<[BTreeMap<String, usize>; LANES]> = RefCell::new(Default::default());
}

/// For each lane, the lines whose operations met subnormal numbers since the last call,
/// with how many operations each; the record is cleared.
pub(in crate::fast) fn take() -> [BTreeMap<String, usize>; LANES] {
    SEEN.with(|s| std::mem::take(&mut *s.borrow_mut()))
}

/// Notes `at` for lane `l` where an operand is subnormal, or the result is subnormal, or
/// `tiny` (the exact product or quotient was nonzero and below the normal range); returns
/// the result.
fn note(at: &Location<'_>, l: usize, operands: &[f32], result: f32, tiny: bool) -> f32 {
    if tiny || result.is_subnormal() || operands.iter().any(|x| x.is_subnormal()) {
        let key = format!("{}:{}", at.file(), at.line());
        SEEN.with(|s| *s.borrow_mut()[l].entry(key).or_default() += 1);
    }
    result
}

/// Whether an exact result (to f64's precision) is nonzero and below f32's normal range.
fn tiny(exact: f64) -> bool {
    exact != 0.0 && exact.abs() < f64::from(f32::MIN_POSITIVE)
}

/// `a·b + c` in f64: exact for the product, one rounding for the sum.
fn fused(a: f32, b: f32, c: f32) -> f64 {
    f64::from(a).mul_add(f64::from(b), f64::from(c))
}

impl Watch {
    /// `f` of each lane's operands, each lane's operation noted at the caller's line; `f`
    /// gives the result and whether its exact value was [`tiny`].
    #[track_caller]
    fn each<const N: usize>(operands: [Self; N], f: impl Fn([f32; N]) -> (f32, bool)) -> Self {
        let at = Location::caller();
        Watch(std::array::from_fn(|l| {
            let x = operands.map(|o| o.0[l]);
            let (result, tiny) = f(x);
            note(at, l, &x, result, tiny)
        }))
    }
}

impl Lane for Watch {
    type Mask = [bool; LANES];
    fn splat(x: f32) -> Self {
        Watch([x; LANES])
    }
    #[track_caller]
    fn add(self, b: Self) -> Self {
        Self::each([self, b], |[a, b]| {
            (a + b, tiny(f64::from(a) + f64::from(b)))
        })
    }
    #[track_caller]
    fn sub(self, b: Self) -> Self {
        Self::each([self, b], |[a, b]| {
            (a - b, tiny(f64::from(a) - f64::from(b)))
        })
    }
    #[track_caller]
    fn sqrt(self) -> Self {
        Self::each([self], |[a]| (a.sqrt(), false))
    }
    fn lt(self, b: Self) -> [bool; LANES] {
        std::array::from_fn(|l| self.0[l] < b.0[l])
    }
    fn le(self, b: Self) -> [bool; LANES] {
        std::array::from_fn(|l| self.0[l] <= b.0[l])
    }
    fn select(m: [bool; LANES], a: Self, b: Self) -> Self {
        Watch(std::array::from_fn(|l| if m[l] { a.0[l] } else { b.0[l] }))
    }
    fn and(a: [bool; LANES], b: [bool; LANES]) -> [bool; LANES] {
        std::array::from_fn(|l| a[l] && b[l])
    }
    fn and_not(a: [bool; LANES], b: [bool; LANES]) -> [bool; LANES] {
        std::array::from_fn(|l| !a[l] && b[l])
    }
    fn any(m: [bool; LANES]) -> bool {
        m.iter().any(|x| *x)
    }
    fn neg_where(self, m: [bool; LANES]) -> Self {
        Watch(std::array::from_fn(|l| self.0[l].neg_where(m[l])))
    }
    fn flip_by_sign_of(self, of: Self) -> Self {
        Watch(std::array::from_fn(|l| self.0[l].flip_by_sign_of(of.0[l])))
    }
    #[track_caller]
    fn mul(self, b: Self) -> Self {
        Self::each([self, b], |[a, b]| (a * b, tiny(fused(a, b, 0.0))))
    }
    #[track_caller]
    fn div(self, b: Self) -> Self {
        Self::each([self, b], |[a, b]| {
            (a / b, tiny(f64::from(a) / f64::from(b)))
        })
    }
    #[track_caller]
    fn madd(self, b: Self, c: Self) -> Self {
        Self::each([self, b, c], |[a, b, c]| {
            (a.mul_add(b, c), tiny(fused(a, b, c)))
        })
    }
    #[track_caller]
    fn msub(self, b: Self, c: Self) -> Self {
        Self::each([self, b, c], |[a, b, c]| {
            (a.mul_add(b, -c), tiny(fused(a, b, -c)))
        })
    }
    #[track_caller]
    fn nmadd(self, b: Self, c: Self) -> Self {
        Self::each([self, b, c], |[a, b, c]| {
            ((-a).mul_add(b, c), tiny(fused(-a, b, c)))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lanes whose operations [`take`] has noted.
    fn noted() -> Vec<usize> {
        let seen = take();
        (0..LANES).filter(|&l| !seen[l].is_empty()).collect()
    }

    /// Sixteen lanes of `x`, with `at` in the lanes it names.
    fn lanes(x: f32, at: &[(usize, f32)]) -> Watch {
        let mut v = [x; LANES];
        at.iter().for_each(|&(l, y)| v[l] = y);
        Watch(v)
    }

    /// It notes the lanes whose operation meets a subnormal number, and only those: an
    /// operand, a product, a fused sum, a difference and a quotient that are subnormal or
    /// underflow to zero; not ordinary numbers, zeros, or a tiny product added to a
    /// normal number (whose exact result is normal). The results are the plain ones.
    #[test]
    fn it_notes_the_lanes_that_meet_subnormal_numbers() {
        take();
        let tiny = 1e-20f32;
        let p = lanes(1.0, &[(0, tiny), (1, tiny), (2, tiny), (5, 0.0)]);
        let product = p.mul(lanes(2.0, &[(0, tiny), (5, 1e-30)]));
        assert_eq!(product.0[0], tiny * tiny);
        assert_eq!(noted(), [0]);
        let fused = p.madd(lanes(3.0, &[(1, tiny), (2, tiny)]), lanes(0.5, &[(2, 0.0)]));
        assert_eq!(
            (fused.0[1], fused.0[2], fused.0[3]),
            (0.5, tiny * tiny, 3.5)
        );
        assert_eq!(noted(), [2]);
        let m = f32::MIN_POSITIVE;
        let d = lanes(1.0, &[(3, 1.5 * m)]).sub(lanes(0.25, &[(3, m)]));
        assert!(d.0[3].is_subnormal() && d.0[4] == 0.75);
        assert_eq!(noted(), [3]);
        let s = lanes(1.0, &[(4, 1e-40)]).add(lanes(1.0, &[]));
        assert_eq!(s.0[4], 1.0);
        assert_eq!(noted(), [4]);
        let q = lanes(1.0, &[(6, 1e-30)]).div(lanes(4.0, &[(6, 1e20)]));
        assert_eq!((q.0[6], q.0[7]), (0.0, 0.25));
        assert_eq!(noted(), [6]);
    }
}
