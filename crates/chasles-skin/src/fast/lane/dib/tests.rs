//! The lane DIB's tests: its series against their closed forms, its logarithm and
//! exponential against the library's, the second-order step, Lemma 3, slots, the library's
//! DIB, and the subnormal numbers of lanes of one influence.

use super::*;
use chasles::{DualQuat, Quat, Vec3};

/// `Σ cₖ sᵏ` in f64: the value of a series' f32 coefficients.
fn sum64(c: &[f32], s: f64) -> f64 {
    c.iter().rev().fold(0.0, |a, k| a * s + f64::from(*k))
}

/// The fitted `H` and `H_S` are their closed forms on `[0, 1]` as `scripts/fit_dib_log.py`
/// documents (relative: 0.3 f32 ulp each with their f32 coefficients, 1 ulp each evaluated
/// in f32), and so give the logarithm's `h = atan2(n, w)/n` and `∂h/∂s = (w − h)/(2s)` at
/// `v = 1 − w` on the unit sphere; the exponential's Taylor series are theirs up to
/// `s = (π/2)²`.
#[test]
fn the_series_are_the_closed_forms() {
    let ulp = f64::from(f32::EPSILON);
    // The closed forms at v = 1 − cos θ: h = θ/sin θ and (cos θ − h)/(2 sin² θ); at v = 0
    // their limits (for v ≥ 1e-3, f64's cancellation in ∂h/∂s stays below 1e-12).
    let h_of = |v: f64| {
        let n = (v * (2.0 - v)).sqrt();
        if n == 0.0 {
            1.0
        } else {
            n.atan2(1.0 - v) / n
        }
    };
    let h_s_of = |v: f64| {
        if v == 0.0 {
            -1.0 / 3.0
        } else {
            ((1.0 - v) - h_of(v)) / (2.0 * v * (2.0 - v))
        }
    };
    let rel = |got: f64, want: f64| ((got - want) / want).abs() / ulp;
    for i in 0..=1000 {
        let f = f64::from(i) / 1000.0;
        // H and H_S up to v = 1: exactly (their f32 coefficients), and in f32 at the f32
        // nearest v.
        let v = f;
        assert!(rel(sum64(&H, v), h_of(v)) <= 0.3, "H({v})");
        assert!(rel(sum64(&H_S, v), h_s_of(v)) <= 0.3, "H_S({v})");
        let v32 = v as f32;
        let (h32, h_s32) = (horner(&H, v32), horner(&H_S, v32));
        let v = f64::from(v32);
        assert!(rel(f64::from(h32), h_of(v)) <= 1.0, "H({v}) in f32: {h32}");
        assert!(
            rel(f64::from(h_s32), h_s_of(v)) <= 1.0,
            "H_S({v}) in f32: {h_s32}"
        );
        // What they stand for, from the angle θ = f π/2 itself: h = atan2(n, w)/n, and
        // ∂h/∂s at fixed w by a central difference in s = n².
        let theta = f * std::f64::consts::FRAC_PI_2;
        let (w, n) = (theta.cos(), theta.sin());
        if theta > 0.1 {
            let h = |s: f64| s.sqrt().atan2(w) / s.sqrt();
            let s = n * n;
            assert!((h_of(1.0 - w) - h(s)).abs() <= 1e-14 * h(s), "h at {theta}");
            let e = 1e-5 * s;
            let slope = (h(s + e) - h(s - e)) / (2.0 * e);
            assert!(
                (h_s_of(1.0 - w) - slope).abs() <= 1e-8,
                "∂h/∂s at {theta}: {slope}"
            );
        }
        // cos √s, sinc √s and its derivative up to s = (π/2)².
        let x = f * std::f64::consts::FRAC_PI_2;
        let s = x * x;
        assert!((sum64(&COS, s) - x.cos()).abs() < 5e-8, "cos {x}");
        if x > 0.1 {
            assert!((sum64(&SINC, s) - x.sin() / x).abs() < 5e-8, "sinc {x}");
            let d = (x.cos() - x.sin() / x) / (2.0 * s);
            assert!((sum64(&D_SINC, s) - d).abs() < 5e-8, "d sinc {x}");
        }
    }
}

