//! Kavan et al. 2006's claims by number ([`crate::claims`]): §4 (DLB within 8.15° and
//! 15 % of ScLERP, on the same screw axis; DIB converges in 1 to 4 updates), Lemma 3 (DIB
//! of two transforms is ScLERP), Lemma 2 (ScLERP is bi-invariant), Appendix B / Figure 7
//! (log-matrix blending is not constant speed), and §5's iterative log-matrix blend.

use super::Figures;
use crate::claim::Paper::Kavan2006;
use crate::claims;
use crate::error::Result;
use crate::section::Section;
use crate::table::{Cell, Number, Table};
use chasles_viz::bars::bars_svg;
use chasles_viz::plot::{lines_svg, Series};

/// The rotation spreads of the DIB update counts, degrees; the claim reads the first.
const SPREADS: [f64; 4] = [30.0, 60.0, 90.0, 180.0];

/// Every claim on `samples` random cases from `seed`, with the pictures if asked.
pub fn blending_claims(samples: usize, seed: u64, figures: Figures) -> Section {
    let mut s = Section::new(format!(
        "Kavan et al. §4, §5, Appendix B: the claims ({samples} random cases, seed {seed})"
    ));
    dlb_vs_sclerp(&mut s, samples, seed, figures);
    s.attempt(
        Kavan2006,
        "Lemma 3",
        "DIB of two transforms is ScLERP",
        |_| -> Result<_> {
            let (diff, it) = claims::lemma_3(samples, seed)?;
            Ok((
                format!("largest difference over {samples} random pairs: {diff:.0e}, after at most {it} update(s)"),
                diff < 1e-9,
            ))
        },
    );
    s.attempt(
        Kavan2006,
        "Lemma 2",
        "ScLERP is bi-invariant",
        |_| -> Result<_> {
            let l2 = claims::lemma_2(samples, seed)?;
            Ok((
                format!("largest violation over {samples} random triples: {l2:.0e}"),
                l2 < 1e-9,
            ))
        },
    );
    figure_7(&mut s, figures);
    dib_updates(&mut s, samples, seed, figures);
    s.attempt(
        Kavan2006,
        "§5",
        "if we replace dual quaternions by matrices, and the initial value of b̂ by the identity (instead of DLB), we obtain an iterative version of Alexa's method [...] In subsequent iterations, the modified DIB algorithm converges to a constant speed and shortest path solution",
        |_| -> Result<_> {
            let (id, piv) = claims::log_iter_reaches_sclerp(samples, seed)?;
            Ok((
                format!(
                    "started at the identity it reaches ScLERP (to 1e-8) on {:.1} % of {samples} random pairs; started at the heavier input, {:.1} %",
                    id * 100.0,
                    piv * 100.0
                ),
                id >= 0.99,
            ))
        },
    );
    s
}

/// §4: DLB against ScLERP — the angle and slide bounds and the shared axis.
fn dlb_vs_sclerp(s: &mut Section, samples: usize, seed: u64, figures: Figures) {
    let d = claims::dlb_vs_sclerp(samples, seed).map_err(|e| e.to_string());
    s.attempt(
        Kavan2006,
        "§4",
        "DLB's rotation angle differs from ScLERP's by less than 8.15°",
        |_| {
            let d = d.as_ref()?;
            Ok::<_, &String>((
                format!(
                    "worst over θ ∈ (0, π], t ∈ [0, 1]: {:.4}° at θ = {:.4}, t = {:.4}",
                    d.angle_deg, d.angle_at.0, d.angle_at.1
                ),
                d.angle_deg < 8.15,
            ))
        },
    );
    s.attempt(
        Kavan2006,
        "§4",
        "DLB's translation along the axis differs from ScLERP's by less than 15 %",
        |_| {
            let d = d.as_ref()?;
            Ok::<_, &String>((
                format!(
                    "worst: {:.4} % at θ = {:.4}, t = {:.4} (the supremum, exactly 15.014 % at θ = π, is just over the paper's rounded 15 %)",
                    d.translation * 100.0,
                    d.translation_at.0,
                    d.translation_at.1
                ),
                d.translation < 0.15 + 1e-9,
            ))
        },
    );
    s.attempt(
        Kavan2006,
        "§4",
        "DLB and ScLERP share the screw axis",
        |_| {
            let d = d.as_ref()?;
            Ok::<_, &String>((
                format!(
                    "largest axis difference over {samples} random pairs: {:.0e}",
                    d.axis
                ),
                d.axis < 1e-9,
            ))
        },
    );
    if figures == Figures::Draw {
        let svg = (|| -> Result<Vec<u8>> {
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
                    .collect::<Result<Vec<_>>>()?;
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
            Ok(lines_svg(
                &ser,
                "DLB − ScLERP rotation angle, two transforms θ apart",
                "t",
                "degrees",
            )
            .into_bytes())
        })();
        s.try_figure(
            "dlb-vs-sclerp.svg",
            svg,
            "§4: the angle difference between DLB and ScLERP over t, growing with θ towards the 8.15° bound",
        );
    }
}

