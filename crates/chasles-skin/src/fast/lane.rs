//! The fast path's quaternion and dual-quaternion algebra, written once over a lane type:
//! `f32` for the scalar kernels (one vertex), `__m256` for the AVX2+FMA kernels (eight
//! vertices, one a lane) and `__m512` for DIB's AVX-512F kernel (sixteen; `avx512`). The
//! rotation `x + s v × (v × x + w x)` by `(w, v)/‖(w, v)‖` with `s = 2/‖(w, v)‖²` (no square
//! root), dual quaternion skinning's transformation of a point and a normal by an
//! unnormalized blend (Kavan et al. 2006, §3 and §6), the dot product and Horner's rule:
//! each function below is every kernel's formula, in one order of operations. The lane type
//! decides only how `a·b ± c` rounds — twice on `f32` (no slow software fusing where the
//! build has no FMA), once on `__m256` and `__m512` — so a scalar kernel gives the very
//! numbers it gave before, and the SIMD kernels theirs; every `__m512` operation is the
//! `__m256` one on twice the lanes, so a lane of sixteen gives a lane of eight's bits.
//!
//! Every function is `inline(always)`, so that in the SIMD kernels (`target_feature`
//! functions) the `__m256` and `__m512` operations inline as single instructions.

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::*;

#[cfg(target_arch = "x86_64")]
mod avx512;
pub(super) mod dib;
#[cfg(test)]
pub(super) mod watch;
mod wide;

/// What the algebra needs of a number: ring operations, division, square root, constants,
/// the three multiply-adds, and per-lane comparisons and choices (DIB's branch-free
/// logarithm and stopping rule).
pub(super) trait Lane: Copy {
    /// The outcome of a comparison in each lane: `bool` for `f32`, all-ones or all-zeros
    /// lanes for `__m256`, a bit a lane (a mask register) for `__m512`.
    type Mask: Copy;
    /// `x` in every lane.
    fn splat(x: f32) -> Self;
    /// `self + b`.
    fn add(self, b: Self) -> Self;
    /// `self − b`.
    fn sub(self, b: Self) -> Self;
    /// `√self`.
    fn sqrt(self) -> Self;
    /// `self < b` (false where either is NaN).
    fn lt(self, b: Self) -> Self::Mask;
    /// `self ≤ b` (false where either is NaN).
    fn le(self, b: Self) -> Self::Mask;
    /// `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// `a and b`.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// `b and not a`.
    fn and_not(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Whether `m` holds in some lane.
    fn any(m: Self::Mask) -> bool;
    /// `self` with its sign flipped where `m` holds.
    fn neg_where(self, m: Self::Mask) -> Self;
    /// `self` with its sign flipped where `of`'s sign bit is set (−0 and NaNs included):
    /// `|of| · self / of` without the division.
    fn flip_by_sign_of(self, of: Self) -> Self;
    /// `self · b`.
    fn mul(self, b: Self) -> Self;
    /// `self / b`.
    fn div(self, b: Self) -> Self;
    /// `self · b + c`.
    fn madd(self, b: Self, c: Self) -> Self;
    /// `self · b − c`.
    fn msub(self, b: Self, c: Self) -> Self;
    /// `c − self · b`.
    fn nmadd(self, b: Self, c: Self) -> Self;
    /// `Σ cₖ sᵏ` by Horner's rule, `a ← a s + cₖ` from the top coefficient down (the SIMD
    /// lanes override it with `target_feature` functions of their own).
    #[inline(always)]
    fn horner<const N: usize>(c: &[f32; N], s: Self) -> Self {
        let mut a = Self::splat(c[N - 1]);
        for k in (0..N - 1).rev() {
            a = a.madd(s, Self::splat(c[k]));
        }
        a
    }
}

impl Lane for f32 {
    type Mask = bool;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        x
    }
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        self + b
    }
    #[inline(always)]
    fn sub(self, b: Self) -> Self {
        self - b
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn lt(self, b: Self) -> bool {
        self < b
    }
    #[inline(always)]
    fn le(self, b: Self) -> bool {
        self <= b
    }
    #[inline(always)]
    fn select(m: bool, a: Self, b: Self) -> Self {
        if m {
            a
        } else {
            b
        }
    }
    #[inline(always)]
    fn and(a: bool, b: bool) -> bool {
        a && b
    }
    #[inline(always)]
    fn and_not(a: bool, b: bool) -> bool {
        !a && b
    }
    #[inline(always)]
    fn any(m: bool) -> bool {
        m
    }
    #[inline(always)]
    fn neg_where(self, m: bool) -> Self {
        if m {
            -self
        } else {
            self
        }
    }
    #[inline(always)]
    fn flip_by_sign_of(self, of: Self) -> Self {
        f32::from_bits(self.to_bits() ^ (of.to_bits() & 0x8000_0000))
    }
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        self * b
    }
    #[inline(always)]
    fn div(self, b: Self) -> Self {
        self / b
    }
    #[inline(always)]
    fn madd(self, b: Self, c: Self) -> Self {
        self * b + c
    }
    #[inline(always)]
    fn msub(self, b: Self, c: Self) -> Self {
        self * b - c
    }
    #[inline(always)]
    fn nmadd(self, b: Self, c: Self) -> Self {
        c - self * b
    }
}

