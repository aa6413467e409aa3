//! Motion blending: two clips of one skeleton blended per joint by DLB (Kavan et al. 2006,
//! §7, "motion blending": "the DLB can be used to blend […] animations of rigid bodies").
//!
//! At every frame both clips are sampled (glTF rules, [`Animation::sample`]) and each node's
//! local rigid transform — rotation and translation as a unit dual quaternion — is blended
//! by DLB ([`chasles::blend::dlb::dlb`], §4) with weights `1 − w` and `w`: bi-invariant,
//! the shortest path (the lighter input is brought into the heavier's hemisphere), and
//! always a rigid transform (the blend is normalized as a dual quaternion). The blended
//! rotation is the dual quaternion's real part and the translation `2 qε q0*`, so each
//! joint stays rigid; scale (not a rigid quantity) is blended linearly. Nodes that only one
//! clip animates blend against the other clip's rest transform, as that clip plays them.
//!
//! Timing: without time warping the blend lasts as long as the longer clip and each clip is
//! played on its own clock (the shorter holds its last pose, as glTF plays a clip past its
//! end). With `sync` the clips are aligned by normalized phase (Kovar & Gleicher's time
//! warping in its simplest form): the blend lasts `(1 − w)·d_A + w·d_B`, and at phase
//! `φ ∈ [0, 1]` clip A is sampled at `φ·d_A`, clip B at `φ·d_B`.
//!
//! The result is a clip of LINEAR channels keyed at every frame (translation and rotation
//! of every node either clip animates; scale where either animates scale), which
//! [`crate::gltf_write::rig_glb`] writes and any glTF player plays: at weight 0 (1) and the
//! clip's own key times it is clip A (B) again, up to rounding.

use crate::animation::{Animation, Channel, Interpolation, Path};
use crate::error::{Result, SkinError};
use crate::rig::{Rig, Trs};
use chasles::blend::dlb::dlb;
use chasles::{DualQuat, Quat, Vec3};

/// How to blend two clips.
#[derive(Debug, Clone, PartialEq)]
pub struct BlendOptions {
    /// The weight of the second clip, in [0, 1] (the first gets `1 − weight`).
    pub weight: f64,
    /// Align the clips by normalized phase (time warping).
    pub sync: bool,
    /// Frames per second of the blended clip; `None`: the finer of the two clips' own key
    /// rates (30 when neither has two keys).
    pub fps: Option<f64>,
    /// The blended clip's name.
    pub name: String,
}

/// A blended clip and how it was made.
#[derive(Debug, Clone, PartialEq)]
pub struct Blended {
    /// The clip: LINEAR channels keyed at every frame.
    pub animation: Animation,
    /// Its frame times (seconds from 0).
    pub times: Vec<f32>,
    /// Where each frame sampled the two clips (seconds in clip A, in clip B).
    pub sampled_at: Vec<(f32, f32)>,
    /// The frame rate used.
    pub fps: f64,
}

/// Checks a blend weight: finite and in [0, 1].
pub fn check_weight(w: f64) -> Result<()> {
    if w.is_finite() && (0.0..=1.0).contains(&w) {
        Ok(())
    } else {
        Err(SkinError::Parameter {
            what: "the weight",
            value: w.to_string(),
            reason: "is not a number in [0, 1]",
        })
    }
}

/// The clip's key rate: one over the median interval between its key times.
pub fn key_rate(a: &Animation) -> Option<f64> {
    let t = a.key_times();
    let mut d: Vec<f64> = t.windows(2).map(|w| f64::from(w[1] - w[0])).collect();
    if d.is_empty() {
        return None;
    }
    d.sort_by(f64::total_cmp);
    let m = d[d.len() / 2];
    (m > 0.0).then(|| 1.0 / m)
}

/// DLB of two local transforms with weights `1 − w` and `w` (shortest path), scale blended
/// linearly. `w` must be in [0, 1] ([`check_weight`]).
pub fn blend_trs(a: &Trs, b: &Trs, w: f64) -> Result<Trs> {
    let dq = |t: &Trs| {
        DualQuat::from_rotation_translation(t.rotation.cast::<f64>(), t.translation.cast::<f64>())
    };
    let d = dlb(&[dq(a), dq(b)], &[1.0 - w, w])?;
    let s = |x: f32, y: f32| ((1.0 - w) * f64::from(x) + w * f64::from(y)) as f32;
    Ok(Trs {
        translation: d.translation().cast(),
        rotation: d.rotation().cast(),
        scale: Vec3::new(
            s(a.scale.x, b.scale.x),
            s(a.scale.y, b.scale.y),
            s(a.scale.z, b.scale.z),
        ),
    })
}

