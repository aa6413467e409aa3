//! The benchmarks' glam and nalgebra baselines (`benches/peers`) are right before they are
//! fast: on a mesh of one influence per vertex every skinning method is the joint's own
//! transform, so each baseline — and our fast LBS and DQS beside them — must give the
//! f64 transform of every vertex to f32 accuracy. Under a non-uniformly scaled joint the
//! cofactor normals (glam cofactor, nalgebra's inverse transpose) stay exact and normals by
//! the blended matrix do not, which is why the benchmarks time both.

use chasles_skin::peers;

use chasles::{Mat4, Vec3};
use chasles_skin::fast::{dqs, dual_quats8, lbs, matrices12, FastRig, Out, Vertex};
use chasles_skin::{synthetic, JointTransforms};

/// `base`'s vertices with all their weight on their first joint.
fn single_influence(base: &FastRig<4>) -> FastRig<4> {
    let v: Vec<Vertex<4>> = base
        .vertices()
        .iter()
        .map(|v| Vertex {
            w: [1.0, 0.0, 0.0, 0.0],
            ..*v
        })
        .collect();
    FastRig::from_vertices(v, base.centres().to_vec()).unwrap()
}

/// Each vertex moved by its joint's matrix in f64: the point by the matrix, the normal by
/// the inverse transpose of its 3×3 block, normalized.
fn reference(rig: &FastRig<4>, jt: &JointTransforms) -> Vec<[f64; 6]> {
    rig.vertices()
        .iter()
        .map(|v| {
            let m = Mat4::<f64>::from_row_major(
                jt.matrices[usize::from(v.j[0])]
                    .to_row_major()
                    .map(f64::from),
            );
            let p = m.transform_point(Vec3::from_array(v.p.map(f64::from)));
            let n = m
                .linear_part()
                .inverse()
                .unwrap()
                .transpose()
                .mul_vec(Vec3::from_array(v.n.map(f64::from)))
                .normalize()
                .unwrap();
            [p.x, p.y, p.z, n.x, n.y, n.z]
        })
        .collect()
}

/// The largest difference between `got` and `want`; NaN if any output is NaN (an output
/// left unwritten is: the outputs start as NaN).
fn worst(got: &[Out], want: &[[f64; 6]]) -> f64 {
    got.iter()
        .zip(want)
        .flat_map(|(g, w)| (0..6).map(move |k| (f64::from(g[k]) - w[k]).abs()))
        .fold(0.0, |m: f64, e| {
            if e.is_nan() || m.is_nan() {
                f64::NAN
            } else {
                m.max(e)
            }
        })
}

#[test]
fn every_baseline_matches_an_f64_reference_on_a_single_influence_mesh() {
    let rig = single_influence(&synthetic::rig(3000, 54, 11));
    let jt = synthetic::joints(54, 11);
    let want = reference(&rig, &jt);
    let v = rig.vertices();
    let mut out = vec![[0f32; 6]; v.len()];
    let pj = peers::Joints::of(&jt);
    let mut check = |name: &str, want: &[[f64; 6]], run: &mut dyn FnMut(&mut [Out])| {
        out.iter_mut().for_each(|o| *o = [f32::NAN; 6]);
        run(&mut out);
        let e = worst(&out, want);
        assert!(e < 4e-6, "{name}: off the f64 reference by {e:e}");
    };
    for (name, f) in peers::BASELINES {
        check(name, &want, &mut |o| f(v, &pj, o));
    }
    let (m12, d8) = (matrices12(&jt), dual_quats8(&jt));
    check("chasles lbs", &want, &mut |o| {
        lbs(&rig, &m12, o, false).unwrap()
    });
    check("chasles dqs", &want, &mut |o| {
        dqs(&rig, &d8, o, false).unwrap()
    });

    // A non-uniform scale on every joint: cofactor normals stay exact, normals by M not.
    let mut scaled = jt.clone();
    for m in &mut scaled.matrices {
        for row in &mut m.m[..3] {
            for (x, s) in row[..3].iter_mut().zip([2.0, 0.5, 1.0]) {
                *x *= s;
            }
        }
    }
    let want = reference(&rig, &scaled);
    let scaled_joints = peers::Joints::of(&scaled);
    let (gj, nm) = (&scaled_joints.glam, &scaled_joints.nalgebra);
    check("glam lbs cofactor, scaled", &want, &mut |o| {
        peers::glam_lbs_cofactor(v, gj, o)
    });
    check("nalgebra lbs, scaled", &want, &mut |o| {
        peers::nalgebra_lbs(v, nm, o)
    });
    let m12 = matrices12(&scaled);
    check("chasles lbs, scaled", &want, &mut |o| {
        lbs(&rig, &m12, o, false).unwrap()
    });
    let mut by_m = vec![[0f32; 6]; v.len()];
    peers::glam_lbs_by_m(v, gj, &mut by_m);
    assert!(
        worst(&by_m, &want) > 0.1,
        "normals by M are wrong under non-uniform scale"
    );
}

