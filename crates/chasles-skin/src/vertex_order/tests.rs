use super::*;
use crate::fast::{skin_pose, FastRig, Out};
use crate::{gltf_load, joint_transforms, skin_joints, Method, Pose};

/// A built-in character.
fn character(m: chasles_models::Model) -> Rig {
    gltf_load::load_slice(m.bytes, m.file).expect("a built-in character loads")
}

/// Vertex v's positive weights (the order's key).
fn kind(rig: &Rig, v: usize) -> usize {
    rig.influences.of(v).filter(|&(_, w)| w > 0.0).count()
}

/// The blocks of `size` that hold a vertex of three influences or more.
fn iterating(rig: &Rig, size: usize) -> usize {
    let n = rig.mesh.positions.len();
    (0..n)
        .step_by(size)
        .filter(|&b| (b..(b + size).min(n)).any(|v| kind(rig, v) >= 3))
        .count()
}

#[test]
fn the_order_sorts_each_window_by_influence_count_and_keeps_the_rest() {
    for m in chasles_models::ALL {
        let rig = character(m);
        let n = rig.mesh.positions.len();
        let order = by_influence_count(&rig).unwrap();
        // A permutation, each vertex in its own window.
        let inv = inverse(&order, n).unwrap();
        assert_eq!(inv.len(), n);
        assert!(order
            .iter()
            .enumerate()
            .all(|(i, &v)| inv[v as usize] as usize == i));
        for (i, &v) in order.iter().enumerate() {
            assert_eq!(
                i / WINDOW,
                v as usize / WINDOW,
                "{}: vertex {v} left its window",
                rig.name
            );
        }
        for (w, window) in order.chunks(WINDOW).enumerate() {
            let kinds: Vec<usize> = window.iter().map(|&v| kind(&rig, v as usize)).collect();
            let sorted = kinds.windows(2).all(|k| {
                if w % 2 == 0 {
                    k[0] <= k[1]
                } else {
                    k[0] >= k[1]
                }
            });
            assert!(sorted, "{}: window {w} is not sorted: {kinds:?}", rig.name);
            // Stable: vertices of one kind keep their order.
            let mut present = kinds.clone();
            present.dedup();
            for k in present {
                let of_kind: Vec<u32> = window
                    .iter()
                    .copied()
                    .filter(|&v| kind(&rig, v as usize) == k)
                    .collect();
                assert!(
                    of_kind.windows(2).all(|p| p[0] < p[1]),
                    "{}: kind {k} reordered",
                    rig.name
                );
            }
        }
    }
}

/// The characters' blocks of sixteen that hold a vertex of three influences or more, in
/// their own order and grouped by [`by_influence_count`] (measured when written; the fast
/// path's grouping, `fast::grouped`, is held to the same counts).
pub(crate) const ITERATING_BLOCKS: [(chasles_models::Model, usize, usize); 3] = [
    (chasles_models::FOX, 26, 5),
    (chasles_models::RIGGED_FIGURE, 22, 13),
    (chasles_models::CESIUM_MAN, 145, 77),
];

#[test]
fn grouped_characters_iterate_in_fewer_blocks() {
    // At most one block a window holds vertices of two influences or fewer and of three or
    // more, so the bound is the latter's own blocks plus one a window.
    for (m, before, after) in ITERATING_BLOCKS {
        let rig = character(m);
        let grouped = rig.reordered(&by_influence_count(&rig).unwrap()).unwrap();
        let n = rig.mesh.positions.len();
        let many = (0..n).filter(|&v| kind(&rig, v) >= 3).count();
        let (a, b) = (iterating(&rig, 16), iterating(&grouped, 16));
        assert_eq!(a, before, "{}", rig.name);
        assert!(
            b <= many.div_ceil(16) + n.div_ceil(WINDOW),
            "{}: {a} → {b}",
            rig.name
        );
        assert_eq!(b, after, "{}: {a} → {b}", rig.name);
    }
}

