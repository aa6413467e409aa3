//! Measuring curves and blends by number: angular velocity (Dam et al. 1998, §5.2,
//! eq. 5.1) and curvature (§6.3.4, §6.3.7, eq. 6.23–6.26) — the measures the algorithms
//! themselves need. The papers' experiments (Table 1, the claims, FLOP counts) live in the
//! `chasles-paper` crate.

pub mod curvature;
pub mod velocity;
