//! `From`/`Into` conversions with other math crates, each behind a cargo feature of the same
//! name: [`glam`](https://docs.rs/glam), [`nalgebra`](https://docs.rs/nalgebra) and
//! [`mint`](https://docs.rs/mint).
//!
//! Memory order differs: glam and nalgebra store quaternions as `x, y, z, w`, we keep
//! `w, x, y, z` (scalar first, as Dam et al. and Kavan et al. write `[s, v]`). The
//! conversions map component by component by name, never by position, so every round trip
//! is exact (no arithmetic is done). Matrices: ours are row-major, glam and nalgebra
//! column-major in memory; again the mapping is by (row, column).

#[cfg(feature = "glam")]
pub mod glam;
#[cfg(feature = "mint")]
pub mod mint;
#[cfg(feature = "nalgebra")]
pub mod nalgebra;
