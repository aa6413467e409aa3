//! ScLERP (Kavan et al. 2006, eq. 4) in the lane algebra: DIB's blend of a lane of two
//! influences (Lemma 3; [`super::dib`]), taken as a weighted sum of the two (2026-12-05,
//! evening).
//!
//! With `ĉ = ⟨q̂ₐ, q̂_b⟩ = c + ε c_ε` (the real part's and the dual part's scalar of
//! `r̂ = q̂ₐ* q̂_b`: `c = ⟨qₐ₀, q_b₀⟩`,
//! `c_ε = ⟨qₐ₀, q_bε⟩ + ⟨qₐε, q_b₀⟩`) the cosine of the dual half-angle `Ω̂`, the power
//! `r̂ᵗ = cos tΩ̂ + sin tΩ̂ n̂` is `(sin (1 − t)Ω̂ + sin tΩ̂ r̂) / sin Ω̂` — Slerp's identity,
//! which holds for dual numbers as for real ones — so ScLERP is the dual Slerp
//!
//! ```text
//! q̂ₐ r̂ᵗ = Ŵ₁₋ₜ q̂ₐ + Ŵₜ q̂_b,   Ŵτ = W(τ, c) + ε c_ε ∂W/∂c,   W(τ, c) = sin τΩ / sin Ω
//! ```
//!
//! (`q̂_b` taken as `−q̂_b` where `c < 0`: the shorter screw, as the logarithm's `w ≥ 0`).
//! With `h = Ω / sin Ω` (the logarithm's [`H`] at `v = 1 − c`) and `u = Ω² = h² v (2 − v)`,
//! `W = τ sinc(τ√u) h` and `∂W/∂c = −2τh² (τ² sinc′(τ²u) − sinc(τ²u) h sinc′(u))`
//! (`du/dc = −2h`; `sinc` and its derivative by [`SINC`] and [`D_SINC`] in `u`), all smooth
//! through `Ω = 0` (a pure move: `W = τ`, `c_ε = 0`). A lane of two is then two dual dot
//! products, [`H`], five short series and a weighted sum, where the logarithm and
//! exponential took two dual quaternion products, two longer series and a normalization
//! after; the result is unit to rounding without one (`‖b0‖²` within 4.8e-7 of 1, the
//! parts orthogonal to 8.4e-8), and the transform divides by `‖b0‖²` anyway. Within 4.0e-7
//! of f64's `sclerp` at every angle from 178° down to 1.5e-7 rad and none (the logarithm and
//! exponential: 4.2e-7; `two_joints_end_at_sclerp`), and on the characters' clips within
//! 4.6e-7 of f64's DIB, as before (`dib_of_two_influences_is_sclerp_to_rounding`). Best
//! of 30 at 10⁵ vertices, one core, sixteen lanes, the builds in turn twice
//! (`examples/dib_influences`, M vertices/s): two influences 140.3–140.8 → 158.7 (2.54–2.58×
//! → 2.23–2.28× DQS's time) with the normalization kept; leaving it out, 157.2–158.2 →
//! 163.1–166.9, CesiumMan 4.02–4.05× → 3.91–3.92×.

use super::super::{horner, Lane};
use super::{eight, shorter_dot, D_SINC, H, SINC};