/// A unit dual quaternion turning by `angle` about a varying axis and moving by up to 2.
fn rigid(f: f32, angle: f32) -> DualQuat<f32> {
    let axis = Vec3::new(1.0, 3.0 * f - 1.0, (7.0 * f).sin());
    let q = Quat::from_axis_angle(axis, angle).unwrap();
    let t = Vec3::new(2.0 * f, 1.0 - f, (3.0 * f).cos());
    DualQuat::from_rotation_translation(q, t)
}

/// On one lane the series' logarithm and exponential are the library's `DualQuat::log`
/// and `exp` (eq. 2 and its inverse; the exponential up to its positive scalar factor,
/// which the normalization removes) at every rotation angle from 0 to a full turn
/// (half-angles to π: w from 1 through 0 to −1, both hemispheres), −0 included.
#[test]
fn the_lane_log_and_exp_are_the_librarys() {
    for i in 0..=400 {
        let f = i as f32 / 400.0;
        // Half-angles 0 … π: w from 1 through 0 to −1.
        let d = rigid(f, std::f32::consts::TAU * f);
        let got = log(&d.to_array());
        let want = if d.real.w < 0.0 { -d } else { d }
            .log()
            .unwrap()
            .to_array();
        for c in 0..8 {
            let tol = 2e-6 * (1.0 + want[c].abs());
            assert!((got[c] - want[c]).abs() < tol, "{f}: {got:?} vs {want:?}");
        }
        // The exponential of a convex blend's update: half-angles up to π/2.
        let mut x = rigid(f, std::f32::consts::PI * f).log().unwrap().to_array();
        x[0] = 0.0;
        x[4] = 0.0;
        let got = normalize(&exp(&x));
        let want = DualQuat::from_array(x)
            .exp()
            .normalize()
            .unwrap()
            .to_array();
        for c in 0..8 {
            assert!((got[c] - want[c]).abs() < 2e-6, "{f}: {got:?} vs {want:?}");
        }
    }
    // w = −0: the sign bit alone takes r̂ to −r̂ (the identity's antipode's log is 0).
    let mut antipode = [0f32; 8];
    antipode[0] = -1.0;
    assert_eq!(log(&antipode), [0.0; 8]);
    let mut half_turn = [0f32; 8];
    (half_turn[0], half_turn[1]) = (-0.0, -1.0);
    let l = log(&half_turn);
    assert!((l[1] - std::f32::consts::FRAC_PI_2).abs() < 1e-6, "{l:?}");
}

/// A xorshift generator from `seed`: uniform numbers in [0, 1).
pub(super) fn uniform(seed: u64) -> impl FnMut() -> f32 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// A vector of `next`'s numbers, each shifted to [−0.5, 0.5).
fn centred(next: &mut impl FnMut() -> f32) -> Vec3<f32> {
    Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5)
}

/// A random unit dual quaternion from `next`: turned by up to 7 rad about any axis, moved
/// by up to 4 along each axis.
fn random_rigid(next: &mut impl FnMut() -> f32) -> [f32; 8] {
    let axis = centred(next);
    let q = Quat::from_axis_angle(axis, 7.0 * next()).unwrap();
    DualQuat::from_rotation_translation(q, centred(next) * 8.0).to_array()
}

