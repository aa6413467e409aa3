//! Clip compression (Kavan et al. 2006, §7, "motion analysis and compression") on CesiumMan
//! and the Fox: the vertex bound holds at every vertex and frame of the original sampling in
//! the written file loaded back, at two tolerances, with Slerp and with Squad; the counts
//! of kept keys; bad input.
//!
//! Measured (DQS; kept keys of original keys, greedy selection):
//!
//! | clip | tolerance | Slerp | Squad |
//! |---|---|---|---|
//! | CesiumMan | 0.001 | 2247 / 2736 | 2232 / 2736 |
//! | CesiumMan | 0.005 | 1401 / 2736 | 1347 / 2736 |
//! | CesiumMan | 0.02 | 801 / 2736 | 717 / 2736 |
//! | Fox Run | 0.5 | 423 / 525 | 443 / 525 |
//! | Fox Run | 2 | 285 / 525 | 252 / 525 |
//! | Fox Walk | 0.5 | 296 / 378 | 291 / 378 |
//! | Fox Survey | 0.5 | 179 / 1743 | 310 / 1743 |
//!
//! Squad keeps fewer keys than Slerp on CesiumMan at every tolerance and on Walk and Run at
//! the looser ones, but not on Run at 0.5 (the Fox's 24-frame run leaves few keys to drop and
//! Squad's tangents, taken from the neighbouring kept keys, overshoot on its sharp turns) nor
//! on Survey (long holds, which Slerp keeps exactly still between two keys and a Catmull–Rom
//! or Squad tangent does not). The test asserts what holds and prints every figure.

use chasles_skin::clip_compress::{
    compress, compress_to_glb, ClipSkins, CompressOptions, Compressed, Rotation,
};
use chasles_skin::gltf_write::rig_glb;
use chasles_skin::{gltf_load, Method, Rig, SkinError};

fn load(m: chasles_models::Model) -> Rig {
    gltf_load::load_slice(m.bytes, m.file).unwrap()
}

fn run(rig: &Rig, clip: &str, tolerance: f64, rotation: Rotation) -> Compressed {
    let c = rig.clip_index(clip).unwrap();
    let opts = CompressOptions {
        tolerance,
        rotation,
        method: Method::Dqs,
    };
    compress(rig, c, &opts).unwrap()
}

/// The worst vertex error of the compressed clip written as .glb and loaded back, against
/// the original clip on the original rig, at the original sampling.
fn file_error(rig: &Rig, clip: &str, done: &Compressed) -> f64 {
    let c = rig.clip_index(clip).unwrap();
    let bytes = rig_glb(rig, std::slice::from_ref(&done.animation), "test").unwrap();
    let back = gltf_load::load_slice(&bytes, "compressed.glb").unwrap();
    assert_eq!(back.animations.len(), 1);
    let written: usize = back.animations[0]
        .channels
        .iter()
        .map(|c| c.times.len())
        .sum();
    assert_eq!(written, done.kept_keys);
    let frames = rig.animations[c].key_times();
    assert_eq!(frames, done.frames);
    let reference = ClipSkins::new(rig, &rig.animations[c], &frames, Method::Dqs).unwrap();
    let file = ClipSkins::new(&back, &back.animations[0], &frames, Method::Dqs).unwrap();
    assert_eq!(file.positions.len(), frames.len());
    reference.worst_distance(&file).unwrap().distance
}

fn check(
    model: chasles_models::Model,
    clip: &str,
    tolerances: [f64; 2],
) -> Vec<(f64, usize, usize)> {
    let rig = load(model);
    let mut kept = Vec::new();
    for tolerance in tolerances {
        let mut pair = [0; 2];
        for (i, rotation) in [Rotation::Slerp, Rotation::Squad].into_iter().enumerate() {
            let done = run(&rig, clip, tolerance, rotation);
            let in_file = file_error(&rig, clip, &done);
            println!(
                "{} {clip} tolerance {tolerance} {}: kept {} of {} keys ({:.1} %), worst {:.4e} in memory, {:.4e} in the file, budget {:.3}",
                model.file,
                rotation.name(),
                done.kept_keys,
                done.original_keys,
                100.0 * done.ratio(),
                done.worst.distance,
                in_file,
                done.budget
            );
            assert!(done.worst.distance <= tolerance);
            assert!(in_file <= tolerance, "{in_file} > {tolerance}");
            assert!(!done.kept_original && done.kept_keys < done.original_keys);
            pair[i] = done.kept_keys;
        }
        kept.push((tolerance, pair[0], pair[1]));
    }
    kept
}

