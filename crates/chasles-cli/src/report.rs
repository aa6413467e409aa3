//! The tour's report on disk: one HTML page, readable with no server, rendered by
//! `chasles_paper::render::html` from the experiments' sections. Each section's pictures
//! are written next to it as the section is done; `index.html` is written last,
//! atomically, so the page never points at a missing picture.

use crate::output::write_atomic;
use anyhow::{Context, Result};
use chasles_paper::{render, Section};
use std::path::{Path, PathBuf};

/// The report being written.
pub struct Report {
    dir: PathBuf,
    sections: Vec<Section>,
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

    /// Writes the section's pictures and keeps the section (without the pictures' bytes)
    /// for the page.
    pub fn add(&mut self, mut section: Section) -> Result<()> {
        for f in section.figures() {
            write_atomic(&self.dir.join(&f.file), &f.bytes)?;
        }
        section.forget_bytes();
        self.sections.push(section);
        Ok(())
    }

    /// Claims that agree and claims made.
    pub fn tally(&self) -> (usize, usize) {
        chasles_paper::tally(&self.sections)
    }

    /// Writes `index.html` and returns its path.
    pub fn finish(&self) -> Result<PathBuf> {
        let path = self.dir.join("index.html");
        write_atomic(&path, render::html::page(&self.sections).as_bytes())?;
        Ok(path)
    }
}
