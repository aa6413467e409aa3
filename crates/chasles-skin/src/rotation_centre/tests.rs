use super::*;
use chasles::Quat;

#[test]
fn clusters_group_equal_joint_sets() {
    let sets: [&[u16]; 5] = [&[3, 1], &[1, 3], &[2], &[1, 3, 3], &[0, 2]];
    let c = Clusters::new(sets.len(), |v| sets[v].iter().copied());
    assert_eq!(c.len(), 3);
    assert_eq!(c.of_vertex(), &[0, 0, 1, 0, 2]);
    assert_eq!(c.joints(0), &[1, 3]);
    assert_eq!(c.joints(2), &[0, 2]);
}

/// Sixteen joints, each turned and moved its own way, and their bind origins.
fn sixteen_joints() -> (Vec<DualQuat<f32>>, Vec<Vec3<f32>>) {
    let d = (0..16)
        .map(|j| {
            let q = Quat::from_axis_angle(Vec3::new(1.0, j as f32, 2.0), 0.3 * j as f32);
            DualQuat::from_rotation_translation(q.unwrap(), Vec3::new(j as f32, 1.0, 0.5))
        })
        .collect();
    let bind = (0..16).map(|j| Vec3::new(0.0, j as f32, 1.0)).collect();
    (d, bind)
}

/// `n` joints, joint j turned by `angle · j` about `axis(j)` and moved by (0.5, j, −1).
fn turned(n: usize, axis: impl Fn(f32) -> Vec3<f32>, angle: f32) -> Vec<DualQuat<f32>> {
    (0..n)
        .map(|j| {
            let j = j as f32;
            let q = Quat::from_axis_angle(axis(j), angle * j).unwrap();
            DualQuat::from_rotation_translation(q, Vec3::new(0.5, j, -1.0))
        })
        .collect()
}

/// Asserts that `got` is the centre of `joints` solved alone, padded with a 0, bit for bit
/// (`what` says where it came from).
fn assert_alone(got: [f32; 4], joints: &[u16], m: &Motions, bind: &[Vec3<f32>], what: &str) {
    let want = pad(rotation_centre(joints, m, bind));
    assert_eq!(
        got.map(f32::to_bits),
        want.map(f32::to_bits),
        "{joints:?} {what}"
    );
}

/// The priors of `sets` side by side, as the lanes take them.
fn priors<const N: usize>(sets: &[&[u16]], bind: &[Vec3<f32>]) -> [[f32; N]; 3] {
    core::array::from_fn(|i| core::array::from_fn(|k| prior(sets[k], bind).get(i)))
}

/// Every motion starts a cache line, wherever the allocator puts the vector, so no
/// 64-byte load of the eight-lane sums straddles two.
#[test]
fn motions_sit_on_whole_cache_lines() {
    let (d, _) = sixteen_joints();
    for _ in 0..4 {
        let m = Motions::new(&d);
        assert_eq!(m.0.len(), 16);
        for x in &m.0 {
            assert_eq!(std::ptr::from_ref(x) as usize % 64, 0);
        }
        assert_eq!(size_of::<Lines>(), size_of::<Motion>(), "no padding");
        assert_eq!(align_of::<Lines>(), 64);
        // Another allocation between poses, so the next vector may start elsewhere.
        std::hint::black_box(vec![0u8; 24]);
    }
}

/// A motion is its dual quaternion's rigid motion in f64, normalized there: R turns a
/// vector as the quaternion does, `RᵀR = I` to f64's rounding (what lets the solve take
/// `Σ RᵀR` as `n I`) even from an f32 dual quaternion off unit length, t is its
/// translation and `Rᵀt` made from them; one that cannot be normalized is NaN (its
/// clusters take their prior).
#[test]
fn motions_are_rigid_to_f64s_rounding() {
    let (mut d, _) = sixteen_joints();
    d[3] = DualQuat::new(d[3].real * 1.001, d[3].dual * 1.001);
    d.push(DualQuat::new(Quat::new(0.0, 0.0, 0.0, 0.0), d[0].dual));
    d.push(DualQuat::new(d[0].real, Quat::new(f32::NAN, 0.0, 0.0, 0.0)));
    let m = Motions::new(&d);
    for (j, d) in d.iter().enumerate().take(16) {
        let x = m.of(j as u16);
        let r = |i: usize, k: usize| x[R + 3 * i + k];
        let unit = d.cast::<f64>().normalize().unwrap();
        let v = Vec3::new(0.3, -1.7, 2.2);
        let turned = unit.real.rotate(v);
        for i in 0..3 {
            let rv: f64 = (0..3).map(|k| r(i, k) * v.get(k)).sum();
            assert!(
                (rv - turned.get(i)).abs() < 1e-14,
                "joint {j}: (R v)[{i}] = {rv}"
            );
            for k in 0..3 {
                let g: f64 = (0..3).map(|l| r(l, i) * r(l, k)).sum();
                let want = if i == k { 1.0 } else { 0.0 };
                assert!((g - want).abs() < 1e-15, "joint {j}: (RᵀR)[{i}][{k}] = {g}");
            }
            let t = unit.translation().get(i);
            assert!((x[T + i] - t).abs() < 1e-12, "joint {j}");
            let u: f64 = (0..3).map(|l| r(l, i) * x[T + l]).sum();
            assert_eq!(x[U + i], u, "joint {j}");
        }
        assert_eq!(x[FIELDS - 1], 0.0);
    }
    assert!(m.of(16).iter().all(|x| x.is_nan()), "a zero real part");
    assert!(m.of(17).iter().all(|x| x.is_nan()), "a NaN");
}

