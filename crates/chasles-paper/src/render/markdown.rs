//! Sections as Markdown: `##` headings, paragraphs, pipe tables (a '|' in a cell is
//! escaped), claims as a list with the verdict in bold, pictures as images.

use crate::section::{Item, Section};
use crate::table::Table;

/// `s` made safe inside a pipe-table cell.
fn cell_text(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

fn table(t: &Table, out: &mut String) {
    out.push_str(&format!("{}:\n\n|", t.caption));
    for h in &t.header {
        out.push_str(&format!(" {} |", cell_text(h)));
    }
    out.push('\n');
    out.push_str(&"|---".repeat(t.header.len()));
    out.push_str("|\n");
    for r in &t.rows {
        out.push('|');
        for c in r {
            let text = cell_text(&c.to_string());
            // Only a check can disagree with the paper (`agrees` is true for other cells).
            if c.agrees() {
                out.push_str(&format!(" {text} |"));
            } else {
                out.push_str(&format!(" **{text}** |"));
            }
        }
        out.push('\n');
    }
    out.push('\n');
}

/// One section as Markdown.
pub fn section(s: &Section) -> String {
    let mut out = format!("## {}\n\n", s.title);
    let mut in_list = false;
    for item in &s.items {
        let is_claim = matches!(item, Item::Claim(_));
        if in_list && !is_claim {
            out.push('\n');
        }
        in_list = is_claim;
        match item {
            Item::Text { text } => out.push_str(&format!("{text}\n\n")),
            Item::Table(t) => table(t, &mut out),
            Item::Claim(c) => out.push_str(&format!(
                "- **{}** — {}: {} — we measure: {}\n",
                c.verdict.word(),
                c.source(),
                c.words,
                c.measured()
            )),
            Item::Figure(f) => {
                if let Some(o) = &f.of {
                    out.push_str(&format!("**{}.** The paper: *{}*\n\n", o.cite(), o.caption));
                }
                // An HTML page (the viewer) is linked, a picture shown.
                let bang = if f.file.ends_with(".html") { "" } else { "!" };
                out.push_str(&format!("{bang}[{}]({})\n\n", f.caption, f.file));
            }
        }
    }
    if in_list {
        out.push('\n');
    }
    out
}

/// Every section, in order.
pub fn sections(s: &[Section]) -> String {
    s.iter().map(section).collect()
}
