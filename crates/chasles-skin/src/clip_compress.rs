//! Clip compression (Kavan et al. 2006, §7, "motion analysis and compression"): key frames
//! removed per joint so that every vertex of the skinned mesh stays within a tolerance `D`
//! of the original clip, at every frame of the clip's own sampling (the union of its key
//! times), in model units.
//!
//! The reconstruction between kept keys is what the written glTF plays — the bound is
//! checked on what a player will show, not on a curve the file cannot hold:
//!
//! * [`Rotation::Slerp`] — LINEAR channels: rotations by Slerp the shorter way (Dam et al.
//!   §6.1.5; glTF's LINEAR rotation), translations and scales linearly. Where a node's
//!   translation is animated, its rigid motion between two kept keys is the one of ScLERP's
//!   rotation (ScLERP's real part is Slerp) with the translation interpolated linearly
//!   rather than along ScLERP's helix: glTF has no screw interpolation, and a file that
//!   played something else than what was checked could break the bound. (Played with
//!   ScLERP's translation instead, the compressed CesiumMan at 0.005 moves by 4.2·10⁻⁵ at
//!   most, 0.8 % of the tolerance, the Fox's Run at 2 units by 0.084, 4 %: the test
//!   `screw_motion_between_kept_keys_stays_near_what_the_file_plays`.)
//! * [`Rotation::Squad`] — CUBICSPLINE channels carrying Squad's keys and tangents: at each
//!   kept key the derivative of Squad (Dam et al. §6.2.1, eq. 6.14–6.16: `dq/dh = q_i (L₊ −
//!   L₋)/2`, `L± = log(q_i⁻¹ q_{i±1})`, and `q_0 L₊`, `−q_N L₋` at the ends, from the end
//!   conditions `s_0 = q_0`, `s_N = q_N`), scaled by each interval's length as glTF's
//!   in- and out-tangents are. glTF has no Squad: the file's curve is the cubic Hermite in
//!   the four components with those tangents, normalized — equal to Squad at the keys, with
//!   its velocity there, C¹ like it, and close to it in between (within 0.0034° on
//!   CesiumMan's walk compressed to 0.005, 0.61° on the Fox's Run at 2 units, whose kept keys
//!   are further apart). That Hermite form is what is checked. Translations and scales get
//!   the Euclidean analogue (Catmull–Rom tangents `(p_{i+1} − p_{i−1})/2`).
//!
//! The key selection is greedy, not optimal: per animated node, starting from its first and
//! last frames, the frame where the node's reconstruction is worst is added as a key until
//! no frame is worse than a budget `b` (Douglas–Peucker's refinement on the node's curve).
//! A node's error at a frame is a bound on how far it moves the vertices below it:
//! `θ·r + σ·‖Δt‖ + ‖Δs‖∞/s_min·r`, with θ the rotation error (radians), r the largest
//! distance over the clip from the node to a vertex bound to it or to a joint below it, σ
//! the size of the parent's world transform (Frobenius norm). Errors of nodes on one chain
//! add up, and skinning blends them, so the whole mesh is then skinned at every frame
//! ([`ClipSkins`]): when its worst vertex error is above `D`, every budget shrinks by 0.7
//! and the selection runs again (from `b = D`), then five geometric halvings of the last
//! bracket find a larger budget that still passes, and the passing selection with the
//! fewest keys is kept. If none passes in 40 rounds (a tolerance below what rounding
//! allows), the clip's own channels are kept (error 0).
//!
//! The counts: kept keys are the written channels' keys, original keys the clip's; a
//! CUBICSPLINE key stores three values (in-tangent, value, out-tangent), a LINEAR key one.

use crate::animation::{Animation, Channel, Interpolation, Path};
use crate::error::{Result, SkinError};
use crate::gltf_write::rig_glb;
use crate::pose::{joint_transforms, world_of, Pose};
use crate::rig::{Rig, Trs};
use crate::skinning::{skin_joints, Method};
use chasles::{Quat, Vec3};
use rayon::prelude::*;

