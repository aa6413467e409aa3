//! Our fast LBS and DQS beside the careful glam and nalgebra baselines of `benches/peers`
//! (each checked against an f64 reference in `tests/peers.rs`), in interleaved rounds on
//! one thread and on all threads: the median time of each per round and the ratio of the
//! peer's median to ours, with the spread over rounds; and a memory copy of the 72 bytes a
//! skinned vertex moves, the bandwidth bound. 54 joints, 4 random influences.
//!
//! `cargo run --release -p chasles-skin --example peers_ratio [VERTICES] [ROUNDS]`

use chasles_skin::peers;

use chasles_skin::fast::{dqs, dual_quats8, lbs, matrices12, Out};
use chasles_skin::synthetic;
use rayon::prelude::*;
use std::hint::black_box;
use std::time::Instant;

/// A kernel: the name and what it does to the whole mesh on one or all threads.
type Kernel<'a> = (&'static str, Box<dyn Fn(&mut [Out], bool) + 'a>);

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100_000);
    let rounds: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(21);
    let rig = synthetic::rig(n, 54, 7);
    let jt = synthetic::joints(54, 7);
    let (m12, d8) = (matrices12(&jt), dual_quats8(&jt));
    let pj = peers::Joints::of(&jt);
    let (gj, gd, nm, nd) = (&pj.glam, &pj.glam_dq, &pj.nalgebra, &pj.nalgebra_dq);
    let v = rig.vertices();
    // The bandwidth bound: a copy of 36 bytes a vertex reads 36 and writes 36, the 72
    // bytes each skinned vertex moves (48 read, 24 written); on all threads in the
    // kernels' chunks of 4096 vertices.
    let src = vec![1u8; n * 36];
    let dst = std::cell::RefCell::new(vec![0u8; n * 36]);
    let kernels: Vec<Kernel> = vec![
        (
            "chasles lbs",
            Box::new(|o, par| lbs(&rig, &m12, o, par).expect("lbs")),
        ),
        (
            "glam lbs by M",
            Box::new(|o, par| peers::run(v, o, par, &|v, o| peers::glam_lbs_by_m(v, gj, o))),
        ),
        (
            "glam lbs cofactor",
            Box::new(|o, par| peers::run(v, o, par, &|v, o| peers::glam_lbs_cofactor(v, gj, o))),
        ),
        (
            "nalgebra lbs",
            Box::new(|o, par| peers::run(v, o, par, &|v, o| peers::nalgebra_lbs(v, nm, o))),
        ),
        (
            "chasles dqs",
            Box::new(|o, par| dqs(&rig, &d8, o, par).expect("dqs")),
        ),
        (
            "glam dqs",
            Box::new(|o, par| peers::run(v, o, par, &|v, o| peers::glam_dqs(v, gd, o))),
        ),
        (
            "nalgebra dqs",
            Box::new(|o, par| peers::run(v, o, par, &|v, o| peers::nalgebra_dqs(v, nd, o))),
        ),
        (
            "memcpy 72 B a vertex",
            Box::new(|_, par| {
                let mut d = dst.borrow_mut();
                if par {
                    d.par_chunks_mut(4096 * 36)
                        .zip(src.par_chunks(4096 * 36))
                        .for_each(|(d, s)| d.copy_from_slice(s));
                } else {
                    d.copy_from_slice(&src);
                }
                black_box(d[n]);
            }),
        ),
    ];
    let mut out = vec![[0f32; 6]; n];
    for parallel in [false, true] {
        let mut secs = vec![Vec::new(); kernels.len()];
        for _ in 0..rounds {
            for (k, (_, f)) in kernels.iter().enumerate() {
                let t = Instant::now();
                f(black_box(&mut out), parallel);
                secs[k].push(t.elapsed().as_secs_f64());
            }
        }
        for s in &mut secs {
            s.sort_by(f64::total_cmp);
        }
        let med = |k: usize| secs[k][rounds / 2];
        let threads = if parallel {
            rayon::current_num_threads()
        } else {
            1
        };
        println!("{n} vertices, {threads} thread(s), {rounds} interleaved rounds");
        println!("| kernel | M vertices/s (median) | spread over rounds | our speed / its (memcpy: our DQS's share of the bound) |");
        println!("|---|---|---|---|");
        for (k, (name, _)) in kernels.iter().enumerate() {
            let ours = if name.contains("lbs") { 0 } else { 4 };
            println!(
                "| {name} | {:.1} | {:.1}–{:.1} | {:.2}× |",
                n as f64 / med(k) / 1e6,
                n as f64 / secs[k][rounds - 1] / 1e6,
                n as f64 / secs[k][0] / 1e6,
                med(k) / med(ours)
            );
        }
    }
}
