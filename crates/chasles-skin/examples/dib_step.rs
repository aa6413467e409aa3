//! How many updates DIB needs with the paper's step and with the SIMD kernel's second-order
//! step (`fast/lane/dib/second_order.rs`), in f64, one blend at a time, and how far each
//! ends from the exact blend: the figures quoted in that module's docs
//! (`cargo run --release -p chasles-skin --example dib_step`). The step is written here
//! again in f64 with the library's dual quaternions, independently of the lanes' f32 code,
//! as a check of the derivation itself. Last, the built-in characters' vertices of three
//! influences or more over their first clip at five times, and their blocks of sixteen in
//! `vertex_order`'s order (the most a block's lanes need): what the SIMD kernel's
//! iterating blocks do on a real rig (`fast::avx512`'s docs).

use chasles::blend::dlb::dlb;
use chasles::{DualQuat, Quat, Vec3};
use chasles_skin::{gltf_load, joint_transforms, synthetic, vertex_order, Pose};

/// The stopping rule's precision, the skinning's.
const PRECISION: f64 = chasles_skin::skinning::DIB_PRECISION as f64;
/// More updates than this count as this many.
const CAP: usize = 11;

/// `a · b` of 3-vectors.
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The vector parts `(a, b)` of a pure dual quaternion's array.
fn parts(x: &[f64; 8]) -> ([f64; 3], [f64; 3]) {
    ([x[1], x[2], x[3]], [x[5], x[6], x[7]])
}

/// `x̂ − ⅓ Σ wᵢ x̂ᵢ × (x̂ᵢ × x̂)` in dual arithmetic, written as the double cross product
/// `x̂ᵢ (x̂ᵢ · x̂) − x̂ (x̂ᵢ · x̂ᵢ)` of dual vectors.
fn second_order(x: &[f64; 8], logs: &[[f64; 8]], w: &[f64]) -> [f64; 8] {
    let (a, b) = parts(x);
    let mut d = *x;
    for (l, wi) in logs.iter().zip(w) {
        let (ai, bi) = parts(l);
        // Dual dot products: p = x̂ᵢ · x̂, s = x̂ᵢ · x̂ᵢ.
        let (p0, p1) = (dot(ai, a), dot(ai, b) + dot(bi, a));
        let (s0, s1) = (dot(ai, ai), 2.0 * dot(ai, bi));
        for c in 0..3 {
            // −⅓ wᵢ (x̂ᵢ p − x̂ s), real and dual parts.
            d[1 + c] -= wi / 3.0 * (ai[c] * p0 - a[c] * s0);
            d[5 + c] -= wi / 3.0 * (ai[c] * p1 + bi[c] * p0 - b[c] * s0 - a[c] * s1);
        }
    }
    d
}

/// DIB from the DLB start with the paper's step or the second-order one: the updates made
/// before the update's norm fell below the precision, and the blend.
fn dib(q: &[DualQuat<f64>], w: &[f64], second: bool) -> (usize, DualQuat<f64>) {
    let mut b = dlb(q, w).expect("unit inputs");
    for updates in 0..=CAP {
        let bc = b.conjugate();
        let logs: Vec<[f64; 8]> = q
            .iter()
            .map(|qi| {
                (bc * *qi)
                    .to_positive_hemisphere()
                    .log()
                    .expect("unit")
                    .to_array()
            })
            .collect();
        let mut x = [0.0; 8];
        for (l, wi) in logs.iter().zip(w) {
            x.iter_mut().zip(l).for_each(|(x, l)| *x += wi * l);
        }
        if x.iter().map(|v| v * v).sum::<f64>().sqrt() < PRECISION || updates == CAP {
            return (updates, b);
        }
        let step = if second {
            second_order(&x, &logs, w)
        } else {
            x
        };
        b = (b * DualQuat::from_array(step).exp())
            .normalize()
            .expect("unit");
    }
    unreachable!("the loop returns at CAP")
}

/// A histogram of update counts, `[count of 0, 1, …, CAP or more]`.
fn histogram(counts: &[usize]) -> Vec<usize> {
    (0..=CAP)
        .map(|k| counts.iter().filter(|&&c| c == k).count())
        .collect()
}

