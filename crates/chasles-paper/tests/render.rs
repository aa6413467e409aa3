//! The typed outcomes and their renderers: the JSON shape of claims, tables and figures;
//! each renderer on a small section (numbers formatted once as their style says, HTML
//! escaping, Markdown pipes); failed operations reported as `Failed`, never skipped.

use chasles::{Quat, Vec3};
use chasles_paper::experiments::{blending_claims::blending_claims, identities, table_1};
use chasles_paper::render::{html, json, markdown, terminal};
use chasles_paper::{
    tally, Cell, Claim, Experiment, Figures, Item, Number, Paper, PaperFigure, Section, Table,
    Verdict,
};

/// A section with one of everything, text that needs escaping, and a number to find.
fn sample() -> Section {
    let mut s = Section::new("Tiny <check> & co");
    s.text("a \"quoted\" <paragraph>");
    s.claim(Claim::check(
        Paper::Kavan2006,
        "§4",
        "DLB is within 8.15° of ScLERP",
        Ok::<_, String>(("worst 8.1491°".to_string(), true)),
    ));
    s.claim(Claim::check(
        Paper::Dam1998,
        "§5.2",
        "Slerp <is> constant speed",
        Ok::<_, String>(("ratio 1.5".to_string(), false)),
    ));
    let mut t = Table::new("numbers | pipes", &["name", "value", "mark"]);
    t.row(vec![
        Cell::text("a|b"),
        Cell::Number(Number::sci(0.000123456, 2)),
        Cell::Check {
            holds: true,
            worst: Some(Number::sci(1.25e-15, 1)),
            note: String::new(),
            paper: Some(false),
        },
    ]);
    t.row(vec![
        Cell::text("fixed"),
        Cell::Number(Number::fixed(std::f64::consts::PI, 3)),
        Cell::Number(Number::integer(42)),
    ]);
    s.table(t);
    s.figure("f.svg", b"<svg/>".to_vec(), "a <figure>");
    s
}

#[test]
fn claims_tables_and_figures_serialize_with_their_fields() {
    let v = serde_json::to_value(sample()).unwrap();
    assert_eq!(v["title"], "Tiny <check> & co");
    let items = v["items"].as_array().unwrap();
    assert_eq!(items.len(), 5);
    assert_eq!(items[0]["kind"], "text");
    assert_eq!(items[0]["text"], "a \"quoted\" <paragraph>");
    let c = &items[1];
    assert_eq!(c["kind"], "claim");
    assert_eq!(c["paper"], "Kavan2006");
    assert_eq!(c["section"], "§4");
    assert_eq!(c["words"], "DLB is within 8.15° of ScLERP");
    assert_eq!(c["ours"], "worst 8.1491°");
    assert_eq!(c["verdict"], "agrees");
    assert_eq!(items[2]["verdict"], "disagrees");
    let t = &items[3];
    assert_eq!(t["kind"], "table");
    assert_eq!(t["caption"], "numbers | pipes");
    assert_eq!(t["header"], serde_json::json!(["name", "value", "mark"]));
    assert_eq!(
        t["rows"][0][0],
        serde_json::json!({"kind": "text", "text": "a|b"})
    );
    assert_eq!(
        t["rows"][0][1],
        serde_json::json!({"kind": "number", "value": 0.000123456, "style": {"sci": 2}})
    );
    assert_eq!(t["rows"][0][2]["kind"], "check");
    assert_eq!(t["rows"][0][2]["holds"], true);
    assert_eq!(t["rows"][0][2]["paper"], false);
    assert_eq!(t["rows"][0][2]["worst"]["value"], 1.25e-15);
    assert_eq!(t["rows"][1][2]["style"], "integer");
    // A figure carries its name and caption, not its bytes.
    assert_eq!(
        items[4],
        serde_json::json!({"kind": "figure", "file": "f.svg", "caption": "a <figure>"})
    );
    // A failed claim carries the error.
    let failed = Claim::check(Paper::Dam1998, "§1", "x", Err::<(String, bool), _>("boom"));
    let f = serde_json::to_value(&failed).unwrap();
    assert_eq!(f["verdict"], serde_json::json!({"failed": "boom"}));
    assert_eq!(f["ours"], "");
}

#[test]
fn numbers_print_as_their_style_says() {
    assert_eq!(Number::sci(0.000123456, 2).to_string(), "1.23e-4");
    assert_eq!(Number::fixed(std::f64::consts::PI, 3).to_string(), "3.142");
    assert_eq!(Number::integer(42).to_string(), "42");
    let check = Cell::Check {
        holds: false,
        worst: Some(Number::sci(2.5, 1)),
        note: "only n = 2".into(),
        paper: Some(true),
    };
    assert_eq!(check.to_string(), "− 2.5e0, only n = 2 (paper +) differs");
    assert!(!check.agrees());
}

