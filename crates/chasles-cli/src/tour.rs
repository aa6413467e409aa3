//! `chasles tour`: a walk through both papers on built-in data, with every number computed
//! on the spot — the core algebra (Dam et al. §3.3, App. A and B; Kavan et al. §3),
//! interpolation (Dam et al. ch. 5–7), blending (Kavan et al. §4, §5, Table 1, Figure 7)
//! and skinning (Kavan et al. §6) — printed to the terminal and written as a report
//! (`--out`, default `report/`): one HTML page with every claim, our measurement, whether
//! they agree, and the pictures (see [`crate::report`]).

use crate::report::Report;
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
use std::path::PathBuf;

/// Options of `chasles tour`.
pub struct TourArgs {
    /// Random inputs per identity in the sweep.
    pub samples: usize,
    /// Seed of the random inputs.
    pub seed: u64,
    /// The report's folder.
    pub out: PathBuf,
}

/// Progress on a terminal (stderr), nothing when piped.
fn stage(what: &str) {
    let mut e = std::io::stderr();
    if e.is_terminal() {
        let _ = write!(e, "\r\x1b[2K  tour: {what} …");
        let _ = e.flush();
    }
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
    let mut rep = Report::new(&args.out)?;
    stage("core algebra");
    rep.section("Dam et al. App. A and B; Kavan et al. §3: the core algebra");

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
        if k == 8 {
            rep.claim(
                "App. B.4 recovers the quaternion from the trace, dividing by 4s with s = cos(angle/2): it loses accuracy as the angle nears 180° (our fix: Shepperd's largest-diagonal choice)",
                format!("at π − 1e-8: trace-only error {t:.1e}, ours {s:.1e}"),
                t > 1e3 * s && s < 1e-12,
            );
        }
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
    rep.claim(
        "App. B.2: at β = π/2 only α − γ is determined; setting γ = 0 still rebuilds the matrix",
        format!(
            "extracted γ = {:.1e}, rebuilt matrix error {rebuilt:.1e}",
            e.angles[2]
        ),
        e.gimbal_lock && e.angles[2] == 0.0 && rebuilt < 1e-12,
    );

    heading("Dam et al. Definitions 14–16: exp, log and powers near the identity and near 2π");
    println!("  rotation angle      |exp(log q) − q|   |(q^½)² − q|");
    let mut worst_exp = 0.0f64;
    for d in [1e-12, 1e-6, 1e-2] {
        for (label, q) in [
            (format!("{d:.0e}"), Quat::from_axis_angle(axis, d)?),
            (format!("2π − {d:.0e}"), -Quat::from_axis_angle(axis, d)?),
        ] {
            let e1 = (q.log()?.exp() - q).norm();
            let h = q.powf(0.5)?;
            let e2 = (h * h - q).norm();
            println!("  {label:<18}  {e1:<17.1e}  {e2:.1e}");
            worst_exp = worst_exp.max(e1).max(e2);
        }
    }
    rep.claim(
        "Definitions 14–16: exp(log q) = q and (q^½)² = q, including next to the identity and to 2π where sin(θ)/θ and log need care",
        format!("worst error over angles 1e-12 … 2π − 1e-12: {worst_exp:.1e}"),
        worst_exp < 1e-12,
    );

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

    interpolation(&mut rep)?;
    blending(&mut rep)?;
    skinning(&mut rep)?;
    stage("identities on random inputs");

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
    rep.section("Identities on random inputs, f64 and f32");
    let mut rows = vec![vec![
        "identity".to_string(),
        "worst f64".into(),
        "worst f32".into(),
    ]];
    for ((name, a), (_, b)) in r64.iter().zip(r32.iter()) {
        println!("  {a:>9.1e} {b:>9.1e}  {name}");
        rows.push(vec![
            name.to_string(),
            format!("{a:.1e}"),
            format!("{b:.1e}"),
        ]);
    }
    let w64 = r64.iter().fold(0.0f64, |m, x| m.max(x.1));
    let w32 = r32.iter().fold(0.0f64, |m, x| m.max(x.1));
    rep.claim(
        "The identities of both papers (conversions round-trip, Lemma 1, exp/log, bi-invariance) hold on every input",
        format!(
            "worst relative error over {} random inputs: {w64:.1e} (f64), {w32:.1e} (f32)",
            args.samples
        ),
        w64 < 1e-12 && w32 < 1e-5,
    );
    rep.table(&rows);
    println!("\nTolerances the test suite demands: 1e-12 (f64) and 1e-5 (f32). Run `cargo test --workspace`.");
    let path = rep.finish()?;
    if std::io::stderr().is_terminal() {
        eprint!("\r\x1b[2K");
    }
    let (ok, n) = rep.tally();
    println!("\nreport: {} ({ok} of {n} claims agree)", path.display());
    Ok(())
}

