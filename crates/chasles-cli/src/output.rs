//! Writing result files whole or not at all: the bytes go to a temporary file in the same
//! folder, which is renamed over the target only when complete — and a command's several
//! outputs ([`write_all`]) are renamed only when all are complete. A failure (full disk, a
//! missing folder, bad input discovered late, Ctrl-C) never leaves a half-written file or
//! half of a command's outputs behind.

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_all(&[(path, bytes)])
}

/// Writes every `(path, bytes)` whole or none of them: each goes to a temporary file beside
/// its target first, and only when all are written are they renamed over their targets. A
/// folder that does not exist, a target that is a folder, a full disk or Ctrl-C before the
/// renames leaves every target as it was.
pub fn write_all(files: &[(&Path, &[u8])]) -> Result<()> {
    // What would make a rename fail, checked before anything is written: a target that is
    // a folder. (A folder made unwritable between the two phases can still fail a later
    // rename after an earlier one.)
    if let Some((p, _)) = files.iter().find(|(p, _)| p.is_dir()) {
        bail!("cannot write {}: it is a folder", p.display());
    }
    let mut ready = Vec::with_capacity(files.len());
    for (path, bytes) in files {
        let dir = parent_of(path);
        let mut tmp = tempfile::NamedTempFile::new_in(dir)
            .with_context(|| format!("cannot create a file in {}", dir.display()))?;
        let live = crate::cleanup::Live::new(tmp.path());
        tmp.write_all(bytes)
            .with_context(|| format!("cannot write {}", path.display()))?;
        ready.push((tmp, live, path));
    }
    for (tmp, _live, path) in ready {
        tmp.persist(path)
            .map_err(|e| e.error)
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}

/// A command's output files, made and checked, not yet written: each path, its bytes and
/// what to say once it is written (`None`: nothing; `Some("")`: `wrote PATH`;
/// `Some(detail)`: `wrote PATH (detail)`). Written all or none ([`write_all`]) once
/// everything the command was asked for is made.
#[derive(Default)]
pub struct Pending(Vec<(PathBuf, Vec<u8>, Option<String>)>);

impl Pending {
    /// Adds `bytes` for `path`, with what to say once it is written.
    pub fn add(&mut self, path: &Path, bytes: Vec<u8>, said: Option<String>) {
        self.0.push((path.to_path_buf(), bytes, said));
    }

    /// Writes every file, all or none, and returns the lines to say.
    pub fn write(&self) -> Result<Vec<String>> {
        let all: Vec<(&Path, &[u8])> = self
            .0
            .iter()
            .map(|(p, b, _)| (p.as_path(), &b[..]))
            .collect();
        write_all(&all)?;
        Ok(self
            .0
            .iter()
            .filter_map(|(p, _, said)| match said.as_deref()? {
                "" => Some(format!("wrote {}", p.display())),
                detail => Some(format!("wrote {} ({detail})", p.display())),
            })
            .collect())
    }
}

/// Refuses, before any work, a folder for frames (given with `flag`) whose parent is not a
/// folder, or that is a file or a folder with something in it (frames are never mixed with
/// other files, nor written over).
pub fn check_frames_dir(flag: &str, dir: &Path) -> Result<()> {
    let parent = parent_of(dir);
    if !parent.is_dir() {
        bail!(
            "{flag} {}: {} is not a folder",
            dir.display(),
            parent.display()
        );
    }
    match std::fs::read_dir(dir) {
        Ok(mut entries) => {
            if entries.next().is_some() {
                bail!("{flag} {} is not empty", dir.display());
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(e).with_context(|| format!("{flag} {}", dir.display())),
    }
}

/// `count` files, the `i`-th named and made by `make(i)`, written into a new hidden folder
/// beside `dir` (registered for removal on Ctrl-C, made as any folder is, so the umask
/// decides its mode) and renamed onto `dir` whole — over `dir` when it is an empty folder
/// ([`check_frames_dir`]) — so that a failure or an interruption leaves neither frames nor
/// the hidden folder behind. `before_rename` (the command's other outputs, written all or
/// none) runs once every frame is made and before the rename: when it fails, the frames go
/// too. Shows progress (`label`) on a terminal.
pub fn write_frames_dir(
    dir: &Path,
    count: usize,
    label: &str,
    mut make: impl FnMut(usize) -> Result<(String, Vec<u8>)>,
    before_rename: impl FnOnce() -> Result<()>,
) -> Result<()> {
    let parent = parent_of(dir);
    let tmp = (0..1000)
        .map(|k| parent.join(format!(".frames-{}-{k}", std::process::id())))
        .find(|p| std::fs::create_dir(p).is_ok())
        .ok_or_else(|| anyhow::anyhow!("cannot create a folder in {}", parent.display()))?;
    let _live = crate::cleanup::Live::new(&tmp);
    let written = (|| -> Result<()> {
        let bar = ProgressBar::new(count as u64);
        bar.set_style(
            ProgressStyle::with_template(&format!("{label} [{{bar:30}}] {{pos}}/{{len}}"))
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        for i in 0..count {
            let (name, bytes) = make(i)?;
            let path = tmp.join(name);
            std::fs::write(&path, bytes)
                .with_context(|| format!("cannot write {}", path.display()))?;
            bar.inc(1);
        }
        bar.finish_and_clear();
        before_rename()?;
        std::fs::rename(&tmp, dir)
            .with_context(|| format!("cannot move the frames to {}", dir.display()))
    })();
    if written.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    written
}

/// The folder `path` is in (`.` for a bare name).
pub fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// The extension of `path`, lower case ("" when none).
pub fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Refuses, before any work is done, an output path given with `flag` whose extension is
/// none of `allowed`: "--plot a.txt must end in .svg or .png".
pub fn check_extension(flag: &str, path: Option<&Path>, allowed: &[&str]) -> Result<()> {
    match path {
        Some(p) if !allowed.contains(&extension(p).as_str()) => {
            let list: Vec<String> = allowed.iter().map(|e| format!(".{e}")).collect();
            anyhow::bail!("{flag} {} must end in {}", p.display(), list.join(" or "))
        }
        _ => Ok(()),
    }
}

/// A number for text tables: shortest exact decimal, with an exponent for very small or
/// very large magnitudes (Rust's `{}` would print 20 zeros).
pub fn num(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 {
        "0".into()
    } else if (1e-5..1e16).contains(&a) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
