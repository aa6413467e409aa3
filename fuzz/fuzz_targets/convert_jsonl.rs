//! Bytes as `chasles convert --jsonl`'s standard input (the first two bytes pick `--from`,
//! `--to` and `--precision`), run by the CLI's own module (`crates/chasles-cli/src/convert.rs`,
//! compiled in by path: the binary's modules are not a library): one output line per input
//! line, each a finite value or `{"line": N, "error": …}`, or a typed error for the whole
//! input (a line past 1 MiB, text that is not UTF-8) — never a panic.
#![no_main]

#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/convert.rs"]
mod convert;
#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/json.rs"]
mod json;
#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/repr.rs"]
mod repr;

use libfuzzer_sys::fuzz_target;
use repr::{Fmt, Repr};

/// Every representation name `--from` and `--to` take (the Euler orders all 24).
fn reprs() -> Vec<Repr> {
    let mut names: Vec<String> = [
        "quat",
        "matrix",
        "matrix3",
        "matrix4",
        "axis-angle",
        "rotvec",
        "rt",
        "dq",
        "screw",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for a in ["x", "y", "z"] {
        for b in ["x", "y", "z"] {
            for c in ["x", "y", "z"] {
                if a != b && b != c {
                    names.push(format!("euler:{a}{b}{c}"));
                    names.push(format!("euler:{}", format!("{a}{b}{c}").to_uppercase()));
                }
            }
        }
    }
    names
        .iter()
        .map(|n| n.parse().expect("a representation's name"))
        .collect()
}

fuzz_target!(|data: &[u8]| {
    let [a, b, input @ ..] = data else { return };
    let all = reprs();
    let from = (*a as usize % (all.len() + 1))
        .checked_sub(1)
        .map(|i| all[i]);
    let to = all[*b as usize % all.len()];
    let precision = (b >> 6 != 0).then_some(usize::from(*a) % 18);
    let mut out = Vec::new();
    if convert::run_jsonl(input, &mut out, from, to, Fmt(precision)).is_ok() {
        let text = std::str::from_utf8(&out).expect("output is UTF-8");
        for line in text.lines() {
            let v: serde_json::Value =
                serde_json::from_str(line).expect("each output line is JSON");
            if v.get("error").is_none() {
                assert!(repr::first_non_finite(&v, "").is_none(), "{line}");
            }
        }
    }
});
