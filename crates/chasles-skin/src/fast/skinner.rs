//! Every method on the fast path behind one call, for tools that skin whole clips
//! (`chasles skin --all-frames`): the rig's layout made once — 4 influences, else 8, else
//! the reference path ([`crate::skinning`]) — the SBS clusters on first use, and each pose's
//! palette per call; all threads. Beneath it, [`skin_pose`]: one pose by any method into a
//! caller's buffer through the [`SkinningJob`], on one thread or all (the benchmarks and
//! tests call it).

use super::{FastRig, Out, Palette, SkinningJob};
use crate::error::{Result, SkinError};
use crate::pose::JointTransforms;
use crate::rig::Rig;
use crate::skinning::{skin_joints, Method, Skinned};
use chasles::Vec3;

/// A rig laid out for the fast path, skinning any [`Method`] on all threads.
#[derive(Debug)]
pub struct Skinner {
    layout: Layout,
}

#[derive(Debug)]
enum Layout {
    Four(FastRig<4>),
    Eight(FastRig<8>),
    /// More than 8 influences on some vertex: the reference path.
    Reference,
}

impl Skinner {
    /// Lays `rig` out (its joint indices were checked when it was built).
    pub fn new(rig: &Rig) -> Result<Self> {
        let layout = match rig.influences.max_per_vertex() {
            0..=4 => Layout::Four(FastRig::new(rig)?),
            5..=8 => Layout::Eight(FastRig::new(rig)?),
            _ => Layout::Reference,
        };
        Ok(Skinner { layout })
    }

    /// How many influences a vertex may have on the fast path taken (0: the reference path).
    pub fn influences(&self) -> usize {
        match self.layout {
            Layout::Four(_) => 4,
            Layout::Eight(_) => 8,
            Layout::Reference => 0,
        }
    }

    /// `rig` (the one this was made from) skinned with joint transforms `jt` by `method`:
    /// the fast path's numbers (within 1e-5 of the reference), an error naming the method
    /// where a position comes out non-finite.
    pub fn skin(&self, rig: &Rig, jt: &JointTransforms, method: Method) -> Result<Skinned> {
        let out = match &self.layout {
            Layout::Four(f) => self.run(f, jt, method)?,
            Layout::Eight(f) => self.run(f, jt, method)?,
            Layout::Reference => return skin_joints(rig, jt, method),
        };
        if let Some(v) = out.iter().position(|o| o.iter().any(|x| !x.is_finite())) {
            return Err(SkinError::NonFiniteOutput {
                rig: rig.name.clone(),
                method: method.name(),
                vertex: v,
            });
        }
        Ok(Skinned {
            positions: out.iter().map(|o| Vec3::new(o[0], o[1], o[2])).collect(),
            normals: out.iter().map(|o| Vec3::new(o[3], o[4], o[5])).collect(),
        })
    }

    fn run<const K: usize>(
        &self,
        f: &FastRig<K>,
        jt: &JointTransforms,
        method: Method,
    ) -> Result<Vec<Out>> {
        let mut out = vec![[0f32; 6]; f.vertices().len()];
        skin_pose(f, jt, method, &mut out, true)?;
        Ok(out)
    }
}

/// One pose skinned by `method` on the fast path into `out`: the method's [`Palette`] made
/// from `jt` (SBS's clusters are the rig's own, made on first use) and run as a
/// [`SkinningJob`]; on all threads when `parallel`.
pub fn skin_pose<const K: usize>(
    rig: &FastRig<K>,
    jt: &JointTransforms,
    method: Method,
    out: &mut [Out],
    parallel: bool,
) -> Result<()> {
    let palette = Palette::from_joint_transforms(method, rig, jt, parallel)?;
    SkinningJob {
        rig,
        palette: &palette,
        output: out.into(),
        parallel,
    }
    .run()
}
