//! Motion blending (Kavan et al. 2006, §7) on the Fox's Walk and Run: weights 0 and 1 give
//! the clips back (also through the written .glb), the blend is rigid per joint, each
//! joint's local transform moves along the screw between the clips' ones, and the joints'
//! world trajectories lie between the two clips' (bounds stated in each test).

use chasles::blend::sclerp::sclerp;
use chasles::{DualQuat, Quat, Vec3};
use chasles_skin::clip_blend::{blend_clips, blend_trs, rigidity_defect, BlendOptions, Blended};
use chasles_skin::gltf_write::rig_glb;
use chasles_skin::pose::world;
use chasles_skin::{gltf_load, skin, Method, Pose, Rig, SkinError, Trs};

fn fox() -> Rig {
    gltf_load::load_slice(chasles_models::FOX.bytes, chasles_models::FOX.file).unwrap()
}

fn size(rig: &Rig) -> f64 {
    f64::from(rig.mesh.positions.iter().fold(0f32, |s, p| s.max(p.norm())))
}

fn walk_run(rig: &Rig) -> (usize, usize) {
    (
        rig.clip_index("Walk").unwrap(),
        rig.clip_index("Run").unwrap(),
    )
}

fn blend(rig: &Rig, w: f64, sync: bool, fps: Option<f64>) -> Blended {
    let (a, b) = walk_run(rig);
    let opts = BlendOptions {
        weight: w,
        sync,
        fps,
        name: format!("blend {w}"),
    };
    blend_clips(rig, a, b, &opts).unwrap()
}

fn rest(rig: &Rig) -> Vec<Trs> {
    rig.nodes.iter().map(|n| n.rest).collect()
}

/// The rotation angle between two unit quaternions (either sign), radians.
fn angle(p: Quat<f32>, q: Quat<f32>) -> f64 {
    let (p, q) = (p.cast::<f64>(), q.cast::<f64>());
    let chord = (p - q).norm().min((p + q).norm());
    4.0 * (chord / 2.0).min(1.0).asin()
}

/// The blend written as .glb with the rig and loaded back.
fn reloaded(rig: &Rig, b: &Blended) -> Rig {
    let bytes = rig_glb(rig, std::slice::from_ref(&b.animation), "test").unwrap();
    let back = gltf_load::load_slice(&bytes, "blend.glb").unwrap();
    assert_eq!(back.animations.len(), 1);
    assert_eq!(back.animations[0].name, b.animation.name);
    back
}

#[test]
fn weights_0_and_1_give_walk_and_run_back_through_the_written_file() {
    let rig = fox();
    let (a, b) = walk_run(&rig);
    let r = rest(&rig);
    let tol_t = 1e-6 * size(&rig);
    for sync in [false, true] {
        for (w, clip) in [(0.0, a), (1.0, b)] {
            let bl = blend(&rig, w, sync, None);
            // The Fox's clips are keyed at 24 fps: the default rate.
            assert!((bl.fps - 24.0).abs() < 1e-3, "{}", bl.fps);
            let back = reloaded(&rig, &bl);
            let back_rest = rest(&back);
            let mut worst = (0.0f64, 0.0f64);
            for (k, t) in bl.times.iter().enumerate() {
                let at = if w == 0.0 {
                    bl.sampled_at[k].0
                } else {
                    bl.sampled_at[k].1
                };
                let want = rig.animations[clip].sample(&r, at);
                let got = back.animations[0].sample(&back_rest, *t);
                for n in 0..rig.nodes.len() {
                    worst.0 = worst.0.max(angle(want[n].rotation, got[n].rotation));
                    let d = (want[n].translation - got[n].translation).norm();
                    worst.1 = worst.1.max(f64::from(d));
                }
            }
            assert!(
                worst.0 < 1e-6 && worst.1 < tol_t,
                "sync {sync}, w {w}: rotation {:e} rad, translation {:e}",
                worst.0,
                worst.1
            );
        }
    }
    // Without time warping the blend lasts as long as Run; with it, as the clip weighted 1.
    let (da, db) = (rig.animations[a].duration(), rig.animations[b].duration());
    let last = |bl: &Blended| *bl.times.last().unwrap();
    assert!((last(&blend(&rig, 0.0, false, None)) - db).abs() < 1e-5);
    assert!((last(&blend(&rig, 0.0, true, None)) - da).abs() < 1e-5);
    assert!((last(&blend(&rig, 1.0, true, None)) - db).abs() < 1e-5);
    let mid = last(&blend(&rig, 0.5, true, None));
    assert!((mid - (da + db) / 2.0).abs() < 1e-5);
}

