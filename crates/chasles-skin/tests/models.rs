//! The five real rigged models built into `chasles-models` (see its README): every one loads,
//! plays its clips and skins with every method; the rest pose reproduces the bind mesh;
//! linear blending loses volume where DQS does not; bad files get errors, not panics.

use chasles::Vec3;
use chasles_skin::animation::{Channel, Interpolation, Path as P};
use chasles_skin::cylinder::{self, Motion};
use chasles_skin::{
    gltf_load, joint_transforms, skin, skin_joints, Influences, JointTransforms, Method, Pose,
    SkinError,
};
use std::path::PathBuf;

/// A rig of `joints` root joints (identity rest transforms and inverse bind matrices, no
/// clips) over `mesh`, moved by `influences`.
fn flat_rig(
    name: &str,
    mesh: chasles_skin::Mesh,
    joints: usize,
    influences: Influences,
) -> Result<chasles_skin::Rig, SkinError> {
    let nodes = (0..joints)
        .map(|i| chasles_skin::Node {
            name: format!("j{i}"),
            parent: None,
            rest: Default::default(),
        })
        .collect();
    chasles_skin::Rig::new(
        name.into(),
        mesh,
        nodes,
        (0..joints).collect(),
        vec![chasles::Mat4::identity(); joints],
        influences,
        Vec::new(),
    )
}

/// A built-in model as a file (the tests load by path, as users do).
fn data(name: &str) -> PathBuf {
    chasles_models::on_disk().unwrap().join(name)
}

/// The scale positions are compared at: the farthest vertex from the origin, at least 1.
fn size(rig: &chasles_skin::Rig) -> f32 {
    rig.mesh
        .positions
        .iter()
        .fold(1.0f32, |m, p| m.max(p.norm()))
}

/// (file, vertices, joints, clips) of every built-in model, from its README.
fn models() -> impl Iterator<Item = (&'static str, usize, usize, usize)> {
    chasles_models::ALL
        .into_iter()
        .map(|m| (m.file, m.vertices, m.joints, m.clips))
}