#[test]
fn cesium_man_meets_the_bound_in_the_written_file_and_squad_keeps_fewer_keys() {
    for (tolerance, slerp, squad) in check(chasles_models::CESIUM_MAN, "0", [0.001, 0.005]) {
        assert!(
            squad < slerp,
            "tolerance {tolerance}: Squad {squad}, Slerp {slerp}"
        );
    }
}

#[test]
fn fox_run_meets_the_bound_in_the_written_file() {
    let kept = check(chasles_models::FOX, "Run", [0.5, 2.0]);
    // At 2 units (2 % of the fox's size) Squad keeps fewer; at 0.5 it does not (see above).
    let (_, slerp, squad) = kept[1];
    assert!(squad < slerp, "tolerance 2: Squad {squad}, Slerp {slerp}");
}

#[test]
fn a_loose_tolerance_keeps_the_ends_and_a_tight_one_the_whole_clip() {
    let rig = load(chasles_models::CESIUM_MAN);
    for rotation in [Rotation::Slerp, Rotation::Squad] {
        let loose = run(&rig, "0", 1e6, rotation);
        assert_eq!(loose.kept_keys, 2 * loose.animation.channels.len());
        assert_eq!(loose.budget, 1.0);
        // Below what f32 rounding of the reconstruction allows: the clip's own channels,
        // exact in memory; the file rounds the weights (renormalized on loading), so it
        // cannot meet 1e-9 and says so.
        let tight = run(&rig, "0", 1e-9, rotation);
        assert!(tight.kept_original && tight.worst.distance == 0.0);
        assert_eq!(tight.ratio(), 1.0);
        let rounding = file_error(&rig, "0", &tight);
        println!("the written file's own rounding: {rounding:e}");
        assert!(rounding < 1e-6, "{rounding}");
        let opts = CompressOptions {
            tolerance: 1e-9,
            rotation,
            method: Method::Dqs,
        };
        let e = compress_to_glb(&rig, 0, &opts, &[], "t").unwrap_err();
        assert!(
            e.to_string().contains("rounding of the written file"),
            "{e}"
        );
    }
}

#[test]
fn bad_tolerances_and_clips_are_errors_naming_them() {
    let rig = load(chasles_models::FOX);
    for tolerance in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let opts = CompressOptions {
            tolerance,
            rotation: Rotation::Squad,
            method: Method::Dqs,
        };
        let e = compress(&rig, 1, &opts).unwrap_err();
        assert!(matches!(e, SkinError::Parameter { .. }), "{e}");
        assert!(e.to_string().contains("tolerance"), "{e}");
    }
    let opts = CompressOptions {
        tolerance: 1.0,
        rotation: Rotation::Slerp,
        method: Method::Dqs,
    };
    assert!(matches!(
        compress(&rig, 3, &opts),
        Err(SkinError::NoAnimation {
            clip: 3,
            count: 3,
            ..
        })
    ));
}

