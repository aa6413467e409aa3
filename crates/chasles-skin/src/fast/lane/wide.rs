//! `N` values of a lane type side by side as one lane type, each operation applied to the
//! `N` in turn: `N` independent dependency chains interleaved instruction by instruction,
//! for code that would otherwise run them one after the other. DIB's SIMD kernel
//! (`lane::dib`) takes its influences' logarithms two at a time this way: each logarithm was
//! then a chain of a square root, divisions and two series, which the processor did not
//! overlap across influences far enough on its own. Best of runs at 10⁵ vertices on one core
//! (`examples/best_of`): 18.0–18.3 M vertices/s one at a time, 20.3 two at a time, 18.4–19.0
//! four at a time (more registers spilled). The chain is now a subtraction and Horner's rule
//! after the product (`lane::dib`'s module docs); measured again then (over the characters'
//! clips at seven times and 10⁵ synthetic vertices of four influences, best of 20, one
//! core, six runs each in turn, M vertices/s), one at a time against two: the synthetic mesh
//! 44.8–46.7 against 45.6–47.6, but the Fox 74.5–76.3 against 71.7–73.1, RiggedFigure
//! 61.7–63.3 against 60.2–62.8 and CesiumMan 64.5–66.8 against 63.1–64.6. Two stay, for the
//! meshes of three and four influences a vertex that DIB's iteration is slowest on.

// By index throughout: zipped iterators over several arrays compiled to slower code in
// these kernels (see `avx2`), and `array::map` to calls in DIB's (`try_map`).
#![allow(clippy::needless_range_loop)]

use super::Lane;

/// `N` values of a lane type side by side, each operation applied to the `N` in turn.
#[derive(Clone, Copy)]
pub(in crate::fast) struct Wide<L, const N: usize>(pub [L; N]);

impl<L: Lane, const N: usize> Wide<L, N> {
    /// `f(self[i], b[i])` for each i.
    #[inline(always)]
    fn zip(self, b: Self, f: impl Fn(L, L) -> L) -> Self {
        let mut a = self.0;
        for i in 0..N {
            a[i] = f(a[i], b.0[i]);
        }
        Wide(a)
    }

    /// `f(self[i], b[i], c[i])` for each i.
    #[inline(always)]
    fn zip3(self, b: Self, c: Self, f: impl Fn(L, L, L) -> L) -> Self {
        let mut a = self.0;
        for i in 0..N {
            a[i] = f(a[i], b.0[i], c.0[i]);
        }
        Wide(a)
    }

    /// `f(self[i], b[i])` for each i, a mask.
    #[inline(always)]
    fn compare(self, b: Self, f: impl Fn(L, L) -> L::Mask) -> [L::Mask; N] {
        let mut m = [f(self.0[0], b.0[0]); N];
        for i in 1..N {
            m[i] = f(self.0[i], b.0[i]);
        }
        m
    }

    /// `f(a[i], b[i])` for each i, of masks.
    #[inline(always)]
    fn masks(
        mut a: [L::Mask; N],
        b: [L::Mask; N],
        f: impl Fn(L::Mask, L::Mask) -> L::Mask,
    ) -> [L::Mask; N] {
        for i in 0..N {
            a[i] = f(a[i], b[i]);
        }
        a
    }
}

