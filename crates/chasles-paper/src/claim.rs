//! A claim of one of the papers, checked by number: the paper's words and where they
//! stand (section, table, figure), what we measured, and the verdict. A measurement whose
//! operation fails gives [`Verdict::Failed`] with the error — a claim is never skipped.

use serde::Serialize;
use std::fmt;

/// The paper a claim comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Paper {
    /// Dam, Koch & Lillholm 1998, *Quaternions, Interpolation and Animation*.
    Dam1998,
    /// Kavan, Collins, Žára & O'Sullivan 2006, *Dual Quaternions for Rigid Transformation
    /// Blending*.
    Kavan2006,
}

impl Paper {
    /// How the text cites it: "Dam et al. 1998".
    pub fn cite(self) -> &'static str {
        match self {
            Paper::Dam1998 => "Dam et al. 1998",
            Paper::Kavan2006 => "Kavan et al. 2006",
        }
    }
}

/// Whether our number bears the claim out.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Our measurement agrees with the paper.
    Agrees,
    /// Our measurement contradicts the paper.
    Disagrees,
    /// The operation behind the measurement failed; the error's text.
    Failed(String),
}

impl Verdict {
    /// `Agrees` when `ok`, else `Disagrees`.
    pub fn of(ok: bool) -> Self {
        if ok {
            Verdict::Agrees
        } else {
            Verdict::Disagrees
        }
    }

    /// Whether it agrees.
    pub fn agrees(&self) -> bool {
        matches!(self, Verdict::Agrees)
    }

    /// One word: "yes", "no" or "failed".
    pub fn word(&self) -> &'static str {
        match self {
            Verdict::Agrees => "yes",
            Verdict::Disagrees => "no",
            Verdict::Failed(_) => "failed",
        }
    }
}

/// One claim, checked.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Claim {
    /// The paper.
    pub paper: Paper,
    /// Where in it: "§5.2, Figure 5.5", "Table 1", "Lemma 3".
    pub section: String,
    /// What the paper says.
    pub words: String,
    /// What we measured, in words with the numbers (empty when the measurement failed).
    pub ours: String,
    /// The verdict.
    pub verdict: Verdict,
}

impl Claim {
    /// A claim from a measurement: `Ok((ours, agrees))`, or the error that stopped it
    /// (then the verdict is [`Verdict::Failed`] with the error's text).
    pub fn check<E: fmt::Display>(
        paper: Paper,
        section: &str,
        words: &str,
        measured: Result<(String, bool), E>,
    ) -> Self {
        let (ours, verdict) = match measured {
            Ok((ours, ok)) => (ours, Verdict::of(ok)),
            Err(e) => (String::new(), Verdict::Failed(e.to_string())),
        };
        Claim {
            paper,
            section: section.to_string(),
            words: words.to_string(),
            ours,
            verdict,
        }
    }

    /// "Dam et al. 1998, §5.2": the paper and the place.
    pub fn source(&self) -> String {
        format!("{}, {}", self.paper.cite(), self.section)
    }

    /// What we measured, or for a failed measurement "failed: " and the error.
    pub fn measured(&self) -> String {
        match &self.verdict {
            Verdict::Failed(e) => format!("failed: {e}"),
            _ => self.ours.clone(),
        }
    }
}
