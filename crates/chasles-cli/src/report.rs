//! The tour's report: one HTML page, readable from disk with no server, that walks through
//! both papers — for every figure and table reproduced, the paper's claim, our number or
//! picture, and whether they agree. Pictures are written next to it as they are made;
//! `index.html` is written last, atomically, so a page never points at a missing picture.

use crate::output::write_atomic;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

enum Item {
    Claim {
        paper: String,
        ours: String,
        agrees: bool,
    },
    Figure {
        file: String,
        caption: String,
    },
    Html(String),
}

struct Section {
    title: String,
    items: Vec<Item>,
}

/// The report being built.
pub struct Report {
    dir: PathBuf,
    sections: Vec<Section>,
}

/// `s` with `& < > "` escaped for HTML.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

impl Report {
    /// A report to be written into `dir` (created if missing).
    pub fn new(dir: &Path) -> Result<Self> {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        Ok(Report {
            dir: dir.to_path_buf(),
            sections: Vec::new(),
        })
    }

    /// Starts a section (a paper's chapter or figure).
    pub fn section(&mut self, title: &str) {
        self.sections.push(Section {
            title: title.to_string(),
            items: Vec::new(),
        });
    }

    fn push(&mut self, item: Item) {
        if self.sections.is_empty() {
            self.section("");
        }
        if let Some(s) = self.sections.last_mut() {
            s.items.push(item);
        }
    }

    /// A claim of the paper, what we measured (with its number), and whether they agree.
    pub fn claim(&mut self, paper: &str, ours: String, agrees: bool) {
        self.push(Item::Claim {
            paper: paper.to_string(),
            ours,
            agrees,
        });
    }

    /// Writes a picture `name` (its extension says the kind) and shows it with `caption`.
    pub fn figure(&mut self, name: &str, bytes: &[u8], caption: &str) -> Result<()> {
        write_atomic(&self.dir.join(name), bytes)?;
        self.push(Item::Figure {
            file: name.to_string(),
            caption: caption.to_string(),
        });
        Ok(())
    }

    /// A table given as rows of cells, the first row the header; cells are escaped.
    pub fn table(&mut self, rows: &[Vec<String>]) {
        let mut h = String::from("<table class=\"data\">\n");
        for (i, r) in rows.iter().enumerate() {
            let tag = if i == 0 { "th" } else { "td" };
            h.push_str("<tr>");
            for c in r {
                h.push_str(&format!("<{tag}>{}</{tag}>", esc(c)));
            }
            h.push_str("</tr>\n");
        }
        h.push_str("</table>\n");
        self.push(Item::Html(h));
    }

    /// Claims that agree and claims made.
    pub fn tally(&self) -> (usize, usize) {
        let claims = self
            .sections
            .iter()
            .flat_map(|s| &s.items)
            .filter_map(|i| match i {
                Item::Claim { agrees, .. } => Some(*agrees),
                _ => None,
            });
        claims.fold((0, 0), |(a, n), ok| (a + ok as usize, n + 1))
    }

    /// Writes `index.html` and returns its path.
    pub fn finish(&self) -> Result<PathBuf> {
        let (ok, n) = self.tally();
        let mut h = String::from(
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>chasles tour: the two papers, reproduced</title>\n<style>\nbody{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;line-height:1.45;color:#222}\ntable{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ccc;padding:.25em .5em;vertical-align:top}\ntable.claims td:nth-child(3){text-align:center;font-weight:bold}\n.yes{color:#1b7f2a}.no{color:#b3261e}\nfigure{margin:1em 0}figure img{max-width:100%;border:1px solid #ddd}figcaption{font-size:.9em;color:#555}\ntable.data td{font-family:monospace;font-size:.85em}\n</style></head><body>\n<h1>chasles tour</h1>\n<p>Dam, Koch &amp; Lillholm 1998, <i>Quaternions, Interpolation and Animation</i>, and Kavan, Collins, Žára &amp; O'Sullivan 2006, <i>Dual Quaternions for Rigid Transformation Blending</i>, reproduced on built-in data. Every number below was computed when this page was written.</p>\n",
        );
        h.push_str(&format!(
            "<p><b>{ok} of {n} claims agree</b> with the papers.</p>\n<ul>\n"
        ));
        for (i, s) in self.sections.iter().enumerate() {
            h.push_str(&format!(
                "<li><a href=\"#s{i}\">{}</a></li>\n",
                esc(&s.title)
            ));
        }
        h.push_str("</ul>\n");
        for (i, s) in self.sections.iter().enumerate() {
            h.push_str(&format!("<h2 id=\"s{i}\">{}</h2>\n", esc(&s.title)));
            let mut in_claims = false;
            for item in &s.items {
                let is_claim = matches!(item, Item::Claim { .. });
                if is_claim && !in_claims {
                    h.push_str("<table class=\"claims\"><tr><th>the paper says</th><th>we measure</th><th>agree</th></tr>\n");
                } else if !is_claim && in_claims {
                    h.push_str("</table>\n");
                }
                in_claims = is_claim;
                match item {
                    Item::Claim {
                        paper,
                        ours,
                        agrees,
                    } => h.push_str(&format!(
                        "<tr class=\"claim\"><td>{}</td><td class=\"measured\">{}</td><td class=\"{}\">{}</td></tr>\n",
                        esc(paper),
                        esc(ours),
                        if *agrees { "yes" } else { "no" },
                        if *agrees { "yes" } else { "no" }
                    )),
                    Item::Figure { file, caption } => h.push_str(&format!(
                        "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
                        esc(file),
                        esc(caption),
                        esc(caption)
                    )),
                    Item::Html(x) => h.push_str(x),
                }
            }
            if in_claims {
                h.push_str("</table>\n");
            }
        }
        h.push_str("</body></html>\n");
        let path = self.dir.join("index.html");
        write_atomic(&path, h.as_bytes())?;
        Ok(path)
    }
}