#[test]
fn many_clusters_solve_alike_on_all_threads() {
    // The 560 sets of 3 of 16 joints: over the threshold for threads.
    let (d, bind) = sixteen_joints();
    let sets: Vec<[u16; 3]> = (0..16u16)
        .flat_map(|a| (a + 1..16).flat_map(move |b| (b + 1..16).map(move |c| [a, b, c])))
        .collect();
    let c = Clusters::new(sets.len(), |v| sets[v]);
    assert!(c.len() >= PARALLEL, "{}", c.len());
    assert_eq!(c.centres(&d, &bind, true), c.centres(&d, &bind, false));
}

/// Every subset of one to four of the first twelve joints, and three of five, in a mixed
/// order (sizes side by side): 796 distinct joint sets, more than [`PARALLEL`] (so that the
/// threads take them) and not a multiple of eight (so that the last group is short).
fn mixed_sets() -> Vec<Vec<u16>> {
    let mut sets: Vec<Vec<u16>> = Vec::new();
    for mask in 1u16..1 << 12 {
        if mask.count_ones() <= 4 {
            sets.push((0..12).filter(|j| mask & 1 << j != 0).collect());
        }
    }
    sets.extend([
        vec![0, 1, 2, 3, 4],
        vec![5, 6, 7, 8, 9],
        vec![10, 11, 12, 13, 14],
    ]);
    let n = sets.len();
    // 389 is prime to 796: a permutation.
    (0..n).map(|i| sets[i * 389 % n].clone()).collect()
}

/// Every cluster's centre is its own, solved alone, bit for bit, whatever the count
/// (the eights, fours and last few of `centres_into`'s chunks) and on all threads or
/// one (in the widest lanes here: `fast::set_avx512` is the process's, which tests
/// running beside this one count on; the widths are compared in the test below).
#[test]
fn every_cluster_gets_its_own_centre() {
    let (d, bind) = sixteen_joints();
    let m = Motions::new(&d);
    let sets = mixed_sets();
    assert_eq!((sets.len(), sets.len() % 8), (796, 4));
    for n in (1..=20).chain([sets.len()]) {
        let c = Clusters::new(n, |v| sets[v].iter().copied());
        assert_eq!(c.len(), n, "the sets are distinct");
        for parallel in [false, true] {
            let got = c.centres(&d, &bind, parallel);
            for (i, got) in got.iter().enumerate() {
                let what = format!("n {n} cluster {i} parallel {parallel}");
                assert_alone(pad(*got), c.joints(i), &m, &bind, &what);
            }
        }
    }
}

/// `centres_vec` writes every entry once, whatever the vector held: refilled from a vector
/// of NaN longer than the clusters (its capacity reused, no zeros written first), each
/// entry is its cluster's padded centre (fourth float 0) solved alone, bit for bit, for
/// every count (the eights, fours and last few) and on one thread or all (796 clusters,
/// past the threads' threshold); likewise into a fresh vector of the palette's entry type.
#[test]
fn centres_vec_writes_every_entry() {
    let (d, bind) = sixteen_joints();
    let m = Motions::new(&d);
    let sets = mixed_sets();
    for n in (1..=20).chain([sets.len()]) {
        let c = Clusters::new(n, |v| sets[v].iter().copied());
        for parallel in [false, true] {
            let what = |i: usize, how: &str| format!("n {n} cluster {i} parallel {parallel} {how}");
            let mut stale = vec![[f32::NAN; 4]; c.len() + 9];
            let cap = stale.capacity();
            c.centres_vec(&d, &bind, parallel, &mut stale);
            assert_eq!((stale.len(), stale.capacity()), (n, cap), "n {n}");
            for (i, got) in stale.iter().enumerate() {
                assert_alone(*got, c.joints(i), &m, &bind, &what(i, "stale"));
            }
            let mut fresh: Vec<crate::fast::RotationCentre> = Vec::new();
            c.centres_vec(&d, &bind, parallel, &mut fresh);
            for (i, r) in fresh.iter().enumerate() {
                let got = [r.centre[0], r.centre[1], r.centre[2], r.pad];
                assert_alone(got, c.joints(i), &m, &bind, &what(i, "fresh"));
            }
        }
    }
}

