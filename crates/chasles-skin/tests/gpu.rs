//! The GPU shaders agree with the CPU reference (Kavan et al. 2006, §6): LBS, DQS and DIB on
//! the twisted cylinder at many angles (the candy wrapper included) and on CesiumMan's
//! walk, positions and normals to 1e-4 of the mesh's size. Runs on any adapter, Mesa's
//! software lavapipe included; with no adapter at all it says why and skips.
#![cfg(feature = "gpu")]

use chasles_skin::cylinder::{self, Motion};
use chasles_skin::gpu::{GpuError, GpuSkinner};
use chasles_skin::{gltf_load, joint_transforms, skin, Method, Pose, Rig};

fn gpu_for(rig: &Rig) -> Option<GpuSkinner> {
    usable(GpuSkinner::new(rig))
}

/// [`gpu_for`] on a fast-path layout.
fn gpu_for_fast(rig: &chasles_skin::fast::FastRig<4>) -> Option<GpuSkinner> {
    usable(GpuSkinner::from_fast(rig))
}

/// The skinner, or `None` (said on stderr) where there is no adapter; a panic on any
/// other error.
fn usable(made: Result<GpuSkinner, GpuError>) -> Option<GpuSkinner> {
    match made {
        Ok(g) => Some(g),
        Err(GpuError::NoAdapter(why)) => {
            eprintln!("skipping the GPU test: no adapter ({why}); install mesa-vulkan-drivers for lavapipe");
            None
        }
        Err(e) => panic!("GPU setup failed: {e}"),
    }
}

/// Largest position and normal differences between the GPU and the CPU, the positions
/// relative to the mesh's extent.
fn compare(rig: &Rig, gpu: &GpuSkinner, pose: &Pose, method: Method) -> (f32, f32) {
    let cpu = skin(rig, pose, method).unwrap();
    let g = gpu
        .skin(&joint_transforms(rig, pose).unwrap(), method)
        .unwrap();
    let extent = cpu
        .positions
        .iter()
        .flat_map(|p| p.to_array())
        .fold(0.0f32, |m, x| m.max(x.abs()))
        .max(1e-6);
    let dp = cpu
        .positions
        .iter()
        .zip(&g.positions)
        .map(|(a, b)| (*a - *b).norm())
        .fold(0.0f32, f32::max);
    let dn = cpu
        .normals
        .iter()
        .zip(&g.normals)
        .map(|(a, b)| (*a - *b).norm())
        .fold(0.0f32, f32::max);
    (dp / extent, dn)
}

#[test]
fn gpu_matches_cpu_on_the_cylinder() {
    let rig = cylinder::twisted_cylinder();
    let Some(gpu) = gpu_for(&rig) else { return };
    eprintln!("adapter: {}", gpu.adapter());
    for motion in [Motion::Twist, Motion::Bend] {
        for deg in [0.0f32, 45.0, 90.0, 135.0, 170.0, 179.0] {
            let pose = cylinder::pose(&rig, motion, deg.to_radians());
            for m in [Method::Lbs, Method::Dqs, Method::Dib] {
                let (dp, dn) = compare(&rig, &gpu, &pose, m);
                assert!(
                    dp < 1e-4 && dn < 1e-4,
                    "{motion:?} {deg}° {}: {dp:e} {dn:e}",
                    m.name()
                );
            }
        }
    }
    // The candy wrapper on the GPU too: the middle ring collapses under LBS only.
    let pose = cylinder::pose(&rig, Motion::Twist, std::f32::consts::PI);
    let jt = joint_transforms(&rig, &pose).unwrap();
    let lbs = gpu.skin(&jt, Method::Lbs).unwrap();
    let dqs = gpu.skin(&jt, Method::Dqs).unwrap();
    let mid = cylinder::RINGS / 2;
    assert!(cylinder::ring_radius(&lbs.positions, mid) < 0.01 * cylinder::RADIUS);
    assert!((cylinder::ring_radius(&dqs.positions, mid) - cylinder::RADIUS).abs() < 1e-4);
}