/// Eight lanes. The methods are safe to call only where AVX2 and FMA run: the trait is
/// private to the fast path, and the `__m256` values it is used on exist only inside the
/// AVX2+FMA kernels, which run only where `simd` found both features. Each method inlines
/// into those kernels as one instruction.
#[cfg(target_arch = "x86_64")]
impl Lane for __m256 {
    type Mask = __m256;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        // SAFETY: see the impl's doc: only called from AVX2+FMA code.
        unsafe { _mm256_set1_ps(x) }
    }
    #[inline(always)]
    fn add(self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_add_ps(self, b) }
    }
    #[inline(always)]
    fn sub(self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_sub_ps(self, b) }
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_sqrt_ps(self) }
    }
    #[inline(always)]
    fn lt(self, b: Self) -> __m256 {
        // SAFETY: as for splat.
        unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(self, b) }
    }
    #[inline(always)]
    fn le(self, b: Self) -> __m256 {
        // SAFETY: as for splat.
        unsafe { _mm256_cmp_ps::<_CMP_LE_OQ>(self, b) }
    }
    #[inline(always)]
    fn select(m: __m256, a: Self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_blendv_ps(b, a, m) }
    }
    #[inline(always)]
    fn and(a: __m256, b: __m256) -> __m256 {
        // SAFETY: as for splat.
        unsafe { _mm256_and_ps(a, b) }
    }
    #[inline(always)]
    fn and_not(a: __m256, b: __m256) -> __m256 {
        // SAFETY: as for splat.
        unsafe { _mm256_andnot_ps(a, b) }
    }
    #[inline(always)]
    fn any(m: __m256) -> bool {
        // SAFETY: as for splat.
        unsafe { _mm256_movemask_ps(m) != 0 }
    }
    #[inline(always)]
    fn neg_where(self, m: __m256) -> Self {
        // A true lane is all ones, its sign bit set: the flip by the sign of the mask.
        self.flip_by_sign_of(m)
    }
    #[inline(always)]
    fn flip_by_sign_of(self, of: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_xor_ps(self, _mm256_and_ps(of, _mm256_set1_ps(-0.0))) }
    }
    #[inline(always)]
    fn mul(self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_mul_ps(self, b) }
    }
    #[inline(always)]
    fn div(self, b: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_div_ps(self, b) }
    }
    #[inline(always)]
    fn madd(self, b: Self, c: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_fmadd_ps(self, b, c) }
    }
    #[inline(always)]
    fn msub(self, b: Self, c: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_fmsub_ps(self, b, c) }
    }
    #[inline(always)]
    fn nmadd(self, b: Self, c: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { _mm256_fnmadd_ps(self, b, c) }
    }
    #[inline(always)]
    fn horner<const N: usize>(c: &[f32; N], s: Self) -> Self {
        // SAFETY: as for splat.
        unsafe { horner8(c, s) }
    }
}