/// The logarithm of what the kernels take it of — the products `b̂* q̂ᵢ` of two unit dual
/// quaternions in f32, by the lanes' own product, unit only to rounding — is f64's
/// logarithm of the same product: the vector parts within 4e-7 relatively (the formula
/// takes `‖r0‖` as 1: off by about `‖r0‖ − 1` in h, 3× that in `∂h/∂s`), over rotations
/// of every angle and moves of up to 4.
#[test]
fn the_lane_log_of_products_is_f64s() {
    let mut next = uniform(0x1234_5678_9abc_def1);
    let (mut worst_real, mut worst_dual) = (0f64, 0f64);
    for _ in 0..20000 {
        let (b, q) = (random_rigid(&mut next), random_rigid(&mut next));
        let conj = std::array::from_fn(|c| if c % 4 == 0 { b[c] } else { -b[c] });
        let r = dqmul(&conj, &q);
        let got = log(&r);
        let r64 = DualQuat::from_array(r.map(f64::from));
        let want = if r64.real.w < 0.0 { -r64 } else { r64 }
            .log()
            .unwrap()
            .to_array();
        let norm = |x: &[f64]| x.iter().map(|x| x * x).sum::<f64>().sqrt();
        let off = |c: std::ops::Range<usize>| {
            norm(&c.map(|c| f64::from(got[c]) - want[c]).collect::<Vec<_>>())
        };
        let (real, dual) = (norm(&want[1..4]), norm(&want[5..8]));
        worst_real = worst_real.max(off(1..4) / real.max(1e-30));
        worst_dual = worst_dual.max(off(5..8) / (real + dual));
    }
    assert!(worst_real <= 4e-7, "{worst_real}");
    assert!(worst_dual <= 4e-7, "{worst_dual}");
}

/// The pass that shows convergence takes the update by one product ([`update_by_sum`]):
/// its vector parts are f64's `Σ wᵢ log(b̂* q̂ᵢ)` of the same f32 numbers as closely as
/// [`update`]'s — within 8e-7 of the logarithms' weighted size `Σ wᵢ ‖log(b̂* q̂ᵢ)‖` far
/// from the blend (both 3.9e-7 when written), over rotations of every angle, either
/// hemisphere, moves of up to 4 and one to four influences — and at the blend itself (DIB
/// in f64, rounded to f32) its norm is below a tenth of the precision (5.4e-7 at most when
/// written), as `update`'s is.
#[test]
fn the_update_by_one_product_is_the_updates() {
    let mut next = uniform(0x5EED_0FD1_B5A1_1C0D);
    let (mut worst_sum, mut worst_update, mut worst_at_blend) = (0f64, 0f64, 0f32);
    for i in 0..20000 {
        let n = 1 + i % 4;
        let mut q = [DualQuat::<f32>::identity().to_array(); 4];
        (0..n).for_each(|k| q[k] = random_rigid(&mut next));
        if i % 3 == 0 {
            q[0] = q[0].map(|c| -c); // the other hemisphere
        }
        let mut raw = [0f32; 4];
        (0..n).for_each(|k| raw[k] = next() + 0.05);
        let (w, _, slots) = convex(raw);
        let (q64, w64): (Vec<DualQuat<f64>>, Vec<f64>) = (0..n)
            .map(|k| (DualQuat::from_array(q[k].map(f64::from)), f64::from(w[k])))
            .unzip();
        // Far from the blend: at a random pose, or the blend itself.
        let at_blend = (i / 4) % 2 == 1;
        let b = if at_blend {
            let (b, _) = chasles::blend::dib::dib(&q64, &w64, 1e-13, 200).unwrap();
            b.to_array().map(|c| c as f32)
        } else {
            random_rigid(&mut next)
        };
        let b = normalize(&b);
        // f64's update at the same f32 numbers.
        let b64 = DualQuat::from_array(b.map(f64::from));
        let (mut want, mut size) = ([0f64; 8], 0f64);
        for (qk, wk) in q64.iter().zip(&w64) {
            let r = b64.conjugate() * *qk;
            let l = if r.real.w < 0.0 { -r } else { r }
                .log()
                .unwrap()
                .to_array();
            (0..8).for_each(|c| want[c] += wk * l[c]);
            size += wk * l.iter().map(|x| x * x).sum::<f64>().sqrt();
        }
        let (got, (full, _)) = (update_by_sum(&b, &q, &w, slots), update(&b, &q, &w, slots));
        let off = |x: [f32; 6]| {
            let parts = [1, 2, 3, 5, 6, 7];
            (0..6)
                .map(|c| (f64::from(x[c]) - want[parts[c]]).powi(2))
                .sum::<f64>()
                .sqrt()
                / size.max(1e-30)
        };
        if at_blend {
            worst_at_blend = worst_at_blend.max(dot(&got, &got).sqrt());
            let norm = dot(&full, &full).sqrt();
            assert!(
                norm < 0.1 * DIB_PRECISION,
                "{i}: the update's own norm {norm}"
            );
        } else {
            worst_sum = worst_sum.max(off(got));
            worst_update = worst_update.max(off([1, 2, 3, 5, 6, 7].map(|c| full[c])));
        }
    }
    assert!(worst_sum <= 8e-7, "by one product {worst_sum}");
    assert!(worst_update <= 8e-7, "by the logarithms {worst_update}");
    assert!(worst_at_blend < 0.1 * DIB_PRECISION, "{worst_at_blend}");
}

