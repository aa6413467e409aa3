//! DIB's fast path against DQS's by the number of influences a vertex has: 10⁵ synthetic
//! vertices (54 joints) with their first 1, 2 or 4 influences kept (the first is the
//! heaviest on average; weights scaled to sum to 1), with 1 and 2 or 2 and 4 alternating
//! vertex by vertex (every block mixed: DIB's fast path groups them by count, and they are
//! timed without the grouping too), and the built-in characters in their first clip half-way
//! through (each skinned as often as makes 10⁵ vertices a run), and CesiumMan's vertices cut
//! to their first one, two and three influences; best of runs on one thread,
//! the methods in turn, and DIB's cost in DQS's. A vertex of one influence keeps DLB's
//! start and one of two takes ScLERP in closed form (Lemma 3), so a block of such vertices
//! makes no update at all. Where the processor has AVX-512F and VL,
//! DIB is timed with its sixteen-vertex kernel and with the eight-vertex AVX2 kernel alone
//! (`set_avx512(false)`), which give the same numbers
//! (`cargo run --release -p chasles-skin --example dib_influences`).

use chasles_skin::fast::{dib, dqs, dual_quats8, set_avx512, uses_avx512, FastRig};
use chasles_skin::{synthetic, JointTransforms, Pose};
#[path = "common/best.rs"]
mod common;
use common::best;

/// How many influences vertex i keeps.
type Count = fn(usize) -> usize;

/// Vertices skinned a run, at least.
const RUN: usize = 100_000;

/// One line: DQS, then DIB with the eight-vertex kernel alone and, where AVX-512 runs,
/// with the sixteen-vertex one, as rates and as DIB's cost in DQS's; the best of 30 rounds,
/// each timing the three in turn (this machine's speed changes from one second to the next).
fn line(name: &str, rig: &FastRig<4>, jt: &JointTransforms) {
    let n = rig.vertices().len();
    let reps = RUN.div_ceil(n);
    let d8 = dual_quats8(jt);
    let mut out = vec![[0f32; 6]; n];
    let wide = uses_avx512(4);
    let mut best_of = [f64::INFINITY; 3];
    for _ in 0..30 {
        let time = |f: &mut dyn FnMut()| best(1, || (0..reps).for_each(|_| f()));
        let a = time(&mut || dqs(rig, &d8, &mut out, false).expect("dqs"));
        let mut by = |sixteen: bool| {
            set_avx512(sixteen);
            let t = time(&mut || dib(rig, &jt.dual_quats, &mut out, false).expect("dib"));
            set_avx512(true);
            t
        };
        let (e, s) = (by(false), if wide { by(true) } else { f64::NAN });
        for (b, t) in best_of.iter_mut().zip([a, e, s]) {
            *b = b.min(t);
        }
    }
    let [a, eight, sixteen] = best_of;
    let rate = |s: f64| (n * reps) as f64 / s / 1e6;
    print!(
        "{name}: DQS {:.1}, DIB by eight {:.1} M vertices/s ({:.2}× DQS's time)",
        rate(a),
        rate(eight),
        eight / a
    );
    if wide {
        println!(", by sixteen {:.1} ({:.2}×)", rate(sixteen), sixteen / a);
    } else {
        println!(" (no AVX-512F and VL here)");
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let base = synthetic::rig(RUN, 54, 7);
    let jt = synthetic::joints(54, 7);
    let cases: [(&str, Count); 5] = [
        ("1 influence", |_| 1),
        ("2 influences", |_| 2),
        ("4 influences", |_| 4),
        ("1 and 2 mixed", |i| 1 + i % 2),
        ("2 and 4 mixed", |i| if i % 2 == 0 { 2 } else { 4 }),
    ];
    for (name, count) in cases {
        let rig = synthetic::with_influences(&base, |i, k| k < count(i));
        line(name, &rig, &jt);
        if rig.groups_dib() {
            let name = format!("{name}, not grouped");
            line(&name, &rig.without_dib_grouping(), &jt);
        }
    }
    for m in [
        chasles_models::CESIUM_MAN,
        chasles_models::FOX,
        chasles_models::RIGGED_FIGURE,
        chasles_models::RIGGED_SIMPLE,
    ] {
        let rig = chasles_skin::gltf_load::load_slice(m.bytes, m.file)?;
        let pose = match rig.animations.first() {
            Some(clip) => Pose::animated(&rig, 0, clip.duration() / 2.0)?,
            None => Pose::rest(&rig),
        };
        let jt = chasles_skin::joint_transforms(&rig, &pose)?;
        let fast = FastRig::<4>::new(&rig)?;
        line(&rig.name, &fast, &jt);
        if m.file == chasles_models::CESIUM_MAN.file {
            // Where its time goes: its vertices cut to their first one, two or three
            // influences (weights scaled to sum to 1), so that the differences give the cost
            // of each count.
            for most in 1..=3 {
                let cut = synthetic::with_influences(&fast, |_, k| k < most);
                line(&format!("{}, at most {most}", rig.name), &cut, &jt);
            }
        }
    }
    Ok(())
}
