//! What a pose costs beside its vertices, on a rig of one's own of up to four influences a
//! vertex (default: the built-in RiggedFigure, 370 vertices, 19 joints), its first clip
//! half-way through, one thread:
//! for each method, `skin_pose` (the joint data made, then the job), the skinning job alone
//! on a palette made once, and the palette alone, in µs a pose (best of runs of 1000
//! poses). On a character of a few hundred vertices the palette is a good part of a pose
//! (`cargo run --release -p chasles-skin --example pose_cost [-- RIG.glb]`); reuse one with
//! `Palette::update` where the joints change every frame.

use chasles_skin::fast::{skin_pose, FastRig, Output, Palette, SkinningJob};
use chasles_skin::{Method, Pose};
#[path = "common/best.rs"]
mod common;
use common::best;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let rig = match std::env::args().nth(1) {
        Some(path) => chasles_skin::load(std::path::Path::new(&path))?,
        None => {
            let m = chasles_models::RIGGED_FIGURE;
            chasles_skin::gltf_load::load_slice(m.bytes, m.file)?
        }
    };
    let pose = match rig.animations.first() {
        Some(clip) => Pose::animated(&rig, 0, clip.duration() / 2.0)?,
        None => Pose::rest(&rig),
    };
    let jt = chasles_skin::joint_transforms(&rig, &pose)?;
    let fast = FastRig::<4>::new(&rig)?;
    let n = fast.vertices().len();
    println!("{}: {n} vertices, {} joints", rig.name, rig.joints.len());
    let mut out = vec![[0f32; 6]; n];
    const POSES: usize = 1000;
    let each = |s: f64| s / POSES as f64 * 1e6;
    for m in Method::ALL {
        let whole = best(20, || {
            for _ in 0..POSES {
                skin_pose(&fast, &jt, m, &mut out, false).expect("skin_pose");
            }
        });
        let palette = Palette::from_joint_transforms(m, &fast, &jt, false)?;
        let job = best(20, || {
            for _ in 0..POSES {
                SkinningJob {
                    rig: &fast,
                    palette: &palette,
                    output: Output::Packed(&mut out),
                    parallel: false,
                }
                .run()
                .expect("the job");
            }
        });
        let made = best(20, || {
            for _ in 0..POSES {
                std::hint::black_box(
                    Palette::from_joint_transforms(m, &fast, &jt, false).expect("palette"),
                );
            }
        });
        println!(
            "{:>4}: skin_pose {:6.2} µs a pose, the job alone {:6.2} ({:.2} ns a vertex), the palette alone {:5.2}",
            m.name(),
            each(whole),
            each(job),
            each(job) * 1e3 / n as f64,
            each(made),
        );
    }
    Ok(())
}