fn main() {
    // The synthetic rig of `chasles skin --bench`: vertex by vertex, and the most a block
    // of eight needs (the SIMD kernel runs until its last lane stops).
    let rig = synthetic::rig(20_000, 54, 7);
    let d: Vec<DualQuat<f64>> = synthetic::joints(54, 7)
        .dual_quats
        .iter()
        .map(|x| x.cast())
        .collect();
    for (name, second) in [("paper's step", false), ("second-order", true)] {
        let counts: Vec<usize> = rig
            .vertices()
            .iter()
            .map(|v| {
                let q: Vec<_> = v.j.iter().map(|&j| d[usize::from(j)]).collect();
                let sum: f32 = v.w.iter().sum();
                let w: Vec<f64> = v.w.iter().map(|&x| f64::from(x / sum)).collect();
                dib(&q, &w, second).0
            })
            .collect();
        let blocks: Vec<usize> = counts
            .chunks(8)
            .map(|c| *c.iter().max().unwrap_or(&0))
            .collect();
        println!(
            "synthetic rig, {name}: vertices by updates {:?}, blocks of eight by updates {:?}",
            histogram(&counts),
            histogram(&blocks)
        );
    }
    // Random blends of 2–4 transforms, ever farther apart.
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    for (angle, shift) in [(1.0, 1.0), (2.0, 3.0), (3.0, 10.0), (3.1, 100.0)] {
        let mut counts = [Vec::new(), Vec::new()];
        let mut worst = [0f64; 2];
        for _ in 0..5000 {
            let n = 2 + (next() * 3.0) as usize;
            let q: Vec<DualQuat<f64>> = (0..n)
                .map(|_| {
                    let axis = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
                    let r = Quat::from_axis_angle(axis, next() * angle).expect("axis");
                    let t = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * shift;
                    DualQuat::from_rotation_translation(r, t)
                })
                .collect();
            let w: Vec<f64> = (0..n).map(|_| next() + 0.01).collect();
            let sum: f64 = w.iter().sum();
            let w: Vec<f64> = w.iter().map(|x| x / sum).collect();
            let (exact, _) = chasles::blend::dib::dib(&q, &w, 1e-13, 500).expect("unit");
            let p = Vec3::new(0.5, -1.0, 2.0);
            for (k, second) in [false, true].into_iter().enumerate() {
                let (updates, b) = dib(&q, &w, second);
                counts[k].push(updates);
                let off = (b.transform_point(p) - exact.transform_point(p)).norm();
                worst[k] = worst[k].max(off / (1.0 + shift));
            }
        }
        for (k, name) in ["paper's step", "second-order"].iter().enumerate() {
            let mean = counts[k].iter().sum::<usize>() as f64 / 5000.0;
            println!(
                "rotations up to {angle} rad, moves up to {shift}, {name}: updates {:?} (mean {mean:.2}, {CAP} meaning {CAP} or more), largest distance from the exact blend {:.1e} × (1 + move)",
                histogram(&counts[k]),
                worst[k]
            );
        }
    }
    for m in [
        chasles_models::CESIUM_MAN,
        chasles_models::RIGGED_FIGURE,
        chasles_models::FOX,
    ] {
        characters(m);
    }
}

/// A character's vertices of three influences or more by the second-order step's updates,
/// its first clip at five times, and its blocks of sixteen in `vertex_order`'s order by the
/// most their lanes need (vertices of one or two need none: `lane::dib` takes them in
/// closed form).
fn characters(m: chasles_models::Model) {
    let rig = gltf_load::load_slice(m.bytes, m.file).expect("a built-in character");
    let clip = &rig.animations[0];
    let order = vertex_order::by_influence_count(&rig).expect("a valid rig");
    let (mut vertices, mut blocks) = (Vec::new(), Vec::new());
    for t in [0.1, 0.3, 0.5, 0.7, 0.9] {
        let pose = Pose::animated(&rig, 0, clip.duration() * t).expect("a clip");
        let jt = joint_transforms(&rig, &pose).expect("a pose");
        let updates: Vec<usize> = order
            .iter()
            .map(|&v| {
                let used: Vec<(usize, f32)> = rig
                    .influences
                    .of(v as usize)
                    .filter(|&(_, w)| w > 0.0)
                    .collect();
                if used.len() < 3 {
                    return 0;
                }
                let sum: f32 = used.iter().map(|&(_, w)| w).sum();
                // The joints made unit in f64, as the kernels make them unit in f32.
                let q: Vec<DualQuat<f64>> = used
                    .iter()
                    .map(|&(j, _)| jt.dual_quats[j].cast().normalize().expect("unit"))
                    .collect();
                let w: Vec<f64> = used.iter().map(|&(_, x)| f64::from(x / sum)).collect();
                let n = dib(&q, &w, true).0;
                vertices.push(n);
                n
            })
            .collect();
        blocks.extend(updates.chunks(16).map(|c| *c.iter().max().unwrap_or(&0)));
    }
    println!(
        "{}, first clip at five times, second-order: vertices of three influences or more by updates {:?}, blocks of sixteen (vertex_order) by updates {:?}",
        rig.name,
        histogram(&vertices),
        histogram(&blocks)
    );
}