/// Appendix B / Figure 7: ‖ω_t‖ of our log-matrix blend against the closed form.
fn figure_7(s: &mut Section, figures: Figures) {
    s.attempt(
        Kavan2006,
        "Figure 7, Appendix B",
        "log-matrix blending does not move at constant angular speed; ‖ω_t‖ follows the closed form",
        |s| -> Result<_> {
            let f7 = claims::figure_7()?;
            let mut t = Table::new(
                format!("‖ω_t‖ of our blend of R0, R1 against Appendix B's closed form; largest difference over 101 points {:.1e}", f7.worst),
                &["t", "measured ‖ω_t‖", "closed form"],
            );
            for r in &f7.rows {
                t.row(vec![
                    Cell::Number(Number::fixed(r[0], 1)),
                    Cell::Number(Number::fixed(r[1], 9)),
                    Cell::Number(Number::fixed(r[2], 9)),
                ]);
            }
            s.table(t);
            if figures == Figures::Draw {
                let pts = |f: &dyn Fn(f64) -> Result<f64>| {
                    (0..=100)
                        .map(|k| {
                            let t = k as f64 / 100.0;
                            Ok((t, f(t)?))
                        })
                        .collect::<Result<Vec<_>>>()
                };
                let ser = [
                    Series {
                        name: "measured",
                        colour: "#1f5fbf",
                        dashed: false,
                        points: pts(&|t| claims::omega_measured(t))?,
                    },
                    Series {
                        name: "Appendix B",
                        colour: "#c0392b",
                        dashed: true,
                        points: pts(&|t| Ok(claims::omega_closed_form(t)))?,
                    },
                ];
                s.paper_figure(
                    crate::section::PaperFigure::new(Kavan2006, "7", "Graph of ‖ω_t‖ for t ∈ [0, 1]"),
                    "figure7.svg",
                    Ok::<_, String>(lines_svg(&ser, "Figure 7: ‖ω_t‖ of log-matrix blending", "t", "‖ω_t‖").into_bytes()),
                    "Figure 7: the angular speed of log-matrix blending, measured by finite differences, against Appendix B's closed form",
                );
            }
            let (lo, hi) = f7
                .rows
                .iter()
                .fold((f64::MAX, 0.0f64), |(a, b), r| (a.min(r[1]), b.max(r[1])));
            Ok((
                format!("‖ω_t‖ from {lo:.6} to {hi:.6}; largest gap to the closed form {:.0e}", f7.worst),
                hi - lo > 1e-3 && f7.worst < 1e-6,
            ))
        },
    );
}

/// §4: DIB's update counts for rotations within 30°, 60°, 90° and 180°.
fn dib_updates(s: &mut Section, samples: usize, seed: u64, figures: Figures) {
    // One histogram per spread, measured once for the table and both claims.
    let hists = SPREADS
        .iter()
        .map(|d| claims::dib_iterations(samples, seed, d.to_radians(), 1e-6))
        .collect::<Result<Vec<_>>>()
        .map_err(|e| e.to_string());
    // Blends done in at most 4 updates, and blends, of a histogram.
    let within4 = |h: &[usize]| (h.iter().take(5).sum::<usize>(), h.iter().sum::<usize>());
    s.attempt(
        Kavan2006,
        "§4",
        "DIB typically converges in 1 to 4 iterations (skinning-like spreads)",
        |s| -> std::result::Result<_, String> {
            let hists = hists.as_ref().map_err(Clone::clone)?;
            let mut t = Table::new(
                format!("DIB updates to precision 1e-6, {samples} blends of 2–8 random transforms with random weights"),
                &["rotations within", "1", "2", "3", "4", "5–9", "10–49", "≥ 50 (capped)"],
            );
            for (d, h) in SPREADS.iter().zip(hists) {
                let get = |a: usize, b: usize| {
                    (a..=b).map(|k| h.get(k).copied().unwrap_or(0)).sum::<usize>() as u64
                };
                let mut row = vec![Cell::text(format!("{d}°"))];
                for (a, b) in [(1, 1), (2, 2), (3, 3), (4, 4), (5, 9), (10, 49), (50, 50)] {
                    row.push(Cell::Number(Number::integer(get(a, b))));
                }
                t.row(row);
            }
            s.table(t);
            let h = &hists[0];
            if figures == Figures::Draw {
                let labels: Vec<String> = (0..h.len()).map(|k| k.to_string()).collect();
                s.figure(
                    "dib-iterations.svg",
                    bars_svg(&labels, h, "DIB: updates to reach precision 1e-6", "updates").into_bytes(),
                    &format!("How many updates DIB took on {samples} random blends of 2–8 transforms with rotations within 30° of each other"),
                );
            }
            let (done, total) = within4(h);
            Ok((
                format!(
                    "{done} of {total} blends (2–8 transforms, rotations within 30°) took at most 4 updates; the most was {}",
                    h.len().saturating_sub(1)
                ),
                done * 100 >= total * 95,
            ))
        },
    );
    // The same words against every spread: where the inputs spread past 90° it takes more.
    s.attempt(
        Kavan2006,
        "§4",
        "In practice, the DIB algorithm converges very quickly, typically in 1 to 4 steps",
        |_| -> std::result::Result<_, String> {
            let hists = hists.as_ref().map_err(Clone::clone)?;
            let counts: Vec<(usize, usize)> = hists.iter().map(|h| within4(h)).collect();
            let parts: Vec<String> = SPREADS
                .iter()
                .zip(&counts)
                .map(|(d, (done, total))| format!("within {d}°: {done} of {total}"))
                .collect();
            Ok((
                format!(
                    "on inputs spread up to 180°, blends done in at most 4 updates: {}",
                    parts.join(", ")
                ),
                counts.iter().all(|(done, total)| done * 100 >= total * 95),
            ))
        },
    );
}
