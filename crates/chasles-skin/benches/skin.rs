//! Skinning speed (issue: vertices per second per method, one thread and all threads, on
//! meshes of 10⁵ and 10⁶ vertices, 54 joints, 4 influences; in the same run the baselines
//! of `peers` — glam LBS with `Mat3A` sums, normals by the blended matrix and by its
//! cofactor, a careful glam DQS on `Vec4` pairs, nalgebra's DQS and LBS as its users call
//! them, each checked against an f64 reference in `tests/peers.rs` — a memory copy of
//! 72 bytes per vertex for the bandwidth bound, and the fast paths' loads and stores
//! alone, `fast::traffic`, for the bound of their own traffic). Criterion times each
//! kernel on its own, one after another; the closing table (`ratios`) times them all again
//! in interleaved rounds (`peers::measure`, the measurement behind `chasles skin --bench`)
//! and prints our speed over each baseline and each kernel's share of both bounds, round
//! by round.
//!
//! `cargo bench -p chasles-skin --bench skin`

use chasles_skin::fast::{
    clusters, dib, dqs, dual_quats8, lbs, log, matrices12, qlb, sbs, skin_pose, traffic, twists,
};
use chasles_skin::synthetic;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

use chasles_skin::peers;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    for n in [100_000usize, 1_000_000] {
        let rig = synthetic::rig(n, 54, 7);
        let jt = synthetic::joints(54, 7);
        let (m12, d8) = (matrices12(&jt), dual_quats8(&jt));
        let pj = peers::Joints::of(&jt);
        let tw = twists(&jt).unwrap();
        let cl = clusters(&rig);
        let mut out = vec![[0f32; 6]; n];
        let mut g = c.benchmark_group(format!("skin {n} vertices, 54 joints, 4 influences"));
        g.throughput(Throughput::Elements(n as u64));
        g.sample_size(if n > 500_000 { 10 } else { 20 });
        for parallel in [false, true] {
            let th = if parallel { "all threads" } else { "1 thread" };
            g.bench_function(format!("chasles lbs, {th}"), |b| {
                b.iter(|| lbs(&rig, &m12, black_box(&mut out), parallel).unwrap())
            });
            g.bench_function(format!("chasles dqs, {th}"), |b| {
                b.iter(|| dqs(&rig, &d8, black_box(&mut out), parallel).unwrap())
            });
            g.bench_function(format!("chasles log, {th}"), |b| {
                b.iter(|| log(&rig, &tw, black_box(&mut out), parallel).unwrap())
            });
            g.bench_function(format!("chasles qlb, {th}"), |b| {
                b.iter(|| qlb(&rig, &jt.dual_quats, black_box(&mut out), parallel).unwrap())
            });
            // Random joints make nearly every vertex its own cluster: SBS's worst case, a
            // rotation centre solved per vertex (a real rig has far fewer clusters; see
            // CesiumMan below).
            g.bench_function(format!("chasles sbs, {th}"), |b| {
                b.iter(|| sbs(&rig, &cl, &jt.dual_quats, black_box(&mut out), parallel).unwrap())
            });
            g.bench_function(format!("chasles dib, {th}"), |b| {
                b.iter(|| dib(&rig, &jt.dual_quats, black_box(&mut out), parallel).unwrap())
            });
        }
        // The baselines of `peers` and the two bounds (a copy of the 72 bytes each vertex
        // moves; the fast paths' loads and stores alone), on one and on all threads.
        let v = rig.vertices();
        let src = vec![1u8; n * 36];
        let mut dst = vec![0u8; n * 36];
        for parallel in [false, true] {
            let th = if parallel { "all threads" } else { "1 thread" };
            for (name, f) in peers::BASELINES {
                g.bench_function(format!("{name}, {th}"), |b| {
                    b.iter(|| peers::run(v, black_box(&mut out), parallel, &|v, o| f(v, &pj, o)))
                });
            }
            g.bench_function(format!("memcpy 72 B moved per vertex, {th}"), |b| {
                b.iter(|| {
                    peers::copy_bound(&src, &mut dst, 36, parallel);
                    black_box(dst[n])
                })
            });
            g.bench_function(format!("traffic: loads and stores alone, {th}"), |b| {
                b.iter(|| traffic(&rig, black_box(&mut out[..]), parallel).unwrap())
            });
        }
        g.finish();
    }
}

/// The layout with 8 influences (glTF's JOINTS_0 and JOINTS_1), every method on one thread:
/// 10⁵ vertices of 8 random joints each, the pose's joint data made in each run.
fn eight_influences(c: &mut Criterion) {
    let n = 100_000;
    let rig = synthetic::rig_with::<8>(n, 54, 7);
    let jt = synthetic::joints(54, 7);
    let mut out = vec![[0f32; 6]; n];
    let mut g = c.benchmark_group(format!("skin {n} vertices, 54 joints, 8 influences"));
    g.throughput(Throughput::Elements(n as u64));
    g.sample_size(20);
    for m in chasles_skin::Method::ALL {
        g.bench_function(format!("chasles {}, 1 thread", m.name()), |b| {
            b.iter(|| skin_pose(&rig, &jt, m, black_box(&mut out), false).unwrap())
        });
    }
    g.finish();
}