#[test]
fn gpu_matches_cpu_on_a_real_character() {
    let m = chasles_models::CESIUM_MAN;
    let rig = gltf_load::load_slice(m.bytes, m.file).unwrap();
    let Some(gpu) = gpu_for(&rig) else { return };
    let d = rig.animations[0].duration();
    for k in 0..5 {
        let pose = Pose::animated(&rig, 0, d * k as f32 / 4.0).unwrap();
        for m in [Method::Lbs, Method::Dqs, Method::Dib] {
            let (dp, dn) = compare(&rig, &gpu, &pose, m);
            assert!(
                dp < 1e-4 && dn < 1e-4,
                "t {k}/4 {}: {dp:e} {dn:e}",
                m.name()
            );
        }
    }
}

#[test]
fn gpu_errors_are_typed() {
    let rig = cylinder::twisted_cylinder();
    let Some(gpu) = gpu_for(&rig) else { return };
    let jt = joint_transforms(&rig, &Pose::rest(&rig)).unwrap();
    assert!(matches!(
        gpu.skin(&jt, Method::Log),
        Err(GpuError::Unsupported("log"))
    ));
    let other = chasles_skin::JointTransforms::identity(5);
    assert!(matches!(
        gpu.skin(&other, Method::Lbs),
        Err(GpuError::JointCount {
            given: 5,
            joints: 2
        })
    ));
}

#[test]
fn gpu_matches_the_fast_path_on_a_synthetic_mesh() {
    use chasles_skin::fast::{dqs, dual_quats8, lbs, matrices12};
    let rig = chasles_skin::synthetic::rig(5000, 54, 3);
    let jt = chasles_skin::synthetic::joints(54, 3);
    let Some(gpu) = gpu_for_fast(&rig) else {
        return;
    };
    let mut out = vec![[0f32; 6]; 5000];
    for m in [Method::Lbs, Method::Dqs] {
        match m {
            Method::Lbs => lbs(&rig, &matrices12(&jt), &mut out, false).unwrap(),
            _ => dqs(&rig, &dual_quats8(&jt), &mut out, false).unwrap(),
        }
        let g = gpu.skin(&jt, m).unwrap();
        let worst = out
            .iter()
            .zip(g.positions.iter().zip(&g.normals))
            .flat_map(|(c, (p, n))| {
                (0..3).map(move |k| {
                    (c[k] - p.to_array()[k])
                        .abs()
                        .max((c[3 + k] - n.to_array()[k]).abs())
                })
            })
            .fold(0.0f32, f32::max);
        assert!(worst < 1e-4, "{}: {worst:e}", m.name());
    }
    // The benchmark's clocks: one positive, finite time per pass, and a positive
    // bandwidth yardstick.
    let start = std::time::Instant::now();
    let times = gpu.shader_seconds(&jt, Method::Dqs, 5).unwrap();
    let wall = start.elapsed().as_secs_f64();
    assert_eq!(times.len(), 5);
    assert!(times.iter().all(|t| t.is_finite() && *t > 0.0), "{times:?}");
    // The passes ran inside the call: their times (the timestamp period applied) add up to
    // less than its wall-clock time.
    assert!(times.iter().sum::<f64>() < wall, "{times:?} in {wall} s");
    eprintln!("clock: {}", gpu.clock().name());
    assert!(gpu.stream_rate(1 << 20, 3).unwrap() > 0.0);
    // Reading into reused vectors gives what a fresh read gives.
    let mut reused = gpu.skin(&jt, Method::Lbs).unwrap();
    gpu.dispatch(&jt, Method::Dqs).unwrap();
    gpu.read_into(&mut reused).unwrap();
    let fresh = gpu.skin(&jt, Method::Dqs).unwrap();
    assert_eq!(reused.positions, fresh.positions);
    assert_eq!(reused.normals, fresh.normals);
    // Split into dispatches of 999 vertices (as for meshes over the binding limit): the
    // same result.
    let chunked = GpuSkinner::from_fast_in_chunks(&rig, 999).unwrap();
    for m in [Method::Lbs, Method::Dqs, Method::Dib] {
        let (a, b) = (gpu.skin(&jt, m).unwrap(), chunked.skin(&jt, m).unwrap());
        assert_eq!(a.positions, b.positions, "{}", m.name());
        assert_eq!(a.normals, b.normals);
    }
    // A joint matrix past the range every path keeps finite is refused before the
    // dispatch, naming the joint.
    let mut broken = jt.clone();
    broken.matrices[17].m[0][3] = f32::NAN;
    let e = gpu.skin(&broken, Method::Lbs).unwrap_err();
    assert!(e.to_string().contains("joint 17's translation[0]"), "{e}");
    // A result that is not finite anyway (joints whose rotation part is zero: DQS divides
    // by its length) is caught on the way back, naming the first vertex it reaches, in
    // whichever dispatch that vertex lies.
    let target = rig.vertices().len() / 2;
    let weighted = |v: &chasles_skin::fast::Vertex<4>| -> Vec<usize> {
        v.j.iter()
            .zip(v.w)
            .filter(|(_, w)| *w > 0.0)
            .map(|(j, _)| usize::from(*j))
            .collect()
    };
    let zeroed = weighted(&rig.vertices()[target]);
    let mut broken = jt.clone();
    for &j in &zeroed {
        broken.dual_quats[j].real = chasles::Quat::new(0.0, 0.0, 0.0, 0.0);
    }
    let first = rig
        .vertices()
        .iter()
        .position(|v| weighted(v).iter().all(|j| zeroed.contains(j)))
        .unwrap();
    assert!(first > 0);
    let past_first_dispatch = GpuSkinner::from_fast_in_chunks(&rig, first.div_ceil(2)).unwrap();
    for g in [&gpu, &past_first_dispatch] {
        assert!(matches!(
            g.skin(&broken, Method::Dqs),
            Err(GpuError::NonFinite(v)) if v == first
        ));
    }
}

