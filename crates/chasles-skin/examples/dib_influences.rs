//! DIB's fast path against DQS's by the number of influences a vertex has: 10⁵ synthetic
//! vertices (54 joints) with their heaviest 1, 2 or 4 influences kept (weights scaled to sum
//! to 1), and with 2 and 4 alternating vertex by vertex (every block of eight mixed); best
//! of runs on one thread, the two methods in turn, and DIB's cost in DQS's. A vertex of at
//! most two influences stops after one update (Lemma 3: the pass that shows it converged is
//! left out), so a block of such vertices makes one update and no second log sum
//! (`cargo run --release -p chasles-skin --example dib_influences`).

use chasles_skin::fast::{dib, dqs, dual_quats8, FastRig};
use chasles_skin::synthetic;
use std::time::Instant;

/// How many influences vertex i keeps.
type Count = fn(usize) -> usize;

/// The shortest of `runs` timed calls of `f` (after one untimed call), in seconds.
fn best(runs: usize, mut f: impl FnMut()) -> f64 {
    f();
    (0..runs)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let n = 100_000;
    let base = synthetic::rig(n, 54, 7);
    let jt = synthetic::joints(54, 7);
    let d8 = dual_quats8(&jt);
    let mut out = vec![[0f32; 6]; n];
    let cases: [(&str, Count); 4] = [
        ("1", |_| 1),
        ("2", |_| 2),
        ("4", |_| 4),
        ("2 and 4 mixed", |i| if i % 2 == 0 { 2 } else { 4 }),
    ];
    for (name, count) in cases {
        let vertices = base
            .vertices()
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let mut v = *v;
                let k = count(i);
                let s: f32 = v.w[..k].iter().sum();
                v.w = std::array::from_fn(|j| if j < k { v.w[j] / s } else { 0.0 });
                v
            })
            .collect();
        let rig = FastRig::from_vertices(vertices, base.centres().to_vec()).expect("the rig");
        let a = best(30, || dqs(&rig, &d8, &mut out, false).expect("dqs"));
        let b = best(10, || {
            dib(&rig, &jt.dual_quats, &mut out, false).expect("dib")
        });
        let rate = |s: f64| n as f64 / s / 1e6;
        println!(
            "{name} influences: DQS {:.1}, DIB {:.1} M vertices/s: DIB costs {:.2}× DQS",
            rate(a),
            rate(b),
            b / a
        );
    }
}
