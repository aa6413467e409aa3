//! Tables with typed cells: text, numbers that carry the precision they print with, and
//! the checked marks of Kavan et al.'s Table 1. Every renderer prints a number through
//! [`Number`]'s `Display`, so a number is formatted in one place only.

use serde::Serialize;
use std::fmt;

/// How a number prints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Style {
    /// Fixed point with this many decimals: `1.000`.
    Fixed(usize),
    /// Scientific with this many decimals: `1.2e-15`.
    Sci(usize),
    /// A whole number.
    Integer,
}

/// A number and how it prints.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Number {
    /// The value (not-a-number serializes as `null`).
    pub value: f64,
    /// How it prints.
    pub style: Style,
}

impl Number {
    /// `value` printed with `decimals` fixed decimals.
    pub fn fixed(value: f64, decimals: usize) -> Self {
        Number {
            value,
            style: Style::Fixed(decimals),
        }
    }
    /// `value` printed in scientific notation with `decimals` decimals.
    pub fn sci(value: f64, decimals: usize) -> Self {
        Number {
            value,
            style: Style::Sci(decimals),
        }
    }
    /// A count.
    pub fn integer(value: u64) -> Self {
        Number {
            value: value as f64,
            style: Style::Integer,
        }
    }
}

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.style {
            Style::Fixed(d) => write!(f, "{:.*}", d, self.value),
            Style::Sci(d) => write!(f, "{:.*e}", d, self.value),
            Style::Integer => write!(f, "{}", self.value.round()),
        }
    }
}

/// One cell.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Cell {
    /// Text.
    Text {
        /// The text.
        text: String,
    },
    /// A number.
    Number(Number),
    /// A property checked by number (a cell of Table 1): whether it holds, the worst
    /// deviation (none where it could not be measured), a remark, and the paper's mark.
    Check {
        /// Whether the property held on every sample.
        holds: bool,
        /// The worst deviation found.
        worst: Option<Number>,
        /// A remark ("only n = 2"); empty when none.
        note: String,
        /// The paper's mark, where the paper gives one.
        paper: Option<bool>,
    },
    /// Our value beside the paper's, and whether they agree (a FLOP count of Table 1).
    Compared {
        /// Ours, as it prints.
        ours: String,
        /// The paper's, as it prints there.
        paper: String,
        /// Whether they agree.
        agrees: bool,
    },
}

impl Cell {
    /// A text cell.
    pub fn text(s: impl Into<String>) -> Self {
        Cell::Text { text: s.into() }
    }

    /// Whether a check agrees with the paper's mark (true for other cells and where the
    /// paper gives none).
    pub fn agrees(&self) -> bool {
        match self {
            Cell::Check { holds, paper, .. } => paper.is_none_or(|p| p == *holds),
            Cell::Compared { agrees, .. } => *agrees,
            _ => true,
        }
    }
}

impl fmt::Display for Cell {
    /// The cell as plain text: a check reads "+ 1.2e-15 (paper +)", with "differs" where
    /// it disagrees with the paper.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Cell::Text { text } => f.write_str(text),
            Cell::Number(n) => n.fmt(f),
            Cell::Compared { ours, paper, .. } => {
                write!(f, "{ours} (paper {paper})")?;
                if !self.agrees() {
                    f.write_str(" differs")?;
                }
                Ok(())
            }
            Cell::Check {
                holds,
                worst,
                note,
                paper,
            } => {
                f.write_str(if *holds { "+" } else { "−" })?;
                match worst {
                    Some(n) => write!(f, " {n}")?,
                    None => f.write_str(" not measured")?,
                }
                if !note.is_empty() {
                    write!(f, ", {note}")?;
                }
                match paper {
                    Some(true) => f.write_str(" (paper +)")?,
                    Some(false) => f.write_str(" (paper −)")?,
                    None => {}
                }
                if !self.agrees() {
                    f.write_str(" differs")?;
                }
                Ok(())
            }
        }
    }
}

/// A table: a caption, the column names and rows of typed cells.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table {
    /// What the table shows.
    pub caption: String,
    /// Column names.
    pub header: Vec<String>,
    /// Rows, each as long as the header.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// An empty table with these columns.
    pub fn new(caption: impl Into<String>, header: &[&str]) -> Self {
        Table {
            caption: caption.into(),
            header: header.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Adds a row.
    pub fn row(&mut self, cells: Vec<Cell>) {
        self.rows.push(cells);
    }
}
