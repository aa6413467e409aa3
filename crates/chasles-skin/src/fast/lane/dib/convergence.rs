//! The pass that shows whether DIB's update converged (Kavan et al. 2006, §4, the box
//! "DIB": `until ‖x̂‖ < precision`), by one product (2026-12-05, evening).
//!
//! After the first update, the pass that shows whether it converged needs only the
//! update's norm, not the moments, and the update's vector parts are linear in the joints:
//! for a unit `r̂ᵢ = b̂* q̂ᵢ`, `a·b = −w wε`, so `log r̂ᵢ`'s vector parts are
//! `(hᵢ + ε gᵢ) r̂ᵢ`'s with `gᵢ = −wε (1 + 2w ∂h/∂s)` (the logarithm's formula,
//! [`super`]'s module docs), and
//!
//! ```text
//! x̂ = vec Σ wᵢ sᵢ (hᵢ + ε gᵢ) b̂* q̂ᵢ = vec b̂* Σ wᵢ sᵢ (hᵢ + ε gᵢ) q̂ᵢ
//! ```
//!
//! ([`update_by_sum`]): each influence two dot products (`r̂ᵢ`'s scalar parts), the two
//! polynomials and a weighted sum, and one product for all of them, where [`super::update`] takes
//! each influence's product and logarithm and its moments. Its vector parts are f64's as
//! closely as the logarithms' (both within 3.9e-7 of the logarithms' weighted size far
//! from the blend; at the blend its norm under 5.4e-7, a twentieth of the precision:
//! `the_update_by_one_product_is_the_updates`). A lane that goes on takes the update
//! again with its moments, which on the characters none does (the pass ends every
//! iterating block, `avx512`'s module docs). The first update's norm is its vector parts'
//! too (the scalar parts are 0 but for rounding, and are no longer computed: within the
//! noise). Best of 30 at 10⁵ vertices, one core, sixteen lanes, the builds in turn twice
//! (`examples/dib_influences`, M vertices/s), the pass alone: four influences 47.8–47.9
//! → 52.3 (7.7–8.0× → 7.1× DQS's time), CesiumMan 88.3–88.5 → 91.6–92.5 (4.21–4.23× →
//! 4.04–4.06×); with ScLERP as a weighted sum ([`mod@super::sclerp`]), both against the
//! kernel before them: four influences 45.1–47.5 → 52.2–53.0 (7.5–7.7× → 6.4–7.1×),
//! CesiumMan 85.9–86.1 → 93.6–96.2 (4.32× → 3.88–3.90×), the Fox 135.0–138.8 →
//! 155.4–158.6, RiggedFigure 75.2–77.8 → 84.5–84.9, one influence unchanged; eight lanes
//! four influences 30.2–32.1 → 35.4–36.6, CesiumMan 59.7–59.9 → 67.3–68.6.
//!
//! Tried and not kept (the same evening): the second-order step by sums as well, so that
//! the kernel takes no logarithm at all. By the same isometry, `⟨b̂* q̂, X̂⟩ = ⟨q̂, b̂ X̂⟩`
//! with `X̂ = (0, x̂)`, the moments' product is `M x̂ = Σ wᵢ x̂ᵢ (x̂ᵢ·x̂) = vec b̂* Σ wᵢ
//! (hᵢ + ε gᵢ)² ⟨q̂ᵢ, b̂ X̂⟩ q̂ᵢ` (the hemisphere signs meet squared) and
//! `tr M = Σ wᵢ (hᵢ + ε gᵢ)² (1 − ĉᵢ²)`: each update became this pass, which kept each
//! influence's `wᵢ (hᵢ + ε gᵢ)²` and the trace, and a second pass over the influences
//! after `x̂` (a dual dot product and a weighted sum each, and two products). Its step was
//! the moments' to 5.6e-7 of its size, and by count about 5 % fewer operations an
//! iterating block, but it ran no faster (`examples/dib_influences`, two runs each in
//! turn): four influences 51.7–52.6 → 50.2–50.3 M vertices/s, CesiumMan 3.92–4.01× →
//! 3.90–3.91× DQS's time, RiggedFigure 3.10–3.13× → 3.32×: the second pass waits on `x̂`,
//! and each influence's coefficients are held across it.

use super::super::{dqmul, horner, Lane};
use super::{conjugate, eight, shorter_dot, H, H_S};

/// The update `x̂ = Σ wᵢ log(b̂* q̂ᵢ)`'s vector parts by one product, `b̂* Σ (αᵢ + ε βᵢ) q̂ᵢ`
/// (module docs; `sᵢ`, the sign of `⟨b0, qᵢ0⟩`, takes `±r̂` to `w ≥ 0` as the logarithm
/// does): each logarithm's vector parts are
/// `(h + ε g) r̂`'s, a dual number times `r̂ = b̂* q̂ᵢ` (for a unit `r̂`, `a·b = −w wε`, so
/// the dual part's `2 ∂h/∂s a·b − wε` is `g = −wε (1 + 2 w ∂h/∂s)`), and the product is
/// linear in `q̂ᵢ`, so the weighted sum is taken first: each influence is two dot products,
/// the two polynomials and a weighted sum, where [`super::update`] takes a product and its
/// logarithm. No moments: for the stopping rule alone.
#[inline(always)]
pub(super) fn update_by_sum<L: Lane, const K: usize>(
    b: &[L; 8],
    q: &[[L; 8]; K],
    w: &[L; K],
    slots: usize,
) -> [L; 6] {
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    let mut sum = [zero; 8];
    for (k, qk) in q.iter().enumerate() {
        if k >= slots {
            break;
        }
        // `r̂`'s scalar parts, taken to `w ≥ 0` (`log`'s `±r̂`).
        let (wr, wd, c) = shorter_dot(b, qk);
        let v = one.sub(wr);
        let (h, h_s) = (horner(&H, v), horner(&H_S, v));
        let g = zero.sub(wd.mul(h_s.add(h_s).madd(wr, one)));
        let (alpha, beta) = (
            w[k].mul(h).flip_by_sign_of(c),
            w[k].mul(g).flip_by_sign_of(c),
        );
        sum = eight(|i| match i {
            0..=3 => alpha.madd(qk[i], sum[i]),
            _ => alpha.madd(qk[i], beta.madd(qk[i - 4], sum[i])),
        });
    }
    let x = dqmul(&conjugate(b), &sum);
    [x[1], x[2], x[3], x[5], x[6], x[7]]
}
