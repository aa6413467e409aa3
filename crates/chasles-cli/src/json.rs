//! Reading JSON into serde-derived types, with errors that name the path of the bad field.
//!
//! Every JSON input of the CLI (blend cases, `convert --jsonl` values, key files) is read
//! through [`from_json`]: serde-derived types deserialized via `serde_path_to_error`, so a
//! field of the wrong shape is a [`FieldError`] naming its path (`transforms[2].rotation[3]`)
//! with serde's reason; text after the document is refused. Checks made after reading (a
//! quaternion of zero length, a matrix that is not rigid) name their field the same way.

use chasles::EulerOrder;
use serde::de::{self, Deserialize, Deserializer, SeqAccess, Visitor};
use std::fmt;

/// What is wrong with a JSON value, and where: the path of the field (empty for the whole
/// value), e.g. `transforms[0].rotation`.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// The field's path, as `serde_path_to_error` writes it; empty for the whole value.
    pub path: String,
    /// What is wrong with it.
    pub reason: String,
}

impl FieldError {
    /// The error `reason` at `path`.
    pub fn new(path: impl Into<String>, reason: impl Into<String>) -> Self {
        FieldError {
            path: path.into(),
            reason: reason.into(),
        }
    }

    /// The same error seen from the value that holds it at `prefix`: `prefix.path`.
    pub fn within(self, prefix: &str) -> Self {
        FieldError {
            path: join(prefix, &self.path),
            reason: self.reason,
        }
    }
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            f.write_str(&self.reason)
        } else {
            write!(f, "{}: {}", self.path, self.reason)
        }
    }
}

impl std::error::Error for FieldError {}

/// The path `b` inside the field at `a`: `a.b`, or `a[i]` when `b` is an index.
pub fn join(a: &str, b: &str) -> String {
    match (a.is_empty(), b.is_empty()) {
        (true, _) => b.to_string(),
        (_, true) => a.to_string(),
        _ if b.starts_with('[') => format!("{a}{b}"),
        _ => format!("{a}.{b}"),
    }
}

/// serde_json's message for `e`; for a `line` of JSON lines, whose position is on the
/// line given elsewhere, "at column N" rather than "at line 1 column N".
fn message(e: &serde_json::Error, line: bool) -> String {
    let s = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    match s.strip_suffix(&suffix) {
        Some(m) if line && e.line() == 1 => format!("{m} at column {}", e.column()),
        _ => s,
    }
}

/// A `serde_path_to_error` error as a [`FieldError`]: its path (empty at the root) and
/// serde's message, syntax errors marked as such.
fn field_error(e: serde_path_to_error::Error<serde_json::Error>, line: bool) -> FieldError {
    let path = e.path().to_string();
    let path = if path == "." { String::new() } else { path };
    let inner = e.into_inner();
    let reason = if inner.is_syntax() || inner.is_eof() {
        format!("not valid JSON: {}", message(&inner, line))
    } else {
        message(&inner, line)
    };
    FieldError { path, reason }
}

/// Reads `text` as `T` ([`from_json`]); `line`: it is one line of JSON lines.
fn read<'a, T: Deserialize<'a>>(text: &'a str, line: bool) -> Result<T, FieldError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let value = serde_path_to_error::deserialize(&mut de).map_err(|e| field_error(e, line))?;
    de.end()
        .map_err(|e| FieldError::new("", format!("not valid JSON: {}", message(&e, line))))?;
    Ok(value)
}

/// Reads one JSON document as `T`, naming the path of the field that does not fit; nothing
/// but white space may follow the document. serde's messages give the line and column.
pub fn from_json<'a, T: Deserialize<'a>>(text: &'a str) -> Result<T, FieldError> {
    read(text, false)
}

/// [`from_json`] for one line of JSON lines: positions are given as the column alone, the
/// line being named by the caller.
pub fn from_json_line<'a, T: Deserialize<'a>>(text: &'a str) -> Result<T, FieldError> {
    read(text, true)
}

/// Numbers as JSON may give them: one number, or an array of numbers nested to any depth,
/// read flat in order (`[[1, 0], [0, 1]]` is `[1, 0, 0, 1]`), so a matrix may be written as
/// rows or as one list. A non-number names its place, e.g. `matrix[1][2]`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Numbers(pub Vec<f64>);

