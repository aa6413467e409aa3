//! Eight vertices at a time with AVX2 and FMA (x86-64, chosen at run time): the vertex
//! fields and the joints' dual quaternions are gathered into 8-lane registers and the DQS
//! arithmetic of [`super::dqs_vertex`] runs lane-parallel, in the same order of operations,
//! so the results agree with the scalar kernel to rounding.

use super::{Out, Vertex};
use std::arch::x86_64::*;

/// Vertex stride in floats (`Vertex<4>` is 48 bytes: p 0–2, n 3–5, joints 6–7 as two u32
/// words of u16 pairs, weights 8–11).
const STRIDE: i32 = 12;

/// Eight vertices' fields in lanes: position, normal, joint indices, weights.
struct Block {
    p: [__m256; 3],
    n: [__m256; 3],
    j: [__m256i; 4],
    w: [__m256; 4],
}

/// Gathers vertices `i … i + 7`.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn load(v: &[Vertex<4>], i: usize) -> Block {
    let vb = v.as_ptr() as *const f32;
    let lane = _mm256_setr_epi32(
        0,
        STRIDE,
        2 * STRIDE,
        3 * STRIDE,
        4 * STRIDE,
        5 * STRIDE,
        6 * STRIDE,
        7 * STRIDE,
    );
    let vi = _mm256_add_epi32(_mm256_set1_epi32(i as i32 * STRIDE), lane);
    let at = |off: i32| _mm256_add_epi32(vi, _mm256_set1_epi32(off));
    let g = |off: i32| _mm256_i32gather_ps::<4>(vb, at(off));
    let lo16 = _mm256_set1_epi32(0xFFFF);
    let j01 = _mm256_i32gather_epi32::<4>(vb as *const i32, at(6));
    let j23 = _mm256_i32gather_epi32::<4>(vb as *const i32, at(7));
    Block {
        p: [g(0), g(1), g(2)],
        n: [g(3), g(4), g(5)],
        j: [
            _mm256_and_si256(j01, lo16),
            _mm256_srli_epi32::<16>(j01),
            _mm256_and_si256(j23, lo16),
            _mm256_srli_epi32::<16>(j23),
        ],
        w: [g(8), g(9), g(10), g(11)],
    }
}

/// Writes eight vertices' results (six lane vectors) to `o[i … i + 7]`.
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn store(o: &mut [Out], i: usize, r: [__m256; 6]) {
    let mut lanes = [[0f32; 8]; 6];
    for (dst, src) in lanes.iter_mut().zip(r) {
        _mm256_storeu_ps(dst.as_mut_ptr(), src);
    }
    for l in 0..8 {
        o[i + l] = [
            lanes[0][l],
            lanes[1][l],
            lanes[2][l],
            lanes[3][l],
            lanes[4][l],
            lanes[5][l],
        ];
    }
}

/// DQS for the first `v.len() / 8 * 8` vertices; returns how many were done.
///
/// # Safety
/// The processor must have AVX2 and FMA, every joint index in `v` must be below
/// `d.len()`, and `o.len() >= v.len()`.
#[target_feature(enable = "avx2,fma")]
pub unsafe fn dqs(v: &[Vertex<4>], d: &[[f32; 8]], o: &mut [Out]) -> usize {
    let db = d.as_ptr() as *const f32;
    let zero = _mm256_setzero_ps();
    let sign = _mm256_set1_ps(-0.0);
    let one = _mm256_set1_ps(1.0);
    let two = _mm256_set1_ps(2.0);
    macro_rules! gd {
        ($base:expr, $c:expr) => {
            _mm256_i32gather_ps::<4>(db, _mm256_add_epi32($base, _mm256_set1_epi32($c)))
        };
    }
    let blocks = v.len() / 8;
    for blk in 0..blocks {
        let i = blk * 8;
        let Block {
            p: [px, py, pz],
            n: [nx, ny, nz],
            j: js,
            w: ws,
        } = load(v, i);
        let base0 = _mm256_slli_epi32::<3>(js[0]);
        let p = [gd!(base0, 0), gd!(base0, 1), gd!(base0, 2), gd!(base0, 3)];
        let mut b = [zero; 8];
        for k in 0..4 {
            let base = _mm256_slli_epi32::<3>(js[k]);
            let q = [
                gd!(base, 0),
                gd!(base, 1),
                gd!(base, 2),
                gd!(base, 3),
                gd!(base, 4),
                gd!(base, 5),
                gd!(base, 6),
                gd!(base, 7),
            ];
            // dot = q0 p0 + q1 p1 + q2 p2 + q3 p3, as the scalar kernel sums it.
            let dot = _mm256_add_ps(
                _mm256_add_ps(
                    _mm256_add_ps(_mm256_mul_ps(q[0], p[0]), _mm256_mul_ps(q[1], p[1])),
                    _mm256_mul_ps(q[2], p[2]),
                ),
                _mm256_mul_ps(q[3], p[3]),
            );
            let neg = _mm256_and_ps(_mm256_cmp_ps::<_CMP_LT_OQ>(dot, zero), sign);
            let w = _mm256_xor_ps(ws[k], neg);
            for c in 0..8 {
                b[c] = _mm256_add_ps(b[c], _mm256_mul_ps(w, q[c]));
            }
        }
        let len2 = _mm256_add_ps(
            _mm256_add_ps(
                _mm256_add_ps(_mm256_mul_ps(b[0], b[0]), _mm256_mul_ps(b[1], b[1])),
                _mm256_mul_ps(b[2], b[2]),
            ),
            _mm256_mul_ps(b[3], b[3]),
        );
        let inv = _mm256_div_ps(one, _mm256_sqrt_ps(len2));
        let [w0, x0, y0, z0, we, xe, ye, ze] = b.map(|x| _mm256_mul_ps(x, inv));
        let mul = |a, b| _mm256_mul_ps(a, b);
        let add = |a, b| _mm256_add_ps(a, b);
        let sub = |a, b| _mm256_sub_ps(a, b);
        // t = v0 × p + w0 p
        let tx = add(sub(mul(y0, pz), mul(z0, py)), mul(w0, px));
        let ty = add(sub(mul(z0, px), mul(x0, pz)), mul(w0, py));
        let tz = add(sub(mul(x0, py), mul(y0, px)), mul(w0, pz));
        let qx = add(
            add(px, mul(two, sub(mul(y0, tz), mul(z0, ty)))),
            mul(
                two,
                sub(add(sub(mul(w0, xe), mul(we, x0)), mul(y0, ze)), mul(z0, ye)),
            ),
        );
        let qy = add(
            add(py, mul(two, sub(mul(z0, tx), mul(x0, tz)))),
            mul(
                two,
                sub(add(sub(mul(w0, ye), mul(we, y0)), mul(z0, xe)), mul(x0, ze)),
            ),
        );
        let qz = add(
            add(pz, mul(two, sub(mul(x0, ty), mul(y0, tx)))),
            mul(
                two,
                sub(add(sub(mul(w0, ze), mul(we, z0)), mul(x0, ye)), mul(y0, xe)),
            ),
        );
        let sx = add(sub(mul(y0, nz), mul(z0, ny)), mul(w0, nx));
        let sy = add(sub(mul(z0, nx), mul(x0, nz)), mul(w0, ny));
        let sz = add(sub(mul(x0, ny), mul(y0, nx)), mul(w0, nz));
        let mx = add(nx, mul(two, sub(mul(y0, sz), mul(z0, sy))));
        let my = add(ny, mul(two, sub(mul(z0, sx), mul(x0, sz))));
        let mz = add(nz, mul(two, sub(mul(x0, sy), mul(y0, sx))));
        store(o, i, [qx, qy, qz, mx, my, mz]);
    }
    blocks * 8
}

