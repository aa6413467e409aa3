//! `chasles blend`: blend rigid transformations given as JSON (Kavan et al. 2006, §2–5).
//!
//! Input: one case or an array of cases. A case is
//! `{"transforms": [T, …], "weights": [w, …]}` (optional `"center": [x, y, z]` for dec and
//! qlb, `"precision"` and `"max_iterations"` for the iterative methods), or for sclerp
//! `{"from": T, "to": T, "t": x}`. A transform T is `{"rotation": [w,x,y,z],
//! "translation": [x,y,z]}`, `{"matrix": [[r00,r01,r02,t0],…,[0,0,0,1]]}` (row-major) or
//! `{"dq": [8 numbers]}`. Output: a JSON array, one object per case in order, with
//! `rotation`, `translation`, `matrix`, `dq`, `rigid` and, for dec, log-iter and dib,
//! `iterations`. `--plot`, `--render` and `--gif` draw the first case
//! ([`crate::blend_pictures`]).

use crate::blend_pictures;
use crate::output::write_atomic;
use crate::picture_args::Pictures;
use crate::repr::motion_from_json;
use anyhow::{anyhow, bail, Context, Result};
use chasles::blend::{blend_dual_quats, Method, Options};
use chasles::{DualQuat, Vec3};
use serde_json::{json, Map, Value};
use std::io::Read;

fn number(o: &Map<String, Value>, name: &str) -> Result<Option<f64>> {
    match o.get(name) {
        None => Ok(None),
        Some(v) => v
            .as_f64()
            .map(Some)
            .ok_or_else(|| anyhow!("field '{name}': expected a number, found {v}")),
    }
}

fn transform(v: &Value, at: &str) -> Result<DualQuat<f64>> {
    if !v.is_object() {
        bail!("{at}: expected an object such as {{\"rotation\": [w,x,y,z], \"translation\": [x,y,z]}}");
    }
    let m = motion_from_json(v, None).with_context(|| at.to_string())?;
    for n in &m.notes {
        eprintln!("note: {at}: {n}");
    }
    Ok(m.dq)
}

/// One case as read: transforms, weights and options.
type Case = (Vec<DualQuat<f64>>, Vec<f64>, Options<f64>);

