//! The tour's report on disk: one HTML page, readable with no server, rendered by
//! `chasles_paper::render::html` from the experiments' sections. Everything is written into
//! a hidden folder beside the report's (`.DIR-PID`) and put in place only when the page is
//! done: a tour that fails or is stopped half-way leaves the previous report as it was and
//! no half report (the hidden folder is removed when the report is dropped unfinished).

use crate::output::write_atomic;
use anyhow::{Context, Result};
use chasles_paper::{render, Section};
use std::path::{Path, PathBuf};

/// The report being written.
pub struct Report {
    _live: crate::cleanup::Live,
    dir: PathBuf,
    building: PathBuf,
    done: bool,
    sections: Vec<Section>,
}

impl Report {
    /// A report to be put into `dir` when finished.
    pub fn new(dir: &Path) -> Result<Self> {
        let parent = crate::output::parent_of(dir);
        std::fs::create_dir_all(parent)
            .with_context(|| format!("cannot create {}", parent.display()))?;
        let base = dir
            .file_name()
            .map_or("report".into(), |n| n.to_string_lossy().into_owned());
        let building = parent.join(format!(".{base}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&building);
        std::fs::create_dir(&building)
            .with_context(|| format!("cannot create {}", building.display()))?;
        Ok(Report {
            _live: crate::cleanup::Live::new(&building),
            dir: dir.to_path_buf(),
            building,
            done: false,
            sections: Vec::new(),
        })
    }

    /// Writes the section's pictures and keeps the section (without the pictures' bytes)
    /// for the page.
    pub fn add(&mut self, mut section: Section) -> Result<()> {
        for f in section.figures() {
            write_atomic(&self.building.join(&f.file), &f.bytes)?;
        }
        section.forget_bytes();
        self.sections.push(section);
        Ok(())
    }

    /// Claims that agree and claims made.
    pub fn tally(&self) -> (usize, usize) {
        chasles_paper::tally(&self.sections)
    }

    /// Writes `index.html`, puts the report in place of any earlier one, and returns the
    /// page's path.
    pub fn finish(&mut self) -> Result<PathBuf> {
        write_atomic(
            &self.building.join("index.html"),
            render::html::page(&self.sections).as_bytes(),
        )?;
        // The old report aside, the new one in, the old one gone.
        let old = self.building.with_extension("old");
        let had_old = self.dir.exists();
        if had_old {
            std::fs::rename(&self.dir, &old)
                .with_context(|| format!("cannot replace {}", self.dir.display()))?;
        }
        if let Err(e) = std::fs::rename(&self.building, &self.dir) {
            if had_old {
                let _ = std::fs::rename(&old, &self.dir);
            }
            return Err(e).with_context(|| format!("cannot write {}", self.dir.display()));
        }
        if had_old {
            let _ = std::fs::remove_dir_all(&old);
        }
        self.done = true;
        Ok(self.dir.join("index.html"))
    }
}

impl Drop for Report {
    /// An unfinished report leaves nothing behind.
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_dir_all(&self.building);
        }
    }
}