/// How rotations are reconstructed between kept keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rotation {
    /// Slerp (glTF LINEAR).
    Slerp,
    /// Squad's keys and tangents (glTF CUBICSPLINE).
    Squad,
}

impl Rotation {
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Rotation::Slerp => "slerp",
            Rotation::Squad => "squad",
        }
    }
}

/// How to compress a clip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompressOptions {
    /// The largest distance any vertex may move from where the original clip puts it, in
    /// model units (positive).
    pub tolerance: f64,
    /// The reconstruction of rotations.
    pub rotation: Rotation,
    /// The skinning method the vertices are measured with.
    pub method: Method,
}

/// A compressed clip and its measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Compressed {
    /// The clip (same name as the original).
    pub animation: Animation,
    /// The original sampling: the frame times every vertex was checked at.
    pub frames: Vec<f32>,
    /// Keys of the original clip's channels.
    pub original_keys: usize,
    /// Keys of the compressed clip's channels.
    pub kept_keys: usize,
    /// The worst vertex error over all frames (model units).
    pub worst: VertexError,
    /// The per-node budget that met the tolerance, as a fraction of it.
    pub budget: f64,
    /// Whether the original channels were kept (the tolerance could not be met otherwise).
    pub kept_original: bool,
}

impl Compressed {
    /// Kept keys over original keys.
    pub fn ratio(&self) -> f64 {
        self.kept_keys as f64 / self.original_keys.max(1) as f64
    }
}

/// The largest distance between two skinnings of a clip, and where.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexError {
    /// The distance (model units).
    pub distance: f64,
    /// The frame.
    pub frame: usize,
    /// The vertex.
    pub vertex: usize,
}

/// Checks a tolerance: finite and positive.
pub fn check_tolerance(d: f64) -> Result<()> {
    if d.is_finite() && d > 0.0 {
        Ok(())
    } else {
        Err(SkinError::Parameter {
            what: "the tolerance",
            value: d.to_string(),
            reason: "is not a positive number (model units)",
        })
    }
}

/// A clip skinned at given frame times: the reference every candidate is measured against.
#[derive(Debug, Clone, PartialEq)]
pub struct ClipSkins {
    /// The frame times.
    pub times: Vec<f32>,
    /// The skinned positions, per frame.
    pub positions: Vec<Vec<Vec3<f32>>>,
}

impl ClipSkins {
    /// Skins `clip` (any clip of `rig`'s nodes, not necessarily one of its own) at `times`
    /// with `method`.
    pub fn new(rig: &Rig, clip: &Animation, times: &[f32], method: Method) -> Result<Self> {
        let rest: Vec<Trs> = rig.nodes.iter().map(|n| n.rest).collect();
        let positions = times
            .par_iter()
            .map(|t| {
                let pose = Pose {
                    local: clip.sample(&rest, *t),
                };
                Ok(skin_joints(rig, &joint_transforms(rig, &pose)?, method)?.positions)
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(ClipSkins {
            times: times.to_vec(),
            positions,
        })
    }

    /// The largest distance between a vertex here and in `other` (same frames, same
    /// vertex count); errors when the counts differ.
    pub fn worst_distance(&self, other: &ClipSkins) -> Result<VertexError> {
        let count = |what, a: usize, b: usize| {
            crate::error::same_count("the compared skinnings", what, a, b)
        };
        count("frames", self.positions.len(), other.positions.len())?;
        let mut worst = VertexError {
            distance: 0.0,
            frame: 0,
            vertex: 0,
        };
        for (f, (a, b)) in self.positions.iter().zip(&other.positions).enumerate() {
            count("vertices", a.len(), b.len())?;
            for (v, (p, q)) in a.iter().zip(b).enumerate() {
                let d = (p.cast::<f64>() - q.cast::<f64>()).norm();
                if d > worst.distance || d.is_nan() {
                    worst = VertexError {
                        distance: d,
                        frame: f,
                        vertex: v,
                    };
                }
            }
        }
        Ok(worst)
    }
}

/// One animated node: its samples at every frame and the constants of its error bound.
struct NodeTrack {
    node: usize,
    paths: Vec<Path>,
    /// Per frame: translation, rotation (hemisphere-chained), scale.
    t: Vec<Vec3<f64>>,
    q: Vec<Quat<f64>>,
    s: Vec<Vec3<f64>>,
    /// Reach r and parent size σ.
    reach: f64,
    sigma: f64,
    s_min: f64,
}

fn v4(v: Vec3<f64>) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, 0.0]
}