/// After an update, `b̂ exp(δ̂)` is renormalized by one Newton step for `1/‖q0‖` from 1
/// ([`renormalize`]): the exponential's series are unit to within 1e-4 for every step the
/// second-order rule can make (`‖δ‖ ≤ (π/2)(1 + (π/2)²/3) < 2.9`), and from there the
/// Newton step gives `normalize`'s result to f32's rounding.
#[test]
fn renormalizing_after_an_update_is_normalizing() {
    let mut next = uniform(0x0DDB_1A5E_5BAD_5EED);
    let mut worst = (0f32, 0f32);
    for i in 0..20000 {
        let b = random_rigid(&mut next);
        // Steps up to 2.9 long, the largest most often.
        let length = 2.9 * if i % 2 == 0 { 1.0 } else { next() };
        let a = centred(&mut next).normalize().unwrap() * length;
        let d = centred(&mut next) * 4.0;
        let step = [0.0, a.x, a.y, a.z, 0.0, d.x, d.y, d.z];
        let e = exp(&step);
        worst.0 = worst.0.max((dot(&e[..4], &e[..4]) - 1.0).abs());
        let p = dqmul(&b, &e);
        let (got, want) = (renormalize(&p), normalize(&p));
        for c in 0..8 {
            worst.1 = worst
                .1
                .max((got[c] - want[c]).abs() / (1.0 + want[c].abs()));
        }
    }
    assert!(
        worst.0 < 1e-4,
        "the exponential's norm is off by {}",
        worst.0
    );
    assert!(worst.1 < 5e-7, "renormalized off by {}", worst.1);
}

/// The second-order step does what its derivation says: from the DLB start of random
/// blends of four joints (rotated by up to 60°, moved by up to 2), one step leaves a
/// residual `‖Σ wᵢ log(b̂* q̂ᵢ)‖` over 20× smaller on average than the paper's step does
/// (43× when written) — third order against first order times the spread² — and never
/// a larger one beyond f32's rounding.
#[test]
fn the_second_order_step_leaves_a_smaller_residual() {
    let residual = |b: &[f32; 8], q: &[[f32; 8]; 4], w: &[f32; 4]| update(b, q, w, 4);
    let norm = |x: &[f32; 8]| dot(x, x).sqrt();
    let (mut plain, mut second) = (0f64, 0f64);
    for i in 0..500 {
        let f = i as f32 / 500.0;
        let q = [0.13, 0.37, 0.61, 0.83]
            .map(|g| rigid((f * 7.0 + g) % 1.0, 1.05 * ((f * 13.0 + g) % 1.0)).to_array());
        let raw = [0.4, 0.3 * f + 0.05, 0.2, 0.1 + 0.2 * (1.0 - f)];
        let (w, _, _) = convex(raw);
        let qs: Vec<DualQuat<f32>> = q.iter().map(|a| DualQuat::from_array(*a)).collect();
        let b = chasles::blend::dlb::dlb(&qs, &w).unwrap().to_array();
        let (x, spread) = residual(&b, &q, &w);
        let after = |d: [f32; 8]| norm(&residual(&normalize(&dqmul(&b, &exp(&d))), &q, &w).0);
        let (p, s) = (after(x), after(spread.step(&x)));
        // f32's rounding floor of the residual: about 1e-7.
        assert!(s <= p.max(3e-7), "{i}: {s} against {p} (from {})", norm(&x));
        plain += f64::from(p);
        second += f64::from(s);
    }
    assert!(
        second * 20.0 < plain,
        "mean residual {second} against {plain}"
    );
}

