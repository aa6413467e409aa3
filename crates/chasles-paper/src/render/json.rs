//! Sections as one JSON document, `{"sections": [...]}`, straight from their `Serialize`
//! derivations (figures carry their file name and caption, not their bytes).

use crate::section::{tally, Section};
use serde::Serialize;

#[derive(Serialize)]
struct Document<'a> {
    /// Claims that agree.
    agree: usize,
    /// Claims made.
    claims: usize,
    sections: &'a [Section],
}

/// The sections as pretty-printed JSON.
pub fn sections(s: &[Section]) -> Result<String, serde_json::Error> {
    let (agree, claims) = tally(s);
    serde_json::to_string_pretty(&Document {
        agree,
        claims,
        sections: s,
    })
}
