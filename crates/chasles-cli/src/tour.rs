//! `chasles tour`: a walk through what the library does, on built-in data, with every
//! number computed on the spot. Today it covers the core algebra (Dam et al. §3.3, App. A
//! and B; Kavan et al. §3); interpolation, blending, skinning and the pictures join it as
//! they land.

use chasles::analysis::curvature::{curvature_energy, Width};
use chasles::analysis::velocity::velocity_angle;
use chasles::interp::slerp::slerp;
use chasles::interp::{
    examples, interpolate, spring, Hemisphere, KeyFrames, Method, SpringConfig, Squad, Timing,
};
use chasles::{DualQuat, EulerOrder, Mat3, Quat, Real, Vec3};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::f64::consts::{FRAC_PI_2, PI};
use std::io::{IsTerminal, Write};

/// Options of `chasles tour`.
pub struct TourArgs {
    /// Random inputs per identity in the sweep.
    pub samples: usize,
    /// Seed of the random inputs.
    pub seed: u64,
}

fn arr(xs: &[f64]) -> String {
    let parts: Vec<String> = xs.iter().map(|x| format!("{x:+.6}")).collect();
    format!("[{}]", parts.join(", "))
}

fn heading(s: &str) {
    println!("\n== {s}");
}

/// Runs the tour, printing to stdout.
pub fn run(args: TourArgs) -> anyhow::Result<()> {
    println!("chasles tour — rotations and rigid motions, with numbers computed now");
    println!("Papers: Dam, Koch & Lillholm 1998 (quaternions, interpolation, animation);");
    println!("        Kavan, Collins, Žára & O'Sullivan 2006 (dual quaternions, rigid blending).");

    heading("Dam et al. App. A + B.1: the report's Euler convention, R = Rz(γ) Ry(β) Rx(α)");
    let angles = [0.1, 0.2, 0.3];
    let q = Quat::from_euler(EulerOrder::DAM, angles);
    let m = Mat3::from_euler(EulerOrder::DAM, angles);
    println!("angles (α, β, γ)      {}", arr(&angles));
    println!("quaternion [w,x,y,z]  {}", arr(&q.to_array()));
    for (i, row) in m.m.iter().enumerate() {
        println!(
            "{} {}",
            if i == 0 {
                "matrix (B.1)         "
            } else {
                "                     "
            },
            arr(row)
        );
    }
    let back = m.to_euler(EulerOrder::DAM)?;
    let err = back
        .angles
        .iter()
        .zip(angles)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    println!(
        "back to angles        {}   (error {err:.1e})",
        arr(&back.angles)
    );

    heading("Dam et al. App. B.4 versus Shepperd's method near 180°");
    println!("B.4 divides by 4s, s = cos(angle/2) → 0. Error of the recovered quaternion:");
    println!("  angle            trace-only (B.4)   largest-diagonal (ours)");
    let axis = Vec3::new(1.0, 2.0, 3.0);
    for k in [2, 4, 6, 8, 10] {
        let angle = PI - 10f64.powi(-k);
        let q = Quat::from_axis_angle(axis, angle)?;
        let m = q.to_rotation_matrix();
        let dist = |p: Quat<f64>| (p - q).norm().min((p + q).norm());
        let t = dist(Quat::from_rotation_matrix_trace_only(&m));
        let s = dist(Quat::from_rotation_matrix(&m)?);
        println!("  π − 1e-{k:<2}        {t:<18.2e} {s:.2e}");
    }

    heading("Dam et al. App. B.2: gimbal lock (β = π/2) sets γ = 0");
    let m = Mat3::from_euler(EulerOrder::DAM, [0.4, FRAC_PI_2, -1.1]);
    let e = m.to_euler(EulerOrder::DAM)?;
    let rebuilt = Mat3::from_euler(EulerOrder::DAM, e.angles).max_abs_diff(&m);
    println!(
        "built from (0.4, π/2, −1.1); extracted {} gimbal_lock={}",
        arr(&e.angles),
        e.gimbal_lock
    );
    println!("α − γ = 1.5 is all the matrix knows; rebuilt matrix error {rebuilt:.1e}");

    heading("Dam et al. Definitions 14–16: exp, log and powers near the identity and near 2π");
    println!("  rotation angle      |exp(log q) − q|   |(q^½)² − q|");
    for d in [1e-12, 1e-6, 1e-2] {
        for (label, q) in [
            (format!("{d:.0e}"), Quat::from_axis_angle(axis, d)?),
            (format!("2π − {d:.0e}"), -Quat::from_axis_angle(axis, d)?),
        ] {
            let e1 = (q.log()?.exp() - q).norm();
            let h = q.powf(0.5)?;
            let e2 = (h * h - q).norm();
            println!("  {label:<18}  {e1:<17.1e}  {e2:.1e}");
        }
    }

    heading("Kavan et al. eq. (1) and (2): a rigid motion as a unit dual quaternion");
    let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), FRAC_PI_2)?;
    let t = Vec3::new(1.0, 2.0, 3.0);
    let dq = DualQuat::from_rotation_translation(q, t);
    println!("90° about z, then translate (1, 2, 3):");
    println!("  q̂ = q0 + ε ½ t q0 = {}", arr(&dq.to_array()));
    let s = dq.to_screw()?;
    println!(
        "  screw: axis {} through {} angle {:.6} slide {:.6} pitch {:.6}",
        arr(&s.axis.to_array()),
        arr(&s.point().to_array()),
        s.angle,
        s.translation,
        s.pitch().unwrap_or(f64::INFINITY)
    );
    let p = Vec3::new(0.5, -1.0, 2.0);
    let by_dq = dq.transform_point(p);
    let by_m = dq.to_matrix4().transform_point(p);
    println!(
        "  point (0.5, −1, 2) → {} (4×4 matrix agrees to {:.1e})",
        arr(&by_dq.to_array()),
        (by_dq - by_m).norm()
    );
    let h = dq.powf(0.5)?;
    println!(
        "  half the screw, q̂^½: {} ; applied twice, error {:.1e}",
        arr(&h.to_array()),
        ((h * h) - dq)
            .to_array()
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
    );
    let tr = DualQuat::from_translation(Vec3::new(0.0, 3.0, 4.0));
    let st = tr.to_screw()?;
    println!(
        "  pure translation (0, 3, 4): screw axis {} slide {:.6} (the translation direction)",
        arr(&st.axis.to_array()),
        st.translation
    );

    interpolation()?;
    blending()?;
    skinning()?;

    heading(&format!(
        "Identities over {} random inputs (seed {}): worst error, relative",
        args.samples, args.seed
    ));
    println!("  {:>9} {:>9}  identity", "f64", "f32");
    let show = std::io::stderr().is_terminal();
    if show {
        eprint!("  checking …\r");
        std::io::stderr().flush().ok();
    }
    let r64 = sweep::<f64>(args.samples, args.seed);
    let r32 = sweep::<f32>(args.samples, args.seed);
    if show {
        eprint!("            \r");
    }
    for ((name, a), (_, b)) in r64.iter().zip(r32.iter()) {
        println!("  {a:>9.1e} {b:>9.1e}  {name}");
    }
    println!("\nTolerances the test suite demands: 1e-12 (f64) and 1e-5 (f32). Run `cargo test --workspace`.");
    Ok(())
}

