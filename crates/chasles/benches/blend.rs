//! Blending speed (Kavan et al. 2006, §5): ns per blend of n = 2, 4, 8 transforms for every
//! method, the DIB/DLB cost ratio, and ScLERP against nalgebra's
//! `UnitDualQuaternion::sclerp` on the same inputs (f64).
//!
//! `cargo bench -p chasles --bench blend`

use chasles::blend::{
    dec::dec, dib::dib, dlb::dlb, lin::lin, log, qlb::qlb, sclerp::sclerp, Options,
};
use chasles::{DualQuat, Mat4, Vec3};
use common::random_rigid;
use criterion::{criterion_group, criterion_main, Criterion};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::hint::black_box;

#[path = "../tests/common/mod.rs"]
mod common;

const CASES: usize = 256;

/// One blend's inputs: as dual quaternions, as matrices, and the weights.
type Case = (Vec<DualQuat<f64>>, Vec<Mat4<f64>>, Vec<f64>);

fn inputs(n: usize, seed: u64) -> Vec<Case> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..CASES)
        .map(|_| {
            // Rotations within 60° of each other, as in skinning.
            let base = random_rigid(&mut rng);
            let x: Vec<DualQuat<f64>> = (0..n)
                .map(|_| {
                    let axis = Vec3::new(
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                    );
                    let r = chasles::Quat::from_axis_angle(axis, rng.random_range(0.0..1.0))
                        .unwrap_or(chasles::Quat::identity());
                    base * DualQuat::from_rotation_translation(r, axis)
                })
                .collect();
            let m = x.iter().map(|d| d.to_matrix4()).collect();
            let w = (0..n).map(|_| rng.random_range(0.1..1.0)).collect();
            (x, m, w)
        })
        .collect()
}

fn bench_methods(c: &mut Criterion) {
    let opt = Options::<f64>::default();
    for n in [2usize, 4, 8] {
        let data = inputs(n, n as u64);
        let mut g = c.benchmark_group(format!("blend n={n} (per {CASES} blends)"));
        g.bench_function("lin", |b| {
            b.iter(|| {
                data.iter()
                    .map(|(_, m, w)| lin(m, w).unwrap().m[0][3])
                    .sum::<f64>()
            })
        });
        g.bench_function("log", |b| {
            b.iter(|| {
                data.iter()
                    .map(|(_, m, w)| log::log_blend(m, w).unwrap().m[0][3])
                    .sum::<f64>()
            })
        });
        g.bench_function("log-iter", |b| {
            b.iter(|| {
                data.iter()
                    .map(|(_, m, w)| {
                        log::log_blend_iterative(m, w, opt.precision, opt.max_iterations)
                            .unwrap()
                            .0
                            .m[0][3]
                    })
                    .sum::<f64>()
            })
        });
        g.bench_function("dec", |b| {
            b.iter(|| {
                data.iter()
                    .map(|(x, _, w)| {
                        dec(x, w, opt.center, opt.precision, opt.max_iterations)
                            .unwrap()
                            .0
                            .real
                            .w
                    })
                    .sum::<f64>()
            })
        });
        g.bench_function("qlb", |b| {
            b.iter(|| {
                data.iter()
                    .map(|(x, _, w)| qlb(x, w, opt.center).unwrap().real.w)
                    .sum::<f64>()
            })
        });
        g.bench_function("dlb", |b| {
            b.iter(|| {
                data.iter()
                    .map(|(x, _, w)| dlb(x, w).unwrap().real.w)
                    .sum::<f64>()
            })
        });
        g.bench_function("dib", |b| {
            b.iter(|| {
                data.iter()
                    .map(|(x, _, w)| {
                        dib(x, w, opt.precision, opt.max_iterations)
                            .unwrap()
                            .0
                            .real
                            .w
                    })
                    .sum::<f64>()
            })
        });
        g.finish();
    }
}

fn bench_sclerp(c: &mut Criterion) {
    let data = inputs(2, 99);
    let ts: Vec<f64> = (0..CASES).map(|i| (i as f64 * 0.618).fract()).collect();
    let na: Vec<(
        nalgebra::UnitDualQuaternion<f64>,
        nalgebra::UnitDualQuaternion<f64>,
    )> = data
        .iter()
        .map(|(x, _, _)| {
            let conv = |d: &DualQuat<f64>| {
                let q = |q: chasles::Quat<f64>| nalgebra::Quaternion::new(q.w, q.x, q.y, q.z);
                nalgebra::UnitDualQuaternion::new_unchecked(
                    nalgebra::DualQuaternion::from_real_and_dual(q(d.real), q(d.dual)),
                )
            };
            (conv(&x[0]), conv(&x[1]))
        })
        .collect();
    // Both libraries get their inputs the same way: a flat array of pairs.
    let ours: Vec<(DualQuat<f64>, DualQuat<f64>)> =
        data.iter().map(|(x, _, _)| (x[0], x[1])).collect();
    let mut g = c.benchmark_group(format!("sclerp (per {CASES})"));
    g.bench_function("chasles", |b| {
        b.iter(|| {
            ours.iter()
                .zip(&ts)
                .map(|((p, q), t)| {
                    // The whole result is used, so neither library's dual part is
                    // optimized away.
                    sclerp(*p, black_box(*q), *t)
                        .unwrap()
                        .to_array()
                        .iter()
                        .sum::<f64>()
                })
                .sum::<f64>()
        })
    });
    g.bench_function("nalgebra", |b| {
        b.iter(|| {
            na.iter()
                .zip(&ts)
                .map(|((p, q), t)| {
                    let d = p.sclerp(black_box(q), *t).into_inner();
                    d.real.coords.sum() + d.dual.coords.sum()
                })
                .sum::<f64>()
        })
    });
    g.finish();
}

criterion_group!(benches, bench_methods, bench_sclerp);
criterion_main!(benches);