/// On four influences and joints turned uniformly (half the antipodality signs flip), the
/// DQS baselines blend as our DQS does: each sign fix is tested, not only the one-joint
/// case (a swapped `copysign` would pass that one).
#[test]
fn the_dqs_baselines_fix_the_signs_as_ours_does() {
    let rig = synthetic::rig(3000, 54, 11);
    let jt = synthetic::uniform_joints(54, 11);
    let v = rig.vertices();
    let mut want = vec![[0f32; 6]; v.len()];
    dqs(&rig, &dual_quats8(&jt), &mut want, false).unwrap();
    let want: Vec<[f64; 6]> = want.iter().map(|o| o.map(f64::from)).collect();
    let pj = peers::Joints::of(&jt);
    let flipped = v
        .iter()
        .filter(|x| {
            let r = |k: usize| jt.dual_quats[usize::from(x.j[k])].real;
            (1..4).any(|k| r(0).dot(r(k)) < 0.0)
        })
        .count();
    assert!(
        flipped > v.len() / 2,
        "{flipped} vertices with a flipped sign"
    );
    let mut out = vec![[f32::NAN; 6]; v.len()];
    peers::glam_dqs(v, &pj.glam_dq, &mut out);
    assert!(
        worst(&out, &want) < 2e-5,
        "glam dqs: {:e}",
        worst(&out, &want)
    );
    out.iter_mut().for_each(|o| *o = [f32::NAN; 6]);
    peers::nalgebra_dqs(v, &pj.nalgebra_dq, &mut out);
    assert!(
        worst(&out, &want) < 2e-5,
        "nalgebra dqs: {:e}",
        worst(&out, &want)
    );
}

/// A rig of `vertices` vertices on a line, each with `influences` equal weights on joints
/// `0..influences` (unparented, at the origin), in its rest pose.
fn spread_rig(vertices: usize, influences: usize) -> (chasles_skin::Rig, JointTransforms) {
    use chasles_skin::{Influences, Mesh, Node, Pose, Rig, Trs};
    let joints = influences.max(1);
    let mesh = Mesh {
        positions: (0..vertices)
            .map(|i| Vec3::new(i as f32, 0.0, 0.0))
            .collect(),
        normals: vec![Vec3::new(0.0, 0.0, 1.0); vertices],
        triangles: vec![],
    };
    let nodes = (0..joints)
        .map(|i| Node {
            name: format!("j{i}"),
            parent: None,
            rest: Trs::default(),
        })
        .collect();
    let list: Vec<(usize, f32)> = (0..influences).map(|j| (j, 1.0)).collect();
    let rig = Rig::new(
        format!("spread{influences}"),
        mesh,
        nodes,
        (0..joints).collect(),
        vec![Mat4::identity(); joints],
        Influences::from_lists(&vec![list; vertices], joints).unwrap(),
        vec![],
    )
    .unwrap();
    let jt = chasles_skin::joint_transforms(&rig, &Pose::rest(&rig)).unwrap();
    (rig, jt)
}

/// `measure_rig` on rigs of one's own: with four influences every method, DIB with its
/// grouping turned off, the five baselines, the copy of 72 bytes a vertex and the
/// traffic bound; with five to eight (the 8-slot layout) every method, ungrouped DIB, the
/// copy of the 96 bytes such a vertex moves and the traffic bound, no baseline (they are
/// written for four); each sample repeated to
/// `min_vertices`. A rig of more than eight influences, or of no vertex, is an error naming
/// it.
#[test]
fn measure_rig_times_up_to_eight_influences_and_names_what_it_cannot() {
    use chasles_skin::SkinError;
    for (influences, rows, copy) in [
        (4, 14, "memcpy, 72 B a vertex"),
        (5, 9, "memcpy, 96 B a vertex"),
        (8, 9, "memcpy, 96 B a vertex"),
    ] {
        let (rig, jt) = spread_rig(37, influences);
        let t = peers::measure_rig(&rig, &jt, 1, 1, 1000).unwrap();
        assert_eq!((t.vertices, t.repeats, t.rows.len()), (37, 28, rows));
        assert_eq!(t.mesh, format!("spread{influences}"));
        assert!(t.rows.iter().any(|r| r.name == copy), "{:?}", t.rows);
        let ungrouped = t.rows.iter().find(|r| r.name == peers::UNGROUPED_DIB);
        assert_eq!(
            ungrouped.map(|r| r.role),
            Some(peers::Role::Ungrouped(chasles_skin::Method::Dib))
        );
        // Each bound's share of itself is 1, and (one round) the traffic's share of the copy
        // is the inverse of the copy's share of the traffic: each column over its own bound.
        let row = |name: &str| t.rows.iter().find(|r| r.name == name).unwrap();
        let (c, tr) = (row(copy), row(peers::TRAFFIC));
        assert_eq!((c.share.median, tr.traffic_share.median), (1.0, 1.0));
        let product = tr.share.median * c.traffic_share.median;
        assert!((product - 1.0).abs() < 1e-12, "{product}: {:?}", t.rows);
        assert!(t.rows.iter().all(|r| r.rate.median > 0.0), "{:?}", t.rows);
    }
    assert_eq!(peers::repeats(370, 100_000), 271);
    assert_eq!(peers::repeats(200_000, 100_000), 1);
    let (rig, jt) = spread_rig(5, 9);
    assert!(matches!(
        peers::measure_rig(&rig, &jt, 1, 1, 1000),
        Err(SkinError::TooManyInfluences {
            most: 9,
            layout: 8,
            ..
        })
    ));
    let (rig, jt) = spread_rig(0, 2);
    let e = peers::measure_rig(&rig, &jt, 1, 1, 1000).unwrap_err();
    assert_eq!(e.to_string(), "the rig spread2 has no vertices to time");
}
