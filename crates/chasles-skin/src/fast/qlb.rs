//! The fast paths for the decomposed blends about a centre (Kavan et al. 2006, §2.2 and §6):
//! decomposed QLB about the vertex's weighted joint origins (Hejl 2004) and spherical blend
//! skinning about its cluster's rotation centre (Kavan & Žára 2005), the centres solved once
//! per pose ([`crate::rotation_centre::Clusters::centres`]).
//!
//! Each joint is one [`Row`] of 24 floats made once per pose: its rotation quaternion, its
//! rigid transform as a 3×4 matrix `[R | t]` (of the dual quaternion) and its bind origin.
//! A vertex about a centre c blends its rows linearly — the quaternions with the
//! antipodality signs against the pivot (QLB), the matrices and origins with the plain
//! weights — and moves by
//!
//! ```text
//! p' = Σ wₖ (Rₖ c + tₖ) + r̂ (p − c),    n' = r̂ n,    r̂ = r / ‖r‖,  r = Σ ±wₖ qₖ
//! ```
//!
//! which is [`chasles::blend::qlb::qlb`]'s recomposition (the centre's images blended, the
//! rest rotated by the QLB rotation) written out: `Σ wₖ (Rₖ c + tₖ)` is the blended matrix
//! applied to c, and the rotation by r̂ takes no square root (every term is quadratic in r:
//! one factor 2/‖r‖², as in DQS). QLB's c is the blended origins; SBS's is its cluster's.
//! Eight vertices at a time with AVX2 and FMA where the processor has them (4 or 8
//! influences; `avx2::qlb`), the scalar kernel below elsewhere; rayon over chunks. Agrees with the
//! reference path to 1e-5 (a test checks every model and clip).

use super::{
    check, for_chunks, pose_table, rotate_scaled, run, Antipodes, FastRig, Kernel, Out, Output,
    Vertex,
};
use crate::error::{same_count, Result, FAST_RIG};
use crate::rotation_centre::Clusters;
use chasles::DualQuat;

/// A joint for QLB and SBS: `[w, x, y, z]` of its rotation, the rows of `[R | t]` (12),
/// its bind origin (3), then 5 zeros — three 8-float registers.
pub type Row = [f32; 24];

/// The rows of joint transforms `d` with bind origins `centres`.
pub(super) fn rows(d: &[DualQuat<f32>], centres: &[chasles::Vec3<f32>]) -> Vec<Row> {
    d.iter().zip(centres).map(|(d, c)| row(d, *c)).collect()
}

/// One joint's row: transform `d`, bind origin `c`.
pub(super) fn row(d: &DualQuat<f32>, c: chasles::Vec3<f32>) -> Row {
    let m = d.to_matrix4();
    let mut r = [0f32; 24];
    r[..4].copy_from_slice(&[d.real.w, d.real.x, d.real.y, d.real.z]);
    for i in 0..12 {
        r[4 + i] = m.m[i / 4][i % 4];
    }
    r[16..19].copy_from_slice(&c.to_array());
    r
}

/// A vertex's blended row: `Σ ±wₖ qₖ` (signs against the pivot, the heaviest influence),
/// then `Σ wₖ [Rₖ | tₖ]` and `Σ wₖ cₖ`.
#[inline(always)]
pub(super) fn blend<const K: usize>(v: &Vertex<K>, rows: &[Row]) -> [f32; 19] {
    let pivot = &rows[usize::from(v.j[0])];
    let mut b = [0f32; 19];
    for k in 0..K {
        let r = &rows[usize::from(v.j[k])];
        let w = v.w[k];
        let sw = if super::real_dot(r, pivot) < 0.0 {
            -w
        } else {
            w
        };
        for i in 0..4 {
            b[i] += sw * r[i];
        }
        for i in 4..19 {
            b[i] += w * r[i];
        }
    }
    b
}