/// Four clusters at once (AVX2 lanes, where the processor has them) give each one's
/// centre bit for bit: clusters of 1 to 4 joints side by side, one
/// with a non-finite joint (the prior), equal rotations (A all rounding: near the prior).
#[test]
fn four_at_once_are_each_alone_bit_for_bit() {
    let mut d = turned(12, |j| Vec3::new(1.0, j, -2.0), 0.37);
    d[11].real.w = f32::NAN;
    d[10] = d[9];
    let bind: Vec<Vec3<f32>> = (0..12).map(|j| Vec3::new(j as f32, 1.0, -0.5)).collect();
    let m = Motions::new(&d);
    let sets: [&[u16]; 8] = [
        &[0, 3, 5, 7],
        &[2],
        &[1, 4, 6],
        &[8, 9],
        &[0, 11],
        &[9, 10],
        &[3, 4, 5, 6],
        &[7],
    ];
    let avx2 = Lanes::allowed(true, false).avx2;
    for g in sets.chunks(4) {
        let mut got = nan_slots();
        four(
            [g[0], g[1], g[2], g[3]],
            &m,
            &priors(g, &bind),
            avx2,
            &mut got,
        );
        // SAFETY: the slots of `nan_slots` hold values.
        let got = unsafe { read_slots(got) };
        for (set, got) in g.iter().zip(got) {
            assert_alone(got, set, &m, &bind, "");
        }
    }
    if !avx2 {
        eprintln!("no AVX2 here: four at once ran one by one");
    }
}

/// Eight clusters at once (AVX-512F's lanes, where the processor has them and they are
/// allowed; nothing elsewhere) give each cluster's centre alone bit for bit: clusters of
/// 1 to 8 joints side by side, with a non-finite joint (the prior) and equal rotations
/// (A all rounding: near the prior) among them, every set in every lane.
#[test]
fn eight_at_once_are_each_alone_bit_for_bit() {
    let mut d = turned(20, |j| Vec3::new(1.0, j, -2.0 + 0.1 * j), 0.29);
    d[19].real.w = f32::INFINITY;
    d[18] = d[17];
    let bind: Vec<Vec3<f32>> = (0..20).map(|j| Vec3::new(j as f32, 1.0, -0.5)).collect();
    let m = Motions::new(&d);
    let sets: [&[u16]; 11] = [
        &[0, 3, 5, 7, 9, 11, 13, 15],
        &[2],
        &[1, 4, 6],
        &[8, 9],
        &[0, 19],
        &[17, 18],
        &[3, 4, 5, 6, 12],
        &[7, 8, 10, 14, 16, 2, 1],
        &[10, 11, 12, 13, 14, 15],
        &[16, 17, 18, 19],
        &[5, 6],
    ];
    // Each width allowed in turn (`Lanes::allowed` keeps those this processor has).
    for widths in [(false, false), (true, false), (true, true)] {
        let lanes = Lanes::allowed(widths.0, widths.1);
        for shift in 0..sets.len() {
            let group: [&[u16]; 8] = core::array::from_fn(|k| sets[(k + shift) % sets.len()]);
            let cl = Clusters::new(8, |v| group[v].iter().copied());
            assert_eq!(cl.len(), 8);
            let mut got: [Slot; 8] = nan_slots();
            let done = eights(&cl, 0, &m, &cl.prior_table(&bind), lanes, &mut got);
            if done == 0 {
                assert!(!lanes.avx512, "eight at once where AVX-512 is allowed");
                continue;
            }
            assert!(lanes.avx512 && done == 8);
            // SAFETY: the slots of `nan_slots` hold values.
            let got = unsafe { read_slots(got) };
            for (c, got) in got.into_iter().enumerate() {
                let what = format!("shift {shift} lanes ({}, {})", lanes.avx2, lanes.avx512);
                assert_alone(got, cl.joints(c), &m, &bind, &what);
            }
        }
    }
    if !Lanes::allowed(true, true).avx512 {
        eprintln!("no AVX-512F here: eight at once did not run (fours do)");
    }
}