#[test]
fn terminal_renderer_aligns_columns_and_shows_verdicts() {
    let out = terminal::section(&sample());
    assert!(out.starts_with("\n== Tiny <check> & co\n"), "{out}");
    // Each number appears once, as its style prints it, and never in another form.
    assert_eq!(out.matches("1.23e-4").count(), 1, "{out}");
    assert!(!out.contains("0.000123456"));
    assert_eq!(out.matches("3.142").count(), 1);
    let lines: Vec<&str> = out.lines().collect();
    let header = lines.iter().position(|l| l.contains("name")).unwrap();
    // Columns line up: "value" starts where the numbers start.
    let col = lines[header].find("value").unwrap();
    assert_eq!(lines[header + 1].find("1.23e-4").unwrap(), col);
    assert_eq!(lines[header + 2].find("3.142").unwrap(), col);
    assert!(lines[header + 1].contains("+ 1.2e-15 (paper −) differs"));
    assert!(out.contains("[yes] Kavan et al. 2006, §4: DLB is within 8.15° of ScLERP"));
    assert!(out.contains("[no] Dam et al. 1998, §5.2"));
    assert!(out.contains("picture: f.svg"));
}

#[test]
fn markdown_renderer_writes_pipe_tables_and_escapes_pipes() {
    let out = markdown::section(&sample());
    assert!(out.starts_with("## Tiny <check> & co\n\n"));
    assert!(
        out.contains("| name | value | mark |\n|---|---|---|\n"),
        "{out}"
    );
    assert!(
        out.contains("| a\\|b | 1.23e-4 | **+ 1.2e-15 (paper −) differs** |"),
        "{out}"
    );
    assert!(out.contains("| fixed | 3.142 | 42 |"), "{out}");
    assert_eq!(out.matches("1.23e-4").count(), 1);
    assert!(out.contains("- **yes** — Kavan et al. 2006, §4: DLB is within 8.15° of ScLERP — we measure: worst 8.1491°"));
    assert!(out.contains("![a <figure>](f.svg)"));
}

#[test]
fn html_renderer_escapes_and_types_the_rows() {
    let page = html::page(&[sample()]);
    assert!(page.starts_with("<!DOCTYPE html>") && page.ends_with("</body></html>\n"));
    assert!(page.contains("<b>1 of 2 claims agree</b>"));
    assert!(
        page.contains("<h2 id=\"s0\">Tiny &lt;check&gt; &amp; co</h2>"),
        "{page}"
    );
    assert!(page.contains("<p>a &quot;quoted&quot; &lt;paragraph&gt;</p>"));
    assert!(!page.contains("<paragraph>") && !page.contains("<check>"));
    assert_eq!(page.matches("<tr class=\"claim\">").count(), 2);
    assert!(page.contains("<td class=\"measured\">worst 8.1491°</td><td class=\"yes\">yes</td>"));
    assert!(page.contains("Slerp &lt;is&gt; constant speed"));
    assert!(page.contains("<td class=\"measured\">ratio 1.5</td><td class=\"no\">no</td>"));
    // Table cells straight from the typed table: a number once, a check with its class.
    assert!(page.contains("<tr><td>a|b</td><td>1.23e-4</td><td class=\"yes differs\">+ 1.2e-15 (paper −) differs</td></tr>"), "{page}");
    assert_eq!(page.matches("1.23e-4").count(), 1);
    assert!(page.contains("<img src=\"f.svg\" alt=\"a &lt;figure&gt;\" loading=\"lazy\">"));
}

#[test]
fn json_renderer_counts_the_claims() {
    let v: serde_json::Value = serde_json::from_str(&json::sections(&[sample()]).unwrap()).unwrap();
    assert_eq!(v["agree"], 1);
    assert_eq!(v["claims"], 2);
    assert_eq!(
        v["sections"][0]["items"][1]["words"],
        "DLB is within 8.15° of ScLERP"
    );
}

#[test]
fn a_failing_operation_gives_a_failed_verdict() {
    // A zero axis cannot be normalized: the core's error becomes the verdict.
    let mut s = Section::new("failure");
    s.attempt(
        Paper::Dam1998,
        "§3.3",
        "a rotation about the zero axis",
        |s| {
            s.text("before the failure");
            let q = Quat::from_axis_angle(Vec3::new(0.0, 0.0, 0.0), 1.0)?;
            Ok::<_, chasles::Error>((format!("{}", q.w), true))
        },
    );
    assert_eq!(s.items.len(), 2, "what came before the failure stays");
    let c = s.claims().next().unwrap();
    match &c.verdict {
        Verdict::Failed(e) => assert!(!e.is_empty()),
        v => panic!("expected a failure, got {v:?}"),
    }
    assert!(c.measured().starts_with("failed: "));
    assert_eq!(tally(std::slice::from_ref(&s)), (0, 1));
    let page = html::page(&[s]);
    assert!(page.contains("<td class=\"no\">failed</td>"), "{page}");
}