/// [`Lane::horner`] on eight lanes, the same steps, as a `target_feature` function of its
/// own: written generically and inlined whole, the series' constants stayed in the Log
/// kernel's loop as loads and it ran 5–10 % slower (measured with `examples/best_of`).
///
/// # Safety
/// The processor must have AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn horner8<const N: usize>(c: &[f32; N], s: __m256) -> __m256 {
    let mut a = _mm256_set1_ps(c[N - 1]);
    for k in (0..N - 1).rev() {
        a = _mm256_fmadd_ps(a, s, _mm256_set1_ps(c[k]));
    }
    a
}

/// Component c of `a × b`: `a_j b_k − a_k b_j`, (c, j, k) cyclic.
#[inline(always)]
pub(super) fn cross<L: Lane>(a: [L; 3], b: [L; 3], c: usize) -> L {
    let (j, k) = ((c + 1) % 3, (c + 2) % 3);
    a[j].msub(b[k], a[k].mul(b[j]))
}

/// `v × x + w x`: the inner step of rotating x by the quaternion (w, v).
#[inline(always)]
pub(super) fn inner<L: Lane>(w: L, v: [L; 3], x: [L; 3]) -> [L; 3] {
    // Components written out, no closures: a closure here can stay a call in the kernels.
    [
        w.madd(x[0], cross(v, x, 0)),
        w.madd(x[1], cross(v, x, 1)),
        w.madd(x[2], cross(v, x, 2)),
    ]
}

/// `x + s v × (v × x + w x)`: x rotated by the unit quaternion `(w, v) / ‖(w, v)‖` given
/// `s = 2 / ‖(w, v)‖²` (no square root).
#[inline(always)]
pub(super) fn rotate<L: Lane>(w: L, v: [L; 3], s: L, x: [L; 3]) -> [L; 3] {
    let t = inner(w, v, x);
    [
        s.madd(cross(v, t, 0), x[0]),
        s.madd(cross(v, t, 1), x[1]),
        s.madd(cross(v, t, 2), x[2]),
    ]
}

/// `Σ x[c] y[c]` over two equally long runs of components, in their order.
#[inline(always)]
pub(super) fn dot<L: Lane>(x: &[L], y: &[L]) -> L {
    let mut a = x[0].mul(y[0]);
    for c in 1..x.len() {
        a = x[c].madd(y[c], a);
    }
    a
}

/// `s = 2 / ‖q‖²` of a quaternion: the factor by which [`rotate`] and [`transform`] turn
/// by `q / ‖q‖` without a square root.
#[inline(always)]
pub(super) fn two_over_norm2<L: Lane>(q: &[L]) -> L {
    L::splat(2.0).div(dot(q, q))
}

/// A position and a normal moved by a blended dual quaternion `b = [w0, x0, y0, z0, wε, xε,
/// yε, zε]`, not necessarily unit: normalized by `s = 2 / ‖b0‖²` (the point transform uses
/// only the vector part of `qε q0*`, which qε's component along q0 does not touch),
/// `p' = p + s (v0 × (v0 × p + w0 p) + w0 vε − wε v0 + v0 × vε)` and
/// `n' = n + s v0 × (v0 × n + w0 n)`. The last step of DQS and DIB, scalar and SIMD.
#[inline(always)]
pub(super) fn transform<L: Lane>(b: [L; 8], p: [L; 3], n: [L; 3]) -> [L; 6] {
    let s = two_over_norm2(&b[..4]);
    let [w0, x0, y0, z0, we, xe, ye, ze] = b;
    let (v0, ve) = ([x0, y0, z0], [xe, ye, ze]);
    let t = inner(w0, v0, p);
    let q = [
        moved(0, s, w0, we, v0, ve, t, p),
        moved(1, s, w0, we, v0, ve, t, p),
        moved(2, s, w0, we, v0, ve, t, p),
    ];
    let m = rotate(w0, v0, s, n);
    [q[0], q[1], q[2], m[0], m[1], m[2]]
}

