//! Skinning speed (issue: vertices per second per method, one thread and all threads, on
//! meshes of 10⁵ and 10⁶ vertices, 54 joints, 4 influences; in the same run: DQS written
//! the obvious way with nalgebra's UnitDualQuaternion, a careful DQS on glam::Quat pairs,
//! LBS with glam::Affine3A, and a memory copy of 72 bytes per vertex for the bandwidth
//! bound).
//!
//! `cargo bench -p chasles-skin --bench skin`

use chasles_skin::fast::{
    clusters, dib, dqs, dual_quats8, lbs, log, matrices12, qlb, sbs, skin_pose, twists, Out,
};
use chasles_skin::synthetic;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{Affine3A, Quat, Vec3, Vec3A};
use rayon::prelude::*;
use std::hint::black_box;

fn careful_glam_dqs(v: &[chasles_skin::fast::Vertex<4>], d: &[(Quat, Quat)], out: &mut [Out]) {
    for (o, v) in out.iter_mut().zip(v) {
        let (p0, _) = d[usize::from(v.j[0])];
        let (mut r, mut e) = (
            Quat::from_xyzw(0.0, 0.0, 0.0, 0.0),
            Quat::from_xyzw(0.0, 0.0, 0.0, 0.0),
        );
        for k in 0..4 {
            let (qr, qe) = d[usize::from(v.j[k])];
            let w = if qr.dot(p0) < 0.0 { -v.w[k] } else { v.w[k] };
            r += qr * w;
            e += qe * w;
        }
        let inv = 1.0 / r.length();
        let (r, e) = (r * inv, e * inv);
        let p = Vec3::from_array(v.p);
        let t = (e * r.conjugate()) * 2.0;
        let q = r * p + Vec3::new(t.x, t.y, t.z);
        let n = r * Vec3::from_array(v.n);
        *o = [q.x, q.y, q.z, n.x, n.y, n.z];
    }
}

fn glam_lbs(v: &[chasles_skin::fast::Vertex<4>], m: &[Affine3A], out: &mut [Out]) {
    for (o, v) in out.iter_mut().zip(v) {
        let mut a = m[usize::from(v.j[0])].matrix3 * v.w[0];
        let mut t = m[usize::from(v.j[0])].translation * v.w[0];
        for k in 1..4 {
            let mj = &m[usize::from(v.j[k])];
            a += mj.matrix3 * v.w[k];
            t += mj.translation * v.w[k];
        }
        let p = a * Vec3A::from_array(v.p) + t;
        let n = (a.inverse().transpose() * Vec3A::from_array(v.n)).normalize_or_zero();
        *o = [p.x, p.y, p.z, n.x, n.y, n.z];
    }
}

fn nalgebra_dqs(
    v: &[chasles_skin::fast::Vertex<4>],
    d: &[nalgebra::UnitDualQuaternion<f32>],
    out: &mut [Out],
) {
    for (o, v) in out.iter_mut().zip(v) {
        let pivot = d[usize::from(v.j[0])];
        let mut sum = nalgebra::DualQuaternion::from_real_and_dual(
            nalgebra::Quaternion::new(0.0, 0.0, 0.0, 0.0),
            nalgebra::Quaternion::new(0.0, 0.0, 0.0, 0.0),
        );
        for k in 0..4 {
            let q = d[usize::from(v.j[k])];
            let w = if q.as_ref().real.dot(&pivot.as_ref().real) < 0.0 {
                -v.w[k]
            } else {
                v.w[k]
            };
            sum += q.into_inner() * w;
        }
        let b = nalgebra::UnitDualQuaternion::new_normalize(sum);
        let p = b.transform_point(&nalgebra::Point3::new(v.p[0], v.p[1], v.p[2]));
        let n = b.transform_vector(&nalgebra::Vector3::new(v.n[0], v.n[1], v.n[2]));
        *o = [p.x, p.y, p.z, n.x, n.y, n.z];
    }
}

fn bench(c: &mut Criterion) {
    for n in [100_000usize, 1_000_000] {
        let rig = synthetic::rig(n, 54, 7);
        let jt = synthetic::joints(54, 7);
        let (m12, d8) = (matrices12(&jt), dual_quats8(&jt));
        let aff: Vec<Affine3A> = jt
            .matrices
            .iter()
            .map(|m| {
                Affine3A::from_cols_array(&[
                    m.m[0][0], m.m[1][0], m.m[2][0], m.m[0][1], m.m[1][1], m.m[2][1], m.m[0][2],
                    m.m[1][2], m.m[2][2], m.m[0][3], m.m[1][3], m.m[2][3],
                ])
            })
            .collect();
        let gq: Vec<(Quat, Quat)> = jt
            .dual_quats
            .iter()
            .map(|d| {
                (
                    Quat::from_xyzw(d.real.x, d.real.y, d.real.z, d.real.w),
                    Quat::from_xyzw(d.dual.x, d.dual.y, d.dual.z, d.dual.w),
                )
            })
            .collect();
        let na: Vec<nalgebra::UnitDualQuaternion<f32>> = jt
            .dual_quats
            .iter()
            .map(|d| {
                nalgebra::UnitDualQuaternion::new_unchecked(
                    nalgebra::DualQuaternion::from_real_and_dual(
                        nalgebra::Quaternion::new(d.real.w, d.real.x, d.real.y, d.real.z),
                        nalgebra::Quaternion::new(d.dual.w, d.dual.x, d.dual.y, d.dual.z),
                    ),
                )
            })
            .collect();
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
        g.bench_function("glam lbs (Affine3A), 1 thread", |b| {
            b.iter(|| glam_lbs(rig.vertices(), &aff, black_box(&mut out)))
        });
        g.bench_function("glam dqs (careful), 1 thread", |b| {
            b.iter(|| careful_glam_dqs(rig.vertices(), &gq, black_box(&mut out)))
        });
        g.bench_function("nalgebra dqs (obvious), 1 thread", |b| {
            b.iter(|| nalgebra_dqs(rig.vertices(), &na, black_box(&mut out)))
        });
        // Bandwidth bound: memcpy of 36 bytes per vertex reads 36 and writes 36 — the 72
        // bytes each skinned vertex must move (48 read, 24 written).
        let src = vec![1u8; n * 36];
        let mut dst = vec![0u8; n * 36];
        g.bench_function("memcpy 72 B moved per vertex, 1 thread", |b| {
            b.iter(|| {
                dst.copy_from_slice(black_box(&src));
                black_box(dst[n])
            })
        });
        // The bound on all threads: the same copy in the kernels' chunks of 4096 vertices.
        g.bench_function("memcpy 72 B moved per vertex, all threads", |b| {
            b.iter(|| {
                dst.par_chunks_mut(4096 * 36)
                    .zip(black_box(&src).par_chunks(4096 * 36))
                    .for_each(|(d, s)| d.copy_from_slice(s));
                black_box(dst[n])
            })
        });
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
/// vertex and split position/normal arrays (both through the stack stage).
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

criterion_group!(benches, bench, eight_influences, figure_1, job);
criterion_main!(benches);