fn energy(f: &[chasles::interp::Frame<f64>]) -> f64 {
    curvature_energy(&f.iter().map(|x| x.q).collect::<Vec<_>>(), Width::Unit)
}

/// Dam et al. chapters 5–7 on the built-in key sets.
fn interpolation() -> anyhow::Result<()> {
    heading("Dam et al. ch. 5–6: Table 5.1's six keys, 550 frames shared by interval angle (§6.2)");
    let set = examples::table_5_1();
    let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain)?;
    println!("  method      curvature energy (eq. 6.23)   speed max/min between keys");
    let methods: [(&str, Option<Method>); 6] = [
        ("lineuler", Some(Method::LinEuler(EulerOrder::DAM))),
        ("linmat", Some(Method::LinMat)),
        ("lerp", Some(Method::Nlerp)),
        ("slerp", Some(Method::Slerp)),
        ("squad", Some(Method::Squad)),
        ("spring", None),
    ];
    for (name, m) in methods {
        let frames = match m {
            Some(m) => interpolate(m, &keys, 550, Timing::Angle)?,
            None => {
                spring(
                    &keys,
                    550,
                    Timing::Angle,
                    &SpringConfig::spring(),
                    &mut |_| {},
                )?
                .frames
            }
        };
        let v = velocity_angle(&frames.iter().map(|f| f.q).collect::<Vec<_>>());
        // Speed ratio inside the intervals (frames next to keys left out).
        let inner: Vec<f64> = frames
            .windows(3)
            .zip(&v[1..])
            .filter(|(w, _)| w.iter().all(|f| f.key.is_none()))
            .map(|(_, s)| *s)
            .collect();
        let (lo, hi) = inner
            .iter()
            .fold((f64::MAX, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
        println!("  {name:<10}  {:<28.4e}  {:.3}", energy(&frames), hi / lo);
    }
    let sq = Squad::new(&keys)?;
    let q = keys.quats();
    let jump = |f: &dyn Fn(usize, f64) -> Quat<f64>| {
        (1..q.len() - 1)
            .map(|k| {
                let d = 1e-4;
                let l = (f(k - 1, 1.0) * 3.0 - f(k - 1, 1.0 - d) * 4.0 + f(k - 1, 1.0 - 2.0 * d))
                    / (2.0 * d);
                let r = (f(k, 0.0) * -3.0 + f(k, d) * 4.0 - f(k, 2.0 * d)) / (2.0 * d);
                (l - r).norm()
            })
            .fold(0.0f64, f64::max)
    };
    println!(
        "  Squad is C¹ at the keys (Proposition 30): largest jump of dq/dh {:.1e}; Slerp's {:.2}",
        jump(&|i, h| sq.eval(i, h)),
        jump(&|i, h| slerp(q[i], q[i + 1], h))
    );

    heading("Dam et al. ch. 7: Spring against Squad on the chapter's examples (200 frames)");
    println!("  set          Slerp start   Squad         Spring        Spring / Squad");
    for set in examples::all().into_iter().skip(1) {
        let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain)?;
        let sl = energy(&interpolate(Method::Slerp, &keys, 200, Timing::Angle)?);
        let sq = energy(&interpolate(Method::Squad, &keys, 200, Timing::Angle)?);
        let sp = energy(
            &spring(
                &keys,
                200,
                Timing::Angle,
                &SpringConfig::spring(),
                &mut |_| {},
            )?
            .frames,
        );
        println!(
            "  {:<12} {sl:<13.4e} {sq:<13.4e} {sp:<13.4e} {:.3}   ({})",
            set.name,
            sp / sq,
            set.section
        );
    }
    Ok(())
}

