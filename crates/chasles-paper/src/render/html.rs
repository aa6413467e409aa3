//! Sections as one self-contained HTML page (the tour's report): a contents list, then per
//! section its claims in a table (the paper's words, our number, whether they agree), its
//! tables, paragraphs and pictures (`<img>` by file name: the caller writes the files next
//! to the page). Every piece of text is escaped.

use crate::section::{tally, Item, Section};
use crate::table::{Cell, Table};

/// `s` with `& < > "` escaped for HTML.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const HEAD: &str = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>chasles tour: the two papers, reproduced</title>\n<style>\nbody{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;line-height:1.45;color:#222}\ntable{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ccc;padding:.25em .5em;vertical-align:top}\ntable.claims td:nth-child(3){text-align:center;font-weight:bold}\n.yes{color:#1b7f2a}.no{color:#b3261e}.where{color:#555}\ntd.differs{outline:2px solid #b3261e}\nfigure{margin:1em 0}a.page{font-weight:bold}figure img{max-width:100%;border:1px solid #ddd}figcaption{font-size:.9em;color:#555}\ntable.data td{font-family:monospace;font-size:.85em}caption{text-align:left;font-size:.9em;color:#555}\n</style></head><body>\n<h1>chasles tour</h1>\n<p>Dam, Koch &amp; Lillholm 1998, <i>Quaternions, Interpolation and Animation</i>, and Kavan, Collins, Žára &amp; O'Sullivan 2006, <i>Dual Quaternions for Rigid Transformation Blending</i>, reproduced on built-in data. Every number below was computed when this page was written.</p>\n";

fn cell(c: &Cell) -> String {
    match c {
        Cell::Check { holds, .. } => format!(
            "<td class=\"{}{}\">{}</td>",
            if *holds { "yes" } else { "no" },
            if c.agrees() { "" } else { " differs" },
            esc(&c.to_string())
        ),
        Cell::Compared { agrees, .. } => format!(
            "<td class=\"{}\">{}</td>",
            if *agrees { "yes" } else { "no differs" },
            esc(&c.to_string())
        ),
        _ => format!("<td>{}</td>", esc(&c.to_string())),
    }
}

