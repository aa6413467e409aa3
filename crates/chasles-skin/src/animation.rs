//! Animations of node transforms, sampled by the glTF 2.0 rules (§3.11 "Animations" and
//! Appendix C of the glTF specification): LINEAR (translation and scale linearly, rotation
//! by Slerp the shorter way — Dam et al. §6.1.5), STEP (the last key at or before t), and
//! CUBICSPLINE (cubic Hermite with the stored in- and out-tangents scaled by the key
//! interval; rotations normalized afterwards). Before the first key the first value holds,
//! after the last key the last.

use crate::error::ChannelProblem;
use crate::rig::Trs;
use chasles::interp::slerp::slerp_shortest;
use chasles::{Quat, Vec3};

/// Which property a channel drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Path {
    /// The node's translation (3 numbers per key).
    Translation,
    /// The node's rotation (4 numbers per key, `[x, y, z, w]` in glTF, stored here as
    /// `[w, x, y, z]` quaternions).
    Rotation,
    /// The node's scale (3 numbers per key).
    Scale,
}

/// How values between keys are found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interpolation {
    /// Linear (Slerp for rotations).
    Linear,
    /// Constant until the next key.
    Step,
    /// Cubic Hermite spline with tangents.
    CubicSpline,
}

/// One animated property of one node.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// The node.
    pub node: usize,
    /// The property.
    pub path: Path,
    /// The interpolation.
    pub interpolation: Interpolation,
    /// Key times, strictly increasing.
    pub times: Vec<f32>,
    /// Values as 4-vectors (`[x, y, z, 0]` or `[w, x, y, z]`); for CUBICSPLINE three per key:
    /// in-tangent, value, out-tangent.
    pub values: Vec<[f32; 4]>,
}

/// A named clip.
#[derive(Debug, Clone, PartialEq)]
pub struct Animation {
    /// The clip's name ("" when unnamed).
    pub name: String,
    /// Its channels.
    pub channels: Vec<Channel>,
}

impl Channel {
    /// Checks the target node, times (finite, strictly increasing) and the number of
    /// values; [`crate::Rig::new`] runs it on every channel.
    pub fn validate(&self, nodes: usize) -> Result<(), ChannelProblem> {
        if self.node >= nodes {
            return Err(ChannelProblem::NodeOutOfRange { nodes });
        }
        if self.times.is_empty() {
            return Err(ChannelProblem::NoKeys);
        }
        if self.times.iter().any(|t| !t.is_finite()) || self.times.windows(2).any(|w| w[1] <= w[0])
        {
            return Err(ChannelProblem::Times);
        }
        let per = if self.interpolation == Interpolation::CubicSpline {
            3
        } else {
            1
        };
        if self.values.len() != self.times.len() * per {
            return Err(ChannelProblem::Values {
                keys: self.times.len(),
                values: self.values.len(),
                expected: self.times.len() * per,
            });
        }
        if self.values.iter().flatten().any(|v| !v.is_finite()) {
            return Err(ChannelProblem::NotFinite);
        }
        Ok(())
    }

    fn value(&self, k: usize) -> [f32; 4] {
        match self.interpolation {
            Interpolation::CubicSpline => self.values[3 * k + 1],
            _ => self.values[k],
        }
    }

    /// The key interval `[times[k], times[k + 1]]` that time t falls in (the first before
    /// the first key, the last after the last) and t's place in it, `u ∈ [0, 1]`. Needs two
    /// keys or more.
    pub fn interval(&self, t: f32) -> (usize, f32) {
        let n = self.times.len();
        let k = self.times.partition_point(|x| *x <= t).clamp(1, n - 1) - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        (k, ((t - t0) / (t1 - t0)).clamp(0.0, 1.0))
    }

    /// The channel's value at time t.
    pub fn sample(&self, t: f32) -> [f32; 4] {
        let n = self.times.len();
        if t <= self.times[0] || n == 1 {
            return self.value(0);
        }
        if t >= self.times[n - 1] {
            return self.value(n - 1);
        }
        let (k, u) = self.interval(t);
        let dt = self.times[k + 1] - self.times[k];
        match self.interpolation {
            Interpolation::Step => self.value(k),
            Interpolation::Linear => {
                let (a, b) = (self.value(k), self.value(k + 1));
                if self.path == Path::Rotation {
                    slerp_shortest(Quat::from_array(a), Quat::from_array(b), u).to_array()
                } else {
                    core::array::from_fn(|i| a[i] + (b[i] - a[i]) * u)
                }
            }
            Interpolation::CubicSpline => {
                let p0 = self.values[3 * k + 1];
                let m0 = self.values[3 * k + 2]; // out-tangent of k
                let p1 = self.values[3 * (k + 1) + 1];
                let m1 = self.values[3 * (k + 1)]; // in-tangent of k + 1
                let (u2, u3) = (u * u, u * u * u);
                let h = [
                    2.0 * u3 - 3.0 * u2 + 1.0,
                    u3 - 2.0 * u2 + u,
                    -2.0 * u3 + 3.0 * u2,
                    u3 - u2,
                ];
                let v: [f32; 4] = core::array::from_fn(|i| {
                    h[0] * p0[i] + h[1] * dt * m0[i] + h[2] * p1[i] + h[3] * dt * m1[i]
                });
                if self.path == Path::Rotation {
                    Quat::from_array(v)
                        .normalize()
                        .map(|q| q.to_array())
                        .unwrap_or(p0)
                } else {
                    v
                }
            }
        }
    }
}

impl Animation {
    /// The last key time of any channel.
    pub fn duration(&self) -> f32 {
        self.channels
            .iter()
            .filter_map(|c| c.times.last().copied())
            .fold(0.0, f32::max)
    }

    /// Every key time of any channel, sorted, times within a millionth of a second (times
    /// stored by different channels in f32) counted once: the clip's own sampling.
    pub fn key_times(&self) -> Vec<f32> {
        let mut t: Vec<f32> = self
            .channels
            .iter()
            .flat_map(|c| c.times.iter().copied())
            .collect();
        t.sort_by(f32::total_cmp);
        t.dedup_by(|b, a| (*b - *a).abs() <= 1e-6 * a.abs().max(1.0));
        t
    }

    /// Whether a channel drives `path` of `node`.
    pub fn animates(&self, node: usize, path: Path) -> bool {
        self.channels
            .iter()
            .any(|c| c.node == node && c.path == path)
    }

    /// The nodes any channel drives, in increasing order.
    pub fn nodes(&self) -> Vec<usize> {
        let mut n: Vec<usize> = self.channels.iter().map(|c| c.node).collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    /// The local transforms of all nodes at time t: the rest transforms with the animated
    /// properties replaced.
    pub fn sample(&self, rest: &[Trs], t: f32) -> Vec<Trs> {
        let mut local = rest.to_vec();
        for c in &self.channels {
            let v = c.sample(t);
            let trs = &mut local[c.node];
            match c.path {
                Path::Translation => trs.translation = Vec3::new(v[0], v[1], v[2]),
                Path::Scale => trs.scale = Vec3::new(v[0], v[1], v[2]),
                Path::Rotation => {
                    trs.rotation = Quat::from_array(v).normalize().unwrap_or(trs.rotation)
                }
            }
        }
        local
    }
}
