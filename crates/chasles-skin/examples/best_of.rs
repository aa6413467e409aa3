//! Best-of-N speed of every method's fast path on one thread, 10⁵ synthetic vertices, 54
//! joints, 4 influences — the per-method functions and the skinning job into each output
//! layout — printed on one line. The minimum time is the figure least moved by a shared,
//! noisy machine; to compare two versions, build this file against each and run them in
//! turn several times (`cargo run --release -p chasles-skin --example best_of`).

use chasles_skin::fast::{
    dib, dqs, dual_quats8, lbs, log, matrices12, qlb, sbs, twists, Output, Palette, SkinningJob,
};
use chasles_skin::{synthetic, Method};
use std::hint::black_box;
#[path = "common/best.rs"]
mod common;
use common::best;

fn main() {
    let n = 100_000;
    let rig = synthetic::rig(n, 54, 7);
    let jt = synthetic::joints(54, 7);
    let (m12, d8, tw) = (
        matrices12(&jt),
        dual_quats8(&jt),
        twists(&jt).expect("twists"),
    );
    let d = &jt.dual_quats;
    let mut out = vec![[0f32; 6]; n];
    let rate = |s: f64| n as f64 / s / 1e6;
    let runs = |m: Method| {
        if matches!(m, Method::Sbs | Method::Dib) {
            8
        } else {
            60
        }
    };
    let mut line = String::from("M vertices/s:");
    for m in Method::ALL {
        let o = &mut out;
        let direct = best(runs(m), || {
            let o = black_box(&mut *o);
            match m {
                Method::Lbs => lbs(&rig, &m12, o, false),
                Method::Dqs => dqs(&rig, &d8, o, false),
                Method::Log => log(&rig, &tw, o, false),
                Method::Qlb => qlb(&rig, d, o, false),
                Method::Sbs => sbs(&rig, rig.clusters(), d, o, false),
                Method::Dib => dib(&rig, d, o, false),
            }
            .expect("skinning")
        });
        line += &format!(" {} {:.1}", m.name(), rate(direct));
    }
    let mut inter = vec![0f32; n * 8];
    let (mut p, mut nr) = (vec![[0f32; 3]; n], vec![[0f32; 3]; n]);
    for m in Method::ALL {
        let palette = Palette::from_joint_transforms(m, &rig, &jt, false).expect("palette");
        let job = |output: Output<'_>| {
            SkinningJob {
                rig: &rig,
                palette: &palette,
                output,
                parallel: false,
            }
            .run()
            .expect("job")
        };
        let a = best(runs(m), || job(Output::Packed(black_box(&mut out))));
        let b = best(runs(m), || {
            job(Output::Interleaved {
                data: black_box(&mut inter),
                stride: 8,
            })
        });
        let c = best(runs(m), || {
            job(Output::Split {
                positions: black_box(&mut p),
                normals: black_box(&mut nr),
            })
        });
        line += &format!(
            " | job {} packed {:.1} stride-8 {:.1} split {:.1}",
            m.name(),
            rate(a),
            rate(b),
            rate(c)
        );
    }
    println!("{line}");
}