/// LBS for the first `v.len() / 8 * 8` vertices, in the order of operations of
/// [`super::lbs_vertex`]; returns how many were done.
///
/// # Safety
/// As for [`dqs`], with `m` the joints' 3×4 matrices.
#[target_feature(enable = "avx2,fma")]
pub unsafe fn lbs(v: &[Vertex<4>], m: &[[f32; 12]], o: &mut [Out]) -> usize {
    let mb = m.as_ptr() as *const f32;
    let zero = _mm256_setzero_ps();
    let twelve = _mm256_set1_epi32(12);
    let blocks = v.len() / 8;
    for blk in 0..blocks {
        let i = blk * 8;
        let Block {
            p: [x, y, z],
            n: [nx, ny, nz],
            j: js,
            w: ws,
        } = load(v, i);
        let mut a = [zero; 12];
        for k in 0..4 {
            let base = _mm256_mullo_epi32(js[k], twelve);
            for (c, ac) in a.iter_mut().enumerate() {
                let g = _mm256_i32gather_ps::<4>(
                    mb,
                    _mm256_add_epi32(base, _mm256_set1_epi32(c as i32)),
                );
                *ac = _mm256_add_ps(*ac, _mm256_mul_ps(ws[k], g));
            }
        }
        let mul = |p, q| _mm256_mul_ps(p, q);
        let add = |p, q| _mm256_add_ps(p, q);
        let sub = |p, q| _mm256_sub_ps(p, q);
        let px = add(add(add(mul(a[0], x), mul(a[1], y)), mul(a[2], z)), a[3]);
        let py = add(add(add(mul(a[4], x), mul(a[5], y)), mul(a[6], z)), a[7]);
        let pz = add(add(add(mul(a[8], x), mul(a[9], y)), mul(a[10], z)), a[11]);
        let c00 = sub(mul(a[5], a[10]), mul(a[6], a[9]));
        let c01 = sub(mul(a[6], a[8]), mul(a[4], a[10]));
        let c02 = sub(mul(a[4], a[9]), mul(a[5], a[8]));
        let c10 = sub(mul(a[2], a[9]), mul(a[1], a[10]));
        let c11 = sub(mul(a[0], a[10]), mul(a[2], a[8]));
        let c12 = sub(mul(a[1], a[8]), mul(a[0], a[9]));
        let c20 = sub(mul(a[1], a[6]), mul(a[2], a[5]));
        let c21 = sub(mul(a[2], a[4]), mul(a[0], a[6]));
        let c22 = sub(mul(a[0], a[5]), mul(a[1], a[4]));
        let mx = add(add(mul(c00, nx), mul(c01, ny)), mul(c02, nz));
        let my = add(add(mul(c10, nx), mul(c11, ny)), mul(c12, nz));
        let mz = add(add(mul(c20, nx), mul(c21, ny)), mul(c22, nz));
        let l = _mm256_sqrt_ps(add(add(mul(mx, mx), mul(my, my)), mul(mz, mz)));
        let ok = _mm256_cmp_ps::<_CMP_GT_OQ>(l, zero);
        let mx = _mm256_blendv_ps(nx, _mm256_div_ps(mx, l), ok);
        let my = _mm256_blendv_ps(ny, _mm256_div_ps(my, l), ok);
        let mz = _mm256_blendv_ps(nz, _mm256_div_ps(mz, l), ok);
        store(o, i, [px, py, pz, mx, my, mz]);
    }
    blocks * 8
}