impl NodeTrack {
    /// The channels of this node with keys at `keys` (frame indices, increasing).
    fn channels(&self, keys: &[usize], times: &[f32], rot: Rotation) -> Result<Vec<Channel>> {
        let kt: Vec<f32> = keys.iter().map(|k| times[*k]).collect();
        let mut out = Vec::with_capacity(self.paths.len());
        for path in &self.paths {
            let (interpolation, values) = match (rot, path) {
                (Rotation::Slerp, Path::Rotation) => (
                    Interpolation::Linear,
                    keys.iter()
                        .map(|k| self.q[*k].cast::<f32>().to_array())
                        .collect(),
                ),
                (Rotation::Slerp, p) => (
                    Interpolation::Linear,
                    keys.iter().map(|k| v4(self.vec(*p, *k))).collect(),
                ),
                (Rotation::Squad, Path::Rotation) => {
                    (Interpolation::CubicSpline, self.squad_rotation(keys, &kt)?)
                }
                (Rotation::Squad, p) => (Interpolation::CubicSpline, self.hermite(*p, keys, &kt)),
            };
            out.push(Channel {
                node: self.node,
                path: *path,
                interpolation,
                times: kt.clone(),
                values,
            });
        }
        Ok(out)
    }

    fn vec(&self, p: Path, k: usize) -> Vec3<f64> {
        match p {
            Path::Scale => self.s[k],
            _ => self.t[k],
        }
    }

    /// Squad's tangents at the kept keys, as glTF CUBICSPLINE values (in, value, out).
    fn squad_rotation(&self, keys: &[usize], kt: &[f32]) -> Result<Vec<[f32; 4]>> {
        let n = keys.len();
        let mut q: Vec<Quat<f64>> = keys.iter().map(|k| self.q[*k]).collect();
        for i in 1..n {
            if q[i].dot(q[i - 1]) < 0.0 {
                q[i] = -q[i];
            }
        }
        let dt = |i: usize| f64::from(kt[i + 1]) - f64::from(kt[i]);
        let mut out = Vec::with_capacity(3 * n);
        for i in 0..n {
            let inv = q[i].conjugate();
            let lp = if i + 1 < n {
                Some((inv * q[i + 1]).log()?)
            } else {
                None
            };
            let lm = if i > 0 {
                Some((inv * q[i - 1]).log()?)
            } else {
                None
            };
            // dq/dh leaving and reaching q_i (equal inside, Squad being C¹ in h).
            let tangent = match (lp, lm) {
                (Some(p), Some(m)) => q[i] * ((p - m) * 0.5),
                (Some(p), None) => q[i] * p,
                (None, Some(m)) => q[i] * (-m),
                (None, None) => Quat::zero(),
            };
            let zero = Quat::zero();
            let tin = if i > 0 {
                tangent * (1.0 / dt(i - 1))
            } else {
                zero
            };
            let tout = if i + 1 < n {
                tangent * (1.0 / dt(i))
            } else {
                zero
            };
            out.push(tin.cast::<f32>().to_array());
            out.push(q[i].cast::<f32>().to_array());
            out.push(tout.cast::<f32>().to_array());
        }
        Ok(out)
    }