/// Kavan et al. 2006 by number: Table 1 measured and the paper's claims.
fn blending() -> anyhow::Result<()> {
    use chasles::analysis::{claims, properties};
    heading("Kavan et al. Table 1, measured on 50 random cases per property");
    let t = properties::measure(50, 2006)?;
    print!("{}", properties::to_markdown(&t));
    let listed: usize = t
        .rows
        .iter()
        .map(|r| r.cells().iter().filter(|c| c.1.paper.is_some()).count())
        .sum();
    println!(
        "  {} of {listed} cells the paper lists agree with it.",
        listed - t.disagreements().len()
    );
    heading("Kavan et al. §4, §5, Appendix B: the claims");
    let d = claims::dlb_vs_sclerp(100, 1)?;
    println!(
        "  DLB vs ScLERP: angle differs by at most {:.4}° (paper: < 8.15°), slide by at most {:.3} % (paper: < 15 %); same screw axis within {:.0e}",
        d.angle_deg,
        d.translation * 100.0,
        d.axis
    );
    let (diff, it) = claims::lemma_3(100, 2)?;
    println!("  Lemma 3: DIB of two transforms = ScLERP within {diff:.0e}, after {it} update");
    println!(
        "  Lemma 2: ScLERP bi-invariant within {:.0e}",
        claims::lemma_2(100, 3)?
    );
    let f7 = claims::figure_7()?;
    let (lo, hi) = f7
        .rows
        .iter()
        .fold((f64::MAX, 0.0f64), |(a, b), r| (a.min(r[1]), b.max(r[1])));
    println!(
        "  Figure 7: log-matrix blending's ‖ω_t‖ runs from {lo:.6} to {hi:.6} (not constant); matches Appendix B's closed form within {:.0e}",
        f7.worst
    );
    let h = claims::dib_iterations(200, 4, 30f64.to_radians(), 1e-6)?;
    println!(
        "  DIB updates for rotations within 30° (2–8 inputs): {:?} (index = updates)",
        h
    );
    Ok(())
}

