//! DIB's fast path on the built-in characters in three vertex orders: the rig's own with
//! the fast path's grouping turned off (`FastRig::without_dib_grouping`), grouped by the
//! fast path itself (a copy of the vertices sorted by influence count within windows of
//! 256, each result stored at its place in the rig's order: `fast::grouped`), and on the rig reordered
//! once (`vertex_order::by_influence_count`, `Rig::reordered`). Each: the best of 20 runs,
//! a run skinning every clip at seven times ten times over, on one thread; the three in
//! turn, twice (`cargo run --release -p chasles-skin --example dib_grouping`).

use chasles_skin::fast::{dib, FastRig};
use chasles_skin::{gltf_load, joint_transforms, vertex_order, Pose};
#[path = "common/best.rs"]
mod common;
use common::best;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for m in [
        chasles_models::FOX,
        chasles_models::RIGGED_FIGURE,
        chasles_models::CESIUM_MAN,
    ] {
        let rig = gltf_load::load_slice(m.bytes, m.file)?;
        let grouped = FastRig::<4>::new(&rig)?;
        let own = grouped.clone().without_dib_grouping();
        let reordered =
            FastRig::<4>::new(&rig.reordered(&vertex_order::by_influence_count(&rig)?)?)?
                .without_dib_grouping();
        let mut poses = Vec::new();
        for (c, clip) in rig.animations.iter().enumerate() {
            for s in 0..7 {
                let pose = Pose::animated(&rig, c, clip.duration() * s as f32 / 6.0)?;
                poses.push(joint_transforms(&rig, &pose)?);
            }
        }
        let mut out = vec![[0f32; 6]; own.vertices().len()];
        let skinned = (own.vertices().len() * poses.len() * 10) as f64;
        let mut line = format!(
            "{}: grouped by the fast path: {}; M vertices/s:",
            rig.name,
            grouped.groups_dib()
        );
        for _ in 0..2 {
            for (name, fast) in [
                ("own order", &own),
                ("grouped", &grouped),
                ("reordered", &reordered),
            ] {
                let t = best(20, || {
                    for _ in 0..10 {
                        for p in &poses {
                            dib(fast, &p.dual_quats, &mut out, false).expect("dib");
                        }
                    }
                });
                line += &format!(" {name} {:.1}", skinned / t / 1e6);
            }
        }
        println!("{line}");
    }
    Ok(())
}
