//! The fast path for log-matrix skinning (Alexa 2002, the "Log" column of Kavan et al.
//! 2006, Table 1 and Figure 1): each joint's rigid transform is taken to its twist
//! `log Cⱼ = (ω, v)` once per pose, and each vertex blends its K twists linearly and maps
//! the sum back by the closed-form exponential — no allocation, rayon over chunks, as for
//! LBS and DQS. The same formulas as the reference path ([`crate::skinning`]), so the two
//! agree to rounding (tests check 1e-5 on every model and clip).

use super::{run, Kernel, Out, Vertex};
use crate::error::Result;
use crate::pose::JointTransforms;
use chasles::blend::log::{exp_twist, log_rigid, Twist};
use chasles::Vec3;

/// The joints' twists for [`log`]: `log` of each joint matrix's nearest rigid transform (a
/// scaled or sheared joint is made rigid first, as the reference path does).
pub fn twists(jt: &JointTransforms) -> Result<Vec<Twist<f32>>> {
    jt.matrices
        .iter()
        .map(|m| log_rigid(&crate::skinning::rigid(m)).map_err(Into::into))
        .collect()
}

#[inline(always)]
fn log_vertex<const K: usize>(v: &Vertex<K>, t: &[Twist<f32>]) -> Out {
    let mut x = Twist {
        w: Vec3::zero(),
        v: Vec3::zero(),
    };
    for k in 0..K {
        let tj = &t[usize::from(v.j[k])];
        x.w += tj.w * v.w[k];
        x.v += tj.v * v.w[k];
    }
    let m = exp_twist(&x);
    let n = Vec3::from_array(v.n);
    let p = m.transform_point(Vec3::from_array(v.p));
    let r = m.linear_part().mul_vec(n);
    let [px, py, pz] = p.to_array();
    let [nx, ny, nz] = r.normalize().unwrap_or(n).to_array();
    [px, py, pz, nx, ny, nz]
}

struct LogKernel;
impl<const K: usize> Kernel<K> for LogKernel {
    type Joint = Twist<f32>;
    type Table = ();
    fn table(_: &[Twist<f32>], _: usize) {}
    #[cfg(target_arch = "x86_64")]
    const AVX2: Option<super::SimdKernel<Twist<f32>, ()>> = None;
    #[inline(always)]
    fn vertex(v: &Vertex<K>, joints: &[Twist<f32>]) -> Out {
        log_vertex(v, joints)
    }
}

/// Log-matrix skinning into `out` with the joints' [`twists`], on all threads when
/// `parallel`.
pub fn log<const K: usize>(
    rig: &super::FastRig<K>,
    twists: &[Twist<f32>],
    out: &mut [Out],
    parallel: bool,
) -> Result<()> {
    run::<K, LogKernel>(rig, twists, out, parallel)
}
