//! The input of `chasles blend` (Kavan et al. 2006, §2–5): one case or an array of cases,
//! read into blend's inputs and blended.
//!
//! A case is `{"transforms": [T, …], "weights": [w, …]}` (optional `"center": [x, y, z]`
//! for dec and qlb, `"precision"` and `"max_iterations"` for the iterative methods), or for
//! sclerp `{"from": T, "to": T, "t": x}`; a transform T is any object form of
//! `chasles convert --jsonl` ([`crate::repr::MotionFields`]).
//!
//! The input is a serde-derived type ([`CaseFile`], its transforms
//! [`crate::repr::MotionFields`]) read through `serde_path_to_error`: an error names the
//! case and the path of the bad field (`case 1: transforms[2].rotation[3]: invalid type: …`),
//! unknown fields are refused (a misspelt `"weight"` is an error, not ignored), so are the
//! two forms of a case at once, and so is text after the document. The fuzz target
//! `blend_cases` (fuzz/) runs [`blend_all`] on arbitrary text.

use crate::json::{from_json, FieldError};
use crate::repr::MotionObject;
use anyhow::{anyhow, bail, Context, Result};
use chasles::blend::{blend_dual_quats, Method, Options};
use chasles::{DualQuat, Vec3};
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{Deserializer, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;
use serde_json::{json, Value};
use std::fmt;

/// One case as written: `transforms` and `weights`, or sclerp's `from`, `to` and `t`, with
/// the options. Every field is optional here so that [`case`] can say which form is meant
/// and what it lacks; unknown fields are refused.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseFile {
    /// The transforms to blend.
    transforms: Option<Vec<MotionObject>>,
    /// One weight per transform.
    weights: Option<Vec<f64>>,
    /// sclerp: the transform at t = 0.
    from: Option<MotionObject>,
    /// sclerp: the transform at t = 1.
    to: Option<MotionObject>,
    /// sclerp: the parameter in [0, 1].
    t: Option<f64>,
    /// The centre of rotation for dec and qlb.
    center: Option<[f64; 3]>,
    /// Stopping tolerance of the iterative methods.
    precision: Option<f64>,
    /// Iteration limit of the iterative methods (a whole number; `5.0` is read as 5).
    max_iterations: Option<f64>,
}

/// The input: one case, or an array of cases.
struct Cases(Vec<CaseFile>);

impl<'de> Deserialize<'de> for Cases {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// An object (one case) or an array of them; the path into either is kept.
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Cases;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(
                    "a case {\"transforms\": [...], \"weights\": [...]} or an array of cases",
                )
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Cases, A::Error> {
                Vec::deserialize(SeqAccessDeserializer::new(seq)).map(Cases)
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Cases, A::Error> {
                CaseFile::deserialize(MapAccessDeserializer::new(map)).map(|c| Cases(vec![c]))
            }
        }
        d.deserialize_any(V)
    }
}

/// The transform `t` found at `at` (`from`, `transforms[2]`) of case `i`, its remarks
/// (normalization) added to `notes`.
fn transform(
    t: MotionObject,
    i: usize,
    at: &str,
    notes: &mut Vec<String>,
) -> Result<DualQuat<f64>, FieldError> {
    let m = t.0.motion().map_err(|e| e.within(at))?;
    notes.extend(m.notes.iter().map(|n| format!("case {i}: {at}: {n}")));
    Ok(m.dq)
}

/// One case as read: transforms, weights and options.
pub type Case = (Vec<DualQuat<f64>>, Vec<f64>, Options<f64>);