/// The folder of the shared glTF models, if present: $CHASLES_DATA, ./shared/data/gltf or
/// ../shared/data/gltf.
fn data_dir() -> Option<std::path::PathBuf> {
    let mut c: Vec<std::path::PathBuf> = std::env::var_os("CHASLES_DATA")
        .map(Into::into)
        .into_iter()
        .collect();
    c.push("shared/data/gltf".into());
    c.push("../shared/data/gltf".into());
    c.into_iter().find(|p| p.join("CesiumMan.glb").is_file())
}

/// Kavan et al. 2006, §6: the candy wrapper and the real characters.
fn skinning() -> anyhow::Result<()> {
    use chasles_skin::cylinder::{self, Motion};
    use chasles_skin::{gltf_load, joint_transforms, Method, Pose};
    heading("Kavan et al. §6 / Figure 6: the candy wrapper on a two-bone cylinder");
    let rig = cylinder::twisted_cylinder();
    println!("  twist   LBS middle radius   DQS middle radius   (relative to rest)");
    for deg in [0.0f32, 90.0, 135.0, 180.0] {
        let l = cylinder::measure(&rig, Method::Lbs, Motion::Twist, deg.to_radians())?;
        let d = cylinder::measure(&rig, Method::Dqs, Motion::Twist, deg.to_radians())?;
        println!("  {deg:>4}°   {:<19.3} {:.3}", l.radius, d.radius);
    }
    let l = cylinder::measure(&rig, Method::Lbs, Motion::Bend, 150f32.to_radians())?;
    let d = cylinder::measure(&rig, Method::Dqs, Motion::Bend, 150f32.to_radians())?;
    println!(
        "  bend 150°: LBS thins to {:.3} and loses {:.1} % volume; DQS keeps the radius and bulges {:.1} % out",
        l.radius,
        (1.0 - l.volume) * 100.0,
        (d.bulge - 1.0) * 100.0
    );
    let Some(dir) = data_dir() else {
        println!("  (the shared glTF models were not found: set CHASLES_DATA to their folder to see the real characters)");
        return Ok(());
    };
    heading("Real characters: where linear blending loses volume (smallest det of the blended 3×3 over the clip)");
    for (file, clip, credit) in [
        ("CesiumMan.glb", "", "CesiumMan, CC-BY 4.0 with trademark limitations, © 2017 Cesium (Khronos glTF-Sample-Models)"),
        ("Fox.glb", "Run", "Fox: mesh CC0 1.0 (PixelMannen), rigging and animation CC-BY 4.0 (@tomkranis)"),
    ] {
        let rig = gltf_load::load(&dir.join(file))?;
        let c = rig.animations.iter().position(|a| a.name == clip).unwrap_or(0);
        let mut worst = f32::MAX;
        for k in 0..=40 {
            let t = rig.animations[c].duration() * k as f32 / 40.0;
            let jt = joint_transforms(&rig, &Pose::animated(&rig, c, t)?)?;
            for v in 0..rig.mesh.positions.len() {
                let mut a = chasles::Mat3::from_rows([[0.0f32; 3]; 3]);
                for (j, w) in rig.influences.of(v) {
                    let m = jt.matrices[j].linear_part();
                    for (r, row) in a.m.iter_mut().enumerate() {
                        for (col, e) in row.iter_mut().enumerate() {
                            *e += m.m[r][col] * w;
                        }
                    }
                }
                worst = worst.min(a.determinant());
            }
        }
        println!(
            "  {file} ({} vertices, {} joints): LBS down to {worst:.2} of the local volume; DQS keeps 1 (rigid blends)",
            rig.mesh.positions.len(),
            rig.joints.len()
        );
        println!("    credit: {credit}");
    }
    Ok(())
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

fn to64<T: Real, const N: usize>(a: [T; N]) -> [f64; N] {
    a.map(|v| v.to_f64())
}

/// Worst relative error of each identity over random inputs, in precision T.
fn sweep<T: Real>(samples: usize, seed: u64) -> Vec<(&'static str, f64)> {
    let mut rng = StdRng::seed_from_u64(seed);
    let orders = EulerOrder::all();
    let mut worst = [0.0f64; 8];
    let names = [
        "matrix → quaternion → matrix (Shepperd)",
        "Euler → quaternion → Euler, all 24 conventions",
        "exp(log q) = q",
        "‖pq‖ = ‖p‖‖q‖",
        "dual quaternion ↔ 4×4 matrix",
        "dual quaternion → screw → dual quaternion",
        "exp(log q̂) = q̂",
        "Lemma 1: log(m̂ q̂ m̂*) = m̂ log(q̂) m̂*",
    ];
    let c = |x: f64| T::from_f64(x);
    for _ in 0..samples {
        let mut rq = || {
            let q = Quat::new(
                c(rng.random_range(-1.0..1.0)),
                c(rng.random_range(-1.0..1.0)),
                c(rng.random_range(-1.0..1.0)),
                c(rng.random_range(-1.0..1.0)),
            );
            q.normalize().unwrap_or(Quat::identity())
        };
        let (q, p, qm) = (rq(), rq(), rq());
        let mut rv = || {
            Vec3::new(
                c(rng.random_range(-5.0..5.0)),
                c(rng.random_range(-5.0..5.0)),
                c(rng.random_range(-5.0..5.0)),
            )
        };
        let (t, tm) = (rv(), rv());
        let m = q.to_rotation_matrix();
        if let Ok(back) = Quat::from_rotation_matrix(&m) {
            worst[0] = worst[0].max(rel(
                &to64(back.to_rotation_matrix().to_row_major()),
                &to64(m.to_row_major()),
            ));
        }
        let order = orders[rng.random_range(0..orders.len())];
        if let Ok(e) = q.to_euler(order) {
            let b = Quat::from_euler(order, e.angles);
            let b = if b.dot(q) < T::ZERO { -b } else { b };
            worst[1] = worst[1].max(rel(&to64(b.to_array()), &to64(q.to_array())));
        }
        let scaled = q * c(rng.random_range(0.1..3.0));
        if let Ok(l) = scaled.log() {
            worst[2] = worst[2].max(rel(&to64(l.exp().to_array()), &to64(scaled.to_array())));
        }
        worst[3] = worst[3].max(rel(
            &[(scaled * p).norm().to_f64()],
            &[(scaled.norm() * p.norm()).to_f64()],
        ));
        let dq = DualQuat::from_rotation_translation(q, t);
        if let Ok(b) = DualQuat::from_matrix4(&dq.to_matrix4()) {
            worst[4] = worst[4].max(rel(
                &to64(b.to_matrix4().to_row_major()),
                &to64(dq.to_matrix4().to_row_major()),
            ));
        }
        if let Ok(b) = dq.to_screw().and_then(|s| DualQuat::from_screw(&s)) {
            worst[5] = worst[5].max(rel(&to64(b.to_array()), &to64(dq.to_array())));
        }
        if let Ok(l) = dq.log() {
            worst[6] = worst[6].max(rel(&to64(l.exp().to_array()), &to64(dq.to_array())));
        }
        let mm = DualQuat::from_rotation_translation(qm, tm);
        if let (Ok(a), Ok(b)) = ((mm * dq * mm.conjugate()).log(), dq.log()) {
            let b = mm * b * mm.conjugate();
            worst[7] = worst[7].max(rel(&to64(a.to_array()), &to64(b.to_array())));
        }
    }
    names.into_iter().zip(worst).collect()
}