/// The largest max/min ratio of the speed `v` inside one interval between keys (frames
/// next to a key left out): 1 for constant speed. The worst interval, not the whole curve,
/// because whole frame counts per interval make the step differ slightly from one interval
/// to the next even for a constant-speed method.
fn speed_ratio_within_intervals(frames: &[chasles::interp::Frame<f64>], v: &[f64]) -> f64 {
    let mut per_interval: Vec<(f64, f64)> = Vec::new();
    let mut interval = 0;
    for (w, s) in frames.windows(3).zip(&v[1..]) {
        if w[1].key.is_some() {
            interval += 1;
        }
        if w.iter().any(|f| f.key.is_some()) {
            continue;
        }
        if per_interval.len() <= interval {
            per_interval.resize(interval + 1, (f64::MAX, 0.0));
        }
        let r = &mut per_interval[interval];
        *r = (r.0.min(*s), r.1.max(*s));
    }
    per_interval
        .iter()
        .filter(|r| r.1 > 0.0)
        .map(|r| r.1 / r.0)
        .fold(1.0f64, f64::max)
}

fn energy(f: &[chasles::interp::Frame<f64>]) -> f64 {
    curvature_energy(&f.iter().map(|x| x.q).collect::<Vec<_>>(), Width::Unit)
}