#[test]
fn every_model_loads_plays_and_skins_with_every_method() {
    for (file, verts, joints, clips) in models() {
        let rig = gltf_load::load(&data(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(
            rig.name, file,
            "a rig is named by its file name, not its path"
        );
        // The bytes built in load to the same rig as the file.
        let built_in = chasles_models::by_file(file).unwrap();
        let from_bytes = gltf_load::load_slice(built_in.bytes, file).unwrap();
        assert_eq!(from_bytes.mesh.positions, rig.mesh.positions, "{file}");
        assert_eq!(from_bytes.joints.len(), rig.joints.len(), "{file}");
        assert_eq!(
            (
                rig.mesh.positions.len(),
                rig.joints.len(),
                rig.animations.len()
            ),
            (verts, joints, clips),
            "{file}"
        );
        for v in 0..verts {
            let s: f32 = rig.influences.of(v).map(|(_, w)| w).sum();
            assert!(
                (s - 1.0).abs() < 1e-6,
                "{file}: vertex {v} weights sum to {s}"
            );
        }
        // The bind pose (C_j = I) reproduces the bind mesh with every method.
        let size = rig
            .mesh
            .positions
            .iter()
            .fold(0.0f32, |m, p| m.max(p.norm()));
        for m in Method::ALL {
            let bind = skin_joints(&rig, &JointTransforms::identity(joints), m).unwrap();
            let err = bind
                .positions
                .iter()
                .zip(&rig.mesh.positions)
                .map(|(a, b)| (*a - *b).norm())
                .fold(0.0f32, f32::max);
            assert!(
                err < 1e-5 * size.max(1.0),
                "{file} {m:?}: bind pose moves vertices by {err}"
            );
            let nerr = bind
                .normals
                .iter()
                .zip(&rig.mesh.normals)
                .map(|(a, b)| (*a - *b).norm())
                .fold(0.0f32, f32::max);
            assert!(
                nerr < 1e-5,
                "{file} {m:?}: bind pose turns normals by {nerr}"
            );
        }
        for (c, clip) in rig.animations.iter().enumerate() {
            for k in 0..5 {
                let t = clip.duration() * k as f32 / 4.0;
                let pose = Pose::animated(&rig, c, t).unwrap();
                for m in Method::ALL {
                    let s = skin(&rig, &pose, m)
                        .unwrap_or_else(|e| panic!("{file} clip {c} t {t} {m:?}: {e}"));
                    assert!(s.positions.iter().all(|p| p.is_finite()));
                    assert!(
                        s.normals.iter().all(|n| (n.norm() - 1.0).abs() < 1e-3),
                        "{file} {m:?}: normals unit"
                    );
                }
                // The rigid methods agree with each other far more than with LBS where joints meet.
                let dqs = skin(&rig, &pose, Method::Dqs).unwrap();
                let dib = skin(&rig, &pose, Method::Dib).unwrap();
                let d = dqs
                    .positions
                    .iter()
                    .zip(&dib.positions)
                    .map(|(a, b)| (*a - *b).norm())
                    .fold(0.0f32, f32::max);
                assert!(
                    d < 0.05 * size.max(1.0),
                    "{file}: DQS and DIB differ by {d}"
                );
            }
        }
    }
}

/// The smallest determinant of LBS's blended 3×3 over a clip (volume lost where < 1).
fn lbs_min_det(file: &str, clip: &str) -> f32 {
    let rig = gltf_load::load(&data(file)).unwrap();
    let c = rig
        .animations
        .iter()
        .position(|a| a.name == clip)
        .unwrap_or(0);
    let over = chasles_skin::volume::lbs_volume_over_clip(&rig, c, 40).unwrap();
    assert_eq!(over.len(), 41);
    over.iter().map(|x| x.1).fold(f32::INFINITY, f32::min)
}

#[test]
fn linear_blending_loses_volume_on_the_real_characters() {
    // Data README: CesiumMan's walk reaches 0.47, Fox's Run 0.51 (an independent reader).
    let c = lbs_min_det("CesiumMan.glb", "");
    let f = lbs_min_det("Fox.glb", "Run");
    assert!((c - 0.47).abs() < 0.03, "CesiumMan {c}");
    assert!((f - 0.51).abs() < 0.03, "Fox {f}");
}

#[test]
fn the_candy_wrapper_by_number() {
    let rig = cylinder::twisted_cylinder();
    let lbs = cylinder::measure(&rig, Method::Lbs, Motion::Twist, std::f32::consts::PI).unwrap();
    let dqs = cylinder::measure(&rig, Method::Dqs, Motion::Twist, std::f32::consts::PI).unwrap();
    assert!(lbs.radius < 0.01, "LBS collapses: {lbs:?}");
    assert!(lbs.volume < 0.85);
    assert!(
        dqs.radius > 0.99 && (dqs.volume - 1.0).abs() < 0.01,
        "DQS keeps the shape: {dqs:?}"
    );
    for deg in [0.0f32, 45.0, 90.0, 135.0, 180.0] {
        let lbs = cylinder::measure(&rig, Method::Lbs, Motion::Twist, deg.to_radians()).unwrap();
        // LBS's middle ring of a twist by θ has radius cos(θ/2) (half of each rotation).
        assert!(
            (lbs.radius - (deg.to_radians() / 2.0).cos()).abs() < 2e-3,
            "{deg}: {lbs:?}"
        );
        for m in [Method::Dqs, Method::Dib, Method::Log] {
            let r = cylinder::measure(&rig, m, Motion::Twist, deg.to_radians()).unwrap();
            assert!(r.radius > 0.999, "{m:?} {deg}: {r:?}");
        }
    }
    // Bending: DQS bulges a little (about 21 % at 150°), LBS thins.
    let dqs = cylinder::measure(&rig, Method::Dqs, Motion::Bend, 150f32.to_radians()).unwrap();
    let lbs = cylinder::measure(&rig, Method::Lbs, Motion::Bend, 150f32.to_radians()).unwrap();
    assert!(dqs.bulge > 1.15 && dqs.bulge < 1.3, "{dqs:?}");
    assert!(lbs.radius < 0.75 && lbs.bulge < 1.05, "{lbs:?}");
}

#[test]
fn clip_sampling_follows_the_gltf_rules() {
    let ch = |interpolation, values: Vec<[f32; 4]>| Channel {
        node: 0,
        path: P::Translation,
        interpolation,
        times: vec![0.0, 1.0, 3.0],
        values,
    };
    let lin = ch(
        Interpolation::Linear,
        vec![[0.0; 4], [1.0, 2.0, 0.0, 0.0], [3.0, 2.0, 0.0, 0.0]],
    );
    assert_eq!(lin.sample(-1.0), [0.0; 4]);
    assert_eq!(lin.sample(0.5), [0.5, 1.0, 0.0, 0.0]);
    assert_eq!(lin.sample(2.0), [2.0, 2.0, 0.0, 0.0]);
    assert_eq!(lin.sample(9.0), [3.0, 2.0, 0.0, 0.0]);
    let step = ch(Interpolation::Step, lin.values.clone());
    assert_eq!(step.sample(0.99), [0.0; 4]);
    assert_eq!(step.sample(1.0), [1.0, 2.0, 0.0, 0.0]);
    // Cubic spline through (0, 0), (1, 1), (3, 1) with zero tangents: Hermite smoothstep.
    let z = [0.0; 4];
    let cub = ch(
        Interpolation::CubicSpline,
        vec![
            z,
            [0.0; 4],
            z,
            z,
            [1.0, 0.0, 0.0, 0.0],
            z,
            z,
            [1.0, 0.0, 0.0, 0.0],
            z,
        ],
    );
    assert!((cub.sample(0.5)[0] - 0.5).abs() < 1e-6);
    assert!((cub.sample(0.25)[0] - (3.0 * 0.0625 - 2.0 * 0.015625)).abs() < 1e-6);
    assert!(cub.validate(1).is_ok() && lin.validate(1).is_ok());
    assert!(
        ch(Interpolation::CubicSpline, lin.values.clone())
            .validate(1)
            .is_err(),
        "cubic needs 3 values per key"
    );
    // Rotations interpolate by Slerp the shorter way.
    let rot = Channel {
        node: 0,
        path: P::Rotation,
        interpolation: Interpolation::Linear,
        times: vec![0.0, 1.0],
        values: vec![
            [1.0, 0.0, 0.0, 0.0],
            [-(0.5f32.cos()), 0.0, 0.0, -(0.5f32.sin())],
        ],
    };
    let q = chasles::Quat::from_array(rot.sample(0.5));
    assert!(
        (q.z - 0.25f32.sin()).abs() < 1e-6 && (q.w - 0.25f32.cos()).abs() < 1e-6,
        "{q:?}"
    );
}

#[test]
fn influences_from_rows_of_slots_are_those_from_lists() {
    // Four slots a vertex, as glTF and numpy hold them: zero weights (dropped), weights out
    // of order (sorted heaviest first) and not summing to 1 (scaled).
    let (joints, weights): (Vec<usize>, Vec<f32>) = (0..200u32)
        .flat_map(|v| {
            (0..4u32).map(move |k| {
                let h = v.wrapping_mul(2_654_435_761).rotate_left(k * 7) ^ (k * 40_503);
                let w = if h % 5 == 0 {
                    0.0
                } else {
                    (h % 97) as f32 / 13.0 + 0.25 * (k % 2) as f32
                };
                ((h % 11) as usize, if k == 0 && w == 0.0 { 0.5 } else { w })
            })
        })
        .unzip();
    let (joints, weights) = (&joints, &weights);
    let row = |v: usize| (0..4).map(move |k| (joints[4 * v + k], weights[4 * v + k]));
    let lists: Vec<Vec<(usize, f32)>> = (0..200).map(|v| row(v).collect()).collect();
    let by_rows = Influences::from_rows((0..200).map(row), 11).unwrap();
    assert_eq!(by_rows, Influences::from_lists(&lists, 11).unwrap());
    assert_eq!(by_rows.vertices(), 200);
    // (`from_lists` calls `from_rows`: the values themselves, made here.) Each vertex's
    // positive weights, heaviest first (ties in slot order), divided by their f64 sum.
    let mut zeros = 0;
    for (v, list) in lists.iter().enumerate() {
        let mut kept: Vec<(usize, f32)> = list.iter().copied().filter(|p| p.1 > 0.0).collect();
        zeros += list.len() - kept.len();
        kept.sort_by(|a, b| b.1.total_cmp(&a.1));
        let sum: f64 = kept.iter().map(|p| f64::from(p.1)).sum();
        let want: Vec<(usize, f32)> = kept
            .iter()
            .map(|&(j, w)| (j, (f64::from(w) / sum) as f32))
            .collect();
        assert_eq!(by_rows.of(v).collect::<Vec<_>>(), want, "vertex {v}");
    }
    assert!(zeros > 50, "{zeros} weights of 0 dropped");
    // The same errors, naming the same vertex.
    let bad = |v: usize| {
        let w = if v == 150 { f32::NAN } else { 1.0 };
        [(0usize, w)].into_iter()
    };
    assert!(matches!(
        Influences::from_rows((0..200).map(bad), 1),
        Err(SkinError::BadWeights { vertex: 150, .. })
    ));
    assert!(matches!(
        Influences::from_rows((0..200).map(row), 10),
        Err(SkinError::JointOutOfRange {
            joint: 10,
            joints: 10,
            ..
        })
    ));
}

#[test]
fn a_layout_built_by_hand_has_its_weights_checked() {
    use chasles_skin::fast::{FastRig, Vertex, WEIGHT_SUM_TOLERANCE};
    let centres = vec![Vec3::zero(); 3];
    let vertex = |w: [f32; 4]| Vertex {
        p: [1.0, 0.0, 0.0],
        n: [0.0, 0.0, 1.0],
        j: [0, 1, 2, 0],
        w,
    };
    let with_second = |w: [f32; 4]| {
        FastRig::from_vertices(
            vec![vertex([1.0, 0.0, 0.0, 0.0]), vertex(w)],
            centres.clone(),
        )
    };
    // Weights summing to 1 to rounding, the heaviest anywhere: taken as they are.
    let f = with_second([0.1, 0.7, 0.2, 0.0]).unwrap();
    assert_eq!(f.vertices()[1].w, [0.1, 0.7, 0.2, 0.0]);
    assert!(with_second([0.5, 0.5 + WEIGHT_SUM_TOLERANCE / 2.0, 0.0, 0.0]).is_ok());
    for (w, says) in [
        (
            [0.5, f32::NAN, 0.5, 0.0],
            "weight NaN for joint 1 is negative or not finite",
        ),
        (
            [1.5, -0.5, 0.0, 0.0],
            "weight -0.5 for joint 1 is negative or not finite",
        ),
        ([0.5, 0.5, f32::INFINITY, 0.0], "weight inf for joint 2"),
        ([0.25, 0.25, 0.0, 0.0], "the weights sum to 0.5, not 1"),
        ([0.0; 4], "the weights sum to 0, not 1"),
        ([0.5, 0.5, 0.5, 0.0], "the weights sum to 1.5, not 1"),
    ] {
        let e = with_second(w).unwrap_err();
        assert!(matches!(e, SkinError::BadWeights { vertex: 1, .. }), "{e}");
        assert!(e.to_string().contains(says), "{e}");
    }
    // A rig's own influences are laid out as `Rig::new` checked them (its fields are
    // public: weights that sum to 4 pass there), as the reference path takes them.
    let heavy = Influences {
        start: vec![0, 2],
        joints: vec![0, 1],
        weights: vec![2.0, 2.0],
    };
    let mesh = chasles_skin::Mesh {
        positions: vec![Vec3::new(1.0, 0.0, 0.0)],
        normals: vec![Vec3::new(0.0, 0.0, 1.0)],
        triangles: Vec::new(),
    };
    let rig = flat_rig("heavy", mesh, 2, heavy).unwrap();
    let f = FastRig::<4>::new(&rig).unwrap();
    assert_eq!(f.vertices()[0].w, [2.0, 2.0, 0.0, 0.0]);
}

#[test]
fn bad_rigs_get_errors_naming_the_problem() {
    assert!(matches!(
        Influences::from_lists(&[vec![(0, 0.5), (7, 0.5)]], 2),
        Err(SkinError::JointOutOfRange {
            vertex: 0,
            joint: 7,
            joints: 2
        })
    ));
    assert!(matches!(
        Influences::from_lists(&[vec![(0, 1.0)], vec![(0, -0.5), (1, 1.5)]], 2),
        Err(SkinError::BadWeights { vertex: 1, .. })
    ));
    assert!(matches!(
        Influences::from_lists(&[vec![(0, f32::NAN)]], 2),
        Err(SkinError::BadWeights { vertex: 0, .. })
    ));
    let e = Influences::from_lists(&[vec![(0, 0.0), (1, 0.0)]], 2).unwrap_err();
    assert!(e.to_string().contains("sum to zero"), "{e}");
    let dir = tempfile::tempdir().unwrap();
    // Truncated files: every cut gives an error, never a panic.
    let bytes = std::fs::read(data("RiggedSimple.glb")).unwrap();
    for cut in [
        10,
        100,
        1000,
        bytes.len() / 2,
        bytes.len() - 16,
        bytes.len() - 1,
    ] {
        let p = dir.path().join(format!("cut{cut}.glb"));
        std::fs::write(&p, &bytes[..cut]).unwrap();
        assert!(gltf_load::load(&p).is_err(), "cut at {cut} loaded");
    }
    // A JSON glTF whose buffer is shorter than its accessors say.
    let text = std::fs::read_to_string(data("SimpleSkin.gltf")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let uri = v["buffers"][0]["uri"].as_str().unwrap().to_string();
    let short = &uri[..uri.len() / 2];
    v["buffers"][0]["uri"] = serde_json::Value::String(short.to_string());
    let p = dir.path().join("short.gltf");
    std::fs::write(&p, v.to_string()).unwrap();
    let e = gltf_load::load(&p).unwrap_err();
    assert!(
        e.to_string().contains("truncated") || e.to_string().contains("base64"),
        "{e}"
    );
    // No skin, missing file, not glTF.
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for n in v["nodes"].as_array_mut().unwrap() {
        n.as_object_mut().unwrap().remove("skin");
    }
    let p = dir.path().join("noskin.gltf");
    std::fs::write(&p, v.to_string()).unwrap();
    assert!(gltf_load::load(&p)
        .unwrap_err()
        .to_string()
        .contains("nothing to skin"));
    assert!(matches!(
        gltf_load::load(&dir.path().join("nope.glb")),
        Err(SkinError::Io { .. })
    ));
    // Bytes in memory cannot refer to a buffer in a separate file.
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["buffers"][0]["uri"] = serde_json::Value::String("simple.bin".into());
    let e = gltf_load::load_slice(v.to_string().as_bytes(), "external.gltf").unwrap_err();
    assert!(e.to_string().contains("separate file"), "{e}");
    let p = dir.path().join("junk.glb");
    std::fs::write(&p, b"this is not gltf").unwrap();
    assert!(matches!(gltf_load::load(&p), Err(SkinError::Gltf { .. })));
    // An animation index or time out of range.
    let rig = gltf_load::load(&data("SimpleSkin.gltf")).unwrap();
    assert!(Pose::animated(&rig, 3, 0.0).is_err());
    assert!(Pose::animated(&rig, 0, f32::NAN).is_err());
    let _ = Vec3::<f32>::zero();
}

/// How far the fast path may stand from the reference path, relatively: rounding, but for
/// DIB the stopping rule's reach too. The reference stops where an update's norm is below
/// `DIB_PRECISION` (1e-5), up to twice that of a turn (a half-angle) and of a lever from the
/// exact blend, while the fast path's SIMD kernels end nearer it (a vertex of two
/// influences by ScLERP in closed form: `dib_of_two_influences_is_sclerp_to_rounding`).
fn reach(method: Method) -> f32 {
    match method {
        Method::Dib => 3.0 * chasles_skin::skinning::DIB_PRECISION,
        _ => 1e-5,
    }
}

/// DIB of a vertex of two influences is ScLERP (Lemma 3): the fast path takes it in closed
/// form, to rounding of the exact blend, where the reference path's iteration (the paper's
/// update from DLB's start, then the pass that finds the next below `DIB_PRECISION`) ends
/// within the stopping rule's reach. On every character's clips, each vertex of two
/// influences against DIB in f64 to 1e-13: the fast path's normals and positions within
/// 1e-6 (relatively). When written: 0.4e-7–4.6e-7 on the five models (ScLERP as a
/// weighted sum, `fast::lane::dib::sclerp`; 0.9e-7–4.4e-7 by the logarithm and
/// exponential), where the reference's reached 1.1e-7 and 2.2e-7 on SimpleSkin and RiggedSimple, 1.1e-6 on the
/// Fox, 1.3e-5 on RiggedFigure and 1.8e-5 on CesiumMan.
#[test]
fn dib_of_two_influences_is_sclerp_to_rounding() {
    use chasles_skin::fast::{skin_pose, uses_simd, FastRig};
    if !uses_simd(4) {
        // The portable path's DIB is the reference's own calls.
        eprintln!("no AVX2+FMA here: the fast path's DIB is the reference's");
        return;
    }
    let mut all = 0;
    for (file, _, _, _) in models() {
        let rig = gltf_load::load(&data(file)).unwrap();
        let size = f64::from(size(&rig));
        let fast = FastRig::<4>::new(&rig).unwrap();
        let (mut fast_off, mut reference_off, mut pairs) = (0f64, 0f64, 0);
        for (c, clip) in rig.animations.iter().enumerate() {
            for step in 0..5 {
                let pose = Pose::animated(&rig, c, clip.duration() * step as f32 / 4.0).unwrap();
                let jt = joint_transforms(&rig, &pose).unwrap();
                let reference = skin(&rig, &pose, Method::Dib).unwrap();
                let mut out = vec![[0f32; 6]; rig.mesh.positions.len()];
                skin_pose(&fast, &jt, Method::Dib, &mut out, false).unwrap();
                for (v, o) in out.iter().enumerate() {
                    let influences: Vec<(usize, f32)> = rig.influences.of(v).collect();
                    if influences.len() != 2 {
                        continue;
                    }
                    let q: Vec<chasles::DualQuat<f64>> = influences
                        .iter()
                        .map(|&(j, _)| jt.dual_quats[j].cast::<f64>().normalize().unwrap())
                        .collect();
                    let w: Vec<f64> = influences.iter().map(|&(_, w)| f64::from(w)).collect();
                    let sum: f64 = w.iter().sum();
                    let w: Vec<f64> = w.iter().map(|x| x / sum).collect();
                    let (b, _) = chasles::blend::dib::dib(&q, &w, 1e-13, 200).unwrap();
                    let n = b.real.rotate(rig.mesh.normals[v].cast::<f64>());
                    let n = n * (1.0 / n.norm());
                    let p = b.transform_point(rig.mesh.positions[v].cast::<f64>());
                    let off = |pos: Vec3<f32>, nrm: Vec3<f32>| {
                        ((pos.cast::<f64>() - p).norm() / size).max((nrm.cast::<f64>() - n).norm())
                    };
                    let fast_v = off(Vec3::new(o[0], o[1], o[2]), Vec3::new(o[3], o[4], o[5]));
                    fast_off = fast_off.max(fast_v);
                    reference_off =
                        reference_off.max(off(reference.positions[v], reference.normals[v]));
                    pairs += 1;
                }
            }
        }
        all += pairs;
        assert!(
            fast_off < 1e-6,
            "{file}: {fast_off:e} (the reference {reference_off:e})"
        );
        eprintln!("{file}: {pairs} vertices of two influences, farthest from f64's DIB: fast {fast_off:.1e}, reference {reference_off:.1e}");
    }
    assert!(all > 20_000, "{all} vertices of two influences");
}

#[test]
fn the_fast_path_agrees_with_the_reference() {
    use chasles_skin::fast::{clusters, dib, dqs, lbs, qlb, sbs, skin_pose, FastRig};
    for (file, _, _, _) in models() {
        let rig = gltf_load::load(&data(file)).unwrap();
        let size = size(&rig);
        let fast = FastRig::<4>::new(&rig).unwrap();
        let fast8 = FastRig::<8>::new(&rig).unwrap();
        for (c, clip) in rig.animations.iter().enumerate() {
            let pose = Pose::animated(&rig, c, clip.duration() * 0.61).unwrap();
            let jt = joint_transforms(&rig, &pose).unwrap();
            for method in Method::ALL {
                let want = skin(&rig, &pose, method).unwrap();
                for parallel in [false, true] {
                    let mut out = vec![[0f32; 6]; rig.mesh.positions.len()];
                    let mut out8 = out.clone();
                    skin_pose(&fast, &jt, method, &mut out, parallel).unwrap();
                    skin_pose(&fast8, &jt, method, &mut out8, parallel).unwrap();
                    let reach = reach(method);
                    for (v, (o, o8)) in out.iter().zip(&out8).enumerate() {
                        let p = Vec3::new(o[0], o[1], o[2]);
                        let n = Vec3::new(o[3], o[4], o[5]);
                        assert!(
                            (p - want.positions[v]).norm() <= reach * size,
                            "{file} {method:?} vertex {v}: {p:?} vs {:?}",
                            want.positions[v]
                        );
                        assert!(
                            (n - want.normals[v]).norm() <= reach,
                            "{file} {method:?} normal {v}: {}",
                            (n - want.normals[v]).norm()
                        );
                        // The two layouts: equal to rounding (the SIMD kernels where the
                        // processor has them, else the scalar ones).
                        for k in 0..6 {
                            assert!(
                                (o[k] - o8[k]).abs() <= 1e-6 * size,
                                "{file} {method:?} vertex {v}: K = 4 {o:?}, K = 8 {o8:?}"
                            );
                        }
                    }
                }
            }
        }
    }
    let rig = gltf_load::load(&data("Fox.glb")).unwrap();
    let fast = FastRig::<4>::new(&rig).unwrap();
    let mut short = vec![[0f32; 6]; 3];
    assert!(
        lbs(&fast, &[[0.0; 12]; 24], &mut short, false).is_err(),
        "output size checked"
    );
    let mut out = vec![[0f32; 6]; 1728];
    assert!(
        dqs(&fast, &[[0.0; 8]; 3], &mut out, false).is_err(),
        "joint count checked"
    );
    let three = [chasles::DualQuat::identity(); 3];
    assert!(
        dib(&fast, &three, &mut out, false).is_err(),
        "joint count checked"
    );
    assert!(
        qlb(&fast, &three, &mut out, false).is_err(),
        "joint count checked"
    );
    let other =
        clusters(&FastRig::<4>::new(&gltf_load::load(&data("SimpleSkin.gltf")).unwrap()).unwrap());
    let d = vec![chasles::DualQuat::identity(); fast.joints()];
    assert!(
        sbs(&fast, &other, &d, &mut out, false).is_err(),
        "clusters of another rig refused"
    );
    // A NaN joint: NaN out for the vertices it moves, no panic.
    let mut d = d;
    d[usize::from(fast.vertices()[0].j[0])].real.w = f32::NAN;
    for method in [Method::Dib, Method::Qlb, Method::Sbs] {
        match method {
            Method::Dib => dib(&fast, &d, &mut out, true),
            Method::Qlb => qlb(&fast, &d, &mut out, true),
            _ => sbs(&fast, &clusters(&fast), &d, &mut out, true),
        }
        .unwrap();
        assert!(out[0].iter().all(|x| x.is_nan()), "{method:?}");
    }
}

#[test]
fn the_skinner_takes_every_method_to_the_fast_path_or_the_reference() {
    use chasles_skin::fast::Skinner;
    let close = |rig: &chasles_skin::Rig,
                 a: &chasles_skin::Skinned,
                 b: &chasles_skin::Skinned,
                 m: Method| {
        let (size, reach) = (size(rig), reach(m));
        for v in 0..a.positions.len() {
            assert!(
                (a.positions[v] - b.positions[v]).norm() <= reach * size,
                "{} {m:?} {v}",
                rig.name
            );
            assert!(
                (a.normals[v] - b.normals[v]).norm() <= reach,
                "{} {m:?} {v}",
                rig.name
            );
        }
    };
    for (file, _, _, _) in models() {
        let rig = gltf_load::load(&data(file)).unwrap();
        let s = Skinner::new(&rig).unwrap();
        assert_eq!(s.influences(), 4, "{file}");
        let pose = Pose::animated(&rig, 0, 0.3).unwrap();
        let jt = joint_transforms(&rig, &pose).unwrap();
        for m in Method::ALL {
            close(
                &rig,
                &s.skin(&rig, &jt, m).unwrap(),
                &skin(&rig, &pose, m).unwrap(),
                m,
            );
        }
    }
    // Nine joints on one vertex: more than the fast layouts hold, so the reference path.
    let joints: Vec<String> = (0..9)
        .map(|j| format!(r#"{{"name": "j{j}", "translation": [{j}, 0, 0]}}"#))
        .collect();
    let all: Vec<String> = (0..9).map(|j| format!("[{j}, {}]", j + 1)).collect();
    let text = format!(
        r#"{{"positions": [[0,0,0],[1,0,0],[0,1,0]], "triangles": [[0,1,2]],
            "joints": [{}], "influences": [[{}], [[1, 1]], [[2, 1]]]}}"#,
        joints.join(","),
        all.join(",")
    );
    let rig = chasles_skin::json_rig::parse_rig(&text, "nine").unwrap();
    let s = Skinner::new(&rig).unwrap();
    assert_eq!(s.influences(), 0);
    let jt = chasles_skin::JointTransforms::identity(9);
    for m in Method::ALL {
        let got = s.skin(&rig, &jt, m).unwrap();
        assert_eq!(got, chasles_skin::skin_joints(&rig, &jt, m).unwrap());
    }
    // A NaN joint transform: an error naming the joint, not NaN vertices.
    let rig = gltf_load::load(&data("CesiumMan.glb")).unwrap();
    let s = Skinner::new(&rig).unwrap();
    let mut jt = chasles_skin::JointTransforms::identity(rig.joints.len());
    jt.dual_quats[0].real.w = f32::NAN;
    jt.matrices[0].m[0][0] = f32::NAN;
    for m in [
        Method::Lbs,
        Method::Dqs,
        Method::Qlb,
        Method::Sbs,
        Method::Dib,
    ] {
        let e = s.skin(&rig, &jt, m).unwrap_err().to_string();
        assert!(e.contains("joint 0's") && e.contains("not finite"), "{e}");
    }
}

const STRIP: &str = r#"{"positions": [[0,0,0],[1,0,0],[2,0,0],[0,1,0],[1,1,0],[2,1,0]],
 "triangles": [[0,1,4],[0,4,3],[1,2,5],[1,5,4]],
 "joints": [{"name": "a"}, {"name": "b", "parent": 0, "translation": [1,0,0]}],
 "influences": [[[0,1]],[[0,0.5],[1,0.5]],[[1,1]],[[0,1]],[[0,0.5],[1,0.5]],[[1,1]]]}"#;

#[test]
fn json_rigs_and_poses() {
    use chasles_skin::json_rig::{parse_pose, parse_rig};
    let rig = parse_rig(STRIP, "strip").unwrap();
    assert_eq!(
        rig.mesh.normals[0],
        Vec3::new(0.0, 0.0, 1.0),
        "normals computed from the triangles"
    );
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let pose = parse_pose(
        &format!(r#"{{"joints": {{"b": {{"rotation": [{h}, 0, 0, {h}]}}}}}}"#),
        &rig,
        "pose",
    )
    .unwrap();
    let s = skin(&rig, &pose, Method::Dqs).unwrap();
    // Joint b at (1, 0, 0) turns 90° about z: (2, 0, 0) → (1, 1, 0); the half-weighted
    // vertex (1, 1, 0) turns 45° about the joint.
    assert!((s.positions[2] - Vec3::new(1.0, 1.0, 0.0)).norm() < 1e-6);
    assert!((s.positions[4] - Vec3::new(1.0 - h, h, 0.0)).norm() < 1e-6);
    let by_index = parse_pose(
        &format!(r#"{{"joints": {{"1": {{"rotation": [{h}, 0, 0, {h}]}}}}}}"#),
        &rig,
        "pose",
    )
    .unwrap();
    assert_eq!(by_index, pose);
    let bad: &[(&str, &str)] = &[
        (
            r#"{"positions": [[0,0,0]], "triangles": [], "joints": [{"name": "a"}], "influences": [[[3, 1]]]}"#,
            "r: influences[0]: vertex 0: joint index 3 out of range",
        ),
        (
            r#"{"positions": [[0,0,0]], "triangles": [], "joints": [{"name": "a"}], "influences": [[[0, -1]]]}"#,
            "negative",
        ),
        (
            r#"{"positions": [[0,0,0]], "triangles": [], "joints": [{"name": "a"}], "influences": [[[0, 0]]]}"#,
            "sum to zero",
        ),
        (
            r#"{"positions": [[0,0]], "triangles": [], "joints": [], "influences": []}"#,
            "positions[0]",
        ),
        (
            r#"{"positions": [[0,0,1e39]], "triangles": [], "joints": [{"name": "a"}], "influences": [[[0, 1]]]}"#,
            "r: positions[0][2]: 1e39 is not a finite f32",
        ),
        (
            r#"{"positions": [[0,0,0]], "triangles": [], "joints": [{"name": "a", "rotaton": [1,0,0,0]}], "influences": [[[0, 1]]]}"#,
            "r: joints[0].rotaton: unknown field `rotaton`, expected one of",
        ),
        (
            r#"{"positions": [[0,0,0]], "triangles": [], "joints": [{"name": "a"}], "influences": [[[0.5, 1]]]}"#,
            "r: influences[0][0][0]: invalid type: floating point `0.5`",
        ),
        (
            r#"{"positions": [[0,0,0]], "triangles": [[0,0,5]], "joints": [{"name": "a"}], "influences": [[[0, 1]]]}"#,
            "triangles[0]: [0, 0, 5] names a vertex out of range",
        ),
        (
            r#"{"positions": [[0,0,0]], "triangles": [], "joints": [{"name": "a", "rotation": [0,0,0,0]}], "influences": [[[0, 1]]]}"#,
            "joints[0].rotation",
        ),
        (
            r#"{"positions": [[0,0,0]], "triangles": [], "joints": [{"name": "a", "parent": 0}], "influences": [[[0, 1]]]}"#,
            "parents must come before",
        ),
        (
            r#"{"positions": [[0,0,0]], "triangles": [], "joints": [{"name": "a"}]}"#,
            "missing field `influences`",
        ),
        (
            r#"{"positions": [[0,0,0]"#,
            "r: positions: not valid JSON: EOF while parsing",
        ),
        (
            "[1, 2",
            "r: [0]: invalid type: integer `1`, expected a sequence",
        ),
    ];
    let trailing = format!("{STRIP} x");
    for (text, needle) in bad.iter().chain([&(
        trailing.as_str(),
        "r: .: not valid JSON: trailing characters",
    )]) {
        let e = parse_rig(text, "r").unwrap_err().to_string();
        assert!(e.contains(needle), "{text}: {e}");
    }
    assert!(parse_pose(r#"{"joints": {"knee": {}}}"#, &rig, "p")
        .unwrap_err()
        .to_string()
        .contains("'knee'"));
    let e = parse_pose(r#"{"joints": {"b": {"scale": [1, 2]}}}"#, &rig, "p").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("p: joints.b.scale: invalid length 2, expected an array of length 3"),
        "{e}"
    );
}

#[test]
fn mutated_files_never_panic() {
    // Deterministic byte mutations of a .glb and a .gltf: loading and skinning either
    // succeed or return an error; no panic.
    let dir = tempfile::tempdir().unwrap();
    let mut seed = 0x1234_5678_9abc_def0u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for file in ["RiggedSimple.glb", "SimpleSkin.gltf"] {
        let bytes = std::fs::read(data(file)).unwrap();
        for round in 0..300 {
            let mut b = bytes.clone();
            for _ in 0..1 + next() % 8 {
                let i = (next() as usize) % b.len();
                b[i] = next() as u8;
            }
            let p = dir.path().join(format!("m{round}-{file}"));
            std::fs::write(&p, &b).unwrap();
            let r = std::panic::catch_unwind(|| {
                if let Ok(rig) = gltf_load::load(&p) {
                    for c in 0..rig.animations.len() {
                        if let Ok(pose) = Pose::animated(&rig, c, 0.3) {
                            for m in Method::ALL {
                                let _ = skin(&rig, &pose, m);
                            }
                        }
                    }
                }
            });
            assert!(r.is_ok(), "{file}, mutation round {round}: panicked");
        }
    }
}

#[test]
fn writers_produce_what_they_promise() {
    use chasles_skin::writers::{glb, obj, ply};
    let rig = gltf_load::load(&data("CesiumMan.glb")).unwrap();
    let pose = Pose::animated(&rig, 0, 0.5).unwrap();
    let s = skin(&rig, &pose, Method::Dqs).unwrap();
    let o = obj(&rig.mesh, &s, "test");
    assert_eq!(o.lines().filter(|l| l.starts_with("v ")).count(), 3273);
    assert_eq!(o.lines().filter(|l| l.starts_with("vn ")).count(), 3273);
    assert_eq!(o.lines().filter(|l| l.starts_with("f ")).count(), 4672);
    let p = ply(&rig.mesh, &s, "test");
    assert!(p.contains("element vertex 3273") && p.contains("element face 4672"));
    // The .glb parses with the gltf crate and holds the deformed positions.
    let bytes = glb(&rig.mesh, &s, "test");
    let g = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = g.blob.clone().unwrap();
    let prim = g
        .document
        .meshes()
        .next()
        .unwrap()
        .primitives()
        .next()
        .unwrap();
    let r = prim.reader(|_| Some(&blob[..]));
    let pos: Vec<[f32; 3]> = r.read_positions().unwrap().collect();
    assert_eq!(pos.len(), 3273);
    assert_eq!(pos[100], s.positions[100].to_array());
    assert_eq!(r.read_indices().unwrap().into_u32().count(), 4672 * 3);
    assert_eq!(bytes.len() % 4, 0);
}

#[test]
fn rig_new_checks_the_parts_with_typed_errors() {
    use chasles::Mat4;
    use chasles_skin::animation::Animation;
    use chasles_skin::{ChannelProblem, Mesh, Node, Rig, Trs};
    let mesh = || Mesh {
        positions: vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ],
        normals: vec![Vec3::new(0.0, 0.0, 1.0); 3],
        triangles: vec![[0, 1, 2]],
    };
    let nodes = || {
        vec![
            Node {
                name: "a".into(),
                parent: None,
                rest: Trs::default(),
            },
            Node {
                name: "b".into(),
                parent: Some(0),
                rest: Trs::default(),
            },
        ]
    };
    let inf = || {
        Influences::from_lists(
            &[vec![(0, 1.0)], vec![(0, 0.5), (1, 0.5)], vec![(1, 1.0)]],
            2,
        )
        .unwrap()
    };
    let ib = || vec![Mat4::identity(); 2];
    let anim = |node: usize, times: Vec<f32>, values: usize| Animation {
        name: "clip".into(),
        channels: vec![Channel {
            node,
            path: P::Rotation,
            interpolation: Interpolation::Linear,
            times,
            values: vec![[1.0, 0.0, 0.0, 0.0]; values],
        }],
    };
    let new = |mesh: Mesh,
               nodes: Vec<Node>,
               joints: Vec<usize>,
               ib: Vec<Mat4<f32>>,
               anims: Vec<Animation>| {
        Rig::new("t".into(), mesh, nodes, joints, ib, inf(), anims)
    };
    let rig = new(
        mesh(),
        nodes(),
        vec![0, 1],
        ib(),
        vec![anim(1, vec![0.0, 1.0], 2)],
    )
    .unwrap();
    assert_eq!(rig.joints, vec![0, 1]);
    // Each broken part is named by its own variant.
    let mut m = mesh();
    m.normals.pop();
    assert!(matches!(
        new(m, nodes(), vec![0, 1], ib(), vec![]),
        Err(SkinError::Count {
            what: "normals",
            expected: 3,
            got: 2,
            ..
        })
    ));
    let mut m = mesh();
    m.triangles[0] = [0, 1, 7];
    assert!(matches!(
        new(m, nodes(), vec![0, 1], ib(), vec![]),
        Err(SkinError::OutOfRange {
            index: 7,
            count: 3,
            ..
        })
    ));
    let mut m = mesh();
    m.positions[1].x = f32::NAN;
    let e = new(m, nodes(), vec![0, 1], ib(), vec![]).unwrap_err();
    assert!(matches!(e, SkinError::NotFinite { .. }));
    assert_eq!(e.to_string(), "t: the position of vertex 1 is not finite");
    assert!(matches!(
        new(mesh(), nodes(), vec![0, 5], ib(), vec![]),
        Err(SkinError::OutOfRange {
            index: 5,
            count: 2,
            ..
        })
    ));
    assert!(matches!(
        new(mesh(), nodes(), vec![0, 1], vec![Mat4::identity()], vec![]),
        Err(SkinError::Count {
            what: "inverse bind matrices",
            expected: 2,
            got: 1,
            ..
        })
    ));
    let mut cyclic = nodes();
    cyclic[0].parent = Some(1);
    assert!(matches!(
        new(mesh(), cyclic, vec![0, 1], ib(), vec![]),
        Err(SkinError::Hierarchy { node: 0, .. })
    ));
    for (a, problem) in [
        (
            anim(9, vec![0.0], 1),
            ChannelProblem::NodeOutOfRange { nodes: 2 },
        ),
        (anim(1, vec![], 0), ChannelProblem::NoKeys),
        (anim(1, vec![1.0, 0.5], 2), ChannelProblem::Times),
        (
            anim(1, vec![0.0, 1.0], 3),
            ChannelProblem::Values {
                keys: 2,
                values: 3,
                expected: 2,
            },
        ),
    ] {
        let e = new(mesh(), nodes(), vec![0, 1], ib(), vec![a]).unwrap_err();
        assert!(
            matches!(e, SkinError::Channel { animation: 0, channel: 0, problem: p, .. } if p == problem),
            "{e}"
        );
    }
    // The fast layout names the influence count it cannot hold.
    let spread: Vec<(usize, f32)> = (0..5).map(|j| (j, 0.2)).collect();
    let wide = flat_rig(
        "wide",
        mesh(),
        5,
        Influences::from_lists(&[spread.clone(), spread.clone(), spread], 5).unwrap(),
    )
    .unwrap();
    assert!(matches!(
        chasles_skin::fast::FastRig::<4>::new(&wide),
        Err(SkinError::TooManyInfluences { layout: 4, .. })
    ));
    assert!(matches!(
        chasles_skin::load(std::path::Path::new("rig.txt")),
        Err(SkinError::UnknownFormat { .. })
    ));
}

#[test]
fn rig_new_checks_influences_built_by_hand() {
    use chasles::Mat4;
    use chasles_skin::{Mesh, Node, Rig, Trs};
    let mesh = Mesh {
        positions: vec![Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0)],
        normals: vec![Vec3::new(0.0, 0.0, 1.0); 2],
        triangles: vec![],
    };
    let node = Node {
        name: "a".into(),
        parent: None,
        rest: Trs::default(),
    };
    let new = |inf: Influences| {
        Rig::new(
            "hand".into(),
            mesh.clone(),
            vec![node.clone()],
            vec![0],
            vec![Mat4::identity()],
            inf,
            vec![],
        )
    };
    let good = Influences::from_lists(&[vec![(0, 1.0)], vec![(0, 1.0)]], 1).unwrap();
    assert!(new(good.clone()).is_ok());
    let mut far = good.clone();
    far.joints[1] = 3;
    assert!(matches!(
        new(far),
        Err(SkinError::JointOutOfRange {
            vertex: 1,
            joint: 3,
            joints: 1
        })
    ));
    let mut backwards = good.clone();
    backwards.start = vec![0, 2, 1];
    assert!(matches!(new(backwards), Err(SkinError::Count { .. })));
    let mut short = good.clone();
    short.weights.pop();
    assert!(matches!(new(short), Err(SkinError::Count { .. })));
    let mut nan = good.clone();
    nan.weights[0] = f32::NAN;
    assert!(matches!(
        new(nan),
        Err(SkinError::BadWeights { vertex: 0, .. })
    ));
    let mut zero = good;
    zero.weights[1] = 0.0;
    assert!(matches!(
        new(zero),
        Err(SkinError::BadWeights { vertex: 1, .. })
    ));
}