#[test]
fn a_reordered_rig_skins_each_vertex_to_the_same_bits() {
    let rig = character(chasles_models::CESIUM_MAN);
    let order = by_influence_count(&rig).unwrap();
    let grouped = rig.reordered(&order).unwrap();
    // The same mesh: each vertex, its normal and influences moved, each triangle's corners
    // the same points.
    for (i, &o) in order.iter().enumerate() {
        let o = o as usize;
        assert_eq!(grouped.mesh.positions[i], rig.mesh.positions[o]);
        assert_eq!(grouped.mesh.normals[i], rig.mesh.normals[o]);
        assert!(grouped.influences.of(i).eq(rig.influences.of(o)));
    }
    let corners = |r: &Rig| -> Vec<_> {
        r.mesh
            .triangles
            .iter()
            .map(|t| t.map(|c| r.mesh.positions[c as usize]))
            .collect()
    };
    assert_eq!(corners(&grouped), corners(&rig));
    assert_ne!(
        grouped.mesh.triangles, rig.mesh.triangles,
        "the order moves CesiumMan's vertices"
    );
    let clip = &rig.animations[0];
    let jt = joint_transforms(
        &rig,
        &Pose::animated(&rig, 0, clip.duration() * 0.37).unwrap(),
    )
    .unwrap();
    let (fast, fast_grouped) = (
        FastRig::<4>::new(&rig).unwrap(),
        FastRig::<4>::new(&grouped).unwrap(),
    );
    let n = order.len();
    for m in Method::ALL {
        // The fast path (DIB's SIMD blocks among them) and the reference.
        for parallel in [false, true] {
            let (mut a, mut b) = (vec![[0f32; 6]; n], vec![[0f32; 6]; n]);
            skin_pose(&fast, &jt, m, &mut a, parallel).unwrap();
            skin_pose(&fast_grouped, &jt, m, &mut b, parallel).unwrap();
            let bits = |o: &Out| o.map(f32::to_bits);
            for (i, &o) in order.iter().enumerate() {
                assert_eq!(
                    bits(&b[i]),
                    bits(&a[o as usize]),
                    "{}: vertex {o} → {i}",
                    m.name()
                );
            }
        }
        let (a, b) = (
            skin_joints(&rig, &jt, m).unwrap(),
            skin_joints(&grouped, &jt, m).unwrap(),
        );
        for (i, &o) in order.iter().enumerate() {
            assert_eq!(b.positions[i], a.positions[o as usize], "{}", m.name());
            assert_eq!(b.normals[i], a.normals[o as usize], "{}", m.name());
        }
    }
}

#[test]
fn an_order_that_is_no_permutation_is_refused() {
    let rig = crate::cylinder::twisted_cylinder();
    let n = rig.mesh.positions.len();
    let mut order: Vec<u32> = (0..n as u32).rev().collect();
    assert!(rig.reordered(&order).is_ok());
    let short = &order[..n - 1];
    assert!(
        matches!(rig.reordered(short), Err(SkinError::Count { expected, got, .. }) if expected == n && got == n - 1)
    );
    order[5] = n as u32;
    let e = rig.reordered(&order).unwrap_err();
    assert!(
        matches!(e, SkinError::OutOfRange { index, count, .. } if index == n && count == n),
        "{e}"
    );
    assert_eq!(
        e.to_string(),
        format!("the vertex order: entry 5 names vertex {n} out of range (there are {n})")
    );
    order[5] = order[6];
    let e = rig.reordered(&order).unwrap_err();
    assert!(matches!(e, SkinError::Parameter { .. }), "{e}");
    assert!(e.to_string().contains("at positions 5 and 6"), "{e}");
    // An empty mesh has the empty order.
    let mut empty = rig.clone();
    empty.mesh = Mesh::default();
    empty.influences = Influences {
        start: vec![0],
        ..Influences::default()
    };
    assert_eq!(by_influence_count(&empty).unwrap(), Vec::<u32>::new());
    assert_eq!(empty.reordered(&[]).unwrap().mesh.positions.len(), 0);
    // A rig made inconsistent by hand: an error, not a panic.
    // (with a good order, too).
    let good: Vec<u32> = (0..n as u32).rev().collect();
    let mut broken = rig.clone();
    broken.mesh.triangles.push([0, 1, n as u32 + 7]);
    let e = broken.reordered(&good).unwrap_err();
    assert!(
        matches!(e, SkinError::OutOfRange { .. }) && e.to_string().contains("triangle"),
        "{e}"
    );
    assert!(matches!(
        inverse(&[], u32::MAX as usize + 1),
        Err(SkinError::Parameter { .. })
    ));
    broken = rig.clone();
    broken.influences.start.pop();
    assert!(by_influence_count(&broken).is_err());
}

#[test]
fn a_reordered_rig_is_written_and_read_back_as_an_asset() {
    // The order is made once, when an asset is built: the Fox grouped, written as .glb with
    // its clips and loaded back, is the grouped rig.
    let rig = character(chasles_models::FOX);
    let grouped = rig.reordered(&by_influence_count(&rig).unwrap()).unwrap();
    let bytes = crate::gltf_write::rig_glb(&grouped, &grouped.animations, "grouped").unwrap();
    let back = gltf_load::load_slice(&bytes, "grouped.glb").unwrap();
    assert_eq!(back.mesh.positions, grouped.mesh.positions);
    assert_eq!(back.mesh.normals, grouped.mesh.normals);
    assert_eq!(back.mesh.triangles, grouped.mesh.triangles);
    let n = grouped.mesh.positions.len();
    for v in 0..n {
        assert!(
            back.influences.of(v).eq(grouped.influences.of(v)),
            "vertex {v}"
        );
    }
    // Its blocks stay grouped: the order of the read-back rig is the identity.
    let again = by_influence_count(&back).unwrap();
    assert!(again.iter().enumerate().all(|(i, &v)| v as usize == i));
}
