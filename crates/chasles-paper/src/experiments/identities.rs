//! Both papers' identities on random inputs, in f64 and f32: conversions that round-trip
//! (Dam et al. App. B, Shepperd's method, all 24 Euler conventions; Kavan et al. §3, the
//! 4×4 matrix and the screw), exp/log (Dam et al. Definitions 14–16; Kavan et al. §3),
//! ‖pq‖ = ‖p‖‖q‖, and Lemma 1. The worst relative error of each, and how many inputs the
//! operation failed on — a failure is counted, never skipped.

use crate::claim::Paper::Kavan2006;
use crate::error::need_samples;
use crate::section::Section;
use crate::table::{Cell, Number, Table};
use chasles::{DualQuat, EulerOrder, Quat, Real, Vec3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The identities, in the order [`sweep`] measures them.
pub const NAMES: [&str; 8] = [
    "matrix → quaternion → matrix (Shepperd)",
    "Euler → quaternion → Euler, all 24 conventions",
    "exp(log q) = q",
    "‖pq‖ = ‖p‖‖q‖",
    "dual quaternion ↔ 4×4 matrix",
    "dual quaternion → screw → dual quaternion",
    "exp(log q̂) = q̂",
    "Lemma 1: log(m̂ q̂ m̂*) = m̂ log(q̂) m̂*",
];

/// One identity measured: the worst relative error and the inputs it failed on.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Worst {
    /// The largest relative error.
    pub error: f64,
    /// Inputs on which an operation returned an error.
    pub failed: usize,
}

impl Worst {
    fn add(&mut self, r: chasles::Result<f64>) {
        match r {
            Ok(e) => self.error = self.error.max(e),
            Err(_) => self.failed += 1,
        }
    }
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

fn to64<T: Real, const N: usize>(a: [T; N]) -> [f64; N] {
    a.map(|v| v.to_f64())
}

/// Every identity of [`NAMES`] over `samples` random inputs from `seed`, in precision T.
pub fn sweep<T: Real>(samples: usize, seed: u64) -> [Worst; 8] {
    let mut rng = StdRng::seed_from_u64(seed);
    let orders = EulerOrder::all();
    let mut w = [Worst::default(); 8];
    let c = |x: f64| T::from_f64(x);
    for _ in 0..samples {
        let mut rq = || {
            let q = Quat::new(
                c(rng.random_range(-1.0..1.0)),
                c(rng.random_range(-1.0..1.0)),
                c(rng.random_range(-1.0..1.0)),
                c(rng.random_range(-1.0..1.0)),
            );
            q.normalize().unwrap_or(Quat::identity())
        };
        let (q, p, qm) = (rq(), rq(), rq());
        let mut rv = || {
            Vec3::new(
                c(rng.random_range(-5.0..5.0)),
                c(rng.random_range(-5.0..5.0)),
                c(rng.random_range(-5.0..5.0)),
            )
        };
        let (t, tm) = (rv(), rv());
        let m = q.to_rotation_matrix();
        w[0].add(Quat::from_rotation_matrix(&m).map(|back| {
            rel(
                &to64(back.to_rotation_matrix().to_row_major()),
                &to64(m.to_row_major()),
            )
        }));
        let order = orders[rng.random_range(0..orders.len())];
        w[1].add(q.to_euler(order).map(|e| {
            let b = Quat::from_euler(order, e.angles);
            let b = if b.dot(q) < T::ZERO { -b } else { b };
            rel(&to64(b.to_array()), &to64(q.to_array()))
        }));
        let scaled = q * c(rng.random_range(0.1..3.0));
        w[2].add(
            scaled
                .log()
                .map(|l| rel(&to64(l.exp().to_array()), &to64(scaled.to_array()))),
        );
        w[3].add(Ok(rel(
            &[(scaled * p).norm().to_f64()],
            &[(scaled.norm() * p.norm()).to_f64()],
        )));
        let dq = DualQuat::from_rotation_translation(q, t);
        w[4].add(DualQuat::from_matrix4(&dq.to_matrix4()).map(|b| {
            rel(
                &to64(b.to_matrix4().to_row_major()),
                &to64(dq.to_matrix4().to_row_major()),
            )
        }));
        w[5].add(
            dq.to_screw()
                .and_then(|s| DualQuat::from_screw(&s))
                .map(|b| rel(&to64(b.to_array()), &to64(dq.to_array()))),
        );
        w[6].add(
            dq.log()
                .map(|l| rel(&to64(l.exp().to_array()), &to64(dq.to_array()))),
        );
        let mm = DualQuat::from_rotation_translation(qm, tm);
        w[7].add((mm * dq * mm.conjugate()).log().and_then(|a| {
            let b = mm * dq.log()? * mm.conjugate();
            Ok(rel(&to64(a.to_array()), &to64(b.to_array())))
        }));
    }
    w
}

/// The sweep in both precisions: a table and the claim that every identity holds to the
/// test suite's tolerances (1e-12 in f64, 1e-5 in f32) on every input.
pub fn identities(samples: usize, seed: u64) -> Section {
    let mut s = Section::new(format!(
        "Identities over {samples} random inputs (seed {seed}): worst error, relative"
    ));
    s.attempt(
        Kavan2006,
        "§3, Lemma 1; Dam et al. App. B, Definitions 14–16",
        "the identities of both papers (conversions round-trip, Lemma 1, exp/log, bi-invariance) hold on every input",
        |s| {
            need_samples(samples)?;
            let (r64, r32) = (sweep::<f64>(samples, seed), sweep::<f32>(samples, seed));
            let mut t = Table::new(
                "worst relative error, and the inputs an operation failed on",
                &["f64", "f32", "failed", "identity"],
            );
            for ((a, b), name) in r64.iter().zip(&r32).zip(NAMES) {
                t.row(vec![
                    Cell::Number(Number::sci(a.error, 1)),
                    Cell::Number(Number::sci(b.error, 1)),
                    Cell::Number(Number::integer((a.failed + b.failed) as u64)),
                    Cell::text(name),
                ]);
            }
            s.table(t);
            s.text("Tolerances the test suite demands: 1e-12 (f64) and 1e-5 (f32). Run `cargo test --workspace`.");
            let worst = |r: &[Worst; 8]| r.iter().fold(0.0f64, |m, x| m.max(x.error));
            let failed: usize = r64.iter().chain(&r32).map(|x| x.failed).sum();
            let (w64, w32) = (worst(&r64), worst(&r32));
            Ok::<_, crate::Error>((
                format!(
                    "worst relative error over {samples} random inputs: {w64:.1e} (f64), {w32:.1e} (f32); {failed} failed operations"
                ),
                w64 < 1e-12 && w32 < 1e-5 && failed == 0,
            ))
        },
    );
    s
}