/// Component c of [`transform`]'s position: `p + s (v0 × t + w0 vε − wε v0 + v0 × vε)`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn moved<L: Lane>(c: usize, s: L, w0: L, we: L, v0: [L; 3], ve: [L; 3], t: [L; 3], p: [L; 3]) -> L {
    let (j, k) = ((c + 1) % 3, (c + 2) % 3);
    let tr = v0[k].nmadd(ve[j], v0[j].madd(ve[k], w0.msub(ve[c], we.mul(v0[c]))));
    s.madd(cross(v0, t, c).add(tr), p[c])
}

/// `Σ cₖ sᵏ` by Horner's rule ([`Lane::horner`]).
#[inline(always)]
pub(super) fn horner<L: Lane, const N: usize>(c: &[f32; N], s: L) -> L {
    L::horner(c, s)
}

/// `(−1)ᵏ / (2k + first)!` for k = 0, 1, …: the Taylor coefficients, in s = θ², of
/// `cos θ` (first 0), `sin θ / θ` (1), `(1 − cos θ) / θ²` (2) and `(θ − sin θ) / θ³` (3).
pub(super) const fn taylor<const N: usize>(first: u32) -> [f32; N] {
    let mut out = [0f32; N];
    let mut k = 0;
    while k < N {
        let mut f = 1f64;
        let mut i = 2;
        while i <= 2 * k as u32 + first {
            f *= i as f64;
            i += 1;
        }
        out[k] = (if k % 2 == 0 { 1.0 } else { -1.0 } / f) as f32;
        k += 1;
    }
    out
}

/// The Taylor coefficients in s = θ² of A = sin θ / θ, B = (1 − cos θ) / θ² and
/// C = (θ − sin θ) / θ³, Log skinning's exponential (the next term of each is below 2e-8 at
/// θ = π).
pub(super) const EXP_A: [f32; 10] = taylor(1);
/// See [`EXP_A`].
pub(super) const EXP_B: [f32; 9] = taylor(2);
/// See [`EXP_A`].
pub(super) const EXP_C: [f32; 9] = taylor(3);

/// A position and a normal moved by `exp(ω, v)`, the rigid motion of a twist with
/// `θ = ‖ω‖ ≤ π` (Log skinning's last step; Alexa 2002): with A, B, C by their series
/// ([`EXP_A`]), `p' = p + v + ω × (A p + B v + ω × (B p + C v))` (= R p + V v) and
/// `n' = n + ω × (A n + B ω × n)` — the library's `exp_twist` regrouped, no trigonometry.
#[inline(always)]
pub(super) fn exp_twist<L: Lane>(w: [L; 3], v: [L; 3], p: [L; 3], n: [L; 3]) -> [L; 6] {
    let s = dot(&w, &w);
    let (ca, cb, cc) = (horner(&EXP_A, s), horner(&EXP_B, s), horner(&EXP_C, s));
    // u = B p + C v; e = A p + B v + ω × u; p' = p + v + ω × e; f = A n + B ω × n;
    // n' = n + ω × f. Each written out: closures and array maps can stay calls.
    let u = [
        cb.madd(p[0], cc.mul(v[0])),
        cb.madd(p[1], cc.mul(v[1])),
        cb.madd(p[2], cc.mul(v[2])),
    ];
    let e = [
        ca.madd(p[0], cb.mul(v[0])).add(cross(w, u, 0)),
        ca.madd(p[1], cb.mul(v[1])).add(cross(w, u, 1)),
        ca.madd(p[2], cb.mul(v[2])).add(cross(w, u, 2)),
    ];
    // The positions before the normals' steps begin: fewer values live at once (the
    // kernel spilled registers the other way round, 10 % slower).
    let q = [
        p[0].add(v[0]).add(cross(w, e, 0)),
        p[1].add(v[1]).add(cross(w, e, 1)),
        p[2].add(v[2]).add(cross(w, e, 2)),
    ];
    let f = [
        ca.madd(n[0], cb.mul(cross(w, n, 0))),
        ca.madd(n[1], cb.mul(cross(w, n, 1))),
        ca.madd(n[2], cb.mul(cross(w, n, 2))),
    ];
    [
        q[0],
        q[1],
        q[2],
        n[0].add(cross(w, f, 0)),
        n[1].add(cross(w, f, 1)),
        n[2].add(cross(w, f, 2)),
    ]
}