/// Dam et al. chapters 5–7 on the built-in key sets.
fn interpolation(rep: &mut Report) -> anyhow::Result<()> {
    stage("interpolation");
    heading("Dam et al. ch. 5–6: Table 5.1's six keys, 550 frames shared by interval angle (§6.2)");
    rep.section(
        "Dam et al. ch. 5–6: six methods through Table 5.1's keys (550 frames, §6.2 timing)",
    );
    let set = examples::table_5_1();
    let keys = KeyFrames::new(&set.keys::<f64>(), None, Hemisphere::Chain)?;
    println!("  method      curvature energy (eq. 6.23)   speed max/min within an interval");
    let mut rows = vec![vec![
        "method".to_string(),
        "curvature energy (eq. 6.23)".into(),
        "speed max/min within an interval (worst)".into(),
    ]];
    let mut ratios = std::collections::HashMap::new();
    let mut pictures = Vec::new();
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
        let (e, ratio) = (energy(&frames), speed_ratio_within_intervals(&frames, &v));
        println!("  {name:<10}  {e:<28.4e}  {ratio:.3}");
        rows.push(vec![
            name.to_string(),
            format!("{e:.4e}"),
            format!("{ratio:.3}"),
        ]);
        ratios.insert(name, ratio);
        let keys_at = chasles_viz::graph::key_indices(&frames);
        let title = format!("{name}: angular velocity (Dam et al. eq. 5.1), Table 5.1 keys");
        let svg = chasles_viz::graph::velocity_svg(&v, &keys_at, &title);
        let png = chasles_viz::sphere::render_frames(&frames, 420).png();
        pictures.push((name, svg, png));
    }
    rep.table(&rows);
    let r = |n: &str| ratios.get(n).copied().unwrap_or(f64::NAN);
    rep.claim(
        "§5.2, Figure 5.5: Slerp moves at constant angular velocity between keys",
        format!(
            "Slerp speed max/min inside the intervals: {:.6}",
            r("slerp")
        ),
        (r("slerp") - 1.0).abs() < 1e-3,
    );
    rep.claim(
        "§5.2, Figures 5.4 and 5.6: LinEuler and LinMat do not move at constant velocity",
        format!(
            "speed max/min within an interval, worst interval: LinEuler {:.3}, LinMat {:.3}",
            r("lineuler"),
            r("linmat")
        ),
        r("lineuler") > 1.05 && r("linmat") > 1.05,
    );
    for (name, svg, png) in pictures {
        rep.figure(
            &format!("velocity-{name}.svg"),
            svg.as_bytes(),
            &format!(
                "§5.2: angular velocity of {name} against the frame index; * marks the key frames"
            ),
        )?;
        if matches!(name, "lineuler" | "lerp" | "slerp" | "squad") {
            rep.figure(
                &format!("sphere-{name}.png"),
                &png,
                &format!("§5.3: the {name} curve on the unit sphere (z = 0 for all of Table 5.1's keys); first key large, keys medium, frames small; frames inside the sphere show dimmed"),
            )?;
        }
    }
    let squad = interpolate(Method::Squad, &keys, 96, Timing::Angle)?;
    let turned: Vec<Quat<f64>> = squad.iter().map(|f| f.q).collect();
    rep.figure(
        "letter-squad.gif",
        &chasles_viz::gif(&chasles_viz::letter::animate(&turned, 240), 5)?,
        "§5.1, direct visualisation: an extruded R turned by the 96 Squad frames through Table 5.1's keys",
    )?;
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
    let (jq, js) = (
        jump(&|i, h| sq.eval(i, h)),
        jump(&|i, h| slerp(q[i], q[i + 1], h)),
    );
    println!(
        "  Squad is C¹ at the keys (Proposition 30): largest jump of dq/dh {jq:.1e}; Slerp's {js:.2}"
    );
    rep.claim(
        "Proposition 30: Squad is C¹ at the key frames (Slerp is not)",
        format!("largest jump of dq/dh at a key: Squad {jq:.1e}, Slerp {js:.2}"),
        jq < 1e-3 && js > 0.1,
    );

    heading("Dam et al. ch. 7: Spring against Squad on the chapter's examples (200 frames)");
    println!("  set          Slerp start   Squad         Spring        Spring / Squad");
    stage("Spring on the chapter 7 examples");
    rep.section("Dam et al. ch. 7: Spring against Squad");
    let mut worst_ratio = 0.0f64;
    let mut rows = vec![vec![
        "set".to_string(),
        "Slerp".into(),
        "Squad".into(),
        "Spring".into(),
        "Spring / Squad".into(),
    ]];
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
        worst_ratio = worst_ratio.max(sp / sq);
        rows.push(vec![
            format!("{} ({})", set.name, set.section),
            format!("{sl:.4e}"),
            format!("{sq:.4e}"),
            format!("{sp:.4e}"),
            format!("{:.3}", sp / sq),
        ]);
    }
    rep.claim(
        "Ch. 7: Spring's curves are smoother than Squad's (lower curvature energy, eq. 6.23) on the chapter's examples",
        format!("largest Spring / Squad energy ratio over the examples: {worst_ratio:.3}"),
        worst_ratio < 1.0,
    );
    rep.table(&rows);
    Ok(())
}