impl<L: Lane, const N: usize> Lane for Wide<L, N> {
    type Mask = [L::Mask; N];
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Wide([L::splat(x); N])
    }
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        self.zip(b, L::add)
    }
    #[inline(always)]
    fn sub(self, b: Self) -> Self {
        self.zip(b, L::sub)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.zip(self, |a, _| a.sqrt())
    }
    #[inline(always)]
    fn lt(self, b: Self) -> Self::Mask {
        self.compare(b, L::lt)
    }
    #[inline(always)]
    fn le(self, b: Self) -> Self::Mask {
        self.compare(b, L::le)
    }
    #[inline(always)]
    fn select(m: Self::Mask, a: Self, b: Self) -> Self {
        let mut r = b.0;
        for i in 0..N {
            r[i] = L::select(m[i], a.0[i], b.0[i]);
        }
        Wide(r)
    }
    #[inline(always)]
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask {
        Self::masks(a, b, L::and)
    }
    #[inline(always)]
    fn and_not(a: Self::Mask, b: Self::Mask) -> Self::Mask {
        Self::masks(a, b, L::and_not)
    }
    #[inline(always)]
    fn any(m: Self::Mask) -> bool {
        m.iter().any(|m| L::any(*m))
    }
    #[inline(always)]
    fn neg_where(self, m: Self::Mask) -> Self {
        let mut r = self.0;
        for i in 0..N {
            r[i] = r[i].neg_where(m[i]);
        }
        Wide(r)
    }
    #[inline(always)]
    fn flip_by_sign_of(self, of: Self) -> Self {
        self.zip(of, L::flip_by_sign_of)
    }
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        self.zip(b, L::mul)
    }
    #[inline(always)]
    fn div(self, b: Self) -> Self {
        self.zip(b, L::div)
    }
    #[inline(always)]
    fn madd(self, b: Self, c: Self) -> Self {
        self.zip3(b, c, L::madd)
    }
    #[inline(always)]
    fn msub(self, b: Self, c: Self) -> Self {
        self.zip3(b, c, L::msub)
    }
    #[inline(always)]
    fn nmadd(self, b: Self, c: Self) -> Self {
        self.zip3(b, c, L::nmadd)
    }
    #[inline(always)]
    fn horner<const M: usize>(c: &[f32; M], s: Self) -> Self {
        let mut a = [L::splat(c[M - 1]); N];
        for k in (0..M - 1).rev() {
            let ck = L::splat(c[k]);
            for i in 0..N {
                a[i] = a[i].madd(s.0[i], ck);
            }
        }
        Wide(a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each operation is the lane type's, side by side: on pairs of f32 every result,
    /// comparison and choice is the one-at-a-time one's, bit for bit.
    #[test]
    fn each_operation_is_the_lane_types_side_by_side() {
        let values = [
            -2.5f32,
            -0.0,
            0.0,
            0.75,
            1.0,
            3.0e-8,
            f32::INFINITY,
            f32::NAN,
        ];
        let same = |a: f32, b: f32| a.to_bits() == b.to_bits();
        for &a in &values {
            for &b in &values {
                for &c in &[0.5f32, -1.5] {
                    let (x, y, z) = (Wide([a, b]), Wide([b, a]), Wide([c, -c]));
                    let one = |f: &dyn Fn(f32, f32, f32) -> f32, w: Wide<f32, 2>| {
                        assert!(same(w.0[0], f(a, b, c)) && same(w.0[1], f(b, a, -c)));
                    };
                    one(&|p, q, _| p.add(q), x.add(y));
                    one(&|p, q, _| p.sub(q), x.sub(y));
                    one(&|p, q, _| p.mul(q), x.mul(y));
                    one(&|p, q, _| p.div(q), x.div(y));
                    one(&|p, _, _| p.sqrt(), x.sqrt());
                    one(&|p, q, r| p.madd(q, r), x.madd(y, z));
                    one(&|p, q, r| p.msub(q, r), x.msub(y, z));
                    one(&|p, q, r| p.nmadd(q, r), x.nmadd(y, z));
                    one(&|p, q, _| p.flip_by_sign_of(q), x.flip_by_sign_of(y));
                    one(&|p, _, r| f32::horner(&[1.0, -0.5, 0.25], p * r), {
                        Wide::horner(&[1.0, -0.5, 0.25], x.mul(z))
                    });
                    let (lt, le) = (x.lt(y), x.le(y));
                    assert_eq!(lt, [a.lt(b), b.lt(a)]);
                    assert_eq!(le, [a.le(b), b.le(a)]);
                    one(
                        &|p, q, _| f32::select(p.lt(q), p, q),
                        Wide::select(lt, x, y),
                    );
                    one(&|p, q, _| p.neg_where(p.le(q)), x.neg_where(le));
                    assert_eq!(Wide::<f32, 2>::and(lt, le), [a < b, b < a]);
                    assert_eq!(Wide::<f32, 2>::and_not(lt, le), [a == b, b == a]);
                    assert_eq!(Wide::<f32, 2>::any(lt), a < b || b < a);
                }
            }
        }
        assert!(same(Wide::<f32, 3>::splat(-0.0).0[2], -0.0));
    }
}