    /// Catmull–Rom tangents at the kept keys (Squad's Euclidean analogue), as CUBICSPLINE.
    fn hermite(&self, p: Path, keys: &[usize], kt: &[f32]) -> Vec<[f32; 4]> {
        let n = keys.len();
        let x: Vec<Vec3<f64>> = keys.iter().map(|k| self.vec(p, *k)).collect();
        let dt = |i: usize| f64::from(kt[i + 1]) - f64::from(kt[i]);
        let mut out = Vec::with_capacity(3 * n);
        for i in 0..n {
            let tangent = match (i > 0, i + 1 < n) {
                (true, true) => (x[i + 1] - x[i - 1]) * 0.5,
                (false, true) => x[i + 1] - x[i],
                (true, false) => x[i] - x[i - 1],
                (false, false) => Vec3::zero(),
            };
            let tin = if i > 0 {
                tangent * (1.0 / dt(i - 1))
            } else {
                Vec3::zero()
            };
            let tout = if i + 1 < n {
                tangent * (1.0 / dt(i))
            } else {
                Vec3::zero()
            };
            out.push(v4(tin));
            out.push(v4(x[i]));
            out.push(v4(tout));
        }
        out
    }

    /// The node's error bound at every frame for these channels.
    fn errors(&self, channels: &[Channel], times: &[f32]) -> Vec<f64> {
        let mut e = vec![0.0f64; times.len()];
        for ch in channels {
            for (f, t) in times.iter().enumerate() {
                let v = ch.sample(*t);
                e[f] += match ch.path {
                    Path::Rotation => {
                        let r = Quat::from_array(v).cast::<f64>();
                        let r = r.normalize().unwrap_or(r);
                        let o = self.q[f];
                        let chord = (r - o).norm().min((r + o).norm());
                        4.0 * (chord / 2.0).min(1.0).asin() * self.reach
                    }
                    Path::Translation => {
                        let d = Vec3::new(v[0], v[1], v[2]).cast::<f64>() - self.t[f];
                        self.sigma * d.norm()
                    }
                    Path::Scale => {
                        let d = Vec3::new(v[0], v[1], v[2]).cast::<f64>() - self.s[f];
                        let m = d.x.abs().max(d.y.abs()).max(d.z.abs());
                        m / self.s_min * self.reach
                    }
                };
            }
        }
        e
    }

    /// Greedy key selection: the worst frame added until every frame is within `budget`.
    fn select(&self, times: &[f32], rot: Rotation, budget: f64) -> Result<Vec<Channel>> {
        let n = times.len();
        let mut keys = vec![0, n - 1];
        loop {
            let ch = self.channels(&keys, times, rot)?;
            let e = self.errors(&ch, times);
            let (f, worst) = e
                .iter()
                .enumerate()
                .filter(|(f, _)| keys.binary_search(f).is_err())
                .fold((usize::MAX, 0.0f64), |(bf, be), (f, x)| {
                    if *x > be {
                        (f, *x)
                    } else {
                        (bf, be)
                    }
                });
            if f == usize::MAX || worst <= budget {
                return Ok(ch);
            }
            let at = keys.binary_search(&f).unwrap_or_else(|i| i);
            keys.insert(at, f);
        }
    }
}