#[test]
fn the_centre_is_the_common_fixed_point() {
    // Joints rotating about different axes through the point x (and then all moved by
    // one offset): x is the point they all map to the same place.
    let x = Vec3::new(0.3f32, -1.2, 2.0);
    let q = [
        Quat::from_axis_angle(Vec3::new(1.0, 0.0, 0.0), 0.7).unwrap(),
        Quat::from_axis_angle(Vec3::new(0.0, 1.0, 1.0), -1.1).unwrap(),
        Quat::from_axis_angle(Vec3::new(1.0, -2.0, 0.5), 0.4).unwrap(),
    ];
    let d = q.map(|q| {
        DualQuat::from_rotation_translation(q, x - q.rotate(x) + Vec3::new(0.5, 0.0, 0.1))
    });
    let bind = [
        Vec3::zero(),
        Vec3::new(5.0, 5.0, 5.0),
        Vec3::new(1.0, 0.0, 4.0),
    ];
    // Three joints: x, and only x.
    let r = Clusters::new(1, |_| [0u16, 1, 2]).centres(&d, &bind, false)[0];
    assert!((r - x).norm() < 1e-4, "{r:?}");
    // Two joints agree on the whole line through x along the axis u of their relative
    // rotation; the Tikhonov term picks its point nearest the prior (the mean of the
    // bind origins).
    let two = Clusters::new(1, |_| [0u16, 1]);
    let r = two.centres(&d, &bind, false)[0];
    let u = (q[1].conjugate() * q[0]).vector().normalize().unwrap();
    let prior = Vec3::new(2.5, 2.5, 2.5);
    let want = x + u * (prior - x).dot(u);
    assert!((r - want).norm() < 1e-3, "{r:?} vs {want:?}");
    // Equal rotations (rank 0): A is f64's rounding alone, so the centre lands near the
    // prior (module docs; the blend does not depend on it).
    let r = two.centres(&[d[0], d[0], d[0]], &bind, false)[0];
    assert!((r - prior).norm() < 1e-4, "{r:?}");
    // One joint: its prior, its own origin, exactly (A made 0, b 0).
    let one = Clusters::new(1, |_| [2u16]);
    let r = one.centres(&d, &bind, false)[0];
    assert_eq!(
        r.to_array().map(f32::to_bits),
        bind[2].to_array().map(f32::to_bits)
    );
}

/// The priors made on a clustering's first solve serve only the bind origins they were made
/// for: solved with other origins (NaN among them), then the first again, a clustering
/// gives what a new one does, bit for bit (a NaN centre as a NaN), in every width and the
/// last clusters of an eight; and the clusters name the joints they need.
#[test]
fn priors_follow_the_bind_origins() {
    let (d, bind) = sixteen_joints();
    let sets: Vec<Vec<u16>> = (0..21u16)
        .map(|i| (0..1 + i % 4).map(|k| (i * 5 + k * 3) % 16).collect())
        .collect();
    let make = || Clusters::new(sets.len(), |v| sets[v].iter().copied());
    let mut other = bind.clone();
    other
        .iter_mut()
        .for_each(|o| *o = *o * 2.0 + Vec3::new(1.0, -3.0, 0.5));
    let mut nan = bind.clone();
    nan[5].y = f32::NAN;
    let bits = |c: &[Vec3<f32>]| -> Vec<[u32; 3]> {
        c.iter()
            .map(|v| {
                v.to_array()
                    .map(|x| if x.is_nan() { u32::MAX } else { x.to_bits() })
            })
            .collect()
    };
    let c = make();
    assert_eq!(c.joint_count(), 16);
    for b in [&bind, &other, &nan, &nan, &bind] {
        for parallel in [false, true] {
            let got = c.centres(&d, b, parallel);
            assert_eq!(bits(&got), bits(&make().centres(&d, b, parallel)));
            assert_eq!(got.iter().any(|x| !x.is_finite()), b[5].y.is_nan());
        }
    }
    assert_eq!(Clusters::default().len(), 0);
    assert_eq!(Clusters::default().joint_count(), 0);
    assert!(Clusters::default().centres(&d, &bind, false).is_empty());
}

