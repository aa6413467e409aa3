//! Slerp and ScLERP over a million stored random pairs with random t, beside glam and
//! nalgebra in one interleaved run (issue 18): every library takes the shorter arc (glam
//! and nalgebra flip internally; ours is `slerp_shortest`, and ScLERP takes it by
//! definition), every result is written out whole, and each library's largest error
//! against an f64 reference on the same pairs is printed beside its speed, so a faster
//! Slerp is never a less accurate one.
//!
//! `cargo run --release -p chasles --example stored_pairs [PAIRS] [ROUNDS]`
//!
//! Why this differs from criterion's loop (`cargo bench -p chasles --bench interp`): there
//! 4096 pairs stay in L1/L2, t is one constant and only `w` is summed, so the compiler
//! drops three quarters of the final blend and the out-of-order core overlaps calls; here
//! 10⁶ pairs stream from memory (36 MB in f32), t varies per call and all four components
//! are stored.

use chasles::blend::sclerp::{sclerp, sclerp_pow};
use chasles::interp::slerp::{
    slerp_pow, slerp_shortest, slerp_shortest_batch, slerp_weights_series,
};
use chasles::{DualQuat, Quat, Vec3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::time::Instant;

/// Random unit pairs (no hemisphere fix: shortest arc is each library's job) and t.
fn pairs(n: usize, seed: u64) -> Vec<([f64; 4], [f64; 4], f64)> {
    let mut rng = StdRng::seed_from_u64(seed);
    let unit = |rng: &mut StdRng| loop {
        let q: [f64; 4] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        if n > 1e-3 && n <= 1.0 {
            return q.map(|v| v / n);
        }
    };
    (0..n)
        .map(|i| {
            let a = unit(&mut rng);
            // A quarter of the pairs close together (the small-angle regime every
            // library special-cases), the rest anywhere.
            let b = if i % 4 == 0 {
                let d: [f64; 4] = std::array::from_fn(|_| rng.random_range(-1e-3..1e-3));
                let b: [f64; 4] = std::array::from_fn(|k| a[k] + d[k]);
                let n = b.iter().map(|v| v * v).sum::<f64>().sqrt();
                b.map(|v| v / n)
            } else {
                unit(&mut rng)
            };
            (a, b, rng.random_range(0.0..1.0))
        })
        .collect()
}

/// The reference: eq. 6.4, `p (p* q)^h`, in f64 along the shorter arc — through the
/// quaternion logarithm and exponential, a formula none of the timed ones uses.
fn reference(a: [f64; 4], b: [f64; 4], t: f64) -> [f64; 4] {
    let (p, mut q) = (Quat::from_array(a), Quat::from_array(b));
    if p.dot(q) < 0.0 {
        q = -q;
    }
    slerp_pow(p, q, t).expect("unit pairs").to_array()
}

/// Largest component error of `got` against the reference, sign-insensitive (q ≡ −q).
fn error(got: [f64; 4], want: [f64; 4]) -> f64 {
    let d = |s: f64| {
        (0..4)
            .map(|k| (got[k] - s * want[k]).abs())
            .fold(0.0, f64::max)
    };
    d(1.0).min(d(-1.0))
}

/// Fills `out[i] = f(i)` and returns the seconds it took. One loop monomorphized per
/// library (not a `&dyn Fn` loop, which the compiler devirtualized and inlined for some
/// closures and not for others, so that a call was timed with the call's overhead for one
/// library and without it for another), each call inlined into its loop as in a user's
/// loop, every result stored.
#[inline(never)]
fn fill<T: Copy, const N: usize>(out: &mut [[T; N]], f: impl Fn(usize) -> [T; N]) -> f64 {
    let start = Instant::now();
    for (i, slot) in out.iter_mut().enumerate() {
        *slot = f(i);
    }
    let s = start.elapsed().as_secs_f64();
    std::hint::black_box(&*out);
    s
}

/// Median, lowest and highest of `v`.
fn spread(v: &mut [f64]) -> (f64, f64, f64) {
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], v[0], v[v.len() - 1])
}

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args
        .next()
        .and_then(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let rounds: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(15);
    let p = pairs(n, 7);
    let want: Vec<[f64; 4]> = p.iter().map(|(a, b, t)| reference(*a, *b, *t)).collect();
    let f32s = |a: [f64; 4]| a.map(|v| v as f32);

    let ours32: Vec<(Quat<f32>, Quat<f32>, f32)> = p
        .iter()
        .map(|(a, b, t)| {
            (
                Quat::from_array(f32s(*a)),
                Quat::from_array(f32s(*b)),
                *t as f32,
            )
        })
        .collect();
    let ours64: Vec<(Quat<f64>, Quat<f64>, f64)> = p
        .iter()
        .map(|(a, b, t)| (Quat::from_array(*a), Quat::from_array(*b), *t))
        .collect();
    let g32 =
        |a: [f64; 4]| glam::Quat::from_xyzw(a[1] as f32, a[2] as f32, a[3] as f32, a[0] as f32);
    let glam32: Vec<(glam::Quat, glam::Quat, f32)> = p
        .iter()
        .map(|(a, b, t)| (g32(*a), g32(*b), *t as f32))
        .collect();
    let g64 = |a: [f64; 4]| glam::DQuat::from_xyzw(a[1], a[2], a[3], a[0]);
    let glam64: Vec<(glam::DQuat, glam::DQuat, f64)> =
        p.iter().map(|(a, b, t)| (g64(*a), g64(*b), *t)).collect();
    let na = |a: [f64; 4]| {
        nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(a[0], a[1], a[2], a[3]))
    };
    let na64: Vec<_> = p.iter().map(|(a, b, t)| (na(*a), na(*b), *t)).collect();

    let mut out32 = vec![[0f32; 4]; n];
    let mut out64 = vec![[0f64; 4]; n];
    let wide = |o: &[[f32; 4]]| o.iter().map(|q| q.map(f64::from)).collect::<Vec<_>>();
    let names = [
        "chasles f32",
        "glam f32",
        "chasles f64",
        "glam f64",
        "nalgebra f64",
        "Eberly series f32",
        "chasles f32 batch",
        "chasles f64 batch",
    ];
    // The batch form's inputs, as a user with arrays holds them.
    let (bp32, bq32, bh32): (Vec<_>, Vec<_>, Vec<_>) = ours32
        .iter()
        .map(|&(a, b, t)| (a, b, t))
        .fold((Vec::new(), Vec::new(), Vec::new()), |mut v, (a, b, t)| {
            v.0.push(a);
            v.1.push(b);
            v.2.push(t);
            v
        });
    let (bp64, bq64, bh64): (Vec<_>, Vec<_>, Vec<_>) =
        ours64
            .iter()
            .fold((Vec::new(), Vec::new(), Vec::new()), |mut v, &(a, b, t)| {
                v.0.push(a);
                v.1.push(b);
                v.2.push(t);
                v
            });
    let mut bo32 = vec![Quat::<f32>::identity(); n];
    let mut bo64 = vec![Quat::<f64>::identity(); n];
    let mut secs: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    let mut worst = vec![0f64; names.len()];
    for round in 0..rounds {
        for (k, name) in names.iter().enumerate() {
            let (s, got) = match *name {
                "chasles f32" => {
                    let s = fill(&mut out32, |i| {
                        let (a, b, t) = ours32[i];
                        slerp_shortest(a, b, t).to_array()
                    });
                    (s, wide(&out32))
                }
                "glam f32" => {
                    let s = fill(&mut out32, |i| {
                        let (a, b, t) = glam32[i];
                        let q = a.slerp(b, t);
                        [q.w, q.x, q.y, q.z]
                    });
                    (s, wide(&out32))
                }
                "chasles f64" => {
                    let s = fill(&mut out64, |i| {
                        let (a, b, t) = ours64[i];
                        slerp_shortest(a, b, t).to_array()
                    });
                    (s, out64.clone())
                }
                "glam f64" => {
                    let s = fill(&mut out64, |i| {
                        let (a, b, t) = glam64[i];
                        let q = a.slerp(b, t);
                        [q.w, q.x, q.y, q.z]
                    });
                    (s, out64.clone())
                }
                "chasles f32 batch" => {
                    let start = Instant::now();
                    slerp_shortest_batch(&bp32, &bq32, &bh32, &mut bo32).expect("same lengths");
                    let s = start.elapsed().as_secs_f64();
                    (
                        s,
                        bo32.iter().map(|q| q.to_array().map(f64::from)).collect(),
                    )
                }
                "chasles f64 batch" => {
                    let start = Instant::now();
                    slerp_shortest_batch(&bp64, &bq64, &bh64, &mut bo64).expect("same lengths");
                    let s = start.elapsed().as_secs_f64();
                    (s, bo64.iter().map(|q| q.to_array()).collect())
                }
                "Eberly series f32" => {
                    let s = fill(&mut out32, |i| {
                        let (a, b, t) = ours32[i];
                        let b = if a.dot(b) < 0.0 { -b } else { b };
                        let (wa, wb) = slerp_weights_series(a.dot(b), t);
                        (a * wa + b * wb).to_array()
                    });
                    (s, wide(&out32))
                }
                _ => {
                    let s = fill(&mut out64, |i| {
                        let (a, b, t) = &na64[i];
                        let q = a.slerp(b, *t);
                        [q.w, q.i, q.j, q.k]
                    });
                    (s, out64.clone())
                }
            };
            secs[k].push(s);
            if round == 0 {
                worst[k] = got
                    .iter()
                    .zip(&want)
                    .map(|(g, w)| error(*g, *w))
                    .fold(0.0, f64::max);
            }
        }
    }
    println!("{n} stored pairs, random t, shorter arc everywhere, all four components stored; {rounds} interleaved rounds");
    println!("| library | ns per Slerp (median) | spread | largest error vs f64 reference |");
    println!("|---|---|---|---|");
    let mut med = Vec::new();
    for (k, name) in names.iter().enumerate() {
        let (m, lo, hi) = spread(&mut secs[k]);
        med.push(m);
        let ns = |s: f64| s * 1e9 / n as f64;
        println!(
            "| {name} | {:.2} | {:.2}–{:.2} | {:.2e} |",
            ns(m),
            ns(lo),
            ns(hi),
            worst[k]
        );
    }
    println!(
        "ratios (median time of the peer / ours): f32 vs glam {:.2}× (batch {:.2}×), f64 vs nalgebra {:.2}× (batch {:.2}×), f64 vs glam {:.2}×",
        med[1] / med[0],
        med[1] / med[6],
        med[4] / med[2],
        med[4] / med[7],
        med[3] / med[2]
    );

    // ScLERP: random unit dual quaternions (rotation anywhere, translation in a unit cube),
    // f64, against eq. 6.4's form p̂ (p̂* q̂)^t as the reference.
    let dq = |a: [f64; 4], t: [f64; 4]| {
        DualQuat::from_rotation_translation(Quat::from_array(a), Vec3::new(t[1], t[2], t[3]))
    };
    let dpairs: Vec<(DualQuat<f64>, DualQuat<f64>, f64)> = p
        .iter()
        .zip(p.iter().rev())
        .map(|((a, b, t), (c, d, _))| (dq(*a, *c), dq(*b, *d), *t))
        .collect();
    let dwant: Vec<[f64; 8]> = dpairs
        .iter()
        .map(|(a, b, t)| sclerp_pow(*a, *b, *t).expect("unit pairs").to_array())
        .collect();
    let na_dq = |d: &DualQuat<f64>| {
        let q = |q: Quat<f64>| nalgebra::Quaternion::new(q.w, q.x, q.y, q.z);
        nalgebra::UnitDualQuaternion::new_unchecked(nalgebra::DualQuaternion::from_real_and_dual(
            q(d.real),
            q(d.dual),
        ))
    };
    let nad: Vec<_> = dpairs
        .iter()
        .map(|(a, b, t)| (na_dq(a), na_dq(b), *t))
        .collect();
    let mut dout = vec![[0f64; 8]; n];
    let mut dsecs = [Vec::new(), Vec::new()];
    let mut dworst = [0f64; 2];
    for round in 0..rounds {
        for k in 0..2 {
            let start = Instant::now();
            if k == 0 {
                for (o, (a, b, t)) in dout.iter_mut().zip(&dpairs) {
                    *o = sclerp(*a, *b, *t).expect("unit pairs").to_array();
                }
            } else {
                for (o, (a, b, t)) in dout.iter_mut().zip(&nad) {
                    let d = a.sclerp(b, *t).into_inner();
                    *o = [
                        d.real.w, d.real.i, d.real.j, d.real.k, d.dual.w, d.dual.i, d.dual.j,
                        d.dual.k,
                    ];
                }
            }
            dsecs[k].push(start.elapsed().as_secs_f64());
            if round == 0 {
                dworst[k] = dout
                    .iter()
                    .zip(&dwant)
                    .map(|(g, w)| {
                        let d =
                            |s: f64| (0..8).map(|i| (g[i] - s * w[i]).abs()).fold(0.0, f64::max);
                        d(1.0).min(d(-1.0))
                    })
                    .fold(0.0, f64::max);
            }
        }
    }
    println!("| library | ns per ScLERP (median) | spread | largest error vs f64 reference |");
    println!("|---|---|---|---|");
    let mut dmed = [0.0; 2];
    for (k, name) in ["chasles f64", "nalgebra f64"].iter().enumerate() {
        let (m, lo, hi) = spread(&mut dsecs[k]);
        dmed[k] = m;
        let ns = |s: f64| s * 1e9 / n as f64;
        println!(
            "| {name} | {:.2} | {:.2}–{:.2} | {:.2e} |",
            ns(m),
            ns(lo),
            ns(hi),
            dworst[k]
        );
    }
    println!(
        "ScLERP ratio (nalgebra's median time / ours): {:.2}×",
        dmed[1] / dmed[0]
    );
}