/// The animated nodes of `clip` with their samples and error-bound constants.
fn tracks(rig: &Rig, clip: &Animation, times: &[f32], reference: &ClipSkins) -> Vec<NodeTrack> {
    let rest: Vec<Trs> = rig.nodes.iter().map(|n| n.rest).collect();
    let locals: Vec<Vec<Trs>> = times.iter().map(|t| clip.sample(&rest, *t)).collect();
    let worlds: Vec<_> = locals.iter().map(|l| world_of(&rig.nodes, l)).collect();
    // The vertices below each node: those bound to a joint whose chain passes through it.
    let nn = rig.nodes.len();
    let mut below: Vec<Vec<bool>> = vec![vec![false; rig.joints.len()]; nn];
    for (j, node) in rig.joints.iter().enumerate() {
        let mut p = Some(*node);
        let mut steps = 0;
        while let Some(k) = p {
            below[k][j] = true;
            p = rig.nodes[k].parent;
            steps += 1;
            if steps > nn {
                break;
            }
        }
    }
    clip.nodes()
        .into_iter()
        .map(|node| {
            let paths: Vec<Path> = [Path::Translation, Path::Rotation, Path::Scale]
                .into_iter()
                .filter(|p| clip.animates(node, *p))
                .collect();
            let mut q: Vec<Quat<f64>> = locals
                .iter()
                .map(|l| l[node].rotation.cast::<f64>())
                .collect();
            for i in 1..q.len() {
                if q[i].dot(q[i - 1]) < 0.0 {
                    q[i] = -q[i];
                }
            }
            let t = locals
                .iter()
                .map(|l| l[node].translation.cast::<f64>())
                .collect();
            let s: Vec<Vec3<f64>> = locals.iter().map(|l| l[node].scale.cast::<f64>()).collect();
            let s_min = s
                .iter()
                .flat_map(|v| [v.x.abs(), v.y.abs(), v.z.abs()])
                .fold(f64::INFINITY, f64::min)
                .max(1e-6);
            let mut reach = 0.0f64;
            let mut sigma = 1.0f64;
            for (f, w) in worlds.iter().enumerate() {
                let o = w[node].translation().cast::<f64>();
                for (v, p) in reference.positions[f].iter().enumerate() {
                    if rig.influences.of(v).any(|(j, _)| below[node][j]) {
                        reach = reach.max((p.cast::<f64>() - o).norm());
                    }
                }
                if let Some(par) = rig.nodes[node].parent {
                    let a = w[par].linear_part();
                    let fro: f64 = a.entries().map(|x| f64::from(x) * f64::from(x)).sum();
                    sigma = sigma.max(fro.sqrt());
                }
            }
            NodeTrack {
                node,
                paths,
                t,
                q,
                s,
                reach,
                sigma,
                s_min,
            }
        })
        .collect()
}

/// Compresses clip `clip` of `rig` (by index); see the module docs. Errors: a clip that
/// does not exist, a tolerance that is not positive and finite, a pose that cannot be
/// skinned.
pub fn compress(rig: &Rig, clip: usize, opts: &CompressOptions) -> Result<Compressed> {
    check_tolerance(opts.tolerance)?;
    let original = rig
        .animations
        .get(clip)
        .ok_or_else(|| SkinError::NoAnimation {
            rig: rig.name.clone(),
            clip,
            count: rig.animations.len(),
        })?;
    let frames = original.key_times();
    let original_keys: usize = original.channels.iter().map(|c| c.times.len()).sum();
    let reference = ClipSkins::new(rig, original, &frames, opts.method)?;
    let keep = |worst| Compressed {
        animation: original.clone(),
        frames: frames.clone(),
        original_keys,
        kept_keys: original_keys,
        worst,
        budget: 0.0,
        kept_original: true,
    };
    let zero = VertexError {
        distance: 0.0,
        frame: 0,
        vertex: 0,
    };
    if frames.len() < 3 {
        return Ok(keep(zero));
    }
    let tracks = tracks(rig, original, &frames, &reference);
    // One selection with every node's budget `b·D`, skinned and measured.
    let attempt = |b: f64| -> Result<Option<Compressed>> {
        let channels = tracks
            .par_iter()
            .map(|t| t.select(&frames, opts.rotation, b * opts.tolerance))
            .collect::<Result<Vec<_>>>()?
            .into_iter()
            .flatten()
            .collect::<Vec<_>>();
        let animation = Animation {
            name: original.name.clone(),
            channels,
        };
        let worst =
            reference.worst_distance(&ClipSkins::new(rig, &animation, &frames, opts.method)?)?;
        if worst.distance > opts.tolerance {
            return Ok(None);
        }
        let kept_keys = animation.channels.iter().map(|c| c.times.len()).sum();
        Ok(Some(Compressed {
            animation,
            frames: frames.clone(),
            original_keys,
            kept_keys,
            worst,
            budget: b,
            kept_original: false,
        }))
    };
    // The largest budget that passes: down by 0.7 from 1 until one does, then five halvings
    // (geometric) of the bracket; the passing selection with the fewest keys is kept.
    let mut best: Option<Compressed> = None;
    let mut keep_best = |c: Compressed| {
        if best.as_ref().is_none_or(|b| c.kept_keys < b.kept_keys) {
            best = Some(c);
        }
    };
    let mut budget = 1.0f64;
    let mut failed = None;
    for _ in 0..40 {
        match attempt(budget)? {
            Some(c) => {
                keep_best(c);
                break;
            }
            None => {
                failed = Some(budget);
                budget *= 0.7;
            }
        }
    }
    if let Some(mut hi) = failed {
        let mut lo = budget;
        for _ in 0..5 {
            let mid = (lo * hi).sqrt();
            match attempt(mid)? {
                Some(c) => {
                    keep_best(c);
                    lo = mid;
                }
                None => hi = mid,
            }
        }
    }
    if let Some(b) = best {
        return Ok(b);
    }
    Ok(keep(zero))
}