/// The normal equations summed over the pairs, as defined: `Σ_{a<b} DᵀD` and `−Σ DᵀE`
/// with `D = R_a − R_b`, `E = t_a − t_b` (before the Tikhonov term), of the joints'
/// motions in f64 (their dual quaternions normalized in f64, as [`Motions`] takes them).
fn pairwise(joints: &[u16], d: &[DualQuat<f32>]) -> ([[f64; 3]; 3], [f64; 3]) {
    let m: Vec<Mat4<f64>> = d
        .iter()
        .map(|d| d.cast::<f64>().normalize().unwrap().to_matrix4())
        .collect();
    let (mut a, mut b) = ([[0f64; 3]; 3], [0f64; 3]);
    for (i, ja) in joints.iter().enumerate() {
        for jb in &joints[i + 1..] {
            let (ma, mb) = (&m[usize::from(*ja)], &m[usize::from(*jb)]);
            let dd = |r: usize, c: usize| ma.m[r][c] - mb.m[r][c];
            for (r, (ar, br)) in a.iter_mut().zip(&mut b).enumerate() {
                for (c, arc) in ar.iter_mut().enumerate() {
                    *arc += (0..3).map(|k| dd(k, r) * dd(k, c)).sum::<f64>();
                }
                *br -= (0..3).map(|k| dd(k, r) * dd(k, 3)).sum::<f64>();
            }
        }
    }
    (a, b)
}

proptest::proptest! {
    /// The O(n) sums give the pairs' normal equations, and so their solution: the
    /// centre's residual gradient `A r − b` (with the Tikhonov term) vanishes, for 1 to 8
    /// joints of any rotations, some nearly equal.
    #[test]
    fn the_centre_solves_the_pairwise_normal_equations(
        n in 1usize..=8,
        seed in proptest::prelude::any::<u64>(),
        spread in proptest::prop_oneof![proptest::prelude::Just(1e-3f32), 0.01f32..3.0],
    ) {
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        let mut v = || Vec3::new(rng.random_range(-1.0f32..1.0), rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
        let base = Quat::from_axis_angle(v() + Vec3::new(0.0, 0.0, 2.0), 0.8).unwrap();
        let d: Vec<DualQuat<f32>> = (0..n)
            .map(|_| {
                let axis = v() + Vec3::new(2.0, 0.0, 0.0);
                let q = base * Quat::from_axis_angle(axis, spread * v().x).unwrap();
                DualQuat::from_rotation_translation(q, v() * 3.0)
            })
            .collect();
        let joints: Vec<u16> = (0..n as u16).collect();
        let bind: Vec<Vec3<f32>> = (0..n).map(|_| v()).collect();
        let r = rotation_centre(&joints, &Motions::new(&d), &bind).cast::<f64>().to_array();
        let (a, b) = pairwise(&joints, &d);
        let lambda = 1e-6 * (a[0][0] + a[1][1] + a[2][2]) + 1e-12;
        let mean = bind.iter().fold(Vec3::zero(), |s, o| s + o.cast::<f64>()) * (1.0 / n as f64);
        let p = mean.to_array();
        let scale = a.iter().flatten().fold(lambda, |m, x| m.max(x.abs()));
        for i in 0..3 {
            let g: f64 = (0..3).map(|k| a[i][k] * r[k]).sum::<f64>() + lambda * (r[i] - p[i]) - b[i];
            // f32 centre, f32 inputs: the gradient is small against A's size times |r|;
            // and the O(n) sums `n² I − SᵀS`, `n U − SᵀT` cancel terms of the size of n²
            // and U (n |t|, |t| < 6) to A's and b's in f64: for joints
            // 1e-3 rad apart (A ~ 1e-6) that rounding is what is left.
            let far = 1.0 + r.iter().fold(0f64, |m, x| m.max(x.abs()));
            let size = scale * far;
            let sums = 16.0 * n as f64 * f64::EPSILON * far * 7.0;
            proptest::prop_assert!(g.abs() <= 1e-5 * size + sums, "row {i}: {g} vs {size}, {sums}");
        }
    }
}

#[test]
fn joint_centres_invert_the_bind_matrices() {
    let origin = Vec3::new(1.0f32, 2.0, -3.0);
    let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 0.4).unwrap();
    let bind = DualQuat::from_rotation_translation(q, origin).to_matrix4();
    let ib = chasles::blend::log::inverse_rigid(&bind);
    let c = joint_centres(&[ib, Mat4::from_rows([[0.0; 4]; 4])]);
    assert!((c[0] - origin).norm() < 1e-5, "{:?}", c[0]);
    assert_eq!(c[1], Vec3::zero(), "a singular matrix gives the origin");
}