/// The vertex moved by a blended row about the centre `c` (see the module's formula).
#[inline(always)]
pub(super) fn about<const K: usize>(v: &Vertex<K>, b: &[f32; 19], c: [f32; 3]) -> Out {
    let [w0, x0, y0, z0] = [b[0], b[1], b[2], b[3]];
    let s = 2.0 / super::real_dot(b, b);
    // y = Σ wₖ (Rₖ c + tₖ): the blended matrix applied to c.
    let y: [f32; 3] = core::array::from_fn(|i| {
        b[4 + 4 * i] * c[0] + b[5 + 4 * i] * c[1] + b[6 + 4 * i] * c[2] + b[7 + 4 * i]
    });
    // x rotated by the unit r̂ = r / ‖r‖.
    let rotate = |x| rotate_scaled([w0, x0, y0, z0], s, x);
    let d = rotate([v.p[0] - c[0], v.p[1] - c[1], v.p[2] - c[2]]);
    let n = rotate(v.n);
    [y[0] + d[0], y[1] + d[1], y[2] + d[2], n[0], n[1], n[2]]
}

/// Decomposed QLB; a joint is a [`Row`].
pub(super) struct QlbKernel;
impl<const K: usize> Kernel<K> for QlbKernel {
    type Joint = Row;
    type Table = Antipodes;
    fn table(joints: &[Row], vertices: usize) -> Antipodes {
        Antipodes::rows(joints, vertices)
    }
    #[cfg(target_arch = "x86_64")]
    const AVX2: Option<super::SimdKernel<K, Row, Antipodes>> = Some(super::avx2::qlb::qlb::<K>);
    #[inline(always)]
    fn vertex(v: &Vertex<K>, joints: &[Row]) -> Out {
        let b = blend(v, joints);
        about(v, &b, [b[16], b[17], b[18]])
    }
}

/// Decomposed QLB skinning (Hejl 2004) into `out` with the joints' unit dual quaternions,
/// each vertex rotated about the weighted bind origins of its joints ([`FastRig::centres`]);
/// on all threads when `parallel`.
pub fn qlb<const K: usize>(
    rig: &FastRig<K>,
    d: &[DualQuat<f32>],
    out: &mut [Out],
    parallel: bool,
) -> Result<()> {
    check(rig, d.len(), out.len())?;
    run::<K, QlbKernel>(rig, &rows(d, rig.centres()), out.into(), parallel)
}

/// Spherical blend skinning into `out` with the joints' unit dual quaternions: the rotation
/// centre of each of `clusters` (made once for the rig with [`clusters`]) is solved for this
/// pose, and each vertex is blended by QLB about its cluster's; on all threads when
/// `parallel`. An error where `clusters` are not this rig's (another vertex count, or a
/// joint past the rig's).
pub fn sbs<const K: usize>(
    rig: &FastRig<K>,
    clusters: &Clusters,
    d: &[DualQuat<f32>],
    out: &mut [Out],
    parallel: bool,
) -> Result<()> {
    check(rig, d.len(), out.len())?;
    // Before the solve, which indexes the joints by the clusters'.
    clusters_fit(rig, clusters, d.len())?;
    let centres = padded_centres(clusters, d, rig.centres(), parallel);
    let rows = rows(d, rig.centres());
    let (_, table) = pose_table::<K, QlbKernel>(&rows, rig.vertices().len());
    sbs_into(rig, clusters, &rows, &table, &centres, out.into(), parallel)
}

/// SBS into `out` with the joints' rows and each of `clusters`' centre for the pose (as
/// 4 floats, the centre first); on all threads when `parallel`. Every size is checked
/// here: the SIMD kernel indexes `centres` by cluster.
pub(super) fn sbs_into<const K: usize>(
    rig: &FastRig<K>,
    clusters: &Clusters,
    rows: &[Row],
    table: &Antipodes,
    centres: &[[f32; 4]],
    out: Output<'_>,
    parallel: bool,
) -> Result<()> {
    check(rig, rows.len(), out.vertices()?)?;
    clusters_fit(rig, clusters, rows.len())?;
    same_count(FAST_RIG, "rotation centres", clusters.len(), centres.len())?;
    let simd = super::simd(K);
    let cluster = clusters.of_vertex();
    let big = rig.vertices().len() >= super::STREAM_VERTICES;
    for_chunks(out, rig.vertices(), parallel, |first, mut o, v| {
        let cl = &cluster[first..first + v.len()];
        #[cfg(target_arch = "x86_64")]
        if simd && v.len() >= 8 {
            let (lead, streams) = super::simd_start(&o, big);
            super::cover(v.len(), lead, streams, |from, to, s| {
                // SAFETY: `simd` holds only for K = 4 or 8 on a processor with AVX2 and
                // FMA; the joint indices were checked when the rig was built and `check`
                // matched `rows` to the joint count; every cluster index is below
                // `clusters.len()`, which is `centres.len()` (checked above); `table` was
                // made from `rows`; `o` is as long as `v` and `cl`; `simd_start` streams only
                // where `o` is packed and `o[lead]` 32-byte aligned.
                unsafe {
                    let (v, cl, o) = (&v[from..to], &cl[from..to], o.range(from, to));
                    super::avx2::qlb::about::<K, true>(v, rows, table, cl, centres, o, s)
                }
            });
            return;
        }
        let _ = (simd, big);
        for (i, (v, c)) in v.iter().zip(cl).enumerate() {
            let c = &centres[*c as usize];
            o.put(i, about(v, &blend(v, rows), [c[0], c[1], c[2]]));
        }
    });
    Ok(())
}