/// Lemma 3 on one lane: a blend of two joints is ScLERP, taken in closed form (the dual
/// Slerp, `sclerp::screw`) — within 1e-6 (relative to 1 + |x|) of the library's f64 `sclerp` at
/// every relative angle up to 178° and down to 1.5e-7 rad and none (the dual weights' limit
/// at Ω = 0), moved by up to 2, either hemisphere; unit to rounding though not normalized
/// after — and where DIB's update would stop at once (it is below the precision). One
/// joint gives the joint itself.
#[test]
fn two_joints_end_at_sclerp() {
    // (f32's rounding: 6.1e-6 when an update from DLB's start took the blend there.)
    let mut worst = 0f64;
    let (mut off_unit, mut off_orth) = (0f32, 0f32);
    for i in 0..=340 {
        let f = i as f32 / 300.0;
        let p = rigid(f % 1.0, 2.0 * f - 1.0);
        // Relative angles up to 178°, then 40 down to 1e-7 rad and none.
        let angle = if i <= 300 {
            3.1 * f
        } else if i < 340 {
            10f32.powf(-7.0 * (i - 300) as f32 / 40.0)
        } else {
            0.0
        };
        let rel = rigid((f * 7.0) % 1.0, angle);
        let mut qj = p * rel;
        if i % 2 == 1 {
            qj = -qj; // the other hemisphere: the same transformation
        }
        for t in [0.0f32, 0.1, 0.37, 0.5, 0.8] {
            let (w, _, slots) = convex([1.0 - t, t, 0.0, 0.0]);
            let identity = DualQuat::<f32>::identity().to_array();
            let q = [p.to_array(), qj.to_array(), identity, identity];
            let got = dib::<f32, 4>(&q, &w, slots);
            off_unit = off_unit.max((dot(&got[..4], &got[..4]) - 1.0).abs());
            let dual = dot(&got[4..], &got[4..]).sqrt();
            off_orth = off_orth.max(dot(&got[..4], &got[4..]).abs() / (1.0 + dual));
            let want =
                chasles::blend::sclerp::sclerp(p.cast::<f64>(), qj.cast::<f64>(), f64::from(w[1]))
                    .unwrap();
            let want = if want.real.dot(DualQuat::from_array(got).real.cast()) < 0.0 {
                -want
            } else {
                want
            };
            for (c, (g, x)) in got.iter().zip(want.to_array()).enumerate() {
                worst = worst.max((f64::from(*g) - x).abs() / (1.0 + x.abs()));
                assert!(
                    (f64::from(*g) - x).abs() < 1e-6 * (1.0 + x.abs()),
                    "{i}, t = {t}, {c}: {got:?} against {want:?}"
                );
            }
            let (x, _) = update(&got, &q, &w, slots);
            let norm = dot(&x, &x).sqrt();
            assert!(norm < DIB_PRECISION, "{i}, t = {t}: {norm}");
        }
    }
    // When written: 4.0e-7 (the logarithm and exponential it replaced: 4.2e-7); unit to
    // 4.8e-7 in ‖b0‖² and its parts orthogonal to 8.4e-8, with no normalization after.
    assert!(worst < 1e-6, "{worst}");
    assert!(off_unit < 1e-6, "‖b0‖² off by {off_unit}");
    assert!(off_orth < 3e-7, "b0·bε off by {off_orth}");
    let p = rigid(0.3, 1.2).to_array();
    let (w, _, slots) = convex([1.0f32, 0.0, 0.0, 0.0]);
    let identity = DualQuat::<f32>::identity().to_array();
    let got = dib::<f32, 4>(&[p, identity, identity, identity], &w, slots);
    for c in 0..8 {
        assert!((got[c] - p[c]).abs() < 1e-6, "{got:?} against {p:?}");
    }
}