#[test]
fn the_skinning_job_runs_on_the_gpu_as_on_the_cpu() {
    use chasles_skin::fast::{FastRig, Output, Palette, SkinningJob};
    let m = chasles_models::CESIUM_MAN;
    let rig = gltf_load::load_slice(m.bytes, m.file).unwrap();
    let fast = FastRig::<4>::new(&rig).unwrap();
    let Some(gpu) = gpu_for_fast(&fast) else {
        return;
    };
    let n = fast.vertices().len();
    let jt = joint_transforms(&rig, &Pose::animated(&rig, 0, 0.9).unwrap()).unwrap();
    for method in [Method::Lbs, Method::Dqs, Method::Dib] {
        let palette = Palette::from_joint_transforms(method, &fast, &jt, false).unwrap();
        let mut cpu = vec![[0f32; 6]; n];
        SkinningJob {
            rig: &fast,
            palette: &palette,
            output: Output::Packed(&mut cpu),
            parallel: true,
        }
        .run()
        .unwrap();
        let close = |got: &[f32], want: &[f32; 6]| {
            for k in 0..6 {
                assert!(
                    (got[k] - want[k]).abs() < 1e-4,
                    "{}: {got:?} vs {want:?}",
                    method.name()
                );
            }
        };
        // The same palette, every layout.
        let mut packed = vec![[0f32; 6]; n];
        gpu.run(&palette, Output::Packed(&mut packed)).unwrap();
        packed.iter().zip(&cpu).for_each(|(g, c)| close(g, c));
        let mut inter = vec![-1f32; n * 9];
        gpu.run(
            &palette,
            Output::Interleaved {
                data: &mut inter,
                stride: 9,
            },
        )
        .unwrap();
        for (g, c) in inter.chunks(9).zip(&cpu) {
            close(&g[..6], c);
            assert_eq!(&g[6..], &[-1.0; 3], "the rest of each vertex is left alone");
        }
        let (mut p, mut nr) = (vec![[0f32; 3]; n], vec![[0f32; 3]; n]);
        gpu.run(
            &palette,
            Output::Split {
                positions: &mut p,
                normals: &mut nr,
            },
        )
        .unwrap();
        for ((p, nr), c) in p.iter().zip(&nr).zip(&cpu) {
            close(&[p[0], p[1], p[2], nr[0], nr[1], nr[2]], c);
        }
    }
    // Methods without a shader, palettes of another rig and short outputs: typed errors.
    let log = Palette::from_joint_transforms(Method::Log, &fast, &jt, false).unwrap();
    let mut out = vec![[0f32; 6]; n];
    assert!(matches!(
        gpu.run(&log, Output::Packed(&mut out)),
        Err(GpuError::Unsupported("log"))
    ));
    let mut short = vec![[0f32; 6]; n - 1];
    let dqs = Palette::from_joint_transforms(Method::Dqs, &fast, &jt, false).unwrap();
    assert!(matches!(
        gpu.run(&dqs, Output::Packed(&mut short)),
        Err(GpuError::Rig(_))
    ));
    let fox = gltf_load::load_slice(chasles_models::FOX.bytes, "fox").unwrap();
    let fox = FastRig::<4>::new(&fox).unwrap();
    let fox_jt = chasles_skin::synthetic::joints(fox.joints(), 2);
    let other = Palette::from_joint_transforms(Method::Dqs, &fox, &fox_jt, false).unwrap();
    assert!(matches!(
        gpu.run(&other, Output::Packed(&mut out)),
        Err(GpuError::JointCount {
            given: 24,
            joints: 19
        })
    ));
}

