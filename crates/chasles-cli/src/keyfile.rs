//! Key-frame files (TOML or JSON) and the built-in sets.
//!
//! ```toml
//! order = "xyz"            # optional: Euler order for keys given as `euler` (default xyz)
//! [[keys]]
//! angle = 1.0              # radians, about `axis` (Dam et al. Table 5.1)
//! axis = [1, 3, 0]
//! time = 0.0               # optional, on every key or on none
//! [[keys]]
//! quat = [1, 0, 0, 0]      # [w, x, y, z]
//! [[keys]]
//! euler = [0.1, 0.2, 0.3]  # radians
//! order = "ZYX"            # optional per key
//! ```
//!
//! JSON takes the same shape, `{"order": "xyz", "keys": [{"angle": 1, "axis": [1, 3, 0]}, …]}`,
//! or just the array of keys. Syntax errors name the line and column; other errors name
//! the key and field, e.g. `keys[2].axis`.

use anyhow::{anyhow, bail, Context, Result};
use chasles::interp::examples;
use chasles::{EulerOrder, Quat, Vec3};
use serde::Deserialize;
use std::path::Path;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Doc {
    #[serde(default)]
    order: Option<String>,
    keys: Vec<Spec>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum JsonDoc {
    Doc(Doc),
    Keys(Vec<Spec>),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Spec {
    angle: Option<f64>,
    axis: Option<[f64; 3]>,
    quat: Option<[f64; 4]>,
    euler: Option<[f64; 3]>,
    order: Option<String>,
    time: Option<f64>,
}

/// Key frames as read: rotations, optional times, and where they came from.
pub struct Keys {
    /// The key rotations.
    pub quats: Vec<Quat<f64>>,
    /// Times, when every key has one.
    pub times: Option<Vec<f64>>,
    /// A name for messages: the file or `builtin:NAME`.
    pub source: String,
}

/// Reads `builtin:NAME` or a `.toml` / `.json` file.
pub fn load(spec: &str) -> Result<Keys> {
    if let Some(name) = spec.strip_prefix("builtin:") {
        let set = examples::by_name(name).ok_or_else(|| {
            let names: Vec<&str> = examples::all().iter().map(|s| s.name).collect();
            anyhow!(
                "no built-in key set '{name}'; there are: {}",
                names.join(", ")
            )
        })?;
        return Ok(Keys {
            quats: set.keys,
            times: None,
            source: spec.to_string(),
        });
    }
    let path = Path::new(spec);
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read key file {spec}"))?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let doc = match ext.as_str() {
        "toml" => toml::from_str::<Doc>(&text)
            .map_err(|e| anyhow!("{spec}: {}", one_line(&e.to_string())))?,
        "json" => match serde_json::from_str::<JsonDoc>(&text) {
            Ok(JsonDoc::Doc(d)) => d,
            Ok(JsonDoc::Keys(keys)) => Doc { order: None, keys },
            Err(e) => {
                // Untagged enums hide the real cause: parse as the object form for it.
                let detail = serde_json::from_str::<Doc>(&text).err().unwrap_or(e);
                bail!("{spec}: {detail}")
            }
        },
        other => bail!("{spec}: key files must end in .toml or .json (got '.{other}')"),
    };
    parse(doc, spec)
}

fn one_line(s: &str) -> String {
    s.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}

fn parse(doc: Doc, source: &str) -> Result<Keys> {
    let default_order: EulerOrder = match &doc.order {
        Some(o) => o.parse().context("field 'order'")?,
        None => EulerOrder::DAM,
    };
    if doc.keys.len() < 2 {
        bail!("{source}: need at least 2 keys, found {}", doc.keys.len());
    }
    let with_time = doc.keys.iter().filter(|k| k.time.is_some()).count();
    if with_time != 0 && with_time != doc.keys.len() {
        let i = doc.keys.iter().position(|k| k.time.is_none()).unwrap_or(0);
        bail!("{source}: keys[{i}].time is missing: give a time on every key or on none");
    }
    let mut quats = Vec::with_capacity(doc.keys.len());
    for (i, k) in doc.keys.iter().enumerate() {
        let at = |field: &str| format!("{source}: keys[{i}].{field}");
        for (field, v) in [("angle", k.angle), ("time", k.time)] {
            if v.is_some_and(|v| !v.is_finite()) {
                bail!("{} is not a finite number", at(field));
            }
        }
        let q = match (k.angle, k.axis, k.quat, k.euler) {
            (Some(angle), Some(axis), None, None) => {
                Quat::from_axis_angle(Vec3::from_array(axis), angle).with_context(|| at("axis"))?
            }
            (None, None, Some(q), None) => Quat::from_array(q).normalize().with_context(|| at("quat"))?,
            (None, None, None, Some(e)) => {
                let order = match &k.order {
                    Some(o) => o.parse().with_context(|| at("order"))?,
                    None => default_order,
                };
                if e.iter().any(|v| !v.is_finite()) {
                    bail!("{} is not finite", at("euler"));
                }
                Quat::from_euler(order, e)
            }
            (Some(_), None, None, None) => bail!("{} is missing (angle needs an axis)", at("axis")),
            (None, Some(_), None, None) => bail!("{} is missing (axis needs an angle)", at("angle")),
            _ => bail!("{source}: keys[{i}] must have exactly one of {{angle, axis}}, {{quat}} or {{euler}}"),
        };
        quats.push(q);
    }
    let times = (with_time > 0).then(|| doc.keys.iter().map(|k| k.time.unwrap_or(0.0)).collect());
    Ok(Keys {
        quats,
        times,
        source: source.to_string(),
    })
}