/// The positive weights may sit in any slots (weights of 0 between them, the identity
/// in those slots, as the kernel puts it): on one lane DIB gives the same bits as with
/// them in the first slots, for every count from one to K (4 and 8), pairs beyond slot
/// 1 included (the counts that decide no update, ScLERP in closed form, or the iteration).
#[test]
fn influences_in_any_slots_give_the_same_bits() {
    fn check<const K: usize>() {
        let identity = DualQuat::<f32>::identity().to_array();
        for i in 0..400 {
            let f = i as f32 / 400.0;
            let count = 1 + i % K;
            // `count` increasing slots out of K, by the bits of a mixed number.
            let mut at: Vec<usize> = Vec::new();
            let mut h = (i * 7919 + 13) % (1 << K);
            for k in 0..K {
                if at.len() + (K - k) == count || (h & 1 == 1 && at.len() < count) {
                    at.push(k);
                }
                h >>= 1;
            }
            assert_eq!(at.len(), count);
            let joints: Vec<[f32; 8]> = (0..count)
                .map(|c| {
                    rigid(
                        (f * 5.0 + 0.17 * c as f32) % 1.0,
                        1.4 * ((f + 0.3 * c as f32) % 1.0),
                    )
                    .to_array()
                })
                .collect();
            let raw: Vec<f32> = (0..count)
                .map(|c| 0.2 + ((f * 11.0 + c as f32 * 0.37) % 1.0))
                .collect();
            let lay = |slot: &dyn Fn(usize) -> usize| {
                let (mut q, mut w) = ([identity; K], [0f32; K]);
                for c in 0..count {
                    (q[slot(c)], w[slot(c)]) = (joints[c], raw[c]);
                }
                let (w, _, slots) = convex(w);
                dib::<f32, K>(&q, &w, slots)
            };
            let (compact, scattered) = (lay(&|c| c), lay(&|c| at[c]));
            assert_eq!(
                compact.map(f32::to_bits),
                scattered.map(f32::to_bits),
                "K = {K}, {i}: slots {at:?}: {compact:?} against {scattered:?}"
            );
        }
    }
    check::<4>();
    check::<8>();
}

