//! The fast path for log-matrix skinning (Alexa 2002, the "Log" column of Kavan et al.
//! 2006, Table 1 and Figure 1): each joint's rigid transform is taken to its twist
//! `log Cⱼ = (ω, v)` once per pose, and each vertex blends its K twists linearly and maps
//! the sum back by the closed-form exponential — no allocation, rayon over chunks, as for
//! LBS and DQS. The same formulas as the reference path ([`crate::skinning`]), so the two
//! agree to rounding (tests check 1e-5 on every model and clip).

use super::{run, Kernel, Out, Vertex};
use crate::error::Result;
use crate::skinning::exp_twist_vertex;
pub use crate::skinning::twists;
use chasles::blend::log::Twist;
use chasles::Vec3;

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
    let (p, n) = exp_twist_vertex(&x, Vec3::from_array(v.p), Vec3::from_array(v.n));
    let ([px, py, pz], [nx, ny, nz]) = (p.to_array(), n.to_array());
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

/// Log-matrix skinning into `out` with the joints' [`twists`] (made once per pose), on all threads when
/// `parallel`.
pub fn log<const K: usize>(
    rig: &super::FastRig<K>,
    twists: &[Twist<f32>],
    out: &mut [Out],
    parallel: bool,
) -> Result<()> {
    run::<K, LogKernel>(rig, twists, out, parallel)
}
