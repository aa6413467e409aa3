//! Random inputs of the measurements: rigid transformations with a uniform rotation and a
//! translation in [−2, 2]³ (as Kavan et al. 2006, Table 1 is measured here), and convex
//! weights.

use chasles::{DualQuat, Quat, Vec3};
use rand::rngs::StdRng;
use rand::Rng;

/// A random rigid transformation: uniform rotation, translation in [−2, 2]³.
pub fn random_rigid(rng: &mut StdRng) -> DualQuat<f64> {
    let q = loop {
        let q = Quat::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let n = q.norm();
        if n > 0.1 && n <= 1.0 {
            break q / n;
        }
    };
    let t = Vec3::new(
        rng.random_range(-2.0..2.0),
        rng.random_range(-2.0..2.0),
        rng.random_range(-2.0..2.0),
    );
    DualQuat::from_rotation_translation(q, t)
}

/// `n` random weights in [0.05, 1) (not normalized; the blends scale them).
pub fn random_weights(rng: &mut StdRng, n: usize) -> Vec<f64> {
    (0..n).map(|_| rng.random_range(0.05..1.0)).collect()
}