#[test]
fn the_shader_takes_dib_constants_from_rust() {
    // The stopping rule is written once: the shader declares overrides and uses no literal.
    let wgsl = include_str!("../src/gpu/skin.wgsl");
    for o in [
        "override dib_precision: f32;",
        "override dib_stall: f32;",
        "override dib_updates: u32;",
    ] {
        assert!(wgsl.contains(o), "{o}");
    }
    let dib = &wgsl[wgsl.find("override dib_precision").unwrap()..];
    for literal in ["1e-5", "1e-3", "8u", "100.0"] {
        assert!(
            !dib.contains(literal),
            "DIB's shader writes {literal} itself"
        );
    }
    assert_eq!(chasles_skin::skinning::DIB_UPDATES, 8);
}

/// The reference, the fast path and the GPU keep one rule on what comes out: a vertex whose
/// position or normal is not finite is an error, and all three give it on the same poses
/// (scales at and past the edge of f32, scales of zero and below the smallest normal).
#[test]
fn cpu_and_gpu_reject_the_same_poses() {
    use chasles::{Quat, Vec3};
    let rig = cylinder::twisted_cylinder();
    let Some(gpu) = gpu_for(&rig) else { return };
    let fast = chasles_skin::fast::Skinner::new(&rig).unwrap();
    let turn = Quat::from_axis_angle(Vec3::new(1.0f32, 1.0, 0.0), 1.0).unwrap();
    let (mut ok, mut refused) = (0, 0);
    for scale in [1.0f32, 1e19, 1e25, 1e38, 3e38, f32::MAX, 0.0, 1e-30, 1e-45] {
        for shift in [0.0f32, 1e18, 1.1e18, 1e30, f32::MAX] {
            let mut pose = Pose::rest(&rig);
            let last = pose.local.len() - 1;
            pose.local[last].scale = Vec3::new(scale, scale, scale);
            pose.local[last].rotation = turn;
            pose.local[last].translation = Vec3::new(shift, 0.0, 0.0);
            let Ok(jt) = joint_transforms(&rig, &pose) else {
                refused += 1;
                continue;
            };
            for m in [Method::Lbs, Method::Dqs, Method::Dib] {
                let r = chasles_skin::skin_joints(&rig, &jt, m);
                let f = fast.skin(&rig, &jt, m);
                let g = gpu.skin(&jt, m);
                let what = format!("{} at scale {scale:e}, shift {shift:e}", m.name());
                assert_eq!(
                    r.is_ok(),
                    f.is_ok(),
                    "reference and fast path differ: {what}"
                );
                assert_eq!(
                    r.is_ok(),
                    g.is_ok(),
                    "CPU and GPU differ: {what}: {:?}",
                    g.err()
                );
                if let Err(e) = &r {
                    assert!(
                        matches!(
                            e,
                            chasles_skin::SkinError::OutOfReach { .. }
                                | chasles_skin::SkinError::NotFinite { .. }
                        ),
                        "{what}: {e}"
                    );
                    refused += 1;
                }
                for s in [r.ok(), f.ok(), g.ok()].into_iter().flatten() {
                    let mut all = s.positions.iter().chain(&s.normals);
                    assert!(all.all(|v| v.is_finite()), "{what}: non-finite output");
                    ok += 1;
                }
            }
        }
    }
    assert!(
        ok > 0 && refused > 0,
        "both outcomes met: {ok} ok, {refused} refused"
    );
}

