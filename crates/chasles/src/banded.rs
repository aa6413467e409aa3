//! Symmetric positive definite band matrices: Cholesky factorization and solution in
//! O(n w²) for half-bandwidth w (Golub & Van Loan, *Matrix Computations*, 4th ed., §4.3.5,
//! band Cholesky). The converged Spring solver's normal equations are such a matrix (a
//! frame's curvature term couples it with its two neighbours on each side: w = 8 for three
//! coordinates a frame), and their size grows with the frames (10⁶ frames, 3·10⁶ unknowns).
//!
//! Written here rather than taken from a crate: nalgebra and glam have dense matrices only,
//! and the sparse solvers (faer's sparse Cholesky and the like) are large dependencies
//! that find by graph analysis the band this code is given; the band algorithm is twenty
//! lines.

use crate::{Error, Result};

/// A symmetric band matrix of size n with half-bandwidth w (`a[i][j] = 0` for
/// `|i − j| > w`), its lower triangle stored row by row; after [`Band::cholesky`], its
/// Cholesky factor L (`A = L Lᵀ`) in the same place.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Band {
    n: usize,
    w: usize,
    /// `a[i][j]` (j ≤ i, i − j ≤ w) at `i (w + 1) + w − (i − j)`.
    a: Vec<f64>,
    /// After [`Band::cholesky`] with w = 8: the reciprocals of L's diagonal.
    inv: Vec<f64>,
}

impl Band {
    /// The zero matrix; an error, not an abort, when it cannot be held in memory.
    pub(crate) fn zeros(n: usize, w: usize) -> Result<Self> {
        let len = n
            .checked_mul(w + 1)
            .ok_or(Error::TooManyFrames { frames: n })?;
        let mut a = Vec::new();
        a.try_reserve_exact(len)
            .map_err(|_| Error::TooManyFrames { frames: n })?;
        a.resize(len, 0.0);
        Ok(Band {
            n,
            w,
            a,
            inv: Vec::new(),
        })
    }

