//! `chasles properties`: Kavan et al. 2006, Table 1 measured, and with `--claims` the
//! paper's other claims by number — the experiments of `chasles_paper::experiments`
//! (`table_1`, `blending_claims`) rendered as Markdown or JSON.

use anyhow::Result;
use chasles_paper::experiments::{blending_claims::blending_claims, table_1::table_1};
use chasles_paper::{render, Figures};

/// Output format.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Markdown tables and lines.
    Markdown,
    /// One JSON object.
    Json,
}

/// Runs `chasles properties`.
pub fn run(samples: usize, seed: u64, format: Format, with_claims: bool) -> Result<()> {
    if samples == 0 {
        anyhow::bail!("--samples must be at least 1");
    }
    let mut sections = vec![table_1(samples, seed, Figures::Skip)];
    if with_claims {
        sections.push(blending_claims(samples, seed, Figures::Skip));
    }
    match format {
        Format::Json => println!("{}", render::json::sections(&sections)?),
        Format::Markdown => print!("{}", render::markdown::sections(&sections)),
    }
    Ok(())
}