/// DIB on the GPU (ScLERP in closed form for a vertex of at most two influences, Lemma 3)
/// and on the CPU's fast path (ScLERP in closed form there too, the iteration for the others)
/// agree within the stopping rule's reach on a mesh of one to four influences a vertex, in
/// any slots (weights of 0 between them too), with every other joint's dual quaternion
/// negated (the same transform: the closed form's hemisphere test), some joints turned by
/// up to 170° and some moved without turning (the logarithm's zero angle).
#[test]
fn gpu_dib_matches_the_fast_path_with_one_to_four_influences() {
    use chasles::{DualQuat, Quat, Vec3};
    use chasles_skin::fast::dib;
    let base = chasles_skin::synthetic::rig(4000, 54, 11);
    let rig = chasles_skin::synthetic::with_influences(&base, |i, k| {
        let h = (i * 7919 / 5) % 9;
        // Counts 1–4 in the first slots; two in slots 0 and 2, or 1 and 3; three around a
        // 0; one in slot 2, or in slot 1 (slot 0's weight 0).
        match h {
            0..=3 => k <= h,
            4 => k == 0 || k == 2,
            5 => k == 1 || k == 3,
            6 => k != 1,
            7 => k == 2,
            _ => k == 1,
        }
    });
    let mut jt = chasles_skin::synthetic::joints(54, 3);
    for (j, d) in jt.dual_quats.iter_mut().enumerate() {
        if j % 5 == 1 {
            let axis = Vec3::new(1.0, j as f32 * 0.3 - 2.0, 0.5);
            let q = Quat::from_axis_angle(axis, 2.97 * (j as f32 / 54.0)).unwrap();
            *d = DualQuat::from_rotation_translation(q, Vec3::new(0.5, -1.0, 0.3));
        } else if j % 5 == 3 {
            *d = DualQuat::from_translation(Vec3::new(j as f32 * 0.05, 1.0, -0.5));
        }
        if j % 2 == 1 {
            *d = -*d;
        }
    }
    jt.matrices = jt.dual_quats.iter().map(|d| d.to_matrix4()).collect();
    let Some(gpu) = gpu_for_fast(&rig) else {
        return;
    };
    let mut out = vec![[0f32; 6]; 4000];
    dib(&rig, &jt.dual_quats, &mut out, false).unwrap();
    let g = gpu.skin(&jt, Method::Dib).unwrap();
    for (k, (c, (p, n))) in out
        .iter()
        .zip(g.positions.iter().zip(&g.normals))
        .enumerate()
    {
        let (p, n) = (p.to_array(), n.to_array());
        for i in 0..3 {
            assert!(
                (c[i] - p[i]).abs() < 1e-4 && (c[3 + i] - n[i]).abs() < 1e-4,
                "vertex {k}: {c:?} against {p:?} {n:?}"
            );
        }
    }
}
