//! Temporaries removed when the run is stopped: `write_atomic`'s hidden files, the tour's
//! report being built, `--frames-dir`'s hidden folder. Each registers while it exists
//! ([`Live`]); on SIGINT or SIGTERM (the `ctrlc` crate's handler) every registered path is
//! removed and the process ends with exit 130, so an interrupted run leaves no `.tmpXXXX`
//! or half report behind. (SIGKILL cannot be caught; nothing can clean up after it.)

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// The paths to remove if the run is stopped.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Set by the handler before it removes anything.
static STOPPING: AtomicBool = AtomicBool::new(false);

/// Whether SIGINT or SIGTERM has come: the handler is removing the temporaries and will end
/// the run with exit 130. An error the run meets after that — a write into the folder the
/// handler just removed — is the interruption's doing, not an error to report: the caller
/// waits for the handler instead ([`await_exit`]).
pub fn stopping() -> bool {
    STOPPING.load(Ordering::SeqCst)
}

/// Waits for the handler to end the process (exit 130).
pub fn await_exit() -> ! {
    loop {
        std::thread::park();
    }
}

/// Installs the handler (once, at start).
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        STOPPING.store(true, Ordering::SeqCst);
        if let Ok(paths) = LIVE.lock() {
            for p in paths.iter() {
                // The run goes on while this thread removes its temporaries: a folder may
                // gain a file between `remove_dir_all`'s listing and its last `rmdir`, so
                // try again until it is gone.
                for _ in 0..1000 {
                    let gone = if p.is_dir() {
                        std::fs::remove_dir_all(p)
                    } else {
                        std::fs::remove_file(p)
                    };
                    if gone.is_ok() || !p.exists() {
                        break;
                    }
                }
            }
        }
        eprintln!("\nchasles: interrupted; temporary files removed");
        std::process::exit(130);
    });
}

/// A temporary path, registered while this lives.
pub struct Live(PathBuf);

impl Live {
    /// Registers `path` (a file or a folder) for removal if the run is stopped.
    pub fn new(path: &Path) -> Self {
        if let Ok(mut paths) = LIVE.lock() {
            paths.push(path.to_path_buf());
        }
        Live(path.to_path_buf())
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        if let Ok(mut paths) = LIVE.lock() {
            if let Some(i) = paths.iter().rposition(|p| *p == self.0) {
                paths.swap_remove(i);
            }
        }
    }
}