#[test]
fn the_blend_is_rigid_per_joint_in_memory_and_in_the_file() {
    let rig = fox();
    for sync in [false, true] {
        for w in [0.2, 0.5, 0.8] {
            let bl = blend(&rig, w, sync, None);
            let back = reloaded(&rig, &bl);
            let mut worst = (0.0f64, 0.0f64);
            for ch in bl
                .animation
                .channels
                .iter()
                .chain(&back.animations[0].channels)
            {
                if ch.path != chasles_skin::animation::Path::Rotation {
                    continue;
                }
                for v in &ch.values {
                    let (n, r) = rigidity_defect(Quat::from_array(*v));
                    worst = (worst.0.max(n), worst.1.max(r));
                }
            }
            // f32 storage: a unit quaternion rounded to f32 is within a few ulps of unit.
            assert!(
                worst.0 < 1e-6 && worst.1 < 2e-6,
                "sync {sync} w {w}: |q| − 1 up to {:e}, RᵀR − I up to {:e}",
                worst.0,
                worst.1
            );
        }
    }
}

#[test]
fn each_joint_moves_along_the_screw_between_the_two_clips() {
    // DLB of two rigid transforms lies on ScLERP's screw between them (Kavan et al. §4: they
    // differ in speed only): for every node and frame, the blend of weight w is ScLERP(A, B,
    // s) for one s in [0, 1] (to 1e-5 rad and 1e-5 of the model's size), s grows with w.
    let rig = fox();
    let (a, b) = walk_run(&rig);
    let r = rest(&rig);
    let tol = 1e-5 * size(&rig);
    let dq = |t: &Trs| {
        DualQuat::from_rotation_translation(t.rotation.cast::<f64>(), t.translation.cast::<f64>())
    };
    let mut worst = (0.0f64, 0.0f64);
    let mut checked = 0;
    for phase in [0.0, 0.2, 0.45, 0.7, 1.0] {
        let la = rig.animations[a].sample(&r, phase * rig.animations[a].duration());
        let lb = rig.animations[b].sample(&r, phase * rig.animations[b].duration());
        for n in rig.animations[a].nodes() {
            let (pa, pb) = (dq(&la[n]), dq(&lb[n]));
            let full = angle(la[n].rotation, lb[n].rotation);
            let move_t = (pb.translation() - pa.translation()).norm();
            if full < 1e-3 && move_t < tol {
                continue;
            }
            let mut last_s = 0.0;
            for w in [0.1, 0.3, 0.5, 0.7, 0.9] {
                let m = blend_trs(&la[n], &lb[n], w).unwrap();
                let s = if full >= 1e-3 {
                    angle(la[n].rotation, m.rotation) / full
                } else {
                    (m.translation.cast::<f64>() - pa.translation()).norm() / move_t
                };
                assert!(
                    (0.0..=1.0 + 1e-6).contains(&s) && s >= last_s,
                    "node {n} w {w}: s {s}"
                );
                last_s = s;
                let on = sclerp(pa, pb, s).unwrap();
                worst.0 = worst.0.max(angle(on.rotation().cast(), m.rotation));
                let dt = on.translation() - m.translation.cast::<f64>();
                worst.1 = worst.1.max(dt.norm());
                checked += 1;
            }
        }
    }
    assert!(checked > 300, "{checked}");
    assert!(
        worst.0 < 1e-5 && worst.1 < tol,
        "off the screw by {:e} rad, {:e}",
        worst.0,
        worst.1
    );
}

/// World positions of every joint at every frame of a blend of `w` with `intervals` + 1
/// frames at phases k / intervals.
fn joint_tracks(rig: &Rig, w: f64, intervals: usize) -> Vec<Vec<Vec3<f64>>> {
    let (a, b) = walk_run(rig);
    let d = (1.0 - w) * f64::from(rig.animations[a].duration())
        + w * f64::from(rig.animations[b].duration());
    let bl = blend(rig, w, true, Some(intervals as f64 / d));
    assert_eq!(bl.times.len(), intervals + 1);
    let r = rest(rig);
    bl.times
        .iter()
        .map(|t| {
            let wd = world(
                rig,
                &Pose {
                    local: bl.animation.sample(&r, *t),
                },
            )
            .unwrap();
            rig.joints
                .iter()
                .map(|j| wd[*j].translation().cast::<f64>())
                .collect()
        })
        .collect()
}

