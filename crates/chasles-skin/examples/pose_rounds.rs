//! What each method's pose costs inside `chasles skin --bench`'s interleaved rounds against
//! back to back: on the synthetic rig (54 joints, 4 random influences; default 2·10⁵
//! vertices, where nearly every vertex is its own SBS cluster), one core, rounds of every
//! kernel the bench times — each method's palette (`Palette::from_joint_transforms`, SBS's
//! centre solve being nearly all of its) and skinning job, the glam and nalgebra baselines,
//! the copy bound and the loads and stores alone — in the bench's order for each round
//! (`peers::order`), then each method's palette and job again back to back; the medians in
//! µs, and a pose as the sum of its two parts' medians. A part that takes longer
//! in the rounds waits on data that the other kernels have pushed out of the caches, or
//! that the processor's prefetchers do not bring in time (SBS's solve took 1.6× its time
//! in the rounds until it asked for its tables ahead, `rotation_centre`'s module docs)
//! (`cargo run --release -p chasles-skin --example pose_rounds [-- VERTICES]`).

use chasles_skin::fast::{traffic, Out, Output, Palette, SkinningJob, Vertex};
use chasles_skin::{peers, synthetic, Method};
use std::time::Instant;

/// Interleaved rounds, after one untimed.
const ROUNDS: usize = 40;

/// Back-to-back runs of each method, after one untimed.
const RUNS: usize = 30;

/// The median of `t`, in µs.
fn median(t: &[f64]) -> f64 {
    peers::Spread::of(t.to_vec()).median * 1e6
}

/// The seconds `f` takes, and what it returns.
fn time<R>(f: impl FnOnce() -> R) -> (f64, R) {
    let start = Instant::now();
    let r = f();
    (start.elapsed().as_secs_f64(), r)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = match std::env::args().nth(1) {
        Some(s) => s.parse()?,
        None => 200_000,
    };
    let rig = synthetic::rig(n, 54, 7);
    let jt = synthetic::joints(54, 7);
    let baselines = peers::Joints::of(&jt);
    let mut out: Vec<Out> = vec![[0.0; 6]; n];
    // The copy bound's buffers: half the bytes a vertex moves each way (its vertex in, its
    // output out), as the bench copies them.
    let half = (size_of::<Vertex<4>>() + size_of::<Out>()) / 2;
    let (src, mut dst) = (vec![1u8; n * half], vec![0u8; n * half]);
    let methods = Method::ALL.len();
    let kernels = methods + peers::BASELINES.len() + 2;
    // [palette, job] of each method in the rounds and back to back.
    let mut rounds: Vec<[Vec<f64>; 2]> = vec![Default::default(); methods];
    let mut warm: Vec<[Vec<f64>; 2]> = vec![Default::default(); methods];
    let pose = |m: Method, out: &mut [Out]| -> Result<[f64; 2], Box<dyn std::error::Error>> {
        let (made, palette) = time(|| Palette::from_joint_transforms(m, &rig, &jt, false));
        let palette = palette?;
        let job = SkinningJob {
            rig: &rig,
            palette: &palette,
            output: Output::Packed(out),
            parallel: false,
        };
        let (ran, done) = time(|| job.run());
        done?;
        Ok([made, ran])
    };
    for round in 0..=ROUNDS {
        // The bench's own order for the round.
        for k in peers::order(kernels, round) {
            if k < methods {
                let t = pose(Method::ALL[k], &mut out)?;
                if round > 0 {
                    rounds[k][0].push(t[0]);
                    rounds[k][1].push(t[1]);
                }
            } else if k < kernels - 2 {
                (peers::BASELINES[k - methods].1)(rig.vertices(), &baselines, &mut out);
            } else if k == kernels - 2 {
                peers::copy_bound(&src, &mut dst, half, false);
            } else {
                traffic(&rig, Output::Packed(&mut out), false)?;
            }
        }
    }
    for (k, m) in Method::ALL.into_iter().enumerate() {
        for run in 0..=RUNS {
            let t = pose(m, &mut out)?;
            if run > 0 {
                warm[k][0].push(t[0]);
                warm[k][1].push(t[1]);
            }
        }
    }
    println!(
        "{n} synthetic vertices, one core: each method's pose in µs, in {ROUNDS} interleaved rounds of the bench's {kernels} kernels | back to back ({RUNS} runs); medians"
    );
    println!(
        "method: palette + job = their sum (rounds) | palette + job = their sum (back to back)"
    );
    for (k, m) in Method::ALL.into_iter().enumerate() {
        // The pose: the sum of the two parts' medians.
        let cell = |t: &[Vec<f64>; 2]| {
            let (p, j) = (median(&t[0]), median(&t[1]));
            format!("{p:6.0} + {j:6.0} = {:6.0}", p + j)
        };
        println!("{:>6}: {} | {}", m.name(), cell(&rounds[k]), cell(&warm[k]));
    }
    Ok(())
}
