//! Measuring curves and blends by number: angular velocity (Dam et al. 1998, §5.2,
//! eq. 5.1) and curvature (§6.3.4, §6.3.7, eq. 6.23–6.26).

pub mod claims;
pub mod curvature;
pub mod flops;
pub mod properties;
pub mod velocity;