fn table(t: &Table, h: &mut String) {
    h.push_str(&format!(
        "<table class=\"data\"><caption>{}</caption>\n<tr>",
        esc(&t.caption)
    ));
    for c in &t.header {
        h.push_str(&format!("<th>{}</th>", esc(c)));
    }
    h.push_str("</tr>\n");
    for r in &t.rows {
        h.push_str("<tr>");
        for c in r {
            h.push_str(&cell(c));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
}

/// The id of a figure's element: its file name with anything but letters, digits and
/// `-` as `-`.
fn anchor(file: &str) -> String {
    let id: String = file
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect();
    format!("f-{id}")
}

/// A picture with its caption; one that reproduces a paper's figure shows the paper's
/// caption first, then ours. A figure that is an HTML page (`.html`, the viewer) is a link.
fn figure(f: &crate::section::Figure, h: &mut String) {
    let caption = match &f.of {
        Some(o) => format!(
            "<b>{}.</b> The paper: <i>{}</i><br>Ours: {}",
            esc(&o.cite()),
            esc(&o.caption),
            esc(&f.caption)
        ),
        None => esc(&f.caption),
    };
    if f.file.ends_with(".html") {
        // A page of its own (the viewer): a link to open it, not a picture.
        h.push_str(&format!(
            "<figure id=\"{}\"><p><a class=\"page\" href=\"{}\">open {}</a></p><figcaption>{caption}</figcaption></figure>\n",
            anchor(&f.file),
            esc(&f.file),
            esc(&f.file),
        ));
        return;
    }
    h.push_str(&format!(
        "<figure id=\"{}\"><img src=\"{}\" alt=\"{}\" loading=\"lazy\"><figcaption>{caption}</figcaption></figure>\n",
        anchor(&f.file),
        esc(&f.file),
        esc(&f.caption),
    ));
}

/// The sort key of a figure number: its numeric parts, then the rest (`6.15` after `6.2`,
/// `1(c)` after `1`).
fn figure_order(number: &str) -> (Vec<u32>, String) {
    let head: String = number
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    let parts = head.split('.').filter_map(|p| p.parse().ok()).collect();
    (parts, number[head.len()..].to_string())
}

/// Every reproduced figure, paper by paper in the papers' order, linked.
fn figures_by_paper(sections: &[Section]) -> String {
    let mut h = String::new();
    for paper in [crate::Paper::Dam1998, crate::Paper::Kavan2006] {
        let mut figs: Vec<(&str, &str)> = sections
            .iter()
            .flat_map(|s| s.figures())
            .filter_map(|f| {
                f.of.as_ref()
                    .filter(|o| o.paper == paper)
                    .map(|o| (o.number.as_str(), f.file.as_str()))
            })
            .collect();
        if figs.is_empty() {
            continue;
        }
        figs.sort_by_key(|f| figure_order(f.0));
        let links: Vec<String> = figs
            .iter()
            .map(|(n, file)| format!("<a href=\"#{}\">{}</a>", anchor(file), esc(n)))
            .collect();
        h.push_str(&format!(
            "<p><b>{}, figures:</b> {}</p>\n",
            esc(paper.cite()),
            links.join(", ")
        ));
    }
    h
}

/// The whole page.
pub fn page(sections: &[Section]) -> String {
    let (ok, n) = tally(sections);
    let mut h = String::from(HEAD);
    h.push_str(&format!(
        "<p><b>{ok} of {n} claims agree</b> with the papers.</p>\n<ul>\n"
    ));
    for (i, s) in sections.iter().enumerate() {
        // The paper's figures the section reproduces, listed under its title.
        let figures: Vec<String> = s
            .figures()
            .filter_map(|f| {
                f.of.as_ref()
                    .map(|o| format!("<a href=\"#{}\">{}</a>", anchor(&f.file), esc(&o.number)))
            })
            .collect();
        let figures = if figures.is_empty() {
            String::new()
        } else {
            format!("<br><small>Figures {}</small>", figures.join(", "))
        };
        h.push_str(&format!(
            "<li><a href=\"#s{i}\">{}</a>{figures}</li>\n",
            esc(&s.title)
        ));
    }
    h.push_str("</ul>\n");
    h.push_str(&figures_by_paper(sections));
    for (i, s) in sections.iter().enumerate() {
        h.push_str(&format!("<h2 id=\"s{i}\">{}</h2>\n", esc(&s.title)));
        let mut in_claims = false;
        for item in &s.items {
            let is_claim = matches!(item, Item::Claim(_));
            if is_claim && !in_claims {
                h.push_str("<table class=\"claims\"><tr><th>the paper says</th><th>we measure</th><th>agree</th></tr>\n");
            } else if !is_claim && in_claims {
                h.push_str("</table>\n");
            }
            in_claims = is_claim;
            match item {
                Item::Claim(c) => {
                    let class = if c.verdict.agrees() { "yes" } else { "no" };
                    h.push_str(&format!(
                        "<tr class=\"claim\"><td><span class=\"where\">{}:</span> {}</td><td class=\"measured\">{}</td><td class=\"{class}\">{}</td></tr>\n",
                        esc(&c.source()),
                        esc(&c.words),
                        esc(&c.measured()),
                        c.verdict.word()
                    ));
                }
                Item::Figure(f) => figure(f, &mut h),
                Item::Table(t) => table(t, &mut h),
                Item::Text { text } => h.push_str(&format!("<p>{}</p>\n", esc(text))),
            }
        }
        if in_claims {
            h.push_str("</table>\n");
        }
    }
    h.push_str("</body></html>\n");
    h
}
