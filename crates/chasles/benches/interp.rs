//! Interpolation speed (issue: Slerp and Squad evaluations per second in f32 and f64, with
//! glam's `Quat::slerp` and nalgebra's `UnitQuaternion::slerp` measured in the same run;
//! Spring's time and final energy for 550 frames on Table 5.1 with the report's schedule).
//!
//! `cargo bench -p chasles --bench interp`

use chasles::analysis::curvature::{curvature_energy, Width};
use chasles::interp::slerp::slerp;
use chasles::interp::{
    examples, interpolate, spring, Hemisphere, KeyFrames, Method, SpringConfig, Squad, Timing,
};
use chasles::{Quat, Real};
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::hint::black_box;

const N: usize = 4096;

fn random_pairs(seed: u64) -> Vec<([f64; 4], [f64; 4], f64)> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut unit = || {
        let q: [f64; 4] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        q.map(|v| v / n)
    };
    (0..N)
        .map(|_| {
            let (a, mut b) = (unit(), unit());
            // Same hemisphere, as after key preparation (glam flips internally).
            if a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>() < 0.0 {
                b = b.map(|v| -v);
            }
            (a, b, 0.37)
        })
        .collect()
}

fn ours<T: Real>(pairs: &[([f64; 4], [f64; 4], f64)]) -> Vec<(Quat<T>, Quat<T>, T)> {
    let c = |a: [f64; 4]| Quat::from_array(a.map(T::from_f64));
    pairs
        .iter()
        .map(|(a, b, h)| (c(*a), c(*b), T::from_f64(*h)))
        .collect()
}

fn bench_slerp(c: &mut Criterion) {
    let pairs = random_pairs(7);
    let mut g = c.benchmark_group("slerp");
    g.throughput(Throughput::Elements(N as u64));
    let o32 = ours::<f32>(&pairs);
    g.bench_function("chasles f32", |b| {
        b.iter(|| {
            o32.iter()
                .fold(0.0f32, |acc, (p, q, h)| acc + slerp(*p, *q, *h).w)
        })
    });
    let g32 = |q: &Quat<f32>| glam::Quat::from_xyzw(q.x, q.y, q.z, q.w);
    let glam32: Vec<(glam::Quat, glam::Quat, f32)> =
        o32.iter().map(|(p, q, h)| (g32(p), g32(q), *h)).collect();
    g.bench_function("glam f32", |b| {
        b.iter(|| {
            glam32
                .iter()
                .fold(0.0f32, |acc, (p, q, h)| acc + p.slerp(*q, *h).w)
        })
    });
    let o64 = ours::<f64>(&pairs);
    g.bench_function("chasles f64", |b| {
        b.iter(|| {
            o64.iter()
                .fold(0.0f64, |acc, (p, q, h)| acc + slerp(*p, *q, *h).w)
        })
    });
    let g64 = |q: &Quat<f64>| glam::DQuat::from_xyzw(q.x, q.y, q.z, q.w);
    let glam64: Vec<(glam::DQuat, glam::DQuat, f64)> =
        o64.iter().map(|(p, q, h)| (g64(p), g64(q), *h)).collect();
    g.bench_function("glam f64", |b| {
        b.iter(|| {
            glam64
                .iter()
                .fold(0.0f64, |acc, (p, q, h)| acc + p.slerp(*q, *h).w)
        })
    });
    fn na<T: Real + nalgebra::RealField>(q: &Quat<T>) -> nalgebra::UnitQuaternion<T> {
        nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(q.w, q.x, q.y, q.z))
    }
    let na64: Vec<(
        nalgebra::UnitQuaternion<f64>,
        nalgebra::UnitQuaternion<f64>,
        f64,
    )> = o64.iter().map(|(p, q, h)| (na(p), na(q), *h)).collect();
    g.bench_function("nalgebra f64", |b| {
        b.iter(|| {
            na64.iter()
                .fold(0.0f64, |acc, (p, q, h)| acc + p.slerp(q, *h).w)
        })
    });
    let na32: Vec<(
        nalgebra::UnitQuaternion<f32>,
        nalgebra::UnitQuaternion<f32>,
        f32,
    )> = o32.iter().map(|(p, q, h)| (na(p), na(q), *h)).collect();
    g.bench_function("nalgebra f32", |b| {
        b.iter(|| {
            na32.iter()
                .fold(0.0f32, |acc, (p, q, h)| acc + p.slerp(q, *h).w)
        })
    });
    g.finish();
}

fn bench_squad(c: &mut Criterion) {
    let set = examples::table_5_1();
    let mut g = c.benchmark_group("squad");
    g.throughput(Throughput::Elements(N as u64));
    fn run<T: Real>(
        g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
        name: &str,
        keys: &[Quat<T>],
    ) {
        let kf = KeyFrames::new(keys, None, Hemisphere::Chain).unwrap();
        let sq = Squad::new(&kf).unwrap();
        let hs: Vec<(usize, T)> = (0..N)
            .map(|i| (i % 5, T::from_f64((i as f64 * 0.618).fract())))
            .collect();
        g.bench_function(name, |b| {
            b.iter(|| {
                hs.iter()
                    .fold(T::ZERO, |acc, (i, h)| acc + sq.eval(*i, *h).w)
            })
        });
    }
    run::<f32>(&mut g, "chasles f32", &set.keys());
    run::<f64>(&mut g, "chasles f64", &set.keys());
    g.finish();
}

fn bench_spring(c: &mut Criterion) {
    let set = examples::table_5_1();
    let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain).unwrap();
    let mut g = c.benchmark_group("spring table5.1 550 frames");
    g.sample_size(20);
    for (name, cfg) in [
        ("justdoit", SpringConfig::justdoit()),
        ("spring", SpringConfig::spring()),
    ] {
        let r = spring(&keys, 550, Timing::Angle, &cfg, &mut |_| {}).unwrap();
        let q: Vec<Quat<f64>> = r.frames.iter().map(|f| f.q).collect();
        let squad: Vec<Quat<f64>> = interpolate(Method::Squad, &keys, 550, Timing::Angle)
            .unwrap()
            .iter()
            .map(|f| f.q)
            .collect();
        println!(
            "{name}: final curvature energy {:.4e} (Squad {:.4e}), {} iterations",
            curvature_energy(&q, Width::Unit),
            curvature_energy(&squad, Width::Unit),
            r.history.iter().filter(|h| h.iteration > 0).count()
        );
        g.bench_function(name, |b| {
            b.iter_batched(
                || cfg.clone(),
                |cfg| black_box(spring(&keys, 550, Timing::Angle, &cfg, &mut |_| {}).unwrap()),
                BatchSize::SmallInput,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, bench_slerp, bench_squad, bench_spring);
criterion_main!(benches);