/// Kavan et al.'s Figure 1 comparison on a real character: every method on CesiumMan
/// (3273 vertices, 19 joints) mid-walk, one thread: the reference path, and the fast path
/// with the pose's joint data made in each run.
fn figure_1(c: &mut Criterion) {
    use chasles_skin::{gltf_load, joint_transforms, skin, Method, Pose};
    let m = chasles_models::CESIUM_MAN;
    let rig = gltf_load::load_slice(m.bytes, m.file).expect("the built-in CesiumMan loads");
    let pose = Pose::animated(&rig, 0, 0.8).unwrap();
    let mut g = c.benchmark_group("CesiumMan, 3273 vertices, 1 thread");
    g.throughput(Throughput::Elements(rig.mesh.positions.len() as u64));
    for m in Method::ALL {
        g.bench_function(format!("{} (reference)", m.name()), |b| {
            b.iter(|| skin(&rig, &pose, m).unwrap())
        });
    }
    let fast = chasles_skin::fast::FastRig::<4>::new(&rig).unwrap();
    let mut out = vec![[0f32; 6]; rig.mesh.positions.len()];
    for m in Method::ALL {
        g.bench_function(format!("{} (fast, with the pose)", m.name()), |b| {
            b.iter(|| {
                let jt = joint_transforms(&rig, &pose).unwrap();
                skin_pose(&fast, &jt, m, &mut out, false).unwrap()
            })
        });
    }
    g.finish();
}

/// The skinning job against the per-method functions it replaced, side by side: every
/// method at 10⁵ vertices on one thread, the palette made once (a job's own cost), into the
/// packed layout (the kernels' own: no copy), an interleaved vertex buffer of 8 floats a
/// vertex and split position/normal arrays (both written in place by the kernels' stores).
fn job(c: &mut Criterion) {
    use chasles_skin::fast::{Output, Palette, SkinningJob};
    let n = 100_000;
    let rig = synthetic::rig(n, 54, 7);
    let jt = synthetic::joints(54, 7);
    let mut out = vec![[0f32; 6]; n];
    let mut inter = vec![0f32; n * 8];
    let (mut p, mut nr) = (vec![[0f32; 3]; n], vec![[0f32; 3]; n]);
    let mut g = c.benchmark_group(format!(
        "job {n} vertices, 54 joints, 4 influences, 1 thread"
    ));
    g.throughput(Throughput::Elements(n as u64));
    g.sample_size(20);
    for m in chasles_skin::Method::ALL {
        let palette = Palette::from_joint_transforms(m, &rig, &jt, false).unwrap();
        let run = |output: Output<'_>| {
            SkinningJob {
                rig: &rig,
                palette: &palette,
                output,
                parallel: false,
            }
            .run()
            .unwrap()
        };
        g.bench_function(
            format!("{} skin_pose (palette made in the run)", m.name()),
            |b| b.iter(|| skin_pose(&rig, &jt, m, black_box(&mut out), false).unwrap()),
        );
        g.bench_function(format!("{} job, packed", m.name()), |b| {
            b.iter(|| run(Output::Packed(black_box(&mut out))))
        });
        g.bench_function(format!("{} job, interleaved stride 8", m.name()), |b| {
            b.iter(|| {
                run(Output::Interleaved {
                    data: black_box(&mut inter),
                    stride: 8,
                })
            })
        });
        g.bench_function(format!("{} job, split", m.name()), |b| {
            b.iter(|| {
                run(Output::Split {
                    positions: black_box(&mut p),
                    normals: black_box(&mut nr),
                })
            })
        });
    }
    g.finish();
}

/// The peer ratios and the shares of both bounds in one table: every kernel, baseline, the
/// copy and the traffic in interleaved rounds (`peers::measure`), so that each ratio is
/// taken within a round.
fn ratios(_: &mut Criterion) {
    let load = peers::Load::start();
    let mut tables = Vec::new();
    for (n, rounds) in [(100_000, 21), (1_000_000, 7)] {
        for threads in [1, rayon::current_num_threads()] {
            tables.push(peers::measure(n, threads, rounds).unwrap());
        }
    }
    println!("\n{}", peers::markdown(&tables));
    for note in peers::cache_notes(&tables, peers::last_level_cache()) {
        println!("{note}");
    }
    if let Some(others) = load.others() {
        println!(
            "other processes kept {:.0}% of the CPUs busy",
            others * 100.0
        );
    }
}

criterion_group!(benches, bench, eight_influences, figure_1, job, ratios);
criterion_main!(benches);
