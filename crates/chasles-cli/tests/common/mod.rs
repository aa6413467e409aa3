//! What the CLI's test files share: running the `chasles` binary, with or without stdin.

#![allow(dead_code)] // each test file uses its own part

use std::io::Write;
use std::process::{Command, Output, Stdio};

/// `chasles ARGS`, waited for.
pub fn chasles(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_chasles"))
        .args(args)
        .output()
        .unwrap()
}

/// `chasles ARGS` with `input` on stdin.
pub fn with_stdin(args: &[&str], input: impl AsRef<[u8]>) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_chasles"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The child may exit before reading (a bad option, an input past a cap): a broken
    // pipe is fine.
    let _ = child.stdin.take().unwrap().write_all(input.as_ref());
    child.wait_with_output().unwrap()
}

/// The stdout of a run that must succeed (its stderr in the failure message).
pub fn stdout(o: &Output) -> String {
    assert!(
        o.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout.clone()).unwrap()
}

/// A built-in model's file on disk (`chasles skin`, `view` and `clip` take paths).
pub fn model(file: &str) -> String {
    chasles_models::on_disk()
        .unwrap()
        .join(file)
        .display()
        .to_string()
}