/// Blends clips `a` and `b` of `rig` (by index) per joint; see the module docs. Errors: a
/// clip that does not exist, a weight outside [0, 1] or NaN, a frame rate that is not
/// positive and finite (or past 10⁴), a blend of more than 10⁶ frames.
pub fn blend_clips(rig: &Rig, a: usize, b: usize, opts: &BlendOptions) -> Result<Blended> {
    check_weight(opts.weight)?;
    let clip = |i: usize| {
        rig.animations.get(i).ok_or_else(|| SkinError::NoAnimation {
            rig: rig.name.clone(),
            clip: i,
            count: rig.animations.len(),
        })
    };
    let (ca, cb) = (clip(a)?, clip(b)?);
    let fps = match opts.fps {
        Some(f) => f,
        None => key_rate(ca)
            .into_iter()
            .chain(key_rate(cb))
            .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))))
            .unwrap_or(30.0)
            .min(1e4),
    };
    if !(fps.is_finite() && fps > 0.0 && fps <= 1e4) {
        return Err(SkinError::Parameter {
            what: "the frame rate",
            value: fps.to_string(),
            reason: "is not a number of frames per second in (0, 10000]",
        });
    }
    let w = opts.weight;
    let (da, db) = (f64::from(ca.duration()), f64::from(cb.duration()));
    let duration = if opts.sync {
        (1.0 - w) * da + w * db
    } else {
        da.max(db)
    };
    let intervals = (duration * fps).round();
    if intervals > 1e6 {
        return Err(SkinError::Parameter {
            what: "the blend's frame count",
            value: intervals.to_string(),
            reason: "is past 10^6 (lower the frame rate)",
        });
    }
    let intervals = (intervals as usize).max(1);
    let rest: Vec<Trs> = rig.nodes.iter().map(|n| n.rest).collect();
    let nodes: Vec<usize> = {
        let mut n = ca.nodes();
        n.extend(cb.nodes());
        n.sort_unstable();
        n.dedup();
        n
    };
    let scaled: Vec<bool> = nodes
        .iter()
        .map(|n| ca.animates(*n, Path::Scale) || cb.animates(*n, Path::Scale))
        .collect();
    let mut times = Vec::with_capacity(intervals + 1);
    let mut sampled_at = Vec::with_capacity(intervals + 1);
    let mut values: Vec<[Vec<[f32; 4]>; 3]> = vec![Default::default(); nodes.len()];
    for k in 0..=intervals {
        let phase = k as f64 / intervals as f64;
        let t = phase * duration;
        let (ta, tb) = if opts.sync {
            (phase * da, phase * db)
        } else {
            (t, t)
        };
        let (ta, tb) = (ta as f32, tb as f32);
        let (la, lb) = (ca.sample(&rest, ta), cb.sample(&rest, tb));
        for (i, n) in nodes.iter().enumerate() {
            let m = blend_trs(&la[*n], &lb[*n], w)?;
            let [t, r, s] = &mut values[i];
            let tr = m.translation.to_array();
            t.push([tr[0], tr[1], tr[2], 0.0]);
            r.push(m.rotation.to_array());
            let sc = m.scale.to_array();
            s.push([sc[0], sc[1], sc[2], 0.0]);
        }
        times.push(t as f32);
        sampled_at.push((ta, tb));
    }
    // f32 rounding can make two frame times of a long, fine clip equal: keep them
    // strictly increasing as glTF requires.
    for k in 1..times.len() {
        if times[k] <= times[k - 1] {
            times[k] = f32::from_bits(times[k - 1].to_bits() + 1);
        }
    }
    let mut channels = Vec::new();
    for (i, n) in nodes.iter().enumerate() {
        let [t, r, s] = std::mem::take(&mut values[i]);
        let mut push = |path, values| {
            channels.push(Channel {
                node: *n,
                path,
                interpolation: Interpolation::Linear,
                times: times.clone(),
                values,
            })
        };
        push(Path::Translation, t);
        push(Path::Rotation, r);
        if scaled[i] {
            push(Path::Scale, s);
        }
    }
    Ok(Blended {
        animation: Animation {
            name: opts.name.clone(),
            channels,
        },
        times,
        sampled_at,
        fps,
    })
}

/// How far a rotation quaternion `[w, x, y, z]` is from unit length, and its matrix from a
/// rotation (`max |RᵀR − I|`, with R built without normalizing): 0 and 0 for a rigid joint.
pub fn rigidity_defect(q: Quat<f32>) -> (f64, f64) {
    let q = q.cast::<f64>();
    let [w, x, y, z] = q.to_array();
    let r = [
        [
            w * w + x * x - y * y - z * z,
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            w * w - x * x + y * y - z * z,
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            w * w - x * x - y * y + z * z,
        ],
    ];
    let mut off = 0.0f64;
    for i in 0..3 {
        for j in 0..3 {
            let d: f64 = (0..3).map(|k| r[k][i] * r[k][j]).sum();
            off = off.max((d - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    ((q.norm() - 1.0).abs(), off)
}
