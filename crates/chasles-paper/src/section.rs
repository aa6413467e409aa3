//! An experiment's outcome: a titled section of claims, tables, figures and text, in the
//! order they are shown; and [`Experiment`], a named function that produces one.

use crate::claim::{Claim, Paper, Verdict};
use crate::table::Table;
use serde::Serialize;
use std::fmt;

/// The paper's figure a picture reproduces: its number and its caption, word for word.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PaperFigure {
    /// The paper.
    pub paper: Paper,
    /// Its number there, e.g. `6.15` or `1(c)`.
    pub number: String,
    /// Its caption there.
    pub caption: String,
}

impl PaperFigure {
    /// Figure `number` of `paper` with its `caption`.
    pub fn new(paper: Paper, number: &str, caption: &str) -> Self {
        PaperFigure {
            paper,
            number: number.to_string(),
            caption: caption.to_string(),
        }
    }
    /// "Dam et al. 1998, Figure 6.15".
    pub fn cite(&self) -> String {
        format!("{}, Figure {}", self.paper.cite(), self.number)
    }
}

/// A picture: the file it is written to (a bare name, its extension the kind: `.html`, a
/// page of its own such as the viewer, is linked rather than shown), its
/// caption, the paper's figure it reproduces (if it does), and its bytes (not serialized:
/// JSON carries the file name and the captions).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Figure {
    /// File name, e.g. `figure7.svg`.
    pub file: String,
    /// What it shows: our caption.
    pub caption: String,
    /// The paper's figure beside which it stands.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub of: Option<PaperFigure>,
    /// The file's contents.
    #[serde(skip)]
    pub bytes: Vec<u8>,
}

/// One item of a section.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Item {
    /// A paragraph.
    Text {
        /// The paragraph.
        text: String,
    },
    /// A claim checked.
    Claim(Claim),
    /// A table.
    Table(Table),
    /// A picture.
    Figure(Figure),
}

/// A titled section: one experiment's outcome.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Section {
    /// The title, naming the paper's chapter, figure or table.
    pub title: String,
    /// What it shows, in order.
    pub items: Vec<Item>,
}

impl Section {
    /// An empty section.
    pub fn new(title: impl Into<String>) -> Self {
        Section {
            title: title.into(),
            items: Vec::new(),
        }
    }

    /// Adds a paragraph.
    pub fn text(&mut self, s: impl Into<String>) {
        self.items.push(Item::Text { text: s.into() });
    }

    /// Adds a claim.
    pub fn claim(&mut self, c: Claim) {
        self.items.push(Item::Claim(c));
    }

    /// Adds a table.
    pub fn table(&mut self, t: Table) {
        self.items.push(Item::Table(t));
    }

    /// Adds a picture.
    pub fn figure(&mut self, file: &str, bytes: Vec<u8>, caption: &str) {
        self.push_figure(file, Ok::<_, String>(bytes), caption, None);
    }

    /// Adds our picture of the paper's figure `of`, with our caption beside the paper's;
    /// a picture that failed to draw becomes a paragraph naming the figure and the error.
    pub fn paper_figure<E: fmt::Display>(
        &mut self,
        of: PaperFigure,
        file: &str,
        bytes: Result<Vec<u8>, E>,
        caption: &str,
    ) {
        self.push_figure(file, bytes, caption, Some(of));
    }

    /// Adds a picture that may have failed to draw: on failure, a paragraph saying so
    /// with the error (never a silently missing picture).
    pub fn try_figure<E: fmt::Display>(
        &mut self,
        file: &str,
        bytes: Result<Vec<u8>, E>,
        caption: &str,
    ) {
        self.push_figure(file, bytes, caption, None);
    }

    /// The one way a picture is added: the figure, or the paragraph saying it failed (with
    /// the paper's figure it stood for, if any).
    fn push_figure<E: fmt::Display>(
        &mut self,
        file: &str,
        bytes: Result<Vec<u8>, E>,
        caption: &str,
        of: Option<PaperFigure>,
    ) {
        match bytes {
            Ok(bytes) => self.items.push(Item::Figure(Figure {
                file: file.to_string(),
                caption: caption.to_string(),
                of,
                bytes,
            })),
            Err(e) => {
                let cite = of.map_or(String::new(), |o| format!("{}: ", o.cite()));
                self.text(format!("{cite}picture {file} failed: {e}"));
            }
        }
    }

    /// Runs a part of the experiment that may fail — one that adds tables, text or
    /// pictures and returns a claim's measurement — and adds the claim: checked, or
    /// [`Verdict::Failed`] with the error. What the part added before failing stays.
    pub fn attempt<E: fmt::Display>(
        &mut self,
        paper: Paper,
        where_: &str,
        words: &str,
        part: impl FnOnce(&mut Section) -> Result<(String, bool), E>,
    ) {
        let measured = part(self);
        self.claim(Claim::check(paper, where_, words, measured));
    }

    /// The claims.
    pub fn claims(&self) -> impl Iterator<Item = &Claim> {
        self.items.iter().filter_map(|i| match i {
            Item::Claim(c) => Some(c),
            _ => None,
        })
    }

    /// The pictures.
    pub fn figures(&self) -> impl Iterator<Item = &Figure> {
        self.items.iter().filter_map(|i| match i {
            Item::Figure(f) => Some(f),
            _ => None,
        })
    }

    /// Drops the pictures' bytes (once they are written), keeping names and captions.
    pub fn forget_bytes(&mut self) {
        for i in &mut self.items {
            if let Item::Figure(f) = i {
                f.bytes = Vec::new();
            }
        }
    }
}

/// Claims that agree and claims made, over sections.
pub fn tally(sections: &[Section]) -> (usize, usize) {
    sections
        .iter()
        .flat_map(Section::claims)
        .fold((0, 0), |(ok, n), c| {
            (ok + usize::from(c.verdict == Verdict::Agrees), n + 1)
        })
}

/// An experiment: a short name for progress reports and the function that runs it.
pub struct Experiment<'a> {
    /// What it does, in a few words ("blending: Table 1").
    pub name: &'static str,
    run: Box<dyn FnOnce() -> Section + 'a>,
}

impl<'a> Experiment<'a> {
    /// An experiment named `name` that runs `run`.
    pub fn new(name: &'static str, run: impl FnOnce() -> Section + 'a) -> Self {
        Experiment {
            name,
            run: Box::new(run),
        }
    }

    /// Runs it.
    pub fn run(self) -> Section {
        (self.run)()
    }
}