/// Whether `clusters` are `rig`'s with `joints` joint transforms: one cluster index a
/// vertex and no joint past the transforms (an error naming which, else).
fn clusters_fit<const K: usize>(
    rig: &FastRig<K>,
    clusters: &Clusters,
    joints: usize,
) -> Result<()> {
    let (n, of_vertex) = (rig.vertices().len(), clusters.of_vertex().len());
    same_count(FAST_RIG, "vertices in the clusters", n, of_vertex)?;
    if clusters.joint_count() > joints {
        return Err(crate::SkinError::OutOfRange {
            rig: FAST_RIG.into(),
            what: "joint of the clusters".into(),
            index: clusters.joint_count() - 1,
            count: joints,
        });
    }
    Ok(())
}

/// The centres of `clusters` for joints `d` with bind origins `bind`, as the kernels read
/// them: four floats, the centre first.
pub(super) fn padded_centres(
    clusters: &Clusters,
    d: &[DualQuat<f32>],
    bind: &[chasles::Vec3<f32>],
    parallel: bool,
) -> Vec<[f32; 4]> {
    let mut centres = Vec::new();
    clusters.centres_vec(d, bind, parallel, &mut centres);
    centres
}

/// The SBS clusters of a fast rig: its vertices grouped by the joints of positive weight.
pub fn clusters<const K: usize>(rig: &FastRig<K>) -> Clusters {
    let v = rig.vertices();
    Clusters::new(v.len(), |i| {
        (0..K)
            .filter(|k| v[i].w[*k] > 0.0)
            .map(|k| v[i].j[k])
            .collect::<Vec<_>>()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic;

    /// QLB rows of random joints, and the same with every odd joint's quaternion negated
    /// (the same rotations: antipodal pairs everywhere).
    fn flipped<const K: usize>(rig: &FastRig<K>) -> (Vec<Row>, Vec<Row>) {
        let r = rows(
            &synthetic::joints(rig.joints(), 5).dual_quats,
            rig.centres(),
        );
        let mut f = r.clone();
        for row in f.iter_mut().skip(1).step_by(2) {
            row[..4].iter_mut().for_each(|x| *x = -*x);
        }
        (r, f)
    }

    /// Joints with antipodal pairs skin as the same joints without, on the scalar kernel and
    /// the SIMD ones, with 4 and 8 influences: QLB's and SBS's SIMD kernels give the same
    /// bits from the table's offsets (antipodal pairs), from its plain copies (none) and from
    /// the dot products (`both_ways`), and the scalar kernel's numbers to rounding.
    #[test]
    fn negated_quaternions_skin_the_same_on_every_kernel() {
        check::<4>(synthetic::rig(1003, 54, 5));
        check::<8>(synthetic::rig_with(1003, 54, 5));
    }

    fn check<const K: usize>(rig: FastRig<K>) {
        let (r, f) = flipped(&rig);
        let cl = clusters(&rig);
        let centres = padded_centres(
            &cl,
            &synthetic::joints(54, 5).dual_quats,
            rig.centres(),
            false,
        );
        let scalar = |rows: &[Row]| -> [Vec<Out>; 2] {
            let v = rig.vertices();
            let sbs = v.iter().zip(cl.of_vertex()).map(|(v, c)| {
                let [x, y, z, _] = centres[*c as usize];
                about(v, &blend(v, rows), [x, y, z])
            });
            [
                v.iter().map(|v| QlbKernel::vertex(v, rows)).collect(),
                sbs.collect(),
            ]
        };
        let close = |a: &[Out], b: &[Out], tol: f32| {
            for (a, b) in a.iter().zip(b) {
                for k in 0..6 {
                    assert!((a[k] - b[k]).abs() < tol, "K = {K}: {a:?} {b:?}");
                }
            }
        };
        let (want, got) = (scalar(&r), scalar(&f));
        close(&want[0], &got[0], 1e-5);
        close(&want[1], &got[1], 1e-5);
        #[cfg(target_arch = "x86_64")]
        if super::super::simd(K) {
            use super::super::antipodes::both_ways;
            use crate::fast::dest::Dest;
            // With antipodal pairs (the table's offsets read) and without (its plain rows).
            for (rows, flips, want) in [(&f, true, &got), (&r, false, &want)] {
                let table = Antipodes::rows(rows, usize::MAX);
                assert_eq!(table.flips, flips);
                // SAFETY (both kernels): AVX2 and FMA are present (`simd`), the synthetic
                // rig's joint indices are below 54 = rows.len(), the table is empty or made
                // from `rows`, every cluster index is below `centres.len()`.
                let qlb = both_ways(table.clone(), |table, out| unsafe {
                    let v = rig.vertices();
                    super::super::avx2::qlb::qlb(v, rows, table, Dest::packed(out), false)
                });
                let sbs = both_ways(table, |table, out| unsafe {
                    let (v, of) = (rig.vertices(), cl.of_vertex());
                    let o = Dest::packed(out);
                    super::super::avx2::qlb::about::<K, true>(
                        v, rows, table, of, &centres, o, false,
                    )
                });
                // The ways to the signs gave the same numbers, bit for bit (`both_ways`), and
                // the SIMD kernels (fused multiply-adds) are the scalar ones to rounding.
                close(&qlb, &want[0][..1000], 4e-6);
                close(&sbs, &want[1][..1000], 4e-6);
            }
        } else {
            eprintln!("no AVX2+FMA here: only the scalar kernel is checked");
        }
    }

    #[test]
    fn one_joint_moves_rigidly_and_the_centre_does_not_matter() {
        // A vertex bound to one joint moves by that joint's transform, whatever the centre.
        let rig = synthetic::rig(8, 54, 9);
        let d = synthetic::joints(54, 9).dual_quats;
        let r = rows(&d, rig.centres());
        for v in rig.vertices() {
            let one = Vertex {
                w: [1.0, 0.0, 0.0, 0.0],
                ..*v
            };
            let b = blend(&one, &r);
            let want = d[usize::from(v.j[0])].transform_point(chasles::Vec3::from_array(v.p));
            for c in [[0.0; 3], [10.0, -3.0, 2.0]] {
                let o = about(&one, &b, c);
                let got = chasles::Vec3::new(o[0], o[1], o[2]);
                assert!((got - want).norm() < 1e-4, "{got:?} vs {want:?}");
            }
        }
    }

    /// `sbs` takes clusters of its own rig only: another rig's (more joints, or other
    /// vertices) get an error naming what does not fit, before any centre is solved.
    #[test]
    fn sbs_refuses_another_rigs_clusters() {
        let small = synthetic::rig(64, 8, 3);
        let d = synthetic::joints(8, 3).dual_quats;
        let mut out = vec![[0f32; 6]; 64];
        sbs(&small, &clusters(&small), &d, &mut out, false).unwrap();
        let more_joints = clusters(&synthetic::rig(64, 54, 3));
        assert!(more_joints.joint_count() > 8);
        let err = sbs(&small, &more_joints, &d, &mut out, false).unwrap_err();
        assert!(matches!(err, crate::SkinError::OutOfRange { .. }), "{err}");
        assert!(err.to_string().contains("joint of the clusters"), "{err}");
        let more_vertices = clusters(&synthetic::rig(65, 8, 3));
        let err = sbs(&small, &more_vertices, &d, &mut out, false).unwrap_err();
        assert!(
            err.to_string().contains("vertices in the clusters"),
            "{err}"
        );
    }
}