/// ScLERP in each lane from its first influence of positive weight `q̂ₐ` to its second
/// `q̂_b` at the second's weight `t` (Kavan et al. eq. 4, `q̂ₐ (q̂ₐ* q̂_b)ᵗ`, along the
/// shorter screw: `q̂_b` or `−q̂_b`, whichever has `⟨qₐ₀, q_b₀⟩ ≥ 0`), by [`screw`]: DIB's
/// blend of a lane of two influences (Lemma 3), whose convex weights are `1 − t` and `t`.
/// Lanes of other counts get a number that [`super::dib`] does not keep.
#[inline(always)]
pub(super) fn sclerp<L: Lane, const K: usize>(q: &[[L; 8]; K], w: &[L; K], slots: usize) -> [L; 8] {
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    // The first and second slots of positive weight (slots 0 and 1 in a `FastRig::new`).
    let (mut a, mut b, mut t, mut seen) = (q[0], q[0], zero, zero);
    // Where every lane's two are slots 0 and 1 (a block of a `FastRig::new`'s vertices of
    // two influences), the loop below would pick them: taken as they are, the same bits
    // without the loop's selects (2026-12-05, `examples/dib_influences`, sixteen lanes, the
    // builds in turn three times: two influences 121.1–122.8 → 124.5–126.1 M vertices/s,
    // CesiumMan 4.20–4.23× → 4.15–4.18× DQS's time, RiggedFigure unchanged).
    let both = L::and(zero.lt(w[0]), zero.lt(w[1.min(K - 1)]));
    let every = zero.le(zero);
    // No lane without both.
    if slots == 2 && !L::any(L::and_not(both, every)) {
        return screw(&q[0], &q[1], w[1]);
    }
    for k in 0..slots {
        let used = zero.lt(w[k]);
        let first = L::and(used, seen.lt(L::splat(0.5)));
        let second = L::and(used, L::and(L::splat(0.5).lt(seen), seen.lt(L::splat(1.5))));
        a = eight(|c| L::select(first, q[k][c], a[c]));
        b = eight(|c| L::select(second, q[k][c], b[c]));
        t = L::select(second, w[k], t);
        seen = seen.add(L::select(used, one, zero));
    }
    screw(&a, &b, t)
}

/// `â exp(t log(â* b̂))`: [`sclerp`]'s formula, taken as the dual Slerp
/// `Ŵₐ(ĉ) â + Ŵ_b(ĉ) b̂` with dual weights of the dual angle's cosine `ĉ = ⟨â, b̂⟩` (module
/// docs): two dual dot products and a weighted sum, where the logarithm and exponential
/// took two dual quaternion products.
#[inline(always)]
fn screw<L: Lane>(a: &[L; 8], b: &[L; 8], t: L) -> [L; 8] {
    let one = L::splat(1.0);
    // The shorter screw: `b̂` or `−b̂`, whichever has `c ≥ 0`.
    let (w, c_du, c) = shorter_dot(a, b);
    let v = one.sub(w);
    // h = Ω/sin Ω = 1/sinc Ω, u = Ω² = h² sin² Ω, sin² Ω = v (2 − v).
    let h = horner(&H, v);
    let u = h.mul(h).mul(v.mul(L::splat(2.0).sub(v)));
    let h_s = h.mul(horner(&D_SINC, u));
    let (wa, wa_c) = weight(one.sub(t), u, h, h_s);
    let (wb, wb_c) = weight(t, u, h, h_s);
    let (wb, wb_c) = (wb.flip_by_sign_of(c), wb_c.flip_by_sign_of(c));
    let (ka, kb) = (c_du.mul(wa_c), c_du.mul(wb_c));
    eight(|i| match i {
        0..=3 => wa.madd(a[i], wb.mul(b[i])),
        _ => wa.madd(a[i], wb.madd(b[i], ka.madd(a[i - 4], kb.mul(b[i - 4])))),
    })
}

/// The Slerp weight `W = sin τΩ / sin Ω = τ sinc(τΩ) h` at `u = Ω²` (`h = 1/sinc Ω`,
/// `h_s = h d sinc √u / du`), and its derivative in `c = cos Ω`,
/// `dW/dc = −2h dW/du = −2τh² (τ² sinc′(τ²u) − sinc(τ²u) h_s)`: [`screw`]'s dual weight
/// `W + ε c_ε dW/dc`.
#[inline(always)]
fn weight<L: Lane>(tau: L, u: L, h: L, h_s: L) -> (L, L) {
    let tau2 = tau.mul(tau);
    let z = tau2.mul(u);
    let (k, k_z) = (horner(&SINC, z), horner(&D_SINC, z));
    let th = tau.mul(h);
    let w = th.mul(k);
    let w_c = L::splat(-2.0)
        .mul(th.mul(h))
        .mul(tau2.msub(k_z, k.mul(h_s)));
    (w, w_c)
}