#[test]
fn screw_motion_between_kept_keys_stays_near_what_the_file_plays() {
    // The rigid parts between kept keys are played as glTF can (Slerp + a linear
    // translation); ScLERP would move the translation along its helix instead. Here the
    // compressed clip's translations are replaced, at every original frame, by ScLERP's
    // between the same kept keys, and the mesh measured again.
    use chasles::blend::sclerp::sclerp;
    use chasles::{DualQuat, Quat, Vec3};
    use chasles_skin::animation::{Animation, Channel, Interpolation, Path};
    for (model, clip, tolerance) in [
        (chasles_models::CESIUM_MAN, "0", 0.005),
        (chasles_models::FOX, "Run", 2.0),
    ] {
        let rig = load(model);
        let done = run(&rig, clip, tolerance, Rotation::Slerp);
        let mut channels = Vec::new();
        for ch in &done.animation.channels {
            if ch.path != Path::Translation {
                channels.push(ch.clone());
                continue;
            }
            let rot = done
                .animation
                .channels
                .iter()
                .find(|c| c.node == ch.node && c.path == Path::Rotation);
            let Some(rot) = rot else {
                channels.push(ch.clone());
                continue;
            };
            assert_eq!(rot.times, ch.times, "one key set per node");
            let dq = |k: usize| {
                let t = ch.values[k];
                DualQuat::from_rotation_translation(
                    Quat::from_array(rot.values[k]).cast::<f64>(),
                    Vec3::new(t[0], t[1], t[2]).cast::<f64>(),
                )
            };
            let values = done
                .frames
                .iter()
                .map(|t| {
                    let (k, u) = ch.interval(*t);
                    let u = f64::from(u);
                    let m = sclerp(dq(k), dq(k + 1), u).unwrap().translation();
                    [m.x as f32, m.y as f32, m.z as f32, 0.0]
                })
                .collect();
            channels.push(Channel {
                node: ch.node,
                path: Path::Translation,
                interpolation: Interpolation::Linear,
                times: done.frames.clone(),
                values,
            });
        }
        let screw = Animation {
            name: "screw".into(),
            channels,
        };
        let c = rig.clip_index(clip).unwrap();
        let reference =
            ClipSkins::new(&rig, &rig.animations[c], &done.frames, Method::Dqs).unwrap();
        let played = ClipSkins::new(&rig, &screw, &done.frames, Method::Dqs).unwrap();
        let written = ClipSkins::new(&rig, &done.animation, &done.frames, Method::Dqs).unwrap();
        let by_screw = reference.worst_distance(&played).unwrap().distance;
        let apart = written.worst_distance(&played).unwrap().distance;
        println!(
            "{} {clip} tolerance {tolerance}: worst vertex error {:.4e} as written (linear translation), {by_screw:.4e} with ScLERP's; the two {apart:.4e} apart",
            model.file, done.worst.distance
        );
        assert!(apart <= 0.1 * tolerance, "{apart}");
        assert!(by_screw <= 1.1 * tolerance, "{by_screw}");
    }
}

#[test]
fn the_written_cubic_form_stays_close_to_squad_itself() {
    // glTF has no Squad: the file holds the cubic Hermite with Squad's keys and tangents.
    // Against Squad itself (eq. 6.14 on the same kept keys) at every original frame, for
    // every rotation channel of the compressed CesiumMan and Fox Run. Measured: 5.9e-5 rad
    // (0.0034°) on CesiumMan at 0.005, 1.06e-2 rad (0.61°) on the Run at 2 units, whose
    // kept keys are further apart: the bounds below are twice those. (The file's curve is
    // what the vertex bound is checked on; this is how far it is from Squad itself.)
    use chasles::interp::squad::Squad;
    use chasles::interp::{Hemisphere, KeyFrames};
    use chasles::Quat;
    use chasles_skin::animation::Path;
    for (model, clip, tolerance, bound) in [
        (chasles_models::CESIUM_MAN, "0", 0.005, 1.2e-4),
        (chasles_models::FOX, "Run", 2.0, 2.1e-2),
    ] {
        let rig = load(model);
        let done = run(&rig, clip, tolerance, Rotation::Squad);
        let mut worst = 0.0f64;
        for ch in &done.animation.channels {
            if ch.path != Path::Rotation || ch.times.len() < 3 {
                continue;
            }
            let keys: Vec<Quat<f64>> = (0..ch.times.len())
                .map(|k| Quat::from_array(ch.values[3 * k + 1]).cast::<f64>())
                .collect();
            let squad =
                Squad::new(&KeyFrames::new(&keys, None, Hemisphere::Chain).unwrap()).unwrap();
            for t in &done.frames {
                let (k, h) = ch.interval(*t);
                let h = f64::from(h);
                let want = squad.eval(k, h);
                let got = Quat::from_array(ch.sample(*t)).cast::<f64>();
                let chord = (want - got).norm().min((want + got).norm());
                worst = worst.max(4.0 * (chord / 2.0).min(1.0).asin());
            }
        }
        println!(
            "{} {clip}: the written Hermite form is within {:.3e} rad ({:.4}°) of Squad",
            model.file,
            worst,
            worst.to_degrees()
        );
        assert!(worst < bound, "{worst}");
    }
}
