//! Spring solved to its optimum (issue: the converged solver's time for 550, 10⁴, 10⁵ and
//! 10⁶ frames on Table 5.1, timing by angle, width 1 — its cost must grow linearly — and,
//! side by side in one run, how long the report's gradient descent needs to come within
//! 0.1 % of the converged energy: measured where it gets there, else extrapolated from its
//! history).
//!
//! `cargo bench -p chasles --bench spring`

use chasles::interp::{
    examples, spring, Hemisphere, KeyFrames, Level, SpringConfig, SpringResult, StepRule, Timing,
};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::time::{Duration, Instant};

fn keys() -> KeyFrames<f64> {
    KeyFrames::new(
        &examples::table_5_1().keys::<f64>(),
        None,
        Hemisphere::AsGiven,
    )
    .unwrap()
}

fn run(cfg: &SpringConfig, frames: usize) -> (SpringResult<f64>, Duration) {
    let start = Instant::now();
    let r = spring(&keys(), frames, Timing::Angle, cfg, &mut |_| {}).unwrap();
    (r, start.elapsed())
}

fn converged(c: &mut Criterion) {
    let mut g = c.benchmark_group("spring converged, Table 5.1, timing by angle");
    g.sample_size(10);
    for frames in [550usize, 10_000, 100_000, 1_000_000] {
        g.throughput(Throughput::Elements(frames as u64));
        if frames >= 100_000 {
            g.measurement_time(Duration::from_secs(if frames > 100_000 { 40 } else { 10 }));
        }
        let cfg = SpringConfig::converged();
        g.bench_function(format!("{frames} frames"), |b| b.iter(|| run(&cfg, frames)));
    }
    g.finish();
}

/// The gradient descent of the report at 550 frames (one level from Slerp, the report's
/// eq. 6.28 with c = 1), with `step`, for at most `iterations`: the iteration and time at
/// which F first came within `gap` of `best`, or, where it did not, the iterations it would
/// need by the power law `F/best − 1 ∝ k^(−p)` fitted over the last doubling of its history.
fn descent(step: StepRule, iterations: usize, best: f64, gap: f64) -> (String, f64) {
    let mut cfg = SpringConfig::slerpsvupti();
    cfg.step = step;
    cfg.levels = vec![Level {
        fraction: 1.0,
        iterations,
    }];
    let (r, took) = run(&cfg, 550);
    let per = took.as_secs_f64() / r.history.len() as f64;
    let gaps: Vec<f64> = r.history.iter().map(|h| h.energy / best - 1.0).collect();
    if let Some(k) = gaps.iter().position(|x| *x <= gap) {
        return (format!("reached at iteration {k}"), k as f64 * per);
    }
    let k = gaps.len() - 1;
    let p = (gaps[k / 2] / gaps[k]).ln() / 2f64.ln();
    let need = k as f64 * (gaps[k] / gap).powf(1.0 / p);
    (
        format!(
            "{:.3} % above after {k} iterations; k^-{p:.2} → {need:.2e} iterations",
            100.0 * gaps[k]
        ),
        need * per,
    )
}

/// The comparison table: the converged solver's time per frame count, and the report's
/// descents against it at 550 frames.
fn against_the_report(_: &mut Criterion) {
    let cfg = SpringConfig::converged();
    println!("\n| frames | converged solve (median of 5) | per frame | F | steps | stopped |");
    println!("|---|---|---|---|---|---|");
    let mut best = 0.0;
    let mut at_550 = 0.0;
    for frames in [550usize, 10_000, 100_000, 1_000_000] {
        let mut times: Vec<(Duration, SpringResult<f64>)> = (0..5)
            .map(|_| {
                let (r, t) = run(&cfg, frames);
                (t, r)
            })
            .collect();
        times.sort_by_key(|t| t.0);
        let (t, r) = &times[2];
        let last = r.history.last().unwrap();
        if frames == 550 {
            best = last.energy;
            at_550 = t.as_secs_f64();
        }
        println!(
            "| {frames} | {:.3} ms | {:.2} µs | {:.6e} | {} | {:?} |",
            t.as_secs_f64() * 1e3,
            t.as_secs_f64() * 1e6 / frames as f64,
            last.energy,
            r.history.len() - 1,
            r.stopped
        );
    }
    println!("\nThe report's descent at 550 frames to within 0.1 % of F = {best:.6e} (the converged solve: {:.3} ms):", at_550 * 1e3);
    println!("| descent | where it got | time to 0.1 % | converged is faster by |");
    println!("|---|---|---|---|");
    for (name, step, its) in [
        (
            "report: adaptive step (App. C's rule, halved on a rise)",
            StepRule::Adaptive(0.02),
            20_000,
        ),
        (
            "accelerated (Nesterov, the `spring` preset's rule)",
            StepRule::Accelerated(0.05),
            100_000,
        ),
    ] {
        let (what, secs) = descent(step, its, best, 1e-3);
        println!("| {name} | {what} | {secs:.3e} s | {:.0}× |", secs / at_550);
    }
}

criterion_group!(benches, converged, against_the_report);
criterion_main!(benches);
