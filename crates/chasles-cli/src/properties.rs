//! `chasles properties`: Kavan et al. 2006, Table 1 measured, and with `--claims` the
//! paper's other claims by number (see `chasles::analysis::{properties, claims}`).

use anyhow::Result;
use chasles::analysis::{claims, properties};
use serde_json::{json, Value};

/// Output format.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Markdown tables and lines.
    Markdown,
    /// One JSON object.
    Json,
}

fn table_json(t: &properties::Table) -> Value {
    let rows: Vec<Value> = t
        .rows
        .iter()
        .map(|r| {
            let mut o = serde_json::Map::new();
            o.insert("method".into(), json!(r.method.name()));
            for (name, c) in r.cells() {
                o.insert(
                    name.into(),
                    json!({"holds": c.holds, "worst": if c.worst.is_nan() { Value::Null } else { json!(c.worst) },
                           "paper": c.paper, "agrees": c.agrees(), "note": c.note}),
                );
            }
            let flops: Vec<Value> = r
                .flops
                .measured
                .iter()
                .map(|(n, c, it)| json!({"n": n, "add": c.add, "mul": c.mul, "div": c.div, "special": c.special, "total": c.total(), "iterations": it}))
                .collect();
            o.insert(
                "flops".into(),
                json!({"measured": flops, "formula": r.flops.formula.map(|(a, b)| json!({"a": a, "b": b})), "paper": r.flops.paper}),
            );
            Value::Object(o)
        })
        .collect();
    json!({"samples": t.samples, "seed": t.seed, "tolerance": properties::TOLERANCE, "rows": rows})
}

/// All the claims, as (JSON, Markdown).
fn claims_report(samples: usize, seed: u64) -> Result<(Value, String)> {
    let d = claims::dlb_vs_sclerp(samples, seed)?;
    let (l3_diff, l3_iter) = claims::lemma_3(samples, seed)?;
    let l2 = claims::lemma_2(samples, seed)?;
    let spreads = [30.0f64, 60.0, 90.0, 180.0];
    let hists = spreads
        .iter()
        .map(|s| claims::dib_iterations(samples, seed, s.to_radians(), 1e-6))
        .collect::<chasles::Result<Vec<_>>>()?;
    let f7 = claims::figure_7()?;
    let (li_id, li_piv) = claims::log_iter_reaches_sclerp(samples, seed)?;
    let mut md = String::new();
    md.push_str("## Claims (Kavan et al. 2006)\n\n");
    md.push_str(&format!(
        "- §4, DLB vs ScLERP: largest rotation-angle difference {:.4}° at θ = {:.4}, t = {:.4} (paper: < 8.15°); largest slide difference {:.4} % at θ = {:.4}, t = {:.4} (paper: < 15 %; exactly 15.014 %, see the docs); same screw axis within {:.1e} over {} random pairs.\n",
        d.angle_deg, d.angle_at.0, d.angle_at.1, d.translation * 100.0, d.translation_at.0, d.translation_at.1, d.axis, samples
    ));
    md.push_str(&format!(
        "- Lemma 3, DIB of two transforms = ScLERP: largest difference {l3_diff:.1e}, at most {l3_iter} update(s) over {samples} random pairs.\n"
    ));
    md.push_str(&format!(
        "- Lemma 2, ScLERP bi-invariant: largest defect {l2:.1e} over {samples} random triples.\n"
    ));
    md.push_str("- §4, DIB \"typically converges in 1 to 4 steps\": updates to precision 1e-6, 2–8 random transforms with random weights:\n\n");
    md.push_str("| rotations within | 1 | 2 | 3 | 4 | 5–9 | 10–49 | ≥ 50 (capped) |\n|---|---|---|---|---|---|---|---|\n");
    for (s, h) in spreads.iter().zip(&hists) {
        let get = |a: usize, b: usize| {
            (a..=b.min(h.len().saturating_sub(1)))
                .map(|k| h.get(k).copied().unwrap_or(0))
                .sum::<usize>()
        };
        md.push_str(&format!(
            "| {s}° | {} | {} | {} | {} | {} | {} | {} |\n",
            get(1, 1),
            get(2, 2),
            get(3, 3),
            get(4, 4),
            get(5, 9),
            get(10, 49),
            get(50, 50)
        ));
    }
    md.push_str(&format!(
        "\n- Appendix B / Figure 7, log-matrix blending is not constant speed: ‖ω_t‖ of our blend of R0, R1 vs the closed form, largest difference {:.1e}:\n\n| t | measured ‖ω_t‖ | closed form |\n|---|---|---|\n",
        f7.worst
    ));
    for r in &f7.rows {
        md.push_str(&format!("| {:.1} | {:.9} | {:.9} |\n", r[0], r[1], r[2]));
    }
    md.push_str(&format!(
        "\n- §5, iterative log-matrix blending reaches ScLERP on two transforms in {:.1} % of random pairs when started at the identity (as §5 says), {:.1} % when started at the heavier input.\n",
        li_id * 100.0,
        li_piv * 100.0
    ));
    let j = json!({
        "dlb_vs_sclerp": {"angle_deg": d.angle_deg, "angle_at": [d.angle_at.0, d.angle_at.1], "translation": d.translation,
                          "translation_at": [d.translation_at.0, d.translation_at.1], "axis": d.axis},
        "lemma_3": {"difference": l3_diff, "max_updates": l3_iter},
        "lemma_2": {"defect": l2},
        "dib_updates": spreads.iter().zip(&hists).map(|(s, h)| json!({"spread_deg": s, "histogram": h})).collect::<Vec<_>>(),
        "figure_7": {"rows": f7.rows, "worst": f7.worst},
        "log_iter_reaches_sclerp": {"from_identity": li_id, "from_heavier_input": li_piv},
    });
    Ok((j, md))
}

/// Runs `chasles properties`.
pub fn run(samples: usize, seed: u64, format: Format, with_claims: bool) -> Result<()> {
    if samples == 0 {
        anyhow::bail!("--samples must be at least 1");
    }
    let t = properties::measure(samples, seed)?;
    let dis = t.disagreements();
    let claims = if with_claims {
        Some(claims_report(samples, seed)?)
    } else {
        None
    };
    match format {
        Format::Json => {
            let mut j = json!({"table_1": table_json(&t), "disagreements": dis.iter().map(|(m, p)| format!("{}: {p}", m.name())).collect::<Vec<_>>()});
            if let Some((c, _)) = claims {
                j["claims"] = c;
            }
            println!("{}", serde_json::to_string_pretty(&j)?);
        }
        Format::Markdown => {
            println!("## Table 1 (Kavan et al. 2006), measured on {samples} random cases per property (seed {seed})\n");
            println!("Each cell: measured mark, worst deviation; the paper's mark in parentheses. '+' means the deviation stayed below {:.0e}.\n", properties::TOLERANCE);
            print!("{}", properties::to_markdown(&t));
            let cells = t
                .rows
                .iter()
                .map(|r| r.cells().iter().filter(|c| c.1.paper.is_some()).count())
                .sum::<usize>();
            if dis.is_empty() {
                println!("\nAll {cells} cells the paper lists agree with it.");
            } else {
                println!("\nDisagreements with the paper: {dis:?}");
            }
            if let Some((_, md)) = claims {
                println!("\n{md}");
            }
        }
    }
    Ok(())
}
