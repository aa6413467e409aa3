//! The tour past Kavan et al. (§7's "motion blending" and "motion analysis and
//! compression"): the Fox's Walk and Run blended per joint by DLB (`chasles clip blend`),
//! and CesiumMan's walk compressed to a vertex tolerance with Slerp and with Squad
//! (`chasles clip compress`).

use anyhow::Result;
use chasles_paper::{Cell, Number, Section, Table};
use chasles_skin::clip_blend::{blend_clips, BlendOptions};
use chasles_skin::clip_compress::{compress, CompressOptions, Rotation};
use chasles_skin::pose::world;
use chasles_skin::{gltf_load, Method, Pose, Rig, Trs};

/// The Fox's hind foot (`b_LeftFoot02_018`) in Walk, Run and their 50/50 blend (time-warped),
/// side view: forward (z) against height (y), 48 phases of each.
fn foot_paths(rig: &Rig) -> Result<String> {
    use chasles_viz::plot::{lines_svg, Series};
    let (a, b) = (rig.clip_index("Walk")?, rig.clip_index("Run")?);
    let foot = rig
        .nodes
        .iter()
        .position(|n| n.name == "b_LeftFoot02_018")
        .ok_or_else(|| anyhow::anyhow!("the Fox has no b_LeftFoot02_018"))?;
    let rest: Vec<Trs> = rig.nodes.iter().map(|n| n.rest).collect();
    let (da, db) = (rig.animations[a].duration(), rig.animations[b].duration());
    let n = 48;
    let opts = |w: f64| BlendOptions {
        weight: w,
        sync: true,
        fps: Some(n as f64 / ((1.0 - w) * f64::from(da) + w * f64::from(db))),
        name: String::new(),
    };
    let path =
        |clip: &chasles_skin::animation::Animation, times: &[f32]| -> Result<Vec<(f64, f64)>> {
            times
                .iter()
                .map(|t| {
                    let w = world(
                        rig,
                        &Pose {
                            local: clip.sample(&rest, *t),
                        },
                    )?;
                    let p = w[foot].translation();
                    Ok((f64::from(p.z), f64::from(p.y)))
                })
                .collect()
        };
    let mut series = Vec::new();
    for (w, name, colour, dashed) in [
        (0.0, "Walk", "#1f5fbf", false),
        (1.0, "Run", "#c0392b", false),
        (0.5, "DLB blend, w = 0.5", "#000000", true),
        (0.25, "w = 0.25", "#7f7f7f", true),
    ] {
        let bl = blend_clips(rig, a, b, &opts(w))?;
        series.push(Series {
            name,
            colour,
            dashed,
            points: path(&bl.animation, &bl.times)?,
        });
    }
    Ok(lines_svg(
        &series,
        "Fox: left hind foot over one cycle, Walk, Run and their per-joint DLB blends (phase-aligned)",
        "forward z (model units)",
        "height y (model units)",
    ))
}

/// Blending and compression, with their pictures.
pub fn clips() -> Section {
    let mut s = Section::new(
        "Beyond Kavan et al. (§7): motion blending and clip compression with dual quaternions",
    );
    s.text(
        "§7 names motion blending and motion compression as uses of dual-quaternion blending to come. `chasles clip blend` blends two clips of one skeleton per joint: DLB of each node's local rotation and translation as a unit dual quaternion, shortest path, time-warped by phase with --sync. `chasles clip compress` drops key frames per joint (greedy: the worst frame first) while every vertex of the skinned mesh stays within a tolerance of the original clip at its own sampling, rotations rebuilt by Slerp (glTF LINEAR) or by Squad's keys and tangents (glTF CUBICSPLINE); the bound is checked on the written file loaded back.",
    );
    let fox = gltf_load::load_slice(chasles_models::FOX.bytes, chasles_models::FOX.file);
    s.try_figure(
        "clip-blend-feet.svg",
        fox.map_err(anyhow::Error::from)
            .and_then(|rig| foot_paths(&rig))
            .map(String::into_bytes),
        "The Fox's left hind foot over one gait cycle (side view) in Walk (blue), Run (red) and DLB blends of the two with Run's weight 0.5 (black, dashed) and 0.25 (grey): the blended stride and lift lie between the walk's and the run's. Fox: mesh CC0 1.0 (PixelMannen), rigging and animation CC-BY 4.0 (@tomkranis)",
    );
    let man = gltf_load::load_slice(
        chasles_models::CESIUM_MAN.bytes,
        chasles_models::CESIUM_MAN.file,
    );
    let measured = man.map_err(anyhow::Error::from).and_then(|rig| {
        let tolerances = [0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05];
        let mut rows = Vec::new();
        for d in tolerances {
            let mut row = vec![d];
            for rotation in [Rotation::Slerp, Rotation::Squad] {
                let opts = CompressOptions {
                    tolerance: d,
                    rotation,
                    method: Method::Dqs,
                };
                let c = compress(&rig, 0, &opts)?;
                row.push(100.0 * c.ratio());
                row.push(c.worst.distance);
            }
            rows.push(row);
        }
        Ok::<_, anyhow::Error>(rows)
    });
    match measured {
        Ok(rows) => {
            let mut t = Table::new(
                "CesiumMan's walk (48 frames, 2736 keys) compressed with DQS as the measure: kept keys and worst vertex error",
                &["tolerance", "Slerp kept %", "Slerp worst", "Squad kept %", "Squad worst"],
            );
            for r in &rows {
                t.row(vec![
                    Cell::Number(Number::sci(r[0], 1)),
                    Cell::Number(Number::fixed(r[1], 1)),
                    Cell::Number(Number::sci(r[2], 2)),
                    Cell::Number(Number::fixed(r[3], 1)),
                    Cell::Number(Number::sci(r[4], 2)),
                ]);
            }
            s.table(t);
            use chasles_viz::plot::{lines_svg, Series};
            let series = [
                Series {
                    name: "Slerp",
                    colour: "#1f5fbf",
                    dashed: false,
                    points: rows.iter().map(|r| (r[0].log10(), r[1])).collect(),
                },
                Series {
                    name: "Squad",
                    colour: "#c0392b",
                    dashed: false,
                    points: rows.iter().map(|r| (r[0].log10(), r[3])).collect(),
                },
            ];
            s.figure(
                "clip-compress-keys.svg",
                lines_svg(
                    &series,
                    "CesiumMan's walk: kept keys against the vertex tolerance",
                    "log10 tolerance (model units)",
                    "kept keys (% of the clip's)",
                )
                .into_bytes(),
                "Kept keys (% of the original clip's) against the tolerance on every vertex, Slerp (blue) and Squad's tangents (red), greedy selection per joint: Squad keeps fewer from 0.001 up (33 % against 46 % at 0.01), more at the tightest, 0.0005 (88 % against 86 %). CesiumMan, CC-BY 4.0 with trademark limitations, © 2017 Cesium",
            );
        }
        Err(e) => s.text(format!(
            "the compression could not be measured: failed: {e}"
        )),
    }
    s
}