/// Kavan et al. 2006 by number: Table 1 measured and the paper's claims.
fn blending(rep: &mut Report) -> anyhow::Result<()> {
    use chasles::analysis::{claims, properties};
    use chasles_viz::bars::bars_svg;
    use chasles_viz::grid::{grid_svg, GridCell};
    use chasles_viz::plot::{lines_svg, Series};
    stage("blending: Table 1");
    heading("Kavan et al. Table 1, measured on 50 random cases per property");
    rep.section("Kavan et al. Table 1: properties of the blending methods, measured");
    let t = properties::measure(50, 2006)?;
    let md = properties::to_markdown(&t);
    print!("{md}");
    let rows: Vec<Vec<String>> = md
        .lines()
        .filter(|l| l.starts_with('|') && !l.starts_with("|-") && !l.starts_with("| -"))
        .map(|l| {
            l.trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect();
    let listed: usize = t
        .rows
        .iter()
        .map(|r| r.cells().iter().filter(|c| c.1.paper.is_some()).count())
        .sum();
    let agree = listed - t.disagreements().len();
    println!("  {agree} of {listed} cells the paper lists agree with it.");
    rep.claim(
        "Table 1: which methods are bi-invariant, constant-speed, coordinate-invariant, shortest-path, closed-form, and how they scale with n",
        format!("{agree} of {listed} cells measured on 50 random cases per property agree"),
        agree == listed,
    );
    rep.table(&rows);
    let names: Vec<&str> = t.rows.iter().map(|r| r.method.name()).collect();
    let columns: Vec<&str> = t.rows[0].cells().iter().map(|c| c.0).collect();
    let cells: Vec<Vec<GridCell>> = t
        .rows
        .iter()
        .map(|r| {
            r.cells()
                .iter()
                .map(|(_, c)| GridCell {
                    value: c.worst,
                    holds: c.holds,
                    agrees: c.agrees(),
                })
                .collect()
        })
        .collect();
    rep.figure(
        "table1.svg",
        grid_svg(&names, &columns, &cells, "Table 1 measured: worst deviation per method and property").as_bytes(),
        "Table 1 as measured: each cell the worst deviation over 50 random cases; green holds, red fails, a frame marks a disagreement with the paper",
    )?;
    // Two transforms 170° apart: what each method does along the way.
    let x = [
        DualQuat::identity(),
        DualQuat::from_rotation_translation(
            Quat::from_axis_angle(Vec3::new(0.0, 0.0, 1.0), 170f64.to_radians())?,
            Vec3::new(3.0, 1.0, 0.0),
        ),
    ];
    let opt = chasles::blend::Options::default();
    let case = crate::blend_pictures::Case {
        x: &x,
        w: &[0.5, 0.5],
        opt: &opt,
    };
    rep.figure(
        "blend-path.svg",
        crate::blend_pictures::plot(&case)?.as_bytes(),
        "Two transforms 170° apart, weights (1 − t, t): the rotation every method produces. ScLERP (dashed) is a straight line, constant speed; DLB stays within 8.15° of it; Lin's rotation part races through the middle",
    )?;
    rep.figure(
        "blend-render.png",
        &crate::blend_pictures::render(&case)?.png(),
        "The same two transforms (grey) and each method's 50/50 blend (red): Lin's matrix shrinks the letter to a sliver, the rigid methods keep it whole",
    )?;
    stage("blending: the claims");
    rep.section("Kavan et al. §4, §5, Appendix B: the claims");
    heading("Kavan et al. §4, §5, Appendix B: the claims");
    let d = claims::dlb_vs_sclerp(100, 1)?;
    println!(
        "  DLB vs ScLERP: angle differs by at most {:.4}° (paper: < 8.15°), slide by at most {:.3} % (paper: < 15 %); same screw axis within {:.0e}",
        d.angle_deg,
        d.translation * 100.0,
        d.axis
    );
    rep.claim(
        "§4: DLB's rotation angle differs from ScLERP's by less than 8.15°",
        format!("worst over θ ∈ (0, π], t ∈ [0, 1]: {:.4}°", d.angle_deg),
        d.angle_deg < 8.15,
    );
    rep.claim(
        "§4: DLB's translation along the axis differs from ScLERP's by less than 15 %",
        format!(
            "worst: {:.3} % (the supremum, at θ → π, is just over the paper's rounded 15 %)",
            d.translation * 100.0
        ),
        d.translation < 0.15 + 1e-9,
    );
    rep.claim(
        "§4: DLB and ScLERP share the screw axis",
        format!(
            "largest axis difference over 100 random pairs: {:.0e}",
            d.axis
        ),
        d.axis < 1e-9,
    );
    let mut series = Vec::new();
    for (deg, colour) in [
        (60.0f64, "#2e7d32"),
        (120.0, "#1f5fbf"),
        (170.0, "#c0392b"),
        (179.9, "#7b1fa2"),
    ] {
        let pts = (0..=100)
            .map(|k| {
                let t = k as f64 / 100.0;
                let (da, _) = claims::dlb_sclerp_difference(deg.to_radians(), t)?;
                Ok((t, da.to_degrees()))
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        series.push((format!("θ = {deg}°"), colour, pts));
    }
    let ser: Vec<Series> = series
        .iter()
        .map(|(n, c, p)| Series {
            name: n,
            colour: c,
            dashed: false,
            points: p.clone(),
        })
        .collect();
    rep.figure(
        "dlb-vs-sclerp.svg",
        lines_svg(&ser, "DLB − ScLERP rotation angle, two transforms θ apart", "t", "degrees").as_bytes(),
        "§4: the angle difference between DLB and ScLERP over t, growing with θ towards the 8.15° bound",
    )?;
    let (diff, it) = claims::lemma_3(100, 2)?;
    println!("  Lemma 3: DIB of two transforms = ScLERP within {diff:.0e}, after {it} update");
    rep.claim(
        "Lemma 3: DIB of two transforms is ScLERP",
        format!("largest difference over 100 random pairs: {diff:.0e}, after {it} update"),
        diff < 1e-9,
    );
    let l2 = claims::lemma_2(100, 3)?;
    println!("  Lemma 2: ScLERP bi-invariant within {l2:.0e}");
    rep.claim(
        "Lemma 2: ScLERP is bi-invariant",
        format!("largest violation over 100 random cases: {l2:.0e}"),
        l2 < 1e-9,
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
    rep.claim(
        "Figure 7 / Appendix B: log-matrix blending does not move at constant angular speed; ‖ω_t‖ follows the closed form",
        format!("‖ω_t‖ from {lo:.6} to {hi:.6}; largest gap to the closed form {:.0e}", f7.worst),
        hi - lo > 1e-3 && f7.worst < 1e-6,
    );
    let pts = |f: &dyn Fn(f64) -> anyhow::Result<f64>| {
        (0..=100)
            .map(|k| {
                let t = k as f64 / 100.0;
                Ok((t, f(t)?))
            })
            .collect::<anyhow::Result<Vec<_>>>()
    };
    let measured = pts(&|t| Ok(claims::omega_measured(t)?))?;
    let closed = pts(&|t| Ok(claims::omega_closed_form(t)))?;
    let ser = [
        Series {
            name: "measured",
            colour: "#1f5fbf",
            dashed: false,
            points: measured,
        },
        Series {
            name: "Appendix B",
            colour: "#c0392b",
            dashed: true,
            points: closed,
        },
    ];
    rep.figure(
        "figure7.svg",
        lines_svg(&ser, "Figure 7: ‖ω_t‖ of log-matrix blending", "t", "‖ω_t‖").as_bytes(),
        "Figure 7: the angular speed of log-matrix blending, measured by finite differences, against Appendix B's closed form",
    )?;
    let h = claims::dib_iterations(200, 4, 30f64.to_radians(), 1e-6)?;
    println!(
        "  DIB updates for rotations within 30° (2–8 inputs): {:?} (index = updates)",
        h
    );
    let total: usize = h.iter().sum();
    let within4: usize = h.iter().take(5).sum();
    rep.claim(
        "§5: DIB typically converges in 1 to 4 iterations (skinning-like spreads)",
        format!(
            "{within4} of {total} blends (2–8 transforms, rotations within 30°) took at most 4 updates; the most was {}",
            h.len().saturating_sub(1)
        ),
        within4 * 100 >= total * 95,
    );
    let mut rows = vec![vec!["updates".to_string(), "blends".into()]];
    rows.extend(
        h.iter()
            .enumerate()
            .filter(|(_, c)| **c > 0)
            .map(|(k, c)| vec![k.to_string(), c.to_string()]),
    );
    rep.table(&rows);
    let labels: Vec<String> = (0..h.len()).map(|k| k.to_string()).collect();
    rep.figure(
        "dib-iterations.svg",
        bars_svg(&labels, &h, "DIB: updates to reach precision 1e-6", "updates").as_bytes(),
        "How many updates DIB took on 200 random blends of 2–8 transforms with rotations within 30° of each other",
    )?;
    Ok(())
}

/// A character the tour skins: its file name (never a path), the clip to play, its credit.
struct Character {
    file: String,
    clip: String,
    credit: String,
    rig: chasles_skin::Rig,
}

/// The characters: CesiumMan's walk and Fox's run, built in (`chasles-models`), then every
/// other `.glb`/`.gltf` in `$CHASLES_DATA` if that is set (first clip). A file there that
/// does not load is reported and left out.
fn characters() -> anyhow::Result<Vec<Character>> {
    use chasles_skin::gltf_load;
    let mut out = Vec::new();
    for (m, clip) in [
        (chasles_models::CESIUM_MAN, ""),
        (chasles_models::FOX, "Run"),
    ] {
        out.push(Character {
            file: m.file.into(),
            clip: clip.into(),
            credit: m.credit.into(),
            rig: gltf_load::load_slice(m.bytes, m.file)?,
        });
    }
    let Some(dir) = std::env::var_os("CHASLES_DATA") else {
        return Ok(out);
    };
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
        .map_err(|e| anyhow::anyhow!("CHASLES_DATA={}: {e}", dir.to_string_lossy()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("glb") | Some("gltf")
            )
        })
        .collect();
    files.sort();
    for path in files {
        let file = path
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        if out.iter().any(|c| c.file == file) {
            continue;
        }
        match gltf_load::load(&path) {
            Ok(rig) if !rig.animations.is_empty() => out.push(Character {
                credit: format!("{file} from $CHASLES_DATA (its own licence applies)"),
                file,
                clip: String::new(),
                rig,
            }),
            Ok(_) => println!("  ($CHASLES_DATA/{file} has no animation: left out)"),
            Err(e) => println!("  ($CHASLES_DATA/{file} does not load, left out: {e})"),
        }
    }
    Ok(out)
}

/// Kavan et al. 2006, §6: the candy wrapper and the real characters.
fn skinning(rep: &mut Report) -> anyhow::Result<()> {
    use crate::pictures;
    use chasles_skin::cylinder::{self, Motion};
    use chasles_skin::{Method, Pose};
    stage("skinning: the candy wrapper");
    heading("Kavan et al. §6 / Figure 6: the candy wrapper on a two-bone cylinder");
    rep.section("Kavan et al. §6, Figures 1 and 6: skinning a two-bone cylinder");
    let rig = cylinder::twisted_cylinder();
    println!("  twist   LBS middle radius   DQS middle radius   (relative to rest)");
    let mut at180 = (f32::NAN, f32::NAN);
    for deg in [0.0f32, 90.0, 135.0, 180.0] {
        let l = cylinder::measure(&rig, Method::Lbs, Motion::Twist, deg.to_radians())?;
        let d = cylinder::measure(&rig, Method::Dqs, Motion::Twist, deg.to_radians())?;
        println!("  {deg:>4}°   {:<19.3} {:.3}", l.radius, d.radius);
        at180 = (l.radius, d.radius);
    }
    rep.claim(
        "Figure 1 / §6: linear blend skinning collapses a joint twisted by 180° to a point (the candy wrapper); dual-quaternion skinning keeps its shape",
        format!(
            "middle radius at 180° twist, relative to rest: LBS {:.3}, DQS {:.3}",
            at180.0, at180.1
        ),
        at180.0 < 0.05 && (at180.1 - 1.0).abs() < 0.02,
    );
    rep.figure(
        "twist-radius.svg",
        pictures::twist_plot()?.as_bytes(),
        "The middle radius against the twist angle for every method: LBS follows cos(θ/2) (dashed; the blended matrix there is (I + Rx(θ))/2) down to 0 at 180°, every rigid method keeps 1",
    )?;
    let pose = cylinder::pose(&rig, Motion::Twist, std::f32::consts::PI);
    rep.figure(
        "cylinder-twist.png",
        &pictures::methods_side_by_side(&rig, &pose, &Method::ALL)?.png(),
        "The cylinder's second bone twisted 180° about its axis, every method: LBS collapses to a point, the others keep the radius",
    )?;
    let pose = cylinder::pose(&rig, Motion::Bend, 120f32.to_radians());
    rep.figure(
        "cylinder-bend.png",
        &pictures::methods_side_by_side(&rig, &pose, &Method::ALL)?.png(),
        "The same cylinder bent 120°: LBS thins at the elbow, DQS keeps the volume and bulges slightly outward",
    )?;
    rep.figure(
        "twist-sweep.gif",
        &chasles_viz::gif(&pictures::twist_sweep(25)?, 6)?,
        "The twist swept 0° → 180° → 0°: LBS (left) against DQS (right)",
    )?;
    let l = cylinder::measure(&rig, Method::Lbs, Motion::Bend, 150f32.to_radians())?;
    let d = cylinder::measure(&rig, Method::Dqs, Motion::Bend, 150f32.to_radians())?;
    println!(
        "  bend 150°: LBS thins to {:.3} and loses {:.1} % volume; DQS keeps the radius and bulges {:.1} % out",
        l.radius,
        (1.0 - l.volume) * 100.0,
        (d.bulge - 1.0) * 100.0
    );
    rep.claim(
        "§6: on bending, LBS loses volume at the joint while DQS keeps it, at the price of a slight bulge",
        format!(
            "bend 150°: LBS radius {:.3}, volume {:.3}; DQS radius {:.3}, volume {:.3}, bulge {:.3}",
            l.radius, l.volume, d.radius, d.volume, d.bulge
        ),
        l.volume < 0.97 && d.radius > 0.95 && d.bulge > 1.0,
    );
    stage("skinning: the characters");
    rep.section("Kavan et al. §6 on real characters");
    heading("Real characters: where linear blending loses volume (smallest det of the blended 3×3 over the clip)");
    for ch in characters()? {
        let (file, clip, credit, rig) = (&ch.file, ch.clip.as_str(), &ch.credit, &ch.rig);
        let c = rig
            .animations
            .iter()
            .position(|a| a.name == clip)
            .unwrap_or(0);
        let over = chasles_skin::volume::lbs_volume_over_clip(rig, c, 40)?;
        let (worst_t, worst) =
            over.iter()
                .copied()
                .fold((0.0, f32::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        println!(
            "  {file} ({} vertices, {} joints): LBS down to {worst:.2} of the local volume; DQS keeps 1 (rigid blends)",
            rig.mesh.positions.len(),
            rig.joints.len()
        );
        println!("    credit: {credit}");
        rep.claim(
            "§6: linear blending of joint matrices shrinks the mesh where joints turn apart; DQS blends only rigid motions",
            format!("{file}: smallest det of LBS's blended 3×3 over the clip {worst:.2} (DQS: 1)"),
            worst < 0.95,
        );
        let name = file
            .rsplit_once('.')
            .map_or(file.as_str(), |(s, _)| s)
            .to_lowercase();
        rep.figure(
            &format!("{name}-volume.svg"),
            pictures::volume_plot(rig, c)?.as_bytes(),
            &format!("{file}: LBS's smallest local volume at 41 times of its clip; rigid blends keep 1. Credit: {credit}"),
        )?;
        let (sphere, joint) = pictures::rotation_sphere(rig, c)?;
        rep.figure(
            &format!("{name}-sphere.png"),
            &sphere.png(),
            &format!("{file}: the rotation of {joint}, the joint that turns most in the clip, on the unit sphere (§5.3's plot on real data): its keys and the sampled curve. Credit: {credit}"),
        )?;
        let pose = Pose::animated(rig, c, worst_t)?;
        rep.figure(
            &format!("{name}.png"),
            &pictures::methods_side_by_side(rig, &pose, &Method::ALL)?.png(),
            &format!("{file} at t = {worst_t:.2} s of its clip, where LBS loses the most volume, skinned by every method. Credit: {credit}"),
        )?;
        rep.figure(
            &format!("{name}-closeup.png"),
            &pictures::methods_closeup(rig, &pose, &Method::ALL)?.png(),
            &format!("{file}, the same pose, close up around the vertex where LBS keeps the least volume ({worst:.2}): LBS pinches, the rigid blends keep the limb's thickness"),
        )?;
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