/// A lane of one influence meets no subnormal number in its block's passes: on the
/// built-in characters (each clip at seven times, blocks of sixteen as the sixteen-vertex
/// kernel takes them, through to the transformation), no operation of such a lane has a
/// subnormal operand or result or underflows (module docs, "Subnormal numbers": before
/// its update took weight 0, the Fox's made thousands and skinned 2.9× slower over its
/// clips; lanes of more influences may still make a few). What was watched is the
/// kernel's arithmetic: every vertex's output is the SIMD kernels' bits, where they run.
#[test]
fn lanes_of_one_influence_meet_no_subnormal_numbers() {
    use super::super::transform;
    use super::super::watch::{take, Watch, LANES};
    use crate::fast::{dual_quats8, uses_simd, FastRig};
    let models = [
        chasles_models::CESIUM_MAN,
        chasles_models::FOX,
        chasles_models::RIGGED_FIGURE,
        chasles_models::RIGGED_SIMPLE,
    ];
    let identity = DualQuat::<f32>::identity().to_array();
    let (mut singles, mut blocks) = (0, 0);
    for m in models {
        let rig = crate::gltf_load::load_slice(m.bytes, m.file).unwrap();
        let fast = FastRig::<4>::new(&rig).unwrap();
        for (clip, animation) in rig.animations.iter().enumerate() {
            for step in 0..7 {
                let t = animation.duration() * step as f32 / 6.0;
                let pose = crate::Pose::animated(&rig, clip, t).unwrap();
                let jt = crate::joint_transforms(&rig, &pose).unwrap();
                let d = dual_quats8(&jt);
                let mut simd = vec![[f32::NAN; 6]; fast.vertices().len()];
                crate::fast::dib(&fast, &jt.dual_quats, &mut simd, false).unwrap();
                for (v, simd) in fast.vertices().chunks_exact(LANES).zip(simd.chunks(LANES)) {
                    let lanes = |f: &dyn Fn(usize) -> f32| Watch(std::array::from_fn(f));
                    let raw = std::array::from_fn(|k| lanes(&|l| v[l].w[k]));
                    let (w, used, slots) = convex::<Watch, 4>(raw);
                    let q = std::array::from_fn(|k| {
                        std::array::from_fn(|c| {
                            lanes(&|l| match used[k][l] {
                                true => d[usize::from(v[l].j[k])][c],
                                false => identity[c],
                            })
                        })
                    });
                    let p = std::array::from_fn(|c| lanes(&|l| v[l].p[c]));
                    let n = std::array::from_fn(|c| lanes(&|l| v[l].n[c]));
                    let out = transform(dib(&q, &w, slots), p, n);
                    if uses_simd(4) {
                        for (l, simd) in simd.iter().enumerate() {
                            let watched = out.map(|c| c.0[l].to_bits());
                            assert_eq!(watched, simd.map(f32::to_bits), "{}, {l}", rig.name);
                        }
                    }
                    for (l, seen) in take().iter().enumerate() {
                        if (0..4).filter(|&k| used[k][l]).count() == 1 {
                            let name = &rig.name;
                            assert!(seen.is_empty(), "{name}, clip {clip} at {t}: {seen:?}");
                            singles += 1;
                        }
                    }
                    blocks += 1;
                }
            }
        }
    }
    if !uses_simd(4) {
        eprintln!("no AVX2+FMA here: the watched outputs were not compared with the kernels'");
    }
    // The characters' blocks, and their lanes of one influence, were there to watch.
    assert!(
        blocks > 1000 && singles > 5000,
        "{blocks} blocks, {singles} lanes"
    );
}

/// On one lane the branch-free DIB is the library's DIB: the same blend to within the
/// stopping rule's reach, on convex weights of two to four joints at every angle, and a
/// NaN joint with weight gives NaN (or stops at once) rather than a number.
#[test]
fn the_lane_dib_is_the_librarys() {
    for i in 0..200 {
        let f = i as f32 / 200.0;
        let joints = [0.1, 0.4, 0.7, 0.9].map(|g| rigid((f + g) % 1.0, 2.8 * (f + g)));
        let raw = [
            0.5 * (1.0 - f),
            0.3,
            0.2 * f,
            if i % 3 == 0 { 0.0 } else { 0.1 },
        ];
        let (w, used, slots) = convex(raw);
        let q = std::array::from_fn(|k| {
            if used[k] {
                joints[k].to_array()
            } else {
                DualQuat::<f32>::identity().to_array()
            }
        });
        let got = DualQuat::from_array(dib::<f32, 4>(&q, &w, slots));
        let (qs, ws): (Vec<DualQuat<f64>>, Vec<f64>) = (0..4)
            .filter(|&k| used[k])
            .map(|k| (joints[k].cast::<f64>(), f64::from(w[k])))
            .unzip();
        let (want, _) = chasles::blend::dib::dib(&qs, &ws, 1e-12, 200).unwrap();
        let p = Vec3::new(0.5f32, -1.0, 2.0);
        let exact = want.transform_point(p.cast::<f64>());
        let off = (got.transform_point(p).cast::<f64>() - exact).norm();
        // The stopping rule's reach at a lever of ‖p‖ ≈ 2.3, and rounding.
        let reach = 2.0 * f64::from(DIB_PRECISION) * (1.0 + 2.0 * 2.3) + 1e-5;
        assert!(off <= reach, "{i}: {off}");
    }
    let mut q = [DualQuat::<f32>::identity().to_array(); 4];
    q[1][2] = f32::NAN;
    let (w, _, slots) = convex([0.5f32, 0.5, 0.0, 0.0]);
    assert!(dib::<f32, 4>(&q, &w, slots).iter().all(|c| c.is_nan()));
}