impl<'de> Deserialize<'de> for Numbers {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// Collects numbers, recursing into arrays.
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Numbers;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number or an array of numbers")
            }
            fn visit_f64<E: de::Error>(self, x: f64) -> Result<Numbers, E> {
                Ok(Numbers(vec![x]))
            }
            fn visit_i64<E: de::Error>(self, x: i64) -> Result<Numbers, E> {
                Ok(Numbers(vec![x as f64]))
            }
            fn visit_u64<E: de::Error>(self, x: u64) -> Result<Numbers, E> {
                Ok(Numbers(vec![x as f64]))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Numbers, A::Error> {
                let mut out = Vec::new();
                while let Some(Numbers(x)) = seq.next_element()? {
                    out.extend(x);
                }
                Ok(Numbers(out))
            }
        }
        d.deserialize_any(V)
    }
}

impl Numbers {
    /// The numbers, which must be `n`: else an error at `path` saying what was expected
    /// (`layout`, e.g. "[w, x, y, z]", may be empty).
    pub fn exactly(&self, n: usize, path: &str, layout: &str) -> Result<&[f64], FieldError> {
        if self.0.len() == n {
            return Ok(&self.0);
        }
        let what = if n == 1 { "number" } else { "numbers" };
        let layout = if layout.is_empty() {
            String::new()
        } else {
            format!(" {layout}")
        };
        Err(FieldError::new(
            path,
            format!("expected {n} {what}{layout}, got {}", self.0.len()),
        ))
    }
}

/// An Euler order given as a string, `"xyz"` (extrinsic) or `"XYZ"` (intrinsic); anything
/// else is an error at the field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Order(pub EulerOrder);

impl<'de> Deserialize<'de> for Order {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map(Order).map_err(de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_flatten_and_name_the_bad_element() {
        assert_eq!(
            from_json::<Numbers>("[[1, 0], [-2, 0.5]]").unwrap(),
            Numbers(vec![1.0, 0.0, -2.0, 0.5])
        );
        assert_eq!(from_json::<Numbers>("3").unwrap(), Numbers(vec![3.0]));
        let e = from_json::<Numbers>("[[1, 0], [0, \"a\"]]").unwrap_err();
        assert_eq!(e.path, "[1][1]");
        assert!(e.reason.contains("expected a number"), "{e}");
    }

    #[test]
    fn syntax_errors_and_trailing_text_are_refused() {
        let e = from_json::<Numbers>("[1, 2").unwrap_err();
        assert!(e.reason.starts_with("not valid JSON"), "{e}");
        let e = from_json::<Numbers>("[1, 2] x").unwrap_err();
        assert!(e.reason.starts_with("not valid JSON"), "{e}");
        assert!(from_json::<Numbers>("[1, 2]  \n").is_ok());
        let e = from_json_line::<Numbers>("[1, \"a\"]").unwrap_err();
        assert!(e.reason.ends_with("at column 7"), "{e}");
        let e = from_json::<Numbers>("[1,\n \"a\"]").unwrap_err();
        assert!(e.reason.ends_with("at line 2 column 4"), "{e}");
    }

    #[test]
    fn paths_join_fields_and_indices() {
        assert_eq!(join("transforms[0]", "rotation"), "transforms[0].rotation");
        assert_eq!(join("matrix", "[2]"), "matrix[2]");
        assert_eq!(join("", "angle"), "angle");
        assert_eq!(join("from", ""), "from");
        let e = FieldError::new("rotation", "bad").within("to");
        assert_eq!(e.to_string(), "to.rotation: bad");
        assert_eq!(FieldError::new("", "bad").to_string(), "bad");
    }

    #[test]
    fn orders_parse_or_name_the_problem() {
        assert_eq!(
            from_json::<Order>("\"ZYX\"").unwrap(),
            Order("ZYX".parse().unwrap())
        );
        let e = from_json::<Order>("\"xxy\"").unwrap_err();
        assert!(e.reason.contains("unknown Euler order"), "{e}");
    }
}
