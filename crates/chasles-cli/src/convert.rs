//! `chasles convert`: one value between representations, or one JSON value per line
//! (serde-derived types whose errors name the line and the field's path; see
//! [`crate::repr::MotionJson`]).

use crate::repr::{motion_from_json_line, motion_from_numbers, parse_numbers, render, Fmt, Repr};
use anyhow::{anyhow, bail, Context, Result};
use std::io::{BufRead, Read, Write};

/// The longest line `--jsonl` reads: 1 MiB (a motion is about a hundred bytes).
pub const MAX_LINE: usize = 1 << 20;

/// Options of `chasles convert`.
pub struct ConvertArgs {
    /// Input representation (required for plain numbers and bare JSON arrays).
    pub from: Option<Repr>,
    /// Output representation.
    pub to: Repr,
    /// Numbers, after the options.
    pub values: Vec<String>,
    /// Read JSON lines from stdin.
    pub jsonl: bool,
    /// Fixed decimals instead of the shortest round-trip form.
    pub precision: Option<usize>,
}

/// Runs the command; returns the process exit code.
pub fn run(args: ConvertArgs) -> Result<i32> {
    let fmt = Fmt(args.precision);
    if args.jsonl {
        if !args.values.is_empty() {
            bail!("--jsonl reads stdin; do not also give values on the command line");
        }
        let stdin = std::io::stdin();
        let stdout = std::io::stdout();
        return run_jsonl(stdin.lock(), &mut stdout.lock(), args.from, args.to, fmt);
    }
    let from = args
        .from
        .ok_or_else(|| anyhow!("--from is required for values on the command line"))?;
    let numbers = parse_numbers(&args.values)?;
    let motion = motion_from_numbers(from, &numbers).with_context(|| format!("--from {from}"))?;
    let out = render(&motion, args.to, fmt).with_context(|| format!("--to {}", args.to))?;
    for n in motion.notes.iter().chain(out.notes.iter()) {
        eprintln!("note: {n}");
    }
    println!("{}", out.text);
    Ok(0)
}

/// One JSON value per input line, one JSON result per output line; a bad line gets
/// `{"line": N, "error": "..."}` in its place (so outputs stay aligned with inputs), a
/// message on stderr, and the exit code becomes 1. Blank lines are skipped.
///
/// Each line is a [`crate::repr::MotionJson`] read through `serde_path_to_error`, so the
/// error names the line and the path of the bad field (`line 4: rotation[3]: invalid
/// type: …`); a misspelt field, two forms at once or text after the value are errors.
pub fn run_jsonl(
    input: impl BufRead,
    out: &mut impl Write,
    from: Option<Repr>,
    to: Repr,
    fmt: Fmt,
) -> Result<i32> {
    let mut code = 0;
    let mut input = input;
    let mut bytes = Vec::new();
    for n in 1.. {
        // One line at a time, at most MAX_LINE bytes: an endless line (`< /dev/zero`)
        // is an error, not a read without end.
        bytes.clear();
        let got = (&mut input)
            .take(MAX_LINE as u64 + 1)
            .read_until(b'\n', &mut bytes)
            .with_context(|| format!("reading line {n}"))?;
        if got == 0 {
            break;
        }
        if bytes.len() > MAX_LINE {
            bail!("line {n} is longer than {MAX_LINE} bytes: not one JSON value per line");
        }
        let line =
            std::str::from_utf8(&bytes).with_context(|| format!("line {n} is not UTF-8 text"))?;
        if line.trim().is_empty() {
            continue;
        }
        let result = motion_from_json_line(line, from)
            .map_err(anyhow::Error::from)
            .and_then(|m| render(&m, to, fmt));
        match result {
            Ok(o) => writeln!(out, "{}", o.json)?,
            Err(e) => {
                code = 1;
                let msg = format!("{e:#}");
                eprintln!("error: line {n}: {msg}");
                writeln!(out, "{}", serde_json::json!({ "line": n, "error": msg }))?;
            }
        }
    }
    Ok(code)
}