/// A compressed clip written as `.glb` and measured there.
#[derive(Debug, Clone)]
pub struct Written {
    /// The compression (its `worst` is the in-memory error).
    pub compressed: Compressed,
    /// The file's bytes: the rig with the compressed clip first, then `extra`.
    pub bytes: Vec<u8>,
    /// The worst vertex error of the file loaded back (rig and clip as read), against the
    /// original clip on the original rig, at the original sampling.
    pub in_file: VertexError,
}

/// [`compress`], then the rig with the clip (and `extra` clips after it) written as `.glb`
/// ([`rig_glb`]), loaded back and skinned at every frame: the bound is checked on the file.
/// Writing rounds a little (the loader renormalizes the f32 weights, so a vertex can move by
/// a few units in the last place): when the file's error passes the tolerance although the
/// clip met it in memory, the clip is compressed again to the tolerance less twice that
/// excess (at most three times). Errors: those of [`compress`]; a tolerance the file cannot
/// meet even with the clip's own channels (below its rounding) is [`SkinError::Parameter`].
pub fn compress_to_glb(
    rig: &Rig,
    clip: usize,
    opts: &CompressOptions,
    extra: &[Animation],
    comment: &str,
) -> Result<Written> {
    let mut target = *opts;
    for _ in 0..4 {
        let compressed = compress(rig, clip, &target)?;
        let mut clips = vec![compressed.animation.clone()];
        clips.extend_from_slice(extra);
        let bytes = rig_glb(rig, &clips, comment)?;
        let back = crate::gltf_load::load_slice(&bytes, &rig.name)?;
        let reference =
            ClipSkins::new(rig, &rig.animations[clip], &compressed.frames, opts.method)?;
        let file = ClipSkins::new(&back, &back.animations[0], &compressed.frames, opts.method)?;
        let in_file = reference.worst_distance(&file)?;
        if in_file.distance <= opts.tolerance {
            return Ok(Written {
                compressed,
                bytes,
                in_file,
            });
        }
        let excess = in_file.distance - compressed.worst.distance;
        target.tolerance = opts.tolerance - 2.0 * excess.max(0.0);
        if compressed.kept_original || target.tolerance <= 0.0 {
            break;
        }
    }
    Err(SkinError::Parameter {
        what: "the tolerance",
        value: opts.tolerance.to_string(),
        reason: "is below the rounding of the written file (its own clip, written, moves vertices further)",
    })
}