#[test]
fn experiments_asked_for_no_samples_report_failures() {
    // Every claim is there, failed with the reason; none is skipped.
    let s = blending_claims(0, 1, Figures::Skip);
    let claims: Vec<&Claim> = s.claims().collect();
    let failed = claims
        .iter()
        .filter(|c| matches!(&c.verdict, Verdict::Failed(e) if e.contains("sample")))
        .count();
    // Figure 7 samples no random inputs: it still runs and agrees.
    assert_eq!(claims.len(), 9, "{claims:?}");
    assert_eq!(failed, 8, "{claims:?}");
    // Table 1's two claims (the properties and the FLOPS) both fail with the reason.
    let t = table_1::table_1(0, 1, Figures::Skip);
    assert_eq!(t.claims().count(), 2);
    assert!(t
        .claims()
        .all(|c| matches!(&c.verdict, Verdict::Failed(e) if e.contains("sample"))));
    let i = identities::identities(0, 1);
    assert!(matches!(
        i.claims().next().unwrap().verdict,
        Verdict::Failed(_)
    ));
}

#[test]
fn experiments_run_in_order_and_draw_only_when_asked() {
    let list = [
        Experiment::new("Table 1", || table_1::table_1(5, 3, Figures::Draw)),
        Experiment::new("identities", || identities::identities(20, 3)),
    ];
    let names: Vec<&str> = list.iter().map(|e| e.name).collect();
    assert_eq!(names, ["Table 1", "identities"]);
    let sections: Vec<Section> = list.into_iter().map(Experiment::run).collect();
    assert!(sections[0].title.contains("Table 1"));
    assert!(sections[1]
        .title
        .starts_with("Identities over 20 random inputs"));
    let fig: Vec<_> = sections[0].figures().collect();
    assert_eq!(fig.len(), 1);
    assert!(String::from_utf8_lossy(&fig[0].bytes).starts_with("<svg"));
    assert_eq!(table_1::table_1(5, 3, Figures::Skip).figures().count(), 0);
    let mut s = sections[0].clone();
    s.forget_bytes();
    assert!(s
        .figures()
        .all(|f| f.bytes.is_empty() && f.file == "table1.svg"));
    assert!(matches!(sections[1].items.last(), Some(Item::Claim(_))));
}

/// A picture of a paper's figure shows the paper's caption, then ours, in every renderer,
/// and the page's contents link it by number.
#[test]
fn a_paper_figure_carries_the_papers_caption_beside_ours() {
    let mut s = Section::new("ch. 6");
    s.paper_figure(
        PaperFigure::new(Paper::Dam1998, "6.15", "One-step <iteration>."),
        "dam-figure-6-15.png",
        Ok::<_, String>(vec![1, 2, 3]),
        "Spring, 350 frames",
    );
    s.paper_figure(
        PaperFigure::new(Paper::Dam1998, "6.16", "First step."),
        "dam-figure-6-16.png",
        Err::<Vec<u8>, _>("no memory"),
        "never drawn",
    );
    let page = html::page(std::slice::from_ref(&s));
    assert!(
        page.contains("<figure id=\"f-dam-figure-6-15-png\">"),
        "{page}"
    );
    assert!(page.contains("<b>Dam et al. 1998, Figure 6.15.</b> The paper: <i>One-step &lt;iteration&gt;.</i><br>Ours: Spring, 350 frames"), "{page}");
    assert!(
        page.contains("Figures <a href=\"#f-dam-figure-6-15-png\">6.15</a></small>"),
        "{page}"
    );
    assert!(page
        .contains("Dam et al. 1998, Figure 6.16: picture dam-figure-6-16.png failed: no memory"));
    let md = markdown::section(&s);
    assert!(
        md.contains("**Dam et al. 1998, Figure 6.15.** The paper: *One-step <iteration>.*"),
        "{md}"
    );
    assert!(terminal::section(&s)
        .contains("picture: dam-figure-6-15.png (Dam et al. 1998, Figure 6.15)"));
    let v: serde_json::Value = serde_json::from_str(&json::sections(&[s]).unwrap()).unwrap();
    let f = &v["sections"][0]["items"][0];
    assert_eq!(f["of"]["number"], "6.15");
    assert_eq!(f["caption"], "Spring, 350 frames");
}
