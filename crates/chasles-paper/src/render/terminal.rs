//! Sections as plain text for a terminal: a heading per section, paragraphs, tables with
//! aligned columns (two spaces or more between columns), claims with their verdict, and
//! the pictures' file names.

use crate::section::{Item, Section};
use crate::table::Table;

/// Characters of `s` as the terminal counts them (one per `char`).
fn width(s: &str) -> usize {
    s.chars().count()
}

/// A table with aligned columns, indented by two spaces; its caption above it.
fn table(t: &Table, out: &mut String) {
    let cells: Vec<Vec<String>> = t
        .rows
        .iter()
        .map(|r| r.iter().map(ToString::to_string).collect())
        .collect();
    let mut widths: Vec<usize> = t.header.iter().map(|h| width(h)).collect();
    for r in &cells {
        for (i, c) in r.iter().enumerate() {
            if i < widths.len() {
                widths[i] = widths[i].max(width(c));
            } else {
                widths.push(width(c));
            }
        }
    }
    out.push_str(&format!("  {}:\n", t.caption));
    let line = |row: &[String], out: &mut String| {
        let mut l = String::from("  ");
        for (i, c) in row.iter().enumerate() {
            l.push_str(c);
            if i + 1 < row.len() {
                l.push_str(&" ".repeat(widths[i] - width(c) + 2));
            }
        }
        out.push_str(l.trim_end());
        out.push('\n');
    };
    line(&t.header, out);
    for r in &cells {
        line(r, out);
    }
}

/// One section as text.
pub fn section(s: &Section) -> String {
    let mut out = format!("\n== {}\n", s.title);
    for item in &s.items {
        match item {
            Item::Text { text } => {
                out.push_str("  ");
                out.push_str(text);
                out.push('\n');
            }
            Item::Table(t) => table(t, &mut out),
            Item::Claim(c) => out.push_str(&format!(
                "  [{}] {}: {}\n        we measure: {}\n",
                c.verdict.word(),
                c.source(),
                c.words,
                c.measured()
            )),
            Item::Figure(f) => {
                // An HTML page (the viewer) is a page to open, not a picture.
                let kind = if f.file.ends_with(".html") {
                    "page"
                } else {
                    "picture"
                };
                match &f.of {
                    Some(o) => out.push_str(&format!("  {kind}: {} ({})\n", f.file, o.cite())),
                    None => out.push_str(&format!("  {kind}: {}\n", f.file)),
                }
            }
        }
    }
    out
}

/// Every section, in order.
pub fn sections(s: &[Section]) -> String {
    s.iter().map(section).collect()
}