/// Case `i` as blend's inputs for `method`, remarks added to `notes`; errors name the field.
fn case(
    c: CaseFile,
    i: usize,
    method: Method,
    notes: &mut Vec<String>,
) -> Result<Case, FieldError> {
    let mut opt = Options::default();
    if let Some([x, y, z]) = c.center {
        opt.center = Vec3::new(x, y, z);
    }
    if let Some(p) = c.precision {
        if !(p > 0.0 && p.is_finite()) {
            return Err(FieldError::new(
                "precision",
                format!("must be positive, got {p}"),
            ));
        }
        opt.precision = p;
    }
    if let Some(n) = c.max_iterations {
        if !(n >= 0.0 && n.fract() == 0.0 && n <= 1e4) {
            return Err(FieldError::new(
                "max_iterations",
                format!("must be a whole number up to 10000 (the iterative methods converge in tens; a cap, not a goal), got {n}"),
            ));
        }
        opt.max_iterations = n as usize;
    }
    let sclerp = [
        ("from", c.from.is_some()),
        ("to", c.to.is_some()),
        ("t", c.t.is_some()),
    ];
    let weighted = [
        ("transforms", c.transforms.is_some()),
        ("weights", c.weights.is_some()),
    ];
    let given = |fields: &[(&'static str, bool)]| fields.iter().find(|f| f.1).map(|f| f.0);
    match (given(&sclerp), given(&weighted)) {
        (Some(a), Some(b)) => Err(FieldError::new(
            "",
            format!("conflicting fields `{b}` and `{a}`: give `transforms` and `weights`, or for sclerp `from`, `to` and `t`"),
        )),
        (Some(_), None) => {
            if method != Method::ScLerp {
                return Err(FieldError::new(
                    "",
                    format!(
                        "`from`/`to`/`t` is the sclerp form; for {} give `transforms` and `weights`",
                        method.name()
                    ),
                ));
            }
            let missing = |name: &str| FieldError::new("", format!("missing field `{name}`"));
            let from = transform(c.from.ok_or_else(|| missing("from"))?, i, "from", notes)?;
            let to = transform(c.to.ok_or_else(|| missing("to"))?, i, "to", notes)?;
            let t = c.t.ok_or_else(|| missing("t"))?;
            if !(0.0..=1.0).contains(&t) {
                return Err(FieldError::new("t", format!("must be in [0, 1], got {t}")));
            }
            Ok((vec![from, to], vec![1.0 - t, t], opt))
        }
        (None, _) => {
            let ts = c
                .transforms
                .ok_or_else(|| FieldError::new("", "missing field `transforms`"))?;
            let w = c
                .weights
                .ok_or_else(|| FieldError::new("", "missing field `weights`"))?;
            let x = ts
                .into_iter()
                .enumerate()
                .map(|(k, t)| transform(t, i, &format!("transforms[{k}]"), notes))
                .collect::<Result<Vec<_>, _>>()?;
            Ok((x, w, opt))
        }
    }
}

/// An error reading the input, its leading `[i]` (the index of the case) written
/// `case i: `; a single case is case 0.
fn case_error(e: FieldError) -> anyhow::Error {
    if e.path.is_empty() {
        return anyhow!(e);
    }
    let indexed = e.path.strip_prefix('[').and_then(|p| p.split_once(']'));
    match indexed {
        Some((i, rest)) if i.parse::<usize>().is_ok() => {
            let rest = rest.strip_prefix('.').unwrap_or(rest);
            anyhow!("case {i}: {}", FieldError::new(rest, e.reason))
        }
        _ => anyhow!("case 0: {e}"),
    }
}

/// What [`blend_all`] gives: the output array (one object per case), the first case as
/// read (for the pictures) and remarks for stderr.
pub struct Blended {
    /// The JSON array `chasles blend` prints.
    pub out: Value,
    /// The first case, if any.
    pub first: Option<Case>,
    /// Remarks (a transform normalized), each naming its case and field.
    pub notes: Vec<String>,
}

/// Blends every case of `input` (JSON text) with `method`. The input is read as [`Cases`]
/// through `serde_path_to_error`: errors name the case and the path of the bad field; a
/// result that is not finite is an error naming its field.
pub fn blend_all(method: Method, input: &str) -> Result<Blended> {
    let Cases(cases) = from_json(input).map_err(case_error)?;
    let mut out = Vec::with_capacity(cases.len());
    let mut first = None;
    let mut notes = Vec::new();
    for (i, c) in cases.into_iter().enumerate() {
        let (x, w, opt) = case(c, i, method, &mut notes).with_context(|| format!("case {i}"))?;
        let b = blend_dual_quats(method, &x, &w, &opt).with_context(|| format!("case {i}"))?;
        if first.is_none() {
            first = Some((x, w, opt));
        }
        let mut o = json!({
            "rotation": b.dq.real.to_array(),
            "translation": b.matrix.translation().to_array(),
            "matrix": b.matrix.m,
            "dq": b.dq.to_array(),
            "rigid": b.rigid,
        });
        if let Some(it) = b.iterations {
            o["iterations"] = json!(it);
            // Stopped by the cap (the stopping rule, tested before each update, had not
            // stopped it; it is not tested after the last): said, in the output and on
            // stderr.
            if it == opt.max_iterations {
                o["capped"] = json!(true);
                notes.push(format!(
                    "case {i}: {} ran all max_iterations = {it} updates; its stopping rule (precision {:e}) had not stopped it",
                    method.name(),
                    opt.precision
                ));
            }
        }
        if let Some(at) = crate::repr::first_non_finite(&o, "") {
            bail!("case {i}: the blend's {at} is not a finite number: the input is beyond the range of f64");
        }
        out.push(o);
    }
    Ok(Blended {
        out: Value::Array(out),
        first,
        notes,
    })
}
