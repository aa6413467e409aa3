//! *Lin*: linear combination of 4×4 matrices, `Σ wᵢ Mᵢ` (Kavan et al. 2006, §2.2 and §5;
//! what linear blend skinning does). Bi-invariant by distributivity, but the result is in
//! general not rigid — it can shrink, shear, even be singular — which is why the paper
//! marks it '−' for rigidity, constant speed and shortest path.

use super::weights::convex_weights;
use crate::{Mat4, Real, Result};

/// `Σ wᵢ Mᵢ` with the weights made convex (see [`super::weights`]).
pub fn lin<T: Real>(m: &[Mat4<T>], w: &[T]) -> Result<Mat4<T>> {
    let w = convex_weights(w, m.len())?;
    let mut out = Mat4::from_rows([[T::ZERO; 4]; 4]);
    for (mi, wi) in m.iter().zip(&w) {
        for r in 0..3 {
            for c in 0..4 {
                out.m[r][c] += mi.m[r][c] * *wi;
            }
        }
    }
    out.m[3][3] = T::ONE;
    Ok(out)
}