/// The quaternion product `a b = (a0 b0 − a⃗·b⃗, a0 b⃗ + b0 a⃗ + a⃗ × b⃗)` of `[w, x, y, z]`s.
#[inline(always)]
pub(super) fn qmul<L: Lane>(a: &[L], b: &[L]) -> [L; 4] {
    let (av, bv) = ([a[1], a[2], a[3]], [b[1], b[2], b[3]]);
    let w = a[3].nmadd(b[3], a[2].nmadd(b[2], a[1].nmadd(b[1], a[0].mul(b[0]))));
    [
        w,
        a[0].madd(bv[0], av[0].madd(b[0], cross(av, bv, 0))),
        a[0].madd(bv[1], av[1].madd(b[0], cross(av, bv, 1))),
        a[0].madd(bv[2], av[2].madd(b[0], cross(av, bv, 2))),
    ]
}

/// The dual quaternion product `a b = a0 b0 + ε (a0 bε + aε b0)` of `[w, x, y, z, wε, xε,
/// yε, zε]`s.
#[inline(always)]
pub(super) fn dqmul<L: Lane>(a: &[L; 8], b: &[L; 8]) -> [L; 8] {
    let r = qmul(&a[..4], &b[..4]);
    let d1 = qmul(&a[..4], &b[4..]);
    let d2 = qmul(&a[4..], &b[..4]);
    [
        r[0],
        r[1],
        r[2],
        r[3],
        d1[0].add(d2[0]),
        d1[1].add(d2[1]),
        d1[2].add(d2[2]),
        d1[3].add(d2[3]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On f32 the algebra is the scalar kernels' written-out formulas, bit for bit.
    #[test]
    fn the_f32_lane_is_the_written_out_scalar_formula() {
        let q = [0.9f32, -0.2, 0.3, 0.1];
        let x = [1.5f32, -2.0, 0.25];
        let [w0, x0, y0, z0] = q;
        let [px, py, pz] = x;
        let t = [
            y0 * pz - z0 * py + w0 * px,
            z0 * px - x0 * pz + w0 * py,
            x0 * py - y0 * px + w0 * pz,
        ];
        assert_eq!(inner(w0, [x0, y0, z0], x), t);
        let s = 2.0 / (w0 * w0 + x0 * x0 + y0 * y0 + z0 * z0);
        assert_eq!(two_over_norm2(&q), s);
        let r = [
            px + s * (y0 * t[2] - z0 * t[1]),
            py + s * (z0 * t[0] - x0 * t[2]),
            pz + s * (x0 * t[1] - y0 * t[0]),
        ];
        assert_eq!(rotate(w0, [x0, y0, z0], s, x), r);
        // A rotation: the length is kept (to rounding), and the unit quaternion's own.
        let len = |v: [f32; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        assert!((len(r) - len(x)).abs() < 1e-5);
        // The transformation of a rigid dual quaternion moves a point as the core does.
        let d = chasles::DualQuat::from_rotation_translation(
            chasles::Quat::new(0.9f32, -0.2, 0.3, 0.1)
                .normalize()
                .unwrap(),
            chasles::Vec3::new(1.0, -2.0, 3.0),
        );
        let k = 3.0f32; // unnormalized by k
        let b = d.to_array().map(|c| c * k);
        let o = transform(b, x, [0.0, 0.0, 1.0]);
        let want = d.transform_point(chasles::Vec3::from_array(x)).to_array();
        for c in 0..3 {
            assert!((o[c] - want[c]).abs() < 1e-5, "{o:?} vs {want:?}");
        }
        assert_eq!(
            horner(&[1.0, 2.0, 3.0], 2.0f32),
            1.0 + 2.0 * (2.0 + 3.0 * 2.0)
        );
    }
}
