//! DIB's fast path against DQS's by the number of influences a vertex has: 10⁵ synthetic
//! vertices (54 joints) with their first 1, 2 or 4 influences kept (the first is the
//! heaviest on average; weights scaled to sum to 1), and with 2 and 4 alternating vertex by
//! vertex (every block of eight mixed); best of runs on one thread, the two methods in
//! turn, and DIB's cost in DQS's. A vertex of at most two influences stops after one update
//! (Lemma 3: the pass that shows it converged is left out), so a block of such vertices
//! makes one update and no second log sum
//! (`cargo run --release -p chasles-skin --example dib_influences`).

use chasles_skin::fast::{dib, dqs, dual_quats8};
use chasles_skin::synthetic;
#[path = "common/best.rs"]
mod common;
use common::best;

/// How many influences vertex i keeps.
type Count = fn(usize) -> usize;

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
        let rig = synthetic::with_influences(&base, |i, k| k < count(i));
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