/// One case: transforms, weights and options.
fn case(v: &Value, method: Method) -> Result<Case> {
    let o = v
        .as_object()
        .ok_or_else(|| anyhow!("expected an object with 'transforms' and 'weights'"))?;
    let mut opt = Options::default();
    if let Some(c) = o.get("center") {
        let c: Vec<f64> = c
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_f64).collect())
            .unwrap_or_default();
        if c.len() != 3 {
            bail!("field 'center': expected 3 numbers");
        }
        opt.center = Vec3::new(c[0], c[1], c[2]);
    }
    if let Some(p) = number(o, "precision")? {
        if !(p > 0.0 && p.is_finite()) {
            bail!("field 'precision': must be positive, got {p}");
        }
        opt.precision = p;
    }
    if let Some(n) = number(o, "max_iterations")? {
        if !(n >= 0.0 && n.fract() == 0.0 && n <= 1e6) {
            bail!("field 'max_iterations': must be a whole number up to 1e6, got {n}");
        }
        opt.max_iterations = n as usize;
    }
    if o.contains_key("from") || o.contains_key("to") {
        if method != Method::ScLerp {
            bail!(
                "'from'/'to'/'t' is the sclerp form; for {} give 'transforms' and 'weights'",
                method.name()
            );
        }
        let from = transform(
            o.get("from")
                .ok_or_else(|| anyhow!("missing field 'from'"))?,
            "from",
        )?;
        let to = transform(
            o.get("to").ok_or_else(|| anyhow!("missing field 'to'"))?,
            "to",
        )?;
        let t = number(o, "t")?.ok_or_else(|| anyhow!("missing field 't'"))?;
        if !(0.0..=1.0).contains(&t) {
            bail!("field 't': must be in [0, 1], got {t}");
        }
        return Ok((vec![from, to], vec![1.0 - t, t], opt));
    }
    let ts = o
        .get("transforms")
        .ok_or_else(|| anyhow!("missing field 'transforms'"))?
        .as_array()
        .ok_or_else(|| anyhow!("field 'transforms': expected an array"))?;
    let x = ts
        .iter()
        .enumerate()
        .map(|(i, t)| transform(t, &format!("transforms[{i}]")))
        .collect::<Result<Vec<_>>>()?;
    let ws = o
        .get("weights")
        .ok_or_else(|| anyhow!("missing field 'weights'"))?
        .as_array()
        .ok_or_else(|| anyhow!("field 'weights': expected an array"))?;
    let w = ws
        .iter()
        .enumerate()
        .map(|(i, v)| {
            v.as_f64()
                .ok_or_else(|| anyhow!("weights[{i}]: expected a number, found {v}"))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok((x, w, opt))
}

/// Blends every case of `input` (JSON text) with `method`, returning the output array and
/// the first case as read.
fn blend_all(method: Method, input: &str) -> Result<(Value, Option<Case>)> {
    let v: Value =
        serde_json::from_str(input).map_err(|e| anyhow!("input is not valid JSON: {e}"))?;
    let cases: Vec<&Value> = match &v {
        Value::Array(a) => a.iter().collect(),
        other => vec![other],
    };
    let mut out = Vec::with_capacity(cases.len());
    let mut first = None;
    for (i, c) in cases.iter().enumerate() {
        let result = case(c, method).and_then(|(x, w, opt)| {
            let b = blend_dual_quats(method, &x, &w, &opt)?;
            if first.is_none() {
                first = Some((x, w, opt));
            }
            Ok(b)
        });
        let b = result.with_context(|| format!("case {i}"))?;
        let mut o = json!({
            "rotation": b.dq.real.to_array(),
            "translation": b.matrix.translation().to_array(),
            "matrix": b.matrix.m,
            "dq": b.dq.to_array(),
            "rigid": b.rigid,
        });
        if let Some(it) = b.iterations {
            o["iterations"] = json!(it);
        }
        out.push(o);
    }
    Ok((Value::Array(out), first))
}

/// Runs `chasles blend`; `pictures` are the `--plot` (SVG), `--render` (PNG), `--gif`
/// (GIF) and `--sphere` (PNG) paths, drawn for the first case (see
/// [`crate::blend_pictures`]).
pub fn run(m: Method, input: &str, pictures: &Pictures) -> Result<()> {
    pictures.check(&["svg"])?;
    let text = if input == "-" {
        let mut s = String::new();
        std::io::stdin()
            .read_to_string(&mut s)
            .context("reading stdin")?;
        s
    } else {
        std::fs::read_to_string(input).with_context(|| format!("cannot read {input}"))?
    };
    let (out, first) = blend_all(m, &text)?;
    println!("{}", serde_json::to_string_pretty(&out)?);
    if pictures.any() {
        let (x, w, opt) = first.ok_or_else(|| anyhow!("no cases to draw"))?;
        let c = blend_pictures::Case {
            x: &x,
            w: &w,
            opt: &opt,
        };
        let Pictures {
            plot,
            render,
            gif,
            sphere,
        } = pictures;
        if let Some(p) = plot {
            write_atomic(p, blend_pictures::plot(&c)?.as_bytes())?;
            eprintln!("wrote {}", p.display());
        }
        if let Some(p) = render {
            write_atomic(p, &blend_pictures::render(&c)?.png())?;
            eprintln!("wrote {}", p.display());
        }
        if let Some(p) = gif {
            let frames = blend_pictures::animate(&c, m, 40)?;
            write_atomic(p, &chasles_viz::gif(&frames, 5)?)?;
            eprintln!("wrote {}", p.display());
        }
        if let Some(p) = sphere {
            write_atomic(p, &blend_pictures::sphere(&c, m)?.png())?;
            eprintln!("wrote {}", p.display());
        }
    }
    Ok(())
}