#[test]
#[allow(clippy::needless_range_loop)] // tracks[weight][frame][joint]: three indices at once
fn joint_trajectories_lie_between_walk_and_run() {
    // What "between" means here, for every joint of the Fox (feet included), at each of 25
    // phases, for weights 0, 0.05, …, 1 with time warping (so that phase φ is Walk at
    // φ·d_Walk and Run at φ·d_Run for every weight). With A and B the joint's world
    // positions in Walk and Run and P_w in the blend:
    //  1. the lens: |P_w − A| ≤ |A − B| + ε and |P_w − B| ≤ |A − B| + ε;
    //  2. monotone: |P_w − A| never decreases and |P_w − B| never increases as w grows, to ε;
    //  3. near the segment: the distance from P_w to the segment AB is at most |A − B| / 2
    //     (joints swing on arcs: a point turned about a pivot sits off the chord by up to
    //     half of it);
    // with ε = 0.5 % of the model's size (94.6 units). Measured: lens excess 0.29 units
    // (0.3 %), non-monotone by 0.093 (0.1 %), distance to the segment 0.43 |A − B|.
    let rig = fox();
    let eps = 0.005 * size(&rig);
    let n = 24;
    let ws: Vec<f64> = (0..=20).map(|i| f64::from(i) / 20.0).collect();
    let tracks: Vec<_> = ws.iter().map(|w| joint_tracks(&rig, *w, n)).collect();
    let (mut lens, mut back, mut seg) = (0.0f64, 0.0f64, 0.0f64);
    for f in 0..=n {
        for j in 0..rig.joints.len() {
            let (a, b) = (tracks[0][f][j], tracks[20][f][j]);
            let ab = b - a;
            let l = ab.norm();
            for i in 1..ws.len() {
                let (p, q) = (tracks[i - 1][f][j], tracks[i][f][j]);
                lens = lens.max((q - a).norm().max((q - b).norm()) - l);
                back = back
                    .max((p - a).norm() - (q - a).norm())
                    .max((q - b).norm() - (p - b).norm());
                if l > 1e-3 * size(&rig) {
                    let s = ((q - a).dot(ab) / (l * l)).clamp(0.0, 1.0);
                    seg = seg.max((q - (a + ab * s)).norm() / l);
                }
            }
        }
    }
    println!("lens excess {lens:.4}, non-monotone {back:.4}, distance to segment {seg:.4} |AB| (ε = {eps:.4})");
    assert!(lens <= eps, "lens excess {lens}");
    assert!(back <= eps, "non-monotone by {back}");
    assert!(seg <= 0.5, "distance to the segment {seg} |AB|");
}

#[test]
fn the_written_blend_skins_as_the_blend_does() {
    let rig = fox();
    let bl = blend(&rig, 0.5, true, None);
    let back = reloaded(&rig, &bl);
    let (r, br) = (rest(&rig), rest(&back));
    let tol = 1e-5 * size(&rig);
    for t in [bl.times[3], bl.times[bl.times.len() / 2], 0.123] {
        let want = skin(
            &rig,
            &Pose {
                local: bl.animation.sample(&r, t),
            },
            Method::Dqs,
        )
        .unwrap();
        let got = skin(
            &back,
            &Pose {
                local: back.animations[0].sample(&br, t),
            },
            Method::Dqs,
        )
        .unwrap();
        assert_eq!(want.positions.len(), got.positions.len());
        for (p, q) in want.positions.iter().zip(&got.positions) {
            assert!(f64::from((*p - *q).norm()) < tol, "t {t}: {p:?} vs {q:?}");
        }
    }
}

#[test]
fn bad_weights_and_unknown_clips_are_errors_naming_them() {
    let rig = fox();
    let (a, b) = walk_run(&rig);
    for w in [f64::NAN, -0.1, 1.5, f64::INFINITY] {
        let opts = BlendOptions {
            weight: w,
            sync: false,
            fps: None,
            name: "x".into(),
        };
        let e = blend_clips(&rig, a, b, &opts).unwrap_err();
        assert!(matches!(e, SkinError::Parameter { .. }), "{e}");
        assert!(e.to_string().contains("weight"), "{e}");
    }
    let opts = BlendOptions {
        weight: 0.5,
        sync: false,
        fps: Some(f64::NAN),
        name: "x".into(),
    };
    let e = blend_clips(&rig, a, b, &opts).unwrap_err();
    assert!(e.to_string().contains("frame rate"), "{e}");
    let e = rig.clip_index("Gallop").unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("'Gallop'") && text.contains("Walk (1)") && text.contains("Run (2)"),
        "{text}"
    );
    let opts = BlendOptions { fps: None, ..opts };
    assert!(matches!(
        blend_clips(&rig, a, 7, &opts),
        Err(SkinError::NoAnimation {
            clip: 7,
            count: 3,
            ..
        })
    ));
}
