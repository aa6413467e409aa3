//! Files read with a size cap, and only when they are regular files: a device (`/dev/zero`),
//! a folder or a pipe posing as a file, or a file past the cap, is a typed error before
//! anything is read whole — no input can make a load read without end or exhaust memory.
//! The caps are the crate's (and the CLI's) documented ceilings for each kind of input.

use crate::error::{Result, SkinError};
use std::io::Read;
use std::path::Path;

/// The largest glTF, GLB or JSON rig file read: 1 GiB.
pub const MAX_MODEL_BYTES: u64 = 1 << 30;
/// The largest pose, key or blend-case file read: 64 MiB.
pub const MAX_TEXT_BYTES: u64 = 64 << 20;

/// The regular file `path`, opened, and its length; a device, folder or pipe is refused.
fn open_regular(path: &Path) -> Result<(std::fs::File, u64)> {
    let name = || path.display().to_string();
    let io = |cause| SkinError::Io {
        path: name(),
        cause,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(SkinError::NotAFile { path: name() });
    }
    Ok((std::fs::File::open(path).map_err(io)?, meta.len()))
}

/// The bytes of the regular file `path`, at most `limit` of them.
pub fn read_file(path: &Path, limit: u64) -> Result<Vec<u8>> {
    let (file, len) = open_regular(path)?;
    let name = path.display().to_string();
    if len > limit {
        return Err(SkinError::TooLarge {
            path: name,
            size: len,
            limit,
        });
    }
    read_capped(file, limit, &name)
}

/// The first `n` bytes of the regular file `path` (fewer if it is shorter; what follows is
/// not read), with `n` at most `limit`: a glTF buffer's declared length.
pub fn read_prefix(path: &Path, n: u64, limit: u64) -> Result<Vec<u8>> {
    let name = path.display().to_string();
    if n > limit {
        return Err(SkinError::TooLarge {
            path: name,
            size: n,
            limit,
        });
    }
    let (file, _) = open_regular(path)?;
    read_capped(file.take(n), n, &name)
}

/// All of `reader`, at most `limit` bytes (a file that grew, or stdin); `name` names it.
pub fn read_capped(reader: impl Read, limit: u64, name: &str) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    reader
        .take(limit.saturating_add(1))
        .read_to_end(&mut out)
        .map_err(|cause| SkinError::Io {
            path: name.to_string(),
            cause,
        })?;
    if out.len() as u64 > limit {
        return Err(SkinError::TooLarge {
            path: name.to_string(),
            size: out.len() as u64,
            limit,
        });
    }
    Ok(out)
}

/// [`read_file`] as UTF-8 text.
pub fn read_text(path: &Path, limit: u64) -> Result<String> {
    String::from_utf8(read_file(path, limit)?).map_err(|e| SkinError::Io {
        path: path.display().to_string(),
        cause: std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text ({e})"),
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_folders_and_big_files_are_refused_before_reading() {
        let dir = tempfile::tempdir().unwrap();
        assert!(matches!(
            read_file(dir.path(), 10),
            Err(SkinError::NotAFile { .. })
        ));
        if Path::new("/dev/zero").exists() {
            let e = read_file(Path::new("/dev/zero"), 10).unwrap_err();
            assert!(matches!(e, SkinError::NotAFile { .. }), "{e}");
        }
        let f = dir.path().join("f");
        std::fs::write(&f, [7u8; 11]).unwrap();
        let e = read_file(&f, 10).unwrap_err();
        assert!(
            e.to_string().contains("11 bytes") && e.to_string().contains("10"),
            "{e}"
        );
        assert_eq!(read_file(&f, 11).unwrap().len(), 11);
        // A stream past its cap stops at the cap.
        let e = read_capped(std::io::repeat(0).take(1 << 20), 1000, "stdin").unwrap_err();
        assert!(matches!(e, SkinError::TooLarge { limit: 1000, .. }), "{e}");
        // A prefix stops at its length; past the limit it is refused.
        assert_eq!(read_prefix(&f, 4, 10).unwrap(), [7u8; 4]);
        assert!(matches!(
            read_prefix(&f, 40, 10),
            Err(SkinError::TooLarge { size: 40, .. })
        ));
        std::fs::write(&f, [0xff, 0xfe]).unwrap();
        assert!(read_text(&f, 10).unwrap_err().to_string().contains("UTF-8"));
    }
}