    /// The size n.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> usize {
        debug_assert!(j <= i && i - j <= self.w && i < self.n);
        i * (self.w + 1) + self.w - (i - j)
    }

    /// Sets every entry to 0.
    pub(crate) fn clear(&mut self) {
        self.a.fill(0.0);
    }

    /// `a[i][j] += v` (and `a[j][i]`), for `j ≤ i ≤ j + w`.
    #[inline(always)]
    pub(crate) fn add(&mut self, i: usize, j: usize, v: f64) {
        let k = self.at(i, j);
        self.a[k] += v;
    }

    /// Row i's stored entries, `a[i][i − w] … a[i][i]` (those left of column 0 unused).
    pub(crate) fn row_mut(&mut self, i: usize) -> &mut [f64] {
        let r = self.w + 1;
        &mut self.a[i * r..(i + 1) * r]
    }

    /// `a[i][i]`.
    pub(crate) fn diagonal(&self, i: usize) -> f64 {
        self.a[self.at(i, i)]
    }

    /// Replaces the matrix by its Cholesky factor L; false (the matrix left half-factored)
    /// if a pivot is not positive and finite: the matrix is not positive definite to
    /// working precision. Row by row, each entry one dot product of two stored rows; the
    /// rows of a band of half-bandwidth 8 (the Spring solver's) as fixed-size arrays, so
    /// the compiler unrolls the dot products.
    pub(crate) fn cholesky(&mut self) -> bool {
        if self.w == 8 {
            return self.cholesky_fixed::<9>();
        }
        let w = self.w;
        let row = w + 1;
        for i in 0..self.n {
            let first = i.saturating_sub(w);
            let (before, rest) = self.a.split_at_mut(i * row);
            let ri = &mut rest[..row];
            for j in first..i {
                // L[i][j] = (A[i][j] − Σ_{first ≤ k < j} L[i][k] L[j][k]) / L[j][j].
                let rj = &before[j * row..(j + 1) * row];
                let len = j - first;
                let (oi, oj) = (w - (i - first), w - (j - first));
                let s = ri[w - (i - j)] - dot(&ri[oi..oi + len], &rj[oj..oj + len]);
                ri[w - (i - j)] = s / rj[w];
            }
            let s = ri[w] - dot(&ri[w - (i - first)..w], &ri[w - (i - first)..w]);
            if !(s > 0.0 && s.is_finite()) {
                return false;
            }
            ri[w] = s.sqrt();
        }
        true
    }

    /// [`Band::cholesky`] for rows of R = w + 1 entries: the first w rows (whose band
    /// starts before column 0) as in the general loop, the others with every loop's bounds
    /// fixed, so that the compiler unrolls them; divisions by the pivots as products with
    /// their reciprocals, kept in `inv` (the rounding differs from a division by at most
    /// an ulp, as the tests allow).
    fn cholesky_fixed<const R: usize>(&mut self) -> bool {
        let w = R - 1;
        let n = self.n;
        let mut inv = std::mem::take(&mut self.inv);
        inv.clear();
        inv.resize(n, 0.0);
        let (rows, _) = self.a.as_chunks_mut::<R>();
        for i in 0..n {
            let (before, rest) = rows.split_at_mut(i);
            let ri = &mut rest[0];
            if i >= w {
                // Row j = i − w + dj is before[i − w + dj]; its pivot's reciprocal is
                // inv[j].
                for dj in 0..w {
                    let rj = &before[i - w + dj];
                    let mut s = ri[dj];
                    for d in 0..dj {
                        s -= ri[d] * rj[w - dj + d];
                    }
                    ri[dj] = s * inv[i - w + dj];
                }
            } else {
                let first = 0;
                for j in first..i {
                    let rj = &before[j];
                    let (oi, oj) = (w - (i - first), w - (j - first));
                    let mut s = ri[w - (i - j)];
                    for d in 0..j - first {
                        s -= ri[oi + d] * rj[oj + d];
                    }
                    ri[w - (i - j)] = s * inv[j];
                }
            }
            let from = w - i.min(w);
            let mut s = ri[w];
            for x in &ri[from..w] {
                s -= x * x;
            }
            if !(s > 0.0 && s.is_finite()) {
                return false;
            }
            ri[w] = s.sqrt();
            inv[i] = 1.0 / ri[w];
        }
        self.inv = inv;
        true
    }

    /// Solves `L Lᵀ x = b` in place (after [`Band::cholesky`]).
    pub(crate) fn solve(&self, b: &mut [f64]) {
        if self.w == 8 {
            return self.solve_fixed::<9>(b);
        }
        let w = self.w;
        let row = w + 1;
        for i in 0..self.n {
            let first = i.saturating_sub(w);
            let ri = &self.a[i * row..(i + 1) * row];
            b[i] = (b[i] - dot(&ri[w - (i - first)..w], &b[first..i])) / ri[w];
        }
        for i in (0..self.n).rev() {
            let first = i.saturating_sub(w);
            let ri = &self.a[i * row..(i + 1) * row];
            b[i] /= ri[w];
            let x = b[i];
            for (bk, l) in b[first..i].iter_mut().zip(&ri[w - (i - first)..w]) {
                *bk -= l * x;
            }
        }
    }

    /// [`Band::solve`] for rows of R = w + 1 entries, the loops past the first w rows of
    /// fixed length, the pivots' reciprocals from the factorization (each row's result is
    /// on the substitution's dependency chain: a product, not a division).
    fn solve_fixed<const R: usize>(&self, b: &mut [f64]) {
        let w = R - 1;
        let (rows, _) = self.a.as_chunks::<R>();
        for (i, ri) in rows.iter().enumerate() {
            let mut s = b[i];
            if i >= w {
                let window: &[f64; R] = b[i - w..=i].try_into().expect("R entries");
                for d in 0..w {
                    s -= ri[d] * window[d];
                }
            } else {
                for (l, x) in ri[w - i..w].iter().zip(&b[..i]) {
                    s -= l * x;
                }
            }
            b[i] = s * self.inv[i];
        }
        for (i, ri) in rows.iter().enumerate().rev() {
            b[i] *= self.inv[i];
            let x = b[i];
            if i >= w {
                let window: &mut [f64; R] = (&mut b[i - w..=i]).try_into().expect("R entries");
                for d in 0..w {
                    window[d] -= ri[d] * x;
                }
            } else {
                for (bk, l) in b[..i].iter_mut().zip(&ri[w - i..w]) {
                    *bk -= l * x;
                }
            }
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random SPD band matrix, dense, and the same as a [`Band`].
    fn matrix(n: usize, w: usize, seed: u64) -> (Vec<Vec<f64>>, Band) {
        let mut s = seed;
        let mut r = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        // A = M Mᵀ + n I with M lower band of half-bandwidth w/2: a band of width ≤ w.
        let h = w / 2;
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| if j <= i && i - j <= h { r() } else { 0.0 })
                    .collect()
            })
            .collect();
        let mut dense = vec![vec![0.0; n]; n];
        let mut band = Band::zeros(n, w).unwrap();
        for i in 0..n {
            for j in 0..n {
                let v: f64 =
                    (0..n).map(|k| m[i][k] * m[j][k]).sum::<f64>() + if i == j { 1.0 } else { 0.0 };
                dense[i][j] = v;
                if j <= i && i - j <= w {
                    band.add(i, j, v);
                }
            }
        }
        (dense, band)
    }

    #[test]
    fn solves_what_the_dense_matrix_multiplies() {
        for (n, w) in [(1, 0), (5, 2), (40, 8), (31, 3)] {
            let (dense, mut band) = matrix(n, w, n as u64 * 7 + w as u64);
            let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
            let mut b: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|j| dense[i][j] * x[j]).sum())
                .collect();
            assert!(band.cholesky());
            band.solve(&mut b);
            for (got, want) in b.iter().zip(&x) {
                assert!((got - want).abs() < 1e-12, "n {n} w {w}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn refuses_what_is_not_positive_definite() {
        let mut b = Band::zeros(3, 1).unwrap();
        for i in 0..3 {
            b.add(i, i, 1.0);
        }
        b.add(1, 0, 2.0); // [[1, 2], [2, 1]] has a negative eigenvalue
        assert!(!b.cholesky());
        let mut nan = Band::zeros(2, 1).unwrap();
        nan.add(0, 0, f64::NAN);
        assert!(!nan.cholesky());
        assert!(matches!(
            Band::zeros(usize::MAX / 2, 8),
            Err(Error::TooManyFrames { .. })
        ));
    }
}
