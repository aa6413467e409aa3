//! The fast path for log-matrix skinning (Alexa 2002, the "Log" column of Kavan et al.
//! 2006, Table 1 and Figure 1): each joint's rigid transform is taken to its twist
//! `log Cⱼ = (ω, v)` once per pose, and each vertex blends its K twists linearly and maps
//! the sum back by the closed-form exponential — no allocation, rayon over chunks, as for
//! LBS and DQS; eight vertices at a time with AVX2 and FMA where the processor has them (4 or
//! 8 influences: `avx2::log`, the exponential's coefficients by their Taylor series, no
//! trigonometric calls). The scalar kernel runs the same exponential (the lane algebra's
//! `exp_twist`, on one vertex; valid for the logarithm's range θ ≤ π); tests check both
//! against the reference path to 1e-5 on every model and clip.

use super::{run, Kernel, Out, Vertex};
use crate::error::Result;
pub use crate::skinning::twists;
use chasles::blend::log::Twist;

/// A twist as `[ω, v, 0, 0]`: one 8-float register.
type Row = [f32; 8];

#[inline(always)]
fn log_vertex<const K: usize>(v: &Vertex<K>, t: &[Row]) -> Out {
    let mut b = [0f32; 6];
    for k in 0..K {
        let tj = &t[usize::from(v.j[k])];
        for i in 0..6 {
            b[i] += v.w[k] * tj[i];
        }
    }
    super::lane::exp_twist([b[0], b[1], b[2]], [b[3], b[4], b[5]], v.p, v.n)
}

pub(super) struct LogKernel;
impl<const K: usize> Kernel<K> for LogKernel {
    type Joint = Row;
    type Table = ();
    fn table(_: &[Row], _: usize) {}
    #[cfg(target_arch = "x86_64")]
    const AVX2: Option<super::SimdKernel<K, Row, ()>> = Some(super::avx2::log::log::<K>);
    #[inline(always)]
    fn vertex(v: &Vertex<K>, joints: &[Row]) -> Out {
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
    run::<K, LogKernel>(rig, &rows(twists), out.into(), parallel)
}

/// The twists as the kernels read them, `[ω, v, 0, 0]`.
pub(super) fn rows(twists: &[Twist<f32>]) -> Vec<Row> {
    twists.iter().map(row).collect()
}

/// One twist as the kernels read it.
pub(super) fn row(t: &Twist<f32>) -> Row {
    let ([a, b, c], [d, e, f]) = (t.w.to_array(), t.v.to_array());
    [a, b, c, d, e, f, 0.0, 0.0]
}
