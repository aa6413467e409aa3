//! Text as `chasles blend`'s input (the first byte picks the method), read and blended by
//! the CLI's own module (`crates/chasles-cli/src/blend_case.rs`, compiled in by path: the
//! binary's modules are not a library): a JSON array of finite results or a typed error,
//! never a panic and never a result that is not finite.
#![no_main]

#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/blend_case.rs"]
mod blend_case;
#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/json.rs"]
mod json;
#[allow(dead_code)]
#[path = "../../crates/chasles-cli/src/repr.rs"]
mod repr;

use chasles::blend::Method;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let method = Method::ALL[usize::from(pick) % Method::ALL.len()];
    if let Ok(b) = blend_case::blend_all(method, text) {
        assert!(
            repr::first_non_finite(&b.out, "").is_none(),
            "{method:?}: {}",
            b.out
        );
    }
});
